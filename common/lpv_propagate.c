#include "lpv_propagate.h"

#include "fpmode.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

/* One kernel, written against a tiny 8-lane vector layer: AVX2+FMA intrinsics when the
 * build targets them, plain C with fmaf otherwise. Both layers perform the same IEEE
 * operations in the same order (fused multiply-adds, max/min with the x86 NaN rule), so
 * a build's result never depends on the thread count. */
#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>

typedef __m256 vf;
typedef __m256 vmask;
static inline vf vf_load(const float *p) { return _mm256_loadu_ps(p); }
static inline vf vf_set1(float x) { return _mm256_set1_ps(x); }
static inline vf vf_zero(void) { return _mm256_setzero_ps(); }
static inline vf vf_mul(vf a, vf b) { return _mm256_mul_ps(a, b); }
static inline vf vf_sub(vf a, vf b) { return _mm256_sub_ps(a, b); }
static inline vf vf_fma(vf a, vf b, vf c) { return _mm256_fmadd_ps(a, b, c); } /* a*b+c */
static inline vf vf_max(vf a, vf b) { return _mm256_max_ps(a, b); }
static inline vf vf_min(vf a, vf b) { return _mm256_min_ps(a, b); }
static inline vf vf_and(vf a, vmask m) { return _mm256_and_ps(a, m); }
static inline vmask vmask_range(int lo, int hi) /* lanes l with lo <= l < hi */
{
    __m256i l = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    __m256i in = _mm256_and_si256(_mm256_cmpgt_epi32(l, _mm256_set1_epi32(lo - 1)),
                                  _mm256_cmpgt_epi32(_mm256_set1_epi32(hi), l));
    return _mm256_castsi256_ps(in);
}
static inline void vf_store(float *p, vf a, int n) /* first n lanes */
{
    if (n >= 8)
        _mm256_storeu_ps(p, a);
    else
        _mm256_maskstore_ps(p, _mm256_castps_si256(vmask_range(0, n)), a);
}
#else
typedef struct { float v[8]; } vf;
typedef struct { unsigned m[8]; } vmask;
static inline vf vf_load(const float *p) { vf r; memcpy(r.v, p, sizeof r.v); return r; }
static inline vf vf_set1(float x) { vf r; for (int l = 0; l < 8; l++) r.v[l] = x; return r; }
static inline vf vf_zero(void) { return vf_set1(0.0f); }
static inline vf vf_mul(vf a, vf b) { for (int l = 0; l < 8; l++) a.v[l] *= b.v[l]; return a; }
static inline vf vf_sub(vf a, vf b) { for (int l = 0; l < 8; l++) a.v[l] -= b.v[l]; return a; }
static inline vf vf_fma(vf a, vf b, vf c) { for (int l = 0; l < 8; l++) c.v[l] = fmaf(a.v[l], b.v[l], c.v[l]); return c; }
static inline vf vf_max(vf a, vf b) { for (int l = 0; l < 8; l++) a.v[l] = a.v[l] > b.v[l] ? a.v[l] : b.v[l]; return a; }
static inline vf vf_min(vf a, vf b) { for (int l = 0; l < 8; l++) a.v[l] = a.v[l] < b.v[l] ? a.v[l] : b.v[l]; return a; }
static inline vf vf_and(vf a, vmask m)
{
    for (int l = 0; l < 8; l++) {
        unsigned bits;
        memcpy(&bits, &a.v[l], sizeof bits);
        bits &= m.m[l];
        memcpy(&a.v[l], &bits, sizeof bits);
    }
    return a;
}
static inline vmask vmask_range(int lo, int hi)
{
    vmask m;
    for (int l = 0; l < 8; l++) m.m[l] = (l >= lo && l < hi) ? ~0u : 0u;
    return m;
}
static inline void vf_store(float *p, vf a, int n) { memcpy(p, a.v, (size_t)(n < 8 ? n : 8) * sizeof(float)); }
#endif

#define ALWAYS_INLINE inline __attribute__((always_inline))

enum { XC = 32 }; /* cells of a row handled at once (a multiple of 8) */

typedef struct job {
    const lpv_volume *src;
    lpv_volume *dst;
    const lpv_volume *geometry; /* NULL: no blocking this step */
    int clamp;
    /* Per neighbour j: the factor sent is p = A_j . src (scattering folded into A_j0), the
     * destination gains p G_j. */
    float a[LPV_NEIGHBOURS][4];
    float g[LPV_NEIGHBOURS][4];
} job;

typedef struct row_ctx {
    ptrdiff_t off[LPV_NEIGHBOURS]; /* source index of x = 0 in the row, minus dx */
    int valid[LPV_NEIGHBOURS];     /* source row inside the lattice */
    size_t row;                    /* destination index of x = 0 */
    int nx;
} row_ctx;

/* XC destination cells from x0, in two passes over a small buffer that stays in L1.
 * Pass 1 computes every factor p[j][c] = (1 - b_j) A_j . S_c(x - o_j): short independent
 * chains, each coefficient broadcast once for the whole chunk. Pass 2 sums
 * dst[c][k] += p[j][c] G_jk over the 26 neighbours in their fixed order with twelve
 * accumulators (3 colours x 4 SH) in registers. Keeping the two apart avoids one long
 * dependency chain per neighbour that the out-of-order window could not hide.
 * Lanes whose source lies beyond the row (x = -1 for dx = +1, x = nx for dx = -1) get
 * p = 0; lanes past the row's end are computed from whatever lies there (a neighbouring
 * row or the zero guard) and never stored. */
static ALWAYS_INLINE void chunk(const job *jb, const row_ctx *r, int x0, int edge,
                                int blocking, int clamp)
{
    enum { NV = XC / 8 };
    _Alignas(32) float P[LPV_NEIGHBOURS][3][XC];
    const int nx = r->nx, nv = ((nx - x0 < XC ? nx - x0 : XC) + 7) / 8;
    const vf zero = vf_zero(), one = vf_set1(1.0f);
    float *const *s = jb->src->ch;
    vmask mask[3][NV]; /* [dx + 1][v]: lanes whose source x = x0 + 8 v + l - dx is in the row */
    if (edge)
        for (int d = 0; d < 3; d++)
            for (int v = 0; v < NV; v++)
                mask[d][v] = vmask_range(d - 1 - (x0 + 8 * v), nx - (x0 + 8 * v) + d - 1);
    /* Pass 1 always fills all NV vectors: loads past the row read following rows or the
     * volume's guard, and those lanes are never stored. */
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        if (!r->valid[j])
            continue;
        const ptrdiff_t o = r->off[j] + x0;
        vf wv[NV];
        if (blocking) {
            float *const *b = jb->geometry->ch;
            const vf g0 = vf_set1(jb->g[j][0]), g1 = vf_set1(jb->g[j][1]);
            const vf g2 = vf_set1(jb->g[j][2]), g3 = vf_set1(jb->g[j][3]);
            for (int v = 0; v < NV; v++) {
                vf t = vf_mul(g0, vf_load(b[0] + o + 8 * v));
                t = vf_fma(g1, vf_load(b[1] + o + 8 * v), t);
                t = vf_fma(g2, vf_load(b[2] + o + 8 * v), t);
                t = vf_fma(g3, vf_load(b[3] + o + 8 * v), t);
                wv[v] = vf_sub(one, vf_min(vf_max(t, zero), one));
            }
        }
        const vf a0 = vf_set1(jb->a[j][0]), a1 = vf_set1(jb->a[j][1]);
        const vf a2 = vf_set1(jb->a[j][2]), a3 = vf_set1(jb->a[j][3]);
        for (int c = 0; c < 3; c++) {
            for (int v = 0; v < NV; v++) {
                const ptrdiff_t ov = o + 8 * v;
                vf p = vf_mul(a0, vf_load(s[4 * c] + ov));
                p = vf_fma(a1, vf_load(s[4 * c + 1] + ov), p);
                p = vf_fma(a2, vf_load(s[4 * c + 2] + ov), p);
                p = vf_fma(a3, vf_load(s[4 * c + 3] + ov), p);
                if (edge)
                    p = vf_and(p, mask[lpv_transfer_offsets[j][0] + 1][v]);
                if (clamp)
                    p = vf_max(p, zero);
                if (blocking)
                    p = vf_mul(p, wv[v]);
                vf_store(&P[j][c][8 * v], p, 8);
            }
        }
    }
    for (int v = 0; v < nv; v++) {
        vf acc[12];
        for (int k = 0; k < 12; k++)
            acc[k] = zero;
        for (int j = 0; j < LPV_NEIGHBOURS; j++) {
            if (!r->valid[j])
                continue;
            const vf pr = vf_load(&P[j][0][8 * v]), pg = vf_load(&P[j][1][8 * v]);
            const vf pb = vf_load(&P[j][2][8 * v]);
            for (int k = 0; k < 4; k++) {
                const vf g = vf_set1(jb->g[j][k]);
                acc[k] = vf_fma(pr, g, acc[k]);
                acc[4 + k] = vf_fma(pg, g, acc[4 + k]);
                acc[8 + k] = vf_fma(pb, g, acc[8 + k]);
            }
        }
        const int xb = x0 + 8 * v;
        const size_t d = r->row + (size_t)xb;
        for (int k = 0; k < 12; k++)
            vf_store(jb->dst->ch[k] + d, acc[k], nx - xb);
    }
}

static void row_setup(const job *jb, int y, int z, row_ctx *r)
{
    const int nx = jb->src->n[0], ny = jb->src->n[1], nz = jb->src->n[2];
    r->nx = nx;
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        const int *o = lpv_transfer_offsets[j];
        int sy = y - o[1], sz = z - o[2];
        r->valid[j] = sy >= 0 && sy < ny && sz >= 0 && sz < nz;
        r->off[j] = ((ptrdiff_t)sz * ny + sy) * nx - o[0];
    }
    r->row = ((size_t)z * ny + y) * nx;
}

/* A tile of Z_TILE slices, visited y-major, then chunk by chunk along x, then z: the
 * destination chunks at (x0, y, z) and (x0, y, z + 1) share 6 of their 9 source rows, so
 * those are still in L1, and a source row comes back for y + 1 while still in L2. */
enum { Z_TILE = 8 };

static ALWAYS_INLINE void tile_rows(const job *jb, int z0, int z1, int blocking, int clamp)
{
    const int nx = jb->src->n[0], ny = jb->src->n[1];
    row_ctx r[Z_TILE];
    for (int y = 0; y < ny; y++) {
        for (int z = z0; z < z1; z++)
            row_setup(jb, y, z, &r[z - z0]);
        for (int x0 = 0; x0 < nx; x0 += XC) {
            int edge = x0 == 0 || x0 + XC >= nx;
            for (int z = z0; z < z1; z++) {
                if (edge)
                    chunk(jb, &r[z - z0], x0, 1, blocking, clamp);
                else
                    chunk(jb, &r[z - z0], x0, 0, blocking, clamp);
            }
        }
    }
}

/* One tile: the work item of the pool. Every cell's sum is the same whatever thread runs
 * it and in whatever order the cells are visited. */
static void tile(void *ctx, int item)
{
    const job *jb = ctx;
    fpmode mode = fpmode_enter();
    const int nz = jb->src->n[2];
    int z0 = item * Z_TILE, z1 = z0 + Z_TILE < nz ? z0 + Z_TILE : nz;
    int blocking = jb->geometry != NULL;
    if (blocking && jb->clamp)
        tile_rows(jb, z0, z1, 1, 1);
    else if (blocking)
        tile_rows(jb, z0, z1, 1, 0);
    else if (jb->clamp)
        tile_rows(jb, z0, z1, 0, 1);
    else
        tile_rows(jb, z0, z1, 0, 0);
    fpmode_leave(mode);
}

static float unit_clamp(float x)
{
    return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; /* NaN -> 0 */
}

void lpv_propagate_step(const lpv_propagate_desc *desc, const lpv_volume *src, lpv_volume *dst)
{
    if (!desc || !desc->transfer || !src || !dst || src == dst ||
        src->channels != LPV_LIGHT_CHANNELS || dst->channels != LPV_LIGHT_CHANNELS ||
        memcmp(src->n, dst->n, sizeof src->n) != 0)
        return;
    job jb;
    jb.src = src;
    jb.dst = dst;
    jb.geometry = NULL;
    if (desc->use_blocking && desc->geometry &&
        desc->geometry->channels == LPV_GEOMETRY_CHANNELS &&
        memcmp(desc->geometry->n, src->n, sizeof src->n) == 0)
        jb.geometry = desc->geometry;
    jb.clamp = desc->clamp_negative != 0;
    double la = unit_clamp(desc->absorption), ls = unit_clamp(desc->scattering);
    double lt = la + ls > 1.0 ? 1.0 : la + ls;
    const lpv_transfer *t = desc->transfer;
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        for (int s = 0; s < 4; s++) {
            jb.g[j][s] = t->gamma[j][s];
            jb.a[j][s] = (float)((1.0 - lt) * t->gamma[j][s]);
        }
        /* g_j l_s <S|1> / <G_j|1> = (g_j l_s / G_j0) S_0; a vector without energy can
         * carry no scattered light. */
        double scatter = t->gamma[j][0] != 0.0f ? t->outscatter[j] * ls / t->gamma[j][0] : 0.0;
        jb.a[j][0] = (float)((1.0 - lt) * t->gamma[j][0] + scatter);
    }
    workpool_run(desc->pool, (src->n[2] + Z_TILE - 1) / Z_TILE, tile, &jb);
}

double lpv_propagate_flops(size_t cells, int use_blocking)
{
    /* Per neighbour and colour: the factor (1 mul + 3 fma = 7 flops) and the update
     * (4 fma = 8). Blocking per neighbour: dot (7), clamp (2), 1 - b (1), and one multiply
     * per colour (3). */
    double per_cell = LPV_NEIGHBOURS * (3.0 * 15.0 + (use_blocking ? 13.0 : 0.0));
    return per_cell * (double)cells;
}
