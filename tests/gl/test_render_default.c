/* The default room on llvmpipe: a picture that is neither black nor saturated, and a
 * spotlight disc exactly where the camera projection puts the spot's axis on the floor. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"

enum { W = 128, H = 96 };

static void test_not_black_not_saturated(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    renderer_view v;
    gltest_look_at(&v, t.scene.camera.position, t.scene.camera.target, t.scene.camera.yfov, W, H);
    renderer_image img;
    for (int f = 0; f < 2; f++) {
        renderer_frame_pass(t.r, &t.params);
        assert_int_equal(renderer_eye_pass(t.r, &v, 0, &img), 0);
    }
    assert_int_equal(img.width, W);
    double mean = 0;
    size_t black = 0, white = 0, n = (size_t)W * H;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *p = img.rgb + 3 * i;
        mean += (p[0] + p[1] + p[2]) / 3.0;
        black += p[0] < 3 && p[1] < 3 && p[2] < 3;
        white += p[0] > 252 && p[1] > 252 && p[2] > 252;
    }
    mean /= (double)n;
    printf("mean %.1f, black %.1f%%, white %.1f%%\n", mean, 100.0 * black / n, 100.0 * white / n);
    assert_true(mean > 15 && mean < 200);
    assert_true(black < n / 4);
    assert_true(white < n / 20);
    gltest_close(&t);
}

/* A narrow spot straight down onto a clear patch of floor, seen from above: the centroid
 * of the lit pixels in the direct-only image is the projection of the spot's axis hit. */
static void test_spot_disc_where_projected(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    const float hit[3] = {-1.0f, 0.0f, -0.2f};
    frame_light *l = &t.params.lights[0];
    l->position[0] = hit[0];
    l->position[1] = 2.5f;
    l->position[2] = hit[2];
    l->direction[0] = 0;
    l->direction[1] = -1;
    l->direction[2] = 0;
    l->outer_angle = 0.30f;
    l->inner_angle = 0.25f;
    renderer_view v;
    const float eye[3] = {0.0f, 2.9f, 0.3f}, target[3] = {0.0f, 0.0f, 0.3f};
    gltest_look_at(&v, eye, target, 1.2f, W, H);
    renderer_frame_pass(t.r, &t.params);
    renderer_image img;
    assert_int_equal(renderer_eye_pass(t.r, &v, 1, &img), 0);

    float want[2];
    gltest_project(&v, hit, want);
    double peak = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        peak = fmax(peak, img.direct[3 * i + 1]);
    double sx = 0, sy = 0, count = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (img.direct[((size_t)y * W + x) * 3 + 1] > 0.5 * peak) {
                sx += x + 0.5;
                sy += y + 0.5;
                count++;
            }
    assert_true(count > 20);
    sx /= count;
    sy /= count;
    printf("disc centroid (%.2f, %.2f), projected (%.2f, %.2f), %g pixels\n", sx, sy, want[0],
           want[1], count);
    assert_true(fabs(sx - want[0]) < 1.5 && fabs(sy - want[1]) < 1.5);
    /* Its size follows the cone: the lit area lies between the inner and outer footprints. */
    float edge_in[3] = {hit[0] + 2.5f * tanf(0.25f), 0, hit[2]};
    float edge_out[3] = {hit[0] + 2.5f * tanf(0.30f), 0, hit[2]};
    float pin[2], pout[2];
    gltest_project(&v, edge_in, pin);
    gltest_project(&v, edge_out, pout);
    double r_in = fabs(pin[0] - want[0]), r_out = fabs(pout[0] - want[0]);
    double r_lit = sqrt(count / 3.14159265358979);
    printf("lit radius %.2f px, cone radii %.2f..%.2f px\n", r_lit, r_in, r_out);
    assert_true(r_lit > r_in - 1.0 && r_lit < r_out + 1.0);
    gltest_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_not_black_not_saturated),
        cmocka_unit_test(test_spot_disc_where_projected),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
