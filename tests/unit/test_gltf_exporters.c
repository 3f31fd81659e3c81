/* glTF as other exporters write it, each file written here and its result asserted:
 * triangle strips and fans, quantized attributes (KHR_mesh_quantization), a texture
 * transform on a second uv set (KHR_texture_transform), Draco compression (the file made
 * by Debian's draco_transcoder from a plain one, decoded through libdraco), glTF 1.0 named
 * as such (text with and without "asset", binary), required extensions it cannot honour,
 * fields of the wrong JSON type named by their path, buffers and images outside the scene
 * file's folder, and materials drawn differently from their definition. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cmocka.h>

#include "image/image.h"
#include "scene/scene_load.h"

#define DIR CAVELIGHT_BINARY_DIR "/test_gltf_exporters.d"

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    fclose(f);
}

/* DIR/name.gltf with this JSON; bin (if any) as DIR/name.bin, which the JSON names "BIN". */
static const char *write_case(const char *name, const char *json, const void *bin, size_t n)
{
    static char path[512];
    char bin_path[512], text[8192];
    mkdir(DIR, 0755);
    snprintf(bin_path, sizeof bin_path, DIR "/%s.bin", name);
    if (bin)
        write_file(bin_path, bin, n);
    /* "BIN" in the JSON stands for the bin file's name. */
    const char *at = strstr(json, "\"BIN\"");
    if (at)
        snprintf(text, sizeof text, "%.*s\"%s.bin\"%s", (int)(at - json), json, name, at + 5);
    else
        snprintf(text, sizeof text, "%s", json);
    snprintf(path, sizeof path, DIR "/%s.gltf", name);
    write_file(path, text, strlen(text));
    return path;
}

static int load(const char *path, int allow_outside, scene *s, char *err, size_t errlen)
{
    scene_load_desc d = {.allow_outside_paths = allow_outside};
    int rc = scene_load_with(path, &d, s, err, errlen);
    if (rc)
        fprintf(stderr, "%s\n", err);
    return rc;
}

static void expect_refused(const char *path, const char *want)
{
    scene s;
    char err[512] = "";
    int rc = scene_load(path, &s, err, sizeof err);
    if (rc == 0 || !strstr(err, want))
        fprintf(stderr, "want \"%s\", got rc %d \"%s\"\n", want, rc, err);
    assert_int_equal(rc, -1);
    assert_non_null(strstr(err, want));
    assert_non_null(strstr(err, path));
    assert_null(strchr(err, '\n'));
    assert_int_equal(s.triangle_count, 0);
}

/* Face normal z of triangle t (from the winding) and its area. */
static float face_z(const scene *s, size_t t, float *area)
{
    const float *p = s->positions + 9 * t;
    float e1[3] = {p[3] - p[0], p[4] - p[1], p[5] - p[2]}, e2[3] = {p[6] - p[0], p[7] - p[1], p[8] - p[2]};
    float c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    float len = sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    *area = 0.5f * len;
    return c[2] / len;
}

/* Positions only, indices 16-bit, one primitive of the given mode. */
static const char *write_indexed(const char *name, int mode, const float *pos, int vertices,
                                 const uint16_t *idx, int count)
{
    unsigned char bin[1024];
    size_t pbytes = (size_t)vertices * 12, ibytes = (size_t)count * 2;
    memcpy(bin, pos, pbytes);
    memcpy(bin + pbytes, idx, ibytes);
    char json[2048];
    snprintf(json, sizeof json,
             "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1,\"mode\":%d}]}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":%d,\"type\":\"VEC3\"},"
             "{\"bufferView\":1,\"componentType\":5123,\"count\":%d,\"type\":\"SCALAR\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteLength\":%zu},{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}],"
             "\"buffers\":[{\"uri\":\"BIN\",\"byteLength\":%zu}]}",
             mode, vertices, count, pbytes, pbytes, ibytes, pbytes + ibytes);
    return write_case(name, json, bin, pbytes + ibytes);
}

/* Two unit quads as one strip joined by degenerate triangles: 4 triangles, all facing +z
 * (the strip's odd triangles are wound the other way round, as the spec says). */
static void test_triangle_strip(void **state)
{
    (void)state;
    const float pos[8 * 3] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 0, 0, 3, 0, 0, 2, 1, 0, 3, 1, 0};
    const uint16_t idx[10] = {0, 1, 2, 3, 3, 4, 4, 5, 6, 7};
    scene s;
    char err[512];
    assert_int_equal(load(write_indexed("strip", 5, pos, 8, idx, 10), 0, &s, err, sizeof err), 0);
    assert_int_equal(s.triangle_count, 4);
    float total = 0, area;
    for (size_t t = 0; t < s.triangle_count; t++) {
        assert_true(face_z(&s, t, &area) > 0.999f);
        total += area;
    }
    assert_true(fabsf(total - 2.0f) < 1e-5f);
    scene_free(&s);
}

/* A regular hexagon as a fan around its centre: 6 triangles facing +z, its area. */
static void test_triangle_fan(void **state)
{
    (void)state;
    float pos[7 * 3] = {0};
    for (int i = 0; i < 6; i++) {
        pos[3 + 3 * i] = cosf((float)i * 3.14159265f / 3);
        pos[4 + 3 * i] = sinf((float)i * 3.14159265f / 3);
    }
    const uint16_t idx[8] = {0, 1, 2, 3, 4, 5, 6, 1};
    scene s;
    char err[512];
    assert_int_equal(load(write_indexed("fan", 6, pos, 7, idx, 8), 0, &s, err, sizeof err), 0);
    assert_int_equal(s.triangle_count, 6);
    float total = 0, area;
    for (size_t t = 0; t < s.triangle_count; t++) {
        assert_true(face_z(&s, t, &area) > 0.999f);
        total += area;
    }
    assert_true(fabsf(total - 1.5f * sqrtf(3.0f)) < 1e-4f);
    scene_free(&s);
}

/* KHR_mesh_quantization: positions as 16-bit integers in millimetres under a node scale of
 * 0.001, normals as normalized bytes, uvs as normalized 16-bit, with strides padded to 4. */
static void test_quantized(void **state)
{
    (void)state;
    unsigned char bin[48] = {0};
    const int16_t p[3][4] = {{0, 0, 0, 0}, {1000, 0, 0, 0}, {0, 1000, -500, 0}};
    const int8_t n[3][4] = {{0, 0, 127, 0}, {0, 0, 127, 0}, {0, 0, 127, 0}};
    const uint16_t uv[3][2] = {{0, 0}, {65535, 0}, {0, 65535}};
    memcpy(bin, p, 24);
    memcpy(bin + 24, n, 12);
    memcpy(bin + 36, uv, 12);
    const char *json =
        "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_mesh_quantization\"],"
        "\"extensionsRequired\":[\"KHR_mesh_quantization\"],\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
        "\"nodes\":[{\"mesh\":0,\"scale\":[0.001,0.001,0.001]}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2}}]}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5122,\"count\":3,\"type\":\"VEC3\"},"
        "{\"bufferView\":1,\"componentType\":5120,\"normalized\":true,\"count\":3,\"type\":\"VEC3\"},"
        "{\"bufferView\":2,\"componentType\":5123,\"normalized\":true,\"count\":3,\"type\":\"VEC2\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":24,\"byteStride\":8},"
        "{\"buffer\":0,\"byteOffset\":24,\"byteLength\":12,\"byteStride\":4},"
        "{\"buffer\":0,\"byteOffset\":36,\"byteLength\":12}],"
        "\"buffers\":[{\"uri\":\"BIN\",\"byteLength\":48}]}";
    scene s;
    char err[512];
    assert_int_equal(load(write_case("quantized", json, bin, sizeof bin), 0, &s, err, sizeof err), 0);
    assert_int_equal(s.triangle_count, 1);
    const float want[9] = {0, 0, 0, 1, 0, 0, 0, 1, -0.5f}, want_uv[6] = {0, 0, 1, 0, 0, 1};
    for (int i = 0; i < 9; i++) {
        assert_true(fabsf(s.positions[i] - want[i]) < 1e-6f);
        assert_true(fabsf(s.normals[i] - (i % 3 == 2 ? 1.0f : 0.0f)) < 1e-6f);
    }
    for (int i = 0; i < 6; i++)
        assert_true(fabsf(s.uvs[i] - want_uv[i]) < 1e-6f);
    assert_string_equal(s.warning, "");
    scene_free(&s);
}

/* KHR_texture_transform with its own texCoord: the texture reads TEXCOORD_1, offset
 * (0.5, 0.25), rotated a quarter turn, scaled (2, 3): u' = v * 3 + 0.5, v' = -2 u + 0.25. */
static void test_texture_transform(void **state)
{
    (void)state;
    const uint8_t rgb[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
    char err[512];
    mkdir(DIR, 0755);
    assert_int_equal(image_write_png(DIR "/checker.png", 2, 2, rgb, err, sizeof err), 0);
    float bin[9 + 6 + 6] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float uv1[6] = {0, 0, 1, 0, 0, 1};
    memcpy(bin + 15, uv1, sizeof uv1);
    const char *json =
        "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_texture_transform\"],\"scene\":0,"
        "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1,\"TEXCOORD_1\":2},"
        "\"material\":0}]}],"
        "\"materials\":[{\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"baseColorTexture\":{\"index\":0,"
        "\"extensions\":{\"KHR_texture_transform\":{\"offset\":[0.5,0.25],\"rotation\":1.5707963268,"
        "\"scale\":[2,3],\"texCoord\":1}}}}}],"
        "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"checker.png\"}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"},"
        "{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"},"
        "{\"bufferView\":2,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":24},"
        "{\"buffer\":0,\"byteOffset\":60,\"byteLength\":24}],"
        "\"buffers\":[{\"uri\":\"BIN\",\"byteLength\":84}]}";
    scene s;
    assert_int_equal(load(write_case("texture_transform", json, bin, sizeof bin), 0, &s, err, sizeof err), 0);
    assert_int_equal(s.texture_count, 1);
    assert_int_equal(s.materials[s.triangle_material[0]].base_color_texture, 0);
    const float want[6] = {0.5f, 0.25f, 0.5f, -1.75f, 3.5f, 0.25f};
    for (int i = 0; i < 6; i++)
        assert_true(fabsf(s.uvs[i] - want[i]) < 1e-5f);
    assert_string_equal(s.warning, "");
    scene_free(&s);
}

/* A closed unit box, indexed, with normals: written plain, then Draco-compressed by
 * Debian's draco_transcoder (the draco package; the test needs it, scripts/deps.sh installs
 * it). Both load to the same 12 triangles, to Draco's quantization (11 bits of positions,
 * 8 of normals by default). A Draco buffer that does not decode is refused in one line. */
static void test_draco(void **state)
{
    (void)state;
    float pos[24 * 3], nrm[24 * 3];
    uint16_t idx[36];
    for (int f = 0; f < 6; f++) {
        int axis = f / 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
        float side = (float)(f % 2);
        const int cu[4] = {0, 1, 1, 0}, cv[4] = {0, 0, 1, 1};
        for (int k = 0; k < 4; k++) {
            float *p = pos + 3 * (4 * f + k), *n = nrm + 3 * (4 * f + k);
            p[axis] = side;
            p[u] = (float)(side > 0 ? cu[k] : cv[k]);
            p[v] = (float)(side > 0 ? cv[k] : cu[k]);
            n[0] = n[1] = n[2] = 0;
            n[axis] = side > 0 ? 1.0f : -1.0f;
        }
        const uint16_t q[6] = {0, 1, 2, 0, 2, 3};
        for (int k = 0; k < 6; k++)
            idx[6 * f + k] = (uint16_t)(4 * f + q[k]);
    }
    unsigned char bin[sizeof pos + sizeof nrm + sizeof idx];
    memcpy(bin, pos, sizeof pos);
    memcpy(bin + sizeof pos, nrm, sizeof nrm);
    memcpy(bin + sizeof pos + sizeof nrm, idx, sizeof idx);
    const char *json =
        "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},\"indices\":2}]}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":24,\"type\":\"VEC3\","
        "\"min\":[0,0,0],\"max\":[1,1,1]},{\"bufferView\":1,\"componentType\":5126,\"count\":24,\"type\":\"VEC3\"},"
        "{\"bufferView\":2,\"componentType\":5123,\"count\":36,\"type\":\"SCALAR\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":288},{\"buffer\":0,\"byteOffset\":288,\"byteLength\":288},"
        "{\"buffer\":0,\"byteOffset\":576,\"byteLength\":72}],"
        "\"buffers\":[{\"uri\":\"BIN\",\"byteLength\":648}]}";
    const char *plain = write_case("box", json, bin, sizeof bin);
    char cmd[1024], err[512];
    snprintf(cmd, sizeof cmd, "draco_transcoder -i '%s' -o '" DIR "/box_draco.gltf' > /dev/null", plain);
    assert_int_equal(system(cmd), 0);
    scene a, b;
    assert_int_equal(load(plain, 0, &a, err, sizeof err), 0);
    assert_int_equal(load(DIR "/box_draco.gltf", 0, &b, err, sizeof err), 0);
    assert_int_equal(a.triangle_count, 12);
    assert_int_equal(b.triangle_count, 12);
    /* Every compressed triangle is one of the plain ones (Draco may reorder the triangles
     * and start each at another corner, keeping its winding). */
    for (size_t t = 0; t < 12; t++) {
        int found = 0;
        for (size_t u = 0; u < 36 && !found; u++) {
            float dp = 0, dn = 0;
            for (int i = 0; i < 9; i++) {
                size_t j = 9 * (u / 3) + (i + 3 * (u % 3)) % 9;
                dp = fmaxf(dp, fabsf(b.positions[9 * t + i] - a.positions[j]));
                dn = fmaxf(dn, fabsf(b.normals[9 * t + i] - a.normals[j]));
            }
            found = dp < 1e-3f && dn < 0.02f;
        }
        assert_true(found);
    }
    scene_free(&a);
    scene_free(&b);
    /* Its bytes overwritten: refused naming the primitive's extension. */
    FILE *f = fopen(DIR "/box_draco.bin", "r+b");
    assert_non_null(f);
    const unsigned char junk[16] = "not a draco mesh";
    assert_int_equal(fwrite(junk, 1, sizeof junk, f), sizeof junk);
    fclose(f);
    expect_refused(DIR "/box_draco.gltf", "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression: cannot decode");
}

/* glTF 1.0 is named for what it is: by asset.version (a string, or a number as 1.0
 * exporters wrote it), by its dictionaries where there is no
 * "asset", and in the binary container by its version field. */
static void test_gltf1(void **state)
{
    (void)state;
    expect_refused(write_case("v1", "{\"asset\":{\"version\":\"1.0\"},\"scene\":\"defaultScene\","
                                    "\"scenes\":{\"defaultScene\":{\"nodes\":[]}}}", NULL, 0),
                   "glTF 1.0 is not supported (asset.version): convert the file to glTF 2.0");
    expect_refused(write_case("v1_number", "{\"asset\":{\"version\":1.0},\"scene\":\"s\"}", NULL, 0),
                   "glTF 1.0 is not supported (asset.version is the number 1.0): convert the file to glTF 2.0");
    expect_refused(write_case("v1_no_asset", "{\"scene\":\"s\",\"meshes\":{\"m\":{\"primitives\":[]}}}", NULL, 0),
                   "glTF 1.0 is not supported (\"meshes\" is a dictionary, no \"asset\")");
    const unsigned char glb1[20] = {'g', 'l', 'T', 'F', 1, 0, 0, 0, 20, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    write_file(DIR "/v1.glb", glb1, sizeof glb1);
    expect_refused(DIR "/v1.glb", "binary glTF 1.0 (KHR_binary_glTF) is not supported");
    expect_refused(write_case("v3", "{\"asset\":{\"version\":\"3.0\"}}", NULL, 0),
                   "asset.version \"3.0\" is not supported (glTF 2.x)");
}

#define TRI_JSON(extra, nodes)                                                                  \
    "{\"asset\":{\"version\":\"2.0\"}," extra "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"       \
    "\"nodes\":" nodes ",\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":0}]}],"   \
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"}],"    \
    "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"buffers\":[{\"uri\":\"BIN\",\"byteLength\":36}]}"
static const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};

/* A required extension it cannot honour is named; one only used is noted, and the file
 * loads with its fallback. */
static void test_extensions(void **state)
{
    (void)state;
    expect_refused(write_case("meshopt", TRI_JSON("\"extensionsUsed\":[\"EXT_meshopt_compression\"],"
                                                  "\"extensionsRequired\":[\"EXT_meshopt_compression\"],"
                                                  "\"materials\":[{}],", "[{\"mesh\":0}]"), tri, sizeof tri),
                   "extensionsRequired[0]: EXT_meshopt_compression cannot be honoured (this importer reads "
                   "KHR_lights_punctual,");
    scene s;
    char err[512];
    const char *used = write_case("webp", TRI_JSON("\"extensionsUsed\":[\"EXT_texture_webp\"],"
                                                   "\"materials\":[{\"pbrMetallicRoughness\":{\"metallicFactor\":0}}],",
                                                   "[{\"mesh\":0}]"), tri, sizeof tri);
    assert_int_equal(load(used, 0, &s, err, sizeof err), 0);
    assert_string_equal(s.warning, "extensions ignored (their fallbacks used): EXT_texture_webp");
    scene_free(&s);
}

/* Materials drawn differently from the file are named in scene.warning, one line. */
static void test_material_warning(void **state)
{
    (void)state;
    scene s;
    char err[512];
    const char *path = write_case(
        "clearcoat", TRI_JSON("\"extensionsUsed\":[\"KHR_materials_clearcoat\"],\"materials\":[{\"name\":\"Coat\","
                              "\"alphaMode\":\"BLEND\",\"pbrMetallicRoughness\":{\"metallicFactor\":0},"
                              "\"extensions\":{\"KHR_materials_clearcoat\":{\"clearcoatFactor\":1}}}],",
                              "[{\"mesh\":0}]"), tri, sizeof tri);
    assert_int_equal(load(path, 0, &s, err, sizeof err), 0);
    assert_string_equal(s.warning, "1 of 1 materials drawn differently from the file: materials[0] \"Coat\" "
                                   "(KHR_materials_clearcoat: no clear-coat layer, alphaMode BLEND: opaque)");
    scene_free(&s);
    /* Specular-glossiness (older exporters): its diffuse colour is the base colour. */
    path = write_case("spec_gloss", TRI_JSON("\"extensionsUsed\":[\"KHR_materials_pbrSpecularGlossiness\"],"
                                             "\"materials\":[{\"extensions\":{\"KHR_materials_pbrSpecularGlossiness\":"
                                             "{\"diffuseFactor\":[0.2,0.4,0.6,1]}}}],", "[{\"mesh\":0}]"), tri, sizeof tri);
    assert_int_equal(load(path, 0, &s, err, sizeof err), 0);
    const float *base = s.materials[s.triangle_material[0]].base_color;
    assert_true(base[0] == 0.2f && base[1] == 0.4f && base[2] == 0.6f);
    assert_string_equal(s.warning, "1 of 1 materials drawn differently from the file: materials[0] "
                                   "(KHR_materials_pbrSpecularGlossiness: diffuse colour only)");
    scene_free(&s);
}

/* Fields of the wrong JSON type, which tinygltf would skip, are refused by their path. */
static void test_json_types(void **state)
{
    (void)state;
    expect_refused(write_case("scene_name", "{\"asset\":{\"version\":\"2.0\"},\"scene\":\"hello\"}", NULL, 0),
                   "scene: must be an index (a whole number from 0), not a string \"hello\"");
    expect_refused(write_case("primitives_object", "{\"asset\":{\"version\":\"2.0\"},\"meshes\":[{\"primitives\":"
                                                   "{\"attributes\":{\"POSITION\":0}}}]}", NULL, 0),
                   "meshes[0].primitives: must be an array of objects, not an object");
    expect_refused(write_case("no_primitives", "{\"asset\":{\"version\":\"2.0\"},\"meshes\":[{\"name\":\"m\"}]}", NULL, 0),
                   "meshes[0].primitives: missing (an array of objects is required)");
    expect_refused(write_case("matrix", TRI_JSON("", "[{\"mesh\":0,\"matrix\":[1,0]}]"), tri, sizeof tri),
                   "nodes[0].matrix: must be an array of 16 numbers, not an array of 2");
    expect_refused(write_case("no_asset", "{\"scenes\":[]}", NULL, 0),
                   "asset: missing (an object is required)");
    expect_refused(write_case("broken", "{\"asset\":{\"version\":\"2.0\"},\n\"scenes\":[}", NULL, 0),
                   "not valid JSON near line 2");
}

/* Buffers and images only from the scene file's folder or below: a uri that climbs out and
 * a link inside that points out are refused naming the uri (never the size of what is
 * there); --allow-outside-paths (allow_outside) loads them. */
static void test_outside_paths(void **state)
{
    (void)state;
    unsigned char outside[1234] = {0};
    memcpy(outside, tri, sizeof tri);
    write_file(CAVELIGHT_BINARY_DIR "/test_gltf_exporters_outside.bin", outside, sizeof outside);
    const char *up = write_case("climb", TRI_JSON("\"materials\":[{}],", "[{\"mesh\":0}]"), NULL, 0);
    char text[4096];
    FILE *f = fopen(up, "r");
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    char *bin = strstr(text, "\"climb.bin\"");
    char fixed[4096];
    snprintf(fixed, sizeof fixed, "%.*s\"../test_gltf_exporters_outside.bin\"%s", (int)(bin - text), text, bin + 11);
    write_file(up, fixed, strlen(fixed));
    scene s;
    char err[512] = "";
    assert_int_equal(scene_load(up, &s, err, sizeof err), -1);
    assert_non_null(strstr(err, "buffers[0].uri \"../test_gltf_exporters_outside.bin\" is outside the scene "
                                "file's folder (--allow-outside-paths allows it)"));
    assert_null(strstr(err, "1234"));
    write_file(CAVELIGHT_BINARY_DIR "/test_gltf_exporters_outside.bin", tri, sizeof tri);
    assert_int_equal(load(up, 1, &s, err, sizeof err), 0);
    assert_int_equal(s.triangle_count, 1);
    scene_free(&s);
    /* A link inside the folder to the same file outside. */
    unlink(DIR "/link.bin");
    assert_int_equal(symlink("../test_gltf_exporters_outside.bin", DIR "/link.bin"), 0);
    snprintf(fixed, sizeof fixed, "%.*s\"link.bin\"%s", (int)(bin - text), text, bin + 11);
    write_file(DIR "/link.gltf", fixed, strlen(fixed));
    expect_refused(DIR "/link.gltf", "buffers[0].uri \"link.bin\" is outside the scene file's folder");
    /* An image from a folder beside. */
    const char *image = write_case("image", TRI_JSON("\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":"
                                                     "{\"index\":0}}}],\"textures\":[{\"source\":0}],\"images\":"
                                                     "[{\"uri\":\"../test_gltf_exporters_outside.bin\"}],",
                                                     "[{\"mesh\":0}]"), tri, sizeof tri);
    expect_refused(image, "images[0].uri \"../test_gltf_exporters_outside.bin\" is outside");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_triangle_strip),
        cmocka_unit_test(test_triangle_fan),
        cmocka_unit_test(test_quantized),
        cmocka_unit_test(test_texture_transform),
        cmocka_unit_test(test_draco),
        cmocka_unit_test(test_gltf1),
        cmocka_unit_test(test_extensions),
        cmocka_unit_test(test_material_warning),
        cmocka_unit_test(test_json_types),
        cmocka_unit_test(test_outside_paths),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
