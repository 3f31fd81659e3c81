#include "gi/vpl/ism_points.h"

#include <math.h>
#include <stdlib.h>

#include "base/vec3.h"
#include "gi/vpl/vpl_select.h"

static const double PI = 3.14159265358979323846;

double ism_scene_area(const scene *s)
{
    double a = 0;
    for (size_t j = 0; j < s->triangle_count; j++)
        a += vec3_triangle_area(s->positions + 9 * j);
    return a;
}

float ism_point_radius(double area, int m)
{
    return (float)sqrt(area / (PI * (m > 0 ? m : 1)));
}

int ism_points(const scene *s, size_t first, size_t n, float *position)
{
    size_t count = s->triangle_count;
    /* not xalloc: the scene's triangles: -1 to the caller */
    double *cdf = malloc((count ? count : 1) * sizeof *cdf);
    if (!cdf)
        return -1;
    double total = 0;
    for (size_t j = 0; j < count; j++)
        cdf[j] = total += vec3_triangle_area(s->positions + 9 * j);
    if (!(total > 0)) {
        free(cdf);
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        int k = (int)(first + i);
        double u = vpl_slot_random(ISM_POINTS_SEED, 3 * k, 0) * total;
        size_t lo = 0, hi = count - 1; /* the first triangle whose CDF exceeds u */
        while (lo < hi) {
            size_t mid = (lo + hi) / 2;
            if (cdf[mid] > u)
                hi = mid;
            else
                lo = mid + 1;
        }
        /* Uniform in the triangle: weights 1 - sqrt(r1), sqrt(r1) (1 - r2), sqrt(r1) r2. */
        double r1 = sqrt(vpl_slot_random(ISM_POINTS_SEED, 3 * k + 1, 0));
        double r2 = vpl_slot_random(ISM_POINTS_SEED, 3 * k + 2, 0);
        float w[3] = {(float)(1 - r1), (float)(r1 * (1 - r2)), (float)(r1 * r2)};
        const float *t = s->positions + 9 * lo;
        for (int c = 0; c < 3; c++)
            position[3 * i + c] = w[0] * t[c] + w[1] * t[3 + c] + w[2] * t[6 + c];
    }
    free(cdf);
    return 0;
}
