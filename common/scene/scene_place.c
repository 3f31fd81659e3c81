/* scene_place: where a scene without a camera is seen from and where a scene without
 * lights gets its light (scene.h). A room is seen and lit from inside, away from the inside
 * of solid objects (a view or a light outside a closed room sees or lights only its
 * outside); an object from outside, the light on its camera's side, clear of its bounds. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene/scene.h"
#include "base/vec3.h"

/* 6 axes and 8 diagonals: enough to tell a room from open space and to find a surface's
 * back around a point; unit length. */
enum { PROBES = 14 };
static const float D3 = 0.57735027f;
static const float probe_dir[PROBES][3] = {
    {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1},
    {D3, D3, D3}, {D3, D3, -D3}, {D3, -D3, D3}, {D3, -D3, -D3},
    {-D3, D3, D3}, {-D3, D3, -D3}, {-D3, -D3, D3}, {-D3, -D3, -D3},
};

/* Distance along unit d from o to triangle t, or INFINITY. */
static double ray_triangle(const float *p, const float o[3], const float d[3])
{
    double v[3][3], od[3], dd[3];
    for (int k = 0; k < 9; k++)
        v[k / 3][k % 3] = p[k];
    for (int k = 0; k < 3; k++) {
        od[k] = o[k];
        dd[k] = d[k];
    }
    return vec3d_ray_triangle(od, dd, v[0], v[1], v[2]);
}

/* scene_point_is_free(), and the distance to the nearest surface a probe met. */
static int probe(const scene *s, const float p[3], int *fronts, double *nearest)
{
    int met = 0, free_point = 1;
    *nearest = INFINITY;
    for (int r = 0; r < PROBES; r++) {
        double best = INFINITY;
        size_t first = 0;
        for (size_t t = 0; t < s->triangle_count; t++) {
            double d = ray_triangle(s->positions + 9 * t, p, probe_dir[r]);
            if (d < best) {
                best = d;
                first = t;
            }
        }
        if (!isfinite(best))
            continue;
        *nearest = fmin(*nearest, best);
        const float *n = s->normals + 9 * first;
        float side = 0;
        for (int k = 0; k < 3; k++)
            side += (n[k] + n[3 + k] + n[6 + k]) * probe_dir[r][k];
        if (side > 0) /* the ray leaves through the back of the surface: p is inside */
            free_point = 0;
        else
            met++;
    }
    if (fronts)
        *fronts = met;
    return free_point;
}

int scene_point_is_free(const scene *s, const float p[3], int *fronts)
{
    double nearest;
    return probe(s, p, fronts, &nearest);
}

/* The point at fractions f of the bounds on each axis. */
static void at(const scene *s, const float f[3], float p[3])
{
    for (int a = 0; a < 3; a++)
        p[a] = s->bounds_min[a] + f[a] * (s->bounds_max[a] - s->bounds_min[a]);
}

/* A room seen from inside: a lamp inside the bounds, three quarters of the way up over the
 * middle, or the first point of a grid over the bounds that is free and clear of every
 * surface by D/16 (40 cm in the default room; a lamp next to a surface lights a hot spot
 * and little else). */
static void ceiling_lamp(const scene *s, float p[3])
{
    static const float height[] = {0.75f, 0.5f, 0.9f, 0.25f};
    static const float across[] = {0.5f, 0.3f, 0.7f, 0.15f, 0.85f};
    enum { NH = sizeof height / sizeof height[0], NA = sizeof across / sizeof across[0] };
    double clearance = scene_diagonal(s) / 16.0, nearest;
    float first[3];
    int found = 0;
    for (int h = 0; h < NH && !found; h++)
        for (int i = 0; i < NA * NA && !found; i++) {
            at(s, (const float[3]){across[i % NA], height[h], across[i / NA]}, p);
            if (h == 0 && i == 0)
                memcpy(first, p, sizeof first);
            found = probe(s, p, NULL, &nearest) && nearest >= clearance;
        }
    if (!found) /* no free point: a closed solid everywhere, or normals that all face out */
        memcpy(p, first, 3 * sizeof(float));
}

/* How far p is outside the bounds (0 inside or on them). */
static float outside_bounds(const scene *s, const float p[3])
{
    float d2 = 0;
    for (int a = 0; a < 3; a++) {
        float d = fmaxf(s->bounds_min[a] - p[a], p[a] - s->bounds_max[a]);
        d2 += d > 0 ? d * d : 0;
    }
    return sqrtf(d2);
}

/* An object seen from outside: above the camera by a quarter of its distance to the middle
 * of the bounds, then moved away from the middle until it is D/16 outside the bounds, so
 * never inside the model nor in the plane of a flat one. */
static void beside_camera(const scene *s, const scene_camera *cam, const float centre[3], float p[3])
{
    float d[3], clearance = scene_diagonal(s) / 16.0f;
    vec3_sub(cam->position, centre, d);
    memcpy(p, cam->position, 3 * sizeof(float));
    p[1] += 0.25f * vec3_length(d);
    vec3_sub(p, centre, d);
    if (!(vec3_normalize(d) > 0))
        d[0] = 0, d[1] = 1, d[2] = 0;
    for (int i = 0; i < 64 && outside_bounds(s, p) < clearance; i++)
        for (int a = 0; a < 3; a++)
            p[a] += d[a] * clearance;
}

void scene_default_light(const scene *s, scene_light *out)
{
    scene_camera cam;
    scene_default_camera(s, &cam);
    float centre[3], p[3];
    for (int a = 0; a < 3; a++)
        centre[a] = 0.5f * (s->bounds_min[a] + s->bounds_max[a]);
    int fronts, room = scene_point_is_free(s, cam.position, &fronts) && 2 * fronts > PROBES;
    if (room)
        ceiling_lamp(s, p);
    else
        beside_camera(s, &cam, centre, p);
    memset(out, 0, sizeof *out);
    out->type = SCENE_LIGHT_POINT;
    memcpy(out->position, p, sizeof p);
    out->direction[1] = -1.0f;
    out->color[0] = out->color[1] = out->color[2] = 1.0f;
    /* 2 W/m^2 on the floor below a room's lamp, or at the middle of an object. */
    float d[3];
    vec3_sub(p, centre, d);
    float reach = room ? p[1] - s->bounds_min[1] : vec3_length(d);
    reach = fmaxf(reach, scene_min_light_distance(s));
    out->intensity = 2.0f * reach * reach;
}

/* The triangles' area-weighted normals summed along axis a: which side a flat model faces. */
static double facing(const scene *s, int a)
{
    double sum = 0;
    for (size_t t = 0; t < s->triangle_count; t++) {
        const float *p = s->positions + 9 * t, *n = s->normals + 9 * t;
        float e1[3], e2[3], c[3];
        vec3_sub(p + 3, p, e1);
        vec3_sub(p + 6, p, e2);
        vec3_cross(e1, e2, c);
        sum += (double)vec3_length(c) * (n[a] + n[3 + a] + n[6 + a]);
    }
    return sum;
}

void scene_default_view(const scene *s, float position[3], float target[3])
{
    if (s->camera.valid) {
        memcpy(position, s->camera.position, sizeof s->camera.position);
        memcpy(target, s->camera.target, sizeof s->camera.target);
        return;
    }
    float extent[3];
    for (int a = 0; a < 3; a++)
        extent[a] = s->bounds_max[a] - s->bounds_min[a];
    int along = extent[0] >= extent[2] ? 0 : 2, across = 2 - along;
    float eye = fminf(1.6f, 0.5f * extent[1]) / fmaxf(extent[1], 1e-30f);
    /* The first free point of a few along the longest horizontal axis: a room when most
     * rays from there meet the front of a surface. */
    static const float start[] = {0.1f, 0.25f, 0.4f}, side[] = {0.5f, 0.3f, 0.7f};
    for (int i = 0; i < 9; i++) {
        float f[3];
        f[along] = start[i % 3];
        f[across] = side[i / 3];
        f[1] = eye;
        at(s, f, position);
        int fronts;
        if (!scene_point_is_free(s, position, &fronts))
            continue;
        if (2 * fronts <= PROBES)
            break; /* open space around it: an object */
        memcpy(target, position, 3 * sizeof(float));
        target[along] = s->bounds_max[along];
        return;
    }
    float size = 0;
    int thin = 0;
    for (int a = 0; a < 3; a++) {
        target[a] = 0.5f * (s->bounds_min[a] + s->bounds_max[a]);
        size = fmaxf(size, extent[a]);
        thin = extent[a] < extent[thin] ? a : thin;
    }
    memcpy(position, target, 3 * sizeof(float));
    if (extent[thin] > 0.1f * size) {
        position[1] += 0.3f * size;
        position[2] += 1.5f * size;
        return;
    }
    /* A flat model (a plan, a panel): from the side its surfaces face, a little askew. */
    position[thin] += (facing(s, thin) >= 0 ? 1.5f : -1.5f) * size;
    position[thin == 1 ? 2 : 1] += 0.3f * size;
}

void scene_default_camera(const scene *s, scene_camera *out)
{
    if (s->camera.valid) {
        *out = s->camera;
        return;
    }
    *out = (scene_camera){.valid = 1, .yfov = 60.0f * 3.14159265f / 180.0f};
    scene_default_view(s, out->position, out->target);
}

int scene_light_note(const scene *s, const char *path, char *out, size_t n)
{
    if (s->light_added)
        scene_light_added_note(s, path, out, n);
    else if (s->light_count == 0)
        snprintf(out, n, "scene %s: only emissive materials and no light: every other surface "
                 "stays dark (add a KHR_lights_punctual light)", path);
    return s->light_added || s->light_count == 0;
}

void scene_light_added_note(const scene *s, const char *path, char *out, size_t n)
{
    const scene_light *l = &s->lights[0];
    snprintf(out, n, "scene %s has no lights: added a point light at (%.3g, %.3g, %.3g), "
             "%.3g W/sr, %s (add a KHR_lights_punctual light to choose your own)",
             path, l->position[0], l->position[1], l->position[2], l->intensity,
             outside_bounds(s, l->position) > 0 ? "outside its bounds on its camera's side"
                                                : "inside its bounds");
}
