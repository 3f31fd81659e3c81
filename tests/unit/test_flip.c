/* flip: FLIP's known answers. Identical images give 0; black against white is the colour
 * term alone, worked out by hand below; a tiny image at 1 pixel per degree, where the
 * contrast filters are the identity and the feature detectors central differences, checks
 * the feature term by hand; LDR-FLIP is symmetric; HDR-FLIP's exposures follow the
 * reference's max and median and do not change when both images are scaled; masks, NaN and
 * invalid arguments. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "image/flip.h"

/* Black against white, worked out from the paper's formulas: white is L* 100 and black 0,
 * a* = b* = 0, so HyAB = 100 and 100^0.7 = 25.119. The largest difference, Hunt-adjusted
 * green (L* 87.736, a* -75.610, b* 72.981) against blue (32.298, 25.578, -34.836), is HyAB
 * 203.302, cmax = 203.302^0.7 = 41.276. 25.119 is above 0.4 cmax = 16.510, so the error is
 * 0.95 + (25.119 - 16.510) / (41.276 - 16.510) * 0.05 = 0.967380. */
#define BLACK_WHITE 0.9673798
/* A uniform grey tone-mapped to 0.85 (linear) against black: L* 93.876, HyAB^0.7 = 23.998. */
#define GREY085_BLACK 0.9651878
/* t(x) = 0.85 of the ACES curve: the linear value HDR-FLIP's first exposure maps the max to. */
#define ACES_085 2.1188723

static float *image(int w, int h, float r, float g, float b)
{
    float *p = malloc(sizeof(float) * 3 * (size_t)w * h);
    assert_non_null(p);
    for (int i = 0; i < w * h; i++) {
        p[3 * i] = r;
        p[3 * i + 1] = g;
        p[3 * i + 2] = b;
    }
    return p;
}

/* Deterministic values in [0, scale). */
static float *noise_image(int w, int h, uint32_t seed, float scale)
{
    float *p = image(w, h, 0, 0, 0);
    for (int i = 0; i < 3 * w * h; i++) {
        seed = seed * 1664525u + 1013904223u;
        p[i] = scale * (float)(seed >> 8) / (float)(1u << 24);
    }
    return p;
}

static void identical_images_are_zero(void **state)
{
    (void)state;
    float *a = noise_image(24, 18, 7, 1.0f);
    flip_result r;
    assert_int_equal(flip_ldr(a, a, 24, 18, NULL, NULL, &r), 0);
    assert_true(r.mean == 0.0);
    assert_int_equal(r.pixels, 24 * 18);
    float *h = noise_image(24, 18, 7, 50.0f);
    assert_int_equal(flip_hdr(h, h, 24, 18, NULL, NULL, &r), 0);
    assert_true(r.mean == 0.0);
    free(a);
    free(h);
}

static void black_against_white(void **state)
{
    (void)state;
    float *black = image(16, 12, 0, 0, 0), *white = image(16, 12, 1, 1, 1);
    float map[16 * 12];
    flip_result r;
    assert_int_equal(flip_ldr(white, black, 16, 12, NULL, map, &r), 0);
    assert_float_equal(r.mean, BLACK_WHITE, 1e-5);
    for (int i = 0; i < 16 * 12; i++) /* uniform: no feature, the same error everywhere */
        assert_float_equal(map[i], BLACK_WHITE, 1e-5);
    free(black);
    free(white);
}

/* 3x1 at 1 ppd: the CSFs' off-centre taps are exp(-pi^2/0.0047) (0 in double) to
 * exp(-pi^2/0.04) (1e-107), and the feature Gaussian's sd is 0.041 pixel, so edges are the
 * central difference [1 0 -1] and points [0.5 -1 0.5]. Reference black, white, black;
 * test all black. Centre: edge 0, point |-1| = 1, so dF = (1/sqrt 2)^0.5 = 0.840896 and
 * FLIP = 0.967380^(1 - 0.840896) = 0.994737. The sides: colour 0, so FLIP 0. */
static void tiny_case_by_hand(void **state)
{
    (void)state;
    float ref[9] = {0, 0, 0, 1, 1, 1, 0, 0, 0}, test[9] = {0};
    float map[3];
    flip_desc d = {.ppd = 1.0};
    flip_result r;
    assert_int_equal(flip_ldr(test, ref, 3, 1, &d, map, &r), 0);
    assert_float_equal(map[0], 0.0, 1e-6);
    assert_float_equal(map[1], 0.9947374, 1e-5);
    assert_float_equal(map[2], 0.0, 1e-6);
    assert_float_equal(r.mean, 0.9947374 / 3.0, 1e-5);
    const uint8_t centre[3] = {0, 1, 0};
    d.mask = centre;
    assert_int_equal(flip_ldr(test, ref, 3, 1, &d, NULL, &r), 0);
    assert_int_equal(r.pixels, 1);
    assert_float_equal(r.mean, 0.9947374, 1e-5);
}

static void ldr_is_symmetric(void **state)
{
    (void)state;
    float *a = noise_image(20, 16, 1, 1.0f), *b = noise_image(20, 16, 2, 1.0f);
    flip_result ab, ba;
    assert_int_equal(flip_ldr(a, b, 20, 16, NULL, NULL, &ab), 0);
    assert_int_equal(flip_ldr(b, a, 20, 16, NULL, NULL, &ba), 0);
    assert_true(ab.mean > 0.1);
    assert_float_equal(ab.mean, ba.mean, 1e-6);
    free(a);
    free(b);
}

/* A uniform reference has max = median: one exposure, which maps it to 0.85. */
static void hdr_uniform_grey(void **state)
{
    (void)state;
    float *grey = image(8, 6, 0.37f, 0.37f, 0.37f), *black = image(8, 6, 0, 0, 0);
    flip_result r;
    assert_int_equal(flip_hdr(black, grey, 8, 6, NULL, NULL, &r), 0);
    assert_int_equal(r.exposures, 1);
    assert_float_equal(r.start_exposure, log2(ACES_085 / 0.37), 1e-5);
    assert_float_equal(r.stop_exposure, r.start_exposure, 1e-12);
    assert_float_equal(r.mean, GREY085_BLACK, 1e-4);
    free(grey);
    free(black);
}

/* Luminances 1, 2 and 8: max 8, median 2, so 2 stops and max(2, ceil 2) = 2 exposures; a
 * black pixel does not count while the mask leaves it out. */
static void hdr_exposure_range(void **state)
{
    (void)state;
    float ref[12] = {1, 1, 1, 2, 2, 2, 8, 8, 8, 0, 0, 0}, test[12] = {0};
    const uint8_t mask[4] = {1, 1, 1, 0};
    flip_desc d = {.mask = mask};
    flip_result r;
    assert_int_equal(flip_hdr(test, ref, 4, 1, &d, NULL, &r), 0);
    assert_float_equal(r.start_exposure, log2(ACES_085 / 8.0), 1e-5);
    assert_float_equal(r.stop_exposure, log2(ACES_085 / 2.0), 1e-5);
    assert_int_equal(r.exposures, 2);
    assert_int_equal(r.pixels, 3);
}

/* Exposures follow the reference, so radiance units do not matter. */
static void hdr_scale_invariant(void **state)
{
    (void)state;
    float *a = noise_image(20, 16, 3, 4.0f), *b = noise_image(20, 16, 4, 4.0f);
    flip_result r1, r2;
    assert_int_equal(flip_hdr(a, b, 20, 16, NULL, NULL, &r1), 0);
    for (int i = 0; i < 3 * 20 * 16; i++) {
        a[i] *= 64.0f;
        b[i] *= 64.0f;
    }
    assert_int_equal(flip_hdr(a, b, 20, 16, NULL, NULL, &r2), 0);
    assert_true(r1.mean > 0.05);
    assert_float_equal(r1.mean, r2.mean, 1e-5);
    assert_float_equal(r2.start_exposure, r1.start_exposure - 6.0, 1e-5);
    free(a);
    free(b);
}

/* A one-pixel checkerboard against its mean grey: plain to see at 1 ppd, where the CSFs
 * are the identity; at the default viewer's 67 ppd they blur it into the grey and the
 * feature detectors (sd 2.7 pixels) no longer resolve it. */
static void fine_detail_fades_with_distance(void **state)
{
    (void)state;
    float *check = image(32, 32, 0, 0, 0), *grey = image(32, 32, 0.5f, 0.5f, 0.5f);
    for (int i = 0; i < 32 * 32; i++)
        for (int c = 0; c < 3; c++)
            check[3 * i + c] = ((i % 32 + i / 32) % 2) ? 1.0f : 0.0f;
    /* sRGB: grey 0.5 is linear 0.214; the checkerboard's linear mean is 0.5 */
    for (int i = 0; i < 3 * 32 * 32; i++)
        grey[i] = 0.7353569f;
    flip_desc near = {.ppd = 1.0}, far = {.ppd = 0};
    flip_result rn, rf;
    assert_int_equal(flip_ldr(check, grey, 32, 32, &near, NULL, &rn), 0);
    assert_int_equal(flip_ldr(check, grey, 32, 32, &far, NULL, &rf), 0);
    assert_true(rn.mean > 0.5);
    assert_true(rf.mean < 0.2 * rn.mean);
    free(check);
    free(grey);
}

static void nan_and_invalid(void **state)
{
    (void)state;
    float *a = image(4, 4, 0.5f, 0.5f, 0.5f), *b = image(4, 4, 0.5f, 0.5f, 0.5f);
    a[5] = NAN;
    flip_result r;
    assert_int_equal(flip_ldr(a, b, 4, 4, NULL, NULL, &r), 0);
    assert_int_equal(r.pixels, 15);
    assert_int_equal(flip_ldr(a, b, 0, 4, NULL, NULL, &r), -1);
    flip_desc bad = {.ppd = -3};
    assert_int_equal(flip_hdr(a, b, 4, 4, &bad, NULL, &r), -1);
    const uint8_t none[16] = {0};
    flip_desc masked = {.mask = none};
    assert_int_equal(flip_ldr(a, b, 4, 4, &masked, NULL, &r), -1);
    assert_int_equal(flip_hdr(a, b, 4, 4, &masked, NULL, &r), -1);
    free(a);
    free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(identical_images_are_zero),
        cmocka_unit_test(black_against_white),
        cmocka_unit_test(tiny_case_by_hand),
        cmocka_unit_test(ldr_is_symmetric),
        cmocka_unit_test(hdr_uniform_grey),
        cmocka_unit_test(hdr_exposure_range),
        cmocka_unit_test(hdr_scale_invariant),
        cmocka_unit_test(fine_detail_fades_with_distance),
        cmocka_unit_test(nan_and_invalid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
