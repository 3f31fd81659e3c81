/* caches_exact: the caches method's rays (Embree, scene_rt.h, on the host's threads).
 *
 * The exact occlusion, its ceiling: a ray from every cache to every VAL, and each cache's
 * proxy light gathered from the VALs it sees (cache_proxy_gather()). What the
 * approximation of cache_light.h stands in for; it costs caches x VALs rays per frame. The
 * same caches, VALs and scene give the same proxies whatever the thread count.
 *
 * Hidden caches: a surface under another one a hair above it (a floor under a rug, two
 * boxes sharing a face, stacked glTF meshes) gets caches that no one sees, and that the
 * interpolation of the visible surface above would take in; a cache whose normal meets a
 * surface within the given distance is hidden (once, at load). */
#ifndef CAVELIGHT_CACHES_EXACT_H
#define CAVELIGHT_CACHES_EXACT_H

#include <stddef.h>

#include "base/workpool.h"
#include "gi/caches/cache_light.h"
#include "reference/scene_rt.h"

typedef struct caches_exact caches_exact;

/* offset: how far rays start and end off the surfaces along their normals (m). */
caches_exact *caches_exact_create(const scene_rt *rt, int threads, float offset);
void caches_exact_destroy(caches_exact *x);
/* The glossy proxies to make too: the viewer and where they go (count of them). */
typedef struct caches_exact_glossy {
    const float *eye;
    cache_proxy *out;
} caches_exact_glossy;

/* The proxies of all count caches from n VALs into out, and the glossy ones (glossy NULL:
 * none, cache_glossy_gather()) with the same rays; *rays_ms and *gather_ms the two steps'
 * times. -1 when memory is short (out untouched). */
int caches_exact_proxies(caches_exact *x, const light_cache *caches, size_t count,
                         const vpl *vals, size_t n, const caches_exact_glossy *glossy,
                         cache_proxy *out, double *rays_ms, double *gather_ms);

/* hidden[i] = 1 for each of count caches whose normal meets a surface within distance. */
void caches_hidden(const scene_rt *rt, const light_cache *caches, size_t count, float distance,
                   float offset, uint8_t *hidden);

#endif
