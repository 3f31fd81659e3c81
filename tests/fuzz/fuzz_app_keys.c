/* libFuzzer target: an application's key records as the wire carries them. The schema is
 * the core keys and the frame settings plus one application key of each kind an
 * application can add (app_host.c: number, vector, matrix, string, blob); any bytes go to
 * params_apply() as a snapshot or delta of that schema, onto a fresh store and onto one
 * holding values in every application key, with the same verdict. What applies must encode
 * and apply again to the same checksum. Built with clang -fsanitize=fuzzer,address,
 * undefined by CMake when clang is present. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cluster/params.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

enum { STRING_CAP = 64, BLOB_CAP = 256 };

static params_schema schema;
static int keys[5];

static void schema_once(void)
{
    static const struct { const char *name; params_type type; size_t capacity; } app[5] = {
        {"app.speed", PARAMS_T_F64, 0},     {"app.tint", PARAMS_T_VEC3, 0},
        {"app.pose", PARAMS_T_MAT4, 0},     {"app.label", PARAMS_T_STRING, STRING_CAP},
        {"app.state", PARAMS_T_BLOB, BLOB_CAP},
    };
    char why[256];
    params_schema_init(&schema);
    for (int i = 0; i < 5; i++)
        if ((keys[i] = params_schema_add_key(&schema, app[i].name, app[i].type, app[i].capacity, NULL, why,
                                             sizeof why)) < 0)
            abort();
}

/* Every application key given a value, committed. */
static void seed_values(params_store *s)
{
    static const float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1};
    static const float v[3] = {0.25f, 0.5f, 1};
    static const uint8_t blob[BLOB_CAP] = {1, 2, 3};
    if (params_set_f64(s, keys[0], 2.5) || params_set(s, keys[1], v, sizeof v) ||
        params_set_mat4(s, keys[2], m) || params_set_bytes(s, keys[3], "hello", 5) ||
        params_set_bytes(s, keys[4], blob, sizeof blob))
        abort();
    params_commit(s);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static uint8_t enc[PARAMS_ENCODED_MAX];
    static params_store fresh, seeded, copy;
    if (!schema.count)
        schema_once();
    if (size < 8)
        return 0;
    uint64_t version;
    memcpy(&version, data, sizeof version);
    params_init(&fresh, &schema);
    params_init(&seeded, &schema);
    seed_values(&seeded);
    int ok = params_apply(&fresh, version, data + 8, size - 8) == 0;
    if (ok != (params_apply(&seeded, version, data + 8, size - 8) == 0))
        abort();
    if (!ok)
        return 0;
    size_t n = params_encode_snapshot(&fresh, enc, sizeof enc);
    params_init(&copy, &schema);
    if (n == 0 || params_apply(&copy, fresh.version, enc, n) != 0 ||
        params_checksum(&copy) != params_checksum(&fresh))
        abort();
    return 0;
}
