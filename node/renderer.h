/* renderer: the render node's work on the current GL context.
 *
 *   renderer_frame_pass()  once per frame, view independent: RSM per spotlight -> VPLs ->
 *                          injection -> ILPV merge and propagation (or classic LPV
 *                          accumulation). Returns the LPV checksum the master compares
 *                          across nodes. Skips all of that and returns the last checksum
 *                          when the LPV's inputs are unchanged and it has converged
 *                          (lpv_converge.h).
 *   renderer_eye_pass()    per (screen, eye): G-buffer -> direct + indirect shading ->
 *                          tone map + gamma -> 8-bit RGB (and optional linear floats).
 *
 * The renderer loads nothing: the caller passes a loaded scene and owns it. */
#ifndef CAVELIGHT_RENDERER_H
#define CAVELIGHT_RENDERER_H

#include <stdint.h>
#include "frame/frame_params.h"
#include "frame/frame_view.h"
#include "gl_functions.h"
#include "lpv/lattice.h"
#include "lpv/lpv_volume.h"
#include "scene/scene.h"

typedef struct renderer renderer;

typedef enum renderer_lpv_backend {
    RENDERER_LPV_AUTO = 0, /* CPU on llvmpipe/softpipe, GL compute on a real GPU */
    RENDERER_LPV_CPU,
    RENDERER_LPV_GL,
} renderer_lpv_backend;

typedef enum renderer_tiles {
    RENDERER_TILES_AUTO = 0, /* shared-memory tiles on a GPU, plain image loads on llvmpipe */
    RENDERER_TILES_ON,
    RENDERER_TILES_OFF,
} renderer_tiles;

typedef enum renderer_lpv_mode {
    RENDERER_LPV_INCREMENTAL = 0, /* ILPV (ilpv.h): history merge, light accumulates over frames */
    RENDERER_LPV_CLASSIC,         /* classic LPV (lpv_classic.h): sum of this frame's steps */
} renderer_lpv_mode;

enum { RENDERER_DEFAULT_RSM_SIZE = 256 };

typedef struct renderer_desc {
    const gl_functions *gl; /* the current context's table (glctx_gl()) */
    const scene *scene;
    renderer_lpv_backend lpv_backend;
    int rsm_size;        /* 0 = RENDERER_DEFAULT_RSM_SIZE */
    int lattice_cells;   /* cells along the scene's longest axis, 0 = 32 */
    long lattice_cell_budget; /* > 0: instead, as many cells in total, spent on the scene's
                                 shape (a long corridor gets finer cells than a cube would) */
    int threads;         /* CPU propagation threads, 0 = all cores */
    int lpv_clamp_negative; /* clamp negative transfers in propagation (see lpv_propagate.h) */
    renderer_tiles lpv_gl_tiles; /* GL propagation variant (shaders/propagate.comp) */
    float indirect_scale;   /* light lifetime in propagation steps; 0 = from the scene's
                               mean free path (docs/node.md); classic mode: 1 */
    renderer_lpv_mode lpv_mode;
    double converge_threshold; /* skip the frame pass below this residual with unchanged
                                  inputs; 0 = 1e-4, negative = never skip */
} renderer_desc;

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
} renderer_image;

typedef struct renderer_timings {
    double rsm_ms, inject_ms, propagate_ms;        /* frame pass (GPU or host clock) */
    double gbuffer_ms, shade_ms, final_ms;          /* last eye pass */
    double frame_host_ms, eye_host_ms;
} renderer_timings;

typedef struct renderer_lpv_stats {
    long frames_skipped;      /* frame passes skipped since creation */
    double last_residual;     /* relative L1 change of the last computed frame's result,
                                 +Inf before two computed frames */
    int skipped_this_frame;   /* the last frame pass was skipped */
    float energy_gain;        /* injected over held lattice energy, times the indirect scale
                                 in the shading (1 in classic mode; docs/lpv.md) */
} renderer_lpv_stats;

/* Returns NULL with a one-line reason in err. */
renderer *renderer_create(const renderer_desc *desc, char *err, size_t errlen);
void renderer_destroy(renderer *r);
/* Takes the frame's parameters as sent (frame_params_sanitize() runs here, once). */
uint64_t renderer_frame_pass(renderer *r, const frame_params *p);
/* Renders the last frame pass's frame from one view. want_linear: also read back
 * final/direct/indirect linear images for measurement. */
int renderer_eye_pass(renderer *r, const renderer_view *view, int want_linear,
                      renderer_image *out);
void renderer_get_timings(const renderer *r, renderer_timings *out);
/* One line: why the last renderer_eye_pass() returned -1. */
const char *renderer_last_error(const renderer *r);
/* Copies the last eye pass's final image into the default framebuffer (a window),
 * scaled to width x height; for the GLFW backend before glctx_swap(). */
void renderer_present(renderer *r, int width, int height);
/* The resolved LPV backend (never AUTO), its lattice, and the propagated light after the
 * last frame pass (12 channels, host memory; read back from GL with the GL backend). */
renderer_lpv_backend renderer_get_lpv_backend(const renderer *r);
const lattice_desc *renderer_get_lattice(const renderer *r);
const lpv_volume *renderer_get_lpv(const renderer *r);
float renderer_get_indirect_scale(const renderer *r);
renderer_lpv_mode renderer_get_lpv_mode(const renderer *r);
void renderer_get_lpv_stats(const renderer *r, renderer_lpv_stats *out);
/* Milliseconds per propagation step on this backend and lattice (blocking on; in classic
 * mode with its addition into the sum), timed over `steps` steps after one untimed step; GL work is finished before the clock stops. It
 * overwrites the light volumes: the next frame pass starts without history and is never
 * skipped; show no eye pass before it. */
double renderer_measure_step_ms(renderer *r, int steps);

#endif
