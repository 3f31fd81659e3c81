/* gi_ilpv: the GI method "ilpv", incremental light propagation volumes (paper section 3),
 * behind gi.h.
 *
 * frame(): the RSM texels of every light become VPLs (read back in a fixed order) and one
 * VPL per emissive triangle is added; they are injected on the host (lpv_inject.h), and
 * the ILPV driver (gi/ilpv/ilpv.h: the history rule, the splat, the chain, the composition;
 * classic mode with --lpv-mode classic) propagates them on the CPU (lpv_propagate.h) or
 * with GL compute shaders (ilpv_gl.h); the checksum is lpv_volume_checksum() of the result,
 * which three SH textures hold for the shading. reuse(): the inputs are unchanged and the
 * result has converged (lpv_converge.h). eye_bind(): those textures and the lattice's
 * placement for its snippet (ilpv_shade.glsl). Its settings: ilpv_settings.h.
 *
 * The functions below inspect the method's state, for tests and benchmarks: the resolved
 * backend, the lattice, the propagated light (host memory), the convergence figures, and
 * one step's cost. */
#ifndef CAVELIGHT_GI_ILPV_H
#define CAVELIGHT_GI_ILPV_H

#include "gi/gi.h"
#include "gi/ilpv/ilpv_settings.h"
#include "gi/ilpv/lattice.h"
#include "gi/ilpv/lpv_volume.h"

extern const gi_method gi_ilpv_method;

typedef struct gi_ilpv gi_ilpv;

typedef struct gi_ilpv_stats {
    long frames_skipped;      /* frame passes skipped since creation */
    double last_residual;     /* relative L1 change of the last computed frame's result,
                                 +Inf before two computed frames */
    int skipped_this_frame;   /* the last frame pass was skipped */
    double injected_energy[3]; /* <L|1> of the last computed frame's injection, per colour:
                                  the flux of its VPLs (W) */
} gi_ilpv_stats;

/* The method's state when g runs ILPV, else NULL. */
gi_ilpv *gi_ilpv_of(gi *g);
ilpv_backend_choice gi_ilpv_backend(const gi_ilpv *l); /* resolved: never AUTO */
ilpv_mode gi_ilpv_mode(const gi_ilpv *l);
lpv_transport gi_ilpv_transport(const gi_ilpv *l);
const lattice_desc *gi_ilpv_lattice(const gi_ilpv *l);
/* The propagated light after the last frame (12 channels, host memory). */
const lpv_volume *gi_ilpv_volume(const gi_ilpv *l);
void gi_ilpv_stats_get(const gi_ilpv *l, gi_ilpv_stats *out);
/* Milliseconds per propagation step on this backend and lattice (blocking on), timed over
 * `steps` steps after one untimed step, GL work finished before the clock stops. It
 * overwrites the chain: the next frame pass starts without history and is never skipped. */
double gi_ilpv_measure_step_ms(gi_ilpv *l, int steps);

#endif
