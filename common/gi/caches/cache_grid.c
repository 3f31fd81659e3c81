#include "gi/caches/cache_grid.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"

float cache_falloff(const light_cache *c, const float x[3], const float n[3], float reach)
{
    float d[3];
    vec3_sub(x, c->position, d);
    float off = vec3_dot(c->normal, d);
    float d2 = vec3_dot(d, d) + CACHE_PLANE_WEIGHT * off * off;
    if (!(d2 < reach * reach) || !(vec3_dot(n, c->normal) > 0))
        return 0.0f;
    return 1.0f - sqrtf(d2) / reach;
}

float cache_weight(const light_cache *c, const float x[3], const float n[3], float reach)
{
    float falloff = cache_falloff(c, x, n, reach);
    return falloff > 0.0f ? falloff * sqrtf(vec3_dot(n, c->normal)) : 0.0f;
}

size_t cache_grid_cell(const cache_grid *g, const float p[3])
{
    size_t cell = 0;
    for (int a = 2; a >= 0; a--) {
        float f = floorf((p[a] - g->origin[a]) / g->cell);
        int i = f < 0 ? 0 : (f >= (float)g->dims[a] ? g->dims[a] - 1 : (int)f);
        cell = cell * (size_t)g->dims[a] + (size_t)i;
    }
    return cell;
}

/* Cell range [lo, hi] per axis that a sphere around p of radius r touches. */
static void cell_range(const cache_grid *g, const float p[3], float r, int lo[3], int hi[3])
{
    for (int a = 0; a < 3; a++) {
        float l = floorf((p[a] - r - g->origin[a]) / g->cell);
        float h = floorf((p[a] + r - g->origin[a]) / g->cell);
        lo[a] = l < 0 ? 0 : (l >= (float)g->dims[a] ? g->dims[a] - 1 : (int)l);
        hi[a] = h < 0 ? 0 : (h >= (float)g->dims[a] ? g->dims[a] - 1 : (int)h);
    }
}

/* Squared distance from p to cell (x, y, z)'s box. */
static float box_distance2(const cache_grid *g, const float p[3], const int c[3])
{
    float d2 = 0;
    for (int a = 0; a < 3; a++) {
        float lo = g->origin[a] + (float)c[a] * g->cell, hi = lo + g->cell;
        float d = p[a] < lo ? lo - p[a] : (p[a] > hi ? p[a] - hi : 0.0f);
        d2 += d * d;
    }
    return d2;
}

/* Calls back (count or fill) for every cell within reach of cache i. */
static void visit(const cache_grid *g, const light_cache *c, uint32_t i, uint32_t *count,
                  uint32_t *fill, uint32_t *index)
{
    int lo[3], hi[3], k[3];
    cell_range(g, c->position, g->reach, lo, hi);
    for (k[2] = lo[2]; k[2] <= hi[2]; k[2]++)
        for (k[1] = lo[1]; k[1] <= hi[1]; k[1]++)
            for (k[0] = lo[0]; k[0] <= hi[0]; k[0]++) {
                if (box_distance2(g, c->position, k) > g->reach * g->reach)
                    continue;
                size_t cell = ((size_t)k[2] * g->dims[1] + k[1]) * g->dims[0] + k[0];
                if (fill)
                    index[fill[cell]++] = i;
                else
                    count[cell]++;
            }
}

typedef struct ranked {
    float d2;
    uint32_t cache;
} ranked;

static int by_distance(const void *a, const void *b)
{
    const ranked *x = a, *y = b;
    if (x->d2 != y->d2)
        return x->d2 < y->d2 ? -1 : 1;
    return (x->cache > y->cache) - (x->cache < y->cache);
}

static int by_cache(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* Keeps the CACHE_GRID_MAX_LIST caches of a long list nearest to its cell's middle, in
 * ascending order; rank is scratch. Returns the kept count. */
static uint32_t trim(const cache_grid *g, const light_cache *caches, size_t cell,
                     uint32_t *list, uint32_t n, ranked *rank)
{
    if (n <= CACHE_GRID_MAX_LIST)
        return n;
    int k[3] = {(int)(cell % g->dims[0]), (int)(cell / g->dims[0] % g->dims[1]),
                (int)(cell / ((size_t)g->dims[0] * g->dims[1]))};
    float mid[3];
    for (int a = 0; a < 3; a++)
        mid[a] = g->origin[a] + ((float)k[a] + 0.5f) * g->cell;
    for (uint32_t j = 0; j < n; j++) {
        float d[3];
        vec3_sub(caches[list[j]].position, mid, d);
        rank[j] = (ranked){vec3_dot(d, d), list[j]};
    }
    qsort(rank, n, sizeof *rank, by_distance);
    for (uint32_t j = 0; j < CACHE_GRID_MAX_LIST; j++)
        list[j] = rank[j].cache;
    qsort(list, CACHE_GRID_MAX_LIST, sizeof *list, by_cache);
    return CACHE_GRID_MAX_LIST;
}

int cache_grid_build(const cache_set *set, const float bounds_min[3], const float bounds_max[3],
                     cache_grid *g, char *err, size_t errlen)
{
    memset(g, 0, sizeof *g);
    g->reach = CACHE_REACH_EDGES * set->edge;
    g->cell = set->edge;
    for (;;) {
        double cells = 1;
        for (int a = 0; a < 3; a++) {
            g->dims[a] = (int)floorf((bounds_max[a] - bounds_min[a]) / g->cell) + 1;
            cells *= g->dims[a];
        }
        if (cells <= CACHE_GRID_MAX_CELLS)
            break;
        g->cell *= 1.25f; /* a large scene at a fine density: fewer, larger cells */
    }
    memcpy(g->origin, bounds_min, sizeof g->origin);
    size_t cells = (size_t)g->dims[0] * g->dims[1] * g->dims[2];
    /* not xalloc: the scene's size over the cache density (a setting): refused in err */
    uint32_t *count = calloc(cells + 1, sizeof *count);
    g->first = calloc(cells + 1, sizeof *g->first);
    if (!count || !g->first) {
        free(count);
        cache_grid_free(g);
        snprintf(err, errlen, "light caches: out of memory for a %zu-cell lookup grid", cells);
        return -1;
    }
    for (size_t i = 0; i < set->count; i++)
        visit(g, &set->caches[i], (uint32_t)i, count, NULL, NULL);
    size_t total = 0;
    for (size_t c = 0; c < cells; c++) {
        g->first[c] = (uint32_t)total;
        total += count[c];
    }
    g->first[cells] = (uint32_t)total;
    /* not xalloc: the scene's caches (a density setting): refused in err */
    g->index = malloc((total ? total : 1) * sizeof *g->index);
    ranked *rank = malloc(((total ? total : 1)) * sizeof *rank);
    if (!g->index || !rank) {
        free(count);
        free(rank);
        cache_grid_free(g);
        snprintf(err, errlen, "light caches: out of memory for %zu lookup entries", total);
        return -1;
    }
    memcpy(count, g->first, cells * sizeof *count); /* fill positions */
    for (size_t i = 0; i < set->count; i++)
        visit(g, &set->caches[i], (uint32_t)i, NULL, count, g->index);
    size_t kept = 0;
    for (size_t c = 0; c < cells; c++) { /* trimmed lists, packed in place */
        uint32_t n = g->first[c + 1] - g->first[c], start = g->first[c];
        g->first[c] = (uint32_t)kept;
        memmove(g->index + kept, g->index + start, n * sizeof *g->index);
        n = trim(g, set->caches, c, g->index + kept, n, rank);
        kept += n;
        if ((int)n > g->longest)
            g->longest = (int)n;
    }
    g->first[cells] = (uint32_t)kept;
    g->listed = kept;
    free(count);
    free(rank);
    return 0;
}

void cache_grid_free(cache_grid *g)
{
    free(g->first);
    free(g->index);
    g->first = g->index = NULL;
}

size_t cache_grid_bytes(const cache_grid *g)
{
    size_t cells = (size_t)g->dims[0] * g->dims[1] * g->dims[2];
    return (cells + 1) * sizeof *g->first + g->listed * sizeof *g->index;
}
