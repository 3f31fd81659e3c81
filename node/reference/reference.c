/* reference: the Embree scene, the per-render setup and the row-parallel run
 * (reference_sample.c traces the paths). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/mat4.h"
#include "base/vec3.h"
#include "base/xalloc.h"
#include "frame/light_view.h"
#include "reference_internal.h"

static float srgb_to_linear(int c)
{
    float v = (float)c / 255.0f;
    return v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f);
}

/* Geometric normals, and the emissive triangles with their lit side and power. */
static int build_tables(reference *ref)
{
    const scene *s = ref->scene;
    /* not xalloc: the scene's triangles: -1 to the caller */
    ref->face_normal = malloc(s->triangle_count * 3 * sizeof *ref->face_normal);
    ref->emitter_triangle = malloc(s->triangle_count * sizeof *ref->emitter_triangle);
    ref->emitter_front = malloc(s->triangle_count * 3 * sizeof *ref->emitter_front);
    ref->emitter_cdf = malloc(s->triangle_count * sizeof *ref->emitter_cdf);
    ref->emitter_of = malloc(s->triangle_count * sizeof *ref->emitter_of);
    ref->emitter_area_pdf = malloc(s->triangle_count * sizeof *ref->emitter_area_pdf);
    if (!ref->face_normal || !ref->emitter_triangle || !ref->emitter_front ||
        !ref->emitter_cdf || !ref->emitter_of || !ref->emitter_area_pdf)
        return -1;
    for (size_t t = 0; t < s->triangle_count; t++) {
        const float *p = s->positions + 9 * t, *vn = s->normals + 9 * t;
        float f[3], nsum[3];
        for (int k = 0; k < 3; k++)
            nsum[k] = vn[k] + vn[3 + k] + vn[6 + k];
        vec3_triangle_normal(p, f);
        float len = vec3_length(f);
        float *n = ref->face_normal + 3 * t;
        for (int k = 0; k < 3; k++) /* degenerate triangles: Embree never reports a hit */
            n[k] = len > 0 ? f[k] / len : 0;
        ref->emitter_of[t] = -1;
        const float *e = s->materials[s->triangle_material[t]].emissive;
        double power = 0.5 * len * (e[0] + e[1] + e[2]) / 3.0;
        if (!(power > 0))
            continue;
        /* The side of the vertex normals, as the rasterizer's emitter VPLs. */
        float side = vec3_dot(n, nsum) < 0 ? -1.0f : 1.0f;
        size_t i = ref->emitter_count++;
        ref->emitter_of[t] = (int32_t)i;
        ref->emitter_triangle[i] = (uint32_t)t;
        ref->emitter_area_pdf[i] = (float)(power / (0.5 * len)); /* / total power below */
        for (int k = 0; k < 3; k++)
            ref->emitter_front[3 * i + k] = side * n[k];
        ref->emitter_power += power;
        ref->emitter_cdf[i] = ref->emitter_power;
    }
    for (size_t i = 0; i < ref->emitter_count; i++)
        ref->emitter_area_pdf[i] = (float)(ref->emitter_area_pdf[i] / ref->emitter_power);
    /* not xalloc: the scene's textures and their sizes: -1 to the caller */
    ref->texture_linear = calloc(s->texture_count ? s->texture_count : 1, sizeof *ref->texture_linear);
    if (!ref->texture_linear)
        return -1;
    float lut[256];
    for (int c = 0; c < 256; c++)
        lut[c] = srgb_to_linear(c);
    for (size_t i = 0; i < s->texture_count; i++) {
        const scene_texture *t = &s->textures[i];
        size_t n = (size_t)t->width * (size_t)t->height;
        float *img = malloc((n ? n : 1) * 3 * sizeof *img); /* not xalloc: as above */
        if (!img)
            return -1;
        for (size_t j = 0; j < n; j++)
            for (int c = 0; c < 3; c++)
                img[3 * j + c] = lut[t->rgba[4 * j + c]];
        ref->texture_linear[i] = img;
    }
    return 0;
}

reference *reference_create(const scene *s, int threads, char *err, size_t errlen)
{
    if (!s || s->triangle_count == 0 || s->material_count == 0) {
        snprintf(err, errlen, "reference: the scene has no triangles or materials (load it first)");
        return NULL;
    }
    reference *ref = xcalloc(1, sizeof *ref);
    ref->scene = s;
    if (build_tables(ref) != 0) {
        snprintf(err, errlen, "reference: out of memory for %zu triangles", s->triangle_count);
        reference_destroy(ref);
        return NULL;
    }
    char why[256];
    if (scene_rt_build(&ref->rt, s, threads, why, sizeof why) != 0) {
        snprintf(err, errlen, "reference: %s", why);
        reference_destroy(ref);
        return NULL;
    }
    if (!(ref->pool = workpool_create(threads))) {
        snprintf(err, errlen, "reference: cannot start %d threads", threads);
        reference_destroy(ref);
        return NULL;
    }
    return ref;
}

void reference_destroy(reference *ref)
{
    if (!ref)
        return;
    if (ref->pool)
        workpool_destroy(ref->pool);
    scene_rt_release(&ref->rt);
    if (ref->texture_linear)
        for (size_t i = 0; i < ref->scene->texture_count; i++)
            free(ref->texture_linear[i]);
    free(ref->texture_linear);
    free(ref->face_normal);
    free(ref->emitter_triangle);
    free(ref->emitter_front);
    free(ref->emitter_cdf);
    free(ref->emitter_of);
    free(ref->emitter_area_pdf);
    free(ref);
}

static int all_finite(const float *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

/* Lights as the renderer hands them to shade.frag: lit ones (light_is_lit()), angles clamped
 * (light_cone()). */
static int setup_job(reference_job *job, const reference_render_desc *d, char *err, size_t errlen)
{
    const frame_params *p = d->params;
    const frame_view *v = d->view;
    if (v->width <= 0 || v->height <= 0 || v->width > 16384 || v->height > 16384) {
        snprintf(err, errlen, "reference: view size %dx%d is out of range (1..16384)", v->width,
                 v->height);
        return -1;
    }
    if (!isfinite(p->absorption)) {
        snprintf(err, errlen, "reference: absorption is not finite");
        return -1;
    }
    for (int i = 0; i < p->light_count && i < FRAME_MAX_LIGHTS; i++) {
        const frame_light *l = &p->lights[i];
        if (!l->enabled)
            continue;
        if (!all_finite(l->position, 3) || !all_finite(l->direction, 3) ||
            !all_finite(l->color, 3) || !isfinite(l->intensity) || !isfinite(l->outer_angle) ||
            !isfinite(l->inner_angle)) {
            snprintf(err, errlen, "reference: light %d has a non-finite position, direction, "
                     "colour, intensity or angle: fix or disable it", i);
            return -1;
        }
        if ((unsigned)l->type >= SCENE_LIGHT_TYPES ||
            (l->type != SCENE_LIGHT_POINT && !(vec3_dot(l->direction, l->direction) > 0))) {
            snprintf(err, errlen, "reference: light %d has an unknown type or no direction: fix "
                     "or disable it", i);
            return -1;
        }
        if (!light_is_lit(l))
            continue;
        reference_light *s = &job->lights[job->light_count++];
        float outer, inner;
        light_cone(l, &outer, &inner);
        s->type = l->type;
        memcpy(s->position, l->position, sizeof s->position);
        memcpy(s->direction, l->direction, sizeof s->direction);
        memcpy(s->axis, l->direction, sizeof s->axis);
        if (!(vec3_normalize(s->axis) > 0))
            memcpy(s->axis, (const float[3]){0, -1, 0}, sizeof s->axis);
        for (int c = 0; c < 3; c++)
            s->radiance[c] = l->color[c] * l->intensity;
        s->cos_outer = cosf(outer);
        s->cos_inner = cosf(inner);
        s->sample_cos = l->type == SCENE_LIGHT_POINT ? -1.0f : s->cos_outer;
        if (l->type == SCENE_LIGHT_DIRECTIONAL) {
            light_view lv;
            light_directional_view(job->ref->scene, s->axis, &lv);
            const float origin[3] = {0, 0, 0};
            s->travel0 = light_directional_travel(job->ref->scene, s->axis, origin);
            memcpy(s->window, lv.window, sizeof s->window);
            s->window_area = 4.0f * lv.extent[0] * lv.extent[1];
        }
    }
    double vp[16], view[16];
    mat4d_from_float(v->projection, vp);
    mat4d_from_float(v->view, view);
    mat4d_mul(vp, view, vp);
    if (mat4d_inverse(vp, job->inv_view_projection) != 0) {
        snprintf(err, errlen, "reference: the view-projection matrix is singular (degenerate camera)");
        return -1;
    }
    job->absorption = p->absorption;
    float closest = scene_min_light_distance(job->ref->scene);
    job->min_light_distance2 = closest * closest;
    job->exposure = p->exposure > 0 ? p->exposure : 1.0f;
    job->width = v->width;
    job->height = v->height;
    job->samples = d->samples > 0 ? d->samples : REFERENCE_DEFAULT_SAMPLES;
    job->max_bounces = d->max_bounces > 0 ? d->max_bounces : REFERENCE_DEFAULT_BOUNCES;
    job->seed = d->seed;
    job->ao_distance = p->ao_distance;
    job->ao_falloff = p->ao_falloff;
    job->ambient = p->ambient;
    return 0;
}

int reference_render(reference *ref, const reference_render_desc *d, reference_images *out,
                     char *err, size_t errlen)
{
    memset(out, 0, sizeof *out);
    if (!ref || !d || !d->params || !d->view) {
        snprintf(err, errlen, "reference: render needs a reference, params and a view");
        return -1;
    }
    double t0 = clock_now_ms();
    reference_job job = {.ref = ref};
    if (setup_job(&job, d, err, errlen) != 0)
        return -1;
    size_t n = (size_t)job.width * (size_t)job.height * 3;
    out->width = job.width;
    out->height = job.height;
    /* not xalloc: the image size (a setting): refused in err */
    out->direct = job.direct = malloc(n * sizeof(float));
    out->indirect1 = job.indirect1 = malloc(n * sizeof(float));
    out->indirect = job.indirect = malloc(n * sizeof(float));
    out->coverage = job.coverage = malloc(n / 3);
    if (d->params->ao != FRAME_AO_OFF)
        out->ao = job.ao = malloc(n * sizeof(float));
    job.row_rays = calloc((size_t)job.height, sizeof *job.row_rays);
    if (!job.direct || !job.indirect1 || !job.indirect || !job.coverage || !job.row_rays ||
        (d->params->ao != FRAME_AO_OFF && !job.ao)) {
        free(job.row_rays);
        reference_images_free(out);
        snprintf(err, errlen, "reference: out of memory for a %dx%d image", job.width, job.height);
        return -1;
    }
    workpool_run(ref->pool, job.height, reference_sample_row, &job);
    for (int y = 0; y < job.height; y++)
        out->rays += job.row_rays[y];
    free(job.row_rays);
    out->render_ms = clock_now_ms() - t0;
    return 0;
}

void reference_images_free(reference_images *img)
{
    if (!img)
        return;
    free(img->direct);
    free(img->indirect1);
    free(img->indirect);
    free(img->coverage);
    free(img->ao);
    img->direct = img->indirect1 = img->indirect = img->ao = NULL;
    img->coverage = NULL;
}

static double half_difference(const float *a, const float *b, size_t n)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += fabs((double)a[i] - b[i]);
    return n ? sum / (2.0 * (double)n) : 0;
}

int reference_render_averaged(reference *ref, const reference_render_desc *d,
                              reference_images *out, reference_noise *noise, char *err,
                              size_t errlen)
{
    reference_images half = {0};
    reference_render_desc second = *d;
    second.seed = d->seed + 1;
    if (reference_render(ref, d, out, err, errlen) != 0)
        return -1;
    if (reference_render(ref, &second, &half, err, errlen) != 0) {
        reference_images_free(out);
        return -1;
    }
    size_t n = (size_t)out->width * out->height * 3;
    noise->direct = half_difference(out->direct, half.direct, n);
    noise->indirect1 = half_difference(out->indirect1, half.indirect1, n);
    double sq = 0;
    size_t covered = 0;
    for (size_t i = 0; i < n; i++) {
        double e = (double)out->indirect1[i] - half.indirect1[i];
        sq += out->coverage[i / 3] ? e * e : 0.0;
        covered += out->coverage[i / 3];
    }
    noise->indirect1_rms = covered ? sqrt(sq / (double)covered) / 2.0 : 0.0;
    noise->indirect = half_difference(out->indirect, half.indirect, n);
    noise->ao = out->ao ? half_difference(out->ao, half.ao, n) : 0.0;
    for (size_t i = 0; i < n; i++) {
        out->direct[i] = 0.5f * (out->direct[i] + half.direct[i]);
        out->indirect1[i] = 0.5f * (out->indirect1[i] + half.indirect1[i]);
        out->indirect[i] = 0.5f * (out->indirect[i] + half.indirect[i]);
        if (out->ao)
            out->ao[i] = 0.5f * (out->ao[i] + half.ao[i]);
    }
    out->render_ms += half.render_ms;
    out->rays += half.rays;
    reference_images_free(&half);
    return 0;
}
