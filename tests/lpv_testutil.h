/* Small helpers shared by the LPV unit tests (header only, each test is one program). */
#ifndef CAVELIGHT_LPV_TESTUTIL_H
#define CAVELIGHT_LPV_TESTUTIL_H

#include <math.h>
#include <stdint.h>

#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_volume.h"
#include "gi/ilpv/sh.h"

/* Deterministic [0, 1) numbers for test data. */
static inline float testutil_rand(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (float)((*s * 0x2545f4914f6cdd1dull) >> 40) * (1.0f / 16777216.0f);
}

/* Largest |a - b| over all channels, divided by the largest |b|. */
static inline double testutil_rel_diff(const lpv_volume *a, const lpv_volume *b)
{
    double diff = 0.0, scale = 0.0;
    for (int c = 0; c < a->channels; c++)
        for (size_t i = 0; i < a->cells; i++) {
            diff = fmax(diff, fabs((double)a->ch[c][i] - b->ch[c][i]));
            scale = fmax(scale, fabs(b->ch[c][i]));
        }
    return scale > 0.0 ? diff / scale : diff;
}

static inline double testutil_energy(const lpv_volume *v)
{
    double e[3];
    lpv_volume_energy(v, e);
    return e[0] + e[1] + e[2];
}

/* Light of every kind: beams, isotropic light, mixtures; a few cells negative or
 * empty; with b, random blockers (70% of cells open). */
static inline void testutil_fill_light(lpv_volume *light, lpv_blockers *b, uint64_t seed)
{
    uint64_t rng = seed;
    for (size_t i = 0; i < light->cells; i++)
        for (int c = 0; c < 3; c++) {
            float d[3] = {testutil_rand(&rng) - 0.5f, testutil_rand(&rng) - 0.5f,
                          testutil_rand(&rng) - 0.5f}, L[4];
            sh_eval(d, L);
            float beam = testutil_rand(&rng), iso = testutil_rand(&rng);
            if (testutil_rand(&rng) < 0.05f)
                beam = iso = -1.0f;
            for (int s = 0; s < 4; s++)
                light->ch[4 * c + s][i] = beam * L[s] + (s == 0 ? iso * (float)SH_Y0 : 0.0f);
        }
    if (b)
        for (size_t i = 0; i < b->cells; i++)
            b->mask[i] = testutil_rand(&rng) < 0.7f ? 0u
                                                    : (uint32_t)(testutil_rand(&rng) * 67108863.0f);
}

#endif
