/* The Embree reference (node/reference/reference.h): direct light and textures equal to the
 * rasterizer's, two closed-form checks (a furnace box and one spot bounce integrated
 * independently), noise that halves with 4x the samples, determinism, and bad input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "gl/gl_testutil.h"
#include "reference/reference.h"

static const double PI = 3.14159265358979323846;

static double image_mean(const float *v, int w, int h)
{
    double s = 0;
    for (size_t i = 0; i < (size_t)w * h * 3; i++)
        s += v[i];
    return s / ((double)w * h * 3);
}

static double image_mad(const float *a, const float *b, int w, int h)
{
    double s = 0;
    for (size_t i = 0; i < (size_t)w * h * 3; i++)
        s += fabs((double)a[i] - b[i]);
    return s / ((double)w * h * 3);
}

/* Mean |raster - reference| of the direct images relative to the mean: over the pixels
 * away from a strong change in either image (shadow, cone and geometry edges, where PCF
 * and one-sample rasterization differ) in rel, over all pixels in rel_all. */
static void direct_difference(gltest *t, reference *ref, const renderer_view *v, double *rel,
                              double *rel_all, double *kept_share)
{
    const int W = v->width, H = v->height;
    renderer_frame_pass(t->r, &t->params);
    renderer_image img;
    assert_int_equal(renderer_eye_pass(t->r, v, 1, &img), 0);
    char err[256];
    reference_render_desc rd = {.params = &t->params, .view = v, .samples = 1, .max_bounces = 1};
    reference_images out;
    assert_int_equal(reference_render(ref, &rd, &out, err, sizeof err), 0);
    const float *a = img.direct, *b = out.direct;
    double sum_all = 0, sum = 0, mean = image_mean(b, W, H);
    size_t kept = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = ((size_t)y * W + x) * 3;
            double d = 0;
            for (int c = 0; c < 3; c++)
                d += fabs((double)a[i + c] - b[i + c]) / 3;
            sum_all += d;
            int edge = 0;
            for (int dy = -2; dy <= 2 && !edge; dy++)
                for (int dx = -2; dx <= 2 && !edge; dx++) {
                    int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= W || ny >= H)
                        continue;
                    size_t j = ((size_t)ny * W + nx) * 3;
                    for (int c = 0; c < 3; c++) {
                        double lim = 0.15 * fmax(fabs(b[i + c]), 0.1 * mean);
                        edge |= fabs((double)a[j + c] - a[i + c]) > lim ||
                                fabs((double)b[j + c] - b[i + c]) > lim;
                    }
                }
            if (!edge) {
                sum += d;
                kept++;
            }
        }
    *rel = sum / (double)(kept ? kept : 1) / mean;
    *rel_all = sum_all / ((double)W * H) / mean;
    *kept_share = (double)kept / ((double)W * H);
    printf("direct: mean %.4f, |raster - reference| %.3f%% of it on %.0f%% of the pixels "
           "(%.3f%% over all)\n", mean, 100 * *rel, 100 * *kept_share, 100 * *rel_all);
    reference_images_free(&out);
}

/* The rasterizer's direct image (3x3 PCF shadows) against the reference's (exact shadow
 * rays) in the default room, from its camera and through an off-axis screen (the back
 * wall). Measured on llvmpipe: camera 0.073% on the 76% of pixels away from edges, 0.35%
 * over all; screen 0.019% on 88%, 0.024% over all (0.12%, 0.49%, 0.24%, 0.28% with the
 * former constant depth bias, which also let zero-thickness walls leak). */
static void test_direct_matches_rasterizer(void **state)
{
    (void)state;
    gltest t;
    assert_int_equal(gltest_open(&t, GLCTX_EGL, ILPV_BACKEND_CPU, 0), 0);
    char err[256];
    reference *ref = reference_create(&t.scene, 0, err, sizeof err);
    assert_non_null(ref);
    renderer_view v;
    gltest_look_at(&v, t.scene.camera.position, t.scene.camera.target, t.scene.camera.yfov, 128, 96);
    double rel, rel_all, kept;
    direct_difference(&t, ref, &v, &rel, &rel_all, &kept);
    assert_true(kept > 0.5 && rel < 0.005 && rel_all < 0.02);

    offaxis_screen_desc sd = {.bottom_left = {-2, 0, -2}, .bottom_right = {2, 0, -2},
                              .top_left = {-2, 3, -2}, .eye = {0.3f, 1.6f, 1.5f},
                              .near_plane = 0.02f, .far_plane = 50.0f};
    memcpy(v.eye_position, sd.eye, sizeof sd.eye);
    assert_int_equal(offaxis_screen(&sd, v.view, v.projection), 0);
    direct_difference(&t, ref, &v, &rel, &rel_all, &kept);
    assert_true(kept > 0.5 && rel < 0.005 && rel_all < 0.02);
    reference_destroy(ref);
    gltest_close(&t);
}

/* A floor with a 4x4 sRGB texture magnified across it, uvs from -1 to 2 (wrap repeat),
 * lit by a wide spot: the reference's bilinear level-0 sampling of the decoded texture
 * gives the rasterizer's direct image. Measured on llvmpipe: 0.24% over all pixels (the
 * texel ramps leave few pixels "away from edges", so the bound is on all of them). */
static void test_texture_matches_rasterizer(void **state)
{
    (void)state;
    gltest t;
    memset(&t, 0, sizeof t);
    char err[512];
    glctx_desc gd = {.backend = GLCTX_EGL};
    assert_non_null(t.ctx = glctx_create(&gd, err, sizeof err));
    uint8_t *rgba = malloc(4 * 4 * 4);
    assert_non_null(rgba);
    for (int i = 0; i < 16; i++) {
        const uint8_t c[4][3] = {{250, 40, 30}, {20, 200, 60}, {40, 60, 230}, {240, 240, 240}};
        memcpy(rgba + 4 * i, c[(i + i / 4) % 4], 3);
        rgba[4 * i + 3] = 255;
    }
    assert_int_equal(scene_add_texture(&t.scene, 4, 4, rgba), 0);
    scene_material m = {{0.9f, 0.8f, 1.0f, 1}, 0, {0, 0, 0}, 0.7f};
    assert_int_equal(scene_add_material(&t.scene, &m), 0);
    const float p1[9] = {-2, 0, -2, -2, 0, 2, 2, 0, 2}, p2[9] = {-2, 0, -2, 2, 0, 2, 2, 0, -2};
    const float uv1[6] = {-1, -1, -1, 2, 2, 2}, uv2[6] = {-1, -1, 2, 2, 2, -1};
    assert_true(scene_add_triangle(&t.scene, p1, NULL, uv1, 0) >= 0);
    assert_true(scene_add_triangle(&t.scene, p2, NULL, uv2, 0) >= 0);
    assert_int_equal(scene_finish(&t.scene, err, sizeof err), 0);
    frame_params_default(&t.params);
    t.params.light_count = 1;
    t.params.lights[0] = (frame_light){.enabled = 1, .position = {0.3f, 3, 0.2f},
                                       .direction = {0, -1, 0}, .color = {1, 1, 1},
                                       .intensity = 20, .outer_angle = 1.2f, .inner_angle = 1.0f};
    gltest_setn(&t.params, "rsm", 64);
    gltest_setn(&t.params, "lattice", 8);
    gltest_set(&t.params, "lpv", "cpu");
    renderer_desc rd = {.gl = glctx_gl(t.ctx), .scene = &t.scene, .first = &t.params};
    assert_non_null(t.r = renderer_create(&rd, err, sizeof err));
    reference *ref = reference_create(&t.scene, 0, err, sizeof err);
    assert_non_null(ref);
    renderer_view v;
    const float eye[3] = {0, 3, 1.5f}, target[3] = {0, 0, 0};
    gltest_look_at(&v, eye, target, 1.0f, 96, 72);
    double rel, rel_all, kept;
    direct_difference(&t, ref, &v, &rel, &rel_all, &kept);
    assert_true(rel_all < 0.01);
    reference_destroy(ref);
    gltest_close(&t);
}

/* Closed box of albedo a whose inner faces all emit L: radiance L a^k arrives after k
 * reflections. Seen from inside: direct = L, indirect1 = a L (emitters -> visible point),
 * indirect = L (a + ... + a^(B+1)) with B bounces. Measured at 256 paths per pixel:
 * -0.06% and +0.4%; without the MIS weights the emitter light would count twice. */
static void test_furnace_box(void **state)
{
    (void)state;
    enum { W = 24, H = 18, BOUNCES = 8 };
    const float albedo = 0.5f, radiance = 2.0f;
    scene s;
    memset(&s, 0, sizeof s);
    char err[256];
    scene_material m = {{albedo, albedo, albedo, 1}, -1, {radiance, radiance, radiance}, 1.0f};
    const float lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    assert_int_equal(scene_add_material(&s, &m), 0);
    assert_int_equal(scene_add_box(&s, lo, hi, 1, 0), 0);
    assert_int_equal(scene_finish(&s, err, sizeof err), 0);
    frame_params p;
    frame_params_default(&p); /* no spots */
    renderer_view v;
    const float eye[3] = {0.2f, -0.1f, 0.3f}, target[3] = {-0.5f, 0.3f, -1.0f};
    gltest_look_at(&v, eye, target, 1.5f, W, H);
    reference *ref = reference_create(&s, 0, err, sizeof err);
    assert_non_null(ref);
    reference_render_desc rd = {.params = &p, .view = &v, .samples = 256, .max_bounces = BOUNCES,
                                .seed = 7};
    reference_images out;
    assert_int_equal(reference_render(ref, &rd, &out, err, sizeof err), 0);
    double want_n = 0, ak = 1;
    for (int k = 1; k <= BOUNCES + 1; k++)
        want_n += radiance * (ak *= albedo);
    double d = image_mean(out.direct, W, H), i1 = image_mean(out.indirect1, W, H),
           in = image_mean(out.indirect, W, H);
    printf("furnace: direct %.4f (want %.4f), indirect1 %.4f (want %.4f), indirect %.4f "
           "(want %.4f)\n", d, radiance, i1, albedo * radiance, in, want_n);
    assert_float_equal(d, radiance, 1e-5);
    assert_float_equal(i1, albedo * radiance, 0.01 * albedo * radiance);
    assert_float_equal(in, want_n, 0.015 * want_n);
    reference_images_free(&out);
    reference_destroy(ref);
    scene_free(&s);
}

static void add_quad(scene *s, const float a[3], const float b[3], const float c[3],
                     const float d[3], uint32_t mat)
{
    float t1[9], t2[9];
    memcpy(t1, a, 12); memcpy(t1 + 3, b, 12); memcpy(t1 + 6, c, 12);
    memcpy(t2, a, 12); memcpy(t2 + 3, c, 12); memcpy(t2 + 6, d, 12);
    assert_true(scene_add_triangle(s, t1, NULL, NULL, mat) >= 0);
    assert_true(scene_add_triangle(s, t2, NULL, NULL, mat) >= 0);
}

/* A spot straight down onto a floor (z >= -1) that meets a wall (z = -1) the spot does not
 * reach, in an absorbing medium. The one-bounce light at a wall point is the floor's
 * reflected spot light integrated over the floor (midpoint rule, written out here):
 *   a_w/pi * int a_f/pi * I spot cos_l / r^2 T(r) * cos_y cos_x / d^2 T(d) dA. */
static void test_one_bounce_closed_form(void **state)
{
    (void)state;
    const float a_floor = 0.8f, a_wall = 0.6f, sigma = 0.1f, intensity = 10.0f;
    const float lpos[3] = {0.0f, 3.0f, 1.5f}, outer = 0.5f, inner = 0.35f;
    const double x0[3] = {0.0, 1.0, -1.0};
    scene s;
    memset(&s, 0, sizeof s);
    char err[256];
    scene_material mf = {{a_floor, a_floor, a_floor, 1}, -1, {0, 0, 0}, 1.0f};
    scene_material mw = {{a_wall, a_wall, a_wall, 1}, -1, {0, 0, 0}, 1.0f};
    assert_int_equal(scene_add_material(&s, &mf), 0);
    assert_int_equal(scene_add_material(&s, &mw), 1);
    const float f0[3] = {-8, 0, -1}, f1[3] = {-8, 0, 8}, f2[3] = {8, 0, 8}, f3[3] = {8, 0, -1};
    const float w0[3] = {-8, 0, -1}, w1[3] = {8, 0, -1}, w2[3] = {8, 5, -1}, w3[3] = {-8, 5, -1};
    add_quad(&s, f0, f1, f2, f3, 0);
    add_quad(&s, w0, w1, w2, w3, 1);
    assert_int_equal(scene_finish(&s, err, sizeof err), 0);

    frame_params p;
    frame_params_default(&p);
    p.absorption = sigma;
    p.light_count = 1;
    p.lights[0] = (frame_light){.enabled = 1, .position = {lpos[0], lpos[1], lpos[2]},
                                .direction = {0, -1, 0}, .color = {1, 1, 1},
                                .intensity = intensity, .outer_angle = outer,
                                .inner_angle = inner};
    double co = cos(outer), ci = cos(inner), want = 0;
    const int N = 600;
    const double R = lpos[1] * tan(outer) + 0.01, cell = 2 * R / N;
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            double y[3] = {lpos[0] - R + (i + 0.5) * cell, 0, lpos[2] - R + (j + 0.5) * cell};
            double l[3] = {lpos[0] - y[0], lpos[1] - y[1], lpos[2] - y[2]};
            double r = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
            double cos_l = l[1] / r; /* = cos at the floor and cos to the spot axis */
            double spot = fmin(fmax((cos_l - co) / (ci - co), 0), 1);
            if (spot <= 0)
                continue;
            double e = intensity * spot * cos_l / (r * r) * pow(1 - sigma, r);
            double dv[3] = {x0[0] - y[0], x0[1] - y[1], x0[2] - y[2]};
            double d = sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]);
            double cos_y = dv[1] / d, cos_x = -dv[2] / d;
            want += a_floor / PI * e * cos_y * cos_x / (d * d) * pow(1 - sigma, d) * cell * cell;
        }
    want *= a_wall / PI;

    /* A 4x4 image covering a few millimetres around x0. */
    renderer_view v;
    const float eye[3] = {0.0f, 1.0f, 2.0f}, target[3] = {0.0f, 1.0f, -1.0f};
    gltest_look_at(&v, eye, target, 0.002f, 4, 4);
    reference *ref = reference_create(&s, 0, err, sizeof err);
    assert_non_null(ref);
    reference_render_desc rd = {.params = &p, .view = &v, .samples = 4096, .max_bounces = 1,
                                .seed = 3};
    reference_images out;
    assert_int_equal(reference_render(ref, &rd, &out, err, sizeof err), 0);
    double got = image_mean(out.indirect1, 4, 4), direct = image_mean(out.direct, 4, 4);
    printf("one bounce at the wall: reference %.6f, integral %.6f (%.2f%%), direct %.3g\n", got,
           want, 100 * (got / want - 1), direct);
    assert_true(want > 1e-3);
    assert_float_equal(got, want, 0.03 * want);
    assert_float_equal(direct, 0, 1e-9);
    reference_images_free(&out);
    reference_destroy(ref);
    scene_free(&s);
}

typedef struct room {
    scene s;
    frame_params p;
    renderer_view v;
    reference *ref;
} room;

static void room_open(room *r, int w, int h, int threads)
{
    char err[256];
    assert_int_equal(scene_load("default", &r->s, err, sizeof err), 0);
    frame_params_default(&r->p);
    frame_params_lights_from_scene(&r->p, &r->s);
    gltest_look_at(&r->v, r->s.camera.position, r->s.camera.target, r->s.camera.yfov, w, h);
    r->ref = reference_create(&r->s, threads, err, sizeof err);
    assert_non_null(r->ref);
}

static void room_close(room *r)
{
    reference_destroy(r->ref);
    scene_free(&r->s);
}

static void render(room *r, int samples, uint64_t seed, reference_images *out)
{
    char err[256];
    reference_render_desc rd = {.params = &r->p, .view = &r->v, .samples = samples, .seed = seed};
    assert_int_equal(reference_render(r->ref, &rd, out, err, sizeof err), 0);
}

/* Coverage: every pixel of the closed default room meets geometry; in the open-top
 * courtyard, looking up, the sky's pixels do not, and they are black in all three
 * images. */
static void test_coverage(void **state)
{
    (void)state;
    enum { W = 40, H = 30 };
    room r;
    room_open(&r, W, H, 0);
    reference_images img;
    render(&r, 1, 1, &img);
    size_t covered = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        covered += img.coverage[i] == 1;
    assert_int_equal(covered, W * H);
    reference_images_free(&img);
    assert_null(img.coverage);
    room_close(&r);

    char err[256];
    assert_int_equal(scene_load("courtyard", &r.s, err, sizeof err), 0);
    frame_params_default(&r.p);
    frame_params_lights_from_scene(&r.p, &r.s);
    const float eye[3] = {0, 1.5f, 2.5f}, up[3] = {0, 9, -2.5f};
    gltest_look_at(&r.v, eye, up, 1.2f, W, H);
    r.ref = reference_create(&r.s, 0, err, sizeof err);
    assert_non_null(r.ref);
    render(&r, 4, 1, &img);
    covered = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        double sum = 0;
        for (int c = 0; c < 3; c++)
            sum += img.direct[3 * i + c] + img.indirect1[3 * i + c] + img.indirect[3 * i + c];
        assert_true(img.coverage[i] <= 1);
        assert_true(img.coverage[i] || sum == 0);
        covered += img.coverage[i];
    }
    printf("coverage: courtyard looking up, %zu of %d pixels meet geometry\n", covered, W * H);
    assert_true(covered > W * H / 4 && covered < W * H * 3 / 4);
    reference_images_free(&img);
    room_close(&r);
}

/* Two independent halves differ by about 1/sqrt(samples): 4x the samples halves it. */
static void test_noise_falls_with_samples(void **state)
{
    (void)state;
    enum { W = 40, H = 30 };
    room r;
    room_open(&r, W, H, 0);
    double mad[2];
    for (int k = 0; k < 2; k++) {
        reference_images a, b;
        render(&r, k ? 32 : 8, 11, &a);
        render(&r, k ? 32 : 8, 12, &b);
        mad[k] = image_mad(a.indirect, b.indirect, W, H);
        reference_images_free(&a);
        reference_images_free(&b);
    }
    printf("|A - B| indirect: %.5f at 8 spp, %.5f at 32 spp (ratio %.3f)\n", mad[0], mad[1],
           mad[1] / mad[0]);
    assert_true(mad[1] / mad[0] > 0.4 && mad[1] / mad[0] < 0.62);
    room_close(&r);
}

/* Same seed: identical bits, whatever the thread count; another seed: different noise.
 * Indirect >= indirect1 on average (a superset of paths). */
static void test_deterministic_and_ordered(void **state)
{
    (void)state;
    enum { W = 32, H = 24 };
    room r, one;
    room_open(&r, W, H, 0);
    room_open(&one, W, H, 1);
    reference_images a, b, c;
    render(&r, 4, 5, &a);
    render(&one, 4, 5, &b);
    render(&r, 4, 6, &c);
    size_t bytes = (size_t)W * H * 3 * sizeof(float);
    assert_memory_equal(a.direct, b.direct, bytes);
    assert_memory_equal(a.indirect1, b.indirect1, bytes);
    assert_memory_equal(a.indirect, b.indirect, bytes);
    assert_memory_equal(a.direct, c.direct, bytes); /* exact, no sampling */
    assert_true(image_mad(a.indirect, c.indirect, W, H) > 0);
    assert_true(image_mad(a.indirect1, c.indirect1, W, H) > 0);
    double m1 = image_mean(a.indirect1, W, H), mn = image_mean(a.indirect, W, H);
    printf("means: indirect1 %.4f, indirect %.4f; %llu rays\n", m1, mn,
           (unsigned long long)a.rays);
    assert_true(m1 > 0 && mn > 1.2 * m1);
    reference_images_free(&a);
    reference_images_free(&b);
    reference_images_free(&c);
    room_close(&one);
    room_close(&r);
}

/* An empty view or a NaN light: an error line, no images, no crash. */
static void test_bad_input(void **state)
{
    (void)state;
    room r;
    room_open(&r, 8, 6, 0);
    char err[256] = "";
    reference_images out;
    r.v.width = 0;
    r.v.height = 0;
    reference_render_desc rd = {.params = &r.p, .view = &r.v, .samples = 1};
    assert_int_equal(reference_render(r.ref, &rd, &out, err, sizeof err), -1);
    assert_null(out.direct);
    printf("0x0: %s\n", err);
    r.v.width = 8;
    r.v.height = 6;
    r.p.lights[0].position[1] = NAN;
    assert_int_equal(reference_render(r.ref, &rd, &out, err, sizeof err), -1);
    printf("NaN light: %s\n", err);
    assert_non_null(strstr(err, "light 0"));
    r.p.lights[0].position[1] = 2.0f;
    r.p.lights[0].intensity = NAN;
    assert_int_equal(reference_render(r.ref, &rd, &out, err, sizeof err), -1);
    room_close(&r);
    scene empty;
    memset(&empty, 0, sizeof empty);
    assert_null(reference_create(&empty, 0, err, sizeof err));
    printf("empty scene: %s\n", err);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_direct_matches_rasterizer),
        cmocka_unit_test(test_texture_matches_rasterizer),
        cmocka_unit_test(test_furnace_box),
        cmocka_unit_test(test_one_bounce_closed_form),
        cmocka_unit_test(test_noise_falls_with_samples),
        cmocka_unit_test(test_coverage),
        cmocka_unit_test(test_deterministic_and_ordered),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
