/* gi_method: what one indirect-light (GI) method implements, and what it is given (gi.h
 * says when the renderer calls it). A method is its folder node/gi/NAME/: its settings
 * (NAME_settings.c, gi_settings.h), this interface (gi_NAME.c defines gi_NAME_method), its
 * shading snippet and its other shaders, and one line in gi_methods.def.
 *
 *   create()    state from the scene and the frame's settings of the method
 *               (gi_settings_read()); NULL with one line in err
 *   reuse()     frame pass, before the RSMs: 1 when last frame's result stands (nothing is
 *               rendered, frame() is not called)
 *   frame()     frame pass, once per frame, view independent, with this frame's RSMs;
 *               returns the host part of the checksum READY carries (desync detection
 *               covers the method); results that stay on the GPU go to gi_desc.sum
 *               instead (gpu_checksum.h: READY carries them a frame late)
 *   screen()    optional (NULL: none), before the eye passes of one screen: all its views
 *               (both eyes), so a method can prepare once what they share (vpl: one light
 *               assignment for both eyes, enclosed clustering)
 *   eye_bind()  eye pass, per screen and eye, with the shading program bound: the
 *               method's uniforms and textures for its shading snippet
 *   stats()     the last frame's stages and figures
 *   objects()   optional (NULL: none), before frame() when scene objects moved or were
 *               hidden (scene_pose.h), and after create() when any is not where it was
 *               loaded: a method that keeps geometry of its own (ILPV's blockers) follows
 *               them here; the renderer's passes (RSMs, shadow maps, G-buffer) draw them
 *               where they are without it
 *
 * The shading snippet (shade: files of the method's folder) defines
 *   vec3 gi_irradiance(vec3 p, vec3 n)
 * the irradiance that reaches surface point p with unit normal n by the method's light
 * (W/m^2, before the albedo), and, when the method sets glossy,
 *   vec3 gi_glossy(vec3 p, vec3 n, vec3 v)
 * the radiance p reflects towards the eye (unit v) by the method's light through the
 * specular lobe, added to the indirect term (shade.frag is compiled with GI_GLOSSY
 * defined then; a method without it shades exactly as before). shade.frag is compiled
 * with the snippet once per method, so the program holds no other method's samplers. Texture units from
 * gi_eye.first_unit on are the method's to number.
 *
 * Not here: which method runs (the frame's gi), when it is rebuilt (gi.h), its settings'
 * names and ranges (gi_settings.h). Every method must give every node the same result for
 * the same frame_params. */
#ifndef CAVELIGHT_GI_METHOD_H
#define CAVELIGHT_GI_METHOD_H

#include <stddef.h>
#include <stdint.h>

#include "frame/frame_params.h"
#include "frame/frame_view.h"
#include "frame/light_view.h"
#include "gl/gl_functions.h"
#include "gl/gpu_checksum.h"
#include "gl/gpu_timer.h"
#include "scene/scene.h"
#include "gl/scene_gl.h"
#include "gi/gi_rsm.h"

typedef struct gi_desc {
    const gl_functions *gl;
    const scene *scene;
    const frame_params *frame;     /* the frame it is built for: the method's settings */
    int rsm_size;                  /* texels per side of each RSM */
    int threads;                   /* CPU threads, 0 = all cores */
    int software;                  /* a software GL (llvmpipe): GL compute is slow there */
    int no_reuse;                  /* reuse() must say 0: every frame is computed (to
                                      measure it) */
    float head_to_eye[3];          /* the viewer: frame_view_head_centre()'s offset */
    gpu_timer *timer;              /* the renderer's: the method's stages' GPU time
                                      (gpu_timer_begin() with the stage's name); may be
                                      NULL */
    gpu_checksum *sum;             /* the renderer's: GPU results into the checksum (may be
                                      NULL) */
} gi_desc;

typedef struct gi_eye {
    GLuint program;                /* the bound shading program, its framebuffer bound */
    int first_unit;                /* texture units from this one on are the method's */
    const frame_view *view;        /* the eye's view */
    int width, height;             /* the eye's G-buffer, on the program's u_position and
                                      u_normal (units 0, 1): a method may run passes of its
                                      own over it, and puts the program, framebuffer and
                                      viewport back */
    const float *eye;              /* u_eye: the eye (w 1) or the direction to it (w 0) */
    float pixel_angle;             /* a pixel's width over its distance from the eye
                                      (w 0: the pixel's width) */
} gi_eye;

/* The scene's objects in this frame (renderer.c), for objects(). */
typedef struct gi_objects {
    int count;                     /* the scene's object_count */
    const float (*model)[16];      /* where each object's triangles are (column-major) */
    const uint8_t *shown;          /* 0: hidden */
    const uint8_t *moved;          /* 1: model or visibility changed since the last call */
} gi_objects;

enum { GI_STATS_MAX = 12 };

typedef struct gi_stat {
    const char *name;              /* "inject", "select", "assignments", ... */
    double value;
} gi_stat;

typedef struct gi_stats {
    int stage_count;               /* the frame pass's stages, host ms with GL finished, in
                                      order (0 when reused) */
    gi_stat stage[GI_STATS_MAX];
    int figure_count;              /* anything else worth reporting (its name says its unit) */
    gi_stat figure[GI_STATS_MAX];
    int hud_cells;                 /* the HUD's steps bar is steps over this many (ILPV: its
                                      lattice's longest axis); 0: the default lattice's */
} gi_stats;

/* The stage or figure named name, or 0 (with *found 0 when found is not NULL). */
double gi_stats_value(const gi_stats *s, const char *name, int *found);
/* The stages' sum: the method's part of the frame pass. */
double gi_stats_total_ms(const gi_stats *s);

typedef struct gi_method {
    const char *name;
    const char *shade[3];          /* its shading snippet: shader files, in order, after
                                      shade.frag (unused entries NULL) */
    int glossy;                    /* 1: the snippet also defines gi_glossy() */
    /* Returns the method's state, or NULL with one line in err. */
    void *(*create)(const gi_desc *desc, char *err, size_t errlen);
    void (*destroy)(void *state);
    int (*reuse)(void *state, const frame_params *p);
    uint64_t (*frame)(void *state, const frame_params *p, const gi_rsm *rsm);
    void (*screen)(void *state, const frame_view *views, int n);
    void (*eye_bind)(void *state, const gi_eye *eye);
    void (*stats)(const void *state, gi_stats *out);
    void (*objects)(void *state, const gi_objects *o);
} gi_method;

#endif
