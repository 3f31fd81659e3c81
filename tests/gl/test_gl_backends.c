/* EGL and OSMesa render the same picture of the default room within a small tolerance
 * (both are Mesa here; on other drivers they may differ by rounding). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"

enum { W = 96, H = 72 };

static uint8_t *render(glctx_backend backend, uint64_t *checksum)
{
    gltest t;
    assert_int_equal(gltest_open(&t, backend, ILPV_BACKEND_CPU, 0), 0);
    renderer_view v;
    gltest_look_at(&v, t.scene.camera.position, t.scene.camera.target, t.scene.camera.yfov, W, H);
    renderer_image img;
    for (int f = 0; f < 2; f++)
        *checksum = renderer_frame_pass(t.r, &t.params);
    assert_int_equal(renderer_eye_pass(t.r, &v, 0, &img), 0);
    uint8_t *copy = malloc((size_t)W * H * 3);
    assert_non_null(copy);
    memcpy(copy, img.rgb, (size_t)W * H * 3);
    gltest_close(&t);
    return copy;
}

static void test_egl_and_osmesa_agree(void **state)
{
    (void)state;
    uint64_t ce, co;
    uint8_t *e = render(GLCTX_EGL, &ce);
    uint8_t *o = render(GLCTX_OSMESA, &co);
    double sum = 0;
    int worst = 0;
    long mean_e = 0;
    for (size_t i = 0; i < (size_t)W * H * 3; i++) {
        int d = abs(e[i] - o[i]);
        sum += d;
        worst = d > worst ? d : worst;
        mean_e += e[i];
    }
    double mean = sum / (W * H * 3);
    printf("mean |EGL - OSMesa| %.4f, max %d, LPV checksums %016llx %016llx\n", mean, worst,
           (unsigned long long)ce, (unsigned long long)co);
    assert_true(mean_e > 10L * W * H * 3); /* a real picture, not two black ones */
    assert_true(mean < 0.5);
    assert_true(worst <= 8);
    free(e);
    free(o);
}

static void test_unknown_backend_name(void **state)
{
    (void)state;
    glctx_backend b;
    assert_int_equal(glctx_parse_backend("osmesa", &b), 0);
    assert_int_equal(b, GLCTX_OSMESA);
    assert_int_equal(glctx_parse_backend("vulkan", &b), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_egl_and_osmesa_agree),
        cmocka_unit_test(test_unknown_backend_name),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
