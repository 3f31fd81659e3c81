/* reference_cli: two half renders -> averaged images, a PNG and a JSON report. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "image.h"
#include "reference.h"
#include "reference_cli.h"

/* Mean of |a - b| / 2 over all channels: the expected error of (a + b) / 2 when a and b
 * are independent estimates of the same image. */
static double half_noise(const float *a, const float *b, size_t n)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += fabs((double)a[i] - b[i]);
    return n ? sum / (2.0 * n) : 0;
}

static double mean(const float *v, size_t n)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += v[i];
    return n ? sum / n : 0;
}

static void add_noise(cJSON *noise, const char *name, const float *a, const float *b,
                      const float *avg, size_t n)
{
    double mae = half_noise(a, b, n), m = mean(avg, n);
    cJSON *o = cJSON_AddObjectToObject(noise, name);
    cJSON_AddNumberToObject(o, "mae", mae);
    cJSON_AddNumberToObject(o, "mean", m);
    cJSON_AddNumberToObject(o, "relative", m > 0 ? mae / m : 0);
}

/* L / (1 + L), then the encoding gamma (shaders/final.frag). */
static void tone_map(const float *hdr, size_t pixels, float encoding, uint8_t *rgb)
{
    for (size_t i = 0; i < 3 * pixels; i++) {
        float l = fmaxf(hdr[i], 0.0f);
        float v = powf(l / (1.0f + l), encoding);
        rgb[i] = (uint8_t)lrintf(fminf(fmaxf(v, 0.0f), 1.0f) * 255.0f);
    }
}

static int write_outputs(const reference_cli_desc *d, const reference_images *h, cJSON *report)
{
    int w = h[0].width, ht = h[0].height;
    size_t n = (size_t)w * ht * 3;
    float *avg[5];
    for (int k = 0; k < 5; k++)
        avg[k] = malloc(n * sizeof(float));
    uint8_t *rgb = malloc(n);
    int rc = rgb ? 0 : -1;
    for (int k = 0; k < 5; k++)
        rc |= avg[k] ? 0 : -1;
    if (rc == 0) {
        for (size_t i = 0; i < n; i++) {
            avg[0][i] = 0.5f * (h[0].direct[i] + h[1].direct[i]);
            avg[1][i] = 0.5f * (h[0].indirect1[i] + h[1].indirect1[i]);
            avg[2][i] = 0.5f * (h[0].indirect[i] + h[1].indirect[i]);
            avg[3][i] = avg[0][i] + avg[1][i];
            avg[4][i] = avg[0][i] + avg[2][i];
        }
        cJSON *noise = cJSON_AddObjectToObject(report, "noise");
        add_noise(noise, "indirect1", h[0].indirect1, h[1].indirect1, avg[1], n);
        add_noise(noise, "indirect", h[0].indirect, h[1].indirect, avg[2], n);
        add_noise(noise, "direct", h[0].direct, h[1].direct, avg[0], n);
        printf("reference: noise of the average: indirect1 %.3g%% of its mean, indirect %.3g%%\n",
               100 * cJSON_GetObjectItem(cJSON_GetObjectItem(noise, "indirect1"), "relative")->valuedouble,
               100 * cJSON_GetObjectItem(cJSON_GetObjectItem(noise, "indirect"), "relative")->valuedouble);
    } else {
        fprintf(stderr, "cavelight-node: out of memory for the reference images\n");
    }
    char path[4096], err[512];
    static const char *names[5] = {"direct", "indirect1", "indirect", "final1", "final"};
    for (int k = 0; k < 5 && rc == 0 && d->out; k++) {
        snprintf(path, sizeof path, "%s/reference_%s.pfm", d->out, names[k]);
        if (image_write_pfm(path, w, ht, avg[k], err, sizeof err) != 0) {
            fprintf(stderr, "cavelight-node: %s\n", err);
            rc = -1;
        }
    }
    if (rc == 0 && d->out) {
        float display = d->params->display_gamma > 0 ? d->params->display_gamma : 2.2f;
        tone_map(avg[4], (size_t)w * ht, frame_params_e2e_gamma(d->params->environment) / display,
                 rgb);
        snprintf(path, sizeof path, "%s/reference.png", d->out);
        if (image_write_png(path, w, ht, rgb, err, sizeof err) != 0) {
            fprintf(stderr, "cavelight-node: %s\n", err);
            rc = -1;
        }
    }
    for (int k = 0; k < 5; k++)
        free(avg[k]);
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
    reference_images half[2] = {{0}};
    int rc = 0;
    for (int i = 0; i < 2 && rc == 0; i++) {
        reference_render_desc rd = {.params = d->params, .view = d->view, .samples = d->samples,
                                    .max_bounces = d->bounces, .seed = d->seed + (uint64_t)i};
        if (reference_render(ref, &rd, &half[i], err, sizeof err) != 0) {
            fprintf(stderr, "cavelight-node: %s\n", err);
            rc = 1;
        }
    }
    if (rc == 0) {
        int samples = d->samples > 0 ? d->samples : 64, bounces = d->bounces > 0 ? d->bounces : 8;
        double ms = half[0].render_ms + half[1].render_ms;
        double rays = (double)(half[0].rays + half[1].rays);
        printf("reference: scene %s (%zu triangles), %dx%d, 2 x %d paths per pixel, %d bounces, "
               "%.0f ms, %.2f Mrays/s\n", d->scene_name, d->scene->triangle_count, half[0].width,
               half[0].height, samples, bounces, ms, ms > 0 ? rays / ms / 1e3 : 0);
        cJSON *report = cJSON_CreateObject();
        cJSON_AddStringToObject(report, "renderer", "reference");
        cJSON_AddStringToObject(report, "scene", d->scene_name);
        cJSON_AddNumberToObject(report, "triangles", (double)d->scene->triangle_count);
        cJSON_AddNumberToObject(report, "width", half[0].width);
        cJSON_AddNumberToObject(report, "height", half[0].height);
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
        int spots = 0;
        for (int i = 0; i < d->params->light_count && i < FRAME_MAX_LIGHTS; i++)
            spots += d->params->lights[i].enabled && d->params->lights[i].intensity > 0;
        cJSON_AddNumberToObject(report, "spots", spots);
        double hms[2] = {half[0].render_ms, half[1].render_ms};
        cJSON_AddItemToObject(report, "half_render_ms", cJSON_CreateDoubleArray(hms, 2));
        cJSON_AddNumberToObject(report, "render_ms", ms);
        cJSON_AddNumberToObject(report, "rays", rays);
        cJSON_AddNumberToObject(report, "mrays_per_s", ms > 0 ? rays / ms / 1e3 : 0);
        if (write_outputs(d, half, report) != 0 || (d->out && write_json(d->out, report) != 0))
            rc = 1;
        cJSON_Delete(report);
    }
    reference_images_free(&half[0]);
    reference_images_free(&half[1]);
    reference_destroy(ref);
    return rc;
}
