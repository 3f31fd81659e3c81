/* node/gi/ilpv/paper_propagate.comp on llvmpipe, run directly (tests/reference/lpv_gl_steps.h):
 * one step agrees with the CPU's paper step (lpv_propagate_step()) with and without
 * blocking, absorption and scattering, on a lattice that is no multiple of the work group;
 * and the thesis's incremental frames -- the merge in shaders/accumulate.comp, S steps with
 * the first unblocked -- agree with lpv_paper_frame() over frames whose power changes. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>

#include "gl/glctx.h"
#include "gi/ilpv/lpv_paper_frame.h"
#include "gi/ilpv/sh.h"
#include "lpv_gl_steps.h"
#include "lpv_testutil.h"

static const int N[3] = {19, 13, 10};

/* Light of every kind (beams, lobes, isotropic), some cells empty; random blockers. */
static void fill(lpv_volume *v, lpv_blockers *b, uint64_t seed)
{
    uint64_t rng = seed;
    for (size_t i = 0; i < v->cells; i++)
        for (int c = 0; c < 3; c++) {
            if (testutil_rand(&rng) < 0.3f)
                continue;
            float d[3] = {testutil_rand(&rng) - 0.5f, testutil_rand(&rng) - 0.5f,
                          testutil_rand(&rng) - 0.5f}, L[4];
            sh_eval(d, L);
            float beam = testutil_rand(&rng), iso = testutil_rand(&rng);
            for (int s = 0; s < 4; s++)
                v->ch[4 * c + s][i] = beam * L[s] + (s == 0 ? iso * (float)SH_Y0 : 0.0f);
        }
    if (b)
        for (size_t i = 0; i < b->cells; i++)
            b->mask[i] = testutil_rand(&rng) < 0.7f ? 0u : (uint32_t)(testutil_rand(&rng) * 67108863.0f);
}

/* Makes the blockers symmetric, as lpv_geometry builds them: a segment is marked in both
 * of its cells (the shader reads the destination's word, the CPU the source's). */
static void symmetric(lpv_blockers *b)
{
    for (int z = 0; z < b->n[2]; z++)
        for (int y = 0; y < b->n[1]; y++)
            for (int x = 0; x < b->n[0]; x++)
                for (int k = 0; k < LPV_NEIGHBOURS; k++) {
                    const int *o = lpv_transfer_offsets[k];
                    int tx = x + o[0], ty = y + o[1], tz = z + o[2];
                    size_t i = (size_t)x + b->n[0] * ((size_t)y + b->n[1] * (size_t)z);
                    if (!((b->mask[i] >> k) & 1u) || tx < 0 || ty < 0 || tz < 0 ||
                        tx >= b->n[0] || ty >= b->n[1] || tz >= b->n[2])
                        continue;
                    b->mask[tx + b->n[0] * ((size_t)ty + b->n[1] * (size_t)tz)] |= 1u << (25 - k);
                }
}

typedef struct fixture {
    glctx *ctx;
    lpv_gl_steps gs;
    lpv_blockers blockers;
    lpv_volume a, b;
} fixture;

static int setup(void **state)
{
    static fixture f;
    char err[512];
    glctx_desc gd = {.backend = GLCTX_EGL};
    if (!(f.ctx = glctx_create(&gd, err, sizeof err)) || lpv_blockers_init(&f.blockers, N) ||
        lpv_volume_init(&f.a, N, LPV_LIGHT_CHANNELS) || lpv_volume_init(&f.b, N, LPV_LIGHT_CHANNELS)) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    fill(&f.a, &f.blockers, 7);
    symmetric(&f.blockers);
    if (lpv_gl_steps_init(&f.gs, glctx_gl(f.ctx), N, &f.blockers, NULL, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    *state = &f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    lpv_gl_steps_free(&f->gs);
    lpv_volume_free(&f->a);
    lpv_volume_free(&f->b);
    lpv_blockers_free(&f->blockers);
    glctx_destroy(f->ctx);
    return 0;
}

static void test_one_step_matches_the_cpu(void **state)
{
    fixture *f = *state;
    GLuint src[3], dst[3];
    lpv_gl_volume_textures(&f->gs, src);
    lpv_gl_volume_textures(&f->gs, dst);
    lpv_gl_upload(&f->gs, &f->a, src);
    const float coeff[][2] = {{0, 0}, {0.1f, 0.05f}, {0.3f, 0.9f}};
    for (int blocking = 0; blocking < 2; blocking++)
        for (int c = 0; c < 3; c++) {
            lpv_propagate_desc pd = {.transport = LPV_TRANSPORT_PAPER,
                                     .blockers = blocking ? &f->blockers : NULL,
                                     .absorption = coeff[c][0], .scattering = coeff[c][1]};
            lpv_gl_step(&f->gs, &pd, src, dst);
            lpv_gl_download(&f->gs, dst, &f->b);
            lpv_volume cpu;
            assert_int_equal(lpv_volume_init(&cpu, N, LPV_LIGHT_CHANNELS), 0);
            lpv_propagate_step(&pd, &f->a, &cpu);
            double d = testutil_rel_diff(&f->b, &cpu);
            printf("blocking %d absorption %.2f scattering %.2f: GL against CPU %.3g\n",
                   blocking, coeff[c][0], coeff[c][1], d);
            assert_true(d < 1e-5);
            assert_true(testutil_energy(&cpu) > 0.0);
            lpv_volume_free(&cpu);
        }
    f->gs.gl->DeleteTextures(3, src);
    f->gs.gl->DeleteTextures(3, dst);
}

/* lpv_paper_frame() on the GPU: merge, then the steps, the first unblocked. */
static void gl_frame(lpv_gl_steps *gs, lpv_paper_history *h, const lpv_volume *injected,
                     GLuint inj[3], GLuint vol[2][3], int *current, const lpv_paper_frame_desc *d)
{
    lpv_paper_merge m = lpv_paper_merge_factors(h, d->lambda_incr, d->emitted_energy);
    lpv_gl_upload(gs, injected, inj);
    lpv_gl_combine(gs, vol[*current], m.a, inj, m.b);
    lpv_propagate_desc pd = d->propagate;
    pd.transport = LPV_TRANSPORT_PAPER;
    for (int step = 0; step < d->steps; step++) {
        pd.blockers = step > 0 ? d->propagate.blockers : NULL;
        lpv_gl_step(gs, &pd, vol[*current], vol[1 - *current]);
        *current = 1 - *current;
    }
    lpv_paper_history_advance(h, d->emitted_energy);
}

static void test_incremental_frames_match_the_cpu(void **state)
{
    fixture *f = *state;
    lattice_desc lat = {{0, 0, 0}, 0.25f, {N[0], N[1], N[2]}};
    lpv_paper_lpv cpu;
    assert_int_equal(lpv_paper_init(&cpu, &lat), 0);
    GLuint inj[3], vol[2][3];
    lpv_gl_volume_textures(&f->gs, inj);
    lpv_gl_volume_textures(&f->gs, vol[0]);
    lpv_gl_volume_textures(&f->gs, vol[1]);
    lpv_paper_history h = {0};
    int current = 0;
    for (int frame = 0; frame < 5; frame++) {
        float power = frame < 2 ? 1.0f : 1.5f;
        lpv_paper_begin_frame(&cpu);
        fill(lpv_paper_injection(&cpu), NULL, 7);
        lpv_volume_scale(lpv_paper_injection(&cpu), power);
        lpv_paper_frame_desc fd = {.steps = 4, .lambda_incr = 0.8f, .emitted_energy = power,
                                   .propagate = {.blockers = &f->blockers, .absorption = 0.02f,
                                                 .scattering = 0.05f}};
        lpv_paper_frame(&cpu, &fd);
        gl_frame(&f->gs, &h, lpv_paper_injection(&cpu), inj, vol, &current, &fd);
    }
    lpv_gl_download(&f->gs, vol[current], &f->b);
    double d = testutil_rel_diff(&f->b, lpv_paper_result(&cpu));
    printf("5 incremental frames: GL against CPU %.3g\n", d);
    assert_true(d < 1e-5);
    assert_int_equal(lpv_volume_count_nonfinite(&f->b), 0);
    f->gs.gl->DeleteTextures(3, inj);
    f->gs.gl->DeleteTextures(3, vol[0]);
    f->gs.gl->DeleteTextures(3, vol[1]);
    lpv_paper_free(&cpu);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_one_step_matches_the_cpu),
        cmocka_unit_test(test_incremental_frames_match_the_cpu),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
