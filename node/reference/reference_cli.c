/* reference_cli: the averaged reference images, a PNG and a JSON report. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "frame/light_view.h"
#include "image/image.h"
#include "reference.h"
#include "reference_cli.h"
#include "image/tonemap.h"

static double mean(const float *v, size_t n)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += v[i];
    return n ? sum / n : 0;
}

static void add_noise(cJSON *noise, const char *name, double mae, const float *avg, size_t n)
{
    double m = mean(avg, n);
    cJSON *o = cJSON_AddObjectToObject(noise, name);
    cJSON_AddNumberToObject(o, "mae", mae);
    cJSON_AddNumberToObject(o, "mean", m);
    cJSON_AddNumberToObject(o, "relative", m > 0 ? mae / m : 0);
}

static int write_outputs(const reference_cli_desc *d, const reference_images *img,
                         const reference_noise *nz, cJSON *report)
{
    int w = img->width, ht = img->height;
    size_t n = (size_t)w * ht * 3;
    /* not xalloc: the image size (a setting): -1 to the caller */
    float *final1 = malloc(n * sizeof(float)), *final = malloc(n * sizeof(float));
    uint8_t *rgb = malloc(n);
    int rc = final1 && final && rgb ? 0 : -1;
    if (rc == 0) {
        for (size_t i = 0; i < n; i++) {
            final1[i] = img->direct[i] + img->indirect1[i];
            final[i] = img->direct[i] + img->indirect[i];
        }
        cJSON *noise = cJSON_AddObjectToObject(report, "noise");
        add_noise(noise, "indirect1", nz->indirect1, img->indirect1, n);
        add_noise(noise, "indirect", nz->indirect, img->indirect, n);
        add_noise(noise, "direct", nz->direct, img->direct, n);
        if (img->ao)
            add_noise(noise, "ao", nz->ao, img->ao, n);
        printf("reference: noise of the average: indirect1 %.3g%% of its mean, indirect %.3g%%\n",
               100 * cJSON_GetObjectItem(cJSON_GetObjectItem(noise, "indirect1"), "relative")->valuedouble,
               100 * cJSON_GetObjectItem(cJSON_GetObjectItem(noise, "indirect"), "relative")->valuedouble);
    } else {
        fprintf(stderr, "cavelight-node: out of memory for the reference images\n");
    }
    char path[4096], err[512];
    static const char *names[6] = {"direct", "indirect1", "indirect", "final1", "final", "ao"};
    const float *images[6] = {img->direct, img->indirect1, img->indirect, final1, final, img->ao};
    for (int k = 0; k < 6 && images[k] && rc == 0 && d->out; k++) { /* ao: when asked for */
        snprintf(path, sizeof path, "%s/reference_%s.pfm", d->out, names[k]);
        if (image_write_pfm(path, w, ht, images[k], err, sizeof err) != 0) {
            fprintf(stderr, "cavelight-node: %s\n", err);
            rc = -1;
        }
    }
    if (rc == 0 && d->out) {
        float display = d->params->display_gamma > 0 ? d->params->display_gamma : 2.2f;
        tonemap_rgb8(final, (size_t)w * ht,
                     frame_params_e2e_gamma(d->params->environment) / display, rgb);
        snprintf(path, sizeof path, "%s/reference.png", d->out);
        if (image_write_png(path, w, ht, rgb, err, sizeof err) != 0) {
            fprintf(stderr, "cavelight-node: %s\n", err);
            rc = -1;
        }
    }
    free(final1);
    free(final);
    free(rgb);
    return rc;
}

static int write_json(const char *dir, const cJSON *report)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/reference.json", dir);
    char *text = cJSON_Print(report);
    FILE *f = fopen(path, "w");
    int rc = text && f && fputs(text, f) >= 0 ? 0 : -1;
    if (f && fclose(f) != 0)
        rc = -1;
    free(text);
    if (rc != 0)
        fprintf(stderr, "cavelight-node: cannot write %s (check the --out folder)\n", path);
    return rc;
}

int reference_cli_run(const reference_cli_desc *d)
{
    char err[512];
    reference *ref = reference_create(d->scene, d->threads, err, sizeof err);
    if (!ref) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        return 1;
    }
    reference_images img = {0};
    reference_noise noise;
    reference_render_desc rd = {.params = d->params, .view = d->view, .samples = d->samples,
                                .max_bounces = d->bounces, .seed = d->seed};
    int rc = 0;
    if (reference_render_averaged(ref, &rd, &img, &noise, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        rc = 1;
    }
    if (rc == 0) {
        int samples = d->samples > 0 ? d->samples : REFERENCE_DEFAULT_SAMPLES,
            bounces = d->bounces > 0 ? d->bounces : REFERENCE_DEFAULT_BOUNCES;
        double ms = img.render_ms, rays = (double)img.rays;
        printf("reference: scene %s (%zu triangles), %dx%d, 2 x %d paths per pixel, %d bounces, "
               "%.0f ms, %.2f Mrays/s\n", d->scene_name, d->scene->triangle_count, img.width,
               img.height, samples, bounces, ms, ms > 0 ? rays / ms / 1e3 : 0);
        cJSON *report = cJSON_CreateObject();
        cJSON_AddStringToObject(report, "renderer", "reference");
        cJSON_AddStringToObject(report, "scene", d->scene_name);
        cJSON_AddNumberToObject(report, "triangles", (double)d->scene->triangle_count);
        cJSON_AddNumberToObject(report, "width", img.width);
        cJSON_AddNumberToObject(report, "height", img.height);
        cJSON_AddNumberToObject(report, "samples_per_half", samples);
        cJSON_AddNumberToObject(report, "samples_total", 2 * samples);
        cJSON_AddNumberToObject(report, "max_bounces", bounces);
        double seeds[2] = {(double)d->seed, (double)(d->seed + 1)};
        cJSON_AddItemToObject(report, "seeds", cJSON_CreateDoubleArray(seeds, 2));
        cJSON_AddNumberToObject(report, "threads", d->threads);
        cJSON_AddNumberToObject(report, "absorption", d->params->absorption);
        cJSON_AddNumberToObject(report, "exposure", d->params->exposure);
        cJSON_AddNumberToObject(report, "display_gamma", d->params->display_gamma);
        cJSON_AddNumberToObject(report, "e2e_gamma", frame_params_e2e_gamma(d->params->environment));
        cJSON_AddItemToObject(report, "eye_position",
                              cJSON_CreateFloatArray(d->view->eye_position, 3));
        int lights = 0;
        for (int i = 0; i < d->params->light_count && i < FRAME_MAX_LIGHTS; i++)
            lights += light_is_lit(&d->params->lights[i]);
        cJSON_AddNumberToObject(report, "lights", lights);
        double sum = 0;
        for (size_t i = 0; i < (size_t)img.width * img.height * 3; i++)
            sum += img.direct[i] + img.indirect[i];
        if (!(sum > 0))
            fprintf(stderr, "cavelight-node: warning: the view receives no light: %s\n",
                    light_dark_reason(lights > 0 || scene_has_emitter(d->scene)));
        cJSON_AddNumberToObject(report, "render_ms", ms);
        cJSON_AddNumberToObject(report, "rays", rays);
        cJSON_AddNumberToObject(report, "mrays_per_s", ms > 0 ? rays / ms / 1e3 : 0);
        if (write_outputs(d, &img, &noise, report) != 0 || (d->out && write_json(d->out, report) != 0))
            rc = 1;
        cJSON_Delete(report);
    }
    reference_images_free(&img);
    reference_destroy(ref);
    return rc;
}
