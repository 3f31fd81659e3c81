/* image_metrics: closed-form checks of every metric (identity, offset, scale, constant
 * images for SSIM), SSIM's response to noise and to structure at equal MAE, masks, NaN/inf
 * pixels, a black reference (no signal) and invalid sizes. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "image/image_metrics.h"

enum { W = 40, H = 30, N = W * H };

static float *image_alloc(void)
{
    float *p = malloc(sizeof(float) * N * 3);
    assert_non_null(p);
    return p;
}

/* Deterministic noise in [-1, 1]. */
static double noise(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (double)(*s >> 8) / (double)(1u << 23) - 1.0;
}

/* A smooth coloured pattern in (0.1, 0.9): structure for SSIM to see. */
static void pattern(float *p)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++)
                p[((size_t)y * W + x) * 3 + c] =
                    (float)(0.5 + 0.3 * sin(0.4 * x + c) * cos(0.3 * y - c));
}

static void test_identical(void **state)
{
    (void)state;
    float *a = image_alloc();
    pattern(a);
    image_metrics m;
    assert_int_equal(image_metrics_compare(a, a, W, H, NULL, &m), 0);
    assert_int_equal(m.pixels, N);
    assert_int_equal(m.nonfinite, 0);
    assert_true(m.mae == 0 && m.relmse == 0 && m.rmse_rel == 0 && m.mae_scaled == 0);
    assert_true(fabs(m.ssim - 1.0) < 1e-12);
    assert_true(fabs(m.best_scale - 1.0) < 1e-12);
    assert_true(m.mean == m.reference_mean && m.mean > 0.3 && m.mean < 0.7);
    free(a);
}

/* ref takes the values a and b in a checkerboard; img = ref + d, then img = 2 * ref. */
static void test_offset_and_scale(void **state)
{
    (void)state;
    const double a = 0.25, b = 0.75, d = 0.125, eps = 0.5;
    float *ref = image_alloc(), *img = image_alloc();
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 3; c++) {
            ref[i * 3 + c] = (float)(((i % W) + (i / W)) % 2 ? b : a);
            img[i * 3 + c] = (float)(ref[i * 3 + c] + d);
        }
    image_metrics_desc desc = {.relmse_epsilon = eps};
    image_metrics m;
    assert_int_equal(image_metrics_compare(img, ref, W, H, &desc, &m), 0);
    double s = ((a + d) * a + (b + d) * b) / ((a + d) * (a + d) + (b + d) * (b + d));
    assert_true(fabs(m.mae - d) < 1e-12);
    assert_true(fabs(m.rmse_rel - d / ((a + b) / 2)) < 1e-12);
    assert_true(fabs(m.relmse - (d * d / (a * a + eps) + d * d / (b * b + eps)) / 2) < 1e-12);
    assert_true(fabs(m.mean - ((a + b) / 2 + d)) < 1e-12);
    assert_true(fabs(m.reference_mean - (a + b) / 2) < 1e-12);
    assert_true(fabs(m.best_scale - s) < 1e-12);
    assert_true(fabs(m.mae_scaled - (fabs(s * (a + d) - a) + fabs(s * (b + d) - b)) / 2) < 1e-12);

    for (int i = 0; i < N * 3; i++)
        img[i] = 2.0f * ref[i];
    assert_int_equal(image_metrics_compare(img, ref, W, H, NULL, &m), 0);
    assert_true(fabs(m.best_scale - 0.5) < 1e-12);
    assert_true(m.mae_scaled < 1e-12);
    assert_true(fabs(m.mae - (a + b) / 2) < 1e-12);
    assert_true(fabs(m.rmse_rel - sqrt((a * a + b * b) / 2) / ((a + b) / 2)) < 1e-12);
    /* Default epsilon 1e-2. */
    assert_true(fabs(m.relmse - (a * a / (a * a + 1e-2) + b * b / (b * b + 1e-2)) / 2) < 1e-12);
    free(ref);
    free(img);
}

static void test_ssim_noise(void **state)
{
    (void)state;
    float *ref = image_alloc(), *img = image_alloc();
    pattern(ref);
    double last = 1.0;
    for (double amp = 0.01; amp < 0.5; amp *= 3) {
        uint32_t seed = 7;
        for (int i = 0; i < N * 3; i++)
            img[i] = (float)(ref[i] + amp * noise(&seed));
        image_metrics m;
        assert_int_equal(image_metrics_compare(img, ref, W, H, NULL, &m), 0);
        assert_true(m.ssim < last);
        assert_true(m.ssim > -1.0);
        last = m.ssim;
    }
    assert_true(last < 0.5);
    free(ref);
    free(img);
}

/* Column stripes 0.3/0.7. A: brighter by 0.2 (same structure). B: +-0.2 in a checkerboard
 * (same mean, new structure). Both have MAE 0.2; SSIM must prefer A. */
static void test_ssim_structure(void **state)
{
    (void)state;
    float *ref = image_alloc(), *a = image_alloc(), *b = image_alloc();
    for (int i = 0; i < N; i++) {
        int x = i % W, y = i / W;
        for (int c = 0; c < 3; c++) {
            ref[i * 3 + c] = x % 2 ? 0.7f : 0.3f;
            a[i * 3 + c] = ref[i * 3 + c] + 0.2f;
            b[i * 3 + c] = ref[i * 3 + c] + ((x + y) % 2 ? 0.2f : -0.2f);
        }
    }
    image_metrics ma, mb;
    assert_int_equal(image_metrics_compare(a, ref, W, H, NULL, &ma), 0);
    assert_int_equal(image_metrics_compare(b, ref, W, H, NULL, &mb), 0);
    assert_true(fabs(ma.mae - mb.mae) < 1e-6);
    assert_true(fabs(mb.mean - mb.reference_mean) < 1e-6);
    assert_true(mb.ssim < ma.ssim - 0.1);
    free(ref);
    free(a);
    free(b);
}

/* Constant images: variances and covariance vanish, so
 * SSIM = (2 mx my + C1) / (mx^2 + my^2 + C1), on every window, borders included. */
static void test_ssim_constant(void **state)
{
    (void)state;
    enum { CW = 4, CH = 3 }; /* smaller than the 11x11 window */
    float img[CW * CH * 3], ref[CW * CH * 3];
    for (int i = 0; i < CW * CH * 3; i++) {
        img[i] = 0.5f;
        ref[i] = 0.8f;
    }
    image_metrics_desc desc = {.ssim_range = 1.0};
    image_metrics m;
    assert_int_equal(image_metrics_compare(img, ref, CW, CH, &desc, &m), 0);
    double mx = 0.5, my = (double)0.8f, c1 = 1e-4;
    assert_true(fabs(m.ssim - (2 * mx * my + c1) / (mx * mx + my * my + c1)) < 1e-9);

    /* Pure red against pure green: SSIM sees Rec. 709 luminance, and L defaults to the
     * reference's maximum luminance. */
    for (int i = 0; i < CW * CH; i++) {
        img[i * 3] = 0, img[i * 3 + 1] = 1, img[i * 3 + 2] = 0;
        ref[i * 3] = 1, ref[i * 3 + 1] = 0, ref[i * 3 + 2] = 0;
    }
    assert_int_equal(image_metrics_compare(img, ref, CW, CH, NULL, &m), 0);
    mx = 0.7152, my = 0.2126, c1 = (0.01 * my) * (0.01 * my);
    assert_true(fabs(m.ssim - (2 * mx * my + c1) / (mx * mx + my * my + c1)) < 1e-9);
}

/* Masked-out pixels count nowhere: not in the means, not inside SSIM windows. */
static void test_mask(void **state)
{
    (void)state;
    float *ref = image_alloc(), *img = image_alloc();
    pattern(ref);
    memcpy(img, ref, sizeof(float) * N * 3);
    uint8_t mask[N];
    size_t kept = 0;
    for (int i = 0; i < N; i++) {
        int x = i % W, y = i / W;
        mask[i] = !(x >= 10 && x < 20 && y >= 5 && y < 15);
        kept += mask[i];
        if (!mask[i])
            for (int c = 0; c < 3; c++)
                img[i * 3 + c] = 5.0f;
    }
    image_metrics m;
    assert_int_equal(image_metrics_compare(img, ref, W, H, NULL, &m), 0);
    assert_true(m.mae > 0.1 && m.ssim < 0.9);
    image_metrics_desc desc = {.mask = mask};
    assert_int_equal(image_metrics_compare(img, ref, W, H, &desc, &m), 0);
    assert_int_equal(m.pixels, kept);
    assert_true(m.mae == 0 && m.relmse == 0);
    assert_true(fabs(m.ssim - 1.0) < 1e-12);

    memset(mask, 0, sizeof mask);
    assert_int_equal(image_metrics_compare(img, ref, W, H, &desc, &m), -1);
    assert_int_equal(m.pixels, 0);
    free(ref);
    free(img);
}

static void test_nonfinite(void **state)
{
    (void)state;
    float *ref = image_alloc(), *img = image_alloc();
    pattern(ref);
    memcpy(img, ref, sizeof(float) * N * 3);
    img[5 * 3 + 1] = NAN;
    img[100 * 3] = INFINITY;
    ref[100 * 3 + 2] = NAN; /* same pixel: counted once */
    ref[333 * 3 + 2] = -INFINITY;
    img[700 * 3] = NAN;     /* masked out below: neither counted nor excluded twice */
    uint8_t mask[N];
    memset(mask, 1, sizeof mask);
    mask[700] = 0;
    image_metrics_desc desc = {.mask = mask};
    image_metrics m;
    assert_int_equal(image_metrics_compare(img, ref, W, H, &desc, &m), 0);
    assert_int_equal(m.nonfinite, 3);
    assert_int_equal(m.pixels, N - 4);
    assert_true(m.mae == 0 && isfinite(m.mean) && isfinite(m.reference_mean));
    assert_true(fabs(m.ssim - 1.0) < 1e-12);

    for (int i = 0; i < N * 3; i++)
        img[i] = NAN;
    assert_int_equal(image_metrics_compare(img, ref, W, H, NULL, &m), -1);
    assert_int_equal(m.nonfinite, N);
    free(ref);
    free(img);
}

/* A black reference has no signal: relative RMSE and SSIM are NAN, never a perfect 0 and
 * 1, whether the image is black too or leaks light; the absolute figures stay defined.
 * One lit pixel in the reference is signal again. */
static void test_no_signal(void **state)
{
    (void)state;
    float *ref = image_alloc(), *img = image_alloc();
    memset(ref, 0, sizeof(float) * N * 3);
    memset(img, 0, sizeof(float) * N * 3);
    image_metrics m;
    assert_int_equal(image_metrics_compare(img, ref, W, H, NULL, &m), 0);
    assert_int_equal(m.no_signal, 1);
    assert_true(isnan(m.rmse_rel) && isnan(m.ssim));
    assert_true(m.mae == 0 && m.mean == 0 && m.reference_mean == 0 && m.relmse == 0);
    assert_int_equal(m.pixels, N);

    img[42 * 3 + 1] = 0.3f; /* a leak where the truth is black */
    assert_int_equal(image_metrics_compare(img, ref, W, H, NULL, &m), 0);
    assert_int_equal(m.no_signal, 1);
    assert_true(isnan(m.rmse_rel) && isnan(m.ssim));
    assert_true(fabs(m.mae - 0.3 / (3.0 * N)) < 1e-9 && m.mean > 0);

    ref[7 * 3] = 0.5f;
    assert_int_equal(image_metrics_compare(img, ref, W, H, NULL, &m), 0);
    assert_int_equal(m.no_signal, 0);
    assert_true(isfinite(m.rmse_rel) && m.rmse_rel > 0 && isfinite(m.ssim) && m.ssim < 1);

    /* Black where the mask looks, lit elsewhere: no signal in what is compared. */
    uint8_t mask[N];
    memset(mask, 1, sizeof mask);
    mask[7] = 0;
    image_metrics_desc desc = {.mask = mask};
    assert_int_equal(image_metrics_compare(img, ref, W, H, &desc, &m), 0);
    assert_int_equal(m.no_signal, 1);
    assert_true(isnan(m.ssim));
    free(ref);
    free(img);
}

/* Debiasing: an offset c against a reference whose noise is s leaves sqrt(c^2 - s^2);
 * a noise above the error leaves 0; and on a noisy reference made of two halves, the
 * halves' estimate of its noise brings the error back to the one against the truth. */
static void test_debiased(void **state)
{
    (void)state;
    float *ref = image_alloc(), *img = image_alloc();
    for (int i = 0; i < N * 3; i++) {
        ref[i] = 2.0f;
        img[i] = 2.5f;
    }
    image_metrics m;
    image_metrics_desc d = {.reference_noise = 0.3};
    assert_int_equal(image_metrics_compare(img, ref, W, H, &d, &m), 0);
    assert_float_equal(m.rmse_rel, 0.25, 1e-9);
    assert_float_equal(m.rmse_rel_debiased, 0.4 / 2.0, 1e-9);
    d.reference_noise = 0.7;
    assert_int_equal(image_metrics_compare(img, ref, W, H, &d, &m), 0);
    assert_true(m.rmse_rel_debiased == 0.0);
    assert_int_equal(image_metrics_compare(img, ref, W, H, NULL, &m), 0);
    assert_true(m.rmse_rel_debiased == m.rmse_rel);

    /* truth 1 + pattern; image = truth + 0.05; halves = truth + noise of sd 0.4 */
    enum { BIG = 200 * 200 };
    float *truth = malloc(sizeof(float) * BIG * 3), *avg = malloc(sizeof(float) * BIG * 3);
    float *test = malloc(sizeof(float) * BIG * 3);
    assert_non_null(truth && avg && test);
    uint32_t seed = 5;
    double sq = 0;
    for (int i = 0; i < BIG * 3; i++) {
        truth[i] = 1.0f + 0.5f * (float)sin(0.01 * i);
        test[i] = truth[i] + 0.05f;
        double a = truth[i] + 0.4 * sqrt(3.0) * noise(&seed);
        double b = truth[i] + 0.4 * sqrt(3.0) * noise(&seed);
        avg[i] = (float)(0.5 * (a + b));
        sq += (a - b) * (a - b);
    }
    image_metrics_desc halves = {.reference_noise = sqrt(sq / (BIG * 3)) / 2.0};
    image_metrics vs_truth;
    assert_int_equal(image_metrics_compare(test, truth, 200, 200, NULL, &vs_truth), 0);
    assert_int_equal(image_metrics_compare(test, avg, 200, 200, &halves, &m), 0);
    assert_true(m.rmse_rel > 4 * vs_truth.rmse_rel);
    assert_float_equal(m.rmse_rel_debiased, vs_truth.rmse_rel, 0.2 * vs_truth.rmse_rel);
    free(truth);
    free(avg);
    free(test);
    free(ref);
    free(img);
}

static void test_bad_sizes(void **state)
{
    (void)state;
    float px[3] = {1, 1, 1};
    image_metrics m;
    assert_int_equal(image_metrics_compare(px, px, 1, 1, NULL, &m), 0);
    assert_int_equal(image_metrics_compare(px, px, 0, 1, NULL, &m), -1);
    assert_int_equal(image_metrics_compare(px, px, 1, -1, NULL, &m), -1);
    assert_int_equal(image_metrics_compare(NULL, px, 1, 1, NULL, &m), -1);
    assert_int_equal(image_metrics_compare(px, NULL, 1, 1, NULL, &m), -1);
    assert_int_equal(image_metrics_compare(px, px, 1, 1, NULL, NULL), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_identical),
        cmocka_unit_test(test_offset_and_scale),
        cmocka_unit_test(test_ssim_noise),
        cmocka_unit_test(test_ssim_structure),
        cmocka_unit_test(test_ssim_constant),
        cmocka_unit_test(test_mask),
        cmocka_unit_test(test_nonfinite),
        cmocka_unit_test(test_no_signal),
        cmocka_unit_test(test_debiased),
        cmocka_unit_test(test_bad_sizes),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
