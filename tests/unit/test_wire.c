/* wire: round trips, CRC, and that no truncated, corrupted, oversized or random buffer
 * ever decodes as a valid message. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "cluster/params.h"
#include "cluster/wire.h"

static size_t sample(int type, uint8_t *buf, size_t cap, const uint8_t *params, size_t plen)
{
    wire_msg m = {.type = (wire_type)type, .version = 42, .base_version = 41,
                  .config_hash = 0x1122334455667788ull, .checksum = 0xdeadbeefcafef00dull,
                  .timings = {0.5f, 1.5f, 2.5f, 3.5f}, .reason = 7, .params = params, .params_len = plen};
    strcpy(m.name, "n01");
    strcpy(m.text, "scene x.gltf: no such file");
    return wire_encode(&m, buf, cap);
}

static void test_crc32_reference(void **state)
{
    assert_int_equal(wire_crc32("123456789", 9), 0xCBF43926u);
    assert_int_equal(wire_crc32("", 0), 0);
}

/* Messages of protocol 1, captured from the build before CRC-32 came from zlib: every
 * byte but the protocol version (2 since the store's gi key) and the CRC that covers it
 * must be the same, and each must decode. */
static const struct { int type; const char *hex; } golden[] = {
        {WIRE_HELLO,
         "43564c540100010014000000aed608b1036e303188776655443322112a000000"
         "00000000"},
        {WIRE_SNAPSHOT,
         "43564c5401000200140000009e12fa072a000000000000000800000001020304"
         "05060708"},
        {WIRE_FRAME,
         "43564c54010003001c00000020568dde2a000000000000002900000000000000"
         "080000000102030405060708"},
        {WIRE_READY,
         "43564c540100040024000000f9297c90036e30312a000000000000000df0feca"
         "efbeadde0000003f0000c03f0000204000006040"},
        {WIRE_SWAP,
         "43564c540100050008000000d08f088d2a00000000000000"},
        {WIRE_BYE,
         "43564c540100060008000000ec4a35c9036e303107000000"},
        {WIRE_HEARTBEAT,
         "43564c54010007000c000000c91c79d9036e30312a00000000000000"},
};
/* A protocol 1 FRAME carrying a delta: head pose, time, lambda_incr and light 0's colour,
 * in key order. The keys of lambda_incr (6) and light 0's colour (0x12) have moved since
 * (protocol 5 numbers keys by a schema: the core keys, the lights, then the settings). */
static const char *golden_frame_delta =
    "43564c5401000300740000007cee990f02000000000000000100000000000000"
    "6000000000000000803f000000000000000000000000000000000000803f0000"
    "00000000000000000000000000000000803f000000000000803e9a99d93f0000"
    "00bf0000803f0300111111111111a13f06000000203f12000000003f0000803e"
    "0000803f";

static size_t from_hex(const char *hex, uint8_t *out)
{
    size_t n = strlen(hex) / 2;
    for (size_t i = 0; i < n; i++) {
        unsigned b;
        sscanf(hex + 2 * i, "%2x", &b);
        out[i] = (uint8_t)b;
    }
    return n;
}

static void test_encoding_unchanged(void **state)
{
    uint8_t params[8] = {1, 2, 3, 4, 5, 6, 7, 8}, want[WIRE_MAX_MESSAGE], got[WIRE_MAX_MESSAGE];
    for (size_t i = 0; i < sizeof golden / sizeof golden[0]; i++) {
        size_t n = from_hex(golden[i].hex, want);
        assert_int_equal(sample(golden[i].type, got, sizeof got, params, sizeof params), n);
        assert_memory_equal(got, want, 4);                  /* magic */
        assert_int_equal(got[4] | got[5] << 8, WIRE_PROTOCOL);
        assert_memory_equal(got + 6, want + 6, 6);          /* type, payload length */
        assert_memory_equal(got + WIRE_HEADER_SIZE, want + WIRE_HEADER_SIZE, n - WIRE_HEADER_SIZE);
        wire_msg m;
        assert_int_equal(wire_decode(got, n, &m), WIRE_OK);
    }
    static params_schema schema;
    static params_store s;
    params_schema_init(&schema);
    params_init(&s, &schema);
    params_commit(&s);
    float head[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.25f, 1.7f, -0.5f, 1};
    int lambda = params_schema_find(&schema, "lambda"), color_key = params_light_key(0, PARAMS_LIGHT_COLOR);
    params_set_mat4(&s, PARAMS_HEAD, head);
    params_set_f64(&s, PARAMS_TIME, 1.0 / 30);
    params_set_f32(&s, lambda, 0.625f);
    const float color[3] = {0.5f, 0.25f, 1};
    params_set(&s, params_light_key(0, PARAMS_LIGHT_COLOR), color, sizeof color);
    uint64_t v = params_commit(&s);
    static uint8_t delta[PARAMS_ENCODED_MAX];
    size_t dn = params_encode_delta(&s, v - 1, delta, sizeof delta);
    wire_msg f = {.type = WIRE_FRAME, .version = v, .base_version = v - 1, .params = delta,
                  .params_len = dn};
    size_t n = from_hex(golden_frame_delta, want);
    assert_int_equal(wire_encode(&f, got, sizeof got), n);
    assert_memory_equal(got, want, 4);
    assert_int_equal(got[4] | got[5] << 8, WIRE_PROTOCOL);
    assert_memory_equal(got + 6, want + 6, 6);
    /* The same records, in key order: versions, head and time (keys 0 and 3) alike; then
     * protocol 1 had lambda (6) before the colour (0x12), protocol 5 the colour first. */
    assert_memory_equal(got + WIRE_HEADER_SIZE, want + WIRE_HEADER_SIZE, n - 20 - WIRE_HEADER_SIZE);
    assert_int_equal(want[n - 20] | want[n - 19] << 8, 6);
    assert_int_equal(want[n - 14] | want[n - 13] << 8, 0x12);
    assert_int_equal(got[n - 20] | got[n - 19] << 8, color_key);
    assert_memory_equal(got + n - 18, want + n - 12, 12);
    assert_int_equal(got[n - 6] | got[n - 5] << 8, lambda);
    assert_memory_equal(got + n - 4, want + n - 18, 4);
}

static void test_round_trip_every_type(void **state)
{
    uint8_t params[100], buf[WIRE_MAX_MESSAGE];
    for (int i = 0; i < 100; i++)
        params[i] = (uint8_t)(i * 7);
    for (int t = WIRE_HELLO; t < WIRE_TYPE_END; t++) {
        size_t len = sample(t, buf, sizeof buf, params, sizeof params);
        assert_true(len >= WIRE_HEADER_SIZE);
        wire_msg m;
        assert_int_equal(wire_decode(buf, len, &m), WIRE_OK);
        assert_int_equal(m.type, t);
        switch (t) {
        case WIRE_HELLO:
            assert_string_equal(m.name, "n01");
            assert_int_equal(m.config_hash, 0x1122334455667788ull);
            assert_int_equal(m.version, 42);
            break;
        case WIRE_SNAPSHOT:
        case WIRE_FRAME:
            assert_int_equal(m.version, 42);
            assert_int_equal(m.base_version, t == WIRE_FRAME ? 41 : 0);
            assert_int_equal(m.params_len, sizeof params);
            assert_memory_equal(m.params, params, sizeof params);
            break;
        case WIRE_READY:
            assert_string_equal(m.name, "n01");
            assert_int_equal(m.checksum, 0xdeadbeefcafef00dull);
            assert_float_equal(m.timings[WIRE_TIMING_TOTAL], 3.5f, 0);
            break;
        case WIRE_SWAP:
            assert_int_equal(m.version, 42);
            break;
        case WIRE_BYE:
            assert_int_equal(m.reason, 7);
            break;
        case WIRE_HEARTBEAT:
            assert_string_equal(m.name, "n01");
            break;
        case WIRE_REFUSE:
            assert_string_equal(m.name, "n01");
            assert_int_equal(m.reason, 7);
            assert_int_equal(m.version, 42);
            assert_string_equal(m.text, "scene x.gltf: no such file");
            break;
        }
    }
}

static void test_truncation_and_bit_flips_rejected(void **state)
{
    uint8_t params[40], buf[WIRE_MAX_MESSAGE];
    memset(params, 0xab, sizeof params);
    for (int t = WIRE_HELLO; t < WIRE_TYPE_END; t++) {
        size_t len = sample(t, buf, sizeof buf, params, sizeof params);
        wire_msg m;
        for (size_t cut = 0; cut < len; cut++)
            assert_int_not_equal(wire_decode(buf, cut, &m), WIRE_OK);
        for (size_t bit = 0; bit < len * 8; bit++) {
            buf[bit / 8] ^= (uint8_t)(1u << (bit % 8));
            assert_int_not_equal(wire_decode(buf, len, &m), WIRE_OK);
            buf[bit / 8] ^= (uint8_t)(1u << (bit % 8));
        }
        assert_int_equal(wire_decode(buf, len, &m), WIRE_OK);
    }
}

static void test_oversized_and_bad_fields(void **state)
{
    static uint8_t big[WIRE_MAX_PAYLOAD + 1], buf[WIRE_MAX_MESSAGE + 64];
    /* Encoder refuses what the decoder would refuse. */
    assert_int_equal(sample(WIRE_FRAME, buf, sizeof buf, big, sizeof big), 0);
    assert_int_equal(sample(WIRE_FRAME, buf, 20, big, 10), 0);
    wire_msg m = {.type = WIRE_HELLO};
    strcpy(m.name, "bad name");
    assert_int_equal(wire_encode(&m, buf, sizeof buf), 0);
    m.name[0] = 0;
    assert_int_equal(wire_encode(&m, buf, sizeof buf), 0);
    m.type = (wire_type)99;
    assert_int_equal(wire_encode(&m, buf, sizeof buf), 0);
    /* REFUSE's text: printable only (no forged log lines), at most WIRE_TEXT_MAX. */
    wire_msg r = {.type = WIRE_REFUSE, .reason = WIRE_REFUSE_SCENE};
    strcpy(r.name, "n01");
    strcpy(r.text, "line\ncavelight-master: forged");
    assert_int_equal(wire_encode(&r, buf, sizeof buf), 0);
    memset(r.text, 'x', WIRE_TEXT_MAX);
    r.text[WIRE_TEXT_MAX] = 0;
    size_t rl = wire_encode(&r, buf, sizeof buf);
    assert_true(rl > 0);
    buf[rl - 1] = '\n'; /* a control character on the wire, CRC put right: refused */
    uint32_t rcrc;
    {
        static uint8_t tmp[WIRE_MAX_MESSAGE];
        memcpy(tmp, buf, 12);
        memcpy(tmp + 12, buf + WIRE_HEADER_SIZE, rl - WIRE_HEADER_SIZE);
        rcrc = wire_crc32(tmp, 12 + rl - WIRE_HEADER_SIZE);
    }
    memcpy(buf + 12, &rcrc, 4);
    wire_msg rd;
    assert_int_equal(wire_decode(buf, rl, &rd), WIRE_E_PAYLOAD);

    /* A header claiming a huge payload is refused before anything is read. */
    size_t len = sample(WIRE_SWAP, buf, sizeof buf, NULL, 0);
    wire_msg d;
    buf[8] = 0xff; buf[9] = 0xff; buf[10] = 0xff; buf[11] = 0x7f;
    assert_int_equal(wire_decode(buf, len, &d), WIRE_E_LENGTH);
    /* Trailing bytes after a valid message. */
    len = sample(WIRE_SWAP, buf, sizeof buf, NULL, 0);
    assert_int_equal(wire_decode(buf, len + 1, &d), WIRE_E_LENGTH);
    /* Other protocol version and type, with a correct CRC. */
    buf[4] = WIRE_PROTOCOL + 1;
    uint32_t crc;
    {
        uint8_t tmp[64];
        memcpy(tmp, buf, 12);
        memcpy(tmp + 12, buf + WIRE_HEADER_SIZE, len - WIRE_HEADER_SIZE);
        crc = wire_crc32(tmp, 12 + len - WIRE_HEADER_SIZE);
    }
    memcpy(buf + 12, &crc, 4);
    assert_int_equal(wire_decode(buf, len, &d), WIRE_E_PROTOCOL);
}

static void test_random_garbage_never_decodes(void **state)
{
    uint8_t buf[512];
    srand(12345);
    for (int i = 0; i < 200000; i++) {
        size_t len = (size_t)(rand() % (int)sizeof buf);
        for (size_t k = 0; k < len; k++)
            buf[k] = (uint8_t)rand();
        /* Half the time, a plausible header so the CRC and payload checks are reached. */
        if (len >= WIRE_HEADER_SIZE && (i & 1)) {
            uint32_t magic = WIRE_MAGIC, payload = (uint32_t)(len - WIRE_HEADER_SIZE);
            memcpy(buf, &magic, 4);
            buf[4] = WIRE_PROTOCOL;
            buf[5] = 0;
            buf[6] = (uint8_t)(1 + rand() % (WIRE_TYPE_END - 1));
            buf[7] = 0;
            memcpy(buf + 8, &payload, 4);
        }
        wire_msg m;
        assert_int_not_equal(wire_decode(buf, len, &m), WIRE_OK);
    }
}

static void test_names(void **state)
{
    assert_true(wire_name_valid("n01"));
    assert_true(wire_name_valid("front-left_2.a"));
    assert_false(wire_name_valid(""));
    assert_false(wire_name_valid("a/b"));
    assert_false(wire_name_valid("0123456789012345678901234567890123"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_crc32_reference),
        cmocka_unit_test(test_encoding_unchanged),
        cmocka_unit_test(test_round_trip_every_type),
        cmocka_unit_test(test_truncation_and_bit_flips_rejected),
        cmocka_unit_test(test_oversized_and_bad_fields),
        cmocka_unit_test(test_random_garbage_never_decodes),
        cmocka_unit_test(test_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
