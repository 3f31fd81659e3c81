#include "lpv/lpv_propagate.h"

#include "base/fpmode.h"

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

/* Destination cells of a row segment (a multiple of 8). A factor row holds the source
 * cells x0 - 8 .. x0 + XS + 15 of its segment: the vector either side of the segment is
 * computed (inner segments of long rows) or zero (source outside the row). */
enum { XS = 64, PW = XS + 24 };
/* The 26 neighbours in 3 groups, one per source z slab (lpv_transfer_offsets is z-major).
 * The partial sums of a destination row go through dst between groups, which changes no
 * rounding. */
static const int group_end[4] = {0, 9, 17, 26};
enum { GROUP_MAX = 9 };

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

static inline vf vf_load_n(const float *p, int n) /* first n lanes, 0 < n; others 0 */
{
#if defined(__AVX2__) && defined(__FMA__)
    if (n >= 8)
        return _mm256_loadu_ps(p);
    return _mm256_maskload_ps(p, _mm256_castps_si256(vmask_range(0, n)));
#else
    vf r = vf_zero();
    memcpy(r.v, p, (size_t)(n < 8 ? n : 8) * sizeof(float));
    return r;
#endif
}

/* dst cells x0 .. x0 + XS - 1 of row (y, z), clipped to the row, set to 0: the first group
 * of a row on the lattice's last z slab has no source slab. */
static void zero_row(const job *jb, int y, int z, int x0)
{
    const int nx = jb->src->n[0], ny = jb->src->n[1];
    const int len = nx - x0 < XS ? nx - x0 : XS;
    const size_t row = ((size_t)z * ny + y) * nx + (size_t)x0;
    for (int k = 0; k < LPV_LIGHT_CHANNELS; k++)
        memset(jb->dst->ch[k] + row, 0, (size_t)len * sizeof(float));
}

/* Pass 1 for neighbour j: the factors p[c] = (1 - b_j) A_j . S_c of the source cells
 * xa .. xb - 1 (multiples of 8) of the source row starting at index so, into P[c] at
 * x - x0 + 8. Aligned loads, each coefficient broadcast once per row. Lanes at or past
 * nx are set to 0 (no light from beyond the row); so is the guard vector of a row end. */
static ALWAYS_INLINE void factors(const job *jb, int j, ptrdiff_t so, int x0, int xa, int xb,
                                  int nx, float (*P)[PW], int blocking, int clamp)
{
    const vf zero = vf_zero(), one = vf_set1(1.0f);
    float *const *s = jb->src->ch;
    const vf a0 = vf_set1(jb->a[j][0]), a1 = vf_set1(jb->a[j][1]);
    const vf a2 = vf_set1(jb->a[j][2]), a3 = vf_set1(jb->a[j][3]);
    vf g0 = zero, g1 = zero, g2 = zero, g3 = zero;
    if (blocking) {
        g0 = vf_set1(jb->g[j][0]);
        g1 = vf_set1(jb->g[j][1]);
        g2 = vf_set1(jb->g[j][2]);
        g3 = vf_set1(jb->g[j][3]);
    }
    for (int x = xa; x < xb; x += 8) {
        const ptrdiff_t o = so + x;
        vf w = one;
        if (blocking) {
            float *const *b = jb->geometry->ch;
            vf t = vf_mul(g0, vf_load(b[0] + o));
            t = vf_fma(g1, vf_load(b[1] + o), t);
            t = vf_fma(g2, vf_load(b[2] + o), t);
            t = vf_fma(g3, vf_load(b[3] + o), t);
            w = vf_sub(one, vf_min(vf_max(t, zero), one));
        }
        for (int c = 0; c < 3; c++) {
            vf p = vf_mul(a0, vf_load(s[4 * c] + o));
            p = vf_fma(a1, vf_load(s[4 * c + 1] + o), p);
            p = vf_fma(a2, vf_load(s[4 * c + 2] + o), p);
            p = vf_fma(a3, vf_load(s[4 * c + 3] + o), p);
            if (clamp)
                p = vf_max(p, zero);
            if (blocking)
                p = vf_mul(p, w);
            vf_store(&P[c][x - x0 + 8], p, 8);
        }
    }
    const int nxv = (nx + 7) & ~7;
    if (xb == nxv) {
        if (nx < nxv) {
            const vmask m = vmask_range(0, nx - (nxv - 8));
            for (int c = 0; c < 3; c++)
                vf_store(&P[c][nxv - 8 - x0 + 8], vf_and(vf_load(&P[c][nxv - 8 - x0 + 8]), m), 8);
        }
        for (int c = 0; c < 3; c++)
            vf_store(&P[c][nxv - x0 + 8], zero, 8);
    }
    if (x0 == 0)
        for (int c = 0; c < 3; c++)
            vf_store(&P[c][0], zero, 8);
}

/* One group of neighbours (those of one source z slab sz, which must lie in the lattice)
 * for destination row (y, z), cells x0 .. x0 + XS - 1 clipped to the row: pass 1 for each
 * neighbour whose source row exists, then pass 2 adds the group to the row, starting from
 * zero for the first group (gi = 0) and from the row's partial sums otherwise. */
static ALWAYS_INLINE void group(const job *jb, int y, int z, int gi, int x0, int blocking,
                                int clamp)
{
    _Alignas(64) float P[GROUP_MAX][3][PW];
    const int nx = jb->src->n[0], ny = jb->src->n[1];
    const int len = nx - x0 < XS ? nx - x0 : XS, nv = (len + 7) / 8;
    const int nxv = (nx + 7) & ~7;
    const int xa = x0 == 0 ? 0 : x0 - 8;
    const int xb = x0 + XS + 8 < nxv ? x0 + XS + 8 : nxv;
    const size_t row = ((size_t)z * ny + y) * nx + (size_t)x0;
    const float *prow[GROUP_MAX];
    int js[GROUP_MAX], count = 0;
    for (int j = group_end[gi]; j < group_end[gi + 1]; j++) {
        const int *o = lpv_transfer_offsets[j];
        const int sy = y - o[1], sz = z - o[2];
        if (sy < 0 || sy >= ny)
            continue;
        factors(jb, j, ((ptrdiff_t)sz * ny + sy) * nx, x0, xa, xb, nx, P[count], blocking, clamp);
        /* destination x reads source x - o_x, at buffer index x - x0 + 8 - o_x */
        prow[count] = &P[count][0][8 - o[0]];
        js[count++] = j;
    }
    if (gi > 0 && count == 0)
        return;
    float *const *d = jb->dst->ch;
    for (int v = 0; v < nv; v++) {
        const int n = len - 8 * v;
        vf acc[12];
        for (int k = 0; k < 12; k++)
            acc[k] = gi == 0 ? vf_zero() : vf_load_n(d[k] + row + 8 * v, n);
        for (int e = 0; e < count; e++) {
            const float *p = prow[e] + 8 * v;
            const float *g = jb->g[js[e]];
            const vf pr = vf_load(p), pg = vf_load(p + PW), pb = vf_load(p + 2 * PW);
            for (int k = 0; k < 4; k++) {
                const vf gk = vf_set1(g[k]);
                acc[k] = vf_fma(pr, gk, acc[k]);
                acc[4 + k] = vf_fma(pg, gk, acc[4 + k]);
                acc[8 + k] = vf_fma(pb, gk, acc[8 + k]);
            }
        }
        for (int k = 0; k < 12; k++)
            vf_store(d[k] + row + 8 * v, acc[k], n);
    }
}

enum { Z_TILE = 8 };

/* Destination rows z0 .. z1 - 1 of the tile, row y by row y. For each y and segment, the
 * source slabs are swept from z1 down to z0 - 1: the three source rows (y - 1 .. y + 1, sz)
 * serve group 0 of destination row sz - 1 (its first), group 1 of sz and group 2 of
 * sz + 1 (its last) while they are in L1, so a source row is brought into L1 three times
 * per step (once per destination y) instead of nine. The tile's source rows for three
 * consecutive y (30 rows, 120 KB at nx = 64) stay in L2. */
static ALWAYS_INLINE void tile_rows(const job *jb, int z0, int z1, int blocking, int clamp)
{
    const int nx = jb->src->n[0], ny = jb->src->n[1], nz = jb->src->n[2];
    for (int y = 0; y < ny; y++)
        for (int x0 = 0; x0 < nx; x0 += XS)
            for (int sz = z1; sz >= z0 - 1; sz--)
                for (int gi = 0; gi < 3; gi++) {
                    const int z = sz + gi - 1;
                    if (z < z0 || z >= z1)
                        continue;
                    if (sz >= 0 && sz < nz)
                        group(jb, y, z, gi, x0, blocking, clamp);
                    else if (gi == 0)
                        zero_row(jb, y, z, x0);
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
