/* reference_light: the light arriving at a path vertex from the lights and the emitters,
 * and the multiple-importance weights between the strategies (reference_sample.c has the
 * overview). */
#include <math.h>

#include "reference_internal.h"
#include "base/vec3.h"

/* Light i arriving at h: irradiance E (on the shading normal) and the unit direction to the
 * light. 0 when it does not reach h. As shade.frag, without PCF. */
int reference_light_one(const reference_job *job, int i, const hit *h, int shadow, float e[3],
                        float l[3], uint64_t *rays)
{
    const reference_light *s = &job->lights[i];
    float f, dist;
    if (s->type == SCENE_LIGHT_DIRECTIONAL) {
        for (int k = 0; k < 3; k++)
            l[k] = -s->axis[k];
        dist = INFINITY;
        f = transmittance(job->absorption, vec3_dot(h->p, s->axis) + s->travel0);
    } else {
        float to[3];
        for (int k = 0; k < 3; k++)
            to[k] = s->position[k] - h->p[k];
        float r2 = vec3_dot(to, to), r = sqrtf(r2);
        if (!(r > 0))
            return 0;
        for (int k = 0; k < 3; k++)
            l[k] = to[k] / r;
        float cone = 1;
        if (s->type == SCENE_LIGHT_SPOT) {
            float c = -vec3_dot(l, s->direction);
            cone = fminf(fmaxf((c - s->cos_outer) / fmaxf(s->cos_inner - s->cos_outer, 1e-4f), 0), 1);
        }
        dist = r;
        f = cone / fmaxf(r2, job->min_light_distance2) * transmittance(job->absorption, r);
    }
    float cos_i = vec3_dot(h->n, l);
    if (cos_i <= 0 || vec3_dot(h->ng, l) <= 0 || !(f > 0))
        return 0;
    if (shadow) {
        float o[3], od[3];
        reference_ray_offset(h, o);
        if (isfinite(dist)) {
            for (int k = 0; k < 3; k++)
                od[k] = s->position[k] - o[k];
            dist = sqrtf(vec3_dot(od, od));
            for (int k = 0; k < 3; k++)
                od[k] /= dist;
        } else {
            for (int k = 0; k < 3; k++)
                od[k] = l[k];
        }
        if (!reference_ray_visible(job, o, od, dist, rays))
            return 0;
    }
    for (int k = 0; k < 3; k++)
        e[k] = s->radiance[k] * f * cos_i;
    return 1;
}

/* a^2 / (a^2 + b^2) of two densities, defined where that is not: a density overflows to
 * infinity where a ray meets a surface at t ~ 0 (a block standing on a floor): the
 * infinite one takes the weight, both 0 give 0. In double no float's square overflows. */
static float power_heuristic(float a, float b)
{
    double a2 = (double)a * a, b2 = (double)b * b;
    if (isinf(a2) || isinf(b2))
        return isinf(b2) ? (isinf(a2) ? 0.5f : 0.0f) : 1.0f;
    return a2 + b2 > 0 ? (float)(a2 / (a2 + b2)) : 0.0f;
}

/* Area density at h of the light strategy (reference_light_connect()) for light i, l the
 * direction from h to the light: a direction uniform in the sampled cone (0 outside it),
 * or for a directional light a point uniform on its window. Densities in area measure take
 * the geometric normal's cosine. */
static float light_area_pdf(const reference_job *job, int i, const hit *h, const float l[3])
{
    const reference_light *s = &job->lights[i];
    if (s->type == SCENE_LIGHT_DIRECTIONAL)
        return vec3_dot(h->ng, l) / s->window_area;
    if (-vec3_dot(l, s->axis) < s->sample_cos)
        return 0;
    float to[3];
    for (int k = 0; k < 3; k++)
        to[k] = s->position[k] - h->p[k];
    return vec3_dot(h->ng, l) / vec3_dot(to, to) / (2 * PI_F * (1 - s->sample_cos));
}

/* Irradiance at h from all lights (Lambertian vertices). cosine_pdf > 0: h was reached
 * from the visible point by a cosine ray of that area density, weighted against the light
 * strategy (reference_light_connect()); 0: no other strategy, full weight. */
void reference_light_all(const reference_job *job, const hit *h, float cosine_pdf, float e[3],
                         uint64_t *rays)
{
    e[0] = e[1] = e[2] = 0;
    for (int i = 0; i < job->light_count; i++) {
        float ei[3], l[3];
        if (!reference_light_one(job, i, h, 1, ei, l, rays))
            continue;
        float w = cosine_pdf > 0 ? power_heuristic(cosine_pdf, light_area_pdf(job, i, h, l)) : 1;
        for (int k = 0; k < 3; k++)
            e[k] += ei[k] * w;
    }
}

/* One-sample estimate of the irradiance at h from the emissive triangles (their front
 * side only, as the LPV's emitter VPLs): a triangle picked by power, a uniform point.
 * mis: a cosine-weighted ray also leaves h, so weight against it. */
void reference_light_emitters(const reference_job *job, const hit *h, int mis, rng *g,
                              float e[3], uint64_t *rays)
{
    const reference *ref = job->ref;
    e[0] = e[1] = e[2] = 0;
    if (ref->emitter_count == 0)
        return;
    double u = (double)rng_next(g) * ref->emitter_power;
    size_t lo = 0, hi = ref->emitter_count - 1;
    while (lo < hi) { /* first cdf entry above u */
        size_t mid = (lo + hi) / 2;
        if (ref->emitter_cdf[mid] > u)
            hi = mid;
        else
            lo = mid + 1;
    }
    uint32_t t = ref->emitter_triangle[lo];
    const scene *s = ref->scene;
    const float *p = s->positions + 9 * (size_t)t;
    float r1 = sqrtf(rng_next(g)), r2 = rng_next(g);
    float b0 = 1 - r1, b1 = r1 * (1 - r2), b2 = r1 * r2;
    float y[3];
    for (int k = 0; k < 3; k++)
        y[k] = b0 * p[k] + b1 * p[3 + k] + b2 * p[6 + k];
    float area = vec3_triangle_area(p); /* > 0 for every listed emitter */
    float o[3], d[3];
    reference_ray_offset(h, o);
    for (int k = 0; k < 3; k++)
        d[k] = y[k] - o[k];
    float dist2 = vec3_dot(d, d), dist = sqrtf(dist2);
    if (!(dist > 0) || !(area > 0))
        return;
    for (int k = 0; k < 3; k++)
        d[k] /= dist;
    float cos_x = vec3_dot(h->n, d), cos_e = -vec3_dot(ref->emitter_front + 3 * lo, d);
    if (cos_x <= 0 || cos_e <= 0 || vec3_dot(h->ng, d) <= 0)
        return;
    if (!reference_ray_visible(job, o, d, dist, rays))
        return;
    const float *le = s->materials[s->triangle_material[t]].emissive;
    float area_pdf = ref->emitter_area_pdf[lo];
    float w = mis ? power_heuristic(area_pdf * dist2 / cos_e, cos_x / PI_F) : 1.0f;
    float f = cos_x * cos_e / dist2 / area_pdf * w * transmittance(job->absorption, dist);
    for (int k = 0; k < 3; k++)
        e[k] = le[k] * f;
}

/* MIS weight of a cosine-weighted ray from `from` (direction d, length t) that hit the
 * front of an emitter; 0 for anything else. */
float reference_light_emitter_hit_weight(const reference *ref, const hit *from, const float d[3],
                                         float t, uint32_t tri)
{
    int32_t i = ref->emitter_of[tri];
    if (i < 0)
        return 0;
    float cos_e = -vec3_dot(ref->emitter_front + 3 * i, d);
    if (cos_e <= 0)
        return 0;
    return power_heuristic(vec3_dot(from->n, d) / PI_F, ref->emitter_area_pdf[i] * t * t / cos_e);
}

/* Light strategy for light i -> y -> x0: a ray from the light (a direction uniform in the
 * sampled cone, or for a directional light a point uniform on its window, along it), its
 * first hit y lit as reference_light_one() says, connected to x0. Adds the radiance it
 * brings to x0 (times x0's albedo / pi) to out, weighted against the cosine strategy. */
void reference_light_connect(const reference_job *job, int i, const hit *x0, rng *g,
                             float out[3], uint64_t *rays)
{
    const reference_light *s = &job->lights[i];
    float from[3], w[3];
    if (s->type == SCENE_LIGHT_DIRECTIONAL) {
        float a = rng_next(g), b = rng_next(g);
        for (int k = 0; k < 3; k++) {
            from[k] = s->window[0][k] + a * s->window[1][k] + b * s->window[2][k];
            w[k] = s->axis[k];
        }
    } else {
        const float *axis = s->axis;
        float t[3], bt[3];
        vec3_basis(axis, t, bt);
        float c = 1 - rng_next(g) * (1 - s->sample_cos), phi = 2 * PI_F * rng_next(g);
        float sn = sqrtf(fmaxf(0, 1 - c * c));
        for (int k = 0; k < 3; k++) {
            w[k] = sn * cosf(phi) * t[k] + sn * sinf(phi) * bt[k] + c * axis[k];
            from[k] = s->position[k];
        }
        vec3_normalize(w);
    }
    struct RTCRayHit rh;
    if (!reference_ray_trace(job, from, w, INFINITY, &rh, rays))
        return;
    hit y;
    float back[3] = {-w[0], -w[1], -w[2]};
    reference_ray_hit(job->ref, &rh.hit, back, &y);
    float e[3], l[3];
    if (!reference_light_one(job, i, &y, 0, e, l, rays)) /* y is the light's first hit */
        return;
    float oy[3], ox[3], d[3];
    reference_ray_offset(&y, oy);
    reference_ray_offset(x0, ox);
    for (int k = 0; k < 3; k++)
        d[k] = ox[k] - oy[k];
    float d2 = vec3_dot(d, d), dist = sqrtf(d2);
    if (!(dist > 0))
        return;
    for (int k = 0; k < 3; k++)
        d[k] /= dist;
    float cos_y = vec3_dot(y.n, d), cos_x = -vec3_dot(x0->n, d);
    if (cos_y <= 0 || cos_x <= 0 || vec3_dot(y.ng, d) <= 0 || -vec3_dot(x0->ng, d) <= 0)
        return;
    if (!reference_ray_visible(job, oy, d, dist, rays))
        return;
    float pdf_light = light_area_pdf(job, i, &y, l), pdf_cos = cos_x / PI_F * vec3_dot(y.ng, d) / d2;
    if (!(pdf_light > 0))
        return;
    float f = cos_y * cos_x / d2 * transmittance(job->absorption, dist) / pdf_light *
              power_heuristic(pdf_light, pdf_cos);
    for (int k = 0; k < 3; k++)
        out[k] += x0->albedo[k] / PI_F * y.albedo[k] / PI_F * e[k] * f;
}
