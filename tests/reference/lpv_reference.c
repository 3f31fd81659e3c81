#include "lpv_reference.h"

#include "lpv/sh.h"

static float clamp01(float x)
{
    return x < 0.0f ? 0.0f : x > 1.0f ? 1.0f : x;
}

void lpv_reference_step(const lpv_reference_desc *desc, const lpv_volume *src, lpv_volume *dst)
{
    const lpv_transfer *t = desc->transfer;
    const int nx = src->n[0], ny = src->n[1], nz = src->n[2];
    float la = clamp01(desc->absorption), ls = clamp01(desc->scattering);
    float lt = la + ls > 1.0f ? 1.0f : la + ls;
    lpv_volume_clear(dst);
    for (int z = 0; z < nz; z++)
        for (int y = 0; y < ny; y++)
            for (int x = 0; x < nx; x++) {
                size_t c = (size_t)x + (size_t)nx * ((size_t)y + (size_t)ny * z);
                for (int j = 0; j < LPV_NEIGHBOURS; j++) {
                    const float *g = t->gamma[j];
                    int tx = x + lpv_transfer_offsets[j][0];
                    int ty = y + lpv_transfer_offsets[j][1];
                    int tz = z + lpv_transfer_offsets[j][2];
                    if (tx < 0 || ty < 0 || tz < 0 || tx >= nx || ty >= ny || tz >= nz)
                        continue; /* light leaving the lattice is lost */
                    size_t d = (size_t)tx + (size_t)nx * ((size_t)ty + (size_t)ny * tz);
                    float b = 0.0f;
                    if (desc->use_blocking && desc->geometry) {
                        const lpv_volume *B = desc->geometry;
                        b = clamp01(B->ch[0][c] * g[0] + B->ch[1][c] * g[1] +
                                    B->ch[2][c] * g[2] + B->ch[3][c] * g[3]);
                    }
                    for (int col = 0; col < 3; col++) {
                        float L[4];
                        for (int s = 0; s < 4; s++)
                            L[s] = src->ch[4 * col + s][c];
                        float energy = (float)SH_ENERGY * L[0], g_energy = (float)SH_ENERGY * g[0];
                        float scattered = g_energy != 0.0f ? t->outscatter[j] * ls * energy / g_energy : 0.0f;
                        float flux = (1.0f - lt) * (L[0] * g[0] + L[1] * g[1] + L[2] * g[2] + L[3] * g[3]) +
                                     scattered;
                        flux *= 1.0f - b;
                        if (desc->clamp_negative && flux < 0.0f)
                            flux = 0.0f;
                        for (int s = 0; s < 4; s++)
                            dst->ch[4 * col + s][d] += flux * g[s];
                    }
                }
            }
}
