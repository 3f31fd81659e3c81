/* renderer: the render node's work on the current GL context.
 *
 *   renderer_frame_pass()  once per frame, view independent: gi_frame_sanitize() (the
 *                          one clamp of what arrived), the GI method the frame asks for with
 *                          its settings (gi.h; another method, or a setting that rebuilds it,
 *                          builds it fresh), the reflective shadow maps of every light view
 *                          (renderer_rsm.h: spots one, point lights six, directional one),
 *                          then the method's frame. Returns the method's checksum, which the
 *                          master compares across nodes. When the method can reuse last
 *                          frame's result (ILPV: unchanged inputs, converged) nothing is
 *                          rendered and the last checksum is returned.
 *   renderer_eye_pass()    per (screen, eye): G-buffer -> ambient occlusion
 *                          (renderer_ao.h, when the frame asks for it) -> direct + the
 *                          method's indirect shading -> tone map + gamma -> HUD -> 8-bit RGB
 *                          (and optional linear floats).
 *
 *   renderer_set_pose()    before a frame pass: where the scene's objects are
 *                          (scene_pose.h); every pass draws them there, the GI method
 *                          follows (gi_objects_moved()) and nothing of the last frame is
 *                          reused when one moved.
 *
 * The renderer loads nothing: the caller passes a loaded scene and owns it. */
#ifndef CAVELIGHT_RENDERER_H
#define CAVELIGHT_RENDERER_H

#include <stdint.h>
#include "frame/frame_params.h"
#include "frame/frame_view.h"
#include "gi/gi.h"
#include "gl/gl_functions.h"
#include "gl/gpu_timer.h"
#include "renderer_ao.h"
#include "renderer_desc.h"
#include "scene/scene.h"
#include "scene/scene_pose.h"

typedef struct renderer renderer;

/* What an eye pass renders from: built by frame_view_screen() or frame_view_camera(). */
typedef frame_view renderer_view;

typedef struct renderer_image {
    int width, height;
    uint8_t *rgb;          /* width*height*3, top row first; owned by the renderer */
    int lit;               /* some pixel shows light (before the HUD); a view that turns
                              black is also reported on stderr, once */
    const float *final;    /* linear RGB floats, or NULL unless requested */
    const float *direct;
    const float *indirect;
    const float *ao;       /* the ambient occlusion as grey RGB, or NULL (ao off) */
} renderer_image;

typedef struct renderer_timings {
    double rsm_ms;                          /* frame pass: the RSMs (GPU clock) */
    gi_stats gi;                            /* frame pass: the GI method's stages (host
                                               ms), its figures */
    double gbuffer_ms, shade_ms, final_ms;  /* per eye pass (GPU clock, gpu's mean) */
    double aa_ms;                           /* its anti-aliasing (GPU clock; 0 when off) */
    renderer_ao_stats ao;                   /* last eye pass: the ambient occlusion (host
                                               ms); its maps' build and memory */
    double frame_host_ms, eye_host_ms;
    gpu_timer_result gpu;                   /* GPU ms per stage of the newest frame whose
                                               timer queries arrived (a frame or more
                                               late, gpu_timer.h): rsm, gi and the method's
                                               own, gbuffer, ao, shade, final (summed over
                                               the eyes), present */
    int fixed;                              /* fields of the last frame the renderer
                                               clamped (gi_frame_sanitize()) */
} renderer_timings;

/* Returns NULL with a one-line reason in err. */
renderer *renderer_create(const renderer_desc *desc, char *err, size_t errlen);
void renderer_destroy(renderer *r);
/* Replaces renderer_desc's gbuffer_draw and its user (NULL: nothing drawn). */
void renderer_set_gbuffer_draw(renderer *r,
                               void (*draw)(void *user, const frame_view *view, const float view_projection[16],
                                            GLuint fbo, GLuint depth_texture),
                               void *user);
/* The objects' pose for the next frame passes (until called: as loaded). */
void renderer_set_pose(renderer *r, const scene_pose *pose);
/* Takes the frame's parameters as sent (gi_frame_sanitize() runs here, once). A method
 * that cannot be built (memory) leaves the current one in place and says why in
 * renderer_last_error(); the checksums then tell the master whether the nodes disagree. */
uint64_t renderer_frame_pass(renderer *r, const frame_params *p);
/* The last computed frame's checksum with its own GPU part, which renderer_frame_pass()
 * returns a frame late (gpu_checksum.h; waits for it): what a test compares between
 * renderers after one frame. */
uint64_t renderer_checksum_complete(renderer *r);
/* The views of one screen (both eyes of a stereo screen), before their eye passes: the GI
 * method may prepare what they share once (vpl: one light assignment over a grid that
 * encloses all of them). Views not announced get their own. */
void renderer_screen(renderer *r, const renderer_view *views, int n);
/* Renders the last frame pass's frame from one view. want_linear: also read back
 * final/direct/indirect linear images for measurement. */
int renderer_eye_pass(renderer *r, const renderer_view *view, int want_linear,
                      renderer_image *out);
void renderer_get_timings(const renderer *r, renderer_timings *out);
/* One line: why the last renderer_eye_pass() returned -1. */
const char *renderer_last_error(const renderer *r);
/* The last frame pass's shadow maps and the VPL source every GI method shares
 * (renderer_rsm.h); the renderer owns them. */
struct renderer_rsm *renderer_get_rsm(renderer *r);
/* The last frame's maps as the GI method got them. */
void renderer_gi_rsm(const renderer *r, gi_rsm *out);
/* Its GPU stage timer: what runs on its context between frame passes (presentation) may
 * add stages. */
gpu_timer *renderer_gpu_timer(renderer *r);
/* The active GI method (gi.h; its own header inspects its state: gi_ilpv.h, gi_vpl.h). */
gi *renderer_gi(renderer *r);

#endif
