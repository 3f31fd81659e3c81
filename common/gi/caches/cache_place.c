#include "gi/caches/cache_place.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"

/* Points per cube face area: (e / POINT_STEPS)^2 each. At most MAX_POINTS in all (a fine
 * density on a large scene): beyond, the points are spread thinner. A scene whose triangles
 * alone need more than CACHE_MAX_POINTS (one point each at least) is refused. */
enum { POINT_STEPS = 3, MAX_POINTS = 1 << 22, POINT_FLOATS = CACHE_POINT_FLOATS };
/* A cube's best normal is sought among at most this many of its points' normals. */
enum { MAX_CANDIDATES = 64 };
/* Points farther than this many edges off a candidate's plane make a cache of their own. */
#define PLANE_TOL 0.25f

double cache_scene_area(const scene *s)
{
    double a = 0;
    for (size_t t = 0; t < s->triangle_count; t++)
        a += vec3_triangle_area(s->positions + 9 * t);
    return a;
}

float cache_place_edge(const scene *s, float density)
{
    if (!(density > 0)) {
        double area = cache_scene_area(s);
        density = area > 0 ? (float)(CACHE_AUTO_COUNT / area) : 1.0f;
    }
    return 1.0f / sqrtf(density);
}

/* Points of triangle t: one per step^2 of its area, and at least one per step of its
 * longest edge (a sliver needs points along its length), at least 1. */
static size_t points_of(const scene *s, size_t t, float step)
{
    const float *p = s->positions + 9 * t;
    float a = vec3_triangle_area(p);
    if (!(a > 0))
        return 0;
    float longest = 0;
    for (int e = 0; e < 3; e++) {
        float d[3];
        vec3_sub(p + 3 * e, p + 3 * ((e + 1) % 3), d);
        longest = fmaxf(longest, vec3_length(d));
    }
    double k = fmax(ceil((double)a / ((double)step * step)), ceil((double)longest / step));
    if (!(k <= CACHE_MAX_POINTS)) /* saturated: the sums below never wrap */
        return (size_t)CACHE_MAX_POINTS + 1;
    return k < 1 ? 1 : (size_t)k;
}

/* The step between points for edge e: e / POINT_STEPS, or wider to stay within
 * MAX_POINTS. */
static float point_step(const scene *s, float edge)
{
    float step = edge / POINT_STEPS;
    for (int tries = 0; tries < 96; tries++) { /* 1.5^96: any extent within SCENE_MAX_COORD */
        size_t n = 0;
        for (size_t t = 0; t < s->triangle_count && n <= MAX_POINTS; t++)
            n += points_of(s, t, step);
        if (n <= MAX_POINTS)
            break;
        step *= 1.5f;
    }
    return step;
}

size_t cache_surface_points(const scene *s, float edge, float *out)
{
    /* R2, the plastic number's low-discrepancy sequence (Roberts 2018), folded into the
     * triangle: even coverage whatever the count. */
    const double a1 = 0.7548776662466927, a2 = 0.5698402909980532;
    float step = point_step(s, edge);
    size_t n = 0;
    for (size_t t = 0; t < s->triangle_count; t++) {
        size_t k = points_of(s, t, step);
        if (!out) {
            n += k;
            continue;
        }
        const float *p = s->positions + 9 * t, *vn = s->normals + 9 * t;
        float share = vec3_triangle_area(p) / (float)k;
        float roughness = s->materials[s->triangle_material[t]].roughness;
        for (size_t j = 0; j < k; j++, n++) {
            double u = fmod(0.5 + a1 * (double)j, 1.0), v = fmod(0.5 + a2 * (double)j, 1.0);
            if (k == 1)
                u = v = 1.0 / 3.0; /* the centroid */
            else if (u + v > 1)
                u = 1 - u, v = 1 - v;
            float w[3] = {(float)(1 - u - v), (float)u, (float)v};
            float *o = out + POINT_FLOATS * n;
            for (int c = 0; c < 3; c++) {
                o[c] = w[0] * p[c] + w[1] * p[3 + c] + w[2] * p[6 + c];
                o[3 + c] = w[0] * vn[c] + w[1] * vn[3 + c] + w[2] * vn[6 + c];
            }
            if (vec3_normalize(o + 3) == 0) /* opposite vertex normals: the face's */
                vec3_triangle_normal(p, o + 3), vec3_normalize(o + 3);
            o[6] = share;
            o[7] = roughness;
        }
    }
    return n;
}

typedef struct keyed {
    uint64_t cube;
    size_t point;
} keyed;

static int by_cube(const void *a, const void *b)
{
    const keyed *x = a, *y = b;
    if (x->cube != y->cube)
        return x->cube < y->cube ? -1 : 1;
    return (x->point > y->point) - (x->point < y->point);
}

/* The cube of point p: the grid starts half an edge below the bounds. */
static uint64_t cube_of(const scene *s, float edge, const int dims[3], const float *p)
{
    uint64_t key = 0;
    for (int a = 2; a >= 0; a--) {
        float f = floorf((p[a] - (s->bounds_min[a] - 0.5f * edge)) / edge);
        int64_t i = f < 0 ? 0 : (f >= (float)dims[a] ? dims[a] - 1 : (int64_t)f);
        key = key * (uint64_t)dims[a] + (uint64_t)i;
    }
    return key;
}

/* Point q joins a cache around candidate point c: normals within the angle tolerance, and q
 * within plane_tol of c's plane (two parallel surfaces in one cube make two caches). */
static int joins(const float *c, const float *q, float cos_eps, float plane_tol)
{
    float d[3];
    vec3_sub(q, c, d);
    return vec3_dot(c + 3, q + 3) >= cos_eps && fabsf(vec3_dot(c + 3, d)) <= plane_tol;
}

/* One cache from the points of a cube still left (left[i]) that join the candidate
 * gathering the most area; they are taken (left[i] = 0). Returns 0 when none is left. */
static int take_cache(const float *pts, const keyed *cube, size_t n, unsigned char *left,
                      float cos_eps, float plane_tol, light_cache *out)
{
    size_t remaining = 0;
    for (size_t i = 0; i < n; i++)
        remaining += left[i];
    if (remaining == 0)
        return 0;
    size_t stride = (remaining + MAX_CANDIDATES - 1) / MAX_CANDIDATES, best = n, seen = 0;
    double best_area = -1;
    for (size_t c = 0; c < n; c++) {
        if (!left[c] || seen++ % stride)
            continue;
        const float *pc = pts + POINT_FLOATS * cube[c].point;
        double area = 0;
        for (size_t i = 0; i < n; i++) {
            const float *q = pts + POINT_FLOATS * cube[i].point;
            if (left[i] && joins(pc, q, cos_eps, plane_tol))
                area += q[6];
        }
        if (area > best_area)
            best_area = area, best = c;
    }
    float centre[POINT_FLOATS];
    memcpy(centre, pts + POINT_FLOATS * cube[best].point, sizeof centre);
    double pos[3] = {0, 0, 0}, nrm[3] = {0, 0, 0}, area = 0, rough = 0;
    for (size_t i = 0; i < n; i++) {
        const float *q = pts + POINT_FLOATS * cube[i].point;
        if (!left[i] || !joins(centre, q, cos_eps, plane_tol))
            continue;
        left[i] = 0;
        for (int k = 0; k < 3; k++) {
            pos[k] += (double)q[6] * q[k];
            nrm[k] += (double)q[6] * q[3 + k];
        }
        area += q[6];
        rough += (double)q[6] * q[7];
    }
    for (int k = 0; k < 3; k++) {
        out->position[k] = (float)(pos[k] / area);
        out->normal[k] = (float)nrm[k];
    }
    if (vec3_normalize(out->normal) == 0)
        memcpy(out->normal, centre + 3, 3 * sizeof *centre);
    out->area = (float)area;
    out->roughness = (float)(rough / area);
    return 1;
}

/* Step 4: the cache onto the plane of its nearest point among the cube's (pts of cube). */
static void snap(const float *pts, const keyed *cube, size_t n, light_cache *c)
{
    float best = INFINITY;
    const float *near = NULL;
    for (size_t i = 0; i < n; i++) {
        const float *q = pts + POINT_FLOATS * cube[i].point;
        float d[3];
        vec3_sub(c->position, q, d);
        float d2 = vec3_dot(d, d);
        if (d2 < best && vec3_dot(c->normal, q + 3) > 0)
            best = d2, near = q;
    }
    if (!near)
        return;
    float d[3];
    vec3_sub(c->position, near, d);
    float off = vec3_dot(d, near + 3);
    for (int k = 0; k < 3; k++)
        c->position[k] -= off * near[k + 3];
}

int cache_place(const scene *s, const cache_place_desc *d, cache_set *out, char *err,
                size_t errlen)
{
    memset(out, 0, sizeof *out);
    out->edge = d->edge;
    out->angle = d->angle;
    size_t n = cache_surface_points(s, d->edge, NULL);
    if (n == 0) {
        snprintf(err, errlen, "light caches: the scene has no surface to place them on");
        return -1;
    }
    if (n > CACHE_MAX_POINTS) {
        snprintf(err, errlen, "light caches: %zu triangles need %zu surface points, over the "
                 "limit of %d (a smaller scene or another GI method)", s->triangle_count, n,
                 CACHE_MAX_POINTS);
        return -1;
    }
    /* not xalloc: the scene's surface points (a density setting): refused in err */
    float *pts = malloc(n * POINT_FLOATS * sizeof *pts);
    keyed *order = malloc(n * sizeof *order);
    unsigned char *left = malloc(n);
    /* at most one cache per point */
    out->caches = malloc(n * sizeof *out->caches);
    if (!pts || !order || !left || !out->caches) {
        free(pts), free(order), free(left), cache_set_free(out);
        snprintf(err, errlen, "light caches: out of memory for %zu surface points", n);
        return -1;
    }
    cache_surface_points(s, d->edge, pts);
    int dims[3];
    for (int a = 0; a < 3; a++) {
        double cells = floor((s->bounds_max[a] - s->bounds_min[a]) / d->edge + 0.5) + 1;
        dims[a] = cells > 1 << 20 ? 1 << 20 : (int)cells;
    }
    for (size_t i = 0; i < n; i++)
        order[i] = (keyed){cube_of(s, d->edge, dims, pts + POINT_FLOATS * i), i};
    qsort(order, n, sizeof *order, by_cube);
    float cos_eps = cosf(d->angle);
    memset(left, 1, n);
    for (size_t a = 0, b; a < n; a = b) {
        for (b = a + 1; b < n && order[b].cube == order[a].cube; b++)
            ;
        light_cache *c = &out->caches[out->count];
        while (take_cache(pts, order + a, b - a, left + a, cos_eps, PLANE_TOL * d->edge, c)) {
            snap(pts, order + a, b - a, c);
            c = &out->caches[++out->count];
        }
    }
    free(pts);
    free(order);
    free(left);
    /* not xalloc: it only shrinks; a failure keeps the larger block */
    light_cache *fit = realloc(out->caches, out->count * sizeof *fit);
    if (fit)
        out->caches = fit;
    return 0;
}

void cache_set_free(cache_set *set)
{
    free(set->caches);
    set->caches = NULL;
    set->count = 0;
}
