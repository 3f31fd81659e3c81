/* byteorder: unsigned integers to and from bytes in a fixed order, whatever the host's.
 *
 * Little-endian for our own formats (the wire messages, the parameter store's encoding),
 * big-endian ("network order") for protocols that use it (VRPN). `bytes` is 1..8; floats
 * travel as the integer of their bits (memcpy). */
#ifndef CAVELIGHT_BYTEORDER_H
#define CAVELIGHT_BYTEORDER_H

#include <stdint.h>

static inline void le_put(uint8_t *p, uint64_t v, int bytes)
{
    for (int i = 0; i < bytes; i++)
        p[i] = (uint8_t)(v >> (8 * i));
}

static inline uint64_t le_get(const uint8_t *p, int bytes)
{
    uint64_t v = 0;
    for (int i = 0; i < bytes; i++)
        v |= (uint64_t)p[i] << (8 * i);
    return v;
}

static inline void be_put(uint8_t *p, uint64_t v, int bytes)
{
    for (int i = 0; i < bytes; i++)
        p[i] = (uint8_t)(v >> (8 * (bytes - 1 - i)));
}

static inline uint64_t be_get(const uint8_t *p, int bytes)
{
    uint64_t v = 0;
    for (int i = 0; i < bytes; i++)
        v = v << 8 | p[i];
    return v;
}

#endif
