/* The splat (lpv_splat.h): the shell holds the injected energy once; the near field is the
 * point source's closed form; the emitting surface's own layer gets no light, the shell's
 * share there lands one layer further out with its direction; blocked and absorbed light is
 * missing; the same bits for any thread count. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>

#include "gi/ilpv/lpv_inject.h"
#include "gi/ilpv/lpv_receive.h"
#include "gi/ilpv/lpv_splat.h"
#include "gi/ilpv/lpv_transfer.h"
#include "gi/ilpv/sh.h"
#include "lpv_testutil.h"

static const double PI = 3.14159265358979323846;

typedef struct fixture {
    lattice_desc lat;
    lpv_volume injected, origin, near, shell;
    lpv_blockers blockers;
    lpv_splat splat;
} fixture;

/* One VPL of flux 1 per colour (the renderer's units: flux / pi) at p with normal n. */
static void open_fixture(fixture *f, const float p[3], const float n[3])
{
    f->lat = (lattice_desc){{0, 0, 0}, 1.0f, {15, 14, 16}};
    assert_int_equal(lpv_volume_init(&f->injected, f->lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&f->origin, f->lat.n, LPV_GEOMETRY_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&f->near, f->lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_volume_init(&f->shell, f->lat.n, LPV_LIGHT_CHANNELS), 0);
    assert_int_equal(lpv_blockers_init(&f->blockers, f->lat.n), 0);
    f->splat = (lpv_splat){0};
    lpv_vpl v = {.position = {p[0], p[1], p[2]}, .normal = {n[0], n[1], n[2]},
                 .flux = {(float)(1 / PI), (float)(2 / PI), (float)(3 / PI)}};
    lpv_inject_vpls(&f->injected, &f->origin, &f->lat, &v, 1, NULL);
}

static void run(fixture *f, float absorption, workpool *pool)
{
    lpv_splat_desc d = {&f->injected, &f->origin, &f->blockers, absorption, pool};
    assert_int_equal(lpv_splat_run(&f->splat, &d, &f->near, &f->shell), 0);
}

static void close_fixture(fixture *f)
{
    lpv_volume *all[] = {&f->injected, &f->origin, &f->near, &f->shell};
    for (int i = 0; i < 4; i++)
        lpv_volume_free(all[i]);
    lpv_blockers_free(&f->blockers);
    lpv_splat_free(&f->splat);
}

static size_t at(const lattice_desc *lat, int x, int y, int z)
{
    return (size_t)x + (size_t)lat->n[0] * ((size_t)y + (size_t)lat->n[1] * z);
}

static void test_shell_holds_the_energy_and_near_is_the_closed_form(void **state)
{
    (void)state;
    const float p[3] = {7.3f, 6.9f, 4.2f}, n[3] = {0.3f, 0.2f, 1.0f};
    fixture f;
    open_fixture(&f, p, n);
    run(&f, 0.0f, NULL);
    double e[3];
    lpv_volume_energy(&f.shell, e);
    for (int c = 0; c < 3; c++)
        assert_float_equal(e[c], c + 1.0, 1e-5 * (c + 1.0));
    /* Each near cell holds, per colour, E cos(w, n) / (pi r^2) as a beam along w (w, r from
     * the VPL, in lattice units with centres at integers) -- or nothing in the own layer,
     * neither near nor shell light. */
    float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), u[3] = {n[0] / len, n[1] / len, n[2] / len};
    int checked = 0;
    for (int z = 0; z < 16; z++)
        for (int y = 0; y < 14; y++)
            for (int x = 0; x < 15; x++) {
                float r[3] = {x - (p[0] - 0.5f), y - (p[1] - 0.5f), z - (p[2] - 0.5f)};
                float d = sqrtf(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
                size_t i = at(&f.lat, x, y, z);
                float ahead = r[0] * u[0] + r[1] * u[1] + r[2] * u[2];
                if (ahead < lpv_own_layer(u)) {
                    for (int c = 0; c < 12; c++)
                        assert_true(f.near.ch[c][i] == 0.0f && f.shell.ch[c][i] == 0.0f);
                    continue;
                }
                if (d >= LPV_SPLAT_RADIUS)
                    continue;
                float cosw = ahead / d, expect = cosw / (float)PI / (d * d > 0.25f ? d * d : 0.25f);
                for (int c = 0; c < 3; c++) {
                    assert_float_equal(f.near.ch[4 * c][i], (c + 1) * expect * (float)SH_Y0,
                                       1e-5f * (c + 1) * expect);
                    assert_float_equal(f.near.ch[4 * c + 3][i], -(c + 1) * expect * (float)SH_Y1 * r[0] / d,
                                       1e-5f * (c + 1) * expect);
                }
                checked++;
            }
    assert_true(checked >= 3);
    close_fixture(&f);
}

/* The shell's share of a cell in a floor VPL's own layer lands in the cell above it, as a
 * beam along the direction from the VPL to the cell it stands for (grazing, not up). */
static void test_own_layer_share_lands_one_layer_out(void **state)
{
    (void)state;
    const float p[3] = {7.5f, 2.0f, 8.5f}, n[3] = {0, 1, 0};
    fixture f;
    open_fixture(&f, p, n);
    run(&f, 0.0f, NULL);
    /* origin (7, 1.5, 8) in centre units: cell (9, 2, 8) is in the own layer, 2.06 cells
     * away (the shell); its share lands in (9, 3, 8) as a beam along (2, 0.5, 0) */
    float r[3] = {2.0f, 0.5f, 0.0f}, d = sqrtf(r[0] * r[0] + r[1] * r[1]);
    size_t lifted = at(&f.lat, 9, 3, 8);
    float e = (float)SH_ENERGY * f.shell.ch[0][lifted];
    float fx = -f.shell.ch[3][lifted] / (float)SH_Y1, fy = -f.shell.ch[1][lifted] / (float)SH_Y1;
    assert_true(e > 0.0f);
    for (size_t i = 0; i < 12; i++)
        assert_true(f.shell.ch[i][at(&f.lat, 9, 2, 8)] == 0.0f);
    /* the cell above also holds its own share (along (2, 1.5, 0)): the mean direction lies
     * between the two, below 45 degrees */
    assert_true(fx > 0.0f && fy > 0.0f && fy < fx && fy / e > r[1] / d * 0.99f);
    close_fixture(&f);
}

/* A wall of blocked segments between the VPL and half of its shell: that half gets
 * nothing, so the shell holds about half the energy; absorption keeps (1 - a)^r. */
static void test_blocked_and_absorbed_light_is_missing(void **state)
{
    (void)state;
    const float p[3] = {7.5f, 7.5f, 8.2f}, n[3] = {1, 0, 0};
    fixture f;
    open_fixture(&f, p, n);
    for (int z = 0; z < 16; z++) /* the segments between x = 8 and x = 9 */
        for (int y = 0; y < 14; y++)
            for (int k = 0; k < LPV_NEIGHBOURS; k++) {
                int o = lpv_transfer_offsets[k][0];
                if (o == 1)
                    f.blockers.mask[at(&f.lat, 8, y, z)] |= 1u << k;
                if (o == -1)
                    f.blockers.mask[at(&f.lat, 9, y, z)] |= 1u << k;
            }
    run(&f, 0.0f, NULL);
    for (int z = 0; z < 16; z++)
        for (int y = 0; y < 14; y++)
            for (int x = 9; x < 15; x++)
                for (int c = 0; c < 12; c++)
                    assert_true(f.near.ch[c][at(&f.lat, x, y, z)] == 0.0f &&
                                f.shell.ch[c][at(&f.lat, x, y, z)] == 0.0f);
    double blocked[3];
    lpv_volume_energy(&f.shell, blocked);
    assert_true(blocked[0] > 0.0 && blocked[0] < 0.9);
    /* Without the wall, with absorption 0.1 per cell: the shell at 2..3 cells keeps
     * 0.9^2 .. 0.9^3 of the energy. */
    lpv_blockers_free(&f.blockers);
    assert_int_equal(lpv_blockers_init(&f.blockers, f.lat.n), 0);
    run(&f, 0.1f, NULL);
    double e[3];
    lpv_volume_energy(&f.shell, e);
    assert_true(e[0] > 0.729 && e[0] < 0.81);
    close_fixture(&f);
}

static void test_same_bits_for_any_thread_count(void **state)
{
    (void)state;
    const float n[3] = {0, 1, 0};
    fixture f;
    open_fixture(&f, (float[3]){5.5f, 1.2f, 6.0f}, n);
    lpv_vpl more[64];
    uint64_t rng = 3;
    for (int i = 0; i < 64; i++) {
        more[i] = (lpv_vpl){.position = {1 + 13 * testutil_rand(&rng), 1 + 12 * testutil_rand(&rng),
                                         1 + 14 * testutil_rand(&rng)},
                            .normal = {testutil_rand(&rng) - 0.5f, testutil_rand(&rng) - 0.5f,
                                       testutil_rand(&rng) - 0.5f},
                            .flux = {testutil_rand(&rng), testutil_rand(&rng), testutil_rand(&rng)}};
    }
    lpv_inject_vpls(&f.injected, &f.origin, &f.lat, more, 64, NULL);
    uint64_t sums[3][2];
    const int threads[3] = {1, 2, 5};
    for (int t = 0; t < 3; t++) {
        workpool *pool = workpool_create(threads[t]);
        run(&f, 0.02f, pool);
        sums[t][0] = lpv_volume_checksum(&f.near);
        sums[t][1] = lpv_volume_checksum(&f.shell);
        workpool_destroy(pool);
    }
    for (int t = 1; t < 3; t++)
        assert_true(sums[t][0] == sums[0][0] && sums[t][1] == sums[0][1]);
    close_fixture(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shell_holds_the_energy_and_near_is_the_closed_form),
        cmocka_unit_test(test_own_layer_share_lands_one_layer_out),
        cmocka_unit_test(test_blocked_and_absorbed_light_is_missing),
        cmocka_unit_test(test_same_bits_for_any_thread_count),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
