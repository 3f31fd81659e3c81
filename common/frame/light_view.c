/* light_view: RSM views, cone, travel and power of a light (light_view.h). */
#include <math.h>
#include <string.h>

#include "base/mat4.h"
#include "frame/light_view.h"
#include "frame/offaxis.h"

static const double PI = 3.14159265358979323846;

static const float cube_axis[LIGHT_VIEW_CUBE_FACES][3] = {
    {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
};

void light_cone(const frame_light *l, float *outer, float *inner)
{
    *outer = fminf(fmaxf(l->outer_angle, 0.01f), 1.45f);
    *inner = fminf(fmaxf(l->inner_angle, 0.0f), *outer);
}

int light_is_lit(const frame_light *l)
{
    return l->enabled && l->intensity > 0;
}

static void centre(const scene *s, float c[3])
{
    for (int a = 0; a < 3; a++)
        c[a] = 0.5f * (s->bounds_min[a] + s->bounds_max[a]);
}

float light_directional_travel(const scene *s, const float d[3], const float p[3])
{
    float c[3];
    centre(s, c);
    return (p[0] - c[0]) * d[0] + (p[1] - c[1]) * d[1] + (p[2] - c[2]) * d[2] +
           0.5f * scene_diagonal(s);
}

/* A directional light's view: the bounds' corners seen along d give the window and the
 * depth range; the eye sits a near-plane margin before the nearest corner. */
void light_directional_view(const scene *s, const float d[3], light_view *v)
{
    memset(v, 0, sizeof *v);
    float c[3], target[3], view[16], proj[16];
    centre(s, c);
    for (int a = 0; a < 3; a++)
        target[a] = c[a] + d[a];
    offaxis_view(c, target, NULL, view);
    const float r[3] = {view[0], view[4], view[8]}, u[3] = {view[1], view[5], view[9]};
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 8; k++) {
        float q[3], e[3];
        for (int a = 0; a < 3; a++)
            q[a] = ((k >> a) & 1 ? s->bounds_max[a] : s->bounds_min[a]) - c[a];
        e[0] = q[0] * r[0] + q[1] * r[1] + q[2] * r[2];
        e[1] = q[0] * u[0] + q[1] * u[1] + q[2] * u[2];
        e[2] = q[0] * d[0] + q[1] * d[1] + q[2] * d[2];
        for (int a = 0; a < 3; a++) {
            lo[a] = fminf(lo[a], e[a]);
            hi[a] = fmaxf(hi[a], e[a]);
        }
    }
    float pad = scene_diagonal(s) / 128.0f;
    for (int a = 0; a < 2; a++) { /* a flat scene seen edge-on still gets a window */
        float mid = 0.5f * (lo[a] + hi[a]), half = fmaxf(0.5f * (hi[a] - lo[a]), pad);
        lo[a] = mid - half;
        hi[a] = mid + half;
        v->extent[a] = half;
    }
    /* The eye moves along d only, so r and u (and the window) stay as measured from c. */
    float eye[3];
    for (int a = 0; a < 3; a++) {
        eye[a] = c[a] + d[a] * (lo[2] - pad);
        target[a] = eye[a] + d[a];
    }
    offaxis_view(eye, target, NULL, view);
    offaxis_orthographic(lo[0], hi[0], lo[1], hi[1], 0.0f, hi[2] - lo[2] + 2 * pad, proj);
    for (int a = 0; a < 3; a++) {
        v->window[0][a] = eye[a] + r[a] * lo[0] + u[a] * lo[1];
        v->window[1][a] = r[a] * (hi[0] - lo[0]);
        v->window[2][a] = u[a] * (hi[1] - lo[1]);
    }
    mat4_mul(proj, view, v->view_projection);
    v->orthographic = 1;
    memcpy(v->axis, d, sizeof v->axis);
}

/* A perspective view from the light at p along axis, yfov wide (tan_half = tan(yfov / 2)). */
static void perspective_view(const scene *s, const float p[3], const float axis[3], float yfov,
                             float tan_half, light_view *v)
{
    float c[3], target[3], view[16], proj[16], dist = 0;
    centre(s, c);
    for (int a = 0; a < 3; a++) {
        target[a] = p[a] + axis[a];
        dist += (c[a] - p[a]) * (c[a] - p[a]);
    }
    float diagonal = scene_diagonal(s);
    offaxis_view(p, target, NULL, view);
    offaxis_perspective(yfov, 1.0f, diagonal / 128.0f,
                        diagonal + sqrtf(dist) + diagonal / 6.4f, proj);
    mat4_mul(proj, view, v->view_projection);
    memcpy(v->axis, axis, sizeof v->axis);
    v->tan_half_fov = tan_half;
}

int light_views(const frame_params *p, const scene *s, int size, light_view *out)
{
    int n = 0;
    for (int i = 0; i < p->light_count && i < FRAME_MAX_LIGHTS; i++) {
        const frame_light *l = &p->lights[i];
        if (!light_is_lit(l))
            continue;
        if (l->type == SCENE_LIGHT_POINT) {
            /* size - 2 margin texels span exactly 90 degrees: texel edges fall on +-1. */
            float tan_half = (float)size / (float)(size - 2 * LIGHT_VIEW_CUBE_MARGIN);
            for (int f = 0; f < LIGHT_VIEW_CUBE_FACES; f++) {
                light_view *v = &out[n++];
                memset(v, 0, sizeof *v);
                v->light = i;
                v->face = f;
                perspective_view(s, l->position, cube_axis[f], 2.0f * atanf(tan_half), tan_half,
                                 v);
                v->vpl_tan = 1.0f;
            }
            continue;
        }
        light_view *v = &out[n++];
        memset(v, 0, sizeof *v);
        if (l->type == SCENE_LIGHT_DIRECTIONAL) {
            light_directional_view(s, l->direction, v);
        } else {
            float outer, inner;
            light_cone(l, &outer, &inner);
            perspective_view(s, l->position, l->direction, 2.0f * outer, tanf(outer), v);
            v->vpl_tan = v->tan_half_fov;
        }
        v->light = i;
    }
    return n;
}

double light_power(const frame_light *l, const scene *s)
{
    if (!light_is_lit(l))
        return 0.0;
    double level = l->intensity * (l->color[0] + l->color[1] + l->color[2]) / 3.0;
    switch (l->type) {
    case SCENE_LIGHT_POINT:
        return level * 4.0 * PI;
    case SCENE_LIGHT_DIRECTIONAL: {
        light_view v;
        light_directional_view(s, l->direction, &v);
        return level * 4.0 * v.extent[0] * v.extent[1];
    }
    default: {
        float outer, inner;
        light_cone(l, &outer, &inner);
        return level * 2.0 * PI * (1.0 - cos(outer));
    }
    }
}

const char *light_dark_reason(int lit)
{
    return lit ? "no light reaches what is seen (the lights point elsewhere, or walls shut them "
                 "out; check their positions and the view)"
               : "every light is off or at zero intensity or colour, and no surface emits";
}
