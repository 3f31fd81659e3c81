/* cache_place: where the caches GI method (node/gi/caches/) keeps its light: light caches
 * spread over the scene's surfaces once per scene, after LightSkin (Lensing and Broll
 * 2013; the high-res RSM paper's "cache distribution").
 *
 * The paper's steps, as done here:
 *   1. the surfaces are sampled: every triangle gets points on a low-discrepancy pattern,
 *      one per (e / 3)^2 of its area, and one per e / 3 of its longest edge at least (a
 *      sliver), each with its share of the area and its interpolated normal (the paper
 *      voxelizes the model itself);
 *   2. the points are binned into cubes of edge e (the paper's d_eps / 2), the grid shifted
 *      by e / 2 so that a wall on the scene's bounds or on a multiple of e from them lies
 *      mid-cube;
 *   3. in each cube, the point whose normal gathers the most area within the angle
 *      tolerance theta_eps (and within e / 4 of its plane, so that two parallel surfaces
 *      in a cube make two caches) becomes a cache: the area-weighted mean position and
 *      normal of those points; they leave the cube, and again until none is left;
 *   4. a cache whose mean lies off the surface (two parallel surfaces in a cube) moves onto
 *      the plane of its nearest point.
 * The paper's step 5 (joining similar caches of neighbouring cubes) is left out: it would
 * move a cache farther than e from the points it stands for, and the reach below is what
 * the interpolation relies on.
 *
 * What this gives: every surface point lies within sqrt(3) e of a cache whose normal is
 * within 2 theta_eps of its own (the point's cube made it), so CACHE_REACH_EDGES x e, the
 * interpolation's radius (cache_grid.h), always reaches one. e follows from a density in
 * caches per m^2 (cache_place_edge()). The same scene and settings give the same caches,
 * bit for bit, on every machine (no threads, float maths in a fixed order).
 * No GL; the caches are plain arrays (cache_file.h stores them on disk). */
#ifndef CAVELIGHT_CACHE_PLACE_H
#define CAVELIGHT_CACHE_PLACE_H

#include <stddef.h>

#include "scene/scene.h"

/* Caches per m^2 when the density is "auto": this many caches over the scene's area
 * (the paper's street scene holds about 5500). */
enum { CACHE_AUTO_COUNT = 4096 };
/* The interpolation reaches this many cube edges: more than sqrt(3), the farthest a point
 * of a cube lies from its cube's cache. */
#define CACHE_REACH_EDGES 2.0f

typedef struct light_cache {
    float position[3];
    float normal[3];       /* unit */
    float area;            /* m^2 of surface it stands for */
    float roughness;       /* its points' material roughness, area-weighted mean, [0, 1] */
} light_cache;

typedef struct cache_place_desc {
    float edge;            /* cube edge e, metres: the caches' spacing */
    float angle;           /* theta_eps, radians, in (0, pi / 4] */
} cache_place_desc;

typedef struct cache_set {
    light_cache *caches;
    size_t count;
    float edge, angle;     /* what they were placed with */
} cache_set;

/* m^2 of all triangles (double sums). */
double cache_scene_area(const scene *s);
/* The cube edge for a density in caches per m^2 (1 / sqrt(density)); density <= 0: auto,
 * CACHE_AUTO_COUNT over the scene's area. */
float cache_place_edge(const scene *s, float density);
/* Places the caches; 0, or -1 with one line in err (no surface, out of memory). */
int cache_place(const scene *s, const cache_place_desc *d, cache_set *out, char *err,
                size_t errlen);
void cache_set_free(cache_set *set);

/* Floats per surface point: position, normal (unit), area, material roughness. */
enum { CACHE_POINT_FLOATS = 8 };
/* cache_place() refuses a scene that needs more surface points than this (512 MB of them). */
enum { CACHE_MAX_POINTS = 1 << 24 };

/* The surface points of step 1 for edge e: CACHE_POINT_FLOATS each,
 * into out (NULL: only counted). Returns how many. The placement's own sampling, for the
 * tests that check every point is reached. */
size_t cache_surface_points(const scene *s, float edge, float *out);

#endif
