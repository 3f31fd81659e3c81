/* vpl_cluster: light assignment for the vpl method's gather (node/gi_vpl.c,
 * shaders/shade.frag): which VPLs can light which part of a view, so that a pixel loops over
 * its cluster's list instead of every VPL.
 *
 * A grid is a view frustum (apex, axes, a window on the image plane at unit depth, near
 * and far) cut into tiles, uniform on the image plane, and slices, exponential in depth
 * (slice k starts at near (far / near)^(k / slices)); tiled assignment is the same with one
 * slice. A VPL is listed in a cluster when its influence sphere (vpl_influence_radius())
 * meets the cluster's box and some corner of the cluster lies in front of the VPL's
 * surface. Both tests are conservative (the box holds the cluster, the cluster is convex
 * and a plane is tested at its corners; both padded against rounding), so a receiver gets
 * every VPL that can light it within the cut, and the lists, kept in VPL order, make the
 * gather add the same terms in the same order as a loop over all VPLs.
 *
 * Enclosed clustering (Stereoscopic clustered shading): one grid whose frustum encloses
 * the frusta of all views of a screen (both eyes), assigned once for all of them.
 * The same VPLs and views give the same lists on every node. Host maths; no GL. */
#ifndef CAVELIGHT_VPL_CLUSTER_H
#define CAVELIGHT_VPL_CLUSTER_H

#include <stddef.h>
#include <stdint.h>

#include "frame/frame_view.h"
#include "gi/vpl/vpl_select.h"

enum {
    VPL_CLUSTER_TILE_PX = 32, /* a tile's side in pixels of the view (Olsson's 32 x 32) */
    VPL_CLUSTER_SLICES = 16,  /* depth slices of a clustered grid */
};

/* The influence cut: a VPL of flux F reaches receivers where its largest possible
 * irradiance, the bounded kernel F / (A + pi r^2) (cosines 1), is at least the fraction
 * `cut` of F / S, the irradiance its flux would give spread evenly over the scene's
 * surface area S. The default fraction is 1: a VPL reaches as far as it outshines its even
 * share. */
#define VPL_CUT_DEFAULT 1.0f

/* The radius r where F / (A + pi r^2) = cut F / S: sqrt(max(S / cut - A, 0) / pi);
 * cut <= 0: no cut (infinity). */
float vpl_influence_radius(float area, float scene_area, float cut);

typedef struct vpl_grid {
    float apex[3], right[3], up[3], forward[3]; /* unit axes, forward into the view */
    float window[4];       /* tangents at unit depth: right min, up min, right max, up max */
    float near, far;       /* depths along forward */
    int tiles[2], slices;
} vpl_grid;

/* A view's own grid: its eye, axes and window, tiles of VPL_CLUSTER_TILE_PX pixels and
 * `slices` slices (1: tiled). Returns -1 for an orthographic view (no apex). */
int vpl_grid_from_view(const frame_view *view, int slices, vpl_grid *out);
/* One grid enclosing the frusta of views[0..n): the apex behind the eyes' mean on the
 * first view's axis, where the side planes of the views meet (s / w: the eyes' spread over
 * the window's width per unit depth), the window and depths those of all frusta's corners
 * seen from it, tiles at the views' pixel density. Returns -1 when a view is
 * orthographic or the views do not look the same way. */
int vpl_grid_enclosing(const frame_view *views, int n, int slices, vpl_grid *out);
/* The cluster holding point p (tiles x, then y, then slices), clamped into the grid; the
 * rule shaders/shade.frag's vpl_cluster() follows. */
int vpl_grid_cluster(const vpl_grid *g, const float p[3]);
int vpl_grid_clusters(const vpl_grid *g);

typedef struct vpl_clusters {
    uint32_t *first;   /* clusters + 1 entries: cluster c lists index[first[c] .. first[c+1]) */
    uint16_t *index;   /* VPL indices, ascending within a cluster */
    size_t assigned;   /* assignments: entries of index */
    size_t capacity_first, capacity_index;
} vpl_clusters;

/* Assigns n VPLs (positions, normals; radius[i] their influence radii) to g's clusters
 * into c (grown as needed, xalloc). */
void vpl_clusters_assign(vpl_clusters *c, const vpl_grid *g, const vpl *v,
                         const float *radius, int n);
void vpl_clusters_free(vpl_clusters *c);

#endif
