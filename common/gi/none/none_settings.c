/* none: direct light only; it has no settings of its own. */
#include "gi/gi_settings.h"

const gi_method_settings none_settings_table = {
    .name = "none",
    .summary = "direct light only",
};
