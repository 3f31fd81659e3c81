/* renderer: the render node's work on the current GL context.
 *
 *   renderer_frame_pass()  once per frame, view independent: frame_params_sanitize(), the
 *                          GI method the frame asks for (gi.h; a switch builds it fresh),
 *                          the reflective shadow maps of every light view (renderer_rsm.h:
 *                          spots one, point lights six, directional one), then the method's frame
 *                          (ILPV: VPLs -> injection -> merge and propagation). Returns the
 *                          method's checksum, which the master compares across nodes. When
 *                          the method can reuse last frame's result (ILPV: unchanged inputs,
 *                          converged; lpv_converge.h) nothing is rendered and the last
 *                          checksum is returned.
 *   renderer_eye_pass()    per (screen, eye): G-buffer -> direct + the method's indirect
 *                          shading -> tone map + gamma -> HUD -> 8-bit RGB (and optional
 *                          linear floats).
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
#include "renderer_desc.h"
#include "scene/scene.h"

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
} renderer_image;

typedef struct renderer_timings {
    double rsm_ms, inject_ms, propagate_ms;        /* frame pass (GPU or host clock) */
    double gbuffer_ms, shade_ms, final_ms;          /* last eye pass */
    double frame_host_ms, eye_host_ms;
    double assign_ms;      /* vpl: the last light assignment (gi_stats.assign_ms) */
    size_t assignments;    /* vpl: its (VPL, cluster) pairs */
} renderer_timings;

/* Returns NULL with a one-line reason in err. */
renderer *renderer_create(const renderer_desc *desc, char *err, size_t errlen);
void renderer_destroy(renderer *r);
/* Takes the frame's parameters as sent (frame_params_sanitize() runs here, once). */
uint64_t renderer_frame_pass(renderer *r, const frame_params *p);
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
/* The active GI method (renderer_desc.gi at first, then the frames' gi). */
frame_gi renderer_get_gi(const renderer *r);
/* While ILPV is the active method (else AUTO, NULL, NULL, 0, the desc's mode, zeros with an
 * infinite residual, 0 ms): */
/* The resolved LPV backend (never AUTO), its lattice, and the propagated light after the
 * last frame pass (12 channels, host memory; read back from GL with the GL backend). */
renderer_lpv_backend renderer_get_lpv_backend(const renderer *r);
const lattice_desc *renderer_get_lattice(const renderer *r);
const lpv_volume *renderer_get_lpv(const renderer *r);
renderer_lpv_mode renderer_get_lpv_mode(const renderer *r);
void renderer_get_lpv_stats(const renderer *r, renderer_lpv_stats *out);
/* Milliseconds per propagation step on this backend and lattice (blocking on; in classic
 * mode with its addition into the sum), timed over `steps` steps after one untimed step; GL work is finished before the clock stops. It
 * overwrites the light volumes: the next frame pass starts without history and is never
 * skipped; show no eye pass before it. */
double renderer_measure_step_ms(renderer *r, int steps);

#endif
