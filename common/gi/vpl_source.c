#include "gi/vpl_source.h"

#include <math.h>
#include <string.h>

#include "base/vec3.h"

/* A 32-bit integer hash with good avalanche (Wellons' lowbias32): slot numbers that
 * differ in one bit get unrelated random numbers. */
static uint32_t mix32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

double vpl_slot_random(uint32_t seed, int i, int dim)
{
    uint32_t h = mix32(mix32(seed ^ 0x9e3779b9U) + (uint32_t)i);
    if (dim)
        h = mix32(h + (uint32_t)dim);
    return (double)(h >> 8) * (1.0 / 16777216.0);
}

/* q (a texel's position) lies on p's plane: within about 3 degrees of it, normals alike. */
static int same_plane(const float *p, const float *np, const float *q, const float *nq)
{
    if (q[3] == 0.0f)
        return 0;
    float d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    float off = fabsf(d[0] * np[0] + d[1] * np[1] + d[2] * np[2]);
    float cosn = np[0] * nq[0] + np[1] * nq[1] + np[2] * nq[2];
    return len > 0 && off <= 0.05f * len && cosn > 0.99f;
}

/* Step to the neighbour on p's plane along one axis (forward first), or 0. */
static int step(const float *pos, const float *nrm, int size, int x, int y, int dx, int dy,
                float out[3])
{
    const float *p = pos + 4 * ((size_t)y * size + x), *n = nrm + 4 * ((size_t)y * size + x);
    for (int sign = 1; sign >= -1; sign -= 2) {
        int qx = x + sign * dx, qy = y + sign * dy;
        if (qx < 0 || qy < 0 || qx >= size || qy >= size)
            continue;
        size_t qi = (size_t)qy * size + qx;
        if (same_plane(p, n, pos + 4 * qi, nrm + 4 * qi)) {
            for (int k = 0; k < 3; k++)
                out[k] = pos[4 * qi + k] - p[k];
            return 1;
        }
    }
    return 0;
}

float vpl_texel_area(const float *position, const float *normal, int size, int x, int y)
{
    float u[3], v[3];
    int hu = step(position, normal, size, x, y, 1, 0, u);
    int hv = step(position, normal, size, x, y, 0, 1, v);
    if (!hu && !hv)
        return 0.0f;
    if (hu && hv) {
        float c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                      u[0] * v[1] - u[1] * v[0]};
        return sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    const float *w = hu ? u : v;
    return w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
}

size_t vpl_from_rsm(const float *position, const float *normal, const float *flux, int size,
                    vpl *out)
{
    size_t n = 0;
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            size_t i = (size_t)y * size + x;
            const float *f = flux + 4 * i;
            if (position[4 * i + 3] == 0.0f || !(f[0] > 0 || f[1] > 0 || f[2] > 0))
                continue;
            vpl *v = &out[n++];
            for (int k = 0; k < 3; k++) {
                v->position[k] = position[4 * i + k];
                v->normal[k] = normal[4 * i + k];
                v->flux[k] = f[k];
            }
            v->area = vpl_texel_area(position, normal, size, x, y);
        }
    return n;
}

size_t vpl_emitters(const scene *s, vpl_emitter *out)
{
    size_t n = 0;
    for (size_t t = 0; t < s->triangle_count; t++) {
        const float *e = s->materials[s->triangle_material[t]].emissive;
        if (!(e[0] > 0 || e[1] > 0 || e[2] > 0))
            continue;
        const float *p = s->positions + 9 * t, *vn = s->normals + 9 * t;
        float f[3];
        vec3_triangle_normal(p, f);
        float len = vec3_length(f);
        if (!(len > 0))
            continue;
        if (out) {
            float side = f[0] * (vn[0] + vn[3] + vn[6]) + f[1] * (vn[1] + vn[4] + vn[7]) +
                         f[2] * (vn[2] + vn[5] + vn[8]);
            float sign = side < 0 ? -1.0f : 1.0f;
            vpl_emitter *v = &out[n];
            for (int k = 0; k < 3; k++) {
                v->position[k] = (p[k] + p[3 + k] + p[6 + k]) / 3.0f;
                v->normal[k] = sign * f[k] / len;
                v->radiance[k] = e[k];
                for (int c = 0; c < 3; c++)
                    v->corner[c][k] = p[3 * c + k];
            }
            v->area = 0.5f * len;
        }
        n++;
    }
    return n;
}

vpl vpl_from_emitter(const vpl_emitter *e)
{
    static const double PI = 3.14159265358979323846;
    vpl v;
    memcpy(v.position, e->position, sizeof v.position);
    memcpy(v.normal, e->normal, sizeof v.normal);
    for (int k = 0; k < 3; k++)
        v.flux[k] = (float)(PI * e->radiance[k] * e->area);
    v.area = e->area;
    return v;
}

void vpl_emitter_point(const vpl_emitter *e, double u1, double u2, float out[3])
{
    double r = sqrt(u1); /* barycentrics (1 - r, r (1 - u2), r u2): uniform in area */
    for (int k = 0; k < 3; k++)
        out[k] = (float)((1 - r) * e->corner[0][k] + r * (1 - u2) * e->corner[1][k] +
                         r * u2 * e->corner[2][k]);
}
