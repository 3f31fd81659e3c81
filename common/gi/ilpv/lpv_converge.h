/* lpv_converge: when may a frame reuse the last LPV result instead of computing it.
 *
 * A frame may be skipped (no RSM, injection or propagation) when its LPV inputs equal the
 * previous frame's (every field of the first light_count lights, light_count, lpv_steps,
 * lambda_incr, absorption, scattering, reset_epoch; floats compared with ==, so a NaN is
 * never equal and never skips) and the last computed frame's residual
 *   sum |L_i - L_{i-1}| / sum |L_i|   over all cells and channels
 * is below the threshold. The residual is summed per z slice in double and the slices in
 * order, so it has the same bits for any thread count: cluster nodes with equal inputs
 * skip the same frames. Before two computed frames the residual is +Inf; a black result
 * after a black one has residual 0. */
#ifndef CAVELIGHT_LPV_CONVERGE_H
#define CAVELIGHT_LPV_CONVERGE_H

#include "frame/frame_params.h"
#include "gi/ilpv/lpv_volume.h"
#include "base/workpool.h"

#define LPV_CONVERGE_DEFAULT_THRESHOLD 1e-4

typedef struct lpv_converge {
    double threshold;     /* resolved: > 0 skips below it, < 0 never skips */
    lpv_volume previous;  /* the last computed result */
    double *slice_sums;   /* 2 per z slice: sum |L_i - L_{i-1}|, sum |L_i| */
    frame_params last;    /* inputs of the last frame, computed or skipped */
    int have_last, have_previous;
    double residual;      /* of the last computed frame */
    long frames_skipped;  /* total */
    int skipped;          /* the last frame was skipped */
} lpv_converge;

/* threshold: 0 = the default 1e-4, negative = never skip (the residual is still measured).
 * Returns 0, or -1 for bad sizes or no memory. */
int lpv_converge_init(lpv_converge *c, const int n[3], double threshold);
void lpv_converge_free(lpv_converge *c);
/* 1 if the LPV inputs of a and b are equal: every method's (gi_reuse_inputs_equal()), then
 * lpv_steps and lambda_incr. */
int lpv_converge_inputs_equal(const frame_params *a, const frame_params *b);
/* Before a frame: decides whether it is skipped (counted and remembered in `skipped`) and
 * records p as the last inputs. */
int lpv_converge_begin(lpv_converge *c, const frame_params *p);
/* The last result is gone (overwritten): the next frame is computed, and so is the one
 * after it (no residual until then). */
void lpv_converge_forget(lpv_converge *c);
/* After a computed frame: the residual against the previous result, or `pending` when
 * that is larger (the share of the result its source says the next frame may still change:
 * light still in flight, an old picture still fading; 0 when nothing is pending); result
 * becomes the previous one. */
double lpv_converge_end(lpv_converge *c, const lpv_volume *result, double pending,
                        workpool *pool);

#endif
