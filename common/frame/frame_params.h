/* frame_params: everything a render node needs to render one frame, as plain values.
 *
 * The master's parameter store (params.h) is turned into one of these on every node for
 * every frame version; the standalone node fills one from the scene and the command line.
 * Nodes that hold equal frame_params render bit-identical LPVs. frame_params_default()
 * gives the renderer's defaults; lights start from the scene's own. */
#ifndef CAVELIGHT_FRAME_PARAMS_H
#define CAVELIGHT_FRAME_PARAMS_H

#include <stdint.h>

#include "gi/vpl_selection.h"
#include "scene/scene.h"

enum { FRAME_MAX_LIGHTS = 8 };

typedef enum frame_environment {
    FRAME_ENV_DARK = 0,   /* end-to-end gamma 1.5 */
    FRAME_ENV_DIM = 1,    /* 1.25 */
    FRAME_ENV_OFFICE = 2, /* 1.125 */
} frame_environment;

/* The indirect-light (GI) method every node uses for the frame (node/gi.h). */
typedef enum frame_gi {
    FRAME_GI_ILPV = 0, /* incremental light propagation volumes */
    FRAME_GI_NONE = 1, /* direct light only */
    FRAME_GI_VPL = 2,  /* virtual point lights with a shadow map each */
    FRAME_GI_COUNT
} frame_gi;

/* One light as the master and every node hold it; the fields mean what scene_light's do
 * (units there). */
typedef struct frame_light {
    int enabled;
    float position[3];    /* world space, metres (directional: where the HUD shows it) */
    float direction[3];   /* unit: spot axis, direction a directional light travels */
    float color[3];       /* linear RGB, 0..1 */
    float intensity;      /* spot, point: radiant intensity, W/sr; directional: W/m^2 */
    float outer_angle;    /* spot: radians, half angle where the cone reaches 0 */
    float inner_angle;    /* spot: radians, half angle where the penumbra starts */
    scene_light_type type;
} frame_light;

typedef struct frame_params {
    uint64_t version;       /* committed frame version (0 standalone) */
    uint32_t reset_epoch;   /* raised by the master to drop every node's LPV history */
    double time;            /* seconds since the session started */
    float head[16];         /* tracked head pose in CAVE space (column-major) */
    float wand[16];         /* wand pose in CAVE space */
    float navigation[16];   /* CAVE-to-world transform */
    int light_count;
    frame_light lights[FRAME_MAX_LIGHTS];
    int lpv_steps;          /* propagation steps per frame */
    float lambda_incr;      /* share of the previous frame's light kept, [0,1) */
    float absorption;       /* per-metre probabilities, [0,1] */
    float scattering;
    frame_environment environment;
    float display_gamma;    /* 2.2 by default */
    float exposure;         /* linear scale before tone mapping, 1 by default */
    int hud_layout;         /* active interaction layout for the HUD, -1 = no HUD */
    int pattern;            /* 1: screens show the calibration pattern (pattern.h), 0 the scene */
    frame_gi gi;            /* indirect-light method */
    int vpl_count;          /* vpl: virtual point lights chosen per frame */
    uint32_t vpl_seed;      /* vpl: which random numbers choose them (the same on every node) */
    vpl_selection vpl_selection; /* vpl: the rule that chooses them (vpl_select.h) */
} frame_params;

/* vpl_count's range and default: a few hundred VPLs with a shadow map each is what a
 * software GL renders in about a second at 320x240; 4096 is the paper's upper end. */
enum { FRAME_VPL_MIN = 64, FRAME_VPL_MAX = 4096, FRAME_VPL_DEFAULT = 256 };

/* The one set of defaults (the parameter store, the standalone node and the benchmarks
 * start from it): identity poses, no lights, 8 steps, lambda_incr 0.8, no medium, the dim
 * environment, display gamma 2.2, exposure 1, no HUD, ILPV, FRAME_VPL_DEFAULT VPLs chosen
 * by flux with seed 0. */
void frame_params_default(frame_params *p);
/* Copies the scene's lights (at most FRAME_MAX_LIGHTS), enabled. A scene loaded without
 * lights has one already (scene_load(), scene_default_light()). */
void frame_params_lights_from_scene(frame_params *p, const scene *s);
/* Largest values frame_params_sanitize() lets through: beyond them float shading overflows
 * or a frame never ends. */
#define FRAME_MAX_LPV_STEPS 256
#define FRAME_MAX_INTENSITY 1e12f
#define FRAME_MAX_EXPOSURE 1e6f

/* Makes every field usable, in place, whatever a master, a config or a command line sent:
 * a light of an unknown type, or whose position, direction (or a zero one), colour,
 * intensity or angles are not finite, is disabled (a point light's direction means nothing:
 * a zero or non-finite one becomes -y); a non-unit direction is normalized; negative colours and intensities
 * become 0, intensities are capped at FRAME_MAX_INTENSITY; lambda_incr NaN or < 0 becomes
 * 0 (no history) and >= 1 becomes 0.999; absorption and scattering are clamped to [0,1]
 * (NaN -> 0); lpv_steps to [0, FRAME_MAX_LPV_STEPS]; light_count to [0, FRAME_MAX_LIGHTS];
 * exposure is capped at FRAME_MAX_EXPOSURE; a non-positive or non-finite exposure or
 * display gamma, an unknown environment, GI method or VPL selection rule and non-finite
 * poses or time get their defaults; vpl_count is clamped to [FRAME_VPL_MIN, FRAME_VPL_MAX] (not positive:
 * FRAME_VPL_DEFAULT).
 * Returns how many fields it changed (0 for valid parameters). This is the only place a
 * frame's values are clamped: the renderer applies it to its own copy once per frame, in
 * renderer_frame_pass(). */
int frame_params_sanitize(frame_params *p);
/* The methods' names, indexed by frame_gi (command lines, reports). */
extern const char *const frame_gi_names[FRAME_GI_COUNT];
/* "ilpv", "none", "vpl"; NULL for a value outside the enum. */
const char *frame_gi_name(frame_gi gi);
/* Returns 0 and the method named name, or -1. */
int frame_gi_parse(const char *name, frame_gi *out);
/* End-to-end gamma of the environment (paper table 3.1). */
float frame_params_e2e_gamma(frame_environment env);

#endif
