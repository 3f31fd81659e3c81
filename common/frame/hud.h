/* hud: what the wand-referenced HUD shows, as plain values the renderer draws.
 *
 * hud_describe() derives everything from frame_params, so every node computes the same
 * HUD from the same frame version without any extra message:
 *   - three layout indicators on the wand's left side (arrow = navigation, cone =
 *     lighting, torus = renderer settings): white when their layout is active, grey
 *     otherwise; the cone always has the colour of light 0 (the light the lighting layout
 *     moves), and a marker in that colour sits at the light's real pose: a spot's cone
 *     with its opening angle, a point light's star, a directional light's arrow;
 *   - four bars on the wand's right side, values in [0, 1]: absorption (A), scattering
 *     (S), lambda_incr (I, white while incremental rendering is on, lambda > 0) and
 *     propagation steps (P) normalised by the lattice resolution.
 * Positions are world space: navigation * wand. hud_layout < 0 hides the HUD. */
#ifndef CAVELIGHT_HUD_H
#define CAVELIGHT_HUD_H

#include "frame/frame_params.h"

enum { HUD_INDICATOR_COUNT = 3, HUD_BAR_COUNT = 4 };

typedef enum hud_shape { HUD_SHAPE_ARROW = 0, HUD_SHAPE_CONE = 1, HUD_SHAPE_TORUS = 2 } hud_shape;

typedef struct hud_indicator {
    hud_shape shape;       /* indicator i stands for interaction layout i */
    int active;
    float color[3];        /* linear RGB */
} hud_indicator;

typedef struct hud_bar {
    char letter;           /* 'A', 'S', 'I', 'P' */
    float value;           /* [0, 1] */
    float color[3];
} hud_bar;

typedef struct hud {
    int visible;
    int active_layout;
    float wand_world[16];  /* navigation * wand, column-major: the HUD's anchor */
    hud_indicator indicators[HUD_INDICATOR_COUNT];
    hud_bar bars[HUD_BAR_COUNT];
    int has_light;         /* lights[0] exists and is enabled */
    scene_light_type light_type; /* its marker: a spot's cone, a point light's star, a
                                    directional light's arrow */
    float light_position[3];/* world space, where the marker is drawn */
    float light_direction[3];
    float light_angle;     /* a spot's outer half angle, radians: the cone's opening */
} hud;

/* The P bar's scale for a GI method without a lattice: the default ILPV lattice's cells
 * (gi_ilpv.c checks that they agree). */
enum { HUD_DEFAULT_LATTICE_CELLS = 32 };

/* lattice_cells: cells along the lattice's longest axis (normalises the P bar; the GI
 * method's, gi_stats.hud_cells; <= 0: HUD_DEFAULT_LATTICE_CELLS). */
void hud_describe(const frame_params *p, int lattice_cells, hud *out);

#define HUD_GREY 0.5f
#define HUD_WHITE 1.0f

#endif
