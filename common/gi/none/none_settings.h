/* none_settings: the none method's one setting (gi_settings.h), without GL. The none
 * method is the skeleton a new method starts from (node/gi/none/gi_none.c says how). */
#ifndef CAVELIGHT_NONE_SETTINGS_H
#define CAVELIGHT_NONE_SETTINGS_H

#include "gi/gi_settings.h"

typedef struct none_settings {
    float irradiance;        /* constant indirect irradiance, W/m^2, on every surface */
} none_settings;

extern const gi_method_settings none_settings_table;

/* The frame's none settings. */
void none_settings_get(const frame_params *p, none_settings *out);

#endif
