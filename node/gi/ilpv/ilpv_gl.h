/* ilpv_gl: the ILPV's GL compute backend (ilpv.h's ilpv_backend): the chain's front and sum
 * as 3D textures (one per colour, four SH coefficients each), one step per dispatch of
 * propagate.comp (the CPU step's rule, lpv_propagate.h), sums by accumulate.comp. The
 * splat comes from the host; the sum goes back to the host for the driver's composition.
 * For the `paper` transport, the thesis's frame (lpv_paper_frame.h) instead: the merge by
 * accumulate.comp, the steps by paper_propagate.comp, the result back to the host.
 * Also the two host <-> texture copies the method's shading needs. Not here: the frame's
 * sequence (ilpv.c), the injection, the shading. */
#ifndef CAVELIGHT_ILPV_GL_H
#define CAVELIGHT_ILPV_GL_H

#include <stddef.h>

#include "gl/gl_functions.h"
#include "gi/ilpv/ilpv.h"
#include "gi/ilpv/lattice.h"
#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_paper_frame.h"
#include "gi/ilpv/lpv_propagate.h"

typedef struct ilpv_gl ilpv_gl;

typedef struct ilpv_gl_variant {
    lpv_transport transport;
    int tiles; /* beams: the shared-memory variant of the step (fast on a GPU, slow on
                  llvmpipe) */
} ilpv_gl_variant;

/* NULL with one line in err. */
ilpv_gl *ilpv_gl_create(const gl_functions *gl, const lattice_desc *lat,
                        const lpv_blockers *blockers, const ilpv_gl_variant *v, char *err,
                        size_t errlen);
void ilpv_gl_destroy(ilpv_gl *g);
/* The blockers again (objects moved), as create() took them. */
void ilpv_gl_update_blockers(ilpv_gl *g, const lpv_blockers *blockers);
/* beams: as a backend; ilpv_free() destroys it. */
ilpv_backend ilpv_gl_backend(ilpv_gl *g);

/* paper: one frame, L = m.a L + m.b injected, `steps` steps of L (no blocking in the first,
 * lpv_paper_frame()), L into result (host, 12 channels). */
void ilpv_gl_paper_frame(ilpv_gl *g, const lpv_volume *injected, lpv_paper_merge m, int steps,
                         float absorption, float scattering, lpv_volume *result);
/* paper: `steps` steps of L alone; block_first 0 leaves the first unblocked. */
void ilpv_gl_paper_steps(ilpv_gl *g, int steps, int block_first, float absorption, float scattering);

/* A host volume (12 channels) into three RGBA32F 3D textures of its size, and back;
 * scratch holds 4 floats per cell. */
void ilpv_gl_upload(const gl_functions *gl, const lpv_volume *v, const GLuint tex[3], float *scratch);
void ilpv_gl_download(const gl_functions *gl, const GLuint tex[3], lpv_volume *v, float *scratch);

#endif
