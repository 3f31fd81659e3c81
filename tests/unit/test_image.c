/* image: PFM round trip (bit exact, row order), PNG written and read back by libpng, and
 * image_read_png on RGB, grey and missing or foreign files. */
#include <png.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "image/image.h"

static void test_pfm_round_trip(void **state)
{
    (void)state;
    enum { W = 5, H = 3 };
    float rgb[W * H * 3];
    for (int i = 0; i < W * H * 3; i++)
        rgb[i] = (float)i * 0.37f - 2.0f;
    char err[256];
    const char *path = CAVELIGHT_BINARY_DIR "/test_image.pfm";
    assert_int_equal(image_write_pfm(path, W, H, rgb, err, sizeof err), 0);
    int w, h;
    float *back = NULL;
    assert_int_equal(image_read_pfm(path, &w, &h, &back, err, sizeof err), 0);
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    assert_memory_equal(back, rgb, sizeof rgb);
    free(back);
    assert_int_equal(image_read_pfm(CAVELIGHT_BINARY_DIR "/nope.pfm", &w, &h, &back, err, sizeof err), -1);
}

static void test_png_round_trip(void **state)
{
    (void)state;
    enum { W = 7, H = 4 };
    uint8_t rgb[W * H * 3];
    for (int i = 0; i < W * H * 3; i++)
        rgb[i] = (uint8_t)(i * 11);
    char err[256];
    const char *path = CAVELIGHT_BINARY_DIR "/test_image.png";
    assert_int_equal(image_write_png(path, W, H, rgb, err, sizeof err), 0);
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    assert_true(png_image_begin_read_from_file(&img, path));
    img.format = PNG_FORMAT_RGB;
    uint8_t back[W * H * 3];
    assert_true(png_image_finish_read(&img, NULL, back, W * 3, NULL));
    assert_memory_equal(back, rgb, sizeof rgb);
    assert_int_equal(image_write_png("/nonexistent-dir/x.png", W, H, rgb, err, sizeof err), -1);
}

static void test_png_read(void **state)
{
    (void)state;
    enum { W = 6, H = 5 };
    uint8_t rgb[W * H * 3];
    for (int i = 0; i < W * H * 3; i++)
        rgb[i] = (uint8_t)(i * 7 + 3);
    char err[256];
    const char *path = CAVELIGHT_BINARY_DIR "/test_image_read.png";
    assert_int_equal(image_write_png(path, W, H, rgb, err, sizeof err), 0);
    int w = 0, h = 0;
    uint8_t *back = NULL;
    assert_int_equal(image_read_png(path, &w, &h, &back, err, sizeof err), 0);
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    assert_memory_equal(back, rgb, sizeof rgb);
    free(back);

    /* A grey file (written through libpng directly) comes back with R = G = B. */
    uint8_t grey[W * H];
    for (int i = 0; i < W * H; i++)
        grey[i] = (uint8_t)(i * 8);
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = W;
    img.height = H;
    img.format = PNG_FORMAT_GRAY;
    const char *grey_path = CAVELIGHT_BINARY_DIR "/test_image_grey.png";
    assert_true(png_image_write_to_file(&img, grey_path, 0, grey, W, NULL));
    assert_int_equal(image_read_png(grey_path, &w, &h, &back, err, sizeof err), 0);
    for (int i = 0; i < W * H; i++)
        for (int c = 0; c < 3; c++)
            assert_int_equal(back[i * 3 + c], grey[i]);
    free(back);

    back = NULL;
    assert_int_equal(image_read_png(CAVELIGHT_BINARY_DIR "/nope.png", &w, &h, &back, err,
                                    sizeof err), -1);
    assert_non_null(strstr(err, "nope.png"));
    const char *pfm = CAVELIGHT_BINARY_DIR "/test_image_not_png.pfm";
    float one[3] = {1, 2, 3};
    assert_int_equal(image_write_pfm(pfm, 1, 1, one, err, sizeof err), 0);
    assert_int_equal(image_read_png(pfm, &w, &h, &back, err, sizeof err), -1);
    assert_null(back);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pfm_round_trip),
        cmocka_unit_test(test_png_round_trip),
        cmocka_unit_test(test_png_read),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
