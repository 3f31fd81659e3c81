#include "lpv_reference.h"

#include <stdlib.h>
#include <string.h>

#include "lpv/sh.h"

void lpv_reference_step(const lpv_propagate_desc *desc, const lpv_volume *src, lpv_volume *dst)
{
    const int *n = src->n;
    size_t cells = src->cells;
    double *acc = calloc(cells * LPV_LIGHT_CHANNELS, sizeof *acc);
    if (!acc)
        return;
    float la = desc->absorption > 0.0f ? (desc->absorption < 1.0f ? desc->absorption : 1.0f) : 0.0f;
    float ls = desc->scattering > 0.0f ? (desc->scattering < 1.0f ? desc->scattering : 1.0f) : 0.0f;
    for (int z = 0; z < n[2]; z++)
        for (int y = 0; y < n[1]; y++)
            for (int x = 0; x < n[0]; x++) {
                size_t i = (size_t)x + (size_t)n[0] * ((size_t)y + (size_t)n[1] * z);
                uint32_t mask = desc->blockers ? desc->blockers->mask[i] : 0;
                for (int c = 0; c < 3; c++) {
                    float L[4] = {src->ch[4 * c][i], src->ch[4 * c + 1][i], src->ch[4 * c + 2][i],
                                  src->ch[4 * c + 3][i]};
                    float e, s[2][3];
                    if (!lpv_transfer_split(L, la, ls, desc->step, &e, s[0], s[1]))
                        continue;
                    float w[2][3][3];
                    for (int h = 0; h < 2; h++)
                        for (int a = 0; a < 3; a++)
                            lpv_transfer_axis_weights(s[h][a], w[h][a]);
                    for (int k = 0; k < LPV_TARGETS; k++) {
                        int o[3] = {0, 0, 0};
                        if (k < LPV_NEIGHBOURS) {
                            if ((mask >> k) & 1u)
                                continue;
                            memcpy(o, lpv_transfer_offsets[k], sizeof o);
                        }
                        int tx = x + o[0], ty = y + o[1], tz = z + o[2];
                        if (tx < 0 || ty < 0 || tz < 0 || tx >= n[0] || ty >= n[1] || tz >= n[2])
                            continue;
                        double energy = 0.0, flux[3] = {0, 0, 0};
                        for (int h = 0; h < 2; h++) {
                            double part = 0.5 * e * w[h][0][o[0] + 1] * w[h][1][o[1] + 1] *
                                          w[h][2][o[2] + 1];
                            energy += part;
                            for (int a = 0; a < 3; a++)
                                flux[a] += part * s[h][a];
                        }
                        size_t t = (size_t)tx + (size_t)n[0] * ((size_t)ty + (size_t)n[1] * tz);
                        double *out = acc + t * LPV_LIGHT_CHANNELS + 4 * c;
                        out[0] += SH_Y0 * energy;
                        out[1] += -SH_Y1 * flux[1];
                        out[2] += SH_Y1 * flux[2];
                        out[3] += -SH_Y1 * flux[0];
                    }
                }
            }
    for (size_t i = 0; i < cells; i++)
        for (int k = 0; k < LPV_LIGHT_CHANNELS; k++) {
            dst->ch[k][i] = (float)acc[i * LPV_LIGHT_CHANNELS + k];
            if (desc->accum)
                desc->accum->ch[k][i] += dst->ch[k][i];
        }
    free(acc);
}
