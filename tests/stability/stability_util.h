/* Helpers shared by the stability tests (docs/stability.md): a GL renderer on any scene,
 * cameras with explicit clip planes, finiteness checks and lattice energies. */
#ifndef CAVELIGHT_STABILITY_UTIL_H
#define CAVELIGHT_STABILITY_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"
#include "frame/frame_params.h"
#include "gi/gi_settings.h"
#include "gi/ilpv/gi_ilpv.h"
#include "gl/glctx.h"
#include "gi/ilpv/ilpv.h"
#include "lpv_testutil.h"
#include "gi/ilpv/lattice.h"
#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_inject.h"
#include "gi/ilpv/lpv_volume.h"
#include "frame/offaxis.h"
#include "renderer.h"
#include "scene/scene.h"

/* The built-in scenes' white. */
#define STAB_WHITE_ALBEDO 0.75

/* Closed-form radiance of a white (STAB_WHITE_ALBEDO) Lambertian surface with normal n at point x
 * lit by spot l, unshadowed: albedo/pi I spot cos / r^2. */
static inline double stab_spot_radiance(const frame_light *l, const float x[3], const float n[3])
{
    double d[3], r2 = 0, axis = 0, cos_i = 0;
    for (int a = 0; a < 3; a++) {
        d[a] = l->position[a] - x[a];
        r2 += d[a] * d[a];
    }
    double r = sqrt(r2);
    for (int a = 0; a < 3; a++) {
        axis -= d[a] / r * l->direction[a];
        cos_i += d[a] / r * n[a];
    }
    double spot = (axis - cos(l->outer_angle)) / (cos(l->inner_angle) - cos(l->outer_angle));
    spot = spot < 0 ? 0 : spot > 1 ? 1 : spot;
    return STAB_WHITE_ALBEDO / 3.14159265358979323846 * l->intensity * spot * cos_i / r2;
}

typedef struct stab_gl {
    glctx *ctx;
    renderer *r;
    frame_params settings; /* the RSM size, lattice and LPV backend it was built for */
} stab_gl;

/* p with the renderer's RSM size, GI method and settings (stab_open_rsm()), so that a
 * frame does not ask for another. */
static inline void stab_settings(const stab_gl *g, frame_params *p)
{
    p->rsm_size = g->settings.rsm_size;
    p->gi = g->settings.gi;
    memcpy(p->gi_settings, g->settings.gi_settings, sizeof p->gi_settings);
}

/* A renderer on the CPU LPV backend for a finished scene the caller owns, with this RSM
 * size and lattice (0: the defaults). Frames given to it take stab_settings(). Returns 0
 * or prints why and returns -1. */
static inline int stab_open_rsm(stab_gl *g, const scene *s, int lattice_cells, int rsm_size)
{
    char err[512];
    memset(g, 0, sizeof *g);
    glctx_desc gd = {.backend = GLCTX_EGL};
    if (!(g->ctx = glctx_create(&gd, err, sizeof err))) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    frame_params_default(&g->settings);
    if (rsm_size > 0)
        g->settings.rsm_size = rsm_size;
    if (lattice_cells > 0)
        gi_set_number(&g->settings, "lattice", lattice_cells);
    gi_set(&g->settings, "lpv", "cpu");
    renderer_desc rd = {.gl = glctx_gl(g->ctx), .scene = s, .first = &g->settings, .threads = 2};
    if (!(g->r = renderer_create(&rd, err, sizeof err))) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    return 0;
}

/* A frame pass of p with the renderer's settings. */
static inline uint64_t stab_frame_pass(stab_gl *g, const frame_params *p)
{
    frame_params f = *p;
    stab_settings(g, &f);
    return renderer_frame_pass(g->r, &f);
}

/* The same with a small RSM (64) for llvmpipe. */
static inline int stab_open(stab_gl *g, const scene *s, int lattice_cells)
{
    return stab_open_rsm(g, s, lattice_cells, 64);
}

static inline void stab_close(stab_gl *g)
{
    renderer_destroy(g->r);
    glctx_destroy(g->ctx);
}

static inline void stab_view(renderer_view *v, const float pos[3], const float target[3],
                             float yfov, int w, int h, float near_plane, float far_plane)
{
    v->width = w;
    v->height = h;
    memcpy(v->eye_position, pos, 3 * sizeof(float));
    offaxis_look_at(pos, target, yfov, (float)w / (float)h, near_plane, far_plane, v->view,
                    v->projection);
}

/* Non-finite values among n floats. */
static inline size_t stab_count_nonfinite(const float *x, size_t n)
{
    size_t bad = 0;
    for (size_t i = 0; i < n; i++)
        bad += !isfinite(x[i]);
    return bad;
}

/* Non-finite values in the three linear images of an eye pass (want_linear). */
static inline size_t stab_image_nonfinite(const renderer_image *img)
{
    size_t n = (size_t)img->width * img->height * 3;
    return stab_count_nonfinite(img->final, n) + stab_count_nonfinite(img->direct, n) +
           stab_count_nonfinite(img->indirect, n);
}

/* <L|1> summed over cells and colours. */
static inline double stab_energy(const lpv_volume *v)
{
    double e[3];
    lpv_volume_energy(v, e);
    return e[0] + e[1] + e[2];
}

/* Mean over colours of what a spot emits into its cone (the renderer's own estimate,
 * node/gi_ilpv.c): I * mean(colour) * 2 pi (1 - cos outer). */
static inline double stab_spot_energy(const frame_light *l)
{
    double outer = fmin(fmax(l->outer_angle, 0.01), 1.45);
    return l->intensity * (l->color[0] + l->color[1] + l->color[2]) / 3.0 * 2.0 *
           3.14159265358979323846 * (1.0 - cos(outer));
}

/* The mean chord of the scene's bounds, 4 V / A (A: the scene's surface area), in cells:
 * about how many steps light lives in a closed room before a wall takes it. */
static inline double stab_mean_chord_cells(const scene *s, float cell)
{
    double volume = 1.0, area = 0.0;
    for (int a = 0; a < 3; a++)
        volume *= (double)s->bounds_max[a] - s->bounds_min[a];
    for (size_t t = 0; t < s->triangle_count; t++)
        area += vec3_triangle_area(s->positions + 9 * t);
    return area > 0.0 ? 4.0 * volume / area / cell : 0.0;
}

/* Mean of a linear RGB image (all pixels, all colours). */
static inline double stab_mean(const float *img, int w, int h)
{
    double s = 0;
    size_t n = (size_t)w * h * 3;
    for (size_t i = 0; i < n; i++)
        s += img[i];
    return s / (double)n;
}

/* VPLs where a spot lights the floor y = 0 over [x0,x1] x [z0,z1], a grid x grid
 * raster (no shadows): flux = albedo E dA / pi, as the renderer passes it. Returns the
 * count written to out (at most grid^2). */
static inline size_t stab_floor_vpls(const scene_light *l, float x0, float x1, float z0,
                                     float z1, int grid, float albedo, lpv_vpl *out)
{
    size_t n = 0;
    float dx = (x1 - x0) / grid, dz = (z1 - z0) / grid;
    float cos_outer = cosf(l->outer_angle), cos_inner = cosf(l->inner_angle);
    for (int i = 0; i < grid; i++)
        for (int k = 0; k < grid; k++) {
            float p[3] = {x0 + (i + 0.5f) * dx, 0.0f, z0 + (k + 0.5f) * dz};
            float d[3], r2 = 0;
            for (int a = 0; a < 3; a++) {
                d[a] = p[a] - l->position[a];
                r2 += d[a] * d[a];
            }
            float r = sqrtf(r2), axis = 0;
            for (int a = 0; a < 3; a++)
                axis += d[a] / r * l->direction[a];
            float spot = (axis - cos_outer) / (cos_inner - cos_outer);
            spot = spot < 0 ? 0 : spot > 1 ? 1 : spot;
            float irradiance = l->intensity * spot * (-d[1] / r) / r2;
            if (!(irradiance > 0))
                continue;
            lpv_vpl *v = &out[n++];
            memset(v, 0, sizeof *v);
            memcpy(v->position, p, sizeof p);
            v->normal[1] = 1.0f;
            for (int a = 0; a < 3; a++)
                v->flux[a] = albedo * l->color[a] * irradiance * dx * dz / 3.14159265f;
        }
    return n;
}

/* The CPU ILPV core on the default room: a lattice of `cells` along the longest axis, the
 * room's blocking lattice, and VPLs where the room's spot lights the floor (a 5 cm grid,
 * albedo 0.75, flux = albedo E dA / pi as the renderer passes it). */
typedef struct stab_cpu {
    scene scene;
    lattice_desc lattice;
    lpv_blockers blockers;
    lpv_vpl *vpls;
    size_t vpl_count;
    ilpv ilpv;
} stab_cpu;

static inline int stab_cpu_open(stab_cpu *c, int cells)
{
    char err[256];
    memset(c, 0, sizeof *c);
    if (scene_load("default", &c->scene, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    const scene *s = &c->scene;
    lattice_fit_desc fit = {.max_axis_cells = cells, .margin_cells = -1.0f};
    memcpy(fit.bounds_min, s->bounds_min, sizeof fit.bounds_min);
    memcpy(fit.bounds_max, s->bounds_max, sizeof fit.bounds_max);
    if (lattice_fit(&fit, &c->lattice, err, sizeof err) != 0 ||
        lpv_blockers_init(&c->blockers, c->lattice.n) != 0 ||
        ilpv_init(&c->ilpv, &(ilpv_desc){.lattice = &c->lattice, .blockers = &c->blockers}) != 0)
        return -1;
    lpv_geometry_add_triangles(&c->blockers, &c->lattice, s->positions, 3 * s->triangle_count,
                               NULL, s->triangle_count, NULL);
    const int grid = 80;
    c->vpls = calloc((size_t)grid * grid, sizeof *c->vpls);
    if (!c->vpls)
        return -1;
    c->vpl_count = stab_floor_vpls(&s->lights[0], -2.0f, 2.0f, -2.0f, 2.0f, grid, 0.75f, c->vpls);
    return 0;
}

static inline void stab_cpu_close(stab_cpu *c)
{
    ilpv_free(&c->ilpv);
    lpv_blockers_free(&c->blockers);
    free(c->vpls);
    scene_free(&c->scene);
}

/* One frame: inject the VPLs, splat, merge, propagate `steps` steps with blocking. */
static inline void stab_cpu_frame(stab_cpu *c, float lambda, int steps, double emitted)
{
    ilpv_begin_frame(&c->ilpv);
    lpv_inject_vpls(ilpv_injection(&c->ilpv), ilpv_origin(&c->ilpv), &c->lattice, c->vpls,
                    c->vpl_count, NULL);
    ilpv_frame_desc fd = {.steps = steps, .lambda_incr = lambda, .emitted_energy = emitted};
    ilpv_frame(&c->ilpv, &fd);
}

#endif
