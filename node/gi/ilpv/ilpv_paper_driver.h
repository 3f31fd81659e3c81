/* ilpv_paper_driver: the ILPV method's `paper` transport (--lpv-transport paper): the
 * thesis's frame (lpv_paper_frame.h) on the CPU (lpv_paper_frame()) or on GL (ilpv_gl.h's
 * paper functions: merge, steps, the result read back), incremental, or classic with
 * lambda_incr 0 every frame. The result is always in host memory, for the checksum and
 * the shading's textures. Not here: the injection (the caller fills
 * ilpv_paper_driver_injection() without origins or splat), the receiver (ilpv_shade.glsl). */
#ifndef CAVELIGHT_ILPV_PAPER_DRIVER_H
#define CAVELIGHT_ILPV_PAPER_DRIVER_H

#include <stddef.h>

#include "base/workpool.h"
#include "gi/ilpv/ilpv_gl.h"
#include "gl/gl_functions.h"
#include "gi/ilpv/lpv_paper_frame.h"

typedef struct ilpv_paper_driver {
    lpv_paper_lpv lpv;            /* CPU: all of it; GL: the injection, the history rule and
                                     the result read back (volume[0]) */
    ilpv_gl *gl;                  /* NULL on the CPU */
    const lpv_blockers *blockers;
    workpool *pool;
} ilpv_paper_driver;

typedef struct ilpv_paper_driver_frame {
    int steps;
    float lambda_incr;            /* 0 for classic LPV */
    double emitted_energy;        /* the lights' E from their parameters */
    float absorption, scattering; /* per metre, as the frame's parameters */
} ilpv_paper_driver_frame;

/* gl NULL: the CPU. Returns 0, or -1 with one line in err. */
int ilpv_paper_driver_init(ilpv_paper_driver *d, const gl_functions *gl, const lattice_desc *lat,
                           const lpv_blockers *blockers, workpool *pool, char *err, size_t errlen);
void ilpv_paper_driver_free(ilpv_paper_driver *d);
void ilpv_paper_driver_reset(ilpv_paper_driver *d);
/* Cleared for this frame. */
lpv_volume *ilpv_paper_driver_injection(ilpv_paper_driver *d);
void ilpv_paper_driver_run(ilpv_paper_driver *d, const ilpv_paper_driver_frame *f);
const lpv_volume *ilpv_paper_driver_result(const ilpv_paper_driver *d);
/* `steps` blocked steps of the current volume without absorption or scattering (a
 * benchmark's timing; GL work is not waited for). Forgets the history. */
void ilpv_paper_driver_steps(ilpv_paper_driver *d, int steps);

#endif
