#include "lpv_propagate.h"

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

/* Cells of a row whose blocking weights are held at once; rows of the buffer are W_STRIDE
 * apart (not a power of two, so that the 26 rows spread over the L1 sets). */
enum { CHUNK = 128, W_STRIDE = CHUNK + 16 };

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

/* w_j = 1 - clamp(<B[c - o_j] | G_j>, 0, 1) for the cells [cx, cx + cn) of the row (cn a
 * multiple of 16). Lanes past a row's ends read neighbouring cells or the guard; they
 * belong to cells that are never stored. */
static void blocking_chunk(const job *jb, const row_ctx *r, int cx, int cn,
                           float w[LPV_NEIGHBOURS][W_STRIDE])
{
    const lpv_volume *geo = jb->geometry;
    const vf one = vf_set1(1.0f), zero = vf_zero();
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        if (!r->valid[j])
            continue;
        vf g0 = vf_set1(jb->g[j][0]), g1 = vf_set1(jb->g[j][1]);
        vf g2 = vf_set1(jb->g[j][2]), g3 = vf_set1(jb->g[j][3]);
        for (int x = 0; x < cn; x += 8) {
            ptrdiff_t o = r->off[j] + cx + x;
            vf b = vf_mul(g0, vf_load(geo->ch[0] + o));
            b = vf_fma(g1, vf_load(geo->ch[1] + o), b);
            b = vf_fma(g2, vf_load(geo->ch[2] + o), b);
            b = vf_fma(g3, vf_load(geo->ch[3] + o), b);
            b = vf_min(vf_max(b, zero), one);
            vf out = vf_sub(one, b);
            vf_store(&w[j][x], out, 8);
        }
    }
}

/* Sixteen destination cells from x0, one colour at a time: eight accumulators (two
 * vectors of 4 SH coefficients) stay in registers across the 26 neighbours, summed in
 * their fixed order, and each broadcast coefficient serves both vectors. Few enough live
 * values (8 accumulators, 2 factors, 1 coefficient, 4 channel pointers) that nothing
 * spills on x86-64 with AVX2. edge: the pair holds x = 0 or x = nx - 1, where a
 * neighbour's source cell may lie beyond the row (x = -1 for dx = +1, x = nx for
 * dx = -1); its factor is masked to zero there (one AND per factor, not per load).
 * Lanes past the row's end are computed from whatever lies there and never stored. */
static ALWAYS_INLINE void pair(const job *jb, const row_ctx *r, int x0,
                               const float w[LPV_NEIGHBOURS][W_STRIDE], int wx, int edge,
                               int blocking, int clamp)
{
    const int nx = r->nx;
    vmask mask[2][3]; /* [half][dx + 1]: lanes whose source x = x0 + 8 h + l - dx is in the row */
    if (edge)
        for (int h = 0; h < 2; h++)
            for (int d = 0; d < 3; d++) {
                int xb = x0 + 8 * h;
                mask[h][d] = vmask_range(d - 1 - xb, nx - xb + d - 1);
            }
    const vf zero = vf_zero();
    for (int c = 0; c < 3; c++) {
        const float *s0 = jb->src->ch[4 * c], *s1 = jb->src->ch[4 * c + 1];
        const float *s2 = jb->src->ch[4 * c + 2], *s3 = jb->src->ch[4 * c + 3];
        vf u0 = zero, u1 = zero, u2 = zero, u3 = zero; /* cells x0 .. x0 + 7 */
        vf v0 = zero, v1 = zero, v2 = zero, v3 = zero; /* cells x0 + 8 .. x0 + 15 */
        for (int j = 0; j < LPV_NEIGHBOURS; j++) {
            if (!r->valid[j])
                continue;
            const ptrdiff_t o = r->off[j] + x0;
            vf a = vf_set1(jb->a[j][0]);
            vf p = vf_mul(a, vf_load(s0 + o)), q = vf_mul(a, vf_load(s0 + o + 8));
            a = vf_set1(jb->a[j][1]);
            p = vf_fma(a, vf_load(s1 + o), p);
            q = vf_fma(a, vf_load(s1 + o + 8), q);
            a = vf_set1(jb->a[j][2]);
            p = vf_fma(a, vf_load(s2 + o), p);
            q = vf_fma(a, vf_load(s2 + o + 8), q);
            a = vf_set1(jb->a[j][3]);
            p = vf_fma(a, vf_load(s3 + o), p);
            q = vf_fma(a, vf_load(s3 + o + 8), q);
            if (edge) {
                const int d = lpv_transfer_offsets[j][0] + 1;
                p = vf_and(p, mask[0][d]);
                q = vf_and(q, mask[1][d]);
            }
            if (clamp) {
                p = vf_max(p, zero);
                q = vf_max(q, zero);
            }
            if (blocking) {
                p = vf_mul(p, vf_load(&w[j][wx]));
                q = vf_mul(q, vf_load(&w[j][wx + 8]));
            }
            vf g = vf_set1(jb->g[j][0]);
            u0 = vf_fma(p, g, u0);
            v0 = vf_fma(q, g, v0);
            g = vf_set1(jb->g[j][1]);
            u1 = vf_fma(p, g, u1);
            v1 = vf_fma(q, g, v1);
            g = vf_set1(jb->g[j][2]);
            u2 = vf_fma(p, g, u2);
            v2 = vf_fma(q, g, v2);
            g = vf_set1(jb->g[j][3]);
            u3 = vf_fma(p, g, u3);
            v3 = vf_fma(q, g, v3);
        }
        size_t d = r->row + (size_t)x0;
        float *const *out = &jb->dst->ch[4 * c];
        int n = nx - x0;
        vf_store(out[0] + d, u0, n);
        vf_store(out[1] + d, u1, n);
        vf_store(out[2] + d, u2, n);
        vf_store(out[3] + d, u3, n);
        if (n > 8) {
            vf_store(out[0] + d + 8, v0, n - 8);
            vf_store(out[1] + d + 8, v1, n - 8);
            vf_store(out[2] + d + 8, v2, n - 8);
            vf_store(out[3] + d + 8, v3, n - 8);
        }
    }
}

/* The row loop, specialized on the two settings so the inner loop has no branches on them. */
static ALWAYS_INLINE void row_blocks(const job *jb, const row_ctx *r, int blocking, int clamp)
{
    _Alignas(32) float w[LPV_NEIGHBOURS][W_STRIDE];
    int nx = r->nx;
    for (int cx = 0; cx < nx; cx += CHUNK) {
        int cn = nx - cx < CHUNK ? nx - cx : CHUNK;
        if (blocking)
            blocking_chunk(jb, r, cx, (cn + 15) & ~15, w);
        for (int x0 = cx; x0 < cx + cn; x0 += 16) {
            if (x0 == 0 || x0 + 16 >= nx)
                pair(jb, r, x0, w, x0 - cx, 1, blocking, clamp);
            else
                pair(jb, r, x0, w, x0 - cx, 0, blocking, clamp);
        }
    }
}

/* Destination rows are visited y-major inside a tile of Z_TILE slices: a source row is
 * used by the 3 x 3 destination rows around it, which then come within a few rows of
 * each other, so it is read from L2 instead of L3 (y-major over whole slices would
 * evict it between slices). */
enum { Z_TILE = 8 };

static void one_row(const job *jb, int y, int z)
{
    const int nx = jb->src->n[0], ny = jb->src->n[1], nz = jb->src->n[2];
    row_ctx r;
    r.nx = nx;
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        const int *o = lpv_transfer_offsets[j];
        int sy = y - o[1], sz = z - o[2];
        r.valid[j] = sy >= 0 && sy < ny && sz >= 0 && sz < nz;
        r.off[j] = ((ptrdiff_t)sz * ny + sy) * nx - o[0];
    }
    r.row = ((size_t)z * ny + y) * nx;
    int blocking = jb->geometry != NULL;
    if (blocking && jb->clamp)
        row_blocks(jb, &r, 1, 1);
    else if (blocking)
        row_blocks(jb, &r, 1, 0);
    else if (jb->clamp)
        row_blocks(jb, &r, 0, 1);
    else
        row_blocks(jb, &r, 0, 0);
}

/* One tile of Z_TILE slices: the work item of the pool. Every cell's sum is the same
 * whatever thread runs it and in whatever order the rows are visited. */
static void tile(void *ctx, int item)
{
    const job *jb = ctx;
    const int ny = jb->src->n[1], nz = jb->src->n[2];
    int z0 = item * Z_TILE, z1 = z0 + Z_TILE < nz ? z0 + Z_TILE : nz;
    for (int y = 0; y < ny; y++)
        for (int z = z0; z < z1; z++)
            one_row(jb, y, z);
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
        /* g_j l_s <S|1> / <G_j|1> = (g_j l_s / G_j0) S_0 */
        jb.a[j][0] = (float)((1.0 - lt) * t->gamma[j][0] + t->outscatter[j] * ls / t->gamma[j][0]);
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
