/* fnv1a: the published 64-bit FNV-1a vectors, and the _le and _word forms against the byte
 * form they stand for (checksums and cache keys depend on all three staying put). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "base/fnv1a.h"

static void test_published_vectors(void **state)
{
    assert_true(fnv1a64(FNV1A64_OFFSET, "", 0) == 0xcbf29ce484222325ull);
    assert_true(fnv1a64(FNV1A64_OFFSET, "a", 1) == 0xaf63dc4c8601ec8cull);
    assert_true(fnv1a64(FNV1A64_OFFSET, "foobar", 6) == 0x85944171f73967e8ull);
}

/* The cluster's seed: HELLO's and READY's values of earlier builds. */
static void test_cluster_seed(void **state)
{
    assert_true(fnv1a64(FNV1A64_CLUSTER_SEED, "none", 4) == 0x8e37b614dbd95475ull);
}

static void test_le_is_bytes_lowest_first(void **state)
{
    const unsigned char bytes[8] = {0x08, 0x07, 0x06, 0x05, 0x04, 0x03, 0x02, 0x01};
    uint64_t v = 0x0102030405060708ull;
    assert_true(fnv1a64_le(7, v, 8) == fnv1a64(7, bytes, 8));
    assert_true(fnv1a64_le(7, v, 4) == fnv1a64(7, bytes, 4));
}

static void test_word_is_one_step(void **state)
{
    uint64_t h = 0x1234;
    assert_true(fnv1a64_word(h, 0xdeadbeefu) == (h ^ 0xdeadbeefu) * FNV1A64_PRIME);
    assert_true(fnv1a64_word(h, 0xab) == fnv1a64_le(h, 0xab, 1));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_published_vectors),
        cmocka_unit_test(test_cluster_seed),
        cmocka_unit_test(test_le_is_bytes_lowest_first),
        cmocka_unit_test(test_word_is_one_step),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
