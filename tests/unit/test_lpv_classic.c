/* Classic LPV (the ILPV driver's classic mode, ilpv.h): 0 steps give the splat alone
 * (near + shell); S steps give near + the sum of T^s shell for s = 0..S, computed here with
 * the scalar reference; the result has the same bits for any thread count and from frame to
 * frame. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gi/ilpv/ilpv.h"
#include "gi/ilpv/lpv_inject.h"
#include "lpv_reference.h"
#include "lpv_testutil.h"

typedef struct setup {
    lattice_desc lat;
    lpv_volume injected, origin;
    lpv_blockers blockers;
} setup;

static void open_setup(setup *s)
{
    s->lat = (lattice_desc){{0, 0, 0}, 0.5f, {11, 9, 13}};
    assert_int_equal(lpv_volume_init(&s->injected, s->lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&s->origin, s->lat.n, LPV_GEOMETRY_CHANNELS), 0);
    assert_int_equal(lpv_blockers_init(&s->blockers, s->lat.n), 0);
    lpv_vpl vpls[] = {
        {.position = {2.0f, 1.0f, 3.1f}, .normal = {0.1f, 1, 0}, .flux = {1, 0.5f, 0.2f}},
        {.position = {4.1f, 2.2f, 1.7f}, .normal = {-1, 0.2f, 0.3f}, .flux = {0.3f, 0.9f, 0.4f}},
    };
    lpv_inject_vpls(&s->injected, &s->origin, &s->lat, vpls, 2, NULL);
    /* A wall across part of the lattice. */
    float wall[] = {0, 0, 4.2f, 5.5f, 0, 4.2f, 5.5f, 3, 4.2f, 0, 3, 4.2f};
    unsigned idx[] = {0, 1, 2, 0, 2, 3};
    lpv_geometry_add_triangles(&s->blockers, &s->lat, wall, 4, idx, 2, NULL);
}

/* A classic frame of the setup's injection, `steps` steps with these per-step
 * probabilities. */
static const lpv_volume *classic_frame(ilpv *c, const setup *s, int steps, float absorption,
                                       float scattering)
{
    lpv_volume_copy(ilpv_injection(c), &s->injected);
    lpv_volume_copy(ilpv_origin(c), &s->origin);
    assert_int_equal(ilpv_frame(c, &(ilpv_frame_desc){.steps = steps, .classic = 1,
                                                      .absorption = absorption,
                                                      .scattering = scattering}),
                     0);
    return ilpv_result(c);
}

static void close_setup(setup *s)
{
    lpv_volume_free(&s->injected);
    lpv_volume_free(&s->origin);
    lpv_blockers_free(&s->blockers);
}

static void test_zero_steps_is_the_splat(void **state)
{
    (void)state;
    setup s;
    open_setup(&s);
    ilpv c;
    assert_int_equal(ilpv_init(&c, &(ilpv_desc){.lattice = &s.lat, .blockers = &s.blockers}), 0);
    const lpv_volume *result = classic_frame(&c, &s, 0, 0.0f, 0.0f);
    lpv_volume expect;
    assert_int_equal(lpv_volume_init(&expect, s.lat.n, LPV_LIGHT_CHANNELS), 0);
    lpv_volume_copy(&expect, &c.near);
    lpv_volume_add(&expect, &c.shell);
    assert_true(lpv_volume_checksum(result) == lpv_volume_checksum(&expect));
    assert_true(testutil_energy(&c.shell) > 0.0);
    lpv_volume_free(&expect);
    ilpv_free(&c);
    close_setup(&s);
}

static void test_sum_matches_reference_steps(void **state)
{
    (void)state;
    setup s;
    open_setup(&s);
    ilpv c;
    assert_int_equal(ilpv_init(&c, &(ilpv_desc){.lattice = &s.lat, .blockers = &s.blockers}), 0);
    const int steps = 9;
    lpv_propagate_desc pd = {.blockers = &s.blockers, .absorption = 0.05f, .scattering = 0.2f};
    const lpv_volume *result = classic_frame(&c, &s, steps, pd.absorption, pd.scattering);
    /* The same sum with the scalar reference, in double. */
    size_t n = result->cells * LPV_LIGHT_CHANNELS;
    double *sum = calloc(n, sizeof *sum);
    lpv_volume a, b;
    assert_int_equal(lpv_volume_init(&a, s.lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&b, s.lat.n, LPV_LIGHT_CHANNELS), 0);
    lpv_volume_copy(&a, &c.shell);
    for (int step = 0; step <= steps; step++) {
        for (int k = 0; k < LPV_LIGHT_CHANNELS; k++)
            for (size_t i = 0; i < result->cells; i++)
                sum[k * result->cells + i] += a.ch[k][i] + (step == 0 ? c.near.ch[k][i] : 0.0f);
        pd.step = (unsigned)step;
        lpv_reference_step(&pd, &a, &b);
        lpv_volume_copy(&a, &b);
    }
    double peak = 0, diff = 0;
    for (int k = 0; k < LPV_LIGHT_CHANNELS; k++)
        for (size_t i = 0; i < result->cells; i++) {
            peak = fmax(peak, fabs(sum[k * result->cells + i]));
            diff = fmax(diff, fabs(sum[k * result->cells + i] - result->ch[k][i]));
        }
    assert_true(peak > 0 && diff <= 1e-5 * peak);
    free(sum);
    lpv_volume_free(&a);
    lpv_volume_free(&b);
    ilpv_free(&c);
    close_setup(&s);
}

static void test_bit_identical_for_threads_and_frames(void **state)
{
    (void)state;
    setup s;
    open_setup(&s);
    uint64_t sums[4];
    const int threads[3] = {1, 2, 3};
    for (int t = 0; t < 3; t++) {
        workpool *pool = workpool_create(threads[t]);
        ilpv c;
        assert_int_equal(ilpv_init(&c, &(ilpv_desc){.lattice = &s.lat, .blockers = &s.blockers,
                                                    .pool = pool}),
                         0);
        sums[t] = lpv_volume_checksum(classic_frame(&c, &s, 6, 0.0f, 0.0f));
        if (t == 0) /* the next frame from the same injection: the same bits */
            sums[3] = lpv_volume_checksum(classic_frame(&c, &s, 6, 0.0f, 0.0f));
        ilpv_free(&c);
        workpool_destroy(pool);
    }
    assert_true(sums[0] == sums[1] && sums[0] == sums[2] && sums[0] == sums[3]);
    close_setup(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_zero_steps_is_the_splat),
        cmocka_unit_test(test_sum_matches_reference_steps),
        cmocka_unit_test(test_bit_identical_for_threads_and_frames),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
