/* renderer_desc: what a renderer is made with (renderer.h), and the settings and figures of
 * its ILPV method that the GI modules share with it (gi_ilpv.h). Types only. */
#ifndef CAVELIGHT_RENDERER_DESC_H
#define CAVELIGHT_RENDERER_DESC_H

#include "frame/frame_params.h"
#include "gl_functions.h"
#include "scene/scene.h"

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

typedef enum renderer_vpl_lights {
    RENDERER_VPL_CLUSTERED = 0, /* vpl: lists per cluster of the view (x, y, depth slices) */
    RENDERER_VPL_TILED,         /* lists per screen tile (one depth slice): the comparison */
    RENDERER_VPL_ALL,           /* every VPL at every pixel (brute force) */
} renderer_vpl_lights;

typedef enum renderer_lpv_mode {
    RENDERER_LPV_INCREMENTAL = 0, /* ILPV (ilpv.h): history merge, light accumulates over frames */
    RENDERER_LPV_CLASSIC,         /* classic LPV (lpv_classic.h): sum of this frame's steps */
} renderer_lpv_mode;

/* How the vpl method tests whether a VPL sees a point (node/vpl_ism.h, gi_vpl.h). */
typedef enum renderer_vpl_visibility {
    RENDERER_VPL_EXACT = 0, /* a cube of six distance maps per VPL from the triangles */
    RENDERER_VPL_ISM,       /* imperfect shadow maps: single-pixel points, pull-push */
    RENDERER_VPL_ISM_SPLAT, /* imperfect shadow maps: points splatted as disks */
} renderer_vpl_visibility;

enum {
    RENDERER_DEFAULT_RSM_SIZE = 256,
    RENDERER_DEFAULT_ISM_SIZE = 32,    /* texels per side of one VPL's imperfect map */
    RENDERER_ISM_SIZE_MIN = 8,         /* a power of two between these */
    RENDERER_ISM_SIZE_MAX = 256,
    RENDERER_DEFAULT_ISM_POINTS = 1024, /* points per VPL's map */
    RENDERER_ISM_POINTS_MIN = 64,
    RENDERER_ISM_POINTS_MAX = 16384,
    RENDERER_VPL_INTERLEAVE_MAX = 8,
};

typedef struct renderer_desc {
    const gl_functions *gl; /* the current context's table (glctx_gl()) */
    const scene *scene;
    renderer_lpv_backend lpv_backend;
    int rsm_size;        /* 0 = RENDERER_DEFAULT_RSM_SIZE */
    int lattice_cells;   /* cells along the scene's longest axis, 0 = 32 */
    long lattice_cell_budget; /* > 0: instead, as many cells in total, spent on the scene's
                                 shape (a long corridor gets finer cells than a cube would) */
    int threads;         /* CPU propagation threads, 0 = all cores */
    renderer_tiles lpv_gl_tiles; /* GL propagation variant (shaders/propagate.comp) */
    renderer_lpv_mode lpv_mode;
    double converge_threshold; /* skip the frame pass below this residual with unchanged
                                  inputs; 0 = 1e-4, negative = never skip */
    frame_gi gi;         /* the GI method built first (0 = ILPV); the frames' gi decides */
    int vpl_point;       /* vpl: gather each VPL as a point, 1/r^2 unbounded, instead of as a
                            disk of its area: only to measure the bound's bias (docs/node.md) */
    renderer_vpl_visibility vpl_visibility;
    int vpl_interleave;  /* vpl: 0 = every pixel gathers every VPL; k = 1..
                            RENDERER_VPL_INTERLEAVE_MAX: interleaved sampling in k x k
                            blocks (gi_vpl.h) */
    int ism_size;        /* 0 = RENDERER_DEFAULT_ISM_SIZE */
    int ism_points;      /* 0 = RENDERER_DEFAULT_ISM_POINTS */
    renderer_vpl_lights vpl_lights; /* vpl: light assignment of the gather */
    float vpl_cut;       /* vpl: influence cut (vpl_cluster.h); 0 = VPL_CUT_DEFAULT,
                            negative = none (every VPL reaches every receiver) */
} renderer_desc;

typedef struct renderer_lpv_stats {
    long frames_skipped;      /* frame passes skipped since creation */
    double last_residual;     /* relative L1 change of the last computed frame's result,
                                 +Inf before two computed frames */
    int skipped_this_frame;   /* the last frame pass was skipped */
    double injected_energy[3]; /* <L|1> of the last computed frame's injection, per colour:
                                  the flux of its VPLs (W) */
} renderer_lpv_stats;

#endif
