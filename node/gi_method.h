/* gi_method: what one indirect-light (GI) method implements, and what it is given (gi.h
 * says when the renderer calls it). A method is one module (gi_ilpv.c, gi_none.c, gi_vpl.c) that
 * defines a const gi_method; gi.c's table lists them. Types for methods; the renderer
 * goes through gi.h.
 *
 *   create()    state from the scene and the renderer's settings; NULL with one line in err
 *   reuse()     frame pass, before the RSMs: 1 when last frame's result stands (nothing is
 *               rendered, frame() is not called)
 *   frame()     frame pass, once per frame, view independent, with this frame's RSMs;
 *               returns the checksum READY carries (desync detection covers the method)
 *   screen()    optional (NULL: none), before the eye passes of one screen: all its views
 *               (both eyes), so a method can prepare once what they share (vpl: one light
 *               assignment for both eyes, enclosed clustering)
 *   eye_bind()  eye pass, per screen and eye, with the shading program bound: the method's
 *               uniforms and textures for shaders/shade.frag: its LPV lookup (u_lpv_enabled,
 *               the samplers u_lpv_r/g/b, ...) or its VPL gather (u_vpl_count, u_vpls,
 *               u_vpl_shadow or u_ism, ...), both off unless the method turns its own on
 *   stats()     the last frame's stage timings and the HUD's lattice size
 *
 * Every method must give every node the same result for the same frame_params. */
#ifndef CAVELIGHT_GI_METHOD_H
#define CAVELIGHT_GI_METHOD_H

#include <stddef.h>
#include <stdint.h>

#include "frame/frame_params.h"
#include "frame/frame_view.h"
#include "frame/light_view.h"
#include "gl_functions.h"
#include "renderer_desc.h"
#include "renderer_rsm.h"
#include "scene/scene.h"

typedef struct gi_desc {
    const gl_functions *gl;
    const scene *scene;
    const renderer_desc *settings; /* the renderer's desc: lattice, backend, threads, ... */
    int rsm_size;                  /* texels per side of each RSM */
    int software;                  /* a software GL (llvmpipe): GL compute is slow there */
    const char *shade_defines;     /* what shaders/shade.frag is compiled with */
} gi_desc;

/* This frame's reflective shadow maps, as the renderer rendered them (renderer_rsm.h). */
typedef struct gi_rsm {
    int size;                      /* texels per side */
    int layers;                    /* light views rendered, one layer each */
    const GLuint *fbo;             /* per layer: position, normal, flux in attachments 0..2 */
    const light_view *views;       /* per layer: the light and view it was rendered from */
    renderer_rsm *maps;            /* renderer_rsm_vpls(maps): the VPL source every method
                                      shares (read back from the maps, on request) */
} gi_rsm;

/* Texture units of the shading program's GI samplers, from gi_eye.first_unit on
 * (first_unit + 3 is the renderer's). gi_eye_bind() puts every method's samplers on their
 * units and turns every lookup off before the method's eye_bind(): a sampler left on unit
 * 0 beside the G-buffer's textures of another type makes the draw a GL error. */
enum {
    GI_UNIT_LPV = 0,        /* u_lpv_r, u_lpv_g, u_lpv_b: three units */
    GI_UNIT_VPL_DATA = 4,   /* u_vpls */
    GI_UNIT_VPL_SHADOW = 5, /* u_vpl_shadow */
    GI_UNIT_VPL_CLUSTERS = 6, /* u_vpl_cluster_first */
    GI_UNIT_VPL_LISTS = 7,  /* u_vpl_cluster_index */
    GI_UNIT_ISM = 8,        /* u_ism */
    GI_UNIT_VPL_IRRADIANCE = 9, /* u_vpl_irradiance */
};

typedef struct gi_eye {
    GLuint program;                /* the bound shading program, its framebuffer bound */
    int first_unit;                /* texture units from this one on are the method's */
    const frame_view *view;        /* the eye's view */
    int width, height;             /* the eye's G-buffer, on units 0 (u_position) and 1
                                      (u_normal): a method may run passes of its own over
                                      it, and puts the program, framebuffer and viewport
                                      back */
    const float *eye;              /* u_eye: the eye (w 1) or the direction to it (w 0) */
    float pixel_angle;             /* a pixel's width over its distance from the eye
                                      (w 0: the pixel's width) */
} gi_eye;

typedef struct gi_stats {
    double inject_ms, propagate_ms; /* the frame's two stages: making the light sources,
                                       spreading them (0 when reused) */
    int lattice_cells;             /* cells along the longest axis (the HUD's P bar); 0: none */
    double assign_ms;              /* vpl: the last light assignment (a view's, or a
                                      screen's for all its eyes), host ms with its upload */
    size_t assignments;            /* vpl: the (VPL, cluster) pairs it listed */
} gi_stats;

typedef struct gi_method {
    const char *name;
    /* Returns the method's state, or NULL with one line in err. */
    void *(*create)(const gi_desc *desc, char *err, size_t errlen);
    void (*destroy)(void *state);
    int (*reuse)(void *state, const frame_params *p);
    uint64_t (*frame)(void *state, const frame_params *p, const gi_rsm *rsm);
    void (*screen)(void *state, const frame_view *views, int n);
    void (*eye_bind)(void *state, const gi_eye *eye);
    void (*stats)(const void *state, gi_stats *out);
} gi_method;

#endif
