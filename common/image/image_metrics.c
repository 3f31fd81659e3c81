#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image/image_metrics.h"

enum { SSIM_RADIUS = 5, SSIM_TAPS = 2 * SSIM_RADIUS + 1, SSIM_MOMENTS = 6 };

static double luminance(const float *p)
{
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

static int pixel_selected(const image_metrics_desc *d, size_t i)
{
    return !d->mask || d->mask[i];
}

static int pixel_finite(const float *img, const float *ref, size_t i)
{
    for (int c = 0; c < 3; c++)
        if (!isfinite(img[i * 3 + c]) || !isfinite(ref[i * 3 + c]))
            return 0;
    return 1;
}

/* Mean SSIM over counted pixels; counted[i] says which. The 2D Gaussian is separable and
 * the truncated window is renormalised by its own filtered weight, so one horizontal pass
 * per row into a ring of SSIM_TAPS rows and one vertical pass per output row suffice. */
static double ssim_mean(const float *img, const float *ref, const uint8_t *counted, int w,
                        int h, double range, double *scratch)
{
    double g[SSIM_TAPS];
    for (int k = 0; k < SSIM_TAPS; k++) {
        double t = k - SSIM_RADIUS;
        g[k] = exp(-t * t / (2.0 * 1.5 * 1.5));
    }
    const double c1 = (0.01 * range) * (0.01 * range), c2 = (0.03 * range) * (0.03 * range);
    double *ring = scratch;                                   /* [slot][moment][x] */
    double *row = scratch + (size_t)SSIM_TAPS * SSIM_MOMENTS * w; /* weight, lx, ly per x */
    double sum = 0;
    for (int y = 0; y < h + SSIM_RADIUS; y++) {
        if (y < h) {
            for (int x = 0; x < w; x++) {
                size_t i = (size_t)y * w + x;
                row[3 * x] = counted[i] ? 1.0 : 0.0;
                row[3 * x + 1] = counted[i] ? luminance(img + i * 3) : 0.0;
                row[3 * x + 2] = counted[i] ? luminance(ref + i * 3) : 0.0;
            }
            double *out = ring + (size_t)(y % SSIM_TAPS) * SSIM_MOMENTS * w;
            for (int x = 0; x < w; x++) {
                double m[SSIM_MOMENTS] = {0};
                int x0 = x - SSIM_RADIUS < 0 ? 0 : x - SSIM_RADIUS;
                int x1 = x + SSIM_RADIUS >= w ? w - 1 : x + SSIM_RADIUS;
                for (int sx = x0; sx <= x1; sx++) {
                    double k = g[sx - x + SSIM_RADIUS] * row[3 * sx];
                    double a = row[3 * sx + 1], b = row[3 * sx + 2];
                    m[0] += k;
                    m[1] += k * a;
                    m[2] += k * b;
                    m[3] += k * a * a;
                    m[4] += k * b * b;
                    m[5] += k * a * b;
                }
                for (int j = 0; j < SSIM_MOMENTS; j++)
                    out[(size_t)j * w + x] = m[j];
            }
        }
        int oy = y - SSIM_RADIUS;
        if (oy < 0)
            continue;
        int y0 = oy - SSIM_RADIUS < 0 ? 0 : oy - SSIM_RADIUS;
        int y1 = oy + SSIM_RADIUS >= h ? h - 1 : oy + SSIM_RADIUS;
        for (int x = 0; x < w; x++) {
            if (!counted[(size_t)oy * w + x])
                continue;
            double m[SSIM_MOMENTS] = {0};
            for (int sy = y0; sy <= y1; sy++) {
                const double *in = ring + (size_t)(sy % SSIM_TAPS) * SSIM_MOMENTS * w;
                double k = g[sy - oy + SSIM_RADIUS];
                for (int j = 0; j < SSIM_MOMENTS; j++)
                    m[j] += k * in[(size_t)j * w + x];
            }
            /* m[0] > 0: the centre tap itself is counted. */
            double mx = m[1] / m[0], my = m[2] / m[0];
            double vx = m[3] / m[0] - mx * mx, vy = m[4] / m[0] - my * my;
            double cxy = m[5] / m[0] - mx * my;
            sum += (2.0 * mx * my + c1) * (2.0 * cxy + c2) /
                   ((mx * mx + my * my + c1) * (vx + vy + c2));
        }
    }
    return sum;
}

/* The absolute error of scale * img against ref over the counted pixels. */
static double scaled_abs_sum(const float *img, const float *ref, const uint8_t *counted, size_t n,
                             double scale)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        if (counted[i])
            for (int c = 0; c < 3; c++)
                sum += fabs(scale * img[i * 3 + c] - ref[i * 3 + c]);
    return sum;
}

int image_metrics_compare(const float *img, const float *ref, int width, int height,
                          const image_metrics_desc *desc, image_metrics *out)
{
    if (!out)
        return -1;
    memset(out, 0, sizeof *out);
    if (!img || !ref || width <= 0 || height <= 0 ||
        (size_t)width > SIZE_MAX / 3 / sizeof(float) / (size_t)height)
        return -1;
    image_metrics_desc d = desc ? *desc : (image_metrics_desc){0};
    if (d.relmse_epsilon == 0)
        d.relmse_epsilon = 1e-2;
    size_t n = (size_t)width * height;
    /* not xalloc: the images' size: -1 to the caller */
    uint8_t *counted = malloc(n);
    double *scratch = malloc(((size_t)SSIM_TAPS * SSIM_MOMENTS + 3) * width * sizeof *scratch);
    if (!counted || !scratch) {
        free(counted);
        free(scratch);
        return -1;
    }

    double abs_sum = 0, sq_sum = 0, rel_sum = 0, img_sum = 0, ref_sum = 0;
    double cross = 0, img_sq = 0, max_lum = 0;
    size_t pixels = 0, nonfinite = 0;
    for (size_t i = 0; i < n; i++) {
        counted[i] = 0;
        if (!pixel_selected(&d, i))
            continue;
        if (!pixel_finite(img, ref, i)) {
            nonfinite++;
            continue;
        }
        counted[i] = 1;
        pixels++;
        for (int c = 0; c < 3; c++) {
            double a = img[i * 3 + c], b = ref[i * 3 + c], e = a - b;
            abs_sum += fabs(e);
            sq_sum += e * e;
            rel_sum += e * e / (b * b + d.relmse_epsilon);
            img_sum += a;
            ref_sum += b;
            cross += a * b;
            img_sq += a * a;
        }
        double lum = luminance(ref + i * 3);
        if (lum > max_lum)
            max_lum = lum;
    }
    out->nonfinite = nonfinite;
    if (pixels == 0) {
        free(counted);
        free(scratch);
        return -1;
    }

    double samples = 3.0 * pixels;
    out->pixels = pixels;
    out->mae = abs_sum / samples;
    out->relmse = rel_sum / samples;
    out->mean = img_sum / samples;
    out->reference_mean = ref_sum / samples;
    out->no_signal = ref_sum == 0;
    out->rmse_rel = out->no_signal ? NAN : sqrt(sq_sum / samples) / out->reference_mean;
    double truth_sq = sq_sum / samples - d.reference_noise * d.reference_noise;
    out->rmse_rel_debiased = out->no_signal ? NAN : sqrt(fmax(truth_sq, 0.0)) / out->reference_mean;
    out->best_scale = img_sq > 0 ? cross / img_sq : 1.0;

    out->mae_scaled = scaled_abs_sum(img, ref, counted, n, out->best_scale) / samples;

    double range = d.ssim_range > 0 ? d.ssim_range : (max_lum > 0 ? max_lum : 1.0);
    out->ssim = out->no_signal
                    ? NAN
                    : ssim_mean(img, ref, counted, width, height, range, scratch) / (double)pixels;
    free(counted);
    free(scratch);
    return 0;
}
