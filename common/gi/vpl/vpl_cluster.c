#include "gi/vpl/vpl_cluster.h"

#include <float.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>

#include "base/vec3.h"
#include "base/xalloc.h"

float vpl_influence_radius(float area, float scene_area, float cut)
{
    if (!(cut > 0))
        return FLT_MAX;
    double r2 = ((double)scene_area / cut - area) / 3.14159265358979323846;
    return r2 > 0 ? (float)sqrt(r2) : 0.0f;
}

/* A view's eye axes (rows of the view matrix) and window (from the projection's
 * x = P00 tan - P02, y = P11 tan - P12 at ndc -1 and 1); near and far from its z row.
 * -1 for an orthographic projection. */
static int view_frustum(const frame_view *v, vpl_grid *g)
{
    const float *m = v->view, *p = v->projection;
    if (p[15] != 0.0f || p[11] == 0.0f)
        return -1;
    for (int k = 0; k < 3; k++) {
        g->right[k] = m[4 * k];
        g->up[k] = m[4 * k + 1];
        g->forward[k] = -m[4 * k + 2];
        g->apex[k] = v->eye_position[k];
    }
    g->window[0] = (-1.0f + p[8]) / p[0];
    g->window[2] = (1.0f + p[8]) / p[0];
    g->window[1] = (-1.0f + p[9]) / p[5];
    g->window[3] = (1.0f + p[9]) / p[5];
    g->near = p[14] / (p[10] - 1.0f);
    g->far = p[14] / (p[10] + 1.0f);
    return g->near > 0 && g->far > g->near ? 0 : -1;
}

/* Tiles of about VPL_CLUSTER_TILE_PX over the fraction of a view's pixels: a view's own
 * grid covers every pixel (rounded up), an enclosing grid keeps the nearest count. */
static int tiles_for(float pixels, float fraction, int round_up)
{
    float t = pixels * fraction / VPL_CLUSTER_TILE_PX;
    int k = round_up ? (int)ceilf(t) : (int)lroundf(t);
    return k < 1 ? 1 : k;
}

int vpl_grid_from_view(const frame_view *view, int slices, vpl_grid *out)
{
    if (view_frustum(view, out) != 0)
        return -1;
    out->tiles[0] = tiles_for((float)view->width, 1.0f, 1);
    out->tiles[1] = tiles_for((float)view->height, 1.0f, 1);
    out->slices = slices < 1 ? 1 : slices;
    return 0;
}

/* Point at depth d through window tangents (tx, ty) of frustum g. */
static void frustum_point(const vpl_grid *g, float d, float tx, float ty, float out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = g->apex[k] + d * (g->forward[k] + tx * g->right[k] + ty * g->up[k]);
}

/* Per image axis (x: right, y: up), in a's axes around the eyes' mean: the lowest and
 * highest corner offsets at the near and the far depth (the eyes share them along
 * forward). A boundary line through its near and far extremes holds every frustum
 * (their envelope is convex), so the apex goes where the two lines of an axis meet:
 * *b behind the mean; the axis that needs the larger b sets it. */
static void enclosing_apex(const vpl_grid *f, int n, const float mean[3], float *b, float centre[2])
{
    const vpl_grid *a = &f[0];
    *b = 0;
    centre[0] = centre[1] = 0;
    for (int axis = 0; axis < 2; axis++) {
        const float *dir = axis ? a->up : a->right;
        float lo[2] = {FLT_MAX, FLT_MAX}, hi[2] = {-FLT_MAX, -FLT_MAX}, depth[2] = {0, 0};
        for (int i = 0; i < n; i++)
            for (int z = 0; z < 2; z++) {
                float d = z ? f[i].far : f[i].near;
                depth[z] = d;
                for (int c = 0; c < 2; c++) {
                    float q[3], rel[3];
                    frustum_point(&f[i], d, f[i].window[2 * c], f[i].window[1 + 2 * c], q);
                    vec3_sub(q, mean, rel);
                    float x = vec3_dot(rel, dir);
                    lo[z] = fminf(lo[z], x);
                    hi[z] = fmaxf(hi[z], x);
                }
            }
        float span = depth[1] - depth[0];
        float slope_lo = (lo[1] - lo[0]) / span, slope_hi = (hi[1] - hi[0]) / span;
        if (slope_hi - slope_lo <= 0)
            continue;
        float zb = depth[0] - (hi[0] - lo[0]) / (slope_hi - slope_lo); /* where they meet */
        if (-zb > *b)
            *b = -zb;
        centre[axis] = lo[0] + slope_lo * (zb - depth[0]);
    }
}

/* The window and depths of every frustum's corners seen from out's apex; -1 when one lies
 * behind it. */
static int enclosing_window(const vpl_grid *f, int n, vpl_grid *out)
{
    float w[4] = {FLT_MAX, FLT_MAX, -FLT_MAX, -FLT_MAX}, dn = FLT_MAX, df = 0;
    for (int i = 0; i < n; i++)
        for (int c = 0; c < 8; c++) {
            float q[3], rel[3];
            frustum_point(&f[i], c & 4 ? f[i].far : f[i].near, f[i].window[c & 1 ? 2 : 0],
                          f[i].window[c & 2 ? 3 : 1], q);
            vec3_sub(q, out->apex, rel);
            float d = vec3_dot(rel, out->forward);
            if (!(d > 0))
                return -1;
            float tx = vec3_dot(rel, out->right) / d, ty = vec3_dot(rel, out->up) / d;
            w[0] = fminf(w[0], tx);
            w[1] = fminf(w[1], ty);
            w[2] = fmaxf(w[2], tx);
            w[3] = fmaxf(w[3], ty);
            dn = fminf(dn, d);
            df = fmaxf(df, d);
        }
    memcpy(out->window, w, sizeof w);
    out->near = dn;
    out->far = df;
    return 0;
}

int vpl_grid_enclosing(const frame_view *views, int n, int slices, vpl_grid *out)
{
    enum { MAX_VIEWS = 8 };
    vpl_grid f[MAX_VIEWS];
    if (n < 1 || n > MAX_VIEWS)
        return -1;
    float mean[3] = {0, 0, 0};
    for (int i = 0; i < n; i++) {
        if (view_frustum(&views[i], &f[i]) != 0 ||
            vec3_dot(f[i].forward, f[0].forward) < 0.9999f ||
            vec3_dot(f[i].right, f[0].right) < 0.9999f)
            return -1;
        for (int k = 0; k < 3; k++)
            mean[k] += f[i].apex[k] / (float)n;
    }
    const vpl_grid *a = &f[0];
    float b, centre[2];
    enclosing_apex(f, n, mean, &b, centre);
    memcpy(out->right, a->right, sizeof out->right);
    memcpy(out->up, a->up, sizeof out->up);
    memcpy(out->forward, a->forward, sizeof out->forward);
    for (int k = 0; k < 3; k++)
        out->apex[k] = mean[k] - b * a->forward[k] + centre[0] * a->right[k] +
                       centre[1] * a->up[k];
    if (enclosing_window(f, n, out) != 0)
        return -1;
    const float *w = out->window;
    /* Tiles at the first view's pixel density. */
    out->tiles[0] = tiles_for((float)views[0].width, (w[2] - w[0]) / (a->window[2] - a->window[0]), 0);
    out->tiles[1] = tiles_for((float)views[0].height, (w[3] - w[1]) / (a->window[3] - a->window[1]), 0);
    out->slices = slices < 1 ? 1 : slices;
    return 0;
}

int vpl_grid_clusters(const vpl_grid *g)
{
    return g->tiles[0] * g->tiles[1] * g->slices;
}

static int clamp_index(float t, int n)
{
    int i = (int)floorf(t * (float)n);
    return i < 0 ? 0 : (i >= n ? n - 1 : i);
}

int vpl_grid_cluster(const vpl_grid *g, const float p[3])
{
    float rel[3];
    vec3_sub(p, g->apex, rel);
    float d = vec3_dot(rel, g->forward);
    float tx = vec3_dot(rel, g->right) / d, ty = vec3_dot(rel, g->up) / d;
    int x = clamp_index((tx - g->window[0]) / (g->window[2] - g->window[0]), g->tiles[0]);
    int y = clamp_index((ty - g->window[1]) / (g->window[3] - g->window[1]), g->tiles[1]);
    int z = clamp_index(logf(d / g->near) / logf(g->far / g->near), g->slices);
    return (z * g->tiles[1] + y) * g->tiles[0] + x;
}

/* Cluster (x, y, z)'s eight corners. */
static void cluster_corners(const vpl_grid *g, int x, int y, int z, float out[8][3])
{
    float dx = (g->window[2] - g->window[0]) / (float)g->tiles[0];
    float dy = (g->window[3] - g->window[1]) / (float)g->tiles[1];
    float ratio = g->far / g->near;
    for (int c = 0; c < 8; c++) {
        float tx = g->window[0] + dx * (float)(x + (c & 1));
        float ty = g->window[1] + dy * (float)(y + ((c >> 1) & 1));
        float d = g->near * powf(ratio, (float)(z + ((c >> 2) & 1)) / (float)g->slices);
        frustum_point(g, d, tx, ty, out[c]);
    }
}

static void push(vpl_clusters *c, uint16_t i)
{
    if (c->assigned == c->capacity_index) {
        c->capacity_index = c->capacity_index ? 2 * c->capacity_index : 4096;
        c->index = xrealloc(c->index, c->capacity_index * sizeof *c->index);
    }
    c->index[c->assigned++] = i;
}

void vpl_clusters_assign(vpl_clusters *c, const vpl_grid *g, const vpl *v,
                         const float *radius, int n)
{
    size_t clusters = (size_t)vpl_grid_clusters(g);
    if (c->capacity_first < clusters + 1) {
        c->capacity_first = clusters + 1;
        c->first = xrealloc(c->first, c->capacity_first * sizeof *c->first);
    }
    c->assigned = 0;
    /* Rounding margin: the shader maps a receiver to its cluster in float. */
    float pad = 1e-4f * g->far;
    size_t k = 0;
    for (int z = 0; z < g->slices; z++)
        for (int y = 0; y < g->tiles[1]; y++)
            for (int x = 0; x < g->tiles[0]; x++, k++) {
                c->first[k] = (uint32_t)c->assigned;
                float corner[8][3], lo[3] = {FLT_MAX, FLT_MAX, FLT_MAX};
                float hi[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
                cluster_corners(g, x, y, z, corner);
                for (int q = 0; q < 8; q++)
                    for (int a = 0; a < 3; a++) {
                        lo[a] = fminf(lo[a], corner[q][a] - pad);
                        hi[a] = fmaxf(hi[a], corner[q][a] + pad);
                    }
                for (int i = 0; i < n; i++) {
                    const float *y0 = v[i].position, *nl = v[i].normal;
                    double d2 = 0;
                    for (int a = 0; a < 3; a++) {
                        float e = y0[a] < lo[a] ? lo[a] - y0[a] : (y0[a] > hi[a] ? y0[a] - hi[a] : 0);
                        d2 += (double)e * e;
                    }
                    if (d2 > (double)radius[i] * radius[i])
                        continue;
                    int ahead = 0;
                    for (int q = 0; q < 8 && !ahead; q++) {
                        float rel[3];
                        vec3_sub(corner[q], y0, rel);
                        ahead = vec3_dot(rel, nl) > -pad;
                    }
                    if (ahead)
                        push(c, (uint16_t)i);
                }
            }
    c->first[k] = (uint32_t)c->assigned;
}

void vpl_clusters_free(vpl_clusters *c)
{
    free(c->first);
    free(c->index);
    memset(c, 0, sizeof *c);
}
