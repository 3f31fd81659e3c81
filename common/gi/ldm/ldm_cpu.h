/* ldm_cpu: the layered depth maps built and traced on the CPU, the oracle the GL build and
 * trace are tested against (node/gi/ldm/ldm_gl.h, shaders/ldm_trace.glsl do the same work).
 *
 * Build: every triangle of the scene, both sides, in every map of the layout (ldm_map.h),
 * covering a texel where its centre lies inside or on an edge of the projected triangle
 * (triangles seen edge-on cover nothing), each depth inserted into the texel's sorted list
 * of the `layers` smallest: the same insertion as the GL build's (an atomic minimum along
 * the list), so the lists are the same whatever the order of insertion. A depth pushed
 * out of a full list is counted (overflow).
 * Trace: from a point along +d or -d of a map, the nearest depth of its texel's list
 * beyond a given distance: the first surface a ray through the texel's centre meets.
 *
 * Single-threaded, plain loops: for tests, not for frames. */
#ifndef CAVELIGHT_LDM_CPU_H
#define CAVELIGHT_LDM_CPU_H

#include <stddef.h>
#include <stdint.h>

#include "gi/ldm/ldm_map.h"
#include "scene/scene.h"

typedef struct ldm_cpu {
    ldm_layout layout;
    ldm_map *maps;       /* layout.directions bases */
    uint32_t *depth;     /* map, row, texel, then layer: float bits or LDM_EMPTY */
    size_t overflow;     /* depths that did not fit their texel's list */
} ldm_cpu;

/* 0, or -1 when out of memory. */
int ldm_cpu_build(const scene *s, const ldm_layout *l, ldm_cpu *out);
void ldm_cpu_free(ldm_cpu *c);
/* The sorted list of texel (x, y) of map m: layout.layers entries. */
const uint32_t *ldm_cpu_texel(const ldm_cpu *c, int m, int x, int y);
/* From p along sign * d of map m (sign +1 or -1): the distance to the first surface of
 * p's texel list farther than `skip` and not beyond max_distance (<= 0: no limit); -1
 * when there is none or p lies outside the map. */
float ldm_cpu_trace(const ldm_cpu *c, int m, int sign, const float p[3], float skip,
                    float max_distance);
/* The list search both the CPU and the GLSL trace do, on one texel's sorted depths: the
 * distance from depth t along +1 or -1 to the first entry farther than skip, or -1. */
float ldm_list_trace(const uint32_t *list, int layers, float t, int sign, float skip);

#endif
