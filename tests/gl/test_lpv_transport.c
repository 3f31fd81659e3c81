/* The ILPV method's two transports (--lpv-transport) in the renderer, default room:
 * - paper on GL agrees with paper on the CPU within 1e-4 of each channel's peak, over
 *   incremental frames with blocking, absorption, scattering and a changed light, and in
 *   classic mode;
 * - paper is not beams: their lattices differ by more than 10% (relative L1);
 * - classic paper ignores lambda_incr: bit-identical to incremental with lambda 0; paper
 *   is bit-identical for 1 and 2 CPU threads;
 * - the paper receiver is the thesis's (algorithm 3): between two floor points the indirect
 *   image's ratio is that of max(0, <SH_cos(-n)|L>) sampled trilinearly half a cell above
 *   the floor, computed here on the host from the method's lattice, within 1%. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"
#include "lpv_reference.h"
#include "gi/ilpv/sh.h"

enum { W = 128, H = 96 };

static void open_paper(gltest *t, ilpv_backend_choice backend, int threads, ilpv_mode mode,
                       lpv_transport transport)
{
    assert_int_equal(gltest_open_transport(t, GLCTX_EGL, backend, threads, ILPV_TILES_OFF,
                                           transport), 0);
    gltest_seti(&t->params, "lpv-mode", mode);
    gi_ilpv *l = gi_ilpv_of(renderer_gi(t->r));
    assert_non_null(l);
    assert_int_equal(gi_ilpv_transport(l), transport);
    assert_int_equal(gi_ilpv_backend(l), backend);
}

/* lpv-mode is a rebuilding setting: set it before the renderer is made. */
static void open_mode(gltest *t, ilpv_backend_choice backend, int threads, ilpv_mode mode,
                      lpv_transport transport)
{
    char err[512];
    open_paper(t, backend, threads, ILPV_MODE_INCREMENTAL, transport);
    if (mode == ILPV_MODE_INCREMENTAL)
        return;
    renderer_destroy(t->r);
    gltest_seti(&t->params, "lpv-mode", mode);
    renderer_desc rd = {.gl = glctx_gl(t->ctx), .scene = &t->scene, .first = &t->params,
                        .threads = threads};
    t->r = renderer_create(&rd, err, sizeof err);
    assert_non_null(t->r);
    assert_int_equal(gi_ilpv_mode(gi_ilpv_of(renderer_gi(t->r))), mode);
}

static uint64_t run_frames(gltest *t, int frames, float lambda)
{
    uint64_t sum = 0;
    t->params.lpv_steps = 4;
    t->params.lambda_incr = lambda;
    t->params.absorption = 0.05f;
    t->params.scattering = 0.1f;
    for (int f = 0; f < frames; f++) {
        if (f == 2)
            t->params.lights[0].intensity *= 1.5f; /* E changes: the merge's factor */
        sum = renderer_frame_pass(t->r, &t->params);
    }
    return sum;
}

static const lpv_volume *volume_of(gltest *t)
{
    return gi_ilpv_volume(gi_ilpv_of(renderer_gi(t->r)));
}

/* One renderer from open to close (a GL context is current from its creation on, so
 * renderers run one after another): the checksum of the last of `frames` frames, and the
 * lattice copied into out when out is not NULL. */
static uint64_t run_alone(ilpv_backend_choice backend, int threads, ilpv_mode mode,
                          lpv_transport transport, int frames, float lambda, lpv_volume *out)
{
    gltest t;
    open_mode(&t, backend, threads, mode, transport);
    uint64_t sum = run_frames(&t, frames, lambda);
    if (out) {
        const lpv_volume *v = volume_of(&t);
        assert_int_equal(lpv_volume_init(out, v->n, LPV_LIGHT_CHANNELS), 0);
        lpv_volume_copy(out, v);
    }
    gltest_close(&t);
    return sum;
}

static void gl_matches_cpu(ilpv_mode mode)
{
    lpv_volume a, b;
    run_alone(ILPV_BACKEND_CPU, 0, mode, LPV_TRANSPORT_PAPER, 4, 0.8f, &a);
    run_alone(ILPV_BACKEND_GL, 0, mode, LPV_TRANSPORT_PAPER, 4, 0.8f, &b);
    assert_int_equal(lpv_volume_count_nonfinite(&b), 0);
    double e[3];
    lpv_volume_energy(&a, e);
    double worst = lpv_reference_rel_diff(&b, &a);
    printf("paper %s: GL against CPU, worst channel %.3g of its peak (energy %.4g)\n",
           mode == ILPV_MODE_CLASSIC ? "classic" : "incremental", worst, e[0]);
    assert_true(e[0] > 0);
    assert_true(worst < 1e-4);
    lpv_volume_free(&a);
    lpv_volume_free(&b);
}

static void test_paper_gl_matches_cpu(void **state)
{
    (void)state;
    gl_matches_cpu(ILPV_MODE_INCREMENTAL);
    gl_matches_cpu(ILPV_MODE_CLASSIC);
}

static void test_paper_is_not_beams(void **state)
{
    (void)state;
    lpv_volume a, v;
    uint64_t cp = run_alone(ILPV_BACKEND_CPU, 0, ILPV_MODE_INCREMENTAL, LPV_TRANSPORT_PAPER, 3, 0.8f, &a);
    uint64_t cb = run_alone(ILPV_BACKEND_CPU, 0, ILPV_MODE_INCREMENTAL, LPV_TRANSPORT_BEAMS, 3, 0.8f, &v);
    double diff = 0, total = 0;
    for (int c = 0; c < LPV_LIGHT_CHANNELS; c++)
        for (size_t i = 0; i < a.cells; i++) {
            diff += fabs((double)a.ch[c][i] - v.ch[c][i]);
            total += fabs((double)v.ch[c][i]);
        }
    printf("paper against beams: relative L1 difference %.3f\n", diff / total);
    assert_true(cp != cb);
    assert_true(diff > 0.1 * total);
    lpv_volume_free(&a);
    lpv_volume_free(&v);
}

static void test_paper_classic_and_threads(void **state)
{
    (void)state;
    const ilpv_backend_choice cpu = ILPV_BACKEND_CPU;
    const ilpv_mode inc = ILPV_MODE_INCREMENTAL;
    assert_true(run_alone(cpu, 2, inc, LPV_TRANSPORT_PAPER, 3, 0.0f, NULL) ==
                run_alone(cpu, 2, ILPV_MODE_CLASSIC, LPV_TRANSPORT_PAPER, 3, 0.8f, NULL));
    uint64_t c1 = run_alone(cpu, 1, inc, LPV_TRANSPORT_PAPER, 3, 0.8f, NULL);
    assert_true(c1 == run_alone(cpu, 2, inc, LPV_TRANSPORT_PAPER, 3, 0.8f, NULL));
    /* lambda 0.8 kept history: not the plain frame */
    assert_true(c1 != run_alone(cpu, 1, inc, LPV_TRANSPORT_PAPER, 3, 0.0f, NULL));
}

/* The thesis's receiver on the host: one colour's max(0, <SH_cos(-n)|L>) at p + n cell/2,
 * trilinear over the 8 cells around it (clamped to the lattice). */
static double paper_receiver(const lpv_volume *v, const lattice_desc *lat, const float p[3],
                             const float n[3], int colour)
{
    float lobe[4], minus[3] = {-n[0], -n[1], -n[2]};
    sh_cosine_lobe(minus, lobe);
    double q[3], f[3];
    int i0[3];
    for (int k = 0; k < 3; k++) {
        q[k] = (p[k] + 0.5 * lat->cell * n[k] - lat->origin[k]) / lat->cell - 0.5;
        i0[k] = (int)floor(q[k]);
        f[k] = q[k] - i0[k];
    }
    double e = 0;
    for (int k = 0; k < 8; k++) {
        int o[3] = {k & 1, (k >> 1) & 1, (k >> 2) & 1}, c[3];
        double w = 1;
        for (int a = 0; a < 3; a++) {
            w *= o[a] ? f[a] : 1 - f[a];
            c[a] = i0[a] + o[a];
            c[a] = c[a] < 0 ? 0 : c[a] >= lat->n[a] ? lat->n[a] - 1 : c[a];
        }
        size_t i = ((size_t)c[2] * lat->n[1] + c[1]) * lat->n[0] + c[0];
        double dot = 0;
        for (int s = 0; s < 4; s++)
            dot += lobe[s] * v->ch[4 * colour + s][i];
        e += w * dot;
    }
    return e > 0 ? e : 0;
}

/* The point of the plane y = p[1] whose projection is the centre of pixel (px, py):
 * Newton steps from p, the Jacobian by differences. */
static void plane_point_at(const renderer_view *v, int px, int py, float p[3])
{
    for (int it = 0; it < 6; it++) {
        float a[2], bx[2], bz[2], qx[3] = {p[0] + 1e-3f, p[1], p[2]}, qz[3] = {p[0], p[1], p[2] + 1e-3f};
        gltest_project(v, p, a);
        gltest_project(v, qx, bx);
        gltest_project(v, qz, bz);
        double j00 = (bx[0] - a[0]) / 1e-3, j10 = (bx[1] - a[1]) / 1e-3;
        double j01 = (bz[0] - a[0]) / 1e-3, j11 = (bz[1] - a[1]) / 1e-3;
        double rx = px + 0.5 - a[0], ry = py + 0.5 - a[1], det = j00 * j11 - j01 * j10;
        p[0] += (float)((j11 * rx - j01 * ry) / det);
        p[2] += (float)((j00 * ry - j10 * rx) / det);
    }
}

/* The floor (white, y = 0, a cell face of the lattice) and the low yellow box's top
 * (y = 0.5, inside a cell layer), seen from above (scene_default.c): the image's indirect
 * light over the albedo, relative between the two, against the host's receiver. */
static void test_paper_receiver(void **state)
{
    (void)state;
    gltest t;
    open_mode(&t, ILPV_BACKEND_CPU, 0, ILPV_MODE_INCREMENTAL, LPV_TRANSPORT_PAPER);
    renderer_view v;
    const float eye[3] = {0.0f, 2.9f, 0.0f}, target[3] = {0.0f, 0.0f, 0.0f};
    gltest_look_at(&v, eye, target, 1.5f, W, H);
    run_frames(&t, 4, 0.8f);
    renderer_image img;
    assert_int_equal(renderer_eye_pass(t.r, &v, 1, &img), 0);
    const gi_ilpv *l = gi_ilpv_of(renderer_gi(t.r));
    const float up[3] = {0, 1, 0};
    float p[2][3] = {{0.9f, 0.0f, 0.9f}, {-0.3f, 0.5f, 0.5f}};
    const int material[2] = {0, 4};
    double seen[2][3], want[2][3];
    for (int k = 0; k < 2; k++) {
        float px[2];
        gltest_project(&v, p[k], px);
        plane_point_at(&v, (int)px[0], (int)px[1], p[k]);
        float o[3] = {eye[0], eye[1], eye[2]}, d[3] = {p[k][0] - eye[0], p[k][1] - eye[1], p[k][2] - eye[2]};
        float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int a = 0; a < 3; a++)
            d[a] /= len;
        assert_true(fabsf(gltest_cast(&t.scene, o, d) - len) < 1e-3f * len); /* that surface */
        gltest_window_mean(img.indirect, W, H, (int)px[0], (int)px[1], 0, seen[k]);
        for (int c = 0; c < 3; c++) {
            seen[k][c] /= t.scene.materials[material[k]].base_color[c];
            want[k][c] = paper_receiver(gi_ilpv_volume(l), gi_ilpv_lattice(l), p[k], up, c);
        }
    }
    for (int c = 0; c < 3; c++) {
        double rs = seen[1][c] / seen[0][c], rw = want[1][c] / want[0][c];
        printf("colour %d: indirect / albedo, box top over floor %.4f, the thesis's receiver "
               "%.4f\n", c, rs, rw);
        assert_true(seen[0][c] > 0 && want[0][c] > 0);
        assert_true(fabs(rs / rw - 1) < 0.01);
    }
    gltest_close(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paper_gl_matches_cpu),
        cmocka_unit_test(test_paper_is_not_beams),
        cmocka_unit_test(test_paper_classic_and_threads),
        cmocka_unit_test(test_paper_receiver),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
