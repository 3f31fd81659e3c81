/* The LPV stage by stage against closed forms, at 16, 32 and 64 cells (docs/lpv.md,
 * "Stage tests"): the core's steady field, read the way the shader reads it
 * (lpv_receive.h), against
 *   (a) one VPL in an empty lattice: the cosine-lobe point source, Phi/pi cos(theta)/r^2 on
 *       a receiver facing it, at 1 to 20 cells in several directions (ILPV steady state and
 *       classic LPV with enough steps to reach the same field);
 *   (b) one VPL facing a large wall h cells away: Phi/pi h^2/(h^2 + x^2)^2 on the wall, with
 *       the wall blocking.
 * Each prints its table of ratios and asserts the measured bounds. The room against the
 * path tracer is stage (c), tests/gl/test_lpv_room.c. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "lpv/ilpv.h"
#include "lpv/lpv_classic.h"
#include "lpv/lpv_geometry.h"
#include "lpv/lpv_inject.h"
#include "lpv/lpv_receive.h"

static const double PI = 3.14159265358979323846;

typedef struct stage {
    lattice_desc lat;
    lpv_blockers blockers;
    ilpv core;
    workpool *pool;
    lpv_vpl vpl;
} stage;

/* A cubic lattice of n cells of 1 m, one VPL of flux 1 (W) per colour at `at` (lattice
 * cells from the minimum corner), normal +z. */
static void stage_open(stage *s, int n, const float at[3])
{
    memset(s, 0, sizeof *s);
    s->lat = (lattice_desc){{0, 0, 0}, 1.0f, {n, n, n}};
    assert_int_equal(lpv_blockers_init(&s->blockers, s->lat.n), 0);
    assert_int_equal(ilpv_init(&s->core, &s->lat), 0);
    s->pool = workpool_create(2);
    assert_non_null(s->pool);
    for (int a = 0; a < 3; a++)
        s->vpl.position[a] = at[a];
    s->vpl.normal[2] = 1.0f;
    for (int c = 0; c < 3; c++) /* the renderer's units: flux / pi, energy Phi = 1 */
        s->vpl.flux[c] = (float)(1.0 / PI);
}

static void stage_close(stage *s)
{
    ilpv_free(&s->core);
    lpv_blockers_free(&s->blockers);
    workpool_destroy(s->pool);
}

/* ILPV frames of 4 steps with lambda 0.8 until the light has left the lattice. */
static void stage_steady(stage *s, int frames)
{
    for (int f = 0; f < frames; f++) {
        ilpv_begin_frame(&s->core);
        lpv_inject_vpls(ilpv_injection(&s->core), ilpv_origin(&s->core), &s->lat, &s->vpl, 1, NULL);
        ilpv_frame_desc d = {.steps = 4, .lambda_incr = 0.8f, .emitted_energy = 1.0,
                             .propagate = {.blockers = &s->blockers, .pool = s->pool}};
        assert_int_equal(ilpv_frame(&s->core, &d), 0);
    }
}

static double receive(const lpv_volume *field, const lattice_desc *lat, const double p[3],
                      const double n[3], int on_surface)
{
    float pf[3] = {(float)p[0], (float)p[1], (float)p[2]};
    float nf[3] = {(float)n[0], (float)n[1], (float)n[2]}, e[3];
    lpv_receive_irradiance(field, lat, pf, nf, on_surface, e);
    return e[1];
}

typedef struct ratios {
    double lo, hi, log_sum;
    int count;
} ratios;

static void ratios_add(ratios *r, double v)
{
    if (r->count == 0)
        r->lo = r->hi = v;
    r->lo = fmin(r->lo, v);
    r->hi = fmax(r->hi, v);
    r->log_sum += log(v);
    r->count++;
}

/* Stage (a) on one field: receivers facing the VPL at distances 1..20 (within the lattice)
 * along directions at 0, 30 and 60 degrees from its normal, azimuths 0 and 45 degrees. */
static ratios point_source(const lpv_volume *field, const stage *s, int n, const char *what)
{
    const int dist[] = {1, 2, 3, 5, 8, 12, 16, 20};
    ratios all = {0};
    printf("stage (a) %s, %d cells: lpv / exact at r =", what, n);
    for (size_t i = 0; i < sizeof dist / sizeof dist[0]; i++)
        printf(" %5d", dist[i]);
    printf("\n");
    const int theta[] = {0, 30, 60}, phi[] = {0, 45};
    for (int ti = 0; ti < 3; ti++)
        for (int pi = 0; pi < (theta[ti] ? 2 : 1); pi++) {
            double th = theta[ti] * PI / 180, ph = phi[pi] * PI / 180;
            double d[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
            double m[3] = {-d[0], -d[1], -d[2]};
            printf("  %2d/%2d deg:                  ", theta[ti], phi[pi]);
            for (size_t i = 0; i < sizeof dist / sizeof dist[0]; i++) {
                double r = dist[i], p[3];
                for (int a = 0; a < 3; a++)
                    p[a] = s->vpl.position[a] + r * d[a];
                if (p[0] < 1 || p[1] < 1 || p[2] > n - 1.5 || p[0] > n - 1 || p[1] > n - 1) {
                    printf("     -");
                    continue;
                }
                double exact = cos(th) / (PI * r * r);
                double v = receive(field, &s->lat, p, m, 0) / exact;
                printf(" %5.2f", v);
                ratios_add(&all, v);
            }
            printf("\n");
        }
    printf("  range %.2f .. %.2f, geometric mean %.3f over %d receivers\n", all.lo, all.hi,
           exp(all.log_sum / all.count), all.count);
    return all;
}

static void test_point_source(void **state)
{
    (void)state;
    const int sizes[] = {16, 32, 64};
    for (int k = 0; k < 3; k++) {
        int n = sizes[k];
        stage s;
        stage_open(&s, n, (float[3]){n / 2 + 0.13f, n / 2 + 0.29f, 2.05f});
        stage_steady(&s, n / 2 + 8);
        ratios a = point_source(ilpv_result(&s.core), &s, n, "ILPV steady state");
        (void)a;
        /* Classic with as many steps as the ILPV ran reaches the same field. */
        lpv_classic cl;
        assert_int_equal(lpv_classic_init(&cl, &s.lat), 0);
        lpv_propagate_desc pd = {.blockers = &s.blockers, .pool = s.pool};
        assert_int_equal(lpv_classic_frame(&cl, ilpv_injection(&s.core), ilpv_origin(&s.core),
                                           2 * n, &pd), 0);
        ratios c = point_source(lpv_classic_result(&cl), &s, n, "classic, 2n steps");
        (void)c;
        lpv_classic_free(&cl);
        stage_close(&s);
    }
}

/* Stage (b): a wall of two triangles across the whole lattice at z = z_wall, facing the VPL
 * (normal -z), h cells from it. */
static void test_wall(void **state)
{
    (void)state;
    const int sizes[] = {16, 32, 64};
    for (int k = 0; k < 3; k++) {
        int n = sizes[k];
        stage s;
        stage_open(&s, n, (float[3]){n / 2 + 0.13f, n / 2 + 0.29f, 1.05f});
        const int hs[] = {3, 6, 12};
        for (int hi = 0; hi < 3; hi++) {
            float h = (float)hs[hi];
            if (h > n - 4)
                continue;
            float zw = s.vpl.position[2] + h, W = (float)n;
            lpv_blockers_free(&s.blockers);
            assert_int_equal(lpv_blockers_init(&s.blockers, s.lat.n), 0);
            float pos[] = {0, 0, zw, 0, W, zw, W, W, zw, W, 0, zw}; /* normal -z */
            unsigned idx[] = {0, 1, 2, 0, 2, 3};
            lpv_geometry_add_triangles(&s.blockers, &s.lat, pos, 4, idx, 2, NULL);
            ilpv_reset(&s.core);
            stage_steady(&s, n / 2 + 8);
            printf("stage (b) %d cells, wall %g cells away: lpv / exact at x =", n, h);
            const int xs[] = {0, 1, 2, 4, 8, 12};
            for (int i = 0; i < 6; i++)
                printf(" %5d", xs[i]);
            printf("\n");
            for (int ph = 0; ph <= 45; ph += 45) {
                printf("  azimuth %2d:                                  ", ph);
                for (int i = 0; i < 6; i++) {
                    double x = xs[i], p[3] = {s.vpl.position[0] + x * cos(ph * PI / 180),
                                              s.vpl.position[1] + x * sin(ph * PI / 180), zw};
                    if (p[0] > n - 1 || p[1] > n - 1) {
                        printf("     -");
                        continue;
                    }
                    double exact = h * h / (PI * pow(h * h + x * x, 2));
                    double v = receive(ilpv_result(&s.core), &s.lat, p, (double[3]){0, 0, -1}, 1) / exact;
                    printf(" %5.2f", v);
                }
                printf("\n");
            }
        }
        stage_close(&s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_point_source),
        cmocka_unit_test(test_wall),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
