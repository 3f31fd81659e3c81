/* params: keys outside frame_params (an application's and the scene objects'): every type,
 * strings and blobs of a bounded capacity, their deltas and snapshots, the refusals of
 * bad names, types and sizes, and the bound on what a delta can make the store hold. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "cluster/params.h"
#include "gi/gi_settings.h"

static params_schema schema;
static int k_number, k_vec4, k_matrix, k_string, k_blob;

static int add(params_schema *s, const char *name, params_type t, size_t capacity, const void *initial)
{
    char err[300] = "";
    int k = params_schema_add_key(s, name, t, capacity, initial, err, sizeof err);
    if (k < 0)
        fprintf(stderr, "%s\n", err);
    return k;
}

static int setup(void **state)
{
    (void)state;
    gi_params_schema(&schema);
    const double two = 2.0;
    const float v[4] = {1, 2, 3, 4};
    k_number = add(&schema, "app.n", PARAMS_T_F64, 0, &two);
    k_vec4 = add(&schema, "app.v", PARAMS_T_VEC4, 0, v);
    k_matrix = add(&schema, "app.m", PARAMS_T_MAT4, 0, NULL);
    k_string = add(&schema, "app.s", PARAMS_T_STRING, 16, NULL);
    k_blob = add(&schema, "app.b", PARAMS_T_BLOB, 100, NULL);
    return k_number < 0 || k_vec4 < 0 || k_matrix < 0 || k_string < 0 || k_blob < 0;
}

static void test_fresh_store_holds_initial_values(void **state)
{
    (void)state;
    static params_store s;
    params_init(&s, &schema);
    double n;
    float v[4], m[16] = {1};
    size_t len = 99;
    assert_int_equal(params_get(&s, k_number, &n, 8), 0);
    assert_true(n == 2.0);
    assert_int_equal(params_get(&s, k_vec4, v, 16), 0);
    assert_true(v[3] == 4.0f);
    assert_int_equal(params_get(&s, k_matrix, m, 64), 0);
    assert_true(m[0] == 0.0f);
    assert_non_null(params_get_bytes(&s, k_string, &len));
    assert_int_equal(len, 0);
    assert_int_equal(params_changed_count(&s, 0), 0);
    /* Not in frame_params: a frame round trip leaves them alone. */
    frame_params f;
    params_to_frame(&s, &f);
    params_set_from_frame(&s, &f);
    assert_int_equal(params_changed_count(&s, 0), 0);
}

static void test_strings_and_blobs_travel_in_deltas_and_snapshots(void **state)
{
    (void)state;
    static params_store m, n, late;
    params_init(&m, &schema);
    params_init(&n, &schema);
    assert_int_equal(params_set_bytes(&m, k_string, "gr\xc3\xbc\xc3\x9f", 6), 0); /* "grüß" */
    const uint8_t blob[5] = {0, 1, 0, 255, 7};
    assert_int_equal(params_set_bytes(&m, k_blob, blob, 5), 0);
    assert_int_equal(params_changed_count(&m, 0), 2);
    uint64_t v = params_commit(&m);
    static uint8_t buf[PARAMS_ENCODED_MAX];
    size_t len = params_encode_delta(&m, v - 1, buf, sizeof buf);
    /* Two records: u16 key, u16 length, the bytes. */
    assert_int_equal(len, (2 + 2 + 6) + (2 + 2 + 5));
    assert_int_equal(params_apply(&n, v, buf, len), 0);
    size_t got;
    assert_memory_equal(params_get_bytes(&n, k_string, &got), "gr\xc3\xbc\xc3\x9f", 6);
    assert_int_equal(got, 6);
    assert_memory_equal(params_get_bytes(&n, k_blob, &got), blob, 5);
    assert_int_equal(params_checksum(&m), params_checksum(&n));
    /* A shorter value replaces a longer one whole; the checksum sees the difference. */
    assert_int_equal(params_set_bytes(&m, k_string, "a", 1), 0);
    params_commit(&m);
    assert_true(params_checksum(&m) != params_checksum(&n));
    params_init(&late, &schema);
    len = params_encode_snapshot(&m, buf, sizeof buf);
    assert_int_equal(params_apply(&late, m.version, buf, len), 0);
    assert_memory_equal(params_get_bytes(&late, k_string, &got), "a", 1);
    assert_int_equal(got, 1);
    assert_int_equal(params_checksum(&late), params_checksum(&m));
    /* An equal value stamps nothing. */
    assert_int_equal(params_set_bytes(&m, k_string, "a", 1), 0);
    assert_int_equal(params_changed_count(&m, m.version), 0);
}

static void test_bad_values_refused(void **state)
{
    (void)state;
    static params_store s;
    params_init(&s, &schema);
    char big[200];
    memset(big, 'x', sizeof big);
    assert_int_equal(params_set_bytes(&s, k_string, big, 17), -1); /* capacity 16 */
    assert_int_equal(params_set_bytes(&s, k_string, big, 16), 0);
    assert_int_equal(params_set_bytes(&s, k_blob, big, 101), -1);
    assert_int_equal(params_set_bytes(&s, k_string, "a\0b", 3), -1);      /* NUL */
    assert_int_equal(params_set_bytes(&s, k_string, "\xc3", 1), -1);      /* cut sequence */
    assert_int_equal(params_set_bytes(&s, k_string, "\xc0\xaf", 2), -1);  /* overlong '/' */
    assert_int_equal(params_set_bytes(&s, k_string, "\xed\xa0\x80", 3), -1); /* surrogate */
    assert_int_equal(params_set_bytes(&s, k_number, "12345678", 8), -1);  /* not bytes */
    assert_int_equal(params_set(&s, k_string, big, 0), -1);               /* not fixed */
    assert_int_equal(params_key_size(&s, k_blob), 0);
}

/* Records as a malicious master (or a corrupted delta) might write them. */
static size_t record(uint8_t *p, int key, size_t len, const void *data)
{
    p[0] = (uint8_t)key;
    p[1] = (uint8_t)(key >> 8);
    p[2] = (uint8_t)len;
    p[3] = (uint8_t)(len >> 8);
    memcpy(p + 4, data, len);
    return 4 + len;
}

static void test_malformed_records_change_nothing(void **state)
{
    (void)state;
    static params_store s;
    params_init(&s, &schema);
    uint64_t before = params_checksum(&s);
    static uint8_t buf[PARAMS_BYTES_KEY_MAX * 4];
    static uint8_t junk[PARAMS_BYTES_KEY_MAX * 2];
    memset(junk, 'y', sizeof junk);
    /* A valid record, then one longer than its key's capacity: nothing applied. */
    size_t n = record(buf, k_string, 3, "abc");
    n += record(buf + n, k_blob, 101, junk);
    assert_int_equal(params_apply(&s, 1, buf, n), -1);
    /* A length beyond the buffer, a string with NUL, the largest length a record can say. */
    n = record(buf, k_blob, 10, junk) - 5;
    assert_int_equal(params_apply(&s, 1, buf, n), -1);
    n = record(buf, k_string, 3, "a\0c");
    assert_int_equal(params_apply(&s, 1, buf, n), -1);
    n = record(buf, k_blob, 65535 > sizeof junk ? sizeof junk : 65535, junk);
    assert_int_equal(params_apply(&s, 1, buf, n), -1);
    /* A duplicate, a truncated length. */
    n = record(buf, k_string, 1, "a");
    n += record(buf + n, k_string, 1, "b");
    assert_int_equal(params_apply(&s, 1, buf, n), -1);
    buf[0] = (uint8_t)k_string;
    buf[1] = (uint8_t)(k_string >> 8);
    buf[2] = 1;
    assert_int_equal(params_apply(&s, 1, buf, 3), -1);
    assert_int_equal(params_checksum(&s), before);
    assert_int_equal(s.version, 0);
}

static void test_schema_refusals(void **state)
{
    (void)state;
    static params_schema s;
    char err[300];
    gi_params_schema(&s);
    uint64_t hash = s.hash;
    char name[PARAMS_NAME_MAX + 1];
    memset(name, 'n', PARAMS_NAME_MAX);
    name[PARAMS_NAME_MAX] = '\0';
    assert_int_equal(params_schema_add_key(&s, name, PARAMS_T_F64, 0, NULL, err, sizeof err), -1);
    assert_non_null(strstr(err, "1 to 63 bytes"));
    assert_int_equal(params_schema_add_key(&s, "", PARAMS_T_F64, 0, NULL, err, sizeof err), -1);
    assert_int_equal(params_schema_add_key(&s, "head", PARAMS_T_F64, 0, NULL, err, sizeof err), -1);
    assert_non_null(strstr(err, "registered twice"));
    assert_int_equal(params_schema_add_key(&s, "x", PARAMS_T_COUNT, 0, NULL, err, sizeof err), -1);
    assert_int_equal(params_schema_add_key(&s, "x", PARAMS_T_BLOB, 0, NULL, err, sizeof err), -1);
    assert_int_equal(params_schema_add_key(&s, "x", PARAMS_T_BLOB, PARAMS_BYTES_KEY_MAX + 1, NULL, err, sizeof err),
                     -1);
    assert_non_null(strstr(err, "does not fit"));
    assert_int_equal(s.hash, hash); /* nothing was added */
    /* The arena is shared: four full keys fill it, a fifth byte does not fit. */
    for (int i = 0; i < PARAMS_BYTES_MAX / PARAMS_BYTES_KEY_MAX; i++) {
        char nm[16];
        snprintf(nm, sizeof nm, "blob%d", i);
        assert_true(params_schema_add_key(&s, nm, PARAMS_T_BLOB, PARAMS_BYTES_KEY_MAX, NULL, err, sizeof err) >= 0);
    }
    assert_int_equal(params_schema_add_key(&s, "one_more", PARAMS_T_STRING, 1, NULL, err, sizeof err), -1);
    /* The key table is bounded too. */
    int added = 0;
    for (int i = 0; s.count < PARAMS_MAX_KEYS; i++, added++) {
        char nm[16];
        snprintf(nm, sizeof nm, "k%d", i);
        assert_true(params_schema_add_key(&s, nm, PARAMS_T_F64, 0, NULL, err, sizeof err) >= 0);
    }
    assert_int_equal(params_schema_add_key(&s, "full", PARAMS_T_F64, 0, NULL, err, sizeof err), -1);
    assert_non_null(strstr(err, "store is full"));
    /* Even so, a snapshot of every key at its largest fits one message (wire.h). */
    static params_store st;
    params_init(&st, &s);
    static uint8_t big[PARAMS_BYTES_KEY_MAX];
    for (int k = 0; k < s.count; k++)
        if (s.keys[k].type == PARAMS_T_BLOB)
            assert_int_equal(params_set_bytes(&st, k, big, s.keys[k].capacity), 0);
    static uint8_t buf[PARAMS_ENCODED_MAX];
    size_t len = params_encode_snapshot(&st, buf, sizeof buf);
    assert_true(len != PARAMS_ENCODE_TOO_SMALL && len <= PARAMS_ENCODED_MAX);
    printf("a full store: %d keys, %zu bytes of strings and blobs, snapshot %zu bytes\n", s.count, s.bytes_used,
           len);
}

static void test_hash_covers_names_types_capacities_and_initial_values(void **state)
{
    (void)state;
    static params_schema a, b, c, d;
    char err[300];
    const double one = 1, two = 2;
    gi_params_schema(&a);
    b = c = d = a;
    params_schema_add_key(&a, "app.x", PARAMS_T_F64, 0, &one, err, sizeof err);
    params_schema_add_key(&b, "app.x", PARAMS_T_F64, 0, &two, err, sizeof err);
    params_schema_add_key(&c, "app.x", PARAMS_T_STRING, 10, NULL, err, sizeof err);
    params_schema_add_key(&d, "app.x", PARAMS_T_STRING, 11, NULL, err, sizeof err);
    assert_true(a.hash != b.hash);
    assert_true(a.hash != c.hash);
    assert_true(c.hash != d.hash);
    assert_true(params_session_hash(7, &c) != params_session_hash(7, &d));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fresh_store_holds_initial_values),
        cmocka_unit_test(test_strings_and_blobs_travel_in_deltas_and_snapshots),
        cmocka_unit_test(test_bad_values_refused),
        cmocka_unit_test(test_malformed_records_change_nothing),
        cmocka_unit_test(test_schema_refusals),
        cmocka_unit_test(test_hash_covers_names_types_capacities_and_initial_values),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
