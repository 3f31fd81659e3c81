#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>

#include "lpv/lpv_geometry.h"
#include "lpv/lpv_transfer.h"
#include "lpv/sh.h"

static size_t idx_of(const lattice_desc *lat, int x, int y, int z)
{
    return (size_t)x + (size_t)lat->n[0] * ((size_t)y + (size_t)lat->n[1] * z);
}

/* One quad, much larger than a cell, across the whole lattice at y = 3.3 m: every cell of
 * that layer is covered, no cell elsewhere, and a covered cell blocks light heading into
 * the front face almost fully and light leaving it not at all. */
static void test_large_quad_leaves_no_holes(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 0.5f, {20, 10, 14}};
    lpv_volume g;
    assert_int_equal(lpv_volume_init(&g, lat.n, LPV_GEOMETRY_CHANNELS), 0);
    float y = 3.3f, X = 10.0f, Z = 7.0f;
    float pos[] = {0, y, 0, 0, y, Z, X, y, Z, X, y, 0}; /* normal +y (counter-clockwise from above) */
    unsigned idx[] = {0, 1, 2, 0, 2, 3};
    lpv_geometry_stats st = {0};
    lpv_geometry_add_triangles(&g, &lat, pos, 4, idx, 2, &st);
    assert_int_equal(st.triangles, 2);
    assert_true(st.samples > 2 * 20 * 14);
    int layer = (int)(y / lat.cell);
    lpv_transfer tr;
    assert_int_equal(lpv_transfer_compute(NULL, &tr), 0);
    int down = -1, up = -1;
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        const int *o = lpv_transfer_offsets[j];
        if (o[0] == 0 && o[2] == 0)
            *(o[1] < 0 ? &down : &up) = j;
    }
    double sum0 = 0.0;
    for (int z = 0; z < lat.n[2]; z++)
        for (int yy = 0; yy < lat.n[1]; yy++)
            for (int x = 0; x < lat.n[0]; x++) {
                size_t i = idx_of(&lat, x, yy, z);
                float b[4] = {g.ch[0][i], g.ch[1][i], g.ch[2][i], g.ch[3][i]};
                sum0 += b[0];
                if (yy != layer) {
                    assert_true(b[0] == 0.0f);
                    continue;
                }
                assert_true(b[0] > 0.0f);
                float into = sh_dot(b, tr.gamma[down]), out = sh_dot(b, tr.gamma[up]);
                assert_true(into > 0.8f && into < 1.15f);
                assert_true(out <= 0.0f);
            }
    /* Total weight is the area in cell units, independent of the sampling density. */
    double area_cells = X * Z / (lat.cell * lat.cell);
    double expect = area_cells * SH_COS0 / (0.22130 * 3.14159265358979 * 7.0 / 12.0);
    assert_true(fabs(sum0 - expect) < 1e-3 * expect);
    lpv_volume_free(&g);
}

/* A tilted triangle: every cell whose centre lies within a quarter cell of the triangle's
 * plane, above the triangle's interior, receives a sample. */
static void test_tilted_triangle_covers_every_cell_it_crosses(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {16, 16, 16}};
    lpv_volume g;
    assert_int_equal(lpv_volume_init(&g, lat.n, LPV_GEOMETRY_CHANNELS), 0);
    float v[9] = {0.5f, 1.2f, 0.3f, 15.6f, 3.1f, 2.2f, 4.4f, 14.9f, 15.1f};
    lpv_geometry_add_triangles(&g, &lat, v, 3, NULL, 1, NULL);
    double e1[3], e2[3], n[3];
    for (int a = 0; a < 3; a++) {
        e1[a] = v[3 + a] - v[a];
        e2[a] = v[6 + a] - v[a];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    int checked = 0;
    for (int z = 0; z < 16; z++)
        for (int y = 0; y < 16; y++)
            for (int x = 0; x < 16; x++) {
                double c[3] = {x + 0.5, y + 0.5, z + 0.5}, d[3];
                for (int a = 0; a < 3; a++)
                    d[a] = c[a] - v[a];
                double dist = (d[0] * n[0] + d[1] * n[1] + d[2] * n[2]) / nl;
                if (fabs(dist) > 0.25)
                    continue;
                double p[3]; /* projection onto the plane, in barycentrics */
                for (int a = 0; a < 3; a++)
                    p[a] = d[a] - dist * n[a] / nl;
                double d11 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
                double d12 = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2];
                double d22 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
                double p1 = p[0] * e1[0] + p[1] * e1[1] + p[2] * e1[2];
                double p2 = p[0] * e2[0] + p[1] * e2[1] + p[2] * e2[2];
                double den = d11 * d22 - d12 * d12;
                double u = (d22 * p1 - d12 * p2) / den, w = (d11 * p2 - d12 * p1) / den;
                if (u < 0 || w < 0 || u + w > 1)
                    continue;
                assert_true(g.ch[0][idx_of(&lat, x, y, z)] > 0.0f);
                checked++;
            }
    assert_true(checked > 50);
    lpv_volume_free(&g);
}

static void test_bad_triangles_are_skipped_and_counted(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {4, 4, 4}};
    lpv_volume g;
    assert_int_equal(lpv_volume_init(&g, lat.n, LPV_GEOMETRY_CHANNELS), 0);
    float pos[] = {
        0.5f, 0.5f, 0.5f, 3.5f, 0.5f, 0.5f, 0.5f, 3.5f, 0.5f, /* 0: good */
        1, 1, 1, 2, 2, 2, 3, 3, 3,                         /* 1: collinear */
        1, 1, 1, 1, 1, 1, 1, 1, 1,                         /* 2: a point */
        NAN, 1, 1, 2, 1, 1, 1, 2, 1,                       /* 3: NaN */
        1, 1, INFINITY, 2, 1, 1, 1, 2, 1,                  /* 4: Inf */
        10, 10, 10, 12, 10, 10, 10, 12, 10,                /* 5: outside */
    };
    unsigned idx[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 0, 1, 99};
    lpv_geometry_stats st = {0};
    lpv_geometry_add_triangles(&g, &lat, pos, 18, idx, 7, &st);
    assert_int_equal(st.triangles, 2);
    assert_int_equal(st.degenerate, 2);
    assert_int_equal(st.invalid, 3); /* NaN, Inf, index 99 out of range */
    assert_true(st.outside > 0);
    assert_true(st.samples > 0);
    assert_int_equal(lpv_volume_count_nonfinite(&g), 0);
    /* A light volume is not a geometry volume: refused, counted, untouched. */
    lpv_volume light;
    assert_int_equal(lpv_volume_init(&light, lat.n, LPV_LIGHT_CHANNELS), 0);
    lpv_geometry_stats st2 = {0};
    lpv_geometry_add_triangles(&light, &lat, pos, 18, NULL, 1, &st2);
    assert_int_equal(st2.invalid, 1);
    assert_int_equal(st2.samples, 0);
    lpv_volume_free(&light);
    lpv_volume_free(&g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_large_quad_leaves_no_holes),
        cmocka_unit_test(test_tilted_triangle_covers_every_cell_it_crosses),
        cmocka_unit_test(test_bad_triangles_are_skipped_and_counted),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
