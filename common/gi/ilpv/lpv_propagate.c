#include "gi/ilpv/lpv_propagate.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "base/fpmode.h"
#include "gi/ilpv/lpv_paper_step.h"
#include "gi/ilpv/lpv_simd.h"
#include "gi/ilpv/sh.h"

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

/* The step as a gather. Per colour a source cell's half h (+, -) sends a = Ex[o_x] Wy[o_y]
 * Wz[o_z] to offset o: the half's energy times the three axis weights, as energy
 * coefficient a and directional coefficients a S (S: the half's direction as SH
 * coefficients over Y0). The split rows of a tile (what split_cells() and axis_weights()
 * give, the x weights times the energy) sit in a ring of three rows in y by the tile's
 * source slabs in z, each computed once per tile. A destination cell sums, per x offset,
 * what the source cells at its own x in the 9 (o_y, o_z) rows send (V_ox: 3 x 4
 * accumulators in registers), and then adds V_-1 of the cell on its right, V_0 of its own and V_+1 of
 * the one on its left: always in that order, so the bits do not depend on the threads. */
enum { EX = 0, WY = 3, WZ = 6, SS = 9, PER_HALF = 12, ARRAYS = 2 * PER_HALF };
/* A row is done in segments of XS cells; ring and V rows hold cells x0 - 8 .. x0 + XS + 7
 * of the segment at index x - x0 + 8. */
enum { XS = 64, PW = XS + 16, RING_Z = Z_TILE + 2 };

/* A split row is stored chunk by chunk: the ARRAYS vectors of 8 cells one after another
 * (what one destination chunk reads of a row lies in a few cache lines); array a of the
 * chunk at ring index i (a multiple of 8) starts at row + i ARRAYS + 8 a. */
typedef struct ring {
    _Alignas(32) float v[3][RING_Z][PW * ARRAYS]; /* source row (y mod 3, z - (z0 - 1)) */
    _Alignas(32) unsigned mask[3][RING_Z][PW];    /* its blockers */
    _Alignas(32) float zero[PW * ARRAYS];         /* a row outside the lattice: sends nothing */
    _Alignas(32) unsigned zero_mask[PW];
    _Alignas(32) float V[3][4][PW];              /* a destination row's V_ox */
} ring;

/* Splits source row (sy, sz), colour c, for the segment at x0 into ring slot (ry, rz). */
static void split_row(const job *jb, ring *rg, int ry, int rz, int sy, int sz, int x0, int c)
{
    const int nx = jb->src->n[0], ny = jb->src->n[1];
    float *out = rg->v[ry][rz];
    unsigned *m = rg->mask[ry][rz];
    const size_t row = ((size_t)sz * ny + sy) * nx;
    for (int i = 0; i < PW; i += 8) {
        int x = x0 - 8 + i, n = nx - x < 8 ? nx - x : 8;
        float *chunk = out + (size_t)i * ARRAYS;
        if (x < 0 || n <= 0) {
            for (int k = 0; k < ARRAYS; k++)
                vf_store(chunk + 8 * k, vf_zero());
            memset(m + i, 0, 8 * sizeof *m);
            continue;
        }
        split sp;
        split_cells(jb, (const float *const *)jb->src->ch, row + (size_t)x, n, c, &sp);
        for (int h = 0; h < 2; h++) {
            float *o = chunk + 8 * h * PER_HALF;
            vf w[3][3];
            for (int a = 0; a < 3; a++)
                axis_weights(sp.dir[h][a], w[a]);
            for (int k = 0; k < 3; k++) {
                vf_store(o + 8 * (EX + k), vf_mul(w[0][k], sp.half));
                vf_store(o + 8 * (WY + k), w[1][k]);
                vf_store(o + 8 * (WZ + k), w[2][k]);
                vf_store(o + 8 * (SS + k), sp.sh[h][k]);
            }
        }
        const unsigned *words = jb->blockers ? jb->blockers->mask + row + x : NULL;
        for (int l = 0; l < 8; l++) /* a loop the compiler turns into vector moves */
            m[i + l] = words && l < n ? words[l] : 0u;
    }
}

/* V_ox of the 8 destination cells at ring index i: what the source cells at the same x in
 * the 9 rows r[(o_z + 1) 3 + o_y + 1] send to offset (o_x, o_y, o_z); with `masked`, a
 * target whose segment the source's word m marks gets nothing. */
static ALWAYS_INLINE void gather_v(const float *const r[9], const unsigned *const m[9], int i,
                                   int masked, vf V[3][4])
{
    for (int ox = 0; ox < 3; ox++)
        for (int k = 0; k < 4; k++)
            V[ox][k] = vf_zero();
    for (int oz = 0; oz < 3; oz++)
        for (int oy = 0; oy < 3; oy++) {
            const float *row = r[oz * 3 + oy] + (size_t)i * ARRAYS;
            vi words = masked ? vi_load(m[oz * 3 + oy] + i) : vi_zero();
            for (int h = 0; h < 2; h++) {
                const float *o = row + 8 * h * PER_HALF;
                vf wyz = vf_mul(vf_load(o + 8 * (WY + oy)), vf_load(o + 8 * (WZ + oz)));
                vf s0 = vf_load(o + 8 * SS), s1 = vf_load(o + 8 * (SS + 1));
                vf s2 = vf_load(o + 8 * (SS + 2));
                for (int ox = 0; ox < 3; ox++) {
                    vf a = vf_mul(vf_load(o + 8 * (EX + ox)), wyz);
                    int k27 = oz * 9 + oy * 3 + ox;
                    if (masked && k27 != 13)
                        a = vf_and(a, vi_bit_clear(words, k27 < 13 ? k27 : k27 - 1));
                    V[ox][0] = vf_add(V[ox][0], a);
                    V[ox][1] = vf_fma(a, s0, V[ox][1]);
                    V[ox][2] = vf_fma(a, s1, V[ox][2]);
                    V[ox][3] = vf_fma(a, s2, V[ox][3]);
                }
            }
        }
}

/* Destination row (y, z), colour c, segment x0: V_ox of its cells and of the cells either
 * side of the segment that lie in the row, then dst = V_-1(x + 1) + V_0(x) + V_+1(x - 1). */
static void dst_row(const job *jb, ring *rg, int y, int z, int z0, int z1, int x0, int c)
{
    const int nx = jb->src->n[0], ny = jb->src->n[1], nz = jb->src->n[2];
    const int len = nx - x0 < XS ? nx - x0 : XS;
    const float *r[9];
    const unsigned *m[9];
    for (int oz = -1; oz <= 1; oz++)
        for (int oy = -1; oy <= 1; oy++) {
            int sy = y - oy, sz = z - oz, k = (oz + 1) * 3 + oy + 1;
            int inside = sy >= 0 && sy < ny && sz >= 0 && sz < nz && sz >= z0 - 1 && sz <= z1;
            r[k] = inside ? rg->v[sy % 3][sz - (z0 - 1)] : rg->zero;
            m[k] = inside ? rg->mask[sy % 3][sz - (z0 - 1)] : rg->zero_mask;
        }
    for (int i = 0; i < PW; i += 8) {
        int x = x0 - 8 + i;
        vf V[3][4];
        if (x >= 0 && x < nx && (i > 0 || x0 > 0) && x < x0 + len + 8) {
            vi any = vi_zero();
            for (int k = 0; k < 9; k++)
                any = vi_or(any, vi_load(m[k] + i));
            if (vi_any(any))
                gather_v(r, m, i, 1, V);
            else
                gather_v(r, m, i, 0, V);
        } else {
            for (int ox = 0; ox < 3; ox++)
                for (int k = 0; k < 4; k++)
                    V[ox][k] = vf_zero();
        }
        for (int ox = 0; ox < 3; ox++)
            for (int k = 0; k < 4; k++)
                vf_store(rg->V[ox][k] + i, V[ox][k]);
    }
    const size_t row = ((size_t)z * ny + y) * nx + (size_t)x0;
    for (int v = 0; v < len; v += 8) {
        const int i = v + 8;
        for (int k = 0; k < 4; k++) {
            vf d = vf_add(vf_load(rg->V[0][k] + i + 1), vf_load(rg->V[1][k] + i));
            d = vf_add(d, vf_load(rg->V[2][k] + i - 1));
            float *p = jb->dst->ch[4 * c + k] + row + v;
            if (len - v >= 8)
                vf_store(p, d);
            else
                vf_store_mask(p, d, vf_lanes(0, len - v));
        }
    }
}

/* One tile of destination slabs z0 .. z1 - 1, segment by segment and colour by colour:
 * row y's destination rows once the source rows y - 1 .. y + 1 of slabs z0 - 1 .. z1 are
 * in the ring; then the finished slabs are added into accum. */
static void tile(void *ctx, int item)
{
    const job *jb = ctx;
    fpmode mode = fpmode_enter();
    const int nx = jb->src->n[0], ny = jb->src->n[1], nz = jb->src->n[2];
    int z0 = item * Z_TILE, z1 = z0 + Z_TILE < nz ? z0 + Z_TILE : nz;
    ring storage, *rg = &storage; /* 250 KB: well inside any thread's stack */
    memset(rg->zero, 0, sizeof rg->zero);
    memset(rg->zero_mask, 0, sizeof rg->zero_mask);
    for (int x0 = 0; x0 < nx; x0 += XS)
        for (int c = 0; c < 3; c++)
            for (int y = -1; y < ny; y++) {
                if (y + 1 < ny)
                    for (int sz = z0 - 1; sz <= z1; sz++)
                        if (sz >= 0 && sz < nz)
                            split_row(jb, rg, (y + 1) % 3, sz - (z0 - 1), y + 1, sz, x0, c);
                if (y >= 0)
                    for (int z = z0; z < z1; z++)
                        dst_row(jb, rg, y, z, z0, z1, x0, c);
            }
    if (jb->accum)
        lpv_volume_add_slab(jb->accum, jb->dst, z0, z1);
    fpmode_leave(mode);
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
    float la = lpv_probability_clamp(desc->absorption), ls = lpv_probability_clamp(desc->scattering);
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
    /* Per colour: the split (about 60 operations), its axis weights (2 halves x 3 axes x 7)
     * and x weights times the energy (6); per (o_y, o_z) and half the y-z weight (1) and per
     * x offset the share (1 multiply) and its four coefficients (1 add, 3 multiply-adds
     * counted as 2: 7); the three V_ox summed (8). */
    double per_cell = 3.0 * (60.0 + 42.0 + 6.0 + 9.0 * 2.0 * (1.0 + 3.0 * 8.0) + 8.0);
    return per_cell * (double)cells;
}
