/* reference_ray: the path tracer's ray primitives on the Embree scene (reference_internal.h):
 * closest hit, visibility between two points, the hit's surface (normals, textured albedo)
 * and the offset that keeps a new ray off its own surface. Shared by reference_sample.c
 * (paths) and reference_light.c (light arriving at a vertex); knows nothing of either. */
#include <math.h>

#include "reference_internal.h"

/* Bilinear, wrap repeat, texel centres at half-integers, as GL samples level 0. */
static void texture_sample(const reference *ref, int t, const float uv[2], float out[3])
{
    const scene_texture *tex = &ref->scene->textures[t];
    const float *img = ref->texture_linear[t];
    float x = uv[0] * tex->width - 0.5f, y = uv[1] * tex->height - 0.5f;
    float fx = floorf(x), fy = floorf(y);
    float ax = x - fx, ay = y - fy;
    long x0 = (long)fx, y0 = (long)fy;
    for (int c = 0; c < 3; c++)
        out[c] = 0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            long xi = (x0 + i) % tex->width, yi = (y0 + j) % tex->height;
            xi += xi < 0 ? tex->width : 0;
            yi += yi < 0 ? tex->height : 0;
            float w = (i ? ax : 1 - ax) * (j ? ay : 1 - ay);
            const float *px = img + 3 * ((size_t)yi * tex->width + (size_t)xi);
            for (int c = 0; c < 3; c++)
                out[c] += w * px[c];
        }
}

/* Fills h from Embree's hit; normals turned to face `toward` (a direction, not a point). */
void reference_ray_hit(const reference *ref, const struct RTCHit *eh, const float toward[3],
                       hit *h)
{
    const scene *s = ref->scene;
    uint32_t t = eh->primID;
    float b0 = 1.0f - eh->u - eh->v, b1 = eh->u, b2 = eh->v;
    const float *p = s->positions + 9 * (size_t)t, *n = s->normals + 9 * (size_t)t;
    const float *uv = s->uvs + 6 * (size_t)t;
    for (int i = 0; i < 3; i++) {
        h->p[i] = b0 * p[i] + b1 * p[3 + i] + b2 * p[6 + i];
        h->n[i] = b0 * n[i] + b1 * n[3 + i] + b2 * n[6 + i];
        h->ng[i] = ref->face_normal[3 * t + i];
    }
    vec3_normalize(h->n);
    if (vec3_dot(h->n, toward) < 0)
        for (int i = 0; i < 3; i++)
            h->n[i] = -h->n[i];
    if (vec3_dot(h->ng, toward) < 0)
        for (int i = 0; i < 3; i++)
            h->ng[i] = -h->ng[i];
    const scene_material *m = &s->materials[s->triangle_material[t]];
    for (int i = 0; i < 3; i++)
        h->albedo[i] = m->base_color[i];
    if (m->base_color_texture >= 0 && (size_t)m->base_color_texture < s->texture_count) {
        float tuv[2] = {b0 * uv[0] + b1 * uv[2] + b2 * uv[4], b0 * uv[1] + b1 * uv[3] + b2 * uv[5]};
        float texel[3];
        texture_sample(ref, m->base_color_texture, tuv, texel);
        for (int i = 0; i < 3; i++)
            h->albedo[i] *= texel[i];
    }
    h->tri = t;
}

/* Ray origin off the surface along the geometric normal, scaled with the coordinates. */
void reference_ray_offset(const hit *h, float o[3])
{
    float scale = 1e-4f * (1.0f + fmaxf(fabsf(h->p[0]), fmaxf(fabsf(h->p[1]), fabsf(h->p[2]))));
    for (int i = 0; i < 3; i++)
        o[i] = h->p[i] + h->ng[i] * scale;
}

int reference_ray_trace(const reference_job *job, const float o[3], const float d[3],
                        float tfar, struct RTCRayHit *rh, uint64_t *rays)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    *rh = (struct RTCRayHit){
        .ray = {.org_x = o[0], .org_y = o[1], .org_z = o[2], .tnear = 0, .dir_x = d[0],
                .dir_y = d[1], .dir_z = d[2], .tfar = tfar, .mask = 0xffffffffu},
        .hit = {.geomID = RTC_INVALID_GEOMETRY_ID, .primID = RTC_INVALID_GEOMETRY_ID},
    };
    scene_rt_intersect(&job->ref->rt, &ctx, rh);
    (*rays)++;
    return rh->hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

/* 1 when nothing lies between o and o + d * dist (d unit), leaving a little at the end. */
int reference_ray_visible(const reference_job *job, const float o[3], const float d[3],
                          float dist, uint64_t *rays)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRay ray = {.org_x = o[0], .org_y = o[1], .org_z = o[2], .tnear = 0,
                         .dir_x = d[0], .dir_y = d[1], .dir_z = d[2],
                         .tfar = dist * (1.0f - 1e-4f), .mask = 0xffffffffu};
    scene_rt_occluded(&job->ref->rt, &ctx, &ray);
    (*rays)++;
    return ray.tfar >= 0; /* Embree sets tfar to -inf on a hit */
}

