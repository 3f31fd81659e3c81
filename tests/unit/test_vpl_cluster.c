/* vpl_cluster: the influence radius is where the bounded kernel meets its stated fraction;
 * a receiver's cluster lists every VPL that reaches it (against brute force over the
 * influence bound) in a view's own grid, a tiled grid and the grid enclosing both eyes of
 * a stereo screen, for points all over both eyes' frusta; the enclosing grid assigns fewer
 * lights than the two eyes' grids together; lists are ascending and deterministic. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "frame/frame_view.h"
#include "gi/vpl/vpl_cluster.h"

enum { LIGHTS = 300, POINTS = 4000 };

static float rnd(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (float)(*s >> 8) / 16777216.0f;
}

static void test_influence_radius(void **state)
{
    (void)state;
    const float area = 0.01f, scene_area = 80.0f, cut = 0.5f, flux = 3.0f;
    float r = vpl_influence_radius(area, scene_area, cut);
    /* The kernel's bound at r is the fraction cut of the flux's even share. */
    assert_float_equal(flux / (area + 3.14159265f * r * r), cut * flux / scene_area, 1e-6f);
    assert_true(vpl_influence_radius(area, scene_area, 0.0f) > 1e30f); /* no cut */
    assert_float_equal(vpl_influence_radius(100.0f, scene_area, 1.0f), 0.0f, 0.0f);
}

/* Both eyes of a head before a 4 x 3 m wall, and lights in the room behind it. */
static void stereo(frame_view eyes[2])
{
    const float bl[3] = {-2, 0, -2}, br[3] = {2, 0, -2}, tl[3] = {-2, 3, -2};
    const float head[3] = {0.3f, 1.6f, 1.5f}, right[3] = {1, 0, 0};
    for (int e = 0; e < 2; e++) {
        float eye[3];
        frame_view_eye(head, right, FRAME_VIEW_EYE_SEPARATION, e ? 1 : -1, eye);
        assert_int_equal(frame_view_screen(bl, br, tl, eye, 12.0f, 320, 240, &eyes[e], NULL), 0);
    }
}

static void lights(vpl *v, float *radius)
{
    uint32_t s = 7;
    for (int i = 0; i < LIGHTS; i++) {
        for (int k = 0; k < 3; k++)
            v[i].position[k] = -3.0f + 6.0f * rnd(&s) + (k == 2 ? -4.0f : 0.0f);
        float n[3] = {rnd(&s) - 0.5f, rnd(&s) - 0.5f, rnd(&s) - 0.5f};
        float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; k++)
            v[i].normal[k] = n[k] / len;
        radius[i] = i % 7 == 0 ? 1e30f : 0.5f + 4.0f * rnd(&s);
    }
}

/* A point of view e's frustum at random pixel and depth (uniform in log depth). */
static void frustum_sample(const frame_view *e, uint32_t *s, float out[3])
{
    vpl_grid g;
    assert_int_equal(vpl_grid_from_view(e, 1, &g), 0);
    float tx = g.window[0] + (g.window[2] - g.window[0]) * rnd(s);
    float ty = g.window[1] + (g.window[3] - g.window[1]) * rnd(s);
    float d = g.near * powf(g.far / g.near, rnd(s));
    for (int k = 0; k < 3; k++)
        out[k] = g.apex[k] + d * (g.forward[k] + tx * g.right[k] + ty * g.up[k]);
}

static int listed(const vpl_clusters *c, int cluster, int i)
{
    for (uint32_t j = c->first[cluster]; j < c->first[cluster + 1]; j++)
        if (c->index[j] == i)
            return 1;
    return 0;
}

/* Every light that reaches a sampled point of either eye is in the point's cluster. */
static void check_covers(const vpl_grid *g, const vpl_clusters *c, const frame_view *eyes,
                         int n_eyes, const vpl *v, const float *radius)
{
    uint32_t s = 99;
    int reached = 0;
    for (int k = 0; k < POINTS; k++) {
        float p[3];
        frustum_sample(&eyes[k % n_eyes], &s, p);
        int cluster = vpl_grid_cluster(g, p);
        assert_true(cluster >= 0 && cluster < vpl_grid_clusters(g));
        for (int i = 0; i < LIGHTS; i++) {
            float d[3] = {p[0] - v[i].position[0], p[1] - v[i].position[1],
                          p[2] - v[i].position[2]};
            float r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            float ahead = d[0] * v[i].normal[0] + d[1] * v[i].normal[1] + d[2] * v[i].normal[2];
            if (r2 > radius[i] * radius[i] || ahead <= 0)
                continue;
            reached++;
            assert_true(listed(c, cluster, i));
        }
    }
    assert_true(reached > POINTS); /* the check saw lights reach points */
    for (int q = 0; q < vpl_grid_clusters(g); q++) /* ascending: the gather's order */
        for (uint32_t j = c->first[q] + 1; j < c->first[q + 1]; j++)
            assert_true(c->index[j] > c->index[j - 1]);
}

static void test_covers_every_fragment(void **state)
{
    (void)state;
    static vpl v[LIGHTS];
    static float radius[LIGHTS];
    lights(v, radius);
    frame_view eyes[2];
    stereo(eyes);
    vpl_clusters c = {0};
    size_t per_eye = 0;
    for (int e = 0; e < 2; e++)
        for (int slices = 1; slices <= VPL_CLUSTER_SLICES; slices += VPL_CLUSTER_SLICES - 1) {
            vpl_grid g;
            assert_int_equal(vpl_grid_from_view(&eyes[e], slices, &g), 0);
            assert_int_equal(g.tiles[0], 10);
            assert_int_equal(g.tiles[1], 8);
            vpl_clusters_assign(&c, &g, v, radius, LIGHTS);
            check_covers(&g, &c, &eyes[e], 1, v, radius);
            per_eye += slices > 1 ? c.assigned : 0;
        }
    vpl_grid enclosing;
    assert_int_equal(vpl_grid_enclosing(eyes, 2, VPL_CLUSTER_SLICES, &enclosing), 0);
    vpl_clusters_assign(&c, &enclosing, v, radius, LIGHTS);
    check_covers(&enclosing, &c, eyes, 2, v, radius);
    printf("light assignments: per eye %zu (two grids), enclosed %zu (%.1f%% fewer), "
           "enclosing grid %dx%dx%d\n", per_eye, c.assigned,
           100.0 * (1.0 - (double)c.assigned / (double)per_eye), enclosing.tiles[0],
           enclosing.tiles[1], enclosing.slices);
    assert_true(c.assigned < per_eye);

    /* The same input, the same lists. */
    vpl_clusters again = {0};
    vpl_clusters_assign(&again, &enclosing, v, radius, LIGHTS);
    assert_int_equal(again.assigned, c.assigned);
    assert_memory_equal(again.index, c.index, c.assigned * sizeof *c.index);
    vpl_clusters_free(&again);
    vpl_clusters_free(&c);

    /* One view encloses itself; orthographic views have no grid. */
    vpl_grid one, own;
    assert_int_equal(vpl_grid_enclosing(eyes, 1, VPL_CLUSTER_SLICES, &one), 0);
    assert_int_equal(vpl_grid_from_view(&eyes[0], VPL_CLUSTER_SLICES, &own), 0);
    for (int k = 0; k < 3; k++)
        assert_float_equal(one.apex[k], own.apex[k], 1e-4f);
    assert_float_equal(one.near, own.near, 1e-4f);
    frame_view ortho = eyes[0];
    memset(ortho.projection, 0, sizeof ortho.projection);
    ortho.projection[0] = ortho.projection[5] = ortho.projection[10] = ortho.projection[15] = 1;
    assert_int_equal(vpl_grid_from_view(&ortho, 1, &own), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_influence_radius),
        cmocka_unit_test(test_covers_every_fragment),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
