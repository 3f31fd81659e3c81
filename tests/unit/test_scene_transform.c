/* scene_transform: a Z-up model in centimetres, 100 m from its origin, placed in a 3 m CAVE
 * through the cluster config's "scene_transform" (the path master and nodes take:
 * cluster_config_scene_desc() -> scene_load_with()): by its floor's centre, by its camera
 * (at the viewer's head, looking at the front wall), fitted to the screens' box, and as
 * modelled but turned and moved. Lights move and keep their look; bad transforms are one
 * line naming the field. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "cluster/cluster_config.h"

#define TMP CAVELIGHT_BINARY_DIR "/test_scene_transform_"

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    fclose(f);
}

/* A closed box x 10000..10400, y 5000..5300, z 0..250 (cm, Z up), a point light of 10^4
 * W/sr 100 cm above its top, and (camera) a camera at (9000, 5150, 170) looking along +x
 * with +z up. */
static const char *write_model(int camera)
{
    static char path[256];
    const float lo[3] = {10000, 5000, 0}, hi[3] = {10400, 5300, 250};
    float pos[36 * 3];
    int n = 0;
    for (int axis = 0; axis < 3; axis++)
        for (int side = 0; side < 2; side++) {
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const int cu[6] = {0, 1, 1, 0, 1, 0}, cv[6] = {0, 0, 1, 0, 1, 1};
            for (int k = 0; k < 6; k++, n++) {
                float *p = pos + 3 * n;
                p[axis] = side ? hi[axis] : lo[axis];
                /* outward: the far side's winding runs the other way */
                p[u] = (side ? cu[k] : cv[k]) ? hi[u] : lo[u];
                p[v] = (side ? cv[k] : cu[k]) ? hi[v] : lo[v];
            }
        }
    snprintf(path, sizeof path, TMP "model%d.gltf", camera);
    write_file(TMP "model.bin", pos, sizeof pos);
    char json[4096];
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0,1%s]}],"
             "\"nodes\":[{\"mesh\":0},{\"translation\":[10200,5150,350],"
             "\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}%s],"
             "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\",\"intensity\":10000}]}},"
             "%s\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":36,\"type\":\"VEC3\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteLength\":432}],"
             "\"buffers\":[{\"uri\":\"test_scene_transform_model.bin\",\"byteLength\":432}]}",
             camera ? ",2" : "",
             camera ? ",{\"camera\":0,\"matrix\":[0,-1,0,0, 0,0,1,0, -1,0,0,0, 9000,5150,170,1]}" : "",
             camera ? "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":1,\"znear\":1}}]," : "");
    write_file(path, json, strlen(json));
    return path;
}

/* A 3 m CAVE's front wall and floor (their box: x, z in [-1.5, 1.5], y in [0, 3]), the
 * head at (0, 1.7, 0), and the transform given. */
static int config(const char *transform, cluster_config *cfg, char *err, size_t errlen)
{
    char json[2048];
    snprintf(json, sizeof json,
             "{\"master\": {\"bind\": \"tcp://*:1\", \"connect\": \"tcp://h:1\"}, %s%s%s"
             "\"observer\": {\"home\": [0, 1.7, 0]}, \"screens\": ["
             "{\"name\": \"front\", \"bottom_left\": [-1.5,0,-1.5], \"bottom_right\": [1.5,0,-1.5], \"top_left\": [-1.5,3,-1.5]},"
             "{\"name\": \"floor\", \"bottom_left\": [-1.5,0,1.5], \"bottom_right\": [1.5,0,1.5], \"top_left\": [-1.5,0,-1.5]}],"
             "\"nodes\": [{\"name\": \"a\", \"screens\": [\"front\"], \"resolution\": [4, 4]}]}",
             transform ? "\"scene_transform\": " : "", transform ? transform : "", transform ? "," : "");
    return cluster_config_parse(json, strlen(json), "t.json", cfg, err, errlen);
}

static void load_placed(const char *transform, int camera, scene *s)
{
    static cluster_config cfg;
    char err[512] = "";
    if (config(transform, &cfg, err, sizeof err) != 0)
        fail_msg("%s", err);
    scene_load_desc d;
    cluster_config_scene_desc(&cfg, &d);
    assert_true(d.stage.box_min[0] == -1.5f && d.stage.box_max[1] == 3.0f && d.stage.box_max[2] == 1.5f);
    if (scene_load_with(write_model(camera), &d, s, err, sizeof err) != 0)
        fail_msg("%s", err);
}

static void assert_bounds(const scene *s, const float lo[3], const float hi[3], float tol)
{
    for (int a = 0; a < 3; a++) {
        if (fabsf(s->bounds_min[a] - lo[a]) > tol || fabsf(s->bounds_max[a] - hi[a]) > tol)
            fail_msg("axis %d: bounds %g..%g, expected %g..%g", a, (double)s->bounds_min[a],
                     (double)s->bounds_max[a], (double)lo[a], (double)hi[a]);
    }
}

/* As modelled, the box is 100 m away and sideways: nowhere near the CAVE. Z up in cm with
 * the centre anchor: metres, y up, its floor's middle on the CAVE's origin; the light 1 m
 * above its top with the intensity that lights it as before (10^4 x 0.01^2). */
static void test_centre(void **state)
{
    (void)state;
    scene s;
    load_placed(NULL, 0, &s);
    assert_true(s.bounds_min[0] == 10000 && s.bounds_max[2] == 250);
    scene_free(&s);
    load_placed("{\"up\": \"z\", \"scale\": 0.01, \"anchor\": \"centre\"}", 0, &s);
    assert_bounds(&s, (const float[3]){-2, 0, -1.5f}, (const float[3]){2, 2.5f, 1.5f}, 1e-4f);
    assert_int_equal(s.light_count, 1);
    assert_false(s.light_added);
    const float light[3] = {0, 3.5f, 0};
    for (int a = 0; a < 3; a++)
        assert_true(fabsf(s.lights[0].position[a] - light[a]) < 1e-4f);
    assert_true(fabsf(s.lights[0].intensity - 1.0f) < 1e-5f);
    /* The box's faces still face out: the top's normal is +y. */
    int up = 0;
    for (size_t t = 0; t < s.triangle_count; t++)
        up += s.positions[9 * t + 1] > 2.49f && s.positions[9 * t + 4] > 2.49f && s.normals[9 * t + 1] > 0.999f;
    assert_int_equal(up, 2);
    scene_free(&s);
}

/* The default anchor with a file camera: the camera at the head, turned to look at the
 * front wall; the box 10 to 14 m ahead, 3 m wide across the view. */
static void test_camera(void **state)
{
    (void)state;
    scene s;
    load_placed("{\"up\": \"z\", \"scale\": 0.01}", 1, &s);
    const float home[3] = {0, 1.7f, 0};
    float d[3];
    for (int a = 0; a < 3; a++) {
        assert_true(fabsf(s.camera.position[a] - home[a]) < 1e-4f);
        d[a] = s.camera.target[a] - s.camera.position[a];
    }
    float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    assert_true(d[2] / len < -0.9999f);
    assert_true(s.camera.up[1] > 0.9999f);
    assert_true(fabsf(s.camera.znear - 0.01f) < 1e-7f);
    assert_bounds(&s, (const float[3]){-1.5f, 0, -14}, (const float[3]){1.5f, 2.5f, -10}, 1e-4f);
    scene_free(&s);
}

/* fit: the largest size that fits the screens' box (here 3 m / 4 m: 0.0075 per cm),
 * standing in the middle of its floor; no scale or anchor needed. */
static void test_fit(void **state)
{
    (void)state;
    scene s;
    load_placed("{\"up\": \"z\", \"fit\": true}", 1, &s);
    assert_bounds(&s, (const float[3]){-1.5f, 0, -1.125f}, (const float[3]){1.5f, 1.875f, 1.125f}, 1e-4f);
    assert_true(fabsf(s.lights[0].intensity - 1e4f * 0.0075f * 0.0075f) < 1e-4f);
    scene_free(&s);
}

/* anchor none: the file's origin stays; then a quarter turn about +y (x -> -z, z -> x)
 * and a move by (0, 0, -2). */
static void test_rotation_translation(void **state)
{
    (void)state;
    scene s;
    load_placed("{\"up\": \"z\", \"anchor\": \"none\", \"rotation_deg\": [0, 90, 0], \"translation\": [0, 0, -2]}",
                0, &s);
    const float light[3] = {-5150, 350, -10202};
    for (int a = 0; a < 3; a++)
        assert_true(fabsf(s.lights[0].position[a] - light[a]) < 1e-2f);
    assert_true(s.lights[0].intensity == 10000.0f);
    scene_free(&s);
}

/* One line naming the field, from the config and from a command line's JSON; a camera
 * anchor without a camera is refused when the scene loads. */
static void test_refused(void **state)
{
    (void)state;
    static const struct { const char *transform, *want; } cases[] = {
        {"3", "field scene_transform: must be an object"},
        {"{\"scale\": 0}", "field scene_transform.scale: 0 is outside [1e-06, 1e+06]"},
        {"{\"up\": \"x\"}", "field scene_transform.up: must be one of: y, z"},
        {"{\"anchor\": \"middle\"}", "field scene_transform.anchor: must be one of: auto, camera, centre, none"},
        {"{\"fit\": true, \"scale\": 2}", "field scene_transform.fit: chooses the scale and the anchor"},
        {"{\"fit\": 1}", "field scene_transform.fit: must be true or false"},
        {"{\"rotation_deg\": [0, 400, 0]}", "field scene_transform.rotation_deg: element 1 must be a number in [-360, 360]"},
        {"{\"translation\": [0, 0]}", "field scene_transform.translation: must be an array of 3 numbers"},
        {"{\"sclae\": 0.01}", "field scene_transform.sclae: unknown (scale, up, anchor, fit, rotation_deg or translation)"},
    };
    cluster_config cfg;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char err[512] = "";
        assert_int_equal(config(cases[i].transform, &cfg, err, sizeof err), -1);
        if (!strstr(err, cases[i].want) || !strstr(err, "cluster config t.json") || strchr(err, '\n'))
            fail_msg("%s: got '%s'", cases[i].transform, err);
    }
    scene_transform t;
    char err[512] = "";
    assert_int_equal(cluster_scene_transform_parse("{\"up\": \"z\", \"scale\": 0.01}", &t, err, sizeof err), 0);
    assert_true(t.up == SCENE_UP_Z && t.scale == 0.01f && t.anchor == SCENE_ANCHOR_AUTO);
    assert_int_equal(cluster_scene_transform_parse("{\"scale\": -1}", &t, err, sizeof err), -1);
    assert_string_equal(err, "scene_transform.scale: -1 is outside [1e-06, 1e+06]");
    assert_int_equal(cluster_scene_transform_parse("up=z", &t, err, sizeof err), -1);
    assert_non_null(strstr(err, "not valid JSON"));

    assert_int_equal(config("{\"anchor\": \"camera\"}", &cfg, err, sizeof err), 0);
    scene_load_desc d;
    cluster_config_scene_desc(&cfg, &d);
    scene s;
    const char *path = write_model(0);
    assert_int_equal(scene_load_with(path, &d, &s, err, sizeof err), -1);
    assert_non_null(strstr(err, path));
    assert_non_null(strstr(err, "scene_transform.anchor: camera, but the scene has no camera"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_centre),
        cmocka_unit_test(test_camera),
        cmocka_unit_test(test_fit),
        cmocka_unit_test(test_rotation_translation),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
