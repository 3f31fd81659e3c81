/* vec3: the small 3-vector maths written once, on plain float[3] (and double[3] where a
 * sum needs the precision: triangle areas summed over a whole scene, blocking lobes).
 *
 * Each function does its arithmetic in the order written here, so that replacing an
 * inline copy by it changes no bit of any result. No SIMD, no allocation. */
#ifndef CAVELIGHT_VEC3_H
#define CAVELIGHT_VEC3_H

#include <math.h>

static inline void vec3_sub(const float a[3], const float b[3], float out[3])
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

static inline float vec3_dot(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* out may not alias a or b. */
static inline void vec3_cross(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static inline float vec3_length(const float v[3])
{
    return sqrtf(vec3_dot(v, v));
}

/* Scales v to unit length unless its length is 0 or NaN (then v is left as it is).
 * Returns the length it had. */
static inline float vec3_normalize(float v[3])
{
    float len = vec3_length(v);
    if (len > 0) {
        v[0] /= len;
        v[1] /= len;
        v[2] /= len;
    }
    return len;
}

/* Orthonormal basis t1, t2 around the unit vector d (Duff et al. 2017, branch on
 * d_z >= 0, so -0 counts as +0 as in GLSL). */
static inline void vec3_basis(const float d[3], float t1[3], float t2[3])
{
    float sign = d[2] >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sign + d[2]);
    float b = d[0] * d[1] * a;
    t1[0] = 1.0f + sign * d[0] * d[0] * a;
    t1[1] = sign * b;
    t1[2] = -sign * d[0];
    t2[0] = b;
    t2[1] = sign + d[1] * d[1] * a;
    t2[2] = -d[1];
}

/* (p1 - p0) x (p2 - p0) of a triangle p = {p0, p1, p2}: its face normal, as long as twice
 * its area, on the side its vertices turn counter-clockwise around. */
static inline void vec3_triangle_normal(const float p[9], float out[3])
{
    float e1[3], e2[3];
    vec3_sub(p + 3, p, e1);
    vec3_sub(p + 6, p, e2);
    vec3_cross(e1, e2, out);
}

static inline float vec3_triangle_area(const float p[9])
{
    float n[3];
    vec3_triangle_normal(p, n);
    return 0.5f * vec3_length(n);
}

static inline void vec3d_sub(const double a[3], const double b[3], double out[3])
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

static inline double vec3d_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void vec3d_cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Distance along d from o to triangle abc, either side (Moeller-Trumbore), or INFINITY;
 * d need not be unit (the distance is then in units of |d|). */
static inline double vec3d_ray_triangle(const double o[3], const double d[3], const double a[3],
                                        const double b[3], const double c[3])
{
    double e1[3], e2[3], s[3], h[3], q[3];
    vec3d_sub(b, a, e1);
    vec3d_sub(c, a, e2);
    vec3d_sub(o, a, s);
    vec3d_cross(d, e2, h);
    double det = vec3d_dot(e1, h);
    if (fabs(det) < 1e-30)
        return INFINITY;
    double u = vec3d_dot(s, h) / det;
    if (u < 0 || u > 1)
        return INFINITY;
    vec3d_cross(s, e1, q);
    double v = vec3d_dot(d, q) / det;
    if (v < 0 || u + v > 1)
        return INFINITY;
    double t = vec3d_dot(e2, q) / det;
    return t > 0 ? t : INFINITY;
}

#endif
