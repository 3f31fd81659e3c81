/* Helpers shared by the GL tests: a context, the default room, a renderer, images. */
#ifndef CAVELIGHT_GL_TESTUTIL_H
#define CAVELIGHT_GL_TESTUTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "frame/frame_params.h"
#include "gi/gi_settings.h"
#include "gi/ilpv/gi_ilpv.h"
#include "gi/vpl/vpl_settings.h"
#include "gl/glctx.h"
#include "frame/offaxis.h"
#include "renderer.h"
#include "scene/scene.h"
#include "scene_testutil.h"

typedef struct gltest {
    glctx *ctx;
    scene scene;
    renderer *r;
    frame_params params; /* the frame the renderer is built for: tests render copies */
} gltest;

/* A setting of p by its option name (gi_settings.h), which a test knows to be valid. */
static inline void gltest_set(frame_params *p, const char *name, const char *value)
{
    const char *why = gi_set(p, name, value);
    if (why) {
        fprintf(stderr, "test: --%s %s: %s\n", name, value, why);
        abort();
    }
}

static inline void gltest_setn(frame_params *p, const char *name, double value)
{
    char text[32];
    snprintf(text, sizeof text, "%.9g", value);
    gltest_set(p, name, text);
}

/* A choice setting (an ILPV backend, a vpl visibility, ...) by its index. */
static inline void gltest_seti(frame_params *p, const char *name, int index)
{
    gi_option_put(gi_option_find(name), (setting_value){.i = index}, p);
}

/* The default room's frame with small sizes (llvmpipe is slow): a 64 RSM, a 20-cell
 * lattice on the given LPV backend and tiles. Returns 0 or prints why and returns -1. */
static inline int gltest_open_transport(gltest *t, glctx_backend backend, ilpv_backend_choice lpv,
                                        int threads, ilpv_tiles tiles, lpv_transport transport)
{
    char err[512];
    memset(t, 0, sizeof *t);
    glctx_desc gd = {.backend = backend};
    if (!(t->ctx = glctx_create(&gd, err, sizeof err)) ||
        scene_load("default", &t->scene, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    frame_params_default(&t->params);
    frame_params_lights_from_scene(&t->params, &t->scene);
    gltest_setn(&t->params, "rsm", 64);
    gltest_setn(&t->params, "lattice", 20);
    gltest_seti(&t->params, "lpv", lpv);
    gltest_seti(&t->params, "gl-tiles", tiles);
    gltest_seti(&t->params, "lpv-transport", transport);
    renderer_desc rd = {.gl = glctx_gl(t->ctx), .scene = &t->scene, .first = &t->params,
                        .threads = threads};
    if (!(t->r = renderer_create(&rd, err, sizeof err))) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    return 0;
}

static inline int gltest_open_tiles(gltest *t, glctx_backend backend, ilpv_backend_choice lpv,
                                    int threads, ilpv_tiles tiles)
{
    return gltest_open_transport(t, backend, lpv, threads, tiles, LPV_TRANSPORT_BEAMS);
}

static inline int gltest_open(gltest *t, glctx_backend backend, ilpv_backend_choice lpv,
                              int threads)
{
    return gltest_open_tiles(t, backend, lpv, threads, ILPV_TILES_AUTO);
}

static inline void gltest_close(gltest *t)
{
    renderer_destroy(t->r);
    glctx_destroy(t->ctx);
    scene_free(&t->scene);
}

static inline void gltest_look_at(renderer_view *v, const float pos[3], const float target[3],
                                  float yfov, int w, int h)
{
    v->width = w;
    v->height = h;
    memcpy(v->eye_position, pos, 3 * sizeof(float));
    offaxis_look_at(pos, target, yfov, (float)w / (float)h, 0.05f, 50.0f, v->view, v->projection);
}

/* World point -> pixel (x right, y down, top row 0). */
static inline void gltest_project(const renderer_view *v, const float p[3], float px[2])
{
    float e[4], c[4];
    for (int r = 0; r < 4; r++)
        e[r] = v->view[r] * p[0] + v->view[4 + r] * p[1] + v->view[8 + r] * p[2] + v->view[12 + r];
    for (int r = 0; r < 4; r++)
        c[r] = v->projection[r] * e[0] + v->projection[4 + r] * e[1] +
               v->projection[8 + r] * e[2] + v->projection[12 + r] * e[3];
    px[0] = (c[0] / c[3] * 0.5f + 0.5f) * v->width;
    px[1] = (0.5f - c[1] / c[3] * 0.5f) * v->height;
}

/* Mean of a linear image over a square window around a pixel. */
static inline void gltest_window_mean(const float *img, int w, int h, int cx, int cy, int half,
                                      double out[3])
{
    out[0] = out[1] = out[2] = 0;
    int n = 0;
    for (int y = cy - half; y <= cy + half; y++)
        for (int x = cx - half; x <= cx + half; x++) {
            if (x < 0 || y < 0 || x >= w || y >= h)
                continue;
            for (int c = 0; c < 3; c++)
                out[c] += img[((size_t)y * w + x) * 3 + c];
            n++;
        }
    for (int c = 0; c < 3; c++)
        out[c] /= n > 0 ? n : 1;
}

/* testutil_ray_cast() in floats: INFINITY when no triangle is met. */
static inline float gltest_cast(const scene *s, const float o[3], const float d[3])
{
    double od[3] = {o[0], o[1], o[2]}, dd[3] = {d[0], d[1], d[2]};
    return (float)testutil_ray_cast(s, od, dd);
}

#endif
