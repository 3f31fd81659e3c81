#include "gi/ilpv/lpv_splat.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/fpmode.h"
#include "base/xalloc.h"
#include "gi/ilpv/lpv_receive.h"
#include "gi/ilpv/lpv_transfer.h"
#include "gi/ilpv/sh.h"

/* Targets are cells whose centre may lie within R + 1 of an origin anywhere in its cell
 * (up to sqrt(3)/2 from the centre, and VPLs sit up to another cell away): |t| < R + 2.9. */
enum { REACH = LPV_SPLAT_RADIUS + 3, MAX_HOPS = REACH, Z_TILE = 8 };
/* Hops that take a shell cell out of its surface's own layer: one for an axis-aligned
 * surface, at most two for any other (the layer is 0.5 (|n_x| + |n_y| + |n_z|) + 0.5 cells
 * thick, and each hop along the axis closest to n moves at least 1 / sqrt(3) cells out). */
enum { LIFT_MAX = 3 };
#define REACH_LIMIT ((double)LPV_SPLAT_RADIUS + 2.9)

typedef struct target {
    int t[3];
    int hops;
    signed char k[MAX_HOPS];     /* neighbour index of each hop */
    signed char at[MAX_HOPS][3]; /* offset (from the source cell) the hop starts at */
} target;

typedef struct table {
    target *targets;
    int count;
} table;

static const double PI = 3.14159265358979323846;

static int neighbour_index(int dx, int dy, int dz)
{
    for (int k = 0; k < LPV_NEIGHBOURS; k++)
        if (lpv_transfer_offsets[k][0] == dx && lpv_transfer_offsets[k][1] == dy &&
            lpv_transfer_offsets[k][2] == dz)
            return k;
    return -1;
}

/* The straight lattice walk from the source cell to t: after hop i of m (m the largest
 * |t_a|) the walk is at round(t i / m), so every hop moves at most one cell per axis. */
static void build_table(table *tb)
{
    int side = 2 * REACH + 1;
    tb->targets = xmalloc((size_t)side * side * side * sizeof *tb->targets);
    tb->count = 0;
    for (int z = -REACH; z <= REACH; z++)
        for (int y = -REACH; y <= REACH; y++)
            for (int x = -REACH; x <= REACH; x++) {
                if (sqrt((double)(x * x + y * y + z * z)) >= REACH_LIMIT)
                    continue;
                target *g = &tb->targets[tb->count++];
                g->t[0] = x;
                g->t[1] = y;
                g->t[2] = z;
                int m = abs(x) > abs(y) ? abs(x) : abs(y);
                m = abs(z) > m ? abs(z) : m;
                g->hops = m;
                int prev[3] = {0, 0, 0};
                for (int i = 1; i <= m; i++) {
                    int cur[3] = {(int)floor((double)x * i / m + 0.5),
                                  (int)floor((double)y * i / m + 0.5),
                                  (int)floor((double)z * i / m + 0.5)};
                    g->k[i - 1] = (signed char)neighbour_index(cur[0] - prev[0], cur[1] - prev[1],
                                                               cur[2] - prev[2]);
                    for (int a = 0; a < 3; a++) {
                        g->at[i - 1][a] = (signed char)prev[a];
                        prev[a] = cur[a];
                    }
                }
            }
}

/* Angular density of the source's light in colour c towards unit w (1/sr). */
static float density(const lpv_splat_source *s, int c, const float w[3])
{
    float cw = s->dir[c][0] * w[0] + s->dir[c][1] * w[1] + s->dir[c][2] * w[2];
    float p = s->iso[c] * (float)(1.0 / (4.0 * PI));
    if (cw > 0.0f)
        p += s->cosine[c] * cw * (float)(1.0 / PI) + s->hemi[c] * (float)(1.0 / (2.0 * PI));
    return p;
}

/* The closest shape of the four for mean cosine q: clamped cosine (q = 2/3), hemisphere
 * (1/2), isotropic (0), linear mixes in between; more than 2/3 (a beam-like injection,
 * which VPLs never give) reads as the clamped cosine. */
static void closure(const float L[4], lpv_splat_source *s, int c)
{
    const float inv_y1 = (float)(1.0 / SH_Y1);
    float e = (float)SH_ENERGY * L[0];
    float f[3] = {-L[3] * inv_y1, -L[1] * inv_y1, L[2] * inv_y1};
    float len = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    s->energy[c] = e > 0.0f && isfinite(e) && isfinite(len) ? e : 0.0f;
    s->cosine[c] = s->hemi[c] = 0.0f;
    s->iso[c] = 1.0f;
    for (int a = 0; a < 3; a++)
        s->dir[c][a] = a == 2 ? 1.0f : 0.0f;
    if (!(s->energy[c] > 0.0f) || !(len > LPV_TRANSFER_MIN_Q * e))
        return;
    for (int a = 0; a < 3; a++)
        s->dir[c][a] = f[a] / len;
    float q = len / e;
    if (q >= 2.0f / 3.0f) {
        s->cosine[c] = 1.0f;
        s->iso[c] = 0.0f;
    } else if (q >= 0.5f) {
        s->cosine[c] = 6.0f * q - 3.0f;
        s->hemi[c] = 1.0f - s->cosine[c];
        s->iso[c] = 0.0f;
    } else {
        s->hemi[c] = 2.0f * q;
        s->iso[c] = 1.0f - s->hemi[c];
    }
}

typedef struct job {
    const lpv_splat *s;
    const table *tb;
    const lpv_splat_desc *d;
    lpv_volume *near, *shell;
    const float (*norm)[3]; /* per source and colour: 1 / sum of p / r^2 over its shell */
    float log_keep;         /* log2(1 - absorption) */
} job;

static size_t index_of(const int n[3], int x, int y, int z)
{
    return (size_t)x + (size_t)n[0] * ((size_t)y + (size_t)n[1] * z);
}

static int visible(const lpv_blockers *b, const int cell[3], const target *g)
{
    if (!b)
        return 1;
    for (int i = 0; i < g->hops; i++) {
        int x = cell[0] + g->at[i][0], y = cell[1] + g->at[i][1], z = cell[2] + g->at[i][2];
        if ((b->mask[index_of(b->n, x, y, z)] >> g->k[i]) & 1u)
            return 0;
    }
    return 1;
}

static void add_beam(lpv_volume *v, size_t i, int c, float e, const float w[3])
{
    v->ch[4 * c][i] += e * (float)SH_Y0;
    v->ch[4 * c + 1][i] += -e * w[1] * (float)SH_Y1;
    v->ch[4 * c + 2][i] += e * w[2] * (float)SH_Y1;
    v->ch[4 * c + 3][i] += -e * w[0] * (float)SH_Y1;
}

/* The cells whose centre lies within lpv_own_layer() of the emitting surface's plane
 * are the ones its own receivers read (lpv_receive.h): its light must not be there, or a
 * lit surface would see its own outgoing light instead of what arrives. */
static int in_own_layer(const lpv_splat_source *src, const float r[3])
{
    const float *n = src->plane;
    return r[0] * n[0] + r[1] * n[1] + r[2] * n[2] < lpv_own_layer(n);
}

/* Where a shell share lands: target c (offset r from the origin), or, when c lies in the
 * emitting surface's own layer, the first cell beyond that layer along the lattice axis
 * closest to the surface's normal, the share keeping its direction. That grazing light
 * passes just above the surface; left in the layer its own receivers read, the receiver's
 * shapes (lpv_receive.h) would count part of it as arriving, and a lit surface would see its
 * own outgoing light. Returns 0, or -1 when the lift leaves the lattice or a surface blocks
 * it. */
static int shell_cell(const lpv_splat_source *src, const lpv_blockers *b, const int n[3], int c[3],
                      float r[3])
{
    int ax = 0;
    for (int a = 1; a < 3; a++)
        if (fabsf(src->plane[a]) > fabsf(src->plane[ax]))
            ax = a;
    int dir = src->plane[ax] > 0.0f ? 1 : -1, o[3] = {0, 0, 0};
    o[ax] = dir;
    int k = neighbour_index(o[0], o[1], o[2]);
    for (int hop = 0; hop < LIFT_MAX && in_own_layer(src, r); hop++) {
        if (c[ax] + dir < 0 || c[ax] + dir >= n[ax] ||
            (b && ((b->mask[index_of(b->n, c[0], c[1], c[2])] >> k) & 1u)))
            return -1;
        c[ax] += dir;
        r[ax] += (float)dir;
    }
    return 0;
}

static void splat_tile(void *ctx, int item)
{
    const job *jb = ctx;
    fpmode mode = fpmode_enter();
    const int *n = jb->near->n;
    const float R = (float)LPV_SPLAT_RADIUS;
    int z0 = item * Z_TILE, z1 = z0 + Z_TILE < n[2] ? z0 + Z_TILE : n[2];
    for (size_t si = 0; si < jb->s->count; si++) {
        const lpv_splat_source *src = &jb->s->sources[si];
        if (src->cell[2] + REACH + LIFT_MAX < z0 || src->cell[2] - REACH - LIFT_MAX >= z1)
            continue;
        for (int ti = 0; ti < jb->tb->count; ti++) {
            const target *g = &jb->tb->targets[ti];
            int c3[3] = {src->cell[0] + g->t[0], src->cell[1] + g->t[1], src->cell[2] + g->t[2]};
            if (c3[0] < 0 || c3[1] < 0 || c3[2] < z0 - LIFT_MAX || c3[2] >= z1 + LIFT_MAX ||
                c3[2] < 0 || c3[0] >= n[0] || c3[1] >= n[1] || c3[2] >= n[2])
                continue;
            float r[3] = {c3[0] - src->origin[0], c3[1] - src->origin[1], c3[2] - src->origin[2]};
            float r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2], dist = sqrtf(r2);
            if (dist >= R + 1.0f || (dist < R && in_own_layer(src, r)))
                continue;
            /* Every hop of the walk must stay inside the lattice and unblocked. */
            int inside = 1;
            for (int i = 1; i < g->hops && inside; i++)
                for (int a = 0; a < 3; a++) {
                    int p = src->cell[a] + g->at[i][a];
                    inside &= p >= 0 && p < n[a];
                }
            if (!inside || !visible(jb->d->blockers, src->cell, g))
                continue;
            float w[3] = {0.0f, 0.0f, 0.0f};
            if (dist > 0.0f)
                for (int a = 0; a < 3; a++)
                    w[a] = r[a] / dist;
            float keep = jb->log_keep != 0.0f ? exp2f(jb->log_keep * dist) : 1.0f;
            float inv_r2 = 1.0f / (r2 > 0.25f ? r2 : 0.25f);
            float at[3] = {r[0], r[1], r[2]};
            if (dist >= R && shell_cell(src, jb->d->blockers, n, c3, at) != 0)
                continue;
            if (c3[2] < z0 || c3[2] >= z1)
                continue;
            size_t i = index_of(n, c3[0], c3[1], c3[2]);
            for (int c = 0; c < 3; c++) {
                if (!(src->energy[c] > 0.0f))
                    continue;
                const float *dir = src->dir[c];
                float wc[3] = {w[0], w[1], w[2]};
                if (dist <= 0.0f) /* origin at the centre: its own direction */
                    wc[0] = dir[0], wc[1] = dir[1], wc[2] = dir[2];
                float p = density(src, c, wc) * inv_r2 * keep;
                if (dist < R)
                    add_beam(jb->near, i, c, src->energy[c] * p, wc);
                else
                    add_beam(jb->shell, i, c, src->energy[c] * p * jb->norm[si][c], wc);
            }
        }
    }
    fpmode_leave(mode);
}

/* 1 / sum over the source's shell cells (all of them, blocked or not, inside the lattice
 * or not) of p / r^2: the shares are then the light's whole energy. */
static void shell_norm(const lpv_splat_source *src, const table *tb, float out[3])
{
    const float R = (float)LPV_SPLAT_RADIUS;
    double sum[3] = {0, 0, 0};
    for (int ti = 0; ti < tb->count; ti++) {
        const target *g = &tb->targets[ti];
        float r[3] = {src->cell[0] + g->t[0] - src->origin[0], src->cell[1] + g->t[1] - src->origin[1],
                      src->cell[2] + g->t[2] - src->origin[2]};
        float r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2], dist = sqrtf(r2);
        if (dist < R || dist >= R + 1.0f)
            continue;
        float w[3] = {r[0] / dist, r[1] / dist, r[2] / dist};
        for (int c = 0; c < 3; c++)
            sum[c] += density(src, c, w) / r2;
    }
    for (int c = 0; c < 3; c++)
        out[c] = sum[c] > 0.0 ? (float)(1.0 / sum[c]) : 0.0f;
}

int lpv_splat_run(lpv_splat *s, const lpv_splat_desc *d, lpv_volume *near, lpv_volume *shell)
{
    lpv_volume_clear(near);
    lpv_volume_clear(shell);
    const lpv_volume *in = d->injected;
    if (!in || in->channels != LPV_LIGHT_CHANNELS || memcmp(in->n, near->n, sizeof in->n) ||
        memcmp(in->n, shell->n, sizeof in->n))
        return 0;
    fpmode mode = fpmode_enter();
    s->count = 0;
    const int *n = in->n;
    for (int z = 0; z < n[2]; z++)
        for (int y = 0; y < n[1]; y++)
            for (int x = 0; x < n[0]; x++) {
                size_t i = index_of(n, x, y, z);
                if (!(in->ch[0][i] > 0.0f) && !(in->ch[4][i] > 0.0f) && !(in->ch[8][i] > 0.0f))
                    continue;
                if (s->count == s->capacity) {
                    size_t cap = s->capacity ? 2 * s->capacity : 256;
                    /* not xalloc: grows with the scene's and the RSM's lights: -1 to the caller */
                    lpv_splat_source *grown = realloc(s->sources, cap * sizeof *grown);
                    if (!grown) {
                        fpmode_leave(mode);
                        lpv_volume_clear(near);
                        return -1;
                    }
                    s->sources = grown;
                    s->capacity = cap;
                }
                lpv_splat_source *src = &s->sources[s->count++];
                src->cell[0] = x;
                src->cell[1] = y;
                src->cell[2] = z;
                const lpv_volume *o = d->origin;
                float w = o && o->channels == LPV_GEOMETRY_CHANNELS ? o->ch[3][i] : 0.0f;
                for (int a = 0; a < 3; a++)
                    src->origin[a] = w > 0.0f && isfinite(w) ? o->ch[a][i] / w : (float)src->cell[a];
                float f[3] = {0, 0, 0};
                for (int c = 0; c < 3; c++) {
                    float L[4] = {in->ch[4 * c][i], in->ch[4 * c + 1][i], in->ch[4 * c + 2][i],
                                  in->ch[4 * c + 3][i]};
                    closure(L, src, c);
                    f[0] -= L[3];
                    f[1] -= L[1];
                    f[2] += L[2];
                }
                float len = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
                for (int a = 0; a < 3; a++)
                    src->plane[a] = len > 0.0f && isfinite(len) ? f[a] / len : 0.0f;
            }
    table tb;
    build_table(&tb);
    /* not xalloc: one per light source of the scene; a failure is this call's -1 */
    float (*norm)[3] = s->count ? malloc(s->count * sizeof *norm) : NULL;
    if (s->count && !norm) {
        free(tb.targets);
        free(norm);
        fpmode_leave(mode);
        return -1;
    }
    for (size_t si = 0; si < s->count; si++)
        shell_norm(&s->sources[si], &tb, norm[si]);
    fpmode_leave(mode);
    /* As the shader's transmittance: at most 0.999999 absorbed per cell. */
    float a = d->absorption > 0.0f ? fminf(d->absorption, 0.999999f) : 0.0f;
    job jb = {s, &tb, d, near, shell, (const float (*)[3])norm, a > 0.0f ? log2f(1.0f - a) : 0.0f};
    workpool_run(d->pool, (n[2] + Z_TILE - 1) / Z_TILE, splat_tile, &jb);
    free(tb.targets);
    free(norm);
    return 0;
}

void lpv_splat_free(lpv_splat *s)
{
    free(s->sources);
    memset(s, 0, sizeof *s);
}
