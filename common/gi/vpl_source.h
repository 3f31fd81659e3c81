/* vpl_source: the light the GI methods start from, owned by none of them: the texels of a
 * reflective shadow map (RSM) and the scene's emissive triangles as virtual point lights
 * (the vpl method's candidates, vpl_select.h; the caches method's VALs, val_select.h; the
 * ILPV's and ldm's emitters), and the fixed random numbers their selections share.
 *
 * An RSM texel's flux is what its surface reflects (W, shaders/rsm.frag); its area is
 * measured on the map itself from the neighbouring texels' positions, so it needs no
 * knowledge of the light's projection. An emissive triangle of radiance L_e and area A is
 * a Lambertian emitter of flux pi L_e A at its centroid, facing its vertex normals' side
 * (what the reference's one-bounce image and ILPV count as emitters' light).
 * Host arrays only; no GL, no allocation. */
#ifndef CAVELIGHT_VPL_SOURCE_H
#define CAVELIGHT_VPL_SOURCE_H

#include <stddef.h>
#include <stdint.h>

#include "scene/scene.h"

/* A Lambertian emitter at a point: radiant intensity flux / pi * cos(angle to normal). */
typedef struct vpl {
    float position[3];
    float normal[3];   /* unit */
    float flux[3];     /* W it sends into its hemisphere, linear RGB */
    float area;        /* m^2 of surface it stands for */
} vpl;

/* The fixed random number in [0, 1) of slot i under seed, dimension dim: 0 is a
 * selection's (vpl_select.h, val_select.h), 1 and 2 place a chosen emitter's VPL on its
 * triangle (below). */
double vpl_slot_random(uint32_t seed, int i, int dim);

/* Surface area of the texel at (x, y) of a size x size map of positions and normals (4
 * floats per texel, position w = 0 where no geometry): the parallelogram of its steps to
 * the neighbours on its plane (forward, else backward difference per axis; an axis with
 * neither takes the other's length). 0 when no neighbour lies on its plane. */
float vpl_texel_area(const float *position, const float *normal, int size, int x, int y);
/* The texels of one RSM layer (position, normal, flux: 4 floats per texel each, row by
 * row) that hold geometry and positive flux, in texel order, into out (room for size^2).
 * Returns how many. */
size_t vpl_from_rsm(const float *position, const float *normal, const float *flux, int size,
                    vpl *out);
/* An emissive triangle: centroid, unit face normal on its vertex normals' side, emitted
 * radiance L_e, area, corners. */
typedef struct vpl_emitter {
    float position[3], normal[3], radiance[3], area;
    float corner[3][3];
} vpl_emitter;
/* The emissive triangles of s with a non-zero area, in triangle order, into out; with out
 * NULL only counts them. Returns how many. */
size_t vpl_emitters(const scene *s, vpl_emitter *out);
/* An emitter as a VPL of flux pi L_e A at its centroid. */
vpl vpl_from_emitter(const vpl_emitter *e);
/* The point of e's triangle at (u1, u2) in [0, 1)^2, uniform in area for uniform (u1, u2).
 * A VPL chosen for an emitter moves there (gi_vpl.c): its light is then an unbiased
 * estimate of the whole triangle's, where the centroid alone misses the light's shape
 * near the emitter by a bias no VPL count removes. */
void vpl_emitter_point(const vpl_emitter *e, double u1, double u2, float out[3]);

#endif
