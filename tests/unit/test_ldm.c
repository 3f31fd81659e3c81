/* Layered depth maps without GL (common/ldm): the direction set's regions have equal areas
 * (counted with an even spread of points over the hemisphere) and small diameters, its
 * cosine sum integrates the hemisphere, it is the same set on every call; the CPU maps
 * traced from random points along random map directions, both ways, meet exactly the
 * surface a brute-force ray caster meets along the ray through the texel's centre (no
 * missed intersection, same distance), and the insertion keeps the smallest depths sorted
 * whatever their order; the memory check names what to change. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>


#include "gi/ldm/ldm_cpu.h"
#include "gi/ldm/ldm_directions.h"
#include "gi/ldm/ldm_map.h"
#include "scene_testutil.h"

static const double PI = 3.14159265358979323846;

/* Point i of m spread evenly over the upper hemisphere's area (a Fibonacci spiral). */
static void hemisphere_point(int i, int m, float out[3])
{
    double y = 1.0 - (i + 0.5) / m, r = sqrt(1.0 - y * y);
    double phi = i * PI * (3.0 - sqrt(5.0));
    out[0] = (float)(r * cos(phi));
    out[1] = (float)y;
    out[2] = (float)(r * sin(phi));
}

static void test_regions_have_equal_area(void **state)
{
    (void)state;
    const int counts[] = {1, 2, 16, 37, 128, 512};
    enum { POINTS = 400000 };
    static int hits[LDM_DIRECTIONS_MAX];
    for (size_t c = 0; c < sizeof counts / sizeof counts[0]; c++) {
        int n = counts[c];
        float dir[LDM_DIRECTIONS_MAX][3];
        assert_int_equal(ldm_directions(n, dir), n);
        memset(hits, 0, sizeof hits);
        double worst_spread = 0, farthest = 0;
        for (int i = 0; i < POINTS; i++) {
            float w[3];
            hemisphere_point(i, POINTS, w);
            int r = ldm_direction_region(n, w);
            assert_true(r >= 0 && r < n);
            hits[r]++;
            double dx = w[0] - dir[r][0], dy = w[1] - dir[r][1], dz = w[2] - dir[r][2];
            farthest = fmax(farthest, sqrt(dx * dx + dy * dy + dz * dz));
        }
        for (int r = 0; r < n; r++) {
            double share = (double)hits[r] * n / POINTS;
            worst_spread = fmax(worst_spread, fabs(share - 1.0));
            assert_true(fabs(sqrt(dir[r][0] * dir[r][0] + dir[r][1] * dir[r][1] +
                                  dir[r][2] * dir[r][2]) - 1.0) < 1e-6);
        }
        /* A region's side is about sqrt(2 pi / n): no point is much farther than that
         * from its centre (a thin sliver would be). */
        double side = sqrt(2.0 * PI / n);
        printf("n %3d: areas within %.4f of equal, farthest point %.3f (%.2f sides)\n", n,
               worst_spread, farthest, farthest / side);
        assert_true(worst_spread < (n <= 128 ? 0.01 : 0.03));
        assert_true(n < 16 || farthest < 1.2 * side);
    }
}

/* sum over the 2n directions (both ways) of max(0, n.d) 2 / n: the hemisphere's cosine
 * integral over pi, 1 for any normal. */
static void test_cosine_sum_integrates(void **state)
{
    (void)state;
    const int counts[] = {16, 64, 256};
    for (size_t c = 0; c < 3; c++) {
        int n = counts[c];
        float dir[LDM_DIRECTIONS_MAX][3];
        ldm_directions(n, dir);
        double worst = 0;
        for (int k = 0; k < 200; k++) {
            float nrm[3];
            hemisphere_point(k, 200, nrm);
            if (k % 2)
                nrm[1] = -nrm[1];
            double s = 0;
            for (int i = 0; i < n; i++) {
                double cd = nrm[0] * dir[i][0] + nrm[1] * dir[i][1] + nrm[2] * dir[i][2];
                s += fabs(cd);
            }
            worst = fmax(worst, fabs(s * 2.0 / n - 1.0));
        }
        printf("n %3d: cosine sum within %.4f of 1\n", n, worst);
        assert_true(worst < 8.0 / n + 0.01);
    }
}

static void test_directions_are_deterministic(void **state)
{
    (void)state;
    static float a[LDM_DIRECTIONS_MAX][3], b[LDM_DIRECTIONS_MAX][3];
    for (int n = 1; n <= LDM_DIRECTIONS_MAX; n += 37) {
        assert_int_equal(ldm_directions(n, a), n);
        assert_int_equal(ldm_directions(n, b), n);
        assert_memory_equal(a, b, sizeof(float) * 3 * n);
        for (int i = 0; i < n; i++) { /* each centre lies in its own region */
            assert_true(a[i][1] >= 0.0f);
            assert_int_equal(ldm_direction_region(n, a[i]), i);
        }
    }
    assert_int_equal(ldm_directions(0, a), 0);
    assert_int_equal(ldm_directions(LDM_DIRECTIONS_MAX + 1, a), 0);
}

/* A small scene of boxes at odd angles inside a room. */
static void test_scene(scene *s)
{
    char err[128];
    memset(s, 0, sizeof *s);
    static const scene_material white = {{0.7f, 0.7f, 0.7f, 1}, -1, {0, 0, 0}, 1};
    assert_true(scene_add_material(s, &white) >= 0);
    const float lo[3] = {-2, 0, -2}, hi[3] = {2, 3, 2};
    assert_int_equal(scene_add_box(s, lo, hi, 1, 0), 0);
    const float blo[3] = {-0.7f, 0, -0.4f}, bhi[3] = {0.3f, 1.1f, 0.5f};
    assert_int_equal(scene_add_box(s, blo, bhi, 0, 0), 0);
    /* a tilted quad */
    const float a[3] = {0.5f, 0.4f, -1.5f}, b[3] = {1.7f, 0.9f, -1.2f}, c[3] = {1.5f, 2.1f, -0.3f},
                d[3] = {0.4f, 1.6f, -0.7f}, n[3] = {0, 0, 1};
    assert_int_equal(scene_add_quad(s, a, b, c, d, n, 0), 0);
    assert_int_equal(scene_finish(s, err, sizeof err), 0);
}

static uint32_t lcg(uint32_t *x)
{
    *x = *x * 1664525u + 1013904223u;
    return *x >> 8;
}

static double uniform(uint32_t *x) { return lcg(x) / 16777216.0; }

static void test_trace_meets_what_rays_meet(void **state)
{
    (void)state;
    scene s;
    test_scene(&s);
    ldm_layout l;
    ldm_layout_init(&l, &s, 16, 48, 12);
    ldm_cpu c;
    assert_int_equal(ldm_cpu_build(&s, &l, &c), 0);
    assert_int_equal(c.overflow, 0);
    uint32_t seed = 12345;
    int hits = 0, misses = 0, rays = 4000;
    double worst = 0;
    for (int k = 0; k < rays; k++) {
        int m = (int)(lcg(&seed) % (uint32_t)l.directions), sign = lcg(&seed) % 2 ? 1 : -1;
        int px = (int)(lcg(&seed) % (uint32_t)l.resolution);
        int py = (int)(lcg(&seed) % (uint32_t)l.resolution);
        const ldm_map *mp = &c.maps[m];
        /* a point on the ray through the texel's centre, at a random depth */
        double su = ((px + 0.5) / l.resolution * 2 - 1) * l.radius;
        double sv = ((py + 0.5) / l.resolution * 2 - 1) * l.radius;
        double t = uniform(&seed) * 2 * l.radius;
        double o[3], dir[3];
        float of[3];
        for (int a = 0; a < 3; a++) {
            o[a] = l.centre[a] + su * mp->u[a] + sv * mp->v[a] + (t - l.radius) * mp->d[a];
            dir[a] = sign * mp->d[a];
            of[a] = (float)o[a];
        }
        double want = testutil_ray_cast(&s, o, dir);
        if (isinf(want))
            want = -1; /* ldm_cpu_trace()'s miss */
        float got = ldm_cpu_trace(&c, m, sign, of, 1e-4f, 0);
        if (want >= 0 && want < 1e-3) /* starts on a surface: either answer is right */
            continue;
        assert_true((got < 0) == (want < 0));
        if (want < 0) {
            misses++;
            continue;
        }
        hits++;
        worst = fmax(worst, fabs(got - want));
    }
    printf("%d rays: %d hits, %d misses, largest distance error %.2g m (scene %.1f m)\n", rays,
           hits, misses, worst, 2 * l.radius);
    assert_true(hits > rays / 4 && misses > 50);
    assert_true(worst < 1e-4 * l.radius);
    ldm_cpu_free(&c);
    scene_free(&s);
}

/* Depths arriving in any order leave the same sorted list of the smallest ones. */
static void test_insertion_keeps_smallest(void **state)
{
    (void)state;
    scene s;
    char err[64];
    memset(&s, 0, sizeof s);
    static const scene_material white = {{0.7f, 0.7f, 0.7f, 1}, -1, {0, 0, 0}, 1};
    scene_add_material(&s, &white);
    /* Eight parallel quads crossing the +y map (the cap direction): 8 layers each texel. */
    for (int i = 0; i < 8; i++) {
        int k = (i * 5) % 8; /* out of order */
        const float lo[3] = {-1, 0.1f * k, -1}, hi[3] = {1, 0.1f * k, 1};
        assert_int_equal(scene_add_rect(&s, lo, hi, 1, 0), 0);
    }
    assert_int_equal(scene_finish(&s, err, sizeof err), 0);
    ldm_layout l;
    ldm_layout_init(&l, &s, 1, 32, 5);
    ldm_cpu c;
    assert_int_equal(ldm_cpu_build(&s, &l, &c), 0);
    const uint32_t *list = ldm_cpu_texel(&c, 0, 16, 16);
    for (int i = 0; i < 5; i++) {
        float t;
        memcpy(&t, &list[i], sizeof t);
        float y = 0.1f * i; /* the map looks down +y: depth grows with y */
        assert_float_equal(t, y - l.centre[1] + l.radius, 1e-5);
    }
    printf("overflow %zu (3 of 8 layers in each covered texel)\n", c.overflow);
    assert_true(c.overflow > 0 && c.overflow % 3 == 0);
    ldm_cpu_free(&c);
    scene_free(&s);
}

static void test_memory_check(void **state)
{
    (void)state;
    char buf[256];
    assert_null(ldm_memory_check(128, 128, 8, 64, "ldm", buf, sizeof buf));
    const char *why = ldm_memory_check(512, 512, 8, 512, "ldm", buf, sizeof buf);
    assert_non_null(why);
    printf("%s\n", why);
    assert_non_null(strstr(why, "4096 MB"));
    assert_non_null(strstr(why, "ldm-memory 512"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_regions_have_equal_area),
        cmocka_unit_test(test_cosine_sum_integrates),
        cmocka_unit_test(test_directions_are_deterministic),
        cmocka_unit_test(test_trace_meets_what_rays_meet),
        cmocka_unit_test(test_insertion_keeps_smallest),
        cmocka_unit_test(test_memory_check),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
