#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"
#include "base/vec3.h"

static int grow(void **p, size_t elem, size_t count, size_t *capacity)
{
    if (count < *capacity)
        return 0;
    size_t cap = *capacity ? *capacity * 2 : 64;
    /* not xalloc: a scene file's count: its import refuses the file, never exits */
    void *q = realloc(*p, cap * elem);
    if (!q)
        return -1;
    *p = q;
    *capacity = cap;
    return 0;
}

int scene_add_material(scene *s, const scene_material *m)
{
    /* not xalloc: a scene file's count: its import refuses the file, never exits */
    scene_material *q = realloc(s->materials, (s->material_count + 1) * sizeof *q);
    if (!q)
        return -1;
    s->materials = q;
    q[s->material_count] = *m;
    return (int)s->material_count++;
}

int scene_add_texture(scene *s, int width, int height, uint8_t *rgba)
{
    /* not xalloc: a scene file's count: its import refuses the file, never exits */
    scene_texture *q = realloc(s->textures, (s->texture_count + 1) * sizeof *q);
    if (!q)
        return -1;
    s->textures = q;
    q[s->texture_count] = (scene_texture){width, height, rgba};
    return (int)s->texture_count++;
}

long scene_add_triangle(scene *s, const float p[9], const float *normals, const float *uvs,
                        uint32_t material)
{
    size_t n = s->triangle_count, cap = s->triangle_capacity;
    size_t c1 = cap, c2 = cap, c3 = cap, c4 = cap, c5 = cap;
    if (grow((void **)&s->positions, 9 * sizeof(float), n, &c1) ||
        grow((void **)&s->normals, 9 * sizeof(float), n, &c2) ||
        grow((void **)&s->uvs, 6 * sizeof(float), n, &c3) ||
        grow((void **)&s->triangle_material, sizeof(uint32_t), n, &c4) ||
        grow((void **)&s->triangle_object, sizeof(int32_t), n, &c5))
        return -1;
    s->triangle_capacity = c5;
    memcpy(s->positions + 9 * n, p, 9 * sizeof(float));
    float *nn = s->normals + 9 * n;
    if (normals) {
        memcpy(nn, normals, 9 * sizeof(float));
    } else {
        float f[3];
        vec3_triangle_normal(p, f);
        for (int v = 0; v < 3; v++)
            memcpy(nn + 3 * v, f, sizeof f);
    }
    for (int v = 0; v < 3; v++) {
        float *q = nn + 3 * v;
        float len = vec3_length(q);
        if (len > 0.0f && isfinite(len)) {
            q[0] /= len; q[1] /= len; q[2] /= len;
        } else {
            q[0] = 0.0f; q[1] = 1.0f; q[2] = 0.0f;
        }
    }
    if (uvs)
        memcpy(s->uvs + 6 * n, uvs, 6 * sizeof(float));
    else
        memset(s->uvs + 6 * n, 0, 6 * sizeof(float));
    s->triangle_material[n] = material;
    s->triangle_object[n] = s->adding_object - 1;
    s->triangle_count = n + 1;
    return (long)n;
}

int scene_add_quad(scene *s, const float a[3], const float b[3], const float c[3],
                   const float d[3], const float n[3], uint32_t material)
{
    float p1[9], p2[9], nn[9];
    memcpy(p1, a, 12); memcpy(p1 + 3, b, 12); memcpy(p1 + 6, c, 12);
    memcpy(p2, a, 12); memcpy(p2 + 3, c, 12); memcpy(p2 + 6, d, 12);
    for (int k = 0; k < 3; k++)
        memcpy(nn + 3 * k, n, 12);
    const float uv1[6] = {0, 0, 1, 0, 1, 1}, uv2[6] = {0, 0, 1, 1, 0, 1};
    return scene_add_triangle(s, p1, nn, uv1, material) < 0 ||
                   scene_add_triangle(s, p2, nn, uv2, material) < 0
               ? -1
               : 0;
}

int scene_add_rect(scene *s, const float lo[3], const float hi[3], int facing,
                   uint32_t material)
{
    int axis = -1;
    for (int a = 0; a < 3; a++)
        if (lo[a] == hi[a])
            axis = axis < 0 ? a : 3;
    if (axis < 0 || axis > 2 || facing == 0)
        return -1;
    /* Corners in the (u, v) = (axis + 1, axis + 2) plane, two triangles. */
    int u = (axis + 1) % 3, v = (axis + 2) % 3;
    float c[4][3];
    const float us[4] = {0, 1, 1, 0}, vs[4] = {0, 0, 1, 1};
    for (int k = 0; k < 4; k++) {
        c[k][axis] = lo[axis];
        c[k][u] = us[k] ? hi[u] : lo[u];
        c[k][v] = vs[k] ? hi[v] : lo[v];
    }
    float n[3] = {0, 0, 0};
    n[axis] = facing > 0 ? 1.0f : -1.0f;
    const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int t = 0; t < 2; t++) {
        float p[9], nn[9], uv[6];
        for (int k = 0; k < 3; k++) {
            int ci = tri[t][k];
            memcpy(p + 3 * k, c[ci], sizeof c[ci]);
            memcpy(nn + 3 * k, n, sizeof n);
            uv[2 * k] = us[ci];
            uv[2 * k + 1] = vs[ci];
        }
        if (scene_add_triangle(s, p, nn, uv, material) < 0)
            return -1;
    }
    return 0;
}

int scene_add_box(scene *s, const float lo[3], const float hi[3], int inward, uint32_t material)
{
    for (int axis = 0; axis < 3; axis++)
        for (int side = 0; side < 2; side++) {
            float flo[3], fhi[3];
            memcpy(flo, lo, sizeof flo);
            memcpy(fhi, hi, sizeof fhi);
            flo[axis] = fhi[axis] = side ? hi[axis] : lo[axis];
            int facing = (side ? 1 : -1) * (inward ? -1 : 1);
            if (scene_add_rect(s, flo, fhi, facing, material) != 0)
                return -1;
        }
    return 0;
}

int scene_add_light(scene *s, const scene_light *l)
{
    if (s->light_count >= SCENE_MAX_LIGHTS)
        return -1;
    s->lights[s->light_count] = *l;
    return s->light_count++;
}

int scene_add_camera(scene *s, const scene_camera *c)
{
    /* not xalloc: a scene file's count: its import refuses the file, never exits */
    scene_camera *q = realloc(s->cameras, (s->camera_count + 1) * sizeof *q);
    if (!q)
        return -1;
    s->cameras = q;
    q[s->camera_count] = *c;
    return (int)s->camera_count++;
}

int scene_pick_camera(scene *s, const char *which, char *err, size_t errlen)
{
    char *end;
    long index = strtol(which, &end, 10);
    int found = -1;
    if (end != which && *end == '\0') {
        if (index >= 0 && (size_t)index < s->camera_count)
            found = (int)index;
    } else {
        for (size_t i = 0; i < s->camera_count && found < 0; i++)
            if (strcmp(which, s->cameras[i].name) == 0 || strcmp(which, s->cameras[i].camera_name) == 0)
                found = (int)i;
    }
    if (found >= 0) {
        s->camera = s->cameras[found];
        return 0;
    }
    if (s->camera_count == 0) {
        snprintf(err, errlen, "camera %s: the scene has no cameras (leave out --camera, or give "
                 "--position and --target)", which);
        return -1;
    }
    int n = snprintf(err, errlen, "camera %s: no such camera; the scene has", which);
    for (size_t i = 0; i < s->camera_count && n >= 0 && (size_t)n < errlen; i++)
        n += snprintf(err + n, errlen - (size_t)n, "%s %zu \"%s\"", i ? "," : "", i,
                      s->cameras[i].name);
    return -1;
}

int scene_finish(scene *s, char *err, size_t errlen)
{
    if (s->triangle_count == 0) {
        snprintf(err, errlen, "scene has no triangles (add a mesh of triangles, strips or fans)");
        return -1;
    }
    for (int a = 0; a < 3; a++) {
        s->bounds_min[a] = INFINITY;
        s->bounds_max[a] = -INFINITY;
    }
    for (size_t i = 0; i < 3 * s->triangle_count; i++)
        for (int a = 0; a < 3; a++) {
            float x = s->positions[3 * i + a];
            if (!isfinite(x)) {
                snprintf(err, errlen, "scene triangle %zu has a non-finite vertex "
                         "(fix the model's positions)", i / 3);
                return -1;
            }
            if (fabsf(x) > SCENE_MAX_COORD) {
                snprintf(err, errlen, "scene triangle %zu has a vertex at %g m, beyond the "
                         "limit of %g m from the origin (scale the model down or move it "
                         "nearer the origin)", i / 3, (double)x, (double)SCENE_MAX_COORD);
                return -1;
            }
            if (x < s->bounds_min[a]) s->bounds_min[a] = x;
            if (x > s->bounds_max[a]) s->bounds_max[a] = x;
        }
    for (int i = 0; i < s->light_count; i++)
        for (int a = 0; a < 3 && s->lights[i].type != SCENE_LIGHT_DIRECTIONAL; a++)
            if (!(fabsf(s->lights[i].position[a]) <= SCENE_MAX_COORD)) {
                snprintf(err, errlen, "scene light %d is at %g m, beyond the limit of %g m "
                         "from the origin (move it nearer)", i,
                         (double)s->lights[i].position[a], (double)SCENE_MAX_COORD);
                return -1;
            }
    for (uint32_t i = 0; i < s->triangle_count; i++)
        if (s->triangle_material[i] >= s->material_count) {
            snprintf(err, errlen, "scene triangle %u uses material %u of %zu", i,
                     s->triangle_material[i], s->material_count);
            return -1;
        }
    return 0;
}

void scene_free(scene *s)
{
    free(s->positions);
    free(s->normals);
    free(s->uvs);
    free(s->triangle_material);
    free(s->triangle_object);
    free(s->objects);
    for (size_t i = 0; i < s->anim_channel_count; i++) {
        free(s->anim_channels[i].times);
        free(s->anim_channels[i].values);
    }
    free(s->anim_channels);
    free(s->materials);
    for (size_t i = 0; i < s->texture_count; i++)
        free(s->textures[i].rgba);
    free(s->textures);
    free(s->cameras);
    memset(s, 0, sizeof *s);
}

int scene_has_emitter(const scene *s)
{
    for (size_t t = 0; t < s->triangle_count; t++) {
        const float *e = s->materials[s->triangle_material[t]].emissive;
        if (e[0] > 0 || e[1] > 0 || e[2] > 0)
            return 1;
    }
    return 0;
}

void scene_light_aim(scene_light *l, const float target[3])
{
    float d[3], len = 0;
    for (int a = 0; a < 3; a++) {
        d[a] = target[a] - l->position[a];
        len += d[a] * d[a];
    }
    len = sqrtf(len);
    if (!(len > 0))
        return;
    for (int a = 0; a < 3; a++)
        l->direction[a] = d[a] / len;
}

float scene_diagonal(const scene *s)
{
    float d2 = 0;
    for (int a = 0; a < 3; a++) {
        float e = s->bounds_max[a] - s->bounds_min[a];
        d2 += e * e;
    }
    return sqrtf(d2);
}

float scene_min_light_distance(const scene *s)
{
    return scene_diagonal(s) / 64.0f;
}

float scene_far_plane(const scene *s)
{
    return 4.0f * scene_diagonal(s) + 10.0f;
}
