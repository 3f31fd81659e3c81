/* Stage (c) of docs/lpv.md: a closed 4 x 3 x 4 m room of uniform albedo 0.75, lit by one
 * spot from under its ceiling onto the floor, at 16, 32 and 64 cells (CPU backend, 4 steps
 * per frame, lambda 0.8, to the steady state): the mean one-bounce indirect light seen on
 * each of the six faces against the path-traced reference (node/reference/reference.h), one view per
 * face from the room's centre. The reference's own noise (from its two halves) is printed
 * next to each ratio; the bounds are the measured ones with a margin. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"
#include "reference/reference.h"

enum { W = 48, H = 36, FRAMES = 40, REF_SAMPLES = 12 };

static void build_room(scene *s)
{
    memset(s, 0, sizeof *s);
    scene_material white = {{0.75f, 0.75f, 0.75f, 1}, -1, {0, 0, 0}, 0.8f};
    assert_int_equal(scene_add_material(s, &white), 0);
    const float lo[3] = {-2, 0, -2}, hi[3] = {2, 3, 2};
    assert_int_equal(scene_add_box(s, lo, hi, 1, 0), 0); /* faces inward */
    scene_light spot = {.position = {-0.8f, 2.8f, 0.6f}, .color = {1, 1, 1}, .intensity = 10.0f,
                        .outer_angle = 0.5f, .inner_angle = 0.4f};
    const float target[3] = {0.6f, 0.0f, -0.6f};
    scene_light_aim(&spot, target);
    assert_true(scene_add_light(s, &spot) >= 0);
    char err[256];
    assert_int_equal(scene_finish(s, err, sizeof err), 0);
}

static double mean(const float *img)
{
    double s = 0;
    for (int i = 0; i < 3 * W * H; i++)
        s += img[i];
    return s / (3.0 * W * H);
}

static void test_faces_against_the_reference(void **state)
{
    (void)state;
    static const char *const face[6] = {"floor", "ceiling", "-x wall", "+x wall", "-z wall", "+z wall"};
    const float centre[3] = {0, 1.5f, 0};
    const float look[6][3] = {{0, 0, 0}, {0, 3, 0}, {-2, 1.5f, 0}, {2, 1.5f, 0}, {0, 1.5f, -2},
                              {0, 1.5f, 2}};
    const float up_fix[6][3] = {{0, 0, 0.05f}, {0, 0, 0.05f}, {0}, {0}, {0}, {0}};
    scene s;
    build_room(&s);
    frame_params p;
    frame_params_default(&p);
    frame_params_lights_from_scene(&p, &s);
    p.lpv_steps = 4;
    p.lambda_incr = 0.8f;
    char err[512];
    reference *ref = reference_create(&s, 2, err, sizeof err);
    assert_non_null(ref);
    renderer_view v[6];
    double truth[6], noise[6];
    for (int f = 0; f < 6; f++) {
        float target[3];
        for (int a = 0; a < 3; a++)
            target[a] = look[f][a] + up_fix[f][a];
        /* 70 degrees: the face fills the view and nothing else shows */
        gltest_look_at(&v[f], centre, target, 1.22f, W, H);
        reference_render_desc rd = {.params = &p, .view = &v[f], .samples = REF_SAMPLES,
                                    .max_bounces = 1, .seed = 1};
        reference_images out;
        reference_noise nz;
        assert_int_equal(reference_render_averaged(ref, &rd, &out, &nz, err, sizeof err), 0);
        truth[f] = mean(out.indirect1);
        noise[f] = nz.indirect1 / truth[f];
        reference_images_free(&out);
    }
    reference_destroy(ref);

    const int sizes[3] = {16, 32, 64};
    /* Measured ratios lpv / reference (docs/lpv.md, "Stage tests"): floor 0.87 .. 1.17,
     * ceiling 1.26 .. 1.29, walls 0.72 .. 0.99, geometric means 0.898 .. 0.932; bounds with
     * a margin. */
    const double lo[6] = {0.7, 1.1, 0.6, 0.6, 0.6, 0.6}, hi[6] = {1.4, 1.45, 1.1, 1.1, 1.1, 1.1};
    for (int k = 0; k < 3; k++) {
        glctx_desc gd = {.backend = GLCTX_EGL};
        glctx *ctx = glctx_create(&gd, err, sizeof err);
        assert_non_null(ctx);
        frame_params q = p;
        gltest_setn(&q, "rsm", 128);
        gltest_setn(&q, "lattice", sizes[k]);
        gltest_set(&q, "lpv", "cpu");
        renderer_desc rd = {.gl = glctx_gl(ctx), .scene = &s, .first = &q, .threads = 2,
                            .no_reuse = 1};
        renderer *r = renderer_create(&rd, err, sizeof err);
        assert_non_null(r);
        for (int f = 0; f < FRAMES * (sizes[k] / 16); f++)
            renderer_frame_pass(r, &q);
        printf("stage (c) %d cells: lpv / reference per face (reference noise)\n", sizes[k]);
        double log_sum = 0;
        for (int f = 0; f < 6; f++) {
            renderer_image img;
            assert_int_equal(renderer_eye_pass(r, &v[f], 1, &img), 0);
            double ratio = mean(img.indirect) / truth[f];
            printf("  %-8s %.3f (%.3f)\n", face[f], ratio, noise[f]);
            log_sum += log(ratio);
            assert_true(ratio > lo[f] && ratio < hi[f]);
        }
        printf("  geometric mean %.3f\n", exp(log_sum / 6));
        assert_true(fabs(log_sum / 6) < 0.15);
        renderer_destroy(r);
        glctx_destroy(ctx);
    }
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_faces_against_the_reference),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
