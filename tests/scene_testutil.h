/* A brute-force ray caster over a scene's triangles, the oracle the tests measure
 * accelerated tracing against (header only, each test is one program). */
#ifndef CAVELIGHT_SCENE_TESTUTIL_H
#define CAVELIGHT_SCENE_TESTUTIL_H

#include <math.h>
#include <stddef.h>

#include "base/vec3.h"
#include "scene/scene.h"

/* The nearest distance along d from o to a triangle of s, either side
 * (vec3d_ray_triangle()), or INFINITY. */
static inline double testutil_ray_cast(const scene *s, const double o[3], const double d[3])
{
    double best = INFINITY;
    for (size_t tri = 0; tri < s->triangle_count; tri++) {
        const float *p = s->positions + 9 * tri;
        double v[3][3];
        for (int k = 0; k < 9; k++)
            v[k / 3][k % 3] = p[k];
        double t = vec3d_ray_triangle(o, d, v[0], v[1], v[2]);
        if (t < best)
            best = t;
    }
    return best;
}

#endif
