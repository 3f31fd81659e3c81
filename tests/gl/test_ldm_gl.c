/* Layered depth maps on llvmpipe (node/ldm_gl.h): the GL build of the default room gives
 * the CPU oracle's lists (common/ldm/ldm_cpu.h) texel for texel, the same on a second
 * build (the atomic insertion does not depend on the order fragments arrive in), with the
 * same overflow count when the lists are too short. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>

#include "gl/gl_testutil.h"
#include "ldm/ldm_cpu.h"
#include "ldm_gl.h"

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
    ldm_gl *m = ldm_gl_create(glctx_gl(f.ctx), &f.s, &l, err, sizeof err);
    if (!m)
        fprintf(stderr, "%s\n", err);
    assert_non_null(m);
    double ms = ldm_gl_build(m);
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
    ldm_gl_build(m);
    assert_true(ldm_gl_checksum(m) == first);
    free(gl);
    ldm_gl_destroy(m);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gl_build_matches_cpu),
        cmocka_unit_test(test_short_lists_overflow_alike),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
