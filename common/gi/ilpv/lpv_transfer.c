#include "gi/ilpv/lpv_transfer.h"

#include <math.h>

#include "base/vec3.h"
#include "gi/ilpv/sh.h"

/* z outermost, x fastest. Neighbour k and 25 - k are antipodal. */
const int lpv_transfer_offsets[LPV_NEIGHBOURS][3] = {
    {-1, -1, -1}, {0, -1, -1}, {1, -1, -1}, {-1, 0, -1}, {0, 0, -1}, {1, 0, -1},
    {-1, 1, -1},  {0, 1, -1},  {1, 1, -1},  {-1, -1, 0}, {0, -1, 0}, {1, -1, 0},
    {-1, 0, 0},   {1, 0, 0},   {-1, 1, 0},  {0, 1, 0},   {1, 1, 0},  {-1, -1, 1},
    {0, -1, 1},   {1, -1, 1},  {-1, 0, 1},  {0, 0, 1},   {1, 0, 1},  {-1, 1, 1},
    {0, 1, 1},    {1, 1, 1},
};

void lpv_transfer_axis_weights(float v, float w[3])
{
    v = v > 1.0f ? 1.0f : v < -1.0f ? -1.0f : v; /* a unit vector's rounding */
    float sigma = 0.5f + 0.5f * v * v;
    w[0] = 0.5f * (sigma - v);
    w[1] = 1.0f - sigma;
    w[2] = 0.5f * (sigma + v);
}

int lpv_transfer_split(const float L[4], float absorption, float scattering, unsigned step,
                       float *energy, float s_plus[3], float s_minus[3])
{
    const float inv_y1 = (float)(1.0 / SH_Y1);
    float keep = 1.0f - absorption, keep_flux = keep * (1.0f - scattering);
    float e = keep * ((float)SH_ENERGY * L[0]);
    *energy = 0.0f;
    if (!(e > 0.0f) || !isfinite(e))
        return 0;
    float f[3] = {keep_flux * (-L[3] * inv_y1), keep_flux * (-L[1] * inv_y1),
                  keep_flux * (L[2] * inv_y1)};
    float len = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!isfinite(len))
        return 0;
    float d[3] = {0.0f, 0.0f, 0.0f}, q;
    if (len > LPV_TRANSFER_MIN_Q * e) {
        for (int a = 0; a < 3; a++)
            d[a] = f[a] / len;
        q = len / e;
        q = q < 1.0f ? q : 1.0f;
    } else { /* no direction: spread around a lattice axis that changes every step */
        d[step % 3] = 1.0f;
        q = 0.0f;
    }
    float t1[3], t2[3];
    vec3_basis(d, t1, t2);
    const float *t = (step & 1) ? t2 : t1;
    float r = sqrtf(fmaxf(0.0f, 1.0f - q * q));
    for (int a = 0; a < 3; a++) {
        s_plus[a] = q * d[a] + r * t[a];
        s_minus[a] = q * d[a] - r * t[a];
    }
    *energy = e;
    return 1;
}

float lpv_transfer_step_probability(float sigma_per_metre, float cell)
{
    double sigma = sigma_per_metre;
    if (!(sigma > 0.0)) /* also NaN */
        return 0.0f;
    if (sigma >= 1.0)
        sigma = 1.0;
    double d = cell;
    if (!(d > 0.0))
        return 0.0f;
    return (float)(1.0 - pow(1.0 - sigma, d));
}
