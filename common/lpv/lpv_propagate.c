#include "lpv/lpv_propagate.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "base/fpmode.h"
#include "lpv/lpv_paper_step.h"
#include "lpv/lpv_simd.h"
#include "lpv/sh.h"

enum { Z_TILE = 8 };

typedef struct job {
    const lpv_volume *src;
    lpv_volume *dst, *accum;
    const lpv_blockers *blockers;
    float keep, keep_flux; /* 1 - l_a and (1 - l_a)(1 - l_s) */
    unsigned step;
} job;

/* First n lanes of p, the others 0 (p may end anywhere inside a channel's guard). */
static inline vf load_n(const float *p, int n)
{
    return n >= 8 ? vf_load(p) : vf_and(vf_load(p), vf_lanes(0, n));
}

/* The split of lpv_transfer_split() on 8 cells: energy halves (already times Y0, the
 * factor of the energy coefficient) and the two directions times Y1 / Y0 in SH order
 * (-y, z, -x), so that a target's coefficients are a + b and a s+ + b s-. Lanes that
 * send nothing get energy 0. */
typedef struct split {
    vf half;     /* Y0 E / 2 */
    vf dir[2][3]; /* s+ and s- in lattice axes, for the weights */
    vf sh[2][3];  /* s+ and s- as SH directional coefficients over Y0 */
} split;

static ALWAYS_INLINE void split_cells(const job *jb, const float *const *ch, size_t at, int n,
                                      int c, split *out)
{
    const float inv_y1 = (float)(1.0 / SH_Y1);
    vf l0 = load_n(ch[4 * c] + at, n), l1 = load_n(ch[4 * c + 1] + at, n);
    vf l2 = load_n(ch[4 * c + 2] + at, n), l3 = load_n(ch[4 * c + 3] + at, n);
    vf e = vf_mul(vf_set1(jb->keep), vf_mul(vf_set1((float)SH_ENERGY), l0));
    vf kf = vf_set1(jb->keep_flux), zero = vf_zero(), one = vf_set1(1.0f);
    vf f[3] = {vf_mul(kf, vf_mul(vf_sub(zero, l3), vf_set1(inv_y1))),
               vf_mul(kf, vf_mul(vf_sub(zero, l1), vf_set1(inv_y1))),
               vf_mul(kf, vf_mul(l2, vf_set1(inv_y1)))};
    vf len2 = vf_fma(f[2], f[2], vf_fma(f[1], f[1], vf_mul(f[0], f[0])));
    vf len = vf_sqrt(len2);
    /* e > 0, e and len finite (x < inf is false for NaN and inf) */
    vf inf = vf_set1(INFINITY);
    vf valid = vf_and(vf_and(vf_gt(e, zero), vf_gt(inf, e)), vf_gt(inf, len));
    /* Lanes that send nothing take the no-direction path, so nothing below is NaN. */
    vf has_dir = vf_and(vf_gt(len, vf_mul(vf_set1(LPV_TRANSFER_MIN_Q), e)), valid);
    vf inv_len = vf_div(one, vf_sel(has_dir, len, one));
    vf d[3];
    for (int a = 0; a < 3; a++)
        d[a] = vf_sel(has_dir, vf_mul(f[a], inv_len), vf_set1(a == (int)(jb->step % 3) ? 1.0f : 0.0f));
    vf q = vf_and(vf_min(vf_div(len, vf_sel(has_dir, e, one)), one), has_dir);
    /* Duff et al. basis around d */
    vf sign = vf_sel(vf_ge(d[2], zero), one, vf_set1(-1.0f));
    vf ab = vf_div(vf_set1(-1.0f), vf_add(sign, d[2]));
    vf b = vf_mul(vf_mul(d[0], d[1]), ab);
    vf t[3];
    if (jb->step & 1) {
        t[0] = b;
        t[1] = vf_add(sign, vf_mul(vf_mul(d[1], d[1]), ab));
        t[2] = vf_sub(zero, d[1]);
    } else {
        t[0] = vf_add(one, vf_mul(vf_mul(sign, vf_mul(d[0], d[0])), ab));
        t[1] = vf_mul(sign, b);
        t[2] = vf_sub(zero, vf_mul(sign, d[0]));
    }
    vf r = vf_sqrt(vf_max(zero, vf_sub(one, vf_mul(q, q))));
    for (int a = 0; a < 3; a++) {
        vf qd = vf_mul(q, d[a]), rt = vf_mul(r, t[a]);
        out->dir[0][a] = vf_add(qd, rt);
        out->dir[1][a] = vf_sub(qd, rt);
    }
    const float k = (float)(SH_Y1 / SH_Y0);
    for (int h = 0; h < 2; h++) {
        out->sh[h][0] = vf_mul(vf_set1(-k), out->dir[h][1]);
        out->sh[h][1] = vf_mul(vf_set1(k), out->dir[h][2]);
        out->sh[h][2] = vf_mul(vf_set1(-k), out->dir[h][0]);
    }
    out->half = vf_and(vf_mul(vf_set1(0.5f * (float)SH_Y0), e), valid);
}

/* lpv_transfer_axis_weights() for 8 lanes: w[0], w[1], w[2] for offsets -1, 0, +1. */
static ALWAYS_INLINE void axis_weights(vf v, vf w[3])
{
    vf one = vf_set1(1.0f);
    v = vf_max(vf_set1(-1.0f), vf_min(v, one));
    vf sigma = vf_fma(vf_mul(vf_set1(0.5f), v), v, vf_set1(0.5f));
    vf h = vf_set1(0.5f);
    w[0] = vf_mul(h, vf_sub(sigma, v));
    w[1] = vf_sub(one, sigma);
    w[2] = vf_mul(h, vf_add(sigma, v));
}

/* The 8 source cells at (x .. x + 7, y, sz) send to the tile's destination rows. */
static ALWAYS_INLINE void send(const job *jb, int x, int y, int sz, int z0, int z1, int blocking)
{
    const int nx = jb->src->n[0], ny = jb->src->n[1];
    const int n = nx - x < 8 ? nx - x : 8;
    const size_t at = ((size_t)sz * ny + y) * nx + (size_t)x;
    vi mask = vi_zero();
    if (blocking) {
        unsigned words[8] = {0};
        memcpy(words, jb->blockers->mask + at, (size_t)n * sizeof *words);
        mask = vi_load(words);
    }
    /* Store masks per x offset: destination lanes inside the row (and sources that exist). */
    vf lanes[3];
    for (int ox = -1; ox <= 1; ox++) {
        int lo = -(x + ox) > 0 ? -(x + ox) : 0, hi = nx - (x + ox) < n ? nx - (x + ox) : n;
        lanes[ox + 1] = vf_lanes(lo, hi);
    }
    int full[3];
    for (int ox = -1; ox <= 1; ox++)
        full[ox + 1] = x + ox >= 0 && x + ox + 8 <= nx && n == 8;
    for (int c = 0; c < 3; c++) {
        split sp;
        split_cells(jb, (const float *const *)jb->src->ch, at, n, c, &sp);
        vf w[2][3][3]; /* half, axis, offset */
        for (int h = 0; h < 2; h++)
            for (int a = 0; a < 3; a++)
                axis_weights(sp.dir[h][a], w[h][a]);
        for (int h = 0; h < 2; h++)
            for (int o = 0; o < 3; o++)
                w[h][0][o] = vf_mul(w[h][0][o], sp.half);
        for (int oz = -1; oz <= 1; oz++) {
            int z = sz + oz;
            if (z < z0 || z >= z1)
                continue;
            for (int oy = -1; oy <= 1; oy++) {
                int yy = y + oy;
                if (yy < 0 || yy >= ny)
                    continue;
                vf yz[2] = {vf_mul(w[0][1][oy + 1], w[0][2][oz + 1]),
                            vf_mul(w[1][1][oy + 1], w[1][2][oz + 1])};
                size_t row = ((size_t)z * ny + yy) * nx;
                for (int ox = -1; ox <= 1; ox++) {
                    vf a = vf_mul(w[0][0][ox + 1], yz[0]), b = vf_mul(w[1][0][ox + 1], yz[1]);
                    int k27 = (oz + 1) * 9 + (oy + 1) * 3 + (ox + 1);
                    if (blocking && k27 != 13) {
                        vf open = vi_bit_clear(mask, k27 < 13 ? k27 : k27 - 1);
                        a = vf_and(a, open);
                        b = vf_and(b, open);
                    }
                    vf coef[4] = {vf_add(a, b),
                                  vf_fma(b, sp.sh[1][0], vf_mul(a, sp.sh[0][0])),
                                  vf_fma(b, sp.sh[1][1], vf_mul(a, sp.sh[0][1])),
                                  vf_fma(b, sp.sh[1][2], vf_mul(a, sp.sh[0][2]))};
                    for (int s = 0; s < 4; s++) {
                        float *p = jb->dst->ch[4 * c + s] + row + (ptrdiff_t)(x + ox);
                        if (full[ox + 1])
                            vf_store(p, vf_add(vf_load(p), coef[s]));
                        else
                            vf_store_mask(p, vf_add(vf_load(p), coef[s]), lanes[ox + 1]);
                    }
                }
            }
        }
    }
}

/* One tile of destination slabs z0 .. z1 - 1: start from 0, add what every source slab
 * z0 - 1 .. z1 sends there, in lattice order, then add the finished rows into accum. */
static ALWAYS_INLINE void tile_rows(const job *jb, int z0, int z1, int blocking)
{
    const int nx = jb->src->n[0], ny = jb->src->n[1], nz = jb->src->n[2];
    size_t lo = (size_t)z0 * ny * nx, count = (size_t)(z1 - z0) * ny * nx;
    for (int k = 0; k < LPV_LIGHT_CHANNELS; k++)
        memset(jb->dst->ch[k] + lo, 0, count * sizeof(float));
    for (int sz = z0 - 1; sz <= z1; sz++) {
        if (sz < 0 || sz >= nz)
            continue;
        for (int y = 0; y < ny; y++)
            for (int x = 0; x < nx; x += 8)
                send(jb, x, y, sz, z0, z1, blocking);
    }
    if (jb->accum)
        for (int k = 0; k < LPV_LIGHT_CHANNELS; k++) {
            float *a = jb->accum->ch[k] + lo;
            const float *d = jb->dst->ch[k] + lo;
            for (size_t i = 0; i < count; i++)
                a[i] += d[i];
        }
}

static void tile(void *ctx, int item)
{
    const job *jb = ctx;
    fpmode mode = fpmode_enter();
    const int nz = jb->src->n[2];
    int z0 = item * Z_TILE, z1 = z0 + Z_TILE < nz ? z0 + Z_TILE : nz;
    if (jb->blockers)
        tile_rows(jb, z0, z1, 1);
    else
        tile_rows(jb, z0, z1, 0);
    fpmode_leave(mode);
}

static float unit_clamp(float x)
{
    return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; /* NaN -> 0 */
}

static int same_light(const lpv_volume *a, const lpv_volume *b)
{
    return a && b && a->channels == LPV_LIGHT_CHANNELS && b->channels == LPV_LIGHT_CHANNELS &&
           memcmp(a->n, b->n, sizeof a->n) == 0;
}

void lpv_propagate_step(const lpv_propagate_desc *desc, const lpv_volume *src, lpv_volume *dst)
{
    if (!desc || !same_light(src, dst) || src == dst ||
        (desc->accum && (!same_light(desc->accum, dst) || desc->accum == dst ||
                         desc->accum == src)) ||
        (desc->blockers && memcmp(desc->blockers->n, src->n, sizeof src->n) != 0))
        return;
    if (desc->transport == LPV_TRANSPORT_PAPER) {
        lpv_paper_step(desc, src, dst);
        return;
    }
    if (desc->transport != LPV_TRANSPORT_BEAMS)
        return;
    job jb;
    jb.src = src;
    jb.dst = dst;
    jb.accum = desc->accum;
    jb.blockers = desc->blockers && desc->blockers->mask ? desc->blockers : NULL;
    float la = unit_clamp(desc->absorption), ls = unit_clamp(desc->scattering);
    jb.keep = 1.0f - la;
    jb.keep_flux = (1.0f - la) * (1.0f - ls);
    jb.step = desc->step;
    workpool_run(desc->pool, (src->n[2] + Z_TILE - 1) / Z_TILE, tile, &jb);
}

const char *const lpv_transport_names[LPV_TRANSPORT_COUNT] = {"beams", "paper"};

double lpv_propagate_flops(lpv_transport t, size_t cells)
{
    if (t == LPV_TRANSPORT_PAPER)
        return lpv_paper_step_flops_per_cell() * (double)cells;
    /* Per colour: the split (about 60 operations) and the 27 targets' weights and
     * coefficients (2 multiplies, 1 add, 3 multiply-adds counted as 2, 4 accumulating
     * adds: 13). */
    double per_cell = 3.0 * (60.0 + LPV_TARGETS * 13.0);
    return per_cell * (double)cells;
}
