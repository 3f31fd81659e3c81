/* frame_params: everything a render node needs to render one frame, as plain values.
 *
 * The master's parameter store (params.h) is turned into one of these on every node for
 * every frame version; the standalone node fills one from the scene and the command line.
 * Nodes that hold equal frame_params render bit-identical LPVs. frame_params_default()
 * gives the renderer's defaults; lights start from the scene's own. */
#ifndef CAVELIGHT_FRAME_PARAMS_H
#define CAVELIGHT_FRAME_PARAMS_H

#include <stdint.h>

#include "base/setting.h"
#include "frame/ao.h"
#include "scene/scene.h"

enum { FRAME_MAX_LIGHTS = 8 };

typedef enum frame_environment {
    FRAME_ENV_DARK = 0,   /* end-to-end gamma 1.5 */
    FRAME_ENV_DIM = 1,    /* 1.25 */
    FRAME_ENV_OFFICE = 2, /* 1.125 */
} frame_environment;

/* Anti-aliasing of each eye's final image (node/renderer_aa.h). */
typedef enum frame_aa {
    FRAME_AA_OFF = 0,
    FRAME_AA_FXAA = 1,
    FRAME_AA_COUNT
} frame_aa;

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

/* The GI methods' own settings (common/gi/gi_settings.h gives each method's settings their
 * slots and meaning): unset means the setting's default. */
enum { FRAME_GI_SETTINGS_MAX = 48 };
typedef struct frame_gi_setting {
    int32_t set;
    setting_value value;
} frame_gi_setting;

typedef struct frame_params {
    uint64_t version;       /* committed frame version (0 standalone) */
    uint32_t reset_epoch;   /* raised by the master to drop every node's LPV history */
    double time;            /* seconds since the session started */
    float head[16];         /* tracked head pose in CAVE space (column-major) */
    float wand[16];         /* wand pose in CAVE space */
    float navigation[16];   /* CAVE-to-world transform */
    int light_count;
    frame_light lights[FRAME_MAX_LIGHTS];
    /* The frame's settings (frame_transport_settings[], frame_display_settings[]) */
    int lpv_steps;          /* propagation steps per frame */
    float lambda_incr;      /* share of the previous frame's light kept, [0,1) */
    float absorption;       /* per-metre probabilities, [0,1] */
    float scattering;
    frame_environment environment;
    float display_gamma;
    float exposure;         /* linear scale before tone mapping */
    int rsm_size;           /* texels per side of each reflective shadow map */
    int gi;                 /* the indirect-light method: its index in node/gi's registry
                               (gi_settings.h); 0, the first, is ILPV */
    int ldm_layers;         /* layered depth maps (ldm_map.h): depths kept per texel */
    int ldm_memory_mb;      /* their memory cap, per set of maps */
    frame_ao ao;            /* the ambient occlusion (ao.h) */
    float ao_distance;      /* its maximum distance, metres; 0: none */
    frame_ao_falloff ao_falloff;
    int ao_directions;      /* its layered depth maps */
    int ao_resolution;
    float ambient;          /* the ambient light's radiance, W/(m^2 sr); 0: none */
    frame_aa aa;            /* anti-aliasing of the final image */
    /* Interaction state */
    int hud_layout;         /* active interaction layout for the HUD, -1 = no HUD */
    int pattern;            /* 1: screens show the calibration pattern (pattern.h), 0 the scene */
    frame_gi_setting gi_settings[FRAME_GI_SETTINGS_MAX];
} frame_params;

/* The frame's settings, the one place of their names, ranges and defaults (offsets into
 * frame_params): how light travels (steps, lambda, absorption, scattering, rsm, and the
 * layered depth maps' layers and memory cap) and how it is shown (env, display-gamma,
 * exposure, the ambient term and its occlusion: ao.h, anti-aliasing). */
extern const setting frame_transport_settings[];
extern const int frame_transport_setting_count;
extern const setting frame_display_settings[];
extern const int frame_display_setting_count;

/* The one set of defaults (the parameter store, the standalone node and the benchmarks
 * start from it): identity poses, no lights, every frame setting at its default, GI method
 * 0 with every GI setting unset (its default), no HUD, no pattern. */
void frame_params_default(frame_params *p);
/* Copies the scene's lights (at most FRAME_MAX_LIGHTS), enabled. A scene loaded without
 * lights has one already (scene_load(), scene_default_light()). */
void frame_params_lights_from_scene(frame_params *p, const scene *s);
/* The largest intensity frame_params_sanitize() lets through: beyond it float shading
 * overflows. */
#define FRAME_MAX_INTENSITY 1e12f

/* Makes every field but the GI method and its settings usable, in place, whatever a
 * master, a config or a command line sent: a light of an unknown type, or whose position,
 * direction (or a zero one), colour, intensity or angles are not finite, is disabled (a
 * point light's direction means nothing: a zero or non-finite one becomes -y); a non-unit
 * direction is normalized; negative colours and intensities become 0, intensities are
 * capped at FRAME_MAX_INTENSITY; light_count is clamped to [0, FRAME_MAX_LIGHTS];
 * non-finite poses or time get their defaults; pattern becomes 0 unless it is 1; every
 * frame setting is clamped by its row (setting_clamp()).
 * Returns how many fields it changed (0 for valid parameters). The GI method and its
 * settings are node/gi's to check (gi_frame_sanitize(), which calls this): the renderer
 * applies that to its own copy once per frame, in renderer_frame_pass(). */
int frame_params_sanitize(frame_params *p);
/* End-to-end gamma of the environment (paper table 3.1). */
float frame_params_e2e_gamma(frame_environment env);

#endif
