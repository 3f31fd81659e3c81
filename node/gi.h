/* gi: the node's indirect-light (GI) methods behind one small interface.
 *
 * The renderer calls the active method at two places of a frame:
 *   frame pass (once per frame, view independent): reuse() before the reflective shadow
 *     maps are rendered (1: last frame's result stands, no RSMs and no frame()), then
 *     frame() with this frame's RSMs; frame() returns the checksum READY carries, so
 *     desync detection covers whatever the method computes;
 *   eye pass (per screen and eye): eye_bind() with the shading program bound, to set the
 *     method's uniforms and textures. shaders/shade.frag adds the indirect light through
 *     its LPV lookup (u_lpv_enabled, the samplers u_lpv_r/g/b, ...) or its VPL gather
 *     (u_vpl_count, u_vpls, u_vpl_shadow, ...); gi_eye_bind() turns both off and gives
 *     every method's samplers their own units (GI_UNIT_*) before the method's eye_bind()
 *     turns its own on: a sampler left on unit 0 beside the G-buffer's textures of
 *     another type makes the draw a GL error.
 * stats() reports its stage timings for the frame report.
 *
 * Methods, indexed by frame_gi: ilpv (gi_ilpv.c), none (gi_none.c: direct light only) and
 * vpl (gi_vpl.c: virtual point lights with shadow maps).
 * A method is one module that defines a const gi_method; gi.c's table lists them. To add
 * one: a gi_X.c, its name in frame_gi (common/frame/frame_params.h) and one line in the
 * table.
 * Every method must give every node the same result for the same frames_params. */
#ifndef CAVELIGHT_GI_H
#define CAVELIGHT_GI_H

#include <stddef.h>
#include <stdint.h>

#include "frame/frame_params.h"
#include "gl_functions.h"
#include "renderer_desc.h"
#include "scene/scene.h"

typedef struct gi_desc {
    const gl_functions *gl;
    const scene *scene;
    const renderer_desc *settings; /* the renderer's desc: lattice, backend, threads, ... */
    int rsm_size;                  /* texels per side of each RSM */
    int software;                  /* a software GL (llvmpipe): GL compute is slow there */
} gi_desc;

/* This frame's reflective shadow maps, as the renderer rendered them. */
typedef struct gi_rsm {
    int size;                      /* texels per side */
    int layers;                    /* lights rendered, one layer each */
    const GLuint *fbo;             /* per layer: position, normal, flux in attachments 0..2 */
} gi_rsm;

/* Texture units of the shading program's GI samplers, from gi_eye.first_unit on
 * (first_unit + 3 is the renderer's). */
enum {
    GI_UNIT_LPV = 0,        /* u_lpv_r, u_lpv_g, u_lpv_b: three units */
    GI_UNIT_VPL_DATA = 4,   /* u_vpls */
    GI_UNIT_VPL_SHADOW = 5, /* u_vpl_shadow */
};

typedef struct gi_eye {
    GLuint program;                /* the bound shading program */
    int first_unit;                /* texture units from this one on are the method's */
} gi_eye;

typedef struct gi_stats {
    double inject_ms, propagate_ms; /* the frame's two stages: making the light sources,
                                       spreading them (0 when reused) */
    int lattice_cells;             /* cells along the longest axis (the HUD's P bar); 0: none */
} gi_stats;

typedef struct gi_method {
    const char *name;
    /* Returns the method's state, or NULL with one line in err. */
    void *(*create)(const gi_desc *desc, char *err, size_t errlen);
    void (*destroy)(void *state);
    int (*reuse)(void *state, const frame_params *p);
    uint64_t (*frame)(void *state, const frame_params *p, const gi_rsm *rsm);
    void (*eye_bind)(void *state, const gi_eye *eye);
    void (*stats)(const void *state, gi_stats *out);
} gi_method;

typedef struct gi gi;

gi *gi_create(frame_gi method, const gi_desc *desc, char *err, size_t errlen);
void gi_destroy(gi *g);
frame_gi gi_active(const gi *g);
int gi_reuse(gi *g, const frame_params *p);
uint64_t gi_frame(gi *g, const frame_params *p, const gi_rsm *rsm);
void gi_eye_bind(gi *g, const gi_eye *eye);
void gi_stats_get(const gi *g, gi_stats *out);
/* The method's own state, for its inspection functions (gi_ilpv.h). */
void *gi_state(const gi *g);

#endif
