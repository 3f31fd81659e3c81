#include <math.h>
#include <string.h>

#include "frame/offaxis.h"
#include "base/vec3.h"

/* Unit length, or -1 for a (nearly) zero vector. */
static int normalize(float v[3])
{
    return vec3_normalize(v) > 1e-12f ? 0 : -1;
}

/* view = rotation with rows (r, u, n) then translation by -eye. */
static void basis_view(const float r[3], const float u[3], const float n[3], const float eye[3],
                       float view[16])
{
    memset(view, 0, 16 * sizeof(float));
    for (int i = 0; i < 3; i++) {
        view[i * 4 + 0] = r[i];
        view[i * 4 + 1] = u[i];
        view[i * 4 + 2] = n[i];
    }
    view[12] = -vec3_dot(r, eye);
    view[13] = -vec3_dot(u, eye);
    view[14] = -vec3_dot(n, eye);
    view[15] = 1.0f;
}

static void frustum(float l, float r, float b, float t, float n, float f, float m[16])
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = 2 * n / (r - l);
    m[5] = 2 * n / (t - b);
    m[8] = (r + l) / (r - l);
    m[9] = (t + b) / (t - b);
    m[10] = -(f + n) / (f - n);
    m[11] = -1;
    m[14] = -2 * f * n / (f - n);
}

int offaxis_screen(const offaxis_screen_desc *d, float view[16], float projection[16])
{
    float n_ = d->near_plane > 0 ? d->near_plane : 0.05f;
    float f_ = d->far_plane > 0 ? d->far_plane : 100.0f;
    float vr[3], vu[3], vn[3], va[3], vb[3], vc[3];
    vec3_sub(d->bottom_right, d->bottom_left, vr);
    vec3_sub(d->top_left, d->bottom_left, vu);
    if (normalize(vr) || normalize(vu))
        return -1;
    vec3_cross(vr, vu, vn);
    if (normalize(vn))
        return -1;
    vec3_sub(d->bottom_left, d->eye, va);
    vec3_sub(d->bottom_right, d->eye, vb);
    vec3_sub(d->top_left, d->eye, vc);
    float dist = -vec3_dot(va, vn); /* eye to screen plane along the normal */
    if (!(dist > 1e-6f))
        return -1;
    float s = n_ / dist;
    float l = vec3_dot(vr, va) * s, r = vec3_dot(vr, vb) * s;
    float b = vec3_dot(vu, va) * s, t = vec3_dot(vu, vc) * s;
    /* The screen's up vector need not be exactly orthogonal to right (a sheared input):
     * re-orthogonalize so that the view stays a rotation. */
    vec3_cross(vn, vr, vu);
    frustum(l, r, b, t, n_, f_, projection);
    basis_view(vr, vu, vn, d->eye, view);
    return 0;
}

int offaxis_eye_in_front(const float bottom_left[3], const float bottom_right[3],
                         const float top_left[3], const float eye[3], float min_distance,
                         float out[3], float *distance)
{
    float vr[3], vu[3], vn[3], rel[3];
    vec3_sub(bottom_right, bottom_left, vr);
    vec3_sub(top_left, bottom_left, vu);
    vec3_cross(vr, vu, vn);
    if (normalize(vn) || !isfinite(eye[0]) || !isfinite(eye[1]) || !isfinite(eye[2]))
        return -1;
    vec3_sub(eye, bottom_left, rel);
    float d = vec3_dot(rel, vn);
    memcpy(out, eye, 3 * sizeof(float));
    if (distance)
        *distance = d;
    if (d >= min_distance)
        return 0;
    for (int i = 0; i < 3; i++)
        out[i] = eye[i] + (min_distance - d) * vn[i];
    return 1;
}

int offaxis_view(const float position[3], const float target[3], const float *up,
                 float view[16])
{
    float f[3], r[3], u[3], back[3];
    vec3_sub(target, position, f);
    if (normalize(f))
        return -1;
    float y[3] = {0, 1, 0};
    if (up && (up[0] != 0 || up[1] != 0 || up[2] != 0)) {
        memcpy(y, up, sizeof y);
    } else if (fabsf(f[1]) > 0.999f) {
        y[1] = 0;
        y[2] = 1;
    }
    vec3_cross(f, y, r);
    if (normalize(r))
        return -1;
    vec3_cross(r, f, u);
    back[0] = -f[0]; back[1] = -f[1]; back[2] = -f[2];
    basis_view(r, u, back, position, view);
    return 0;
}

void offaxis_perspective(float yfov, float aspect, float near_plane, float far_plane,
                         float projection[16])
{
    float t = near_plane * tanf(0.5f * yfov), rr = t * aspect;
    frustum(-rr, rr, -t, t, near_plane, far_plane, projection);
}

void offaxis_orthographic(float left, float right, float bottom, float top, float near_plane,
                          float far_plane, float m[16])
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = 2 / (right - left);
    m[5] = 2 / (top - bottom);
    m[10] = -2 / (far_plane - near_plane);
    m[12] = -(right + left) / (right - left);
    m[13] = -(top + bottom) / (top - bottom);
    m[14] = -(far_plane + near_plane) / (far_plane - near_plane);
    m[15] = 1;
}

int offaxis_look_at(const float position[3], const float target[3], float yfov, float aspect,
                    float near_plane, float far_plane, float view[16], float projection[16])
{
    if (offaxis_view(position, target, NULL, view) != 0)
        return -1;
    offaxis_perspective(yfov, aspect, near_plane, far_plane, projection);
    return 0;
}

void offaxis_stereo_eyes(const float head[3], const float right[3], float separation,
                         float left_eye[3], float right_eye[3])
{
    for (int i = 0; i < 3; i++) {
        left_eye[i] = head[i] - 0.5f * separation * right[i];
        right_eye[i] = head[i] + 0.5f * separation * right[i];
    }
}
