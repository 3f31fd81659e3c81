/* lpv_paper_step: the `paper` transport's step (lpv_paper.h) on the CPU, the kernel behind
 * lpv_propagate_step() when desc->transport is LPV_TRANSPORT_PAPER. Internal to
 * common/gi/ilpv: call lpv_propagate_step(), which checks the arguments. */
#ifndef CAVELIGHT_LPV_PAPER_STEP_H
#define CAVELIGHT_LPV_PAPER_STEP_H

#include "gi/ilpv/lpv_step.h"

/* Arguments already checked: same shapes, 12 channels, distinct volumes. */
void lpv_paper_step(const lpv_propagate_desc *desc, const lpv_volume *src, lpv_volume *dst);

/* Floating-point operations per cell of one step (multiply-adds count 2). */
double lpv_paper_step_flops_per_cell(void);

#endif
