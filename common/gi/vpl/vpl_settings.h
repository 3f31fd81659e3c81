/* vpl_settings: the vpl method's settings (gi_settings.h), without GL: what every program
 * needs to name, check and send them. */
#ifndef CAVELIGHT_VPL_SETTINGS_H
#define CAVELIGHT_VPL_SETTINGS_H

#include "gi/gi_settings.h"
#include "gi/vpl/vpl_selection.h"

/* How a VPL's visibility is tested (vpl_ism.h, gi_vpl.h). */
typedef enum vpl_visibility {
    VPL_VISIBILITY_EXACT = 0, /* a cube of six distance maps per VPL from the triangles */
    VPL_VISIBILITY_ISM,       /* imperfect shadow maps: single-pixel points, pull-push */
    VPL_VISIBILITY_ISM_SPLAT, /* imperfect shadow maps: points splatted as disks */
} vpl_visibility;

/* The gather's light assignment (vpl_cluster.h). */
typedef enum vpl_lights {
    VPL_LIGHTS_CLUSTERED = 0, /* lists per cluster of the view (x, y, depth slices) */
    VPL_LIGHTS_TILED,         /* lists per screen tile (one depth slice): the comparison */
    VPL_LIGHTS_ALL,           /* every VPL at every pixel (brute force) */
} vpl_lights;

typedef enum vpl_bound {
    VPL_BOUND_DISK = 0, /* each VPL a disk of its area near it (bounded) */
    VPL_BOUND_POINT,    /* a point, 1/r^2 unbounded: only to measure the disk's bias */
} vpl_bound;

/* vpl-count's range and default: a few hundred VPLs with a shadow map each is what a
 * software GL renders in about a second at 320x240; 4096 is the paper's upper end. */
enum { VPL_COUNT_MIN = 64, VPL_COUNT_MAX = 4096, VPL_COUNT_DEFAULT = 256 };
enum { VPL_INTERLEAVE_MAX = 8 };
/* An imperfect map's side (a power of two) and points. */
enum { VPL_ISM_SIZE_MIN = 8, VPL_ISM_SIZE_MAX = 256, VPL_ISM_POINTS_MIN = 64, VPL_ISM_POINTS_MAX = 16384 };

/* Exact visibility's shadow maps: at most VPL_TEXEL_BUDGET depth texels (16 bit) for all
 * cube faces, 128 MB; faces are VPL_FACE texels on a side while that fits (1365 VPLs),
 * smaller beyond. */
enum { VPL_FACE = 64, VPL_TEXEL_BUDGET = 1 << 26, VPL_FACES = 6 };
/* The face side for n VPLs. */
int vpl_shadow_face(int n);

typedef struct vpl_settings {
    int count;                /* VPLs chosen per frame */
    int seed;                 /* which random numbers choose them (the same on every node) */
    vpl_selection selection;  /* the rule that chooses them (vpl_select.h) */
    vpl_bound bound;
    vpl_visibility visibility;
    int interleave;           /* 0: every pixel gathers every VPL; k: k x k interleaving */
    int ism_size;             /* texels per side of one VPL's imperfect map */
    int ism_points;           /* points per imperfect map */
    vpl_lights lights;
    float cut;                /* the influence cut (vpl_cluster.h); <= 0: none */
} vpl_settings;

extern const gi_method_settings vpl_settings_table;

/* The frame's vpl settings. */
void vpl_settings_get(const frame_params *p, vpl_settings *out);

#endif
