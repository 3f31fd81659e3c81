/* Layered depth maps on llvmpipe (node/gi/ldm/ldm_gl.h): the GL build of the default room gives
 * the CPU oracle's lists (common/gi/ldm/ldm_cpu.h) texel for texel, the same on a second
 * build (the atomic insertion does not depend on the order fragments arrive in), with the
 * same overflow count when the lists are too short. Ambient occlusion (renderer_ao.h,
 * frame/ao.h) of points on a floor beside a wall, the wall far larger than the distance
 * limit (an infinite wall to them): the LDM AO and the path tracer's AO against the
 * closed form, for occlusion and obscurance; the screen-space baseline for comparison. */
#include "reference/reference.h"
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>

#include "gl/gl_testutil.h"
#include "gi/ldm/ldm_cpu.h"
#include "gi/ldm/ldm_gl.h"

typedef struct fixture {
    glctx *ctx;
    scene s;
} fixture;

static void open_room(fixture *f)
{
    char err[256];
    memset(f, 0, sizeof *f);
    glctx_desc gd = {.backend = GLCTX_EGL};
    f->ctx = glctx_create(&gd, err, sizeof err);
    if (!f->ctx)
        fprintf(stderr, "%s\n", err);
    assert_non_null(f->ctx);
    assert_int_equal(scene_load("default", &f->s, err, sizeof err), 0);
}

static void close_room(fixture *f)
{
    scene_free(&f->s);
    glctx_destroy(f->ctx);
}

/* Texels whose lists differ between the GL and the CPU (a depth off by more than tol, or
 * a different count), over all maps. */
static size_t compare(const ldm_cpu *c, const uint32_t *gl, float tol, size_t *filled)
{
    const ldm_layout *l = &c->layout;
    size_t texels = (size_t)l->directions * l->resolution * l->resolution, differ = 0;
    *filled = 0;
    for (size_t i = 0; i < texels; i++) {
        const uint32_t *a = c->depth + i * l->layers, *b = gl + i * l->layers;
        int same = 1;
        for (int k = 0; k < l->layers && same; k++) {
            if ((a[k] == LDM_EMPTY) != (b[k] == LDM_EMPTY)) {
                same = 0;
                break;
            }
            if (a[k] == LDM_EMPTY)
                break;
            float x, y;
            memcpy(&x, &a[k], 4);
            memcpy(&y, &b[k], 4);
            same = fabsf(x - y) <= tol;
        }
        *filled += a[0] != LDM_EMPTY;
        differ += !same;
    }
    return differ;
}

static void build_and_compare(int layers, double allowed)
{
    fixture f;
    open_room(&f);
    char err[256];
    ldm_layout l;
    ldm_layout_init(&l, &f.s, 16, 48, layers);
    ldm_cpu c;
    assert_int_equal(ldm_cpu_build(&f.s, &l, &c), 0);
    scene_gl *mesh = scene_gl_create(glctx_gl(f.ctx), &f.s, err, sizeof err);
    ldm_gl *m = mesh ? ldm_gl_create(glctx_gl(f.ctx), &l, err, sizeof err) : NULL;
    if (!m)
        fprintf(stderr, "%s\n", err);
    assert_non_null(m);
    double ms = ldm_gl_build(m, mesh);
    size_t words = (size_t)(ldm_memory_bytes(&l) / 4);
    uint32_t *gl = malloc(words * 4);
    ldm_gl_read(m, gl);
    size_t filled, differ = compare(&c, gl, 1e-5f * l.radius, &filled);
    printf("%d layers: %zu of %zu covered texels differ (%.3f%%), overflow GL %zu CPU %zu, "
           "build %.1f ms\n", layers, differ, filled, 100.0 * differ / filled,
           ldm_gl_overflow(m), c.overflow, ms);
    assert_true(filled > 1000);
    assert_true(differ <= allowed * filled);
    /* Overflow: only texels on a triangle edge may count otherwise (a centre exactly on it). */
    assert_true(labs((long)ldm_gl_overflow(m) - (long)c.overflow) <= (long)(allowed * filled) + 2);
    uint64_t first = ldm_gl_checksum(m);
    ldm_gl_build(m, mesh);
    assert_true(ldm_gl_checksum(m) == first);
    free(gl);
    ldm_gl_destroy(m);
    scene_gl_destroy(mesh);
    ldm_cpu_free(&c);
    close_room(&f);
}

static void test_gl_build_matches_cpu(void **state)
{
    (void)state;
    build_and_compare(12, 0.001);
}

static void test_short_lists_overflow_alike(void **state)
{
    (void)state;
    build_and_compare(2, 0.001);
}

static const double PI = 3.14159265358979323846;

/* A floor point at distance h from an infinite wall, distance limit D: the cosine-weighted
 * directions (uniform on the unit disk below them) toward the wall meet it at h / x, x
 * the disk coordinate towards it. Occlusion hides x > c = h / D: AO = 1 - (acos c -
 * c sqrt(1 - c^2)) / pi. Obscurance hides by 1 - h / (x D) there: AO = 1 - 2/pi integral
 * from c to 1 of sqrt(1 - x^2) (1 - c / x) dx, with integral sqrt(1 - x^2) / x dx =
 * sqrt(1 - x^2) - ln((1 + sqrt(1 - x^2)) / x). */
static double wall_ao(double h, double D, int obscurance)
{
    double c = h / D;
    if (c >= 1)
        return 1.0;
    double r = sqrt(1 - c * c), segment = acos(c) - c * r; /* 2 integral sqrt(1 - x^2) */
    if (!obscurance)
        return 1.0 - segment / PI;
    double log_part = -(r - log((1 + r) / c)); /* integral from c to 1 of sqrt(1-x^2)/x */
    return 1.0 - (segment - 2.0 * c * log_part) / PI;
}

enum { AW = 96, AH = 72, SPOTS = 6 };

/* The floor and the wall (x = 0, facing -x), a 1 m distance limit: AO at points x = -h. */
static void test_ao_beside_wall(void **state)
{
    (void)state;
    scene s;
    char err[256];
    memset(&s, 0, sizeof s);
    static const scene_material white = {{0.7f, 0.7f, 0.7f, 1}, -1, {0, 0, 0}, 1};
    scene_add_material(&s, &white);
    const float flo[3] = {-2.0f, 0, -1.5f}, fhi[3] = {0, 0, 1.5f};
    const float wlo[3] = {0, 0, -1.5f}, whi[3] = {0, 1.5f, 1.5f};
    assert_int_equal(scene_add_rect(&s, flo, fhi, 1, 0), 0);
    assert_int_equal(scene_add_rect(&s, wlo, whi, -1, 0), 0);
    assert_int_equal(scene_finish(&s, err, sizeof err), 0);
    glctx_desc gd = {.backend = GLCTX_EGL};
    glctx *ctx = glctx_create(&gd, err, sizeof err);
    assert_non_null(ctx);
    reference *ref = reference_create(&s, 2, err, sizeof err);
    assert_non_null(ref);
    renderer_view v;
    const float eye[3] = {-0.5f, 1.6f, 0.0f}, target[3] = {-0.5f, 0.0f, 0.0f};
    gltest_look_at(&v, eye, target, 1.2f, AW, AH);
    const double hs[SPOTS] = {0.1, 0.2, 0.35, 0.5, 0.7, 0.9};
    const char *modes[3] = {"ldm", "ssao", NULL};
    for (int fall = 0; fall < 2; fall++) {
        frame_params p;
        frame_params_default(&p);
        gltest_set(&p, "gi", "none");
        gltest_set(&p, "ao-directions", "128");
        gltest_set(&p, "ao-resolution", "128");
        gltest_set(&p, "ao-distance", "1");
        gltest_set(&p, "ao-falloff", fall ? "obscurance" : "occlusion");
        double worst[3] = {0, 0, 0};
        for (int mode = 0; mode < 3; mode++) {
            static float ao[AW * AH * 3];
            if (modes[mode]) {
                gltest_set(&p, "ao", modes[mode]);
                renderer_desc rd = {.gl = glctx_gl(ctx), .scene = &s, .first = &p, .threads = 2};
                renderer *r = renderer_create(&rd, err, sizeof err);
                assert_non_null(r);
                renderer_frame_pass(r, &p);
                renderer_image img;
                assert_int_equal(renderer_eye_pass(r, &v, 1, &img), 0);
                assert_non_null(img.ao);
                memcpy(ao, img.ao, sizeof ao);
                renderer_destroy(r);
            } else {
                reference_images out;
                reference_render_desc rd = {.params = &p, .view = &v, .samples = 1024, .seed = 3};
                assert_int_equal(reference_render(ref, &rd, &out, err, sizeof err), 0);
                memcpy(ao, out.ao, sizeof ao);
                reference_images_free(&out);
            }
            printf("%s %-10s", fall ? "obscurance" : "occlusion ", modes[mode] ? modes[mode] : "reference");
            for (int k = 0; k < SPOTS; k++) {
                const float at[3] = {(float)-hs[k], 0, 0};
                float px[2];
                gltest_project(&v, at, px);
                double sum = 0; /* 3 x 3 pixels around it, along z (the same distance) */
                for (int dy = -1; dy <= 1; dy++)
                    for (int dx = -1; dx <= 1; dx++)
                        sum += ao[((int)px[1] + dy) * AW * 3 + ((int)px[0] + dx) * 3];
                double got = sum / 9, want = wall_ao(hs[k], 1.0, fall);
                printf("  h %.2f: %.3f (%.3f)", hs[k], got, want);
                worst[mode] = fmax(worst[mode], fabs(got - want));
            }
            printf("\n");
        }
        printf("largest error: ldm %.3f, ssao %.3f, reference %.3f\n", worst[0], worst[1], worst[2]);
        assert_true(worst[0] < 0.05);
        assert_true(worst[2] < 0.03);
    }
    reference_destroy(ref);
    glctx_destroy(ctx);
    scene_free(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gl_build_matches_cpu),
        cmocka_unit_test(test_short_lists_overflow_alike),
        cmocka_unit_test(test_ao_beside_wall),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
