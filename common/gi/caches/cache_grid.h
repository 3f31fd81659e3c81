/* cache_grid: which light caches (cache_place.h) can light a surface point, and with which
 * weight: the lookup and the weights of the caches method's interpolation (the paper's
 * equation 8 and 9; node/gi/caches/caches_interpolate.frag is the GPU's copy of
 * cache_weight()).
 *
 * A point x with normal n takes every cache c within the reach R (cache_place.h) by
 *   w(x, c) = (1 - d / R) sqrt(max(n . n_c, 0)),   d^2 = |x - c|^2 + 15 (n_c . (x - c))^2:
 * the paper's weight (Ward's, adapted by Lensing) with the distance off the cache's plane
 * counted four times, so that a cache on a parallel surface a little above or below (a
 * table top over the floor) does not light x. The paper finds the 16 nearest caches per
 * vertex at load; here the scene is a uniform grid of cells of edge e, each listing the
 * caches within R of any of its points (at most CACHE_GRID_MAX_LIST, the nearest to its
 * middle), so a pixel reads one list.
 * No GL; the node uploads the lists. */
#ifndef CAVELIGHT_CACHE_GRID_H
#define CAVELIGHT_CACHE_GRID_H

#include <stddef.h>
#include <stdint.h>

#include "gi/caches/cache_place.h"

enum { CACHE_GRID_MAX_LIST = 128, CACHE_GRID_MAX_CELLS = 1 << 22 };
/* The weight of the distance off a cache's plane: (1 + this) times its square. */
#define CACHE_PLANE_WEIGHT 15.0f

typedef struct cache_grid {
    float origin[3];       /* corner of cell (0, 0, 0) */
    float cell;            /* edge, m */
    int dims[3];
    float reach;           /* R, m */
    uint32_t *first;       /* cell i lists index[first[i] .. first[i + 1]) */
    uint32_t *index;       /* cache numbers, ascending within a list */
    size_t listed;
    int longest;           /* the longest list */
} cache_grid;

/* The grid over the bounds for set (reach CACHE_REACH_EDGES x set->edge). 0, or -1 with one
 * line in err (out of memory). */
int cache_grid_build(const cache_set *set, const float bounds_min[3], const float bounds_max[3],
                     cache_grid *g, char *err, size_t errlen);
void cache_grid_free(cache_grid *g);
/* The cell holding p (clamped into the grid). */
size_t cache_grid_cell(const cache_grid *g, const float p[3]);
/* w(x, c) above, 0 beyond the reach or behind. */
float cache_weight(const light_cache *c, const float x[3], const float n[3], float reach);
/* Its first factor, 1 - d / R (0 beyond the reach or behind): the glossy proxies' weight
 * takes it with the reflections' cosine in place of the normals' (cache_light.h). */
float cache_falloff(const light_cache *c, const float x[3], const float n[3], float reach);
/* Bytes the lists take (first and index). */
size_t cache_grid_bytes(const cache_grid *g);

#endif
