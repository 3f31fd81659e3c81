/* present: a node's output of its final images, one path for the cluster node and the
 * standalone node.
 *
 * present_create() makes the GL context the renderer draws on (a window's for window
 * output, else EGL, or OSMesa when EGL is missing and fallback is asked) and everything
 * that shows the images. Each frame the caller writes every viewport's image (one screen
 * for one eye, top row first) into present_source(), gives 3d warps the eye's view
 * (present_set_view()), and present_frame() sends every image through the warp-and-blend
 * pass (present_warp.h: the screen's projector warp and blend maps, or the image as
 * rendered) to the output:
 *   PRESENT_WINDOW    GLFW windows (present_window.h): per eye the viewports side by side
 *                     in their order (an MPCDI region where its buffer places it), the two
 *                     eyes in the stereo mode: side-by-side, top-bottom, red-cyan anaglyph
 *                     (red from the left eye), quad-buffered (the driver's left and right
 *                     back buffers; where it offers none, one line says so and it shows
 *                     side-by-side) or one window per eye; the composition is scaled to the
 *                     window (its size, or a fullscreen monitor's mode), then swapped;
 *   PRESENT_PNG       OUT/NAME.png per viewport, replaced atomically, and with keep_frames
 *                     also OUT/NAME-NNNNNN.png by frame version: what the projector shows;
 *   PRESENT_HEADLESS  nothing; the images stay readable in present_source().
 * Does not: render (renderer.h), choose views, read warp files (the caller passes loaded
 * warp_maps, which present_create() uploads and does not keep), or draw the master's
 * windows (master/pixel_window.c: another program, see docs/architecture.md). */
#ifndef CAVELIGHT_PRESENT_H
#define CAVELIGHT_PRESENT_H

#include <stddef.h>
#include <stdint.h>

#include "cluster/cluster_config.h"
#include "gl/glctx.h"
#include "warp/warp_map.h"

enum { PRESENT_MAX_VIEWPORTS = 2 * CLUSTER_NODE_MAX_SCREENS };

typedef enum present_output {
    PRESENT_HEADLESS = 0,
    PRESENT_PNG,
    PRESENT_WINDOW,
} present_output;

typedef struct present_viewport {
    const char *name;        /* PNG output: OUT/NAME.png */
    int width, height;       /* the rendered image */
    int eye;                 /* 0: the left (or only) eye, 1: the right */
    const warp_map *warp;    /* NULL: shown as rendered */
    const float *to_cave;    /* WARP_POINT_GRID: the map's points to CAVE space; NULL = identity */
} present_viewport;

typedef struct present_desc {
    present_output output;
    glctx_backend backend;   /* headless and PNG output: GLCTX_EGL (0) or GLCTX_OSMESA */
    int fallback;            /* EGL missing: OSMesa */
    const char *log_name;    /* what log lines start with, "cavelight-node n01" */
    int quiet;
    int viewport_count;
    const present_viewport *viewports;
    const char *out_dir;     /* PNG output */
    int keep_frames;
    const char *title;       /* window output */
    const char *display;     /* window output without DISPLAY or WAYLAND_DISPLAY: this X
                                display (a node started over ssh or as a service) */
    cluster_stereo stereo;   /* window output with two eyes */
    const cluster_window *window; /* NULL: a window of the images' size, vsync on */
} present_desc;

typedef struct present present;

typedef struct present_frame_desc {
    uint64_t version;        /* keep_frames: the file's number */
    float display_gamma;     /* the frame's: blending works in linear light; 0 = the
                                frame's default (frame_params_default()) */
    int show_blend;          /* tint the blend regions instead of blending (--pattern-blend) */
} present_frame_desc;

/* Returns NULL with one line in err. */
present *present_create(const present_desc *desc, char *err, size_t errlen);
void present_destroy(present *p);
glctx *present_context(present *p);
/* Where viewport vp's image goes for the next frame: width * height RGB, top row first. */
uint8_t *present_source(present *p, int vp);
/* WARP_POINT_GRID: CAVE space to the viewport image's clip space this frame (projection *
 * view * navigation of the eye that rendered it). */
void present_set_view(present *p, int vp, const float cave_to_clip[16]);
/* Returns 0, 1 when a window was asked to close, or -1 with err. */
int present_frame(present *p, const present_frame_desc *f, char *err, size_t errlen);

#endif
