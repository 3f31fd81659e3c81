/* gi_none: the GI method "none": direct light only, or a constant indirect irradiance
 * (none-irradiance). Its checksum is a constant per setting (it has no view-independent
 * state to disagree about). */
#ifndef CAVELIGHT_GI_NONE_H
#define CAVELIGHT_GI_NONE_H

#include "gi/gi_method.h"

extern const gi_method gi_none_method;

#endif
