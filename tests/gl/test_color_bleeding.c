/* Colour bleeding in the default room: in the indirect-only image, the floor beside the
 * red wall is redder than floor far from it, while the direct light there is white. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"

enum { W = 128, H = 96 };

/* Red over green: independent of brightness, and the walls' albedos differ most there. */
static double redness(const double c[3])
{
    return c[0] / (c[1] + 1e-30);
}

static void test_floor_beside_red_wall_is_redder(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    renderer_view v;
    /* From above, the whole floor in view. */
    const float eye[3] = {0.0f, 2.9f, 0.0f}, target[3] = {0.0f, 0.0f, 0.0f};
    gltest_look_at(&v, eye, target, 1.5f, W, H);
    renderer_image img;
    for (int f = 0; f < 6; f++) /* a few incremental frames towards the steady state */
        renderer_frame_pass(t.r, &t.params);
    assert_int_equal(renderer_eye_pass(t.r, &v, 1, &img), 0);

    const float near_red[3] = {-1.75f, 0.0f, 1.3f}, far_red[3] = {0.9f, 0.0f, 1.3f};
    float pn[2], pf[2];
    gltest_project(&v, near_red, pn);
    gltest_project(&v, far_red, pf);
    double in_near[3], in_far[3], d_near[3], d_far[3];
    gltest_window_mean(img.indirect, W, H, (int)pn[0], (int)pn[1], 2, in_near);
    gltest_window_mean(img.indirect, W, H, (int)pf[0], (int)pf[1], 2, in_far);
    gltest_window_mean(img.direct, W, H, (int)pn[0], (int)pn[1], 2, d_near);
    gltest_window_mean(img.direct, W, H, (int)pf[0], (int)pf[1], 2, d_far);
    printf("indirect near red wall %.4g %.4g %.4g (redness %.3f), far %.4g %.4g %.4g "
           "(redness %.3f)\n", in_near[0], in_near[1], in_near[2], redness(in_near), in_far[0],
           in_far[1], in_far[2], redness(in_far));
    assert_true(in_near[0] > 0 && in_far[0] > 0);
    assert_true(redness(in_near) > 1.3 * redness(in_far));
    /* The redness is not the light's: direct light at those points is white or absent. */
    assert_true(redness(d_near) < 1.2 && redness(d_far) < 1.2);
    gltest_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_floor_beside_red_wall_is_redder),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
