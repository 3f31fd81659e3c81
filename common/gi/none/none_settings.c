/* none: direct light and a constant indirect irradiance (0, the default: none at all). */
#include "gi/none/none_settings.h"

#include <stddef.h>

#define FIELD(f) offsetof(none_settings, f)
static const setting rows[] = {
    {"none-irradiance", "E", SETTING_FLOAT, 0, 1e6, 0, NULL, 0, 0, FIELD(irradiance),
     "none: a constant indirect irradiance on every surface,\nW/m^2 (the classic ambient term; 0: direct light only)"},
};
#undef FIELD

const gi_method_settings none_settings_table = {
    .name = "none",
    .summary = "direct light only, or a constant indirect term",
    .rows = rows,
    .count = (int)(sizeof rows / sizeof rows[0]),
    .struct_size = sizeof(none_settings),
};

void none_settings_get(const frame_params *p, none_settings *out)
{
    gi_settings_read(GI_METHOD_ID(none), p, out);
}
