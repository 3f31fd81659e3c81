#include "gi/caches/caches_exact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/vec3.h"
#include "base/xalloc.h"

/* Caches per work item: fixed ranges, so results do not depend on the thread count. */
enum { CACHES_PER_ITEM = 16 };

struct caches_exact {
    const scene_rt *rt;
    workpool *pool;
    float offset;
};

typedef struct job {
    const caches_exact *x;
    const light_cache *caches;
    size_t count;
    const vpl *vals;
    size_t n;
    uint8_t *visible;          /* count x n */
    const caches_exact_glossy *glossy; /* or NULL */
    cache_proxy *out;
} job;

/* 1 when nothing lies between a and b (both moved off their surfaces along their normals). */
static int clear(const scene_rt *rt, const float a[3], const float na[3], const float b[3],
                 const float nb[3], float offset)
{
    float o[3], e[3], d[3];
    for (int k = 0; k < 3; k++) {
        o[k] = a[k] + offset * na[k];
        e[k] = b[k] + offset * nb[k];
    }
    vec3_sub(e, o, d);
    float len = vec3_normalize(d);
    if (!(len > 0))
        return 1;
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay ray = {.org_x = o[0], .org_y = o[1], .org_z = o[2], .tnear = 0,
                         .dir_x = d[0], .dir_y = d[1], .dir_z = d[2],
                         .tfar = len * (1.0f - 1e-4f), .mask = 0xffffffffu};
    scene_rt_occluded(rt, &ctx, &ray);
    return ray.tfar >= 0; /* Embree sets tfar to -inf on a hit */
}

/* Rays of caches [item * CACHES_PER_ITEM, ...): only towards VALs in front of both. */
static void rays(void *ctx, int item)
{
    job *j = ctx;
    size_t end = (size_t)(item + 1) * CACHES_PER_ITEM;
    for (size_t c = (size_t)item * CACHES_PER_ITEM; c < end && c < j->count; c++) {
        const light_cache *lc = &j->caches[c];
        uint8_t *row = j->visible + c * j->n;
        for (size_t v = 0; v < j->n; v++) {
            const vpl *l = &j->vals[v];
            float d[3];
            vec3_sub(l->position, lc->position, d);
            int faces = vec3_dot(lc->normal, d) > 0 && vec3_dot(l->normal, d) < 0;
            row[v] = faces && clear(j->x->rt, lc->position, lc->normal, l->position, l->normal,
                                    j->x->offset);
        }
    }
}

static void gather(void *ctx, int item)
{
    job *j = ctx;
    size_t end = (size_t)(item + 1) * CACHES_PER_ITEM;
    for (size_t c = (size_t)item * CACHES_PER_ITEM; c < end && c < j->count; c++) {
        const uint8_t *seen = j->visible + c * j->n;
        cache_proxy_gather(&j->caches[c], j->vals, j->n, seen, &j->out[c]);
        if (j->glossy)
            cache_glossy_gather(&j->caches[c], j->glossy->eye, j->vals, j->n, seen,
                                &j->glossy->out[c]);
    }
}

void caches_hidden(const scene_rt *rt, const light_cache *caches, size_t count, float distance,
                   float offset, uint8_t *hidden)
{
    for (size_t i = 0; i < count; i++) {
        const light_cache *c = &caches[i];
        float end[3];
        for (int k = 0; k < 3; k++)
            end[k] = c->position[k] + distance * c->normal[k];
        hidden[i] = !clear(rt, c->position, c->normal, end, c->normal, offset);
    }
}

caches_exact *caches_exact_create(const scene_rt *rt, int threads, float offset)
{
    caches_exact *x = xcalloc(1, sizeof *x);
    x->rt = rt;
    x->offset = offset;
    x->pool = workpool_create(threads);
    if (!x->pool) {
        free(x);
        return NULL;
    }
    return x;
}

void caches_exact_destroy(caches_exact *x)
{
    if (!x)
        return;
    workpool_destroy(x->pool);
    free(x);
}

int caches_exact_proxies(caches_exact *x, const light_cache *caches, size_t count,
                         const vpl *vals, size_t n, const caches_exact_glossy *glossy,
                         cache_proxy *out, double *rays_ms, double *gather_ms)
{
    /* not xalloc: caches times VALs (the scene and a setting): -1 to the caller */
    job j = {x, caches, count, vals, n, malloc(count * (n ? n : 1)), glossy, out};
    if (!j.visible)
        return -1;
    int items = (int)((count + CACHES_PER_ITEM - 1) / CACHES_PER_ITEM);
    double t0 = clock_now_ms();
    workpool_run(x->pool, items, rays, &j);
    double t1 = clock_now_ms();
    workpool_run(x->pool, items, gather, &j);
    *rays_ms = t1 - t0;
    *gather_ms = clock_now_ms() - t1;
    free(j.visible);
    return 0;
}
