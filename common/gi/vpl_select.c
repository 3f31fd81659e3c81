#include "gi/vpl_select.h"

#include <math.h>
#include <string.h>

/* A 32-bit integer hash with good avalanche (Wellons' lowbias32): slot numbers that
 * differ in one bit get unrelated random numbers. */
static uint32_t mix32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

double vpl_slot_random(uint32_t seed, int i, int dim)
{
    uint32_t h = mix32(mix32(seed ^ 0x9e3779b9U) + (uint32_t)i);
    if (dim)
        h = mix32(h + (uint32_t)dim);
    return (double)(h >> 8) * (1.0 / 16777216.0);
}

static double importance(const vpl *v)
{
    double f = (double)v->flux[0] + v->flux[1] + v->flux[2];
    return f > 0 && isfinite(f) ? f : 0.0;
}

int vpl_select(const vpl *candidates, size_t count, int n, uint32_t seed, double *cdf,
               vpl *out, size_t *chosen)
{
    double total = 0;
    for (size_t j = 0; j < count; j++)
        cdf[j] = total += importance(&candidates[j]);
    if (!(total > 0) || n <= 0)
        return 0;
    size_t j = 0;
    for (int i = 0; i < n; i++) {
        /* The first candidate whose CDF exceeds the target owns it (its interval is not
         * empty). Targets increase with i, so one forward walk finds them all. */
        double target = ((double)i + vpl_slot_random(seed, i, 0)) / n * total;
        while (j + 1 < count && cdf[j] <= target)
            j++;
        while (importance(&candidates[j]) == 0) /* a target rounded up to the total */
            j--;
        const vpl *c = &candidates[j];
        double scale = total / ((double)n * importance(c)); /* 1 / (n p_j) */
        out[i] = *c;
        for (int k = 0; k < 3; k++)
            out[i].flux[k] = (float)(c->flux[k] * scale);
        out[i].area = (float)(c->area * scale);
        if (chosen)
            chosen[i] = j;
    }
    return n;
}

uint64_t vpl_checksum(const vpl *v, int n)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (int i = 0; i < n; i++) {
        const float *f[4] = {v[i].position, v[i].normal, v[i].flux, &v[i].area};
        const int len[4] = {3, 3, 3, 1};
        for (int a = 0; a < 4; a++)
            for (int k = 0; k < len[a]; k++) {
                uint32_t bits;
                memcpy(&bits, &f[a][k], sizeof bits);
                for (int b = 0; b < 4; b++) {
                    h ^= (bits >> (8 * b)) & 0xffu;
                    h *= 0x100000001b3ull;
                }
            }
    }
    return h;
}
