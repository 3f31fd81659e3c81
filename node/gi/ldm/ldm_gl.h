/* ldm_gl: layered depth maps (LDMs) on the GPU: n maps in the deterministic directions of
 * ldm_directions.h, each a k-buffer of res^2 texels holding the `layers` smallest depths
 * of the surfaces over its centre, sorted (common/gi/ldm/ldm_map.h: where they lie, what
 * they cost).
 *
 * Built in one pass over the scene per map into a shader storage buffer: the scene's
 * triangles, both sides, through the map's orthographic projection into a framebuffer
 * without attachments; each fragment inserts its depth with atomic minima down its
 * texel's list (shaders/ldm_build.frag), so the lists do not depend on the order the GPU
 * rasterizes in, and a depth that does not fit is counted. Traced by
 * shaders/ldm_trace.glsl, which a program includes and ldm_gl_bind() feeds.
 *
 * Why a k-buffer and not per-pixel linked lists (the paper's): its memory is known before
 * it is built, so the memory cap (ldm-memory) is checked when the settings are read, not
 * after a frame ran out; one pass builds it already sorted, with no node pool, no
 * allocation counter and no sort pass; and its content is the same on every node. What
 * it costs: a texel with more than `layers` surfaces keeps the nearest only (the map
 * looks from the +d side), which `overflow` counts.
 *
 * The maps hold the scene's triangles where scene_gl draws them (its objects' poses) when
 * ldm_gl_build() runs: its owner builds them again when objects move. Their bounding
 * sphere is the scene's as loaded (ldm_layout_init()): what moves outside it is clipped. */
#ifndef CAVELIGHT_LDM_GL_H
#define CAVELIGHT_LDM_GL_H

#include <stddef.h>
#include <stdint.h>

#include "gl/gl_functions.h"
#include "gi/ldm/ldm_map.h"
#include "gl/scene_gl.h"

typedef struct ldm_gl ldm_gl;

/* The maps' buffers for layout l (its memory checked by the caller); NULL with one line in
 * err. */
ldm_gl *ldm_gl_create(const gl_functions *gl, const ldm_layout *l, char *err, size_t errlen);
void ldm_gl_destroy(ldm_gl *m);
/* Renders every map from mesh (scene_gl_draw_geometry(): hidden objects left out); GL
 * finished. Returns the host ms it took (the checksum's read-back after it not counted). */
double ldm_gl_build(ldm_gl *m, const scene_gl *mesh);
const ldm_layout *ldm_gl_layout(const ldm_gl *m);
/* The bases of its maps (layout.directions). */
const ldm_map *ldm_gl_maps(const ldm_gl *m);
/* After a build: FNV-1a of every list (read back), and the depths that did not fit. */
uint64_t ldm_gl_checksum(const ldm_gl *m);
size_t ldm_gl_overflow(const ldm_gl *m);
/* The buffers on their binding points (0: depths, 1: bases) and the bound program prog's
 * u_ldm_* uniforms, for shaders/ldm_trace.glsl. */
void ldm_gl_bind(const ldm_gl *m, GLuint prog);
/* The k-buffer as built (directions x res^2 x layers words, ldm_cpu.h's order). */
void ldm_gl_read(const ldm_gl *m, uint32_t *out);

#endif
