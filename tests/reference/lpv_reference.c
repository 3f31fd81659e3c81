#include "lpv_reference.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gi/ilpv/sh.h"

static float unit_clamp(float x)
{
    return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;
}

/* Cell (x, y, z) in lattice order, or -1 outside. */
static long cell_index(const int n[3], int x, int y, int z)
{
    if (x < 0 || y < 0 || z < 0 || x >= n[0] || y >= n[1] || z >= n[2])
        return -1;
    return (long)x + (long)n[0] * ((long)y + (long)n[1] * z);
}

static void paper_cell(const lpv_propagate_desc *desc, const lpv_volume *src, int x, int y, int z,
                       double *acc)
{
    const lpv_paper_transfer *t = desc->paper ? desc->paper : lpv_paper_transfer_default();
    double la = unit_clamp(desc->absorption), ls = unit_clamp(desc->scattering);
    double keep = la + ls < 1.0 ? 1.0 - la - ls : 0.0;
    long i = cell_index(src->n, x, y, z);
    uint32_t mask = desc->blockers ? desc->blockers->mask[i] : 0;
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        const int *o = lpv_transfer_offsets[j];
        long d = cell_index(src->n, x + o[0], y + o[1], z + o[2]);
        if (d < 0 || ((mask >> j) & 1u))
            continue;
        for (int c = 0; c < 3; c++) {
            const float *g = t->gamma[j];
            double dot = 0.0;
            for (int s = 0; s < 4; s++)
                dot += (double)src->ch[4 * c + s][i] * g[s];
            double p = keep * dot + t->outscatter[j] * ls * SH_ENERGY * src->ch[4 * c][i];
            if (!(p > 0.0))
                continue;
            for (int s = 0; s < 4; s++)
                acc[d * LPV_LIGHT_CHANNELS + 4 * c + s] += p * g[s];
        }
    }
}

static void beams_cell(const lpv_propagate_desc *desc, const lpv_volume *src, int x, int y, int z,
                       double *acc)
{
    const int *n = src->n;
    float la = unit_clamp(desc->absorption), ls = unit_clamp(desc->scattering);
    long i = cell_index(n, x, y, z);
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
            long t = cell_index(n, x + o[0], y + o[1], z + o[2]);
            if (t < 0)
                continue;
            double energy = 0.0, flux[3] = {0, 0, 0};
            for (int h = 0; h < 2; h++) {
                double part = 0.5 * e * w[h][0][o[0] + 1] * w[h][1][o[1] + 1] * w[h][2][o[2] + 1];
                energy += part;
                for (int a = 0; a < 3; a++)
                    flux[a] += part * s[h][a];
            }
            double *out = acc + t * LPV_LIGHT_CHANNELS + 4 * c;
            out[0] += SH_Y0 * energy;
            out[1] += -SH_Y1 * flux[1];
            out[2] += SH_Y1 * flux[2];
            out[3] += -SH_Y1 * flux[0];
        }
    }
}

void lpv_reference_step(const lpv_propagate_desc *desc, const lpv_volume *src, lpv_volume *dst)
{
    const int *n = src->n;
    size_t cells = src->cells;
    double *acc = calloc(cells * LPV_LIGHT_CHANNELS, sizeof *acc);
    if (!acc)
        return;
    for (int z = 0; z < n[2]; z++)
        for (int y = 0; y < n[1]; y++)
            for (int x = 0; x < n[0]; x++) {
                if (desc->transport == LPV_TRANSPORT_PAPER)
                    paper_cell(desc, src, x, y, z, acc);
                else
                    beams_cell(desc, src, x, y, z, acc);
            }
    for (size_t i = 0; i < cells; i++)
        for (int k = 0; k < LPV_LIGHT_CHANNELS; k++) {
            dst->ch[k][i] = (float)acc[i * LPV_LIGHT_CHANNELS + k];
            if (desc->accum)
                desc->accum->ch[k][i] += dst->ch[k][i];
        }
    free(acc);
}

double lpv_reference_rel_diff(const lpv_volume *a, const lpv_volume *ref)
{
    double worst = 0.0;
    for (int c = 0; c < LPV_LIGHT_CHANNELS; c++) {
        double peak = 0.0, diff = 0.0;
        for (size_t i = 0; i < ref->cells; i++) {
            peak = fmax(peak, fabs(ref->ch[c][i]));
            diff = fmax(diff, fabs((double)a->ch[c][i] - ref->ch[c][i]));
        }
        worst = fmax(worst, peak > 0.0 ? diff / peak : diff);
    }
    return worst;
}
