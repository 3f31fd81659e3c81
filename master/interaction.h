/* interaction: the wand's interaction layouts (paper, appendix "User Interaction").
 *
 * Three layouts, switched round-robin by the R button:
 *   navigation  C: fly along the wand's pointing direction (-Z of the wand) at
 *                  v = 1.4 m/s * (d / 0.4 m)^2.5, d = wand-to-head distance in the
 *                  horizontal plane (the head projected to the wand's height);
 *               L: hold and turn the wand to turn the CAVE about the vertical through the
 *                  head (yaw only, so the floor stays level); M: reset the navigation.
 *   lighting    C: the spotlight follows the wand like a flashlight; M/L: intensity up and
 *                  down by a factor per press; Y: hue, X: saturation (HSV, value kept).
 *   settings    M/L: propagation steps up/down; X: absorption; Y: scattering;
 *               AUX: next lambda_incr preset; C: next GI method (the registry's order, round-robin:
 *               the paper's "switch pipeline", live on every node in the same frame).
 *   grab        (only with desc.grab: a scene with objects) C: pick the object under the
 *                  wand's ray and carry it while held (grab.h; the session does it).
 * CAVE space is Y up; navigation is the CAVE-to-world transform.
 *
 * interaction_update() applies one input state to the frame parameters and returns the
 * INTERACTION_CHANGED_* bits of the fields whose values actually changed, so that the
 * master sends updates only when something changed. */
#ifndef CAVELIGHT_INTERACTION_H
#define CAVELIGHT_INTERACTION_H

#include <stdint.h>
#include "frame/frame_params.h"
#include "input/input_state.h"

typedef enum interaction_layout {
    INTERACTION_NAVIGATION = 0,
    INTERACTION_LIGHTING = 1,
    INTERACTION_SETTINGS = 2,
    INTERACTION_GRAB = 3,       /* after settings, with desc.grab only */
    INTERACTION_LAYOUT_COUNT = 4
} interaction_layout;

enum {
    INTERACTION_CHANGED_HEAD = 1u << 0,       /* frame_params.head */
    INTERACTION_CHANGED_WAND = 1u << 1,       /* frame_params.wand */
    INTERACTION_CHANGED_NAVIGATION = 1u << 2, /* frame_params.navigation */
    INTERACTION_CHANGED_LIGHT = 1u << 3,      /* lights[desc.light] (and light_count) */
    INTERACTION_CHANGED_STEPS = 1u << 4,      /* lpv_steps */
    INTERACTION_CHANGED_ABSORPTION = 1u << 5,
    INTERACTION_CHANGED_SCATTERING = 1u << 6,
    INTERACTION_CHANGED_LAMBDA = 1u << 7,     /* lambda_incr */
    INTERACTION_CHANGED_GI = 1u << 8,         /* gi */
    INTERACTION_CHANGED_LAYOUT = 1u << 9,     /* hud_layout */
};

enum { INTERACTION_LAMBDA_PRESETS = 4 };

typedef struct interaction_desc {
    float speed;              /* m/s at the reference distance, 0 = 1.4 */
    float reference_distance; /* m, 0 = 0.4 */
    float exponent;           /* 0 = 2.5 */
    float max_distance;       /* d is clamped to this, m, 0 = 1.0 (caps the speed) */
    float intensity_step;     /* factor per M/L press, 0 = sqrt(2) */
    float hue_rate;           /* hue turns per second at full Y, 0 = 0.25 */
    float saturation_rate;    /* per second at full X, 0 = 0.5 */
    float medium_rate;        /* absorption/scattering per second at full axis, 0 = 0.25 */
    float dead_zone;          /* axis values below this are 0, 0 = 0.15 */
    int steps_min, steps_max; /* 0 = 1 and 64 */
    int light;                /* index of the flashlight spot, default 0 */
    float lambda_presets[INTERACTION_LAMBDA_PRESETS]; /* all 0 = {0, 0.5, 0.8, 0.9} */
    interaction_layout first_layout;
    int grab;                 /* 1: R cycles through the grab layout too */
} interaction_desc;

/* Plain state, owned by the caller; initialise with interaction_init(). */
typedef struct interaction {
    interaction_desc desc;    /* with defaults filled in */
    interaction_layout layout;
    int dragging;
    float drag_navigation[16];
    float drag_yaw;
    float drag_pivot[3];
    int hsv_known;
    float hue, saturation, value;
} interaction;

void interaction_init(interaction *ia, const interaction_desc *desc);
/* dt: seconds since the previous update (input_state.dt). Returns INTERACTION_CHANGED_*. */
uint32_t interaction_update(interaction *ia, const input_state *in, double dt, frame_params *p);

/* The maths, exposed for tests and the HUD. */
float interaction_speed(const interaction_desc *desc, float distance);
/* h in turns [0,1), s and v in [0,1]. */
void interaction_hsv_to_rgb(float h, float s, float v, float rgb[3]);
void interaction_rgb_to_hsv(const float rgb[3], float *h, float *s, float *v);

#endif
