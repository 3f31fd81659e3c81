/* renderer_hud: where the wand-referenced HUD (common/frame/hud.h) sits in the world.
 *
 * The HUD is a small panel in the wand's frame (the wand points along its -Z, +X is its
 * right, +Y its up), RENDERER_HUD_DISTANCE in front of the wand's origin and facing the
 * user behind it: the three layout indicators (arrow, cone, torus; top to bottom) on the
 * left, the bars A, S, I, P (top to bottom) on the right, each growing along the wand's
 * +X from its start by value * RENDERER_HUD_BAR_LENGTH, with its letter between. Light 0
 * gets a marker at its real pose: a spot's cone opened by its outer angle, a point
 * light's star, a directional light's arrow along its direction.
 * The renderer draws this in world space with each eye's view and projection, so it
 * appears at the right stereo depth on every screen; renderer_hud_layout() gives the same
 * positions to callers (tests, picking). */
#ifndef CAVELIGHT_RENDERER_HUD_H
#define CAVELIGHT_RENDERER_HUD_H

#include "frame/hud.h"
#include "gl/gl_functions.h"

#define RENDERER_HUD_DISTANCE 0.12f   /* panel in front of the wand origin, metres */
#define RENDERER_HUD_BAR_LENGTH 0.12f /* a bar at value 1 */
#define RENDERER_HUD_LIGHT_MARKER 0.08f /* size of the marker drawn at light 0 */

typedef struct renderer_hud renderer_hud;

/* Program and meshes on the current context. Returns NULL with one line in err. */
renderer_hud *renderer_hud_create(const gl_functions *gl, char *err, size_t errlen);
void renderer_hud_destroy(renderer_hud *h);
/* Into the bound framebuffer (depth-tested against what it holds), if p->hud_layout >= 0;
 * lattice_cells: the resolution the settings bar shows (0 when the GI method has none). */
void renderer_hud_draw(renderer_hud *h, const frame_params *p, int lattice_cells,
                       const float view_projection[16], const float eye[3], float encoding_gamma);

typedef struct renderer_hud_places {
    float indicator[HUD_INDICATOR_COUNT][3]; /* world centre of each indicator */
    float bar_start[HUD_BAR_COUNT][3];       /* world point where each bar starts */
    float bar_axis[3];                       /* unit world direction the bars grow in */
    float panel_corner[8][3];                /* world box around everything near the wand */
} renderer_hud_places;

void renderer_hud_layout(const hud *h, renderer_hud_places *out);

/* A wand pose (CAVE = world when navigation is identity) that puts the HUD panel on a
 * view's axis, 0.42 m ahead of the eye, the wand pointing where the view looks. view is
 * world-to-eye and rigid (as offaxis_look_at() and offaxis_screen() give). */
void renderer_hud_wand_in_front(const float view[16], float wand[16]);

#endif
