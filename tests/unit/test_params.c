/* params: versions, deltas carry exactly the changed keys, snapshots, validation. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "cluster/params.h"
#include "gi/gi_settings.h"
#include "gi/vpl/vpl_settings.h"

/* Every program's schema: the core keys and every GI and display setting. */
static params_schema schema;

/* f with every GI setting resolved (set, at its value or default), so that frames that
 * mean the same compare equal byte for byte. */
static void resolve(frame_params *f)
{
    for (int i = 0; i < gi_option_count(); i++)
        gi_option_put(gi_option_at(i), gi_option_get(gi_option_at(i), f), f);
}

static int key(const char *name)
{
    int k = params_schema_find(&schema, name);
    assert_true(k >= 0);
    return k;
}

static void head_at(float m[16], float x, float y, float z)
{
    memset(m, 0, 64);
    m[0] = m[5] = m[10] = m[15] = 1;
    m[12] = x;
    m[13] = y;
    m[14] = z;
}

static void test_fresh_stores_agree(void **state)
{
    params_store a, b;
    params_init(&a, &schema);
    params_init(&b, &schema);
    assert_int_equal(a.version, 0);
    assert_int_equal(params_changed_count(&a, 0), 0);
    assert_int_equal(params_checksum(&a), params_checksum(&b));
    /* A fresh store holds frame_params_default(), field for field. */
    frame_params f, d;
    params_to_frame(&a, &f);
    frame_params_default(&d);
    resolve(&d);
    assert_memory_equal(&f, &d, sizeof f);
}

static void test_delta_carries_only_changes(void **state)
{
    params_store m, n;
    params_init(&m, &schema);
    params_init(&n, &schema);
    float head[16];
    head_at(head, 0.1f, 1.7f, 0.2f);
    assert_int_equal(params_set_mat4(&m, PARAMS_HEAD, head), 0);
    assert_int_equal(params_set_f64(&m, PARAMS_TIME, 1.0 / 60), 0);
    assert_int_equal(params_commit(&m), 1);
    assert_int_equal(params_changed_count(&m, 0), 2);

    static uint8_t buf[PARAMS_ENCODED_MAX];
    size_t len = params_encode_delta(&m, 0, buf, sizeof buf);
    assert_int_equal(len, (2 + 64) + (2 + 8));
    assert_int_equal(params_apply(&n, 1, buf, len), 0);
    assert_int_equal(n.version, 1);
    assert_int_equal(params_checksum(&n), params_checksum(&m));

    /* Same head again: not a change. New time: the only key in the next delta. */
    params_set_mat4(&m, PARAMS_HEAD, head);
    params_set_f64(&m, PARAMS_TIME, 2.0 / 60);
    params_commit(&m);
    len = params_encode_delta(&m, 1, buf, sizeof buf);
    assert_int_equal(len, 2 + 8);
    assert_int_equal(params_apply(&n, 2, buf, len), 0);
    assert_int_equal(params_checksum(&n), params_checksum(&m));

    /* Nothing changed: an empty delta, still a valid version step. */
    params_commit(&m);
    assert_int_equal(params_encode_delta(&m, 2, buf, sizeof buf), 0);
    assert_int_equal(params_apply(&n, 3, buf, 0), 0);
    assert_int_equal(params_checksum(&n), params_checksum(&m));
}

static void test_snapshot_joins_late(void **state)
{
    params_store m, late;
    params_init(&m, &schema);
    params_set_i32(&m, PARAMS_LIGHT_COUNT, 1);
    for (int v = 1; v <= 50; v++) {
        float head[16];
        head_at(head, sinf((float)v), 1.7f, 0);
        params_set_mat4(&m, PARAMS_HEAD, head);
        params_set_u32(&m, PARAMS_RESET_EPOCH, (uint32_t)(v / 10));
        params_set_f32(&m, params_light_key(0, PARAMS_LIGHT_INTENSITY), (float)v);
        params_commit(&m);
    }
    /* A late store gets everything, whatever it held before. */
    params_init(&late, &schema);
    params_set_i32(&late, key("steps"), 99);
    static uint8_t buf[PARAMS_ENCODED_MAX];
    size_t len = params_encode_snapshot(&m, buf, sizeof buf);
    size_t expect = 0;
    for (int k = 0; k < schema.count; k++)
        expect += 2 + params_key_size(&m, k);
    assert_int_equal(len, expect);
    assert_true(len <= PARAMS_ENCODED_MAX);
    assert_int_equal(params_apply(&late, m.version, buf, len), 0);
    assert_int_equal(params_checksum(&late), params_checksum(&m));
    frame_params a, b;
    params_to_frame(&m, &a);
    params_to_frame(&late, &b);
    assert_memory_equal(&a, &b, sizeof a);
    assert_int_equal(b.version, 50);
    assert_int_equal(b.reset_epoch, 5);
    assert_float_equal(b.lights[0].intensity, 50.0f, 0);
}

static void test_small_buffer_reported(void **state)
{
    params_store m;
    params_init(&m, &schema);
    uint8_t buf[100];
    assert_int_equal(params_encode_snapshot(&m, buf, sizeof buf), PARAMS_ENCODE_TOO_SMALL);
}

static void test_bad_deltas_leave_store_unchanged(void **state)
{
    params_store m, n;
    params_init(&m, &schema);
    params_init(&n, &schema);
    float head[16];
    head_at(head, 1, 2, 3);
    params_set_mat4(&m, PARAMS_HEAD, head);
    params_set_f32(&m, key("exposure"), 2.0f);
    params_commit(&m);
    static uint8_t buf[PARAMS_ENCODED_MAX];
    size_t len = params_encode_delta(&m, 0, buf, sizeof buf);
    uint64_t before = params_checksum(&n);

    /* Every truncation except a record boundary that ends a whole record fails. */
    for (size_t cut = 1; cut < len; cut++) {
        int rc = params_apply(&n, 1, buf, cut);
        if (cut == 2 + 64) {
            assert_int_equal(rc, 0); /* just the head record */
            params_init(&n, &schema);
        } else {
            assert_int_equal(rc, -1);
        }
        assert_int_equal(params_checksum(&n), before);
    }
    /* Unknown key. */
    uint8_t bad[8] = {0xff, 0x7f, 0, 0, 0, 0, 0, 0};
    assert_int_equal(params_apply(&n, 1, bad, 6), -1);
    /* Duplicate key. */
    uint8_t dup[12];
    float e = 3.0f;
    dup[0] = (uint8_t)key("exposure");
    dup[1] = (uint8_t)(key("exposure") >> 8);
    memcpy(dup + 2, &e, 4);
    memcpy(dup + 6, dup, 6);
    assert_int_equal(params_apply(&n, 1, dup, 12), -1);
    assert_int_equal(params_apply(&n, 1, dup, 6), 0);
    assert_float_equal(params_get_f32(&n, key("exposure")), 3.0f, 0);
    /* Non-finite float. */
    float nan = NAN;
    memcpy(dup + 2, &nan, 4);
    assert_int_equal(params_apply(&n, 2, dup, 6), -1);
    assert_int_equal(n.version, 1);
}

static void test_typed_setters(void **state)
{
    params_store s;
    params_init(&s, &schema);
    assert_int_equal(params_set_f32(&s, PARAMS_HEAD, 1.0f), -1);
    assert_int_equal(params_set_i32(&s, schema.count, 1), -1);
    assert_int_equal(params_set_f32(&s, key("vpl-count"), 1.0f), -1); /* an int key */
    assert_int_equal(params_light_key(FRAME_MAX_LIGHTS, 0), -1);
    assert_string_equal(params_key_name(&s, params_light_key(3, PARAMS_LIGHT_POSE)), "light3.pose");
    assert_string_equal(params_key_name(&s, params_light_key(2, PARAMS_LIGHT_TYPE)), "light2.type");
    assert_string_equal(params_key_name(&s, key("vpl-selection")), "vpl-selection");
    assert_int_equal(params_changed_count(&s, 0), 0);

    frame_params f;
    params_to_frame(&s, &f);
    f.light_count = 2;
    f.lights[1] = f.lights[0];
    f.lights[1].position[0] = 4;
    f.lights[1].type = SCENE_LIGHT_DIRECTIONAL;
    f.lambda_incr = 0.5f;
    assert_null(gi_set(&f, "vpl-selection", "regular"));
    assert_null(gi_set(&f, "gi", "vpl"));
    params_set_from_frame(&s, &f);
    params_commit(&s);
    frame_params g;
    params_to_frame(&s, &g);
    f.version = 1;
    assert_memory_equal(&f, &g, sizeof f);
}

/* A frame's unset GI setting travels as its default; a set one as its value, in the
 * frame's slot on the other side. */
static void test_gi_settings_travel(void **state)
{
    params_store m, n;
    params_init(&m, &schema);
    params_init(&n, &schema);
    frame_params f;
    frame_params_default(&f);
    assert_null(gi_set(&f, "vpl-interleave", "4"));
    params_set_from_frame(&m, &f);
    params_commit(&m);
    static uint8_t buf[PARAMS_ENCODED_MAX];
    size_t len = params_encode_delta(&m, 0, buf, sizeof buf);
    assert_int_equal(len, 2 + 4); /* only the changed setting */
    assert_int_equal(params_apply(&n, 1, buf, len), 0);
    frame_params g;
    params_to_frame(&n, &g);
    const gi_option *o = gi_option_find("vpl-interleave");
    assert_true(gi_option_is_set(o, &g));
    assert_int_equal(gi_option_get(o, &g).i, 4);
    assert_int_equal(gi_option_get(gi_option_find("vpl-count"), &g).i, VPL_COUNT_DEFAULT);
}

/* Another build's keys: the hello hash differs for the same config. */
static void test_session_hash_covers_the_schema(void **state)
{
    params_schema core;
    params_schema_init(&core);
    assert_true(core.hash != schema.hash);
    assert_true(params_session_hash(7, &core) != params_session_hash(7, &schema));
    assert_true(params_session_hash(7, &schema) != params_session_hash(8, &schema));
    assert_true(params_session_hash(7, &schema) == params_session_hash(7, &schema));
    /* A name taken twice is refused. */
    assert_int_equal(params_schema_add(&core, &frame_transport_settings[0], 0, -1), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fresh_stores_agree),
        cmocka_unit_test(test_delta_carries_only_changes),
        cmocka_unit_test(test_snapshot_joins_late),
        cmocka_unit_test(test_small_buffer_reported),
        cmocka_unit_test(test_bad_deltas_leave_store_unchanged),
        cmocka_unit_test(test_typed_setters),
        cmocka_unit_test(test_gi_settings_travel),
        cmocka_unit_test(test_session_hash_covers_the_schema),
    };
    gi_params_schema(&schema);
    return cmocka_run_group_tests(tests, NULL, NULL);
}
