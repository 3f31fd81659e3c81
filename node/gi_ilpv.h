/* gi_ilpv: the GI method "ilpv", incremental light propagation volumes (paper section 3),
 * behind gi.h.
 *
 * frame(): the RSM texels of every light become VPLs (read back in a fixed order) and one
 * VPL per emissive triangle is added; they are injected on the host (lpv_inject.h), then
 * merged with last frame's light and propagated by the CPU core (ilpv.h, lpv_classic.h in
 * classic mode) or by GL compute shaders (shaders/merge.comp, propagate.comp,
 * accumulate.comp); the checksum is lpv_volume_checksum() of the result. reuse(): the
 * inputs are unchanged and the result has converged (lpv_converge.h). eye_bind(): the
 * three SH textures and the lattice's placement and level for shaders/shade.frag.
 *
 * The functions below inspect the method's state (the renderer's renderer_get_lpv() and
 * friends forward to them): the resolved backend, the lattice, the propagated light (host
 * memory), the indirect scale, the convergence figures, and one step's cost. */
#ifndef CAVELIGHT_GI_ILPV_H
#define CAVELIGHT_GI_ILPV_H

#include "gi_method.h"
#include "lpv/lattice.h"
#include "lpv/lpv_volume.h"

extern const gi_method gi_ilpv_method;

typedef struct gi_ilpv gi_ilpv;

renderer_lpv_backend gi_ilpv_backend(const gi_ilpv *l);
renderer_lpv_mode gi_ilpv_mode(const gi_ilpv *l);
const lattice_desc *gi_ilpv_lattice(const gi_ilpv *l);
const lpv_volume *gi_ilpv_volume(const gi_ilpv *l);
float gi_ilpv_indirect_scale(const gi_ilpv *l);
void gi_ilpv_lpv_stats(const gi_ilpv *l, renderer_lpv_stats *out);
/* Milliseconds per propagation step (renderer_measure_step_ms()); forgets the history. */
double gi_ilpv_measure_step_ms(gi_ilpv *l, int steps);

#endif
