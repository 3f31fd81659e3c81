/* gi_ldm: the GI method "ldm", single-bounce indirect light through layered depth maps
 * (Aalund, Frisvad and Baerentzen's photon splitting), behind gi.h.
 *
 * create(): ldm-directions maps of ldm-resolution^2 texels, ldm-layers deep (node/gi/ldm/ldm_gl.h:
 * the deterministic equal-area directions, a k-buffer per map), built once: the scene
 * never moves. Refused with one line over ldm-memory.
 * frame(): primary photons from every light view's RSM in ldm-photons^2 blocks and from
 * the emissive triangles (ldm_photons.h); each split into one photon per map, traced along
 * the map's direction on its normal's side to the first surface (ldm_split.comp, one slot
 * per photon and map). READY carries the FNV-1a of the split photons with the maps'
 * checksum.
 * eye_bind(): the split photons splatted over the eye's G-buffer (ldm_splat.vert/.frag:
 * each a beam of its footprint, widening by its spread, lighting the points inside it
 * that face it and see its origin back through its own map; additive) into an
 * irradiance texture its shading snippet (ldm_shade.glsl) reads.
 * reuse(): a frame whose lights, medium and ldm settings are the last frame's keeps its
 * photons, unless the renderer computes every frame (gi_desc.no_reuse: then the maps are
 * rebuilt every frame too, so the benchmark's construct figure is what a moving scene
 * would pay).
 *
 * Stages (stats): construct (the maps, when built this frame), photons (RSM read-back and
 * blocks), trace (the split: trace and write in one pass). Figures: splat_ms (the last
 * eye), memory_mb, overflow (depths the maps could not hold), photons, splits (non-empty
 * split photons). */
#ifndef CAVELIGHT_GI_LDM_H
#define CAVELIGHT_GI_LDM_H

#include "gi/gi_method.h"

extern const gi_method gi_ldm_method;

#endif
