/* The GI methods behind node/gi.h on llvmpipe: "none" renders the same direct light as
 * ILPV and no indirect light at all, with a constant checksum; a frame that asks for
 * another method switches the renderer in that frame, and switching back to ILPV starts
 * it afresh: the same light, bit for bit, as a new renderer's first frames. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"

enum { W = 64, H = 48 };

static void view(renderer_view *v)
{
    const float eye[3] = {1.3f, 1.6f, 1.9f}, target[3] = {-0.5f, 0.9f, -1.2f};
    gltest_look_at(v, eye, target, 1.15f, W, H);
}

/* One frame of p; copies of its direct and indirect linear images (W*H*3 floats each). */
static uint64_t frame(gltest *t, const frame_params *p, float *direct, float *indirect)
{
    uint64_t checksum = renderer_frame_pass(t->r, p);
    renderer_view v;
    view(&v);
    renderer_image img;
    assert_int_equal(renderer_eye_pass(t->r, &v, 1, &img), 0);
    memcpy(direct, img.direct, sizeof(float) * W * H * 3);
    memcpy(indirect, img.indirect, sizeof(float) * W * H * 3);
    return checksum;
}

static double sum(const float *x) /* over all pixels and channels */
{
    double s = 0;
    for (int i = 0; i < W * H * 3; i++)
        s += x[i];
    return s;
}

static void test_none_is_direct_only(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, RENDERER_LPV_CPU, 0), 0);
    static float d_ilpv[W * H * 3], i_ilpv[W * H * 3], d_none[W * H * 3], i_none[W * H * 3];
    frame(&t, &t.params, d_ilpv, i_ilpv);
    assert_int_equal(renderer_get_gi(t.r), FRAME_GI_ILPV);
    frame_params p = t.params;
    p.gi = FRAME_GI_NONE;
    uint64_t c1 = frame(&t, &p, d_none, i_none);
    assert_int_equal(renderer_get_gi(t.r), FRAME_GI_NONE);
    assert_null(renderer_get_lattice(t.r));
    assert_null(renderer_get_lpv(t.r));
    printf("indirect light: ILPV %.4g, none %.4g (sum over the image)\n", sum(i_ilpv), sum(i_none));
    assert_true(sum(i_ilpv) > 0);
    for (int i = 0; i < W * H * 3; i++)
        assert_true(i_none[i] == 0.0f);
    assert_memory_equal(d_none, d_ilpv, sizeof d_none);
    p.time = 1.0; /* no state: the same checksum every frame */
    assert_true(frame(&t, &p, d_none, i_none) == c1);
    gltest_close(&t);
}

static void test_switch_back_starts_afresh(void **state)
{
    (void)state;
    gltest a, b;
    assert_int_equal(gltest_open(&a, GLCTX_EGL, RENDERER_LPV_CPU, 0), 0);
    static float d[W * H * 3], ia[W * H * 3], ib[W * H * 3];
    frame_params p = a.params;
    for (int f = 0; f < 3; f++) /* history builds up */
        frame(&a, &p, d, ia);
    p.gi = FRAME_GI_NONE;
    frame(&a, &p, d, ia);
    p.gi = FRAME_GI_ILPV;
    uint64_t after[2];
    for (int f = 0; f < 2; f++)
        after[f] = frame(&a, &p, d, ia);
    assert_int_equal(renderer_get_gi(a.r), FRAME_GI_ILPV);

    assert_int_equal(gltest_open(&b, GLCTX_EGL, RENDERER_LPV_CPU, 0), 0);
    for (int f = 0; f < 2; f++) {
        uint64_t fresh = frame(&b, &p, d, ib);
        printf("frame %d after switching back: %016llx, fresh renderer: %016llx\n", f,
               (unsigned long long)after[f], (unsigned long long)fresh);
        assert_true(after[f] == fresh);
    }
    assert_memory_equal(ia, ib, sizeof ia);
    gltest_close(&b);
    gltest_close(&a);
}

static void test_created_with_none(void **state)
{
    (void)state;
    char err[512];
    gltest t;
    memset(&t, 0, sizeof t);
    assert_non_null(t.ctx = glctx_create(&(glctx_desc){.backend = GLCTX_EGL}, err, sizeof err));
    assert_int_equal(scene_load("default", &t.scene, err, sizeof err), 0);
    renderer_desc rd = {.gl = glctx_gl(t.ctx), .scene = &t.scene, .rsm_size = 64,
                        .lattice_cells = 20, .gi = FRAME_GI_NONE};
    assert_non_null(t.r = renderer_create(&rd, err, sizeof err));
    assert_int_equal(renderer_get_gi(t.r), FRAME_GI_NONE);
    frame_params_default(&t.params);
    frame_params_lights_from_scene(&t.params, &t.scene);
    /* The frames' gi decides: a default frame asks for ILPV. */
    static float d[W * H * 3], i[W * H * 3];
    frame(&t, &t.params, d, i);
    assert_int_equal(renderer_get_gi(t.r), FRAME_GI_ILPV);
    assert_non_null(renderer_get_lattice(t.r));
    gltest_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_none_is_direct_only),
        cmocka_unit_test(test_switch_back_starts_afresh),
        cmocka_unit_test(test_created_with_none),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
