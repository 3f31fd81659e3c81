/* The GI methods behind node/gi/gi.h on llvmpipe: "none" renders the same direct light as
 * ILPV and no indirect light at all, with a constant checksum; a frame that asks for
 * another method switches the renderer in that frame, and switching back to ILPV starts
 * it afresh: the same light, bit for bit, as a new renderer's first frames; every method
 * of the registry renders; a setting that rebuilds a method does so, the others do not; a
 * cluster node's limits keep a runaway frame on the last settings within them. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

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
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    static float d_ilpv[W * H * 3], i_ilpv[W * H * 3], d_none[W * H * 3], i_none[W * H * 3];
    frame(&t, &t.params, d_ilpv, i_ilpv);
    assert_int_equal(gi_active(renderer_gi(t.r)), gi_method_find("ilpv"));
    frame_params p = t.params;
    p.gi = gi_method_find("none");
    uint64_t c1 = frame(&t, &p, d_none, i_none);
    assert_int_equal(gi_active(renderer_gi(t.r)), gi_method_find("none"));
    assert_null(gi_ilpv_of(renderer_gi(t.r)));
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
    assert_int_equal(gltest_open(&a, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    static float d[W * H * 3], ia[W * H * 3], ib[W * H * 3];
    frame_params p = a.params;
    for (int f = 0; f < 3; f++) /* history builds up */
        frame(&a, &p, d, ia);
    p.gi = gi_method_find("none");
    frame(&a, &p, d, ia);
    p.gi = gi_method_find("ilpv");
    uint64_t after[2];
    for (int f = 0; f < 2; f++)
        after[f] = frame(&a, &p, d, ia);
    assert_int_equal(gi_active(renderer_gi(a.r)), gi_method_find("ilpv"));

    assert_int_equal(gltest_open(&b, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
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
    frame_params_default(&t.params);
    frame_params_lights_from_scene(&t.params, &t.scene);
    gltest_setn(&t.params, "rsm", 64);
    gltest_setn(&t.params, "lattice", 20);
    frame_params first = t.params;
    gltest_set(&first, "gi", "none");
    renderer_desc rd = {.gl = glctx_gl(t.ctx), .scene = &t.scene, .first = &first};
    assert_non_null(t.r = renderer_create(&rd, err, sizeof err));
    assert_int_equal(gi_active(renderer_gi(t.r)), gi_method_find("none"));
    /* The frames' gi decides: a default frame asks for ILPV. */
    static float d[W * H * 3], i[W * H * 3];
    frame(&t, &t.params, d, i);
    assert_int_equal(gi_active(renderer_gi(t.r)), gi_method_find("ilpv"));
    assert_non_null(gi_ilpv_lattice(gi_ilpv_of(renderer_gi(t.r))));
    gltest_close(&t);
}

/* Every method of the registry renders the room, live-switched in turn on one renderer,
 * with a checksum that repeats for a static frame; what it adds to the direct light is
 * finite and, but for "none", some light. */
static void test_every_registry_method(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    static float d[W * H * 3], i[W * H * 3];
    for (int m = 0; m < gi_method_count(); m++) {
        frame_params p = t.params;
        p.gi = m;
        gltest_setn(&p, "vpl-count", 64);
        uint64_t first = frame(&t, &p, d, i);
        assert_int_equal(gi_active(renderer_gi(t.r)), m);
        double light = sum(i);
        printf("%s: checksum %016llx, indirect %.4g\n", gi_method_at(m)->name,
               (unsigned long long)first, light);
        assert_true(isfinite(light));
        assert_true(strcmp(gi_method_at(m)->name, "none") == 0 ? light == 0 : light > 0);
        p.lambda_incr = 0; /* no history: the same frame again gives the same checksum */
        uint64_t a = frame(&t, &p, d, i), b = frame(&t, &p, d, i);
        assert_true(a == b);
    }
    gltest_close(&t);
}

/* A setting that rebuilds its method (the lattice) builds it fresh in that frame; one that
 * does not (vpl's count) keeps the method and takes effect. */
static void test_rebuild_settings(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    static float d[W * H * 3], i[W * H * 3];
    frame_params p = t.params;
    frame(&t, &p, d, i);
    assert_int_equal(gi_ilpv_lattice(gi_ilpv_of(renderer_gi(t.r)))->n[0], 20);
    gltest_setn(&p, "lattice", 12);
    frame(&t, &p, d, i);
    int longest = 0;
    for (int a = 0; a < 3; a++) {
        int n = gi_ilpv_lattice(gi_ilpv_of(renderer_gi(t.r)))->n[a];
        longest = n > longest ? n : longest;
    }
    assert_int_equal(longest, 12);
    gltest_set(&p, "gi", "vpl");
    gltest_setn(&p, "vpl-count", 64);
    uint64_t c64 = frame(&t, &p, d, i);
    const gi *before = renderer_gi(t.r);
    gltest_setn(&p, "vpl-count", 128);
    uint64_t c128 = frame(&t, &p, d, i);
    assert_true(renderer_gi(t.r) == before && c128 != c64);
    gltest_close(&t);
}

/* A cluster node's limits (gi_cost.h): a frame asking for a runaway lattice and steps is
 * rendered with the last settings within them, bit for bit, and says why once; settings
 * within the limits are taken again at once. */
static void test_limits_keep_the_last_settings(void **state)
{
    (void)state;
    gltest a;
    assert_int_equal(gltest_open(&a, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    gi_limits lim = {.base = a.params, .memory_mb = 2048};
    memcpy(lim.bounds_min, a.scene.bounds_min, sizeof lim.bounds_min);
    memcpy(lim.bounds_max, a.scene.bounds_max, sizeof lim.bounds_max);
    char err[512];
    gltest b = a; /* the same context and scene: a renderer without limits */
    renderer_desc rd = {.gl = glctx_gl(a.ctx), .scene = &a.scene, .first = &a.params, .limits = &lim};
    renderer_destroy(a.r);
    assert_non_null(a.r = renderer_create(&rd, err, sizeof err));
    rd.limits = NULL;
    assert_non_null(b.r = renderer_create(&rd, err, sizeof err));
    static float d[W * H * 3], ia[W * H * 3], ib[W * H * 3];
    frame_params runaway = a.params;
    gltest_setn(&runaway, "lattice", 128);
    gltest_setn(&runaway, "steps", 256);
    for (int f = 0; f < 3; f++) {
        uint64_t ca = frame(&a, f == 0 ? &a.params : &runaway, d, ia);
        uint64_t cb = frame(&b, &a.params, d, ib);
        assert_true(ca == cb);
        assert_memory_equal(ia, ib, sizeof ia);
    }
    assert_non_null(strstr(renderer_last_error(a.r), "frame settings refused: the ilpv settings would take"));
    const lattice_desc *lat = gi_ilpv_lattice(gi_ilpv_of(renderer_gi(a.r)));
    assert_true(lat->n[0] <= 20 && lat->n[1] <= 20 && lat->n[2] <= 20); /* never built */
    frame_params finer = a.params; /* within: taken */
    gltest_setn(&finer, "lattice", 32);
    frame(&a, &finer, d, ia);
    lat = gi_ilpv_lattice(gi_ilpv_of(renderer_gi(a.r)));
    assert_true(lat->n[0] == 32 || lat->n[1] == 32 || lat->n[2] == 32);
    renderer_destroy(b.r);
    gltest_close(&a);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_none_is_direct_only),
        cmocka_unit_test(test_switch_back_starts_afresh),
        cmocka_unit_test(test_created_with_none),
        cmocka_unit_test(test_every_registry_method),
        cmocka_unit_test(test_rebuild_settings),
        cmocka_unit_test(test_limits_keep_the_last_settings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
