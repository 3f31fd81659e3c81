/* mat4: the few 4x4 matrix operations the renderer, HUD and interaction share.
 *
 * Matrices are float[16], column-major (element (row r, column c) at [c * 4 + r]), as GL
 * and the wire format expect. Plain scalar loops on purpose: cglm's SIMD paths need
 * 16/32-byte aligned mat4 storage (our matrices live unaligned in structs and messages)
 * and may fuse multiply-adds, which would change results between builds. */
#ifndef CAVELIGHT_MAT4_H
#define CAVELIGHT_MAT4_H

/* out = a * b; out may alias a or b. */
void mat4_mul(const float a[16], const float b[16], float out[16]);

/* The double forms, for chains that must not round to float between steps (glTF node
 * trees, animation poses, the path tracer's camera). mat4d_mul() sums each element from
 * k = 0 to 3, starting from 0: callers' results depend on that order. out may alias. */
void mat4d_mul(const double a[16], const double b[16], double out[16]);
void mat4d_identity(double out[16]);
void mat4d_from_float(const float m[16], double out[16]);
/* The inverse of any m (projective too), by Gauss-Jordan with partial pivoting; -1 (out
 * untouched) when m is singular. mat4_affine_inverse_d() is the cheaper affine case. */
int mat4d_inverse(const double m[16], double out[16]);

/* out = the inverse of the affine m (last row 0 0 0 1: rotation, scale, shear and a
 * translation), computed in double; returns -1 (out untouched) when m is singular or not
 * finite. The _d form works on doubles throughout. */
int mat4_affine_inverse(const float m[16], float out[16]);
int mat4_affine_inverse_d(const double m[16], double out[16]);

/* out = the affine point p transformed by m (w = 1, no division). */
void mat4_transform_point(const float m[16], const float p[3], float out[3]);

/* out = T * Rz * Ry * Rx * S: a scale, then rotations about x, y and z by deg (degrees,
 * XYZ Euler), then a translation by t. The one rule for "translation, rotation_deg, scale"
 * in the configs (tracker_to_cave, scene_transform). */
void mat4_from_trs_deg(const float t[3], const float deg[3], float scale, float out[16]);

#endif
