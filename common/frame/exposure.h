/* exposure: an exposure derived from a scene's light, for pictures that are neither dark
 * nor burnt out whatever the scene's units.
 *
 * The estimate spreads the power of every lit light (light_power()) and every emissive
 * surface (pi L A) evenly over all the scene's surfaces and takes one diffuse bounce:
 * the average surface radiance is L = albedo * power / (pi * area), albedo the
 * area-weighted mean of the materials' base colour factors (textures are not read). The
 * exposure puts that radiance at EXPOSURE_KEY, the photographic middle grey of Reinhard
 * et al.'s key value (2002), before the L/(1+L) tone map. It only scales the final image:
 * the indirect light, checksums and the reference's radiance are not touched. */
#ifndef CAVELIGHT_EXPOSURE_H
#define CAVELIGHT_EXPOSURE_H

#include "frame/frame_params.h"

#define EXPOSURE_KEY 0.18

/* The exposure for p's lights in s, within the exposure setting's range; 1 when nothing emits or s
 * has no surface. */
float exposure_from_light(const frame_params *p, const scene *s);

#endif
