/* cluster_view: what one cluster node renders and shows.
 *
 * Owns the node's scene, GL context and renderer. cluster_view_render() runs the frame
 * pass (RSM, injection, propagation) once and then an eye pass per (screen, eye) of the
 * node, with an off-axis projection from the tracked head: the eyes sit at the head pose
 * times observer.head_to_eye, offset by +-eye_separation/2 along the head's right axis;
 * screens and eyes go from CAVE space to world space through the navigation transform.
 * While the frame asks for the calibration pattern (frame_params.pattern), every screen
 * shows it (frame/pattern.h) instead of the scene; the frame pass still runs.
 * cluster_view_present() shows the images of the last rendered frame through the node's
 * presentation (present.h: one viewport per screen and eye, each through its screen's
 * projector warp and blend from the config, read once here): PNG files (DIR/SCREEN-EYE.png,
 * replaced atomically; with keep_frames also DIR/SCREEN-EYE-NNNNNN.png numbered by the
 * frame's version, so that a replay can be reviewed frame by frame), windows in the node's
 * stereo mode on its monitors, or nothing (headless). The renderer follows the
 * frames' GI method and settings (renderer.h). cluster_view_create() renders one untracked
 * frame with the config's settings, so shaders are compiled before a join. */
#ifndef CAVELIGHT_CLUSTER_VIEW_H
#define CAVELIGHT_CLUSTER_VIEW_H

#include <stddef.h>
#include <stdint.h>

#include "cluster/cluster_config.h"
#include "frame/frame_params.h"
#include "app/app_host.h"
#include "renderer.h"
#include "cluster/wire.h"

typedef struct cluster_view cluster_view;

typedef struct cluster_view_desc {
    const cluster_config *config;
    int node;                 /* index into config->nodes */
    cluster_output output;
    const char *out_dir;      /* PNG output, NULL = CLUSTER_DEFAULT_OUT */
    const char *scene;        /* NULL = config scene, "" there = "default" */
    int threads;              /* CPU threads of the GI methods, 0 = all cores */
    int keep_frames;          /* PNG output: also SCREEN-EYE-NNNNNN.png (frame version) */
    int show_blend;           /* while the pattern shows: tint the blend regions (present.h) */
    int quiet;                /* no informational lines (the window's) */
} cluster_view_desc;

enum { CLUSTER_VIEW_MAX_EYES = 2 };

cluster_view *cluster_view_create(const cluster_view_desc *desc, char *err, size_t errlen);
void cluster_view_destroy(cluster_view *v);
/* Frame pass + all eye passes of frame f as the master sent it. Returns 0, the GI checksum
 * and how many fields the renderer clamped, or -1 with err. */
int cluster_view_render(cluster_view *v, const frame_params *f, uint64_t *checksum,
                        float timings[WIRE_TIMING_COUNT], int *fixed, char *err, size_t errlen);
/* Returns 0, 1 when the window was closed (the node should leave), -1 with err. */
int cluster_view_present(cluster_view *v, char *err, size_t errlen);
/* The last rendered image of (node screen index, eye index), top row first. */
const uint8_t *cluster_view_image(const cluster_view *v, int screen, int eye, int *width, int *height);
int cluster_view_eye_count(const cluster_config *cfg, int node);
const char *cluster_view_eye_name(const cluster_config *cfg, int node, int eye);

/* The scene it loaded (its objects: the node's keys, cluster/scene_keys.h). */
const scene *cluster_view_scene(const cluster_view *v);
/* Where the objects are in the next cluster_view_render(). */
void cluster_view_set_pose(cluster_view *v, const scene_pose *pose);
/* An application whose draw runs in every eye pass, into the G-buffer (NULL: none). */
void cluster_view_set_app(cluster_view *v, app_host *app);
/* app_host_desc's draw and gl_proc for an application on this view (user: the view). */
int cluster_view_app_draw(void *view, const cavelight_draw *d, int mode, const cavelight_vertex *v, int count,
                          float size);
void *cluster_view_gl_proc(void *view, const char *name);

/* The view of one screen for one eye: side -1 left, 0 centre, +1 right. Pure maths,
 * no GL: the seam test and other tools use it too. Returns 0, 1 when the eye was nearer the
 * screen's plane than the near plane or behind it and was moved in front (frame_view_screen();
 * *distance, if not NULL: where it was), or -1 (degenerate corners or pose). */
int cluster_view_compute(const cluster_config *cfg, int screen, int side, const frame_params *f,
                         int width, int height, float far_plane, renderer_view *out,
                         float *distance);

#endif
