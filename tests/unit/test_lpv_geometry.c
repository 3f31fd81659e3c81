/* The blockers (lpv_geometry.h): exactly the segments between cell centres that cross a
 * triangle are blocked, in both cells and from both sides; a centre on the plane counts as
 * in front; a closed box lets nothing out; bad triangles are counted. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>

#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_transfer.h"
#include "lpv_testutil.h"

/* Centre of cell c on axis a, world units. */
static double centre(const lattice_desc *lat, int a, int c)
{
    return lat->origin[a] + (c + 0.5) * lat->cell;
}

/* A quad across the whole lattice at y = y0 (normal +y): a segment is blocked exactly when
 * its two centres lie on different sides (a centre on the plane counts as above it). */
static void check_plane(float y0)
{
    lattice_desc lat = {{0, 0, 0}, 0.5f, {10, 8, 7}};
    lpv_blockers b;
    assert_int_equal(lpv_blockers_init(&b, lat.n), 0);
    float X = 5.0f, Z = 3.5f;
    float pos[] = {0, y0, 0, 0, y0, Z, X, y0, Z, X, y0, 0}; /* normal +y */
    unsigned idx[] = {0, 1, 2, 0, 2, 3};
    lpv_geometry_stats st = {0};
    lpv_geometry_add_triangles(&b, &lat, pos, 4, idx, 2, &st);
    assert_int_equal(st.triangles, 2);
    size_t blocked = 0;
    for (int z = 0; z < lat.n[2]; z++)
        for (int y = 0; y < lat.n[1]; y++)
            for (int x = 0; x < lat.n[0]; x++)
                for (int k = 0; k < LPV_NEIGHBOURS; k++) {
                    const int *o = lpv_transfer_offsets[k];
                    int qy = y + o[1];
                    if (x + o[0] < 0 || x + o[0] >= lat.n[0] || qy < 0 || qy >= lat.n[1] ||
                        z + o[2] < 0 || z + o[2] >= lat.n[2])
                        continue;
                    int above = centre(&lat, 1, y) >= y0, q_above = centre(&lat, 1, qy) >= y0;
                    int expect = above != q_above;
                    assert_int_equal(lpv_blockers_blocked(&b, x, y, z, k), expect);
                    /* the same segment seen from the other end */
                    assert_int_equal(lpv_blockers_blocked(&b, x + o[0], qy, z + o[2], 25 - k), expect);
                    blocked += (size_t)expect;
                }
    assert_true(blocked > 0);
    lpv_blockers_free(&b);
}

static void test_a_plane_blocks_exactly_the_segments_that_cross_it(void **state)
{
    (void)state;
    check_plane(1.6f);  /* between centres 1.25 and 1.75 */
    check_plane(1.75f); /* through the centres of row 3: they count as above */
}

/* A closed box of single-sided faces (all normals out): no segment from a cell inside to a
 * cell outside is open, whichever way it runs. */
static void test_closed_box_lets_nothing_out(void **state)
{
    (void)state;
    lattice_desc lat = {{-1, -1, -1}, 0.25f, {12, 12, 12}};
    lpv_blockers b;
    assert_int_equal(lpv_blockers_init(&b, lat.n), 0);
    const float lo = -0.6f, hi = 0.55f;
    float v[8][3];
    for (int i = 0; i < 8; i++)
        for (int a = 0; a < 3; a++)
            v[i][a] = (i >> a) & 1 ? hi : lo;
    const unsigned faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                  {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    unsigned idx[36];
    for (int f = 0; f < 6; f++) {
        const unsigned *q = faces[f];
        unsigned t[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
        for (int k = 0; k < 6; k++)
            idx[6 * f + k] = t[k];
    }
    lpv_geometry_add_triangles(&b, &lat, &v[0][0], 8, idx, 12, NULL);
    size_t checked = 0;
    for (int z = 0; z < 12; z++)
        for (int y = 0; y < 12; y++)
            for (int x = 0; x < 12; x++) {
                int c[3] = {x, y, z}, in = 1;
                for (int a = 0; a < 3; a++)
                    in &= centre(&lat, a, c[a]) > lo && centre(&lat, a, c[a]) < hi;
                for (int k = 0; k < LPV_NEIGHBOURS; k++) {
                    const int *o = lpv_transfer_offsets[k];
                    int q[3] = {x + o[0], y + o[1], z + o[2]}, qin = 1;
                    for (int a = 0; a < 3; a++)
                        qin &= q[a] >= 0 && q[a] < 12 && centre(&lat, a, q[a]) > lo &&
                               centre(&lat, a, q[a]) < hi;
                    if (in != qin && q[0] >= 0 && q[1] >= 0 && q[2] >= 0 && q[0] < 12 &&
                        q[1] < 12 && q[2] < 12) {
                        assert_int_equal(lpv_blockers_blocked(&b, x, y, z, k), 1);
                        checked++;
                    }
                }
            }
    assert_true(checked > 100);
    lpv_blockers_free(&b);
}

static void test_bad_triangles_are_counted(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {4, 4, 4}};
    lpv_blockers b;
    assert_int_equal(lpv_blockers_init(&b, lat.n), 0);
    float pos[] = {1, 1, 1, 2, 1, 1, 3, 1, 1,               /* zero area */
                   NAN, 1, 1, 2, 2, 2, 1, 3, 1,             /* NaN */
                   1, 1, 1, 3, 1, 1, 1, INFINITY, 1,        /* Inf */
                   0.5f, 0.5f, 2.2f, 3.5f, 0.5f, 2.2f, 0.5f, 3.5f, 2.2f}; /* fine */
    unsigned idx[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 0, 1, 99};
    lpv_geometry_stats st = {0};
    lpv_geometry_add_triangles(&b, &lat, pos, 12, idx, 5, &st);
    assert_int_equal(st.triangles, 1);
    assert_int_equal(st.degenerate, 1);
    assert_int_equal(st.invalid, 3);
    assert_true(st.segments > 0);
    /* Refused input when the shapes differ: nothing set, everything counted. */
    lpv_blockers other;
    lattice_desc small = {{0, 0, 0}, 1.0f, {3, 4, 4}};
    assert_int_equal(lpv_blockers_init(&other, small.n), 0);
    lpv_geometry_stats st2 = {0};
    lpv_geometry_add_triangles(&other, &lat, pos, 12, NULL, 4, &st2);
    assert_int_equal(st2.invalid, 4);
    for (size_t i = 0; i < other.cells; i++)
        assert_true(other.mask[i] == 0);
    assert_int_equal(lpv_blockers_blocked(&b, -1, 0, 0, 0), 0);
    assert_int_equal(lpv_blockers_blocked(&b, 0, 0, 0, 26), 0);
    lpv_blockers_free(&other);
    lpv_blockers_free(&b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_plane_blocks_exactly_the_segments_that_cross_it),
        cmocka_unit_test(test_closed_box_lets_nothing_out),
        cmocka_unit_test(test_bad_triangles_are_counted),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
