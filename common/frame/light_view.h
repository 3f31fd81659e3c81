/* light_view: what every renderer needs to know about a light beyond its parameters: the
 * views its reflective shadow map (RSM) is rendered from, its cone as clamped for
 * rendering, the distance its light travels through the scene's medium and the power it
 * emits. Plain maths on frame_params and the scene's bounds; no GL.
 *
 *   spot         one perspective view from the light along its axis, opened to the outer
 *                cone
 *   point        six cube faces (+x, -x, +y, -y, +z, -z). Each face's image spans 90
 *                degrees plus LIGHT_VIEW_CUBE_MARGIN texels on every side, so that the
 *                shadow filter near a face's edge reads real texels; only the inner 90
 *                degrees carry VPLs, so every direction from the light belongs to exactly one
 *                face
 *   directional  one orthographic view along the light, window and depth fitted to the
 *                scene's bounds
 *
 * Perspective views clip at D/128 and D + |light - centre| + D/6.4 (D the bounds'
 * diagonal), so that a 4 cm model and a 4 km site render alike (docs/stability.md). */
#ifndef CAVELIGHT_LIGHT_VIEW_H
#define CAVELIGHT_LIGHT_VIEW_H

#include "frame/frame_params.h"

enum { LIGHT_VIEW_CUBE_FACES = 6, LIGHT_VIEW_CUBE_MARGIN = 3,
       LIGHT_VIEW_MAX = LIGHT_VIEW_CUBE_FACES * FRAME_MAX_LIGHTS };

typedef struct light_view {
    int light;               /* index into frame_params.lights */
    int face;                /* cube face 0..5 (+x, -x, +y, -y, +z, -z); 0 for other types */
    int orthographic;
    float view_projection[16];
    float axis[3];           /* unit: the direction the view looks along */
    float tan_half_fov;      /* perspective: half the image plane's side at distance 1 */
    float vpl_tan;           /* perspective: texels whose image-plane coordinates are within
                                +-vpl_tan carry VPLs (cube faces: 1, the 90 degrees) */
    float extent[2];         /* orthographic: half width and height of the window, metres */
    float window[3][3];      /* orthographic: a corner of the window (outside the bounds) and
                                its two edges, world space: light enters the scene through it */
} light_view;

/* The cone as renderers use it: outer half angle clamped to [0.01, 1.45] rad (the RSM is a
 * perspective view), inner to [0, outer]. */
void light_cone(const frame_light *l, float *outer, float *inner);
/* 1 when the light is enabled and emits (intensity > 0): it gets views and light. */
int light_is_lit(const frame_light *l);
/* The views of every lit light of p, in light then face order; size is the RSM's side in
 * texels (the cube margin is in texels). Returns how many (at most LIGHT_VIEW_MAX). */
int light_views(const frame_params *p, const scene *s, int size, light_view *out);
/* The orthographic view of a directional light travelling along unit d. */
void light_directional_view(const scene *s, const float d[3], light_view *out);
/* How far a directional light along unit d has travelled through the scene's medium when
 * it reaches p: from the bounds' bounding sphere (centre c, radius D/2), dot(p - c, d) + D/2.
 * Absorption counts from there. */
float light_directional_travel(const scene *s, const float d[3], const float p[3]);
/* Why a view receives no light, for the warning that says so: lit says whether any light
 * is lit or any surface emits. */
const char *light_dark_reason(int lit);
/* Power the light sends into the scene, W, its colour's channels averaged: spot
 * I 2 pi (1 - cos outer), point 4 pi I, directional E times its view's window area. 0 when
 * it is not lit. */
double light_power(const frame_light *l, const scene *s);

#endif
