/* scene: the built-in scenes, glTF import (transforms, materials, spot lights) and clean
 * rejection of missing, malformed and unsupported files. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "image/image.h"
#include "scene/scene.h"

#define TMP CAVELIGHT_BINARY_DIR "/test_scene_"

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    fclose(f);
}

/* The corridor is long and thin: a lattice fitted to it is a small share of a cube. */
static void test_corridor(void **state)
{
    (void)state;
    scene s;
    char err[256];
    assert_int_equal(scene_load("corridor", &s, err, sizeof err), 0);
    assert_int_equal(s.light_count, 1);
    assert_true(s.camera.valid);
    const float lo[3] = {0, 0, -1.2f}, hi[3] = {12, 2.6f, 1.2f};
    for (int a = 0; a < 3; a++) {
        assert_true(fabsf(s.bounds_min[a] - lo[a]) < 1e-6f);
        assert_true(fabsf(s.bounds_max[a] - hi[a]) < 1e-6f);
    }
    /* The spot sits inside and points down the corridor's near end. */
    assert_true(s.lights[0].position[0] < 1 && s.lights[0].direction[1] < -0.5f);
    assert_true(s.lights[0].direction[0] > 0.2f);
    scene_free(&s);
}

/* Every built-in scene loads by name with a camera and a light source; the list ends. */
static void test_builtin_scenes(void **state)
{
    (void)state;
    int count = 0;
    for (int i = 0; scene_builtin_name(i); i++, count++) {
        scene s;
        char err[256];
        assert_int_equal(scene_load(scene_builtin_name(i), &s, err, sizeof err), 0);
        assert_true(s.triangle_count >= 10 && s.camera.valid);
        int emitters = 0;
        for (size_t m = 0; m < s.material_count; m++)
            emitters += s.materials[m].emissive[0] > 0;
        assert_true(s.light_count + emitters >= 1);
        scene_free(&s);
    }
    assert_int_equal(count, 8);
    assert_null(scene_builtin_name(count));
    assert_null(scene_builtin_name(-1));
}

/* Room B of the doorway scene is out of the spot's cone: points along the edges of the
 * doorway (x = 4, z in [-1.5, -0.5], y in [0, 2.1]) lie outside its outer angle. The
 * courtyard has no roof: nothing at the walls' top faces down. */
static void test_doorway_and_courtyard(void **state)
{
    (void)state;
    scene s;
    char err[256];
    assert_int_equal(scene_load("doorway", &s, err, sizeof err), 0);
    const scene_light *l = &s.lights[0];
    for (int k = 0; k <= 40; k++) {
        float u = (float)k / 40.0f;
        const float edge[4][3] = {{4, 0, -1.5f + u}, {4, 2.1f, -1.5f + u},
                                  {4, 2.1f * u, -1.5f}, {4, 2.1f * u, -0.5f}};
        for (int e = 0; e < 4; e++) {
            float d[3], len = 0, c = 0;
            for (int a = 0; a < 3; a++) {
                d[a] = edge[e][a] - l->position[a];
                len += d[a] * d[a];
            }
            for (int a = 0; a < 3; a++)
                c += d[a] / sqrtf(len) * l->direction[a];
            assert_true(c < cosf(l->outer_angle));
        }
    }
    scene_free(&s);
    assert_int_equal(scene_load("courtyard", &s, err, sizeof err), 0);
    assert_true(s.bounds_max[1] - s.bounds_min[1] > s.bounds_max[0] - s.bounds_min[0]);
    for (size_t t = 0; t < s.triangle_count; t++)
        assert_false(s.positions[9 * t + 1] == s.bounds_max[1] &&
                     s.positions[9 * t + 4] == s.bounds_max[1] &&
                     s.positions[9 * t + 7] == s.bounds_max[1]);
    assert_true(s.lights[0].position[1] > s.bounds_max[1]);
    scene_free(&s);
}

/* The arcaded courtyard: 12 x 8.6 x 24 m, open to the sky over the court; its one light is
 * a point lamp in the lower gallery at x > 0 (between the columns and the outer wall,
 * under the first-floor slab), in free space; the camera stands in the court. */
static void test_arcades(void **state)
{
    (void)state;
    scene s;
    char err[256];
    assert_int_equal(scene_load("arcades", &s, err, sizeof err), 0);
    const float lo[3] = {-6, 0, -12}, hi[3] = {6, 8.6f, 12};
    for (int a = 0; a < 3; a++) {
        assert_true(fabsf(s.bounds_min[a] - lo[a]) < 1e-6f);
        assert_true(fabsf(s.bounds_max[a] - hi[a]) < 1e-6f);
    }
    assert_int_equal(s.light_count, 1);
    const scene_light *l = &s.lights[0];
    assert_int_equal(l->type, SCENE_LIGHT_POINT);
    assert_true(l->position[0] > 3.7f && l->position[0] < 6.0f && l->position[1] < 4.0f);
    assert_true(scene_point_is_free(&s, l->position, NULL));
    int fronts;
    const float court[3] = {0, 4, 0};
    assert_true(scene_point_is_free(&s, court, &fronts));
    assert_true(fronts < 14); /* some rays escape through the open top */
    assert_true(fabsf(s.camera.position[0]) < 3.3f);
    scene_free(&s);
}

/* scene_add_rect: two triangles with the normal along the flat axis, signed by facing;
 * refused when no axis or two axes are flat, or facing is 0. */
static void test_rect(void **state)
{
    (void)state;
    scene s;
    memset(&s, 0, sizeof s);
    const float lo[3] = {0, 1, 0}, hi[3] = {2, 1, 3};
    assert_int_equal(scene_add_rect(&s, lo, hi, -1, 0), 0);
    assert_int_equal(s.triangle_count, 2);
    for (int v = 0; v < 6; v++) {
        assert_true(s.normals[3 * v + 1] == -1.0f && s.positions[3 * v + 1] == 1.0f);
        assert_true(s.normals[3 * v] == 0 && s.normals[3 * v + 2] == 0);
    }
    const float line[3] = {2, 1, 0}, box[3] = {2, 2, 3};
    assert_int_equal(scene_add_rect(&s, lo, line, 1, 0), -1);
    assert_int_equal(scene_add_rect(&s, lo, box, 1, 0), -1);
    assert_int_equal(scene_add_rect(&s, lo, hi, 0, 0), -1);
    assert_int_equal(s.triangle_count, 2);
    scene_free(&s);
}

static void test_default_room(void **state)
{
    (void)state;
    scene s;
    char err[256];
    assert_int_equal(scene_load("default", &s, err, sizeof err), 0);
    assert_true(s.triangle_count >= 12 + 24);
    assert_int_equal(s.light_count, 1);
    const float lo[3] = {-2, 0, -2}, hi[3] = {2, 3, 2};
    for (int a = 0; a < 3; a++) {
        assert_true(fabsf(s.bounds_min[a] - lo[a]) < 1e-6f);
        assert_true(fabsf(s.bounds_max[a] - hi[a]) < 1e-6f);
    }
    int red = 0, emissive = 0;
    for (size_t t = 0; t < s.triangle_count; t++) {
        const scene_material *m = &s.materials[s.triangle_material[t]];
        red += m->base_color[0] > 0.5f && m->base_color[1] < 0.2f;
        emissive += m->emissive[0] > 0;
        for (int v = 0; v < 3; v++) {
            const float *n = s.normals + 9 * t + 3 * v;
            assert_true(fabsf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0f) < 1e-5f);
        }
    }
    assert_int_equal(red, 2);
    assert_int_equal(emissive, 2);
    /* The spot points down into the room. */
    assert_true(s.lights[0].direction[1] < -0.5f);
    scene_free(&s);
    assert_int_equal(s.triangle_count, 0);
}

/* One triangle (0,0,0) (1,0,0) (0,1,0) with normals +z, under a node translated by
 * (1,2,3) and scaled by 2; a spot at (0,5,0) rotated -90 degrees about x, so that its -z
 * axis points down; an emissive material with KHR_materials_emissive_strength. */
static const char gltf_text[] =
    "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,"
    "\"extensionsUsed\":[\"KHR_lights_punctual\",\"KHR_materials_emissive_strength\"],"
    "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"spot\",\"color\":[1,0.5,0.25],"
    "\"intensity\":40,\"spot\":{\"innerConeAngle\":0.2,\"outerConeAngle\":0.5}}]}},"
    "\"scenes\":[{\"nodes\":[0,1]}],"
    "\"nodes\":[{\"mesh\":0,\"translation\":[1,2,3],\"scale\":[2,2,2]},"
    "{\"translation\":[0,5,0],\"rotation\":[-0.70710678,0,0,0.70710678],"
    "\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}],"
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},\"material\":0}]}],"
    "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.2,0.4,0.6,1],\"roughnessFactor\":0.3},"
    "\"emissiveFactor\":[1,0.5,0],\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":3}}}],"
    "\"buffers\":[{\"uri\":\"test_scene_tri.bin\",\"byteLength\":72}],"
    "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":36}],"
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},"
    "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}]}";

static void write_triangle_bin(void)
{
    const float data[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    write_file(TMP "tri.bin", data, sizeof data);
}

static void test_gltf_transform_material_light(void **state)
{
    (void)state;
    write_triangle_bin();
    write_file(TMP "ok.gltf", gltf_text, strlen(gltf_text));
    scene s;
    char err[512] = "";
    int rc = scene_load(TMP "ok.gltf", &s, err, sizeof err);
    if (rc)
        fprintf(stderr, "%s\n", err);
    assert_int_equal(rc, 0);
    assert_int_equal(s.triangle_count, 1);
    const float want[9] = {1, 2, 3, 3, 2, 3, 1, 4, 3};
    for (int i = 0; i < 9; i++)
        assert_true(fabsf(s.positions[i] - want[i]) < 1e-5f);
    assert_true(fabsf(s.normals[2] - 1.0f) < 1e-5f);
    const scene_material *m = &s.materials[s.triangle_material[0]];
    assert_true(fabsf(m->base_color[1] - 0.4f) < 1e-6f);
    assert_true(fabsf(m->emissive[0] - 3.0f) < 1e-6f && fabsf(m->emissive[1] - 1.5f) < 1e-6f);
    assert_true(fabsf(m->roughness - 0.3f) < 1e-6f);
    assert_int_equal(s.light_count, 1);
    const scene_light *l = &s.lights[0];
    assert_true(fabsf(l->position[1] - 5.0f) < 1e-5f);
    /* -90 degrees about x turns the light's -z axis to -y: pointing down. */
    assert_true(fabsf(l->direction[1] + 1.0f) < 1e-4f);
    assert_true(fabsf(l->intensity - 40.0f) < 1e-5f);
    assert_true(fabsf(l->outer_angle - 0.5f) < 1e-6f && fabsf(l->inner_angle - 0.2f) < 1e-6f);
    assert_true(fabsf(l->color[2] - 0.25f) < 1e-6f);
    scene_free(&s);
}

/* A base colour texture (a PNG beside the file): decoded to RGBA8 and linked from the
 * material, uvs imported. */
static void test_gltf_texture(void **state)
{
    (void)state;
    write_triangle_bin();
    const uint8_t rgb[2 * 2 * 3] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 10, 20, 30};
    char err[512] = "";
    assert_int_equal(image_write_png(TMP "tex.png", 2, 2, rgb, err, sizeof err), 0);
    const float uv[6] = {0, 0, 1, 0, 0, 1};
    FILE *f = fopen(TMP "tri.bin", "ab");
    assert_non_null(f);
    assert_int_equal(fwrite(uv, sizeof uv, 1, f), 1);
    fclose(f);
    const char *text =
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
        "\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1},\"material\":0}]}],"
        "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
        "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"test_scene_tex.png\"}],"
        "\"buffers\":[{\"uri\":\"test_scene_tri.bin\",\"byteLength\":96}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":72,\"byteLength\":24}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,1,0]},"
        "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"}]}";
    write_file(TMP "tex.gltf", text, strlen(text));
    scene s;
    int rc = scene_load(TMP "tex.gltf", &s, err, sizeof err);
    if (rc)
        fprintf(stderr, "%s\n", err);
    assert_int_equal(rc, 0);
    assert_int_equal(s.texture_count, 1);
    const scene_material *m = &s.materials[s.triangle_material[0]];
    assert_int_equal(m->base_color_texture, 0);
    assert_true(m->base_color[0] == 1.0f && m->base_color[3] == 1.0f);
    const scene_texture *t = &s.textures[0];
    assert_int_equal(t->width, 2);
    assert_int_equal(t->height, 2);
    const uint8_t want[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 10, 20, 30, 255};
    assert_memory_equal(t->rgba, want, sizeof want);
    assert_true(s.uvs[2] == 1.0f && s.uvs[5] == 1.0f);
    /* No normals in the file: the face normal, +z for this winding. */
    assert_true(fabsf(s.normals[2] - 1.0f) < 1e-6f);
    scene_free(&s);
}

static void expect_rejected(const char *path, const char *needle)
{
    scene s;
    char err[512] = "";
    assert_int_equal(scene_load(path, &s, err, sizeof err), -1);
    assert_non_null(strstr(err, needle));
    assert_null(strchr(err, '\n'));
    assert_int_equal(s.triangle_count, 0);
}

/* Far plane and fallback view from the bounds; the scene's own camera wins. A closed room
 * (a box facing in) is seen from inside: eye height, 10% along its longest horizontal
 * axis, looking along it. The same box facing out is an object, seen from outside. */
static void test_far_plane_and_default_view(void **state)
{
    (void)state;
    const float lo[3] = {-1, 0, -2}, hi[3] = {1, 3, 2}; /* extents 2 x 3 x 4 */
    for (int inward = 1; inward >= 0; inward--) {
        scene s;
        memset(&s, 0, sizeof s);
        assert_true(scene_add_material(&s, &(scene_material){.base_color = {1, 1, 1, 1},
                                                             .base_color_texture = -1}) == 0);
        assert_true(scene_add_box(&s, lo, hi, inward, 0) >= 0);
        char err[128];
        assert_int_equal(scene_finish(&s, err, sizeof err), 0);
        assert_true(fabsf(scene_far_plane(&s) - (4.0f * sqrtf(29.0f) + 10.0f)) < 1e-4f);
        float pos[3], target[3];
        scene_default_view(&s, pos, target);
        if (inward) {
            assert_true(pos[0] == 0 && pos[1] == 1.5f && fabsf(pos[2] + 1.6f) < 1e-6f);
            assert_true(target[0] == 0 && target[1] == 1.5f && target[2] == 2.0f);
        } else {
            assert_true(target[0] == 0 && target[1] == 1.5f && target[2] == 0);
            assert_true(pos[0] == 0 && fabsf(pos[1] - 2.7f) < 1e-6f && pos[2] == 6.0f);
        }
        s.camera = (scene_camera){.valid = 1, .position = {5, 6, 7}, .target = {1, 2, 3}};
        scene_default_view(&s, pos, target);
        assert_true(pos[0] == 5 && pos[1] == 6 && pos[2] == 7);
        assert_true(target[0] == 1 && target[1] == 2 && target[2] == 3);
        scene_free(&s);
    }
}

/* Inside a closed room with a solid block (outward faces) in its middle: the middle is not
 * free, the room around it is; the default light and view go to free points inside. The
 * block alone is an object: seen from outside. */
static void test_free_points(void **state)
{
    (void)state;
    scene s;
    memset(&s, 0, sizeof s);
    assert_true(scene_add_material(&s, &(scene_material){.base_color = {1, 1, 1, 1},
                                                         .base_color_texture = -1}) == 0);
    const float lo[3] = {-2, 0, -3}, hi[3] = {2, 3, 3};
    const float blo[3] = {-1, 0.5f, -1}, bhi[3] = {1, 2.5f, 1};
    assert_true(scene_add_box(&s, lo, hi, 1, 0) >= 0);
    assert_true(scene_add_box(&s, blo, bhi, 0, 0) >= 0);
    char err[128];
    assert_int_equal(scene_finish(&s, err, sizeof err), 0);
    int fronts;
    assert_false(scene_point_is_free(&s, (const float[3]){0, 2.25f, 0}, &fronts));
    assert_int_equal(fronts, 0);
    assert_true(scene_point_is_free(&s, (const float[3]){1.8f, 2.25f, 0}, &fronts));
    assert_int_equal(fronts, 14);
    scene_light l;
    scene_default_light(&s, &l);
    assert_int_equal(l.type, SCENE_LIGHT_POINT);
    assert_true(scene_point_is_free(&s, l.position, NULL));
    for (int a = 0; a < 3; a++)
        assert_true(l.position[a] > lo[a] && l.position[a] < hi[a]);
    assert_true(fabsf(l.intensity - 2.0f * l.position[1] * l.position[1]) < 1e-4f);
    float pos[3], target[3];
    scene_default_view(&s, pos, target);
    assert_true(scene_point_is_free(&s, pos, NULL));
    for (int a = 0; a < 3; a++)
        assert_true(pos[a] > lo[a] && pos[a] < hi[a]);
    scene_free(&s);

    memset(&s, 0, sizeof s);
    assert_true(scene_add_material(&s, &(scene_material){.base_color = {1, 1, 1, 1},
                                                         .base_color_texture = -1}) == 0);
    assert_true(scene_add_box(&s, blo, bhi, 0, 0) >= 0);
    assert_int_equal(scene_finish(&s, err, sizeof err), 0);
    scene_default_view(&s, pos, target);
    assert_true(pos[2] > bhi[2]);
    scene_free(&s);
}

static void test_bad_files_rejected(void **state)
{
    (void)state;
    expect_rejected(TMP "does_not_exist.gltf", "does_not_exist.gltf");
    write_file(TMP "bad.gltf", "{\"asset\": {\"version\": \"2.0\"", 27);
    expect_rejected(TMP "bad.gltf", "bad.gltf");
    write_file(TMP "bad.glb", "glTF\x02\0\0\0garbage", 15);
    expect_rejected(TMP "bad.glb", "bad.glb");
    expect_rejected(TMP "scene.obj", "unknown format");
    /* Valid JSON, but the accessor points past its buffer. */
    write_triangle_bin();
    char text[sizeof gltf_text + 16];
    snprintf(text, sizeof text, "%s", gltf_text);
    char *count = strstr(text, "\"count\":3");
    count[8] = '9';
    write_file(TMP "overrun.gltf", text, strlen(text));
    expect_rejected(TMP "overrun.gltf", "overrun.gltf");
    /* No meshes at all. */
    const char *empty = "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[]}],\"scene\":0}";
    write_file(TMP "empty.gltf", empty, strlen(empty));
    expect_rejected(TMP "empty.gltf", "no triangles");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_room),
        cmocka_unit_test(test_corridor),
        cmocka_unit_test(test_builtin_scenes),
        cmocka_unit_test(test_doorway_and_courtyard),
        cmocka_unit_test(test_arcades),
        cmocka_unit_test(test_rect),
        cmocka_unit_test(test_gltf_transform_material_light),
        cmocka_unit_test(test_gltf_texture),
        cmocka_unit_test(test_far_plane_and_default_view),
        cmocka_unit_test(test_free_points),
        cmocka_unit_test(test_bad_files_rejected),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
