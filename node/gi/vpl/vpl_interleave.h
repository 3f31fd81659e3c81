/* vpl_interleave: interleaved sampling of the vpl method's gather (gi_vpl.h; Keller and
 * Heidrich 2001, Segovia et al. 2006, as the many-light thesis 3.4 and 4.5 use it).
 *
 * The VPLs split into k x k subsets (VPL i in subset i mod k^2: every subset a stratified
 * share of the flux-ordered slots); pixel (x, y) gathers subset (x mod k) + k (y mod k)
 * only, scaled by N / its size, so each pixel's estimate stays unbiased at 1/k^2 of the
 * cost. The gather runs de-interleaved (vpl_deinterleave.frag with vpl_gather.glsl: the
 * G-buffer's pixels of one subset side by side, so neighbouring fragments read the same
 * VPLs and maps); vpl_blur.frag re-interleaves and averages each pixel's k x k
 * window, every subset once, weighting a neighbour by the cosine between the normals and
 * only when it lies within a pixel's footprint of the pixel's tangent plane: the
 * structured noise goes, depth and normal edges stay. k = 1 is the plain gather.
 * The method's shading snippet then reads the result (u_vpl_irradiance) instead of
 * gathering.
 *
 * Not here: which VPLs and maps (gi_vpl.c binds them on the gather program). GL only. */
#ifndef CAVELIGHT_VPL_INTERLEAVE_H
#define CAVELIGHT_VPL_INTERLEAVE_H

#include <stddef.h>

#include "gi/gi_method.h"

typedef struct vpl_interleave vpl_interleave;

/* k x k blocks, 1..VPL_INTERLEAVE_MAX. NULL with one line in err. */
vpl_interleave *vpl_interleave_create(const gl_functions *gl, int block, char *err,
                                      size_t errlen);
void vpl_interleave_destroy(vpl_interleave *il);
/* The de-interleaved gather: the caller makes it current and binds the VPL uniforms,
 * samplers and textures on it as on the shading program, then calls vpl_interleave_run(). */
GLuint vpl_interleave_program(const vpl_interleave *il);
/* Gather and blur for eye e (its G-buffer on units 0 and 1); then e's program, framebuffer
 * and viewport are current again and the result is bound on texture unit `unit`. */
void vpl_interleave_run(vpl_interleave *il, const gi_eye *e, int unit);

#endif
