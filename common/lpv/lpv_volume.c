#include "lpv/lpv_volume.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/fnv1a.h"
#include "lpv/sh.h"

/* Large allocations start on page boundaries, so without this every channel (and every
 * z plane of a power-of-two lattice) would map to the same L1 cache sets and the
 * propagation's 12 x 9 source rows would evict each other. Channel c starts 27 c lines
 * (mod 64) further; geometry channels continue the sequence after the 12 light ones. */
static size_t stagger(int c, int channels)
{
    int k = c + (channels == LPV_GEOMETRY_CHANNELS ? LPV_LIGHT_CHANNELS : 0);
    return (size_t)((27 * k) % 64) * 16;
}

int lpv_volume_init(lpv_volume *v, const int n[3], int channels)
{
    memset(v, 0, sizeof *v);
    if (channels != LPV_LIGHT_CHANNELS && channels != LPV_GEOMETRY_CHANNELS)
        return -1;
    size_t cells = 1;
    for (int a = 0; a < 3; a++) {
        if (n[a] < 1 || n[a] > (1 << 16))
            return -1;
        cells *= (size_t)n[a];
        v->n[a] = n[a];
    }
    if (cells > ((size_t)1 << 34))
        return -1;
    /* Whole 64-byte lines plus zeroed guards before and after each channel, so that
     * vector loads a few cells past either end of a channel stay inside the allocation, and
     * room for the stagger below. */
    size_t bytes = ((cells * sizeof(float) + 63) & ~(size_t)63) +
                   2 * LPV_VOLUME_GUARD * sizeof(float) + 63 * 64;
    v->cells = cells;
    v->channels = channels;
    for (int c = 0; c < channels; c++) {
        float *base = aligned_alloc(64, bytes);
        if (!base) {
            lpv_volume_free(v);
            return -1;
        }
        memset(base, 0, bytes);
        v->ch[c] = base + LPV_VOLUME_GUARD + stagger(c, channels);
    }
    return 0;
}

void lpv_volume_free(lpv_volume *v)
{
    for (int c = 0; c < LPV_MAX_CHANNELS; c++)
        if (v->ch[c])
            free(v->ch[c] - LPV_VOLUME_GUARD - stagger(c, v->channels));
    memset(v, 0, sizeof *v);
}

void lpv_volume_clear(lpv_volume *v)
{
    for (int c = 0; c < v->channels; c++)
        memset(v->ch[c], 0, v->cells * sizeof(float));
}

void lpv_volume_copy(lpv_volume *dst, const lpv_volume *src)
{
    if (dst == src || dst->cells != src->cells || dst->channels != src->channels)
        return;
    for (int c = 0; c < src->channels; c++)
        memcpy(dst->ch[c], src->ch[c], src->cells * sizeof(float));
}

void lpv_volume_add(lpv_volume *dst, const lpv_volume *src)
{
    lpv_volume_add_scaled(dst, src, 1.0f); /* 1 x s is s exactly: the same sums */
}

void lpv_volume_add_slab(lpv_volume *dst, const lpv_volume *src, int z0, int z1)
{
    size_t plane = (size_t)src->n[0] * src->n[1], lo = (size_t)z0 * plane, count = (size_t)(z1 - z0) * plane;
    for (int k = 0; k < src->channels; k++) {
        float *a = dst->ch[k] + lo;
        const float *d = src->ch[k] + lo;
        for (size_t i = 0; i < count; i++)
            a[i] += d[i];
    }
}

void lpv_volume_add_scaled(lpv_volume *dst, const lpv_volume *src, float a)
{
    if (dst == src || dst->cells != src->cells || dst->channels != src->channels)
        return;
    for (int c = 0; c < src->channels; c++) {
        float *d = dst->ch[c];
        const float *s = src->ch[c];
        for (size_t i = 0; i < src->cells; i++)
            d[i] += a * s[i];
    }
}

void lpv_volume_scale(lpv_volume *v, float a)
{
    for (int c = 0; c < v->channels; c++) {
        float *d = v->ch[c];
        for (size_t i = 0; i < v->cells; i++)
            d[i] *= a;
    }
}

void lpv_volume_energy(const lpv_volume *v, double energy_rgb[3])
{
    for (int c = 0; c < 3; c++) {
        energy_rgb[c] = 0.0;
        if (v->channels != LPV_LIGHT_CHANNELS)
            continue;
        const float *l0 = v->ch[4 * c];
        double sum = 0.0;
        for (size_t i = 0; i < v->cells; i++)
            sum += l0[i];
        energy_rgb[c] = SH_ENERGY * sum;
    }
}

uint64_t lpv_volume_checksum(const lpv_volume *v)
{
    uint64_t h = FNV1A64_OFFSET;
    for (int c = 0; c < v->channels; c++) {
        const float *p = v->ch[c];
        for (size_t i = 0; i < v->cells; i++) {
            uint32_t bits; /* a value, not bytes: the same on every host's byte order */
            memcpy(&bits, &p[i], sizeof bits);
            h = fnv1a64_word(h, bits);
        }
    }
    return h;
}

size_t lpv_volume_count_nonfinite(const lpv_volume *v)
{
    size_t bad = 0;
    for (int c = 0; c < v->channels; c++)
        for (size_t i = 0; i < v->cells; i++)
            bad += !isfinite(v->ch[c][i]);
    return bad;
}
