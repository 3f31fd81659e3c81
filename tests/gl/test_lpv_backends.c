/* The two propagation backends on the same input: the GL compute shader agrees with the
 * CPU core within 1e-3 relative, over several incremental frames with blocking and
 * scattering; and the CPU path is bit-identical for 1 and 2 threads. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"
#include "lpv_reference.h"

static void run_frames(gltest *t, int frames, uint64_t *checksum)
{
    t->params.lpv_steps = 4;
    t->params.lambda_incr = 0.8f;
    t->params.absorption = 0.05f;
    t->params.scattering = 0.1f;
    for (int f = 0; f < frames; f++) {
        if (f == 2)
            t->params.lights[0].intensity *= 1.5f; /* E changes: exercises the merge factor */
        *checksum = renderer_frame_pass(t->r, &t->params);
    }
}

/* Both variants of the shader: plain image loads and shared-memory tiles. */
static void gl_matches_cpu(ilpv_tiles tiles)
{
    gltest cpu, gpu;
    uint64_t c_cpu, c_gpu;
    assert_int_equal(gltest_open(&cpu, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    run_frames(&cpu, 4, &c_cpu);
    assert_int_equal(gltest_open_tiles(&gpu, GLCTX_EGL, ILPV_BACKEND_GL, 0, tiles), 0);
    assert_int_equal(gi_ilpv_backend(gi_ilpv_of(renderer_gi(gpu.r))), ILPV_BACKEND_GL);
    run_frames(&gpu, 4, &c_gpu);
    const lpv_volume *a = gi_ilpv_volume(gi_ilpv_of(renderer_gi(cpu.r))), *b = gi_ilpv_volume(gi_ilpv_of(renderer_gi(gpu.r)));
    assert_int_equal(a->cells, b->cells);
    assert_int_equal(lpv_volume_count_nonfinite(b), 0);
    for (int c = 0; c < LPV_LIGHT_CHANNELS; c++) { /* light in every channel */
        double peak = 0;
        for (size_t i = 0; i < a->cells; i++)
            peak = fmax(peak, fabs(a->ch[c][i]));
        assert_true(peak > 0);
    }
    double worst = lpv_reference_rel_diff(b, a);
    double ea[3], eb[3];
    lpv_volume_energy(a, ea);
    lpv_volume_energy(b, eb);
    printf("max relative difference %.3g; energy cpu %.6g gl %.6g\n", worst, ea[0], eb[0]);
    assert_true(worst < 1e-3);
    for (int c = 0; c < 3; c++)
        assert_true(fabs(ea[c] - eb[c]) <= 1e-3 * fabs(ea[c]));
    gltest_close(&gpu);
    gltest_close(&cpu);
}

static void test_gl_images_match_cpu(void **state)
{
    (void)state;
    gl_matches_cpu(ILPV_TILES_OFF);
}

static void test_gl_tiles_match_cpu(void **state)
{
    (void)state;
    gl_matches_cpu(ILPV_TILES_ON);
}

static void test_cpu_bit_identical_across_threads(void **state)
{
    (void)state;
    gltest one, two;
    uint64_t c1, c2;
    assert_int_equal(gltest_open(&one, GLCTX_EGL, ILPV_BACKEND_CPU, 1), 0);
    run_frames(&one, 3, &c1);
    assert_int_equal(gltest_open(&two, GLCTX_EGL, ILPV_BACKEND_CPU, 2), 0);
    run_frames(&two, 3, &c2);
    assert_true(c1 == c2);
    assert_true(c1 == lpv_volume_checksum(gi_ilpv_volume(gi_ilpv_of(renderer_gi(one.r)))));
    gltest_close(&two);
    gltest_close(&one);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gl_images_match_cpu),
        cmocka_unit_test(test_gl_tiles_match_cpu),
        cmocka_unit_test(test_cpu_bit_identical_across_threads),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
