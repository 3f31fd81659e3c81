/* glTF import refuses malformed files with one line naming the JSON path: each case below
 * breaks one field of a valid indexed triangle (which loads, as the first case shows). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "scene/scene.h"

#define TMP CAVELIGHT_BINARY_DIR "/test_gltf_refusals_"
#define BIN "test_gltf_refusals_tri.bin"

/* A part left NULL takes the valid default. */
typedef struct gltf_case {
    const char *want; /* substring of the one-line error; NULL: must load */
    const char *views, *accessors, *meshes, *nodes, *scenes, *extra;
} gltf_case;

static const char default_views[] =
    "[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":36},"
    "{\"buffer\":0,\"byteOffset\":72,\"byteLength\":6}]";
static const char default_accessors[] =
    "[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
    "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
    "{\"bufferView\":2,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]";
static const char default_meshes[] =
    "[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},\"indices\":2}]}]";

/* A mesh node, a light node and a camera node; the lights and one perspective camera. */
#define LIT_NODES "[{\"mesh\":0,\"children\":[1,2]},{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}," \
                  "{\"camera\":0,\"translation\":[0,0,3]}]"
#define LIGHTS(l) "\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[" l "]}},"
#define CAMERAS "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":1,\"znear\":0.1}}],"

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    fclose(f);
}

/* Positions, normals (+z), uint16 indices 0 1 2 and two bytes of padding: 80 bytes. */
static void write_bin(void)
{
    unsigned char bin[80] = {0};
    const float f[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const uint16_t idx[3] = {0, 1, 2};
    memcpy(bin, f, sizeof f);
    memcpy(bin + 72, idx, sizeof idx);
    write_file(CAVELIGHT_BINARY_DIR "/" BIN, bin, sizeof bin);
}

static void run_case(int i, const gltf_case *c)
{
    char text[4096], path[512], err[512] = "";
    snprintf(text, sizeof text,
             "{\"asset\":{\"version\":\"2.0\"},%s\"scene\":0,\"scenes\":%s,\"nodes\":%s,\"meshes\":%s,"
             "\"accessors\":%s,\"bufferViews\":%s,"
             "\"buffers\":[{\"uri\":\"" BIN "\",\"byteLength\":80}]}",
             c->extra ? c->extra : "", c->scenes ? c->scenes : "[{\"nodes\":[0]}]",
             c->nodes ? c->nodes : "[{\"mesh\":0}]", c->meshes ? c->meshes : default_meshes,
             c->accessors ? c->accessors : default_accessors, c->views ? c->views : default_views);
    snprintf(path, sizeof path, TMP "%d.gltf", i);
    write_file(path, text, strlen(text));
    scene s;
    int rc = scene_load(path, &s, err, sizeof err);
    if (!c->want) {
        if (rc)
            fprintf(stderr, "case %d: %s\n", i, err);
        assert_int_equal(rc, 0);
        assert_int_equal(s.triangle_count, 1);
        scene_free(&s);
        return;
    }
    if (rc == 0 || !strstr(err, c->want) || strchr(err, '\n') || !strstr(err, path))
        fprintf(stderr, "case %d: want \"%s\", got rc %d \"%s\"\n", i, c->want, rc, err);
    assert_int_equal(rc, -1);
    assert_non_null(strstr(err, c->want));
    assert_non_null(strstr(err, path));
    assert_null(strchr(err, '\n'));
    assert_int_equal(s.triangle_count, 0);
}

static void test_refusals(void **state)
{
    (void)state;
    write_bin();
    const gltf_case cases[] = {
        {NULL},
        {"bufferViews[0].buffer 3 out of range (1 buffers)",
         .views = "[{\"buffer\":3,\"byteLength\":36},{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteLength\":6}]"},
        {"bufferViews[1]: bytes 60 + 36 outside buffers[0] (80 bytes)",
         .views = "[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":60,\"byteLength\":36},"
                  "{\"buffer\":0,\"byteOffset\":72,\"byteLength\":6}]"},
        {"byteStride' must be the multiple of 4 : 2",
         .views = "[{\"buffer\":0,\"byteLength\":36,\"byteStride\":2},{\"buffer\":0,\"byteLength\":36},"
                  "{\"buffer\":0,\"byteOffset\":72,\"byteLength\":6}]"},
        {"accessors[0].bufferView 9 out of range (3 bufferViews)",
         .accessors = "[{\"bufferView\":9,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                      "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                      "{\"bufferView\":2,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]"},
        {"accessors[0]: byteOffset 0 + count 2147483648 x stride 12 outside bufferViews[0] (36 bytes)",
         .accessors = "[{\"bufferView\":0,\"componentType\":5126,\"count\":2147483648,\"type\":\"VEC3\"},"
                      "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                      "{\"bufferView\":2,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]"},
        {"accessors[1]: byteOffset 4 + count 3 x stride 12 outside bufferViews[1] (36 bytes)",
         .accessors = "[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                      "{\"bufferView\":1,\"byteOffset\":4,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                      "{\"bufferView\":2,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]"},
        {"accessors[2].sparse: sparse accessors are not supported",
         .accessors = "[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                      "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                      "{\"bufferView\":2,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\","
                      "\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":2,\"componentType\":5123},"
                      "\"values\":{\"bufferView\":2}}}]"},
        {"attributes.POSITION: accessors[0] is VEC2 FLOAT, expected VEC3 FLOAT",
         .accessors = "[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"},"
                      "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                      "{\"bufferView\":2,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]"},
        {"meshes[0].primitives[0].attributes.NORMAL: count 2 differs from POSITION's 3",
         .accessors = "[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                      "{\"bufferView\":1,\"componentType\":5126,\"count\":2,\"type\":\"VEC3\"},"
                      "{\"bufferView\":2,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]"},
        {"meshes[0].primitives[0].attributes.POSITION 7 out of range (3 accessors)",
         .meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":7},\"indices\":2}]}]"},
        {"meshes[0].primitives[0].attributes: no POSITION",
         .meshes = "[{\"primitives\":[{\"attributes\":{\"NORMAL\":1}}]}]"},
        {"meshes[0].primitives[0].indices: accessors[0] is VEC3 FLOAT, expected SCALAR",
         .meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":0}]}]"},
        /* Bytes 13..15 of the positions are 00 80 3f: the second index is 128. */
        {"meshes[0].primitives[0].indices: accessors[3][1] = 128 out of range (3 vertices)",
         .accessors = "[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                      "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
                      "{\"bufferView\":2,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"},"
                      "{\"bufferView\":0,\"byteOffset\":13,\"componentType\":5121,\"count\":3,\"type\":\"SCALAR\"}]",
         .meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":3}]}]"},
        {"meshes[0].primitives[0].material 4 out of range (0 materials)",
         .meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":4}]}]"},
        {"nodes[0].mesh 2 out of range (1 meshes)", .nodes = "[{\"mesh\":2}]"},
        {"nodes[0].children[0] 5 out of range (1 nodes)", .nodes = "[{\"mesh\":0,\"children\":[5]}]"},
        {"nodes[1]: nested deeper than 64 levels or in a cycle",
         .nodes = "[{\"mesh\":0},{\"children\":[2]},{\"children\":[1]}]"},
        {"nodes[2].children[0]: nodes[1] already has a parent (nodes[0])",
         .nodes = "[{\"mesh\":0,\"children\":[1]},{\"mesh\":0},{\"children\":[1]}]"},
        {"scenes[0].nodes[0] 3 out of range (1 nodes)", .scenes = "[{\"nodes\":[3]}]"},
        {"scene 0 out of range (0 scenes)", .scenes = "[]"},
        {"nodes[0].extensions.KHR_lights_punctual.light 3 out of range (0 lights)",
         .nodes = "[{\"mesh\":0,\"extensions\":{\"KHR_lights_punctual\":{\"light\":3}}}]"},
        {"materials[0].pbrMetallicRoughness.baseColorTexture.index 1 out of range (0 textures)",
         .extra = "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":1}}}],"},
        {"textures[0].source 2 out of range (0 images)",
         .extra = "\"textures\":[{\"source\":2}],"},
        {"images[0].uri \"missing.png\": file not found or empty",
         .extra = "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
                  "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"missing.png\"}],",
         .meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":0}]}]"},
        {"images[0]: cannot decode",
         .extra = "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
                  "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"" BIN "\"}],",
         .meshes = "[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":0}]}]"},
        /* Lights and cameras: what the importer uses is checked too. */
        {NULL, .nodes = LIT_NODES, .extra = LIGHTS("{\"type\":\"point\",\"intensity\":5}") CAMERAS},
        {"extensions.KHR_lights_punctual.lights[0].type \"area\" unknown (spot, point or directional)",
         .nodes = LIT_NODES, .extra = LIGHTS("{\"type\":\"area\"}") CAMERAS},
        {"extensions.KHR_lights_punctual.lights[0].intensity -1.000000 invalid (0 to 1e12)",
         .nodes = LIT_NODES, .extra = LIGHTS("{\"type\":\"directional\",\"intensity\":-1}") CAMERAS},
        {"extensions.KHR_lights_punctual.lights[0].color: must be an array of 3 numbers, not an array of 2",
         .nodes = LIT_NODES, .extra = LIGHTS("{\"type\":\"point\",\"color\":[1,1]}") CAMERAS},
        {"extensions.KHR_lights_punctual.lights[0].spot.outerConeAngle 2.000000 invalid (0 < outer <= pi/2)",
         .nodes = LIT_NODES,
         .extra = LIGHTS("{\"type\":\"spot\",\"spot\":{\"outerConeAngle\":2}}") CAMERAS},
        {"extensions.KHR_lights_punctual.lights[0].spot.innerConeAngle 0.500000 invalid (0 <= inner <= outer)",
         .nodes = LIT_NODES,
         .extra = LIGHTS("{\"type\":\"spot\",\"spot\":{\"outerConeAngle\":0.4,\"innerConeAngle\":0.5}}") CAMERAS},
        {"nodes[0].camera 2 out of range (1 cameras)", .nodes = "[{\"mesh\":0,\"camera\":2}]",
         .extra = CAMERAS},
        {"cameras[0].perspective.yfov 4.000000 invalid (0 < yfov < pi)",
         .nodes = LIT_NODES, .extra = LIGHTS("{\"type\":\"point\"}")
             "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":4,\"znear\":0.1}}],"},
        {"cameras[0].perspective.zfar 0.050000 invalid (> znear)",
         .nodes = LIT_NODES, .extra = LIGHTS("{\"type\":\"point\"}")
             "\"cameras\":[{\"type\":\"perspective\",\"perspective\":{\"yfov\":1,\"znear\":0.1,\"zfar\":0.05}}],"},
        {"cameras[0].orthographic.ymag 0.000000 invalid (> 0)",
         .nodes = LIT_NODES, .extra = LIGHTS("{\"type\":\"point\"}")
             "\"cameras\":[{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":1,\"ymag\":0,\"znear\":0,\"zfar\":9}}],"},
        {"nodes[2]: the camera's transform has no view direction or up (zero scale?)",
         .nodes = "[{\"mesh\":0},{\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},"
                  "{\"camera\":0,\"scale\":[1,0,1]}]",
         .scenes = "[{\"nodes\":[0,1,2]}]", .extra = LIGHTS("{\"type\":\"point\"}") CAMERAS},
    };
    for (int i = 0; i < (int)(sizeof cases / sizeof cases[0]); i++)
        run_case(i, &cases[i]);
}

/* The binary container goes through the same checks: a GLB whose BIN chunk is shorter than
 * its accessor says. */
static void test_glb_refused(void **state)
{
    (void)state;
    const char json[] = "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
                        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
                        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":30,\"type\":\"VEC3\"}],"
                        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
                        "\"buffers\":[{\"byteLength\":36}]}";
    uint32_t json_len = (uint32_t)((sizeof json - 1 + 3) & ~3u), bin_len = 36;
    uint32_t total = 12 + 8 + json_len + 8 + bin_len;
    unsigned char glb[1024];
    memset(glb, ' ', sizeof glb);
    uint32_t head[5] = {0x46546C67, 2, total, json_len, 0x4E4F534A};
    memcpy(glb, head, sizeof head);
    memcpy(glb + 20, json, sizeof json - 1);
    uint32_t bin_head[2] = {bin_len, 0x004E4942};
    memcpy(glb + 20 + json_len, bin_head, sizeof bin_head);
    memset(glb + 28 + json_len, 0, bin_len);
    write_file(TMP "short.glb", glb, total);
    scene s;
    char err[512] = "";
    assert_int_equal(scene_load(TMP "short.glb", &s, err, sizeof err), -1);
    assert_non_null(strstr(err, "accessors[0]: byteOffset 0 + count 30 x stride 12 outside bufferViews[0] (36 bytes)"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_glb_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
