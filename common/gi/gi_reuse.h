/* gi_reuse: when a GI method may keep the last frame's result instead of computing it.
 *
 * Every method's frame depends on the lights, the medium and the master's reset epoch
 * (gi_reuse_inputs_equal()) and on its own settings; some also on what else they name
 * (vpl's and caches' view rules: the viewer). A method keeps one gi_reuse and asks
 * gi_reuse_unchanged() in its reuse(). Floats are compared with ==, so a NaN is never
 * equal and never reuses. No GL. Not here: ILPV's convergence rule (lpv_converge.h), which
 * adds its own fields and a residual. */
#ifndef CAVELIGHT_GI_REUSE_H
#define CAVELIGHT_GI_REUSE_H

#include <stddef.h>

#include "frame/frame_params.h"

typedef struct gi_reuse {
    int never;             /* gi_desc.no_reuse: every frame is computed (to measure it) */
    int have_last;
    frame_params last;     /* the last frame's parameters, computed or reused */
} gi_reuse_state;

/* 1 when a and b light the scene alike: the same light count and every field of those
 * lights, the same absorption and scattering, the same reset epoch. */
int gi_reuse_inputs_equal(const frame_params *a, const frame_params *b);
/* 1 when the last result stands for p: a last frame exists, reuse is allowed, the frame
 * inputs are equal, the method's settings now (size bytes) equal *kept, and same (the
 * method's own condition, computed against r->last) holds. Then p becomes r->last and now
 * is copied into *kept, whatever the answer. */
int gi_reuse_unchanged(gi_reuse_state *r, const frame_params *p, const void *now, void *kept,
                       size_t size, int same);

#endif
