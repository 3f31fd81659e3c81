/* lpv_splat: the first LPV_SPLAT_RADIUS cells of every injected cell's light, in closed
 * form, and the light that leaves them, which propagation (lpv_propagate.h) carries on.
 *
 * Propagating the injection from its cell directly would send it along a handful of
 * lattice directions (every cell's light moves as two beams per step), so near its source
 * the light would form rays. Instead each injected cell's light leaves from where its VPLs
 * are (lpv_inject.h's origin) with the angular distribution its SH coefficients describe,
 * read as the closest of four shapes (clamped cosine, hemisphere, isotropic, mixed
 * linearly by the mean cosine q: 2/3, 1/2, 0), and is written
 *   - into `near`, for every cell whose centre is closer than R = LPV_SPLAT_RADIUS cells to
 *     the origin: the light passing through that cell per step, E p(w) / r^2 as a beam
 *     along w (p the angular density, w the direction from the origin to the centre, r the
 *     distance in cells, at least 1/2): the closed form of a point source's field;
 *   - into `shell`, for the cells with R <= r < R + 1: the same shares normalized so that
 *     the shell holds the light's whole energy once (the light of one step at distance R),
 *     each cell's share a beam along w.
 * A cell gets nothing when a surface blocks one of the lattice hops that lead there from
 * the injected cell (lpv_geometry.h) or when it lies outside the lattice; absorption keeps
 * (1 - absorption)^r. The emitting surface's own layer (lpv_own_layer(), what its own
 * receivers read) gets no light: a near cell there gets nothing, and a shell cell's share
 * lands in the first cell beyond that layer along the lattice axis closest to the surface's
 * normal, with its direction (grazing light just above the surface, which the receiver's
 * shapes would otherwise partly count as arriving at the surface that sent it). The ILPV renders near + sum over steps of propagated shells
 * (ilpv.h). Deterministic and independent of the thread count: each work item owns a range
 * of z slabs and adds the injected cells in lattice order. */
#ifndef CAVELIGHT_LPV_SPLAT_H
#define CAVELIGHT_LPV_SPLAT_H

#include "base/workpool.h"
#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_volume.h"

enum { LPV_SPLAT_RADIUS = 2 };

typedef struct lpv_splat_source {
    int cell[3];
    float origin[3];  /* lattice units */
    float plane[3];   /* unit normal of the emitting surface (mean flux direction), or 0 */
    float energy[3], dir[3][3], cosine[3], hemi[3], iso[3]; /* per colour */
} lpv_splat_source;

/* Scratch the splat keeps between frames (the list of injected cells). */
typedef struct lpv_splat {
    lpv_splat_source *sources;
    size_t count, capacity;
} lpv_splat;

typedef struct lpv_splat_desc {
    const lpv_volume *injected;   /* 12 channels */
    const lpv_volume *origin;     /* 4 channels (lpv_inject.h) or NULL: the cell centres */
    const lpv_blockers *blockers; /* NULL: nothing blocks */
    float absorption;             /* per cell of travel (lpv_transfer_step_probability) */
    workpool *pool;               /* NULL: the calling thread */
} lpv_splat_desc;

/* Clears near and shell (12 channels, the injection's shape) and fills them. Returns 0,
 * or -1 when out of memory (near and shell are then cleared). */
int lpv_splat_run(lpv_splat *s, const lpv_splat_desc *desc, lpv_volume *near,
                  lpv_volume *shell);
void lpv_splat_free(lpv_splat *s);

#endif
