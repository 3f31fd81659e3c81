/* fnv1a: the one 64-bit FNV-1a of the program (checksums READY carries, cache file keys,
 * the config and schema hashes HELLO compares).
 *
 * Byte order is part of each caller's result: fnv1a64() hashes memory as it lies, the _le
 * forms hash a value's bytes from the lowest (the same on every host), and fnv1a64_word()
 * folds a whole 32-bit word per step (4x fewer serial multiplies, not byte-wise FNV-1a;
 * lpv_volume_checksum() and ilpv_injection_key() are defined by it). */
#ifndef CAVELIGHT_FNV1A_H
#define CAVELIGHT_FNV1A_H

#include <stddef.h>
#include <stdint.h>

#define FNV1A64_PRIME 0x100000001b3ull
/* The standard offset basis. */
#define FNV1A64_OFFSET 0xcbf29ce484222325ull
/* The cluster's seed (config, schema, store and ldm checksums): the standard basis with its
 * last decimal digit lost; kept so that those hashes do not change. */
#define FNV1A64_CLUSTER_SEED 1469598103934665603ull

static inline uint64_t fnv1a64(uint64_t h, const void *data, size_t n)
{
    const unsigned char *b = data;
    for (size_t i = 0; i < n; i++)
        h = (h ^ b[i]) * FNV1A64_PRIME;
    return h;
}

/* The n low bytes of v, lowest first. */
static inline uint64_t fnv1a64_le(uint64_t h, uint64_t v, int n)
{
    for (int i = 0; i < n; i++)
        h = (h ^ ((v >> (8 * i)) & 0xffu)) * FNV1A64_PRIME;
    return h;
}

static inline uint64_t fnv1a64_word(uint64_t h, uint64_t w) { return (h ^ w) * FNV1A64_PRIME; }

#endif
