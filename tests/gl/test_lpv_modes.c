/* The renderer's LPV modes and frame skipping on real contexts:
 * - classic LPV: the GL accumulation agrees with the CPU one within 1e-3 relative, also
 *   with 0 steps (the splat alone) right after a lit frame; one incremental frame with
 *   lambda 0 is the classic sum, bit for bit;
 * - skipping: with static lights and lambda 0 frames are skipped from the third on, with
 *   the same checksum and bit-identical images as a run that never skips; a moved light is
 *   computed on that very frame; lambda 0.9 converges (its ages summed), then skips, and its images stay
 *   within 1e-3 of the never-skipping run; a NaN or an ever-changing input never skips;
 *   the GL backend skips like the CPU one. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"
#include "lpv_reference.h"

enum { W = 64, H = 48 };

static void open_with(gltest *t, ilpv_backend_choice backend, ilpv_mode mode,
                      double threshold)
{
    char err[512];
    memset(t, 0, sizeof *t);
    glctx_desc gd = {.backend = GLCTX_EGL};
    t->ctx = glctx_create(&gd, err, sizeof err);
    assert_non_null(t->ctx);
    assert_int_equal(scene_load("default", &t->scene, err, sizeof err), 0);
    frame_params_default(&t->params);
    frame_params_lights_from_scene(&t->params, &t->scene);
    gltest_setn(&t->params, "rsm", 64);
    gltest_setn(&t->params, "lattice", 20);
    gltest_seti(&t->params, "lpv", backend);
    gltest_set(&t->params, "gl-tiles", "off");
    gltest_seti(&t->params, "lpv-mode", mode);
    gltest_setn(&t->params, "converge-threshold", threshold);
    renderer_desc rd = {.gl = glctx_gl(t->ctx), .scene = &t->scene, .first = &t->params};
    t->r = renderer_create(&rd, err, sizeof err);
    if (!t->r)
        fprintf(stderr, "%s\n", err);
    assert_non_null(t->r);
}

static void classic_gl_matches_cpu(int steps)
{
    gltest cpu, gpu;
    open_with(&cpu, ILPV_BACKEND_CPU, ILPV_MODE_CLASSIC, -1);
    open_with(&gpu, ILPV_BACKEND_GL, ILPV_MODE_CLASSIC, -1);
    assert_int_equal(gi_ilpv_mode(gi_ilpv_of(renderer_gi(gpu.r))), ILPV_MODE_CLASSIC);
    gltest *both[2] = {&cpu, &gpu};
    for (int k = 0; k < 2; k++) {
        both[k]->params.lambda_incr = 0.8f; /* ignored by classic */
        both[k]->params.absorption = 0.05f;
        both[k]->params.scattering = 0.1f;
        for (int f = 0; f < 2; f++) { /* a lit frame first: nothing of it may remain */
            both[k]->params.lpv_steps = f == 0 ? 3 : steps;
            if (f == 1)
                both[k]->params.lights[0].intensity *= 1.5f;
            renderer_frame_pass(both[k]->r, &both[k]->params);
        }
    }
    const lpv_volume *a = gi_ilpv_volume(gi_ilpv_of(renderer_gi(cpu.r))), *b = gi_ilpv_volume(gi_ilpv_of(renderer_gi(gpu.r)));
    assert_int_equal(lpv_volume_count_nonfinite(b), 0);
    double worst = lpv_reference_rel_diff(b, a), ea[3], eb[3];
    lpv_volume_energy(a, ea);
    lpv_volume_energy(b, eb);
    printf("classic, %d steps: max relative difference GL vs CPU %.3g, energy %.6g / %.6g\n",
           steps, worst, ea[0], eb[0]);
    assert_true(worst < 1e-3);
    for (int c = 0; c < 3; c++)
        assert_true(fabs(ea[c] - eb[c]) <= 1e-3 * fabs(ea[c]));
    gltest_close(&gpu);
    gltest_close(&cpu);
}

static void test_classic_gl_matches_cpu(void **state)
{
    (void)state;
    classic_gl_matches_cpu(6);
}

static void test_classic_zero_steps(void **state)
{
    (void)state;
    classic_gl_matches_cpu(0);
}

/* Classic with S steps and one incremental frame with lambda 0 and S steps are the same
 * sum (the splat and the light of ages 1 .. S): the same bits. */
static void test_classic_sums_steps(void **state)
{
    (void)state;
    gltest inc, cla;
    open_with(&inc, ILPV_BACKEND_CPU, ILPV_MODE_INCREMENTAL, -1);
    open_with(&cla, ILPV_BACKEND_CPU, ILPV_MODE_CLASSIC, -1);
    inc.params.lpv_steps = cla.params.lpv_steps = 8;
    inc.params.lambda_incr = 0;
    renderer_frame_pass(inc.r, &inc.params);
    renderer_frame_pass(cla.r, &cla.params);
    const lpv_volume *vi = gi_ilpv_volume(gi_ilpv_of(renderer_gi(inc.r))), *vc = gi_ilpv_volume(gi_ilpv_of(renderer_gi(cla.r)));
    double ei[3], ec[3];
    lpv_volume_energy(vi, ei);
    lpv_volume_energy(vc, ec);
    printf("energy: incremental (lambda 0, 8 steps) %.6g, classic (8 steps) %.6g\n", ei[0], ec[0]);
    assert_true(ei[0] > 0);
    for (int c = 0; c < LPV_LIGHT_CHANNELS; c++)
        assert_memory_equal(vi->ch[c], vc->ch[c], sizeof(float) * vi->cells);
    gltest_close(&cla);
    gltest_close(&inc);
}

/* Frames with one eye pass each; returns the number skipped; keeps the last final image. */
static int run(gltest *t, int frames, uint64_t *checksum, float *final)
{
    renderer_view v;
    gltest_look_at(&v, t->scene.camera.position, t->scene.camera.target, t->scene.camera.yfov,
                   W, H);
    int skipped = 0;
    for (int f = 0; f < frames; f++) {
        *checksum = renderer_frame_pass(t->r, &t->params);
        gi_ilpv_stats s;
        gi_ilpv_stats_get(gi_ilpv_of(renderer_gi(t->r)), &s);
        skipped += s.skipped_this_frame;
        renderer_image img;
        assert_int_equal(renderer_eye_pass(t->r, &v, 1, &img), 0);
        if (final)
            memcpy(final, img.final, sizeof(float) * 3 * W * H);
    }
    return skipped;
}

static double image_rel_diff(const float *a, const float *b)
{
    double diff = 0, peak = 0;
    for (int i = 0; i < 3 * W * H; i++) {
        diff = fmax(diff, fabs((double)a[i] - b[i]));
        peak = fmax(peak, fabs(b[i]));
    }
    return diff / peak;
}

static void test_static_lambda0_skips_exactly(void **state)
{
    (void)state;
    static float img_skip[3 * W * H], img_full[3 * W * H];
    gltest s, n;
    open_with(&s, ILPV_BACKEND_CPU, ILPV_MODE_INCREMENTAL, 0);
    open_with(&n, ILPV_BACKEND_CPU, ILPV_MODE_INCREMENTAL, -1);
    s.params.lambda_incr = n.params.lambda_incr = 0;
    uint64_t cs, cn;
    assert_int_equal(run(&s, 2, &cs, NULL), 0); /* the second one measures residual 0 */
    gi_ilpv_stats st;
    gi_ilpv_stats_get(gi_ilpv_of(renderer_gi(s.r)), &st);
    assert_true(st.last_residual == 0.0);
    assert_int_equal(run(&s, 3, &cs, img_skip), 3);
    assert_int_equal(run(&n, 5, &cn, img_full), 0);
    assert_true(cs == cn);
    assert_memory_equal(img_skip, img_full, sizeof img_skip);
    renderer_timings t;
    renderer_get_timings(s.r, &t);
    assert_true(t.rsm_ms == 0 && gi_stats_total_ms(&t.gi) == 0);

    /* A moved light is computed on that very frame, in lockstep with the other run. */
    s.params.lights[0].position[0] += 0.3f;
    n.params.lights[0].position[0] += 0.3f;
    assert_int_equal(run(&s, 1, &cs, img_skip), 0);
    run(&n, 1, &cn, img_full);
    assert_true(cs == cn);
    assert_memory_equal(img_skip, img_full, sizeof img_skip);
    renderer_get_timings(s.r, &t);
    assert_true(gi_stats_value(&t.gi, "propagate", NULL) > 0);
    assert_int_equal(run(&s, 3, &cs, NULL), 2); /* converged again: skipping resumes */
    gi_ilpv_stats_get(gi_ilpv_of(renderer_gi(s.r)), &st);
    assert_int_equal(st.frames_skipped, 5);
    gltest_close(&n);
    gltest_close(&s);
}

static void test_lambda09_converges_then_skips(void **state)
{
    (void)state;
    static float img_skip[3 * W * H], img_full[3 * W * H];
    gltest s, n;
    open_with(&s, ILPV_BACKEND_CPU, ILPV_MODE_INCREMENTAL, 0);
    open_with(&n, ILPV_BACKEND_CPU, ILPV_MODE_INCREMENTAL, -1);
    s.params.lambda_incr = n.params.lambda_incr = 0.9f;
    s.params.lpv_steps = n.params.lpv_steps = 2;
    int first_skip = -1;
    uint64_t cs, cn;
    for (int f = 0; f < 200 && first_skip < 0; f++) {
        renderer_frame_pass(s.r, &s.params);
        gi_ilpv_stats st;
        gi_ilpv_stats_get(gi_ilpv_of(renderer_gi(s.r)), &st);
        if (st.skipped_this_frame)
            first_skip = f;
    }
    printf("lambda 0.9: first skipped frame %d\n", first_skip);
    /* Static lights: the chain sums the light's ages until the newest is below the
     * threshold, however large lambda is (at 2 steps a frame that takes some 30 steps). */
    assert_true(first_skip > 5 && first_skip < 100);
    assert_int_equal(run(&s, 3, &cs, img_skip), 3);
    run(&n, first_skip + 3, &cn, img_full);
    double d = image_rel_diff(img_skip, img_full);
    printf("lambda 0.9: image difference to the never-skipping run %.3g\n", d);
    assert_true(d < 1e-3);
    gltest_close(&n);
    gltest_close(&s);
}

/* A NaN absorption is sanitized to its default (0) before the skip rule sees it: with
 * lambda_incr 0 a valid, constant input whose result converges at once, so frames 3 to 5
 * skip. A changing input never does. */
static void test_nan_is_sanitized_and_changing_input_never_skips(void **state)
{
    (void)state;
    gltest t;
    open_with(&t, ILPV_BACKEND_CPU, ILPV_MODE_INCREMENTAL, 0);
    t.params.lambda_incr = 0;
    t.params.absorption = NAN;
    uint64_t c;
    assert_int_equal(run(&t, 5, &c, NULL), 3);
    gi_ilpv_stats st;
    gi_ilpv_stats_get(gi_ilpv_of(renderer_gi(t.r)), &st);
    assert_true(st.last_residual == 0.0);
    t.params.lambda_incr = 0;
    for (int f = 0; f < 5; f++) { /* a tiny change every frame */
        t.params.lights[0].intensity *= 1.0001f;
        assert_int_equal(run(&t, 1, &c, NULL), 0);
    }
    gltest_close(&t);
}

/* Measuring the step cost leaves the renderer as if it had just been created: no history
 * (lambda 0.8: the next frame equals a fresh renderer's first) and no skipping on stale
 * volumes (lambda 0: converged before, computed again after, same result). */
static void test_measure_then_render(void **state)
{
    (void)state;
    for (int combo = 0; combo < 4; combo++) {
        ilpv_backend_choice backend = combo & 1 ? ILPV_BACKEND_GL : ILPV_BACKEND_CPU;
        ilpv_mode mode = combo & 2 ? ILPV_MODE_CLASSIC : ILPV_MODE_INCREMENTAL;
        gltest a, b;
        open_with(&a, backend, mode, 0);
        open_with(&b, backend, mode, 0);
        a.params.lambda_incr = b.params.lambda_incr = 0.8f;
        uint64_t ca, cb;
        run(&a, 4, &ca, NULL);
        double ms = gi_ilpv_measure_step_ms(gi_ilpv_of(renderer_gi(a.r)), 2);
        printf("backend %d, mode %d: %.3g ms per step\n", backend, mode, ms);
        assert_true(ms > 0);
        assert_int_equal(run(&a, 1, &ca, NULL), 0);
        run(&b, 1, &cb, NULL);
        assert_true(ca == cb);

        a.params.lambda_incr = 0; /* the same result as the last frame, the first after reset */
        assert_int_equal(run(&a, 4, &ca, NULL), 3);
        gi_ilpv_measure_step_ms(gi_ilpv_of(renderer_gi(a.r)), 1);
        assert_int_equal(run(&a, 2, &cb, NULL), 0);
        assert_true(ca == cb);
        assert_int_equal(run(&a, 1, &cb, NULL), 1);
        gltest_close(&b);
        gltest_close(&a);
    }
}

static void test_gl_backend_skips(void **state)
{
    (void)state;
    for (int mode = 0; mode < 2; mode++) {
        gltest t;
        open_with(&t, ILPV_BACKEND_GL, (ilpv_mode)mode, 0);
        t.params.lambda_incr = 0;
        uint64_t c2, c5;
        assert_int_equal(run(&t, 2, &c2, NULL), 0);
        assert_int_equal(run(&t, 3, &c5, NULL), 3);
        assert_true(c2 == c5);
        gltest_close(&t);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_classic_gl_matches_cpu),
        cmocka_unit_test(test_classic_zero_steps),
        cmocka_unit_test(test_classic_sums_steps),
        cmocka_unit_test(test_static_lambda0_skips_exactly),
        cmocka_unit_test(test_lambda09_converges_then_skips),
        cmocka_unit_test(test_nan_is_sanitized_and_changing_input_never_skips),
        cmocka_unit_test(test_measure_then_render),
        cmocka_unit_test(test_gl_backend_skips),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
