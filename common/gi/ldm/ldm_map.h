/* ldm_map: where the layered depth maps (LDMs) lie and what they cost, the one rule the
 * GL build (node/gi/ldm/ldm_gl.h), the shaders (shaders/ldm_trace.glsl) and the CPU oracle
 * (ldm_cpu.h) share.
 *
 * Map i looks along direction d_i (ldm_directions.h) at the scene's bounding sphere
 * (centre c, radius R): an orthographic square of side 2R, resolution^2 texels, texel
 * (x, y) covering u in [-R, R] and v in [-R, R] of the map's basis (u, v, d_i). A point p
 * lies at texel ((p - c).u / R + 1) res / 2 (same for v) and depth t = (p - c).d_i + R in
 * [0, 2R]. Each texel keeps the `layers` smallest depths of the surfaces that cover its
 * centre, sorted (a k-buffer); a texel's list holds the bits of non-negative floats (their
 * order is the floats' order) and LDM_EMPTY after the last one.
 *
 * Not here: building or tracing the maps. */
#ifndef CAVELIGHT_LDM_MAP_H
#define CAVELIGHT_LDM_MAP_H

#include <stddef.h>
#include <stdint.h>

#include "frame/ldm_limits.h"
#include "scene/scene.h"

#define LDM_EMPTY 0xffffffffu

typedef struct ldm_layout {
    int directions;      /* maps, 1..LDM_DIRECTIONS_MAX */
    int resolution;      /* texels per side */
    int layers;          /* depths kept per texel */
    float centre[3];     /* the scene's bounding sphere */
    float radius;
} ldm_layout;

/* One map's orthonormal basis: u, v across the map, d the direction it looks along. */
typedef struct ldm_map {
    float u[3], v[3], d[3];
} ldm_map;

/* The layout of n maps of res^2 texels and `layers` depths around s (scene_finish()ed):
 * its bounding sphere a little larger than the bounds' (nothing touches the map's edge). */
void ldm_layout_init(ldm_layout *l, const scene *s, int directions, int resolution, int layers);
/* The maps' bases, l->directions of them (ldm_directions()). */
void ldm_layout_maps(const ldm_layout *l, ldm_map *out);
/* A texel's side in metres. */
float ldm_texel(const ldm_layout *l);
/* p in map m: texel coordinates (x, y, continuous: texel i spans [i, i + 1)) and depth. */
void ldm_project(const ldm_layout *l, const ldm_map *m, const float p[3], float *x, float *y,
                 float *t);
/* The k-buffer's bytes: directions x resolution^2 x layers x 4. */
double ldm_memory_bytes(const ldm_layout *l);
/* NULL when the maps fit cap_mb (MB of 2^20 bytes), else one line saying what they need and
 * what to change, in buf. `what` names them ("ldm", "ao"). */
const char *ldm_memory_check(int directions, int resolution, int layers, int cap_mb,
                             const char *what, char *buf, size_t cap);

#endif
