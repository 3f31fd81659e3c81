/* standalone: cavelight-node --standalone, a render node without a master.
 *
 * Loads the scene (the command line is node_cli.h's), renders --frames frames (frame
 * pass, then an eye pass per eye) and writes images and a timing report (report.json);
 * --renderer reference runs the path tracer instead (reference_cli.h). The cluster mode
 * is cluster_node.h. */
#ifndef CAVELIGHT_STANDALONE_H
#define CAVELIGHT_STANDALONE_H

#include "frame/frame_params.h"
#include "gl/glctx.h"
#include "renderer.h"

typedef struct node_options {
    int standalone;
    glctx_backend gl;
    const char *scene;
    int allow_outside_paths;     /* glTF buffers and images from outside the file's folder */
    float budget_ms;          /* > 0: choose the ILPV's lattice and steps (ilpv_budget.h) */
    float light_drift;        /* test: light 0 moves this far along x each frame */
    int threads;
    int frames, width, height;
    const char *out;
    int pfm;
    /* camera: the scene's (--camera picks one of a file's), or look-at, unless a screen is
     * given; without --height, a file camera's aspect ratio sets the height */
    const char *camera;
    int have_position, have_target, have_screen, have_eye, have_height;
    float position[3], target[3], yfov; /* radians, <= 0: the scene's */
    float screen[9], eye[3];
    int stereo;
    float eye_separation;
    /* the frame parameters: frame_params_default() with the command line's values (the
     * GI method and its settings among them, gi_settings.h); lights come from the scene */
    frame_params frame;
    int exposure_auto;    /* 1 unless --exposure N: from the scene's light (exposure.h) */
    int have_wand;        /* HUD (docs/node.md): wand position given */
    float wand[3];
    /* --renderer reference: the path tracer (docs/reference.md) instead of GL */
    int reference, samples, bounces;
    unsigned long long seed;
    const char *app;      /* --app: an application run without a cluster (standalone_app.h) */
} node_options;

/* The frame a standalone run starts from: o->frame (frame_params_default() and the
 * command line), the scene's lights, and the wand in front of the first eye when the HUD
 * is shown without --wand. Frame version and time are 0. */
void standalone_frame_params(const node_options *o, const scene *s,
                             const renderer_view *first_eye, frame_params *out);
/* Returns the process exit status. */
int standalone_run(const node_options *o);

#endif
