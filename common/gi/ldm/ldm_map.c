/* ldm_map: see ldm_map.h. */
#include "gi/ldm/ldm_map.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/vec3.h"
#include "gi/ldm/ldm_directions.h"

void ldm_layout_init(ldm_layout *l, const scene *s, int directions, int resolution, int layers)
{
    memset(l, 0, sizeof *l);
    l->directions = directions;
    l->resolution = resolution;
    l->layers = layers;
    for (int a = 0; a < 3; a++)
        l->centre[a] = 0.5f * (s->bounds_min[a] + s->bounds_max[a]);
    /* 1% wider than the bounds' sphere: no surface lies on the maps' edge. */
    l->radius = 0.505f * scene_diagonal(s);
    if (!(l->radius > 0))
        l->radius = 1.0f;
}

void ldm_layout_maps(const ldm_layout *l, ldm_map *out)
{
    float d[LDM_DIRECTIONS_MAX][3];
    ldm_directions(l->directions, d);
    for (int i = 0; i < l->directions; i++) {
        memcpy(out[i].d, d[i], sizeof d[i]);
        vec3_basis(d[i], out[i].u, out[i].v);
    }
}

float ldm_texel(const ldm_layout *l) { return 2.0f * l->radius / (float)l->resolution; }

void ldm_project(const ldm_layout *l, const ldm_map *m, const float p[3], float *x, float *y,
                 float *t)
{
    float q[3];
    vec3_sub(p, l->centre, q);
    float half = 0.5f * (float)l->resolution;
    *x = (vec3_dot(q, m->u) / l->radius + 1.0f) * half;
    *y = (vec3_dot(q, m->v) / l->radius + 1.0f) * half;
    *t = vec3_dot(q, m->d) + l->radius;
}

double ldm_memory_bytes(const ldm_layout *l)
{
    return ldm_limits_memory_bytes(l->directions, l->resolution, l->layers);
}

const char *ldm_memory_check(int directions, int resolution, int layers, int cap_mb,
                             const char *what, char *buf, size_t cap)
{
    ldm_layout l = {.directions = directions, .resolution = resolution, .layers = layers};
    double mb = ldm_memory_bytes(&l) / (1024.0 * 1024.0);
    if (mb <= cap_mb)
        return NULL;
    snprintf(buf, cap, "%s: %d maps of %d^2 texels x %d layers need %.0f MB, over "
             "ldm-memory %d MB: fewer directions, a lower resolution or fewer layers, or "
             "raise ldm-memory", what, directions, resolution, layers, mb, cap_mb);
    return buf;
}
