#include "gi/ilpv/lpv_paper_step.h"

#include <stddef.h>
#include <string.h>

#include "base/fpmode.h"
#include "gi/ilpv/lpv_simd.h"
#include "gi/ilpv/sh.h"

/* A destination row is done in segments of XS cells. For each neighbour j a factor row
 * holds p_j of the source cells x0 - 8 .. x0 + XS + 7 (index x - x0 + 8), so the
 * destination cell x reads it at x - o_x - x0 + 8. */
enum { Z_TILE = 8, XS = 64, PW = XS + 16 };

typedef struct job {
    const lpv_volume *src;
    lpv_volume *dst, *accum;
    const lpv_blockers *blockers;
    float a[LPV_NEIGHBOURS][4]; /* p_j = max(0, <L|A_j>): A_j = keep G_j + l_s gamma_j <.|1> */
    float g[LPV_NEIGHBOURS][4]; /* G_j */
} job;

/* The blockers' words of the n source cells at index at (n > 0), 0 past the row. */
static ALWAYS_INLINE vi mask_words(const job *jb, size_t at, int n)
{
    if (n == 8)
        return vi_load(jb->blockers->mask + at);
    unsigned words[8] = {0};
    memcpy(words, jb->blockers->mask + at, (size_t)n * sizeof *words);
    return vi_load(words);
}

/* The factor row of neighbour j for the segment at x0 of destination row (y, z), whose
 * source row (sy, sz) lies in the lattice: p_j of the source cells x0 - 8 .. x0 + XS + 7,
 * colours R, G, B; 0 for blocked cells and cells outside the row. */
static ALWAYS_INLINE void factor_row(const job *jb, int j, int sy, int sz, int x0, float (*P)[PW])
{
    const int nx = jb->src->n[0], ny = jb->src->n[1];
    const size_t row = ((size_t)sz * ny + sy) * nx;
    const vf zero = vf_zero();
    for (int c = 0; c < 3; c++) {
        const float *l0 = jb->src->ch[4 * c] + row, *l1 = jb->src->ch[4 * c + 1] + row;
        const float *l2 = jb->src->ch[4 * c + 2] + row, *l3 = jb->src->ch[4 * c + 3] + row;
        const vf a0 = vf_set1(jb->a[j][0]), a1 = vf_set1(jb->a[j][1]);
        const vf a2 = vf_set1(jb->a[j][2]), a3 = vf_set1(jb->a[j][3]);
        float *out = P[c];
        for (int x = x0 - 8; x < x0 + XS + 8; x += 8) {
            float *o = out + (x - x0 + 8);
            int n = nx - x < 8 ? nx - x : 8;
            if (x < 0 || n <= 0) {
                vf_store(o, zero);
                continue;
            }
            vf p = vf_mul(a0, vf_load(l0 + x));
            p = vf_fma(a1, vf_load(l1 + x), p);
            p = vf_fma(a2, vf_load(l2 + x), p);
            p = vf_fma(a3, vf_load(l3 + x), p);
            p = vf_max(p, zero);
            if (n < 8)
                p = vf_and(p, vf_lanes(0, n));
            if (jb->blockers)
                p = vf_and(p, vi_bit_clear(mask_words(jb, row + (size_t)x, n), j));
            vf_store(o, p);
        }
    }
}

/* The neighbours in three groups, one per source z slab (lpv_transfer_offsets is
 * z-major): group g reads slab z + 1 - g. */
static const int group_end[4] = {0, 9, 17, 26};
enum { GROUP_MAX = 9 };

/* Group gi of destination row (y, z), cells x0 .. x0 + XS - 1 clipped to the row, whose
 * source slab lies in the lattice: the group's factor rows, then each cell adds p_j G_j
 * over the group's j in order, to 0 for the first group and to the row's partial sums in
 * dst otherwise (a float stored and loaded again: the same rounding as one sum). */
static ALWAYS_INLINE void group(const job *jb, int y, int z, int gi, int x0)
{
    _Alignas(64) float P[GROUP_MAX][3][PW];
    const int nx = jb->src->n[0], ny = jb->src->n[1];
    const float *prow[GROUP_MAX];
    int js[GROUP_MAX], count = 0;
    for (int j = group_end[gi]; j < group_end[gi + 1]; j++) {
        const int *o = lpv_transfer_offsets[j];
        int sy = y - o[1];
        if (sy < 0 || sy >= ny)
            continue;
        factor_row(jb, j, sy, z - o[2], x0, P[count]);
        prow[count] = &P[count][0][8 - o[0]];
        js[count++] = j;
    }
    const int len = nx - x0 < XS ? nx - x0 : XS;
    const size_t row = ((size_t)z * ny + y) * nx + (size_t)x0;
    float *const *d = jb->dst->ch;
    for (int v = 0; v < len; v += 8) {
        const vf lanes = vf_lanes(0, len - v);
        vf acc[12];
        for (int k = 0; k < 12; k++)
            acc[k] = gi == 0 ? vf_zero() : vf_and(vf_load(d[k] + row + v), lanes);
        for (int e = 0; e < count; e++) {
            const float *p = prow[e] + v, *g = jb->g[js[e]];
            const vf pr = vf_load(p), pg = vf_load(p + PW), pb = vf_load(p + 2 * PW);
            for (int s = 0; s < 4; s++) {
                const vf gs = vf_set1(g[s]);
                acc[s] = vf_fma(pr, gs, acc[s]);
                acc[4 + s] = vf_fma(pg, gs, acc[4 + s]);
                acc[8 + s] = vf_fma(pb, gs, acc[8 + s]);
            }
        }
        if (len - v >= 8)
            for (int k = 0; k < 12; k++)
                vf_store(d[k] + row + v, acc[k]);
        else
            for (int k = 0; k < 12; k++)
                vf_store_mask(d[k] + row + v, acc[k], lanes);
    }
}

/* dst cells x0 .. x0 + XS - 1 of row (y, z), clipped to the row, set to 0: a row on the
 * lattice's last slab has no first group. */
static void zero_row(const job *jb, int y, int z, int x0)
{
    const int nx = jb->src->n[0], ny = jb->src->n[1];
    const int len = nx - x0 < XS ? nx - x0 : XS;
    const size_t row = ((size_t)z * ny + y) * nx + (size_t)x0;
    for (int k = 0; k < LPV_LIGHT_CHANNELS; k++)
        memset(jb->dst->ch[k] + row, 0, (size_t)len * sizeof(float));
}

/* Destination slabs z0 .. z1 - 1, row y by row y. For each y and segment the source slabs
 * are swept from z1 down to z0 - 1: the three source rows (y - 1 .. y + 1, sz) serve group
 * 0 of destination row sz - 1, group 1 of sz and group 2 of sz + 1 while they are in L1. */
static void tile(void *ctx, int item)
{
    const job *jb = ctx;
    fpmode mode = fpmode_enter();
    const int nx = jb->src->n[0], ny = jb->src->n[1], nz = jb->src->n[2];
    int z0 = item * Z_TILE, z1 = z0 + Z_TILE < nz ? z0 + Z_TILE : nz;
    for (int y = 0; y < ny; y++)
        for (int x0 = 0; x0 < nx; x0 += XS)
            for (int sz = z1; sz >= z0 - 1; sz--)
                for (int gi = 0; gi < 3; gi++) {
                    int z = sz + gi - 1;
                    if (z < z0 || z >= z1)
                        continue;
                    if (sz >= 0 && sz < nz)
                        group(jb, y, z, gi, x0);
                    else if (gi == 0)
                        zero_row(jb, y, z, x0);
                }
    if (jb->accum)
        lpv_volume_add_slab(jb->accum, jb->dst, z0, z1);
    fpmode_leave(mode);
}

void lpv_paper_step(const lpv_propagate_desc *desc, const lpv_volume *src, lpv_volume *dst)
{
    const lpv_paper_transfer *t = desc->paper ? desc->paper : lpv_paper_transfer_default();
    job jb;
    jb.src = src;
    jb.dst = dst;
    jb.accum = desc->accum;
    jb.blockers = desc->blockers && desc->blockers->mask ? desc->blockers : NULL;
    float la = lpv_probability_clamp(desc->absorption), ls = lpv_probability_clamp(desc->scattering);
    float keep = la + ls < 1.0f ? 1.0f - la - ls : 0.0f;
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        for (int s = 0; s < 4; s++) {
            jb.g[j][s] = t->gamma[j][s];
            jb.a[j][s] = keep * t->gamma[j][s];
        }
        /* gamma_j l_s <L|1> = (gamma_j l_s 2 sqrt(pi)) L_0 */
        jb.a[j][0] += t->outscatter[j] * ls * (float)SH_ENERGY;
    }
    workpool_run(desc->pool, (src->n[2] + Z_TILE - 1) / Z_TILE, tile, &jb);
}

double lpv_paper_step_flops_per_cell(void)
{
    /* Per neighbour and colour: the factor (1 multiply, 3 multiply-adds, the clamp: 8) and
     * the update (4 multiply-adds: 8). */
    return LPV_NEIGHBOURS * 3.0 * 16.0;
}
