/* ldm_photons: the ldm method's primary photons, without GL: where the light first met a
 * surface, each to be split into one photon per map direction (gi_ldm.h).
 *
 * An RSM layer is cut into side x side blocks of texels; a block's lit texels make one
 * photon: their flux summed (what the surface reflects, W), their position and normal
 * averaged with the flux as weight, their areas (vpl_texel_area()) summed into the
 * footprint, a disk of the same area. An emissive triangle is one photon of flux
 * pi L_e A at its centroid (as the other methods count emitters). Blocks in texel order,
 * layers in view order: deterministic. */
#ifndef CAVELIGHT_LDM_PHOTONS_H
#define CAVELIGHT_LDM_PHOTONS_H

#include <stddef.h>

#include "gi/ldm/ldm_settings.h"
#include "gi/ldm/ldm_map.h"
#include "gi/vpl_source.h"

/* As the trace shader reads it (std430: three vec4). */
typedef struct ldm_photon {
    float position[3], radius;    /* the footprint: a disk of this radius on its surface */
    float normal[3], weight;      /* unit, the lit side; weight: 1 / the sum over the maps
                                     of |n . d|, each split photon's share per cosine */
    float flux[3], spread;        /* W reflected; how much the footprint's radius grows per
                                     metre of the split photon's way */
} ldm_photon;

/* The photons of one RSM layer (position, normal, flux: 4 floats per texel, row by row,
 * size^2 texels) in side^2 blocks (side <= size; a block is size / side texels wide, the
 * last ones take the rest) into out (room for side^2). light: the light's position, for the
 * light spread (NULL: parallel light). Returns how many blocks had light. */
size_t ldm_photons_from_rsm(const float *position, const float *normal, const float *flux,
                            int size, int side, const float *light, ldm_photon *out);
ldm_photon ldm_photon_from_emitter(const vpl_emitter *e);
/* Each photon's weight for the maps, and its spread: the cone of a direction cell
 * (cos = 1 - 1 / count) or, for LDM_SPREAD_LIGHT, what from_rsm measured (an emitter:
 * the cell's). */
void ldm_photons_finish(ldm_photon *p, size_t n, const ldm_map *maps, int count,
                        ldm_spread spread);

#endif
