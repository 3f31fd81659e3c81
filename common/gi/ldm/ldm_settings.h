/* ldm_settings: the ldm method's settings (gi_settings.h), without GL: what every program
 * needs to name, check and send them. The maps' depth per texel and memory cap are the
 * frame's (ldm-layers, ldm-memory: frame_params.h), shared with the AO's maps. */
#ifndef CAVELIGHT_LDM_SETTINGS_H
#define CAVELIGHT_LDM_SETTINGS_H

#include "gi/gi_settings.h"

/* How wide a split photon's footprint grows along its way (gi_ldm.h). */
typedef enum ldm_spread {
    LDM_SPREAD_LIGHT = 0, /* the light's own divergence, the paper's rotated differential */
    LDM_SPREAD_CELL,      /* the cone of its direction's cell, solid angle 2 pi / n: smooth,
                             but the beam's sides are not what its trace checks, and light
                             passes thin walls (docs/stability.md) */
} ldm_spread;

enum { LDM_PHOTONS_MIN = 4, LDM_PHOTONS_MAX = 256 };

typedef struct ldm_settings {
    int directions;          /* maps */
    int resolution;          /* texels per side of each */
    int photons;             /* primary photons per side of each light view's RSM */
    float distance;          /* farthest a split photon travels, metres; 0: any */
    ldm_spread spread;
} ldm_settings;

extern const gi_method_settings ldm_settings_table;

/* NULL, or one line when the frame's AO maps (ao ldm: layered depth maps whatever the
 * method) exceed ldm-memory; the settings' check asks it first. */
const char *ldm_ao_check(const frame_params *p);
/* The frame's ldm settings. */
void ldm_settings_get(const frame_params *p, ldm_settings *out);

#endif
