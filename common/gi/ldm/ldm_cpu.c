/* ldm_cpu: see ldm_cpu.h. */
#include "gi/ldm/ldm_cpu.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static uint32_t float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static float bits_float(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* The GL build's insertion: an atomic minimum down the list, carrying the larger value. */
static int insert(uint32_t *list, int layers, uint32_t z)
{
    for (int i = 0; i < layers && z != LDM_EMPTY; i++) {
        uint32_t old = list[i];
        list[i] = old < z ? old : z;
        z = old > z ? old : z;
    }
    return z != LDM_EMPTY;
}

/* Whether a texel centre with barycentric weights w covers the triangle: inside, or on an
 * edge that the GL's fill rule gives it (a top or left edge, counter-clockwise with y up),
 * so that a centre on an edge two triangles share belongs to one of them, as on the GPU. */
static int covers(const double w[3], const double x[3], const double y[3], double area)
{
    for (int e = 0; e < 3; e++) {
        if (w[e] > 0)
            continue;
        if (w[e] < 0)
            return 0;
        int a = (e + 1) % 3, b = (e + 2) % 3;
        double dx = (x[b] - x[a]) * (area > 0 ? 1 : -1), dy = (y[b] - y[a]) * (area > 0 ? 1 : -1);
        int top = dy == 0 && dx < 0, left = dy < 0;
        if (!top && !left)
            return 0;
    }
    return 1;
}

/* One triangle (texel coordinates and depths of its corners) into map m. */
static void raster(ldm_cpu *c, int m, const double x[3], const double y[3], const float t[3])
{
    int res = c->layout.resolution, layers = c->layout.layers;
    double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    if (area == 0.0)
        return;
    double lo[2] = {fmin(x[0], fmin(x[1], x[2])), fmin(y[0], fmin(y[1], y[2]))};
    double hi[2] = {fmax(x[0], fmax(x[1], x[2])), fmax(y[0], fmax(y[1], y[2]))};
    int x0 = (int)fmax(floor(lo[0] - 0.5), 0), x1 = (int)fmin(ceil(hi[0] - 0.5), res - 1);
    int y0 = (int)fmax(floor(lo[1] - 0.5), 0), y1 = (int)fmin(ceil(hi[1] - 0.5), res - 1);
    for (int py = y0; py <= y1; py++)
        for (int px = x0; px <= x1; px++) {
            double cx = px + 0.5, cy = py + 0.5, w[3];
            for (int e = 0; e < 3; e++) { /* barycentric weight of corner e */
                int a = (e + 1) % 3, b = (e + 2) % 3;
                w[e] = ((x[b] - x[a]) * (cy - y[a]) - (cx - x[a]) * (y[b] - y[a])) / area;
            }
            if (!covers(w, x, y, area))
                continue;
            float depth = (float)(w[0] * t[0] + w[1] * t[1] + w[2] * t[2]);
            uint32_t *list = c->depth + (((size_t)m * res + py) * res + px) * layers;
            c->overflow += (size_t)insert(list, layers, float_bits(fmaxf(depth, 0.0f)));
        }
}

int ldm_cpu_build(const scene *s, const ldm_layout *l, ldm_cpu *out)
{
    memset(out, 0, sizeof *out);
    out->layout = *l;
    size_t entries = (size_t)l->directions * l->resolution * l->resolution * l->layers;
    /* not xalloc: the size the ldm settings ask for: -1 lets the caller name them */
    out->maps = malloc((size_t)l->directions * sizeof *out->maps);
    out->depth = malloc(entries * sizeof *out->depth);
    if (!out->maps || !out->depth) {
        ldm_cpu_free(out);
        return -1;
    }
    memset(out->depth, 0xff, entries * sizeof *out->depth);
    ldm_layout_maps(l, out->maps);
    for (int m = 0; m < l->directions; m++)
        for (size_t tri = 0; tri < s->triangle_count; tri++) {
            double x[3], y[3];
            float t[3];
            for (int k = 0; k < 3; k++) {
                float fx, fy;
                ldm_project(l, &out->maps[m], s->positions + 9 * tri + 3 * k, &fx, &fy, &t[k]);
                x[k] = fx;
                y[k] = fy;
            }
            raster(out, m, x, y, t);
        }
    return 0;
}

void ldm_cpu_free(ldm_cpu *c)
{
    free(c->maps);
    free(c->depth);
    memset(c, 0, sizeof *c);
}

const uint32_t *ldm_cpu_texel(const ldm_cpu *c, int m, int x, int y)
{
    int res = c->layout.resolution;
    return c->depth + (((size_t)m * res + y) * res + x) * c->layout.layers;
}

float ldm_list_trace(const uint32_t *list, int layers, float t, int sign, float skip)
{
    float best = -1.0f;
    for (int i = 0; i < layers && list[i] != LDM_EMPTY; i++) {
        float along = (bits_float(list[i]) - t) * (float)sign;
        if (along > skip && (best < 0 || along < best))
            best = along;
        if (sign > 0 && along > skip)
            break; /* sorted: the first one beyond is the nearest */
    }
    return best;
}

float ldm_cpu_trace(const ldm_cpu *c, int m, int sign, const float p[3], float skip,
                    float max_distance)
{
    float x, y, t;
    ldm_project(&c->layout, &c->maps[m], p, &x, &y, &t);
    int res = c->layout.resolution;
    if (!(x >= 0 && y >= 0 && x < res && y < res))
        return -1.0f;
    float d = ldm_list_trace(ldm_cpu_texel(c, m, (int)x, (int)y), c->layout.layers, t, sign, skip);
    return max_distance > 0 && d > max_distance ? -1.0f : d;
}
