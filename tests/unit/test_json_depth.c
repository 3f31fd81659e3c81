/* json_depth: the nesting limit every JSON reader checks before its parser recurses. The
 * pre-scan counts [ and { outside strings; a glTF (text and .glb's JSON chunk) and a
 * cluster config of 200,000 nested arrays are refused in one line naming the file and the
 * limit (issue 34: the parsers' recursion overflowed the stack). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "base/json_depth.h"
#include "cluster/cluster_config.h"
#include "scene/scene.h"

enum { DEEP = 200000 };

/* depth opening brackets (alternating [ and {"a":) and their closings, NUL-terminated. */
static char *nested(int depth, size_t *len)
{
    char *s = malloc(10 * (size_t)depth + 1);
    size_t n = 0;
    for (int i = 0; i < depth; i++)
        n += (size_t)sprintf(s + n, "%s", i % 2 ? "{\"a\":" : "[");
    for (int i = depth - 1; i >= 0; i--)
        s[n++] = i % 2 ? '}' : ']';
    s[n] = 0;
    *len = n;
    return s;
}

static void test_scan(void **state)
{
    (void)state;
    char err[128] = "";
    size_t n;
    char *ok = nested(JSON_DEPTH_MAX, &n);
    assert_int_equal(json_depth_check(ok, n, err, sizeof err), 0);
    free(ok);
    char *deep = nested(JSON_DEPTH_MAX + 1, &n);
    assert_int_equal(json_depth_check(deep, n, err, sizeof err), -1);
    assert_string_equal(err, "JSON nested deeper than 128 levels (at byte 384)");
    free(deep);
    /* brackets in strings, escaped quotes among them, are text */
    char text[1024];
    size_t k = (size_t)sprintf(text, "{\"s\":\"\\\"");
    for (int i = 0; i < 300; i++)
        text[k++] = '[';
    k += (size_t)sprintf(text + k, "\",\"t\":[1]}");
    assert_int_equal(json_depth_check(text, k, err, sizeof err), 0);
}

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, n, f), n);
    fclose(f);
}

/* Valid glTF JSON whose "extras" hold nested arrays (the importer's own checks pass). */
static void test_gltf_and_glb(void **state)
{
    (void)state;
    static const char start[] = "{\"asset\":{\"version\":\"2.0\"},\"extras\":";
    size_t h = strlen(start), n = h + 2 * (size_t)DEEP + 1;
    char *deep = malloc(n + 1);
    memcpy(deep, start, h);
    memset(deep + h, '[', DEEP);
    memset(deep + h + DEEP, ']', DEEP);
    deep[n - 1] = '}';
    deep[n] = 0;
    const char *path = CAVELIGHT_BINARY_DIR "/test_json_depth.gltf";
    write_file(path, deep, n);
    scene s;
    char err[512] = "";
    assert_int_equal(scene_load(path, &s, err, sizeof err), -1);
    print_message("%s\n", err);
    assert_non_null(strstr(err, path));
    assert_non_null(strstr(err, "JSON nested deeper than 128 levels"));
    /* the same JSON as a .glb's first chunk */
    size_t padded = (n + 3) & ~(size_t)3, total = 20 + padded;
    unsigned char *glb = calloc(1, total);
    uint32_t head[5] = {0x46546C67u, 2, (uint32_t)total, (uint32_t)padded, 0x4E4F534Au};
    memcpy(glb, head, sizeof head);
    memset(glb + 20, ' ', padded);
    memcpy(glb + 20, deep, n);
    const char *glb_path = CAVELIGHT_BINARY_DIR "/test_json_depth.glb";
    write_file(glb_path, glb, total);
    assert_int_equal(scene_load(glb_path, &s, err, sizeof err), -1);
    assert_non_null(strstr(err, "JSON nested deeper than 128 levels"));
    free(glb);
    free(deep);
}

static void test_cluster_config(void **state)
{
    (void)state;
    size_t n;
    char *deep = nested(DEEP, &n);
    cluster_config c;
    char err[512] = "";
    assert_int_equal(cluster_config_parse(deep, n, "deep.json", &c, err, sizeof err), -1);
    print_message("%s\n", err);
    assert_string_equal(err, "cluster config deep.json: JSON nested deeper than 128 levels (at byte 384)");
    scene_transform t;
    assert_int_equal(cluster_scene_transform_parse(deep, &t, err, sizeof err), -1);
    assert_non_null(strstr(err, "JSON nested deeper than 128 levels"));
    free(deep);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_scan),
        cmocka_unit_test(test_gltf_and_glb),
        cmocka_unit_test(test_cluster_config),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
