/* When a frame may reuse the last LPV result: every LPV input counts (a NaN never equals
 * itself), the residual is the relative L1 change with the same bits for any thread
 * count, the first two computed frames are never skipped, a negative threshold never
 * skips, and a change resumes at once. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "gi/ilpv/lpv_converge.h"
#include "lpv_testutil.h"

static void params(frame_params *p)
{
    frame_params_default(p);
    p->light_count = 2;
    for (int i = 0; i < 2; i++) {
        frame_light *l = &p->lights[i];
        *l = (frame_light){.enabled = 1, .position = {1.0f * i, 2, 3}, .direction = {0, -1, 0},
                           .color = {1, 0.5f, 0.25f}, .intensity = 5, .outer_angle = 0.6f,
                           .inner_angle = 0.4f};
    }
}

static void test_every_input_counts(void **state)
{
    (void)state;
    frame_params a, b;
    params(&a);
    b = a;
    assert_true(lpv_converge_inputs_equal(&a, &b));
    /* What the LPV does not read does not count. */
    b.version = 9;
    b.time = 3.5;
    b.head[12] = 1;
    b.exposure = 2;
    b.lights[5].intensity = 100; /* beyond light_count */
    assert_true(lpv_converge_inputs_equal(&a, &b));
    for (int field = 0; field < 17; field++) {
        b = a;
        frame_light *l = &b.lights[1];
        switch (field) {
        case 0: b.light_count = 1; break;
        case 1: b.lpv_steps++; break;
        case 2: b.lambda_incr += 0.1f; break;
        case 3: b.absorption = 0.01f; break;
        case 4: b.scattering = 0.01f; break;
        case 5: b.reset_epoch++; break;
        case 6: l->enabled = 0; break;
        case 7: l->position[0] += 1e-6f; break;
        case 8: l->position[2] = -3; break;
        case 9: l->direction[1] = -0.999f; break;
        case 10: l->color[2] = 0.3f; break;
        case 11: l->intensity = 5.0001f; break;
        case 12: l->outer_angle = 0.61f; break;
        case 13: l->inner_angle = 0.41f; break;
        case 14: l->position[1] = NAN; break;
        case 15: b.lambda_incr = NAN; break;
        case 16: l->type = SCENE_LIGHT_POINT; break;
        }
        assert_false(lpv_converge_inputs_equal(&a, &b));
        if (field == 14 || field == 15) /* NaN: not even equal to itself */
            assert_false(lpv_converge_inputs_equal(&b, &b));
    }
}

static void fill(lpv_volume *v, uint64_t seed, float scale)
{
    uint64_t rng = seed;
    for (int c = 0; c < LPV_LIGHT_CHANNELS; c++)
        for (size_t i = 0; i < v->cells; i++)
            v->ch[c][i] = scale * (testutil_rand(&rng) - 0.3f);
}

static void test_residual(void **state)
{
    (void)state;
    const int n[3] = {13, 7, 9};
    lpv_volume v;
    assert_int_equal(lpv_volume_init(&v, n, LPV_LIGHT_CHANNELS), 0);
    double first_bits = 0;
    for (int threads = 1; threads <= 3; threads++) {
        workpool *pool = workpool_create(threads);
        lpv_converge c;
        assert_int_equal(lpv_converge_init(&c, n, 0), 0);
        assert_true(c.threshold == LPV_CONVERGE_DEFAULT_THRESHOLD);
        fill(&v, 5, 1.0f);
        assert_true(isinf(lpv_converge_end(&c, &v, 0.0, pool))); /* nothing to compare with */
        assert_true(lpv_converge_end(&c, &v, 0.0, pool) == 0.0);
        fill(&v, 5, 2.0f); /* every value doubles: sum|2x - x| / sum|2x| = 1/2 */
        assert_true(fabs(lpv_converge_end(&c, &v, 0.0, pool) - 0.5) < 1e-12);
        fill(&v, 6, 1.0f);
        double r = lpv_converge_end(&c, &v, 0.0, pool);
        assert_true(r > 0.1 && r < 2.0);
        if (threads == 1)
            first_bits = r;
        assert_memory_equal(&r, &first_bits, sizeof r);
        v.ch[3][17] = NAN;
        assert_true(isnan(lpv_converge_end(&c, &v, 0.0, pool)));
        lpv_volume_clear(&v);
        lpv_converge_end(&c, &v, 0.0, pool);
        assert_true(lpv_converge_end(&c, &v, 0.0, pool) == 0.0); /* black after black */
        /* What the source says is pending counts when it is larger. */
        assert_true(lpv_converge_end(&c, &v, 0.25, pool) == 0.25);
        assert_true(isnan(lpv_converge_end(&c, &v, NAN, pool)));
        lpv_converge_free(&c);
        workpool_destroy(pool);
    }
    lpv_volume_free(&v);
}

/* One frame as the renderer runs it: begin, and if not skipped, a result and end. */
static int frame(lpv_converge *c, const frame_params *p, lpv_volume *v, float scale)
{
    if (lpv_converge_begin(c, p))
        return 1;
    fill(v, 1, scale);
    lpv_converge_end(c, v, 0.0, NULL);
    return 0;
}

static void test_skip_rule(void **state)
{
    (void)state;
    const int n[3] = {4, 4, 4};
    lpv_volume v;
    assert_int_equal(lpv_volume_init(&v, n, LPV_LIGHT_CHANNELS), 0);
    frame_params p;
    params(&p);
    lpv_converge c;
    assert_int_equal(lpv_converge_init(&c, n, 1e-3), 0);
    assert_int_equal(frame(&c, &p, &v, 1.0f), 0); /* no residual yet */
    assert_int_equal(frame(&c, &p, &v, 1.0f), 0); /* residual 0 measured now */
    assert_int_equal(frame(&c, &p, &v, 1.0f), 1);
    assert_int_equal(frame(&c, &p, &v, 1.0f), 1);
    assert_int_equal(c.frames_skipped, 2);
    p.lights[0].position[0] += 0.5f; /* a change is computed on that very frame */
    assert_int_equal(frame(&c, &p, &v, 1.5f), 0);
    assert_false(c.skipped);
    /* While the result still changes (residual 1/3, then 1/16, 1/17) nothing is skipped. */
    assert_int_equal(frame(&c, &p, &v, 1.6f), 0);
    assert_int_equal(frame(&c, &p, &v, 1.7f), 0);
    assert_int_equal(frame(&c, &p, &v, 1.7f), 0); /* residual 0 */
    assert_int_equal(frame(&c, &p, &v, 1.7f), 1);
    /* A NaN input never skips, even converged. */
    p.scattering = NAN;
    for (int f = 0; f < 4; f++)
        assert_int_equal(frame(&c, &p, &v, 1.7f), 0);
    assert_int_equal(c.frames_skipped, 3);
    /* After the result was overwritten, two frames are computed before skipping again. */
    p.scattering = 0;
    assert_int_equal(frame(&c, &p, &v, 1.7f), 0);
    assert_int_equal(frame(&c, &p, &v, 1.7f), 1); /* the NaN frames measured residual 0 */
    lpv_converge_forget(&c);
    assert_int_equal(frame(&c, &p, &v, 1.7f), 0);
    assert_int_equal(frame(&c, &p, &v, 1.7f), 0);
    assert_int_equal(frame(&c, &p, &v, 1.7f), 1);
    lpv_converge_free(&c);

    assert_int_equal(lpv_converge_init(&c, n, -1.0), 0); /* never skip */
    params(&p);
    for (int f = 0; f < 4; f++)
        assert_int_equal(frame(&c, &p, &v, 1.0f), 0);
    assert_true(c.residual == 0.0);
    assert_int_equal(c.frames_skipped, 0);
    lpv_converge_free(&c);
    lpv_volume_free(&v);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_input_counts),
        cmocka_unit_test(test_residual),
        cmocka_unit_test(test_skip_rule),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
