/* reference_sample: one row of the path-traced reference (reference.h for the model).
 *
 * Per pixel: one primary ray through the pixel centre gives the visible point x0 and its
 * exact direct light (no sampling). Each of `samples` paths then adds
 *   - emitter -> x0 (indirect1 and indirect);
 *   - for k = 1..max_bounces: a cosine-weighted ray to x_k, the spots' light reflected
 *     there by next-event estimation (k = 1 goes to indirect1 too), and emitter -> x_k.
 * Emitter -> x_k light combines two strategies with the power heuristic (multiple
 * importance sampling): area sampling of the emissive triangles, and the cosine-weighted
 * ray from x_k hitting an emitter. Area sampling alone has unbounded variance where an
 * emitter meets a surface (1/d^2 at corners); the weights remove it and count each path
 * once. At the last vertex no ray leaves, so area sampling there takes full weight.
 * Spot -> x1 -> x0 (the LPV's own light) has two strategies too, also weighted by the power
 * heuristic: the cosine ray from x0 with next-event estimation at x1, and a ray from the
 * spot into its cone whose hit is connected to x0 (as the RSM's texels are). The second
 * finds a small lit patch that cosine rays rarely hit; it halves the one-bounce noise of the
 * default room for 1.4x the rays. At later vertices it would cost twice the rays for a
 * quarter less noise, so there the cosine strategy works alone. */
#include <math.h>
#include <string.h>

#include "reference_internal.h"

static uint64_t splitmix64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* Cosine-weighted direction around n. */
static void cosine_direction(const float n[3], rng *g, float d[3])
{
    float r1 = rng_next(g), r2 = rng_next(g);
    float r = sqrtf(r1), phi = 2 * PI_F * r2;
    float x = r * cosf(phi), y = r * sinf(phi), z = sqrtf(fmaxf(0, 1 - r1));
    float t[3], bt[3];
    vec3_basis(n, t, bt);
    for (int k = 0; k < 3; k++)
        d[k] = x * t[k] + y * bt[k] + z * n[k];
    vec3_normalize(d);
}

/* Exact direct light at the visible point: emission + Blinn-Phong of every light, seen from
 * v (unit, back along the primary ray: towards the eye, or an orthographic view's way). */
static void shade_direct(const reference_job *job, const hit *h, const float v[3], float out[3],
                         uint64_t *rays)
{
    const scene_material *m = &job->ref->scene->materials[job->ref->scene->triangle_material[h->tri]];
    for (int k = 0; k < 3; k++)
        out[k] = m->emissive[k];
    float alpha = m->roughness * m->roughness;
    float mexp = 2.0f / fmaxf(alpha * alpha, 1e-3f) - 2.0f;
    for (int i = 0; i < job->light_count; i++) {
        float e[3], l[3], hv[3];
        if (!reference_light_one(job, i, h, 1, e, l, rays))
            continue;
        for (int k = 0; k < 3; k++)
            hv[k] = l[k] + v[k];
        vec3_normalize(hv);
        float spec = (mexp + 8) / (8 * PI_F) * 0.04f * powf(fmaxf(vec3_dot(h->n, hv), 0), mexp);
        for (int k = 0; k < 3; k++)
            out[k] += (h->albedo[k] / PI_F + spec) * e[k];
    }
}

/* One path from the visible point; adds to the one-bounce and many-bounce sums. At every
 * vertex x_k: light arriving from emitters (and by the spot strategy at x0); then a cosine
 * ray to x_(k+1), emission it hits, and the spots' light at x_(k+1) by next-event
 * estimation. One-bounce light: all of that at k = 0. */
static void sample_path(const reference_job *job, const hit *x0, rng *g, double acc1[3],
                        double acc[3], uint64_t *rays)
{
    const scene *s = job->ref->scene;
    float arrive[3] = {1, 1, 1}; /* throughput from the camera vertex to cur, before its BRDF */
    hit cur = *x0;
    for (int k = 0;; k++) {
        int more = k < job->max_bounces; /* a cosine ray leaves x_k */
        float e[3], c[3] = {0, 0, 0};
        reference_light_emitters(job, &cur, more, g, e, rays);
        for (int i = 0; more && k == 0 && i < job->light_count; i++)
            reference_light_connect(job, i, &cur, g, c, rays);
        for (int j = 0; j < 3; j++) {
            float v = arrive[j] * (c[j] + cur.albedo[j] / PI_F * e[j]);
            acc1[j] += k == 0 ? v : 0;
            acc[j] += v;
        }
        if (!more)
            break;
        float beta[3]; /* f cos / pdf = albedo for the cosine ray */
        for (int j = 0; j < 3; j++)
            beta[j] = arrive[j] * cur.albedo[j];
        if (k >= 2) { /* Russian roulette, unbiased: survivors carry 1/q */
            float q = fminf(0.95f, fmaxf(beta[0], fmaxf(beta[1], beta[2])));
            if (!(rng_next(g) < q))
                break;
            for (int j = 0; j < 3; j++)
                beta[j] /= q;
        }
        float d[3], o[3];
        cosine_direction(cur.n, g, d);
        if (vec3_dot(d, cur.ng) <= 0)
            break; /* below the true surface (smooth normals): no light that way */
        reference_ray_offset(&cur, o);
        struct RTCRayHit rh;
        if (!reference_ray_trace(job, o, d, INFINITY, &rh, rays))
            break;
        float back[3] = {-d[0], -d[1], -d[2]}, t = rh.ray.tfar;
        hit next;
        reference_ray_hit(job->ref, &rh.hit, back, &next);
        float tr = transmittance(job->absorption, t);
        float we = reference_light_emitter_hit_weight(job->ref, &cur, d, t, next.tri);
        const float *le = s->materials[s->triangle_material[next.tri]].emissive;
        float cosine_pdf = k == 0 ? vec3_dot(cur.n, d) / PI_F * vec3_dot(next.ng, back) / (t * t) : 0;
        float es[3];
        reference_light_all(job, &next, cosine_pdf, es, rays);
        for (int j = 0; j < 3; j++) {
            arrive[j] = beta[j] * tr;
            /* emitter -> x_k and spot -> x_(k+1) -> x_k */
            float v = arrive[j] * (le[j] * we + next.albedo[j] / PI_F * es[j]);
            acc1[j] += k == 0 ? v : 0;
            acc[j] += v;
        }
        cur = next;
    }
}

/* The visible point's ambient occlusion (frame/ao.h) from `samples` cosine rays: each
 * ray's visibility of the first surface within the distance limit. A direction below the
 * true surface (smooth normals) meets it at once. */
static float ambient_occlusion(const reference_job *job, const hit *x0, uint64_t pix,
                               uint64_t *rays)
{
    rng g = {splitmix64(job->seed ^ splitmix64(pix ^ 0xa0a0a0a0a0a0a0a0ull))};
    float far = job->ao_distance > 0 ? job->ao_distance : INFINITY, o[3];
    reference_ray_offset(x0, o);
    double sum = 0;
    for (int s = 0; s < job->samples; s++) {
        float d[3];
        cosine_direction(x0->n, &g, d);
        if (vec3_dot(d, x0->ng) <= 0) {
            sum += ao_visibility(0.0f, job->ao_distance, job->ao_falloff);
            continue;
        }
        struct RTCRayHit rh;
        float t = reference_ray_trace(job, o, d, far, &rh, rays) ? rh.ray.tfar : -1.0f;
        sum += ao_visibility(t, job->ao_distance, job->ao_falloff);
    }
    return (float)(sum / job->samples);
}

void reference_sample_row(void *ctx, int row)
{
    reference_job *job = ctx;
    uint64_t rays = 0;
    for (int x = 0; x < job->width; x++) {
        size_t pix = (size_t)row * job->width + x;
        float *dst[3] = {job->direct + 3 * pix, job->indirect1 + 3 * pix, job->indirect + 3 * pix};
        for (int i = 0; i < 3; i++)
            dst[i][0] = dst[i][1] = dst[i][2] = 0;
        job->coverage[pix] = 0;
        float *ao = job->ao ? job->ao + 3 * pix : NULL;
        if (ao)
            ao[0] = ao[1] = ao[2] = 1.0f;
        /* Pixel centre -> clip space at the near and far planes -> world. */
        double ndc[2] = {2.0 * (x + 0.5) / job->width - 1.0, 1.0 - 2.0 * (row + 0.5) / job->height};
        double w[2][3];
        for (int z = 0; z < 2; z++) {
            double c[4] = {ndc[0], ndc[1], z ? 1.0 : -1.0, 1.0}, q[4];
            for (int r = 0; r < 4; r++)
                q[r] = job->inv_view_projection[r] * c[0] + job->inv_view_projection[4 + r] * c[1] +
                       job->inv_view_projection[8 + r] * c[2] + job->inv_view_projection[12 + r] * c[3];
            for (int k = 0; k < 3; k++)
                w[z][k] = q[k] / q[3];
        }
        float o[3], d[3];
        for (int k = 0; k < 3; k++) {
            o[k] = (float)w[0][k];
            d[k] = (float)(w[1][k] - w[0][k]);
        }
        float len = sqrtf(vec3_dot(d, d));
        if (!(len > 0) || !isfinite(len))
            continue;
        for (int k = 0; k < 3; k++)
            d[k] /= len;
        struct RTCRayHit rh;
        if (!reference_ray_trace(job, o, d, len, &rh, &rays))
            continue;
        job->coverage[pix] = 1;
        hit x0;
        float toward_eye[3] = {-d[0], -d[1], -d[2]};
        reference_ray_hit(job->ref, &rh.hit, toward_eye, &x0);
        shade_direct(job, &x0, toward_eye, dst[0], &rays);
        if (ao)
            ao[0] = ao[1] = ao[2] = ambient_occlusion(job, &x0, pix, &rays);
        for (int k = 0; k < 3; k++) /* the ambient term, as shade.frag has it */
            dst[0][k] += x0.albedo[k] * job->ambient * (ao ? ao[0] : 1.0f);
        rng g = {splitmix64(job->seed ^ splitmix64(pix))};
        double acc1[3] = {0, 0, 0}, acc[3] = {0, 0, 0};
        for (int s = 0; s < job->samples; s++)
            sample_path(job, &x0, &g, acc1, acc, &rays);
        for (int k = 0; k < 3; k++) {
            dst[0][k] *= job->exposure;
            dst[1][k] = (float)(acc1[k] / job->samples) * job->exposure;
            dst[2][k] = (float)(acc[k] / job->samples) * job->exposure;
        }
    }
    job->row_rays[row] = rays;
}
