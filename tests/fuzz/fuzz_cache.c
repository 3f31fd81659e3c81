/* libFuzzer target: any bytes as a light cache file (caches-HASH.bin, what anyone who can
 * write the cache folder could leave there) through cache_file_parse(), the reader's checks
 * and decoding. The key the reader expects is taken from the input's own header, so that
 * mutations get past the key check to the size, checksum and records; a file that passes
 * must decode to the count its header gives. Built with clang -fsanitize=fuzzer,address,
 * undefined by CMake when clang is present. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "gi/caches/cache_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static uint64_t le(const uint8_t *p, int n)
{
    uint64_t v = 0;
    for (int i = n - 1; i >= 0; i--)
        v = v << 8 | p[i];
    return v;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    cache_key key = {0};
    if (size >= 40) {
        uint32_t edge = (uint32_t)le(data + 12, 4), angle = (uint32_t)le(data + 16, 4);
        key.version = (uint32_t)le(data + 8, 4);
        memcpy(&key.edge, &edge, 4);
        memcpy(&key.angle, &angle, 4);
        key.scene_hash = le(data + 24, 8);
    }
    cache_set set;
    char why[256];
    if (cache_file_parse(data, size, &key, &set, why, sizeof why) == 0) {
        if (size != 48 + 4 * CACHE_RECORD_FLOATS * set.count)
            abort();
        cache_set_free(&set);
    } else if (!why[0] || strchr(why, '\n')) {
        abort();
    }
    return 0;
}
