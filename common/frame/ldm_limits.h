/* ldm_limits: the ranges of the layered depth maps' settings and the maps' memory. The
 * frame's own rows (ldm-layers, ao-directions, ao-resolution in frame_params.c), the AO's
 * cost (gi/gi_cost.c) and the ldm method's maps (gi/ldm/ldm_map.h, ldm_directions.h)
 * take them from here, so neither the frame nor the costs need a GI method's header. */
#ifndef CAVELIGHT_LDM_LIMITS_H
#define CAVELIGHT_LDM_LIMITS_H

/* Map resolution (texels per side) and depths kept per texel. */
enum { LDM_RESOLUTION_MIN = 32, LDM_RESOLUTION_MAX = 512, LDM_LAYERS_MIN = 1,
       LDM_LAYERS_MAX = 32 };
/* The settings' range of maps, 16..512; ldm_directions() takes any count from 1 (a
 * single cap). */
enum { LDM_DIRECTIONS_MIN = 16, LDM_DIRECTIONS_MAX = 512 };

/* The k-buffer's bytes: directions x resolution^2 x layers x 4. */
static inline double ldm_limits_memory_bytes(int directions, int resolution, int layers)
{
    return (double)directions * resolution * resolution * layers * 4.0;
}

#endif
