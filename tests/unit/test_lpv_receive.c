/* The receiver (lpv_receive.h): the closed forms of the four shapes and their mixes, and
 * which cells a surface point reads (in front of its plane, within its own layer). */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>

#include "gi/ilpv/lpv_receive.h"
#include "gi/ilpv/sh.h"

static const double PI = 3.14159265358979323846;

/* Coefficients of light of energy e with mean direction q d. */
static void light(float e, float q, const float d[3], float L[4])
{
    L[0] = e * (float)SH_Y0;
    L[1] = -e * q * d[1] * (float)SH_Y1;
    L[2] = e * q * d[2] * (float)SH_Y1;
    L[3] = -e * q * d[0] * (float)SH_Y1;
}

static void test_closed_forms(void **state)
{
    (void)state;
    const float down[3] = {0, -1, 0}, up[3] = {0, 1, 0}, side[3] = {1, 0, 0};
    const float floor_n[3] = {0, 1, 0};
    float L[4];
    /* A beam straight down onto a floor: all of it; grazing or leaving: nothing. */
    light(2.0f, 1.0f, down, L);
    assert_float_equal(lpv_receive_closure(L, floor_n, 1.0f), 2.0f, 1e-5f);
    light(2.0f, 1.0f, side, L);
    assert_float_equal(lpv_receive_closure(L, floor_n, 1.0f), 0.0f, 1e-5f);
    light(2.0f, 1.0f, up, L);
    assert_float_equal(lpv_receive_closure(L, floor_n, 1.0f), 0.0f, 1e-5f);
    /* A clamped cosine lobe heading down (q = 2/3): 2/3 of its energy; heading up: 0. */
    light(3.0f, 2.0f / 3.0f, down, L);
    assert_float_equal(lpv_receive_closure(L, floor_n, 1.0f), 2.0f, 1e-4f);
    light(3.0f, 2.0f / 3.0f, up, L);
    assert_float_equal(lpv_receive_closure(L, floor_n, 1.0f), 0.0f, 1e-4f);
    /* A hemisphere (q = 1/2) heading down: 1/2; sideways: 1/4; isotropic: 1/4. */
    light(4.0f, 0.5f, down, L);
    assert_float_equal(lpv_receive_closure(L, floor_n, 1.0f), 2.0f, 1e-4f);
    light(4.0f, 0.5f, side, L);
    assert_float_equal(lpv_receive_closure(L, floor_n, 1.0f), 1.0f, 1e-4f);
    light(4.0f, 0.0f, side, L);
    assert_float_equal(lpv_receive_closure(L, floor_n, 1.0f), 1.0f, 1e-5f);
    /* Irradiance is per unit area: a cell of 0.5 m gives four times as much. */
    assert_float_equal(lpv_receive_closure(L, floor_n, 0.5f), 4.0f, 1e-4f);
    /* Between the shapes it mixes linearly, continuously in q. */
    float prev = -1.0f;
    for (int i = 0; i <= 100; i++) {
        light(1.0f, i / 100.0f, down, L);
        float g = lpv_receive_closure(L, floor_n, 1.0f);
        assert_true(g >= prev - 1e-6f); /* more directed light heading down gives more */
        prev = g;
    }
    /* Nothing from negative or no energy. */
    light(-1.0f, 0.0f, down, L);
    assert_true(lpv_receive_closure(L, floor_n, 1.0f) == 0.0f);
    /* The lobe's closed form against a numerical integral, at an oblique angle. */
    float d[3] = {(float)sin(1.0), (float)-cos(1.0), 0.0f};
    light(1.0f, 2.0f / 3.0f, d, L);
    double sum = 0.0;
    const int N = 400;
    for (int a = 0; a < N; a++)
        for (int b = 0; b < 2 * N; b++) {
            double z = 1.0 - 2.0 * (a + 0.5) / N, ph = PI * (b + 0.5) / N, rr = sqrt(1 - z * z);
            double w[3] = {rr * cos(ph), rr * sin(ph), z};
            double lobe = fmax(0.0, w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / PI;
            sum += lobe * fmax(0.0, -w[1]) * 4.0 * PI / (2.0 * N * N);
        }
    assert_float_equal(lpv_receive_closure(L, floor_n, 1.0f), sum, 2e-3);
}

/* A surface point reads the cells in front of its plane within its own layer only. */
static void test_reads_the_front_layer(void **state)
{
    (void)state;
    lattice_desc lat = {{0, 0, 0}, 1.0f, {4, 4, 4}};
    lpv_volume v;
    assert_int_equal(lpv_volume_init(&v, lat.n, LPV_LIGHT_CHANNELS), 0);
    const float down[3] = {0, -1, 0}, n[3] = {0, 1, 0};
    float L[4], out[3];
    for (int y = 0; y < 4; y++) /* layer y holds light of energy 10^y heading down */
        for (int z = 0; z < 4; z++)
            for (int x = 0; x < 4; x++) {
                light(powf(10.0f, (float)y), 1.0f, down, L);
                for (int s = 0; s < 4; s++)
                    v.ch[4 + s][(size_t)x + 4 * ((size_t)y + 4 * z)] = L[s];
            }
    /* On a floor at y = 1.2: the cells at y = 1.5 (layer 1) only. */
    lpv_receive_irradiance(&v, &lat, (float[3]){2.0f, 1.2f, 2.0f}, n, 1, out);
    assert_float_equal(out[1], 10.0f, 1e-3f);
    /* At y = 1.5, a centre on the plane counts as in front. */
    lpv_receive_irradiance(&v, &lat, (float[3]){2.0f, 1.5f, 2.0f}, n, 1, out);
    assert_float_equal(out[1], 10.0f, 1e-3f);
    /* The same point in free space mixes both neighbouring layers. */
    lpv_receive_irradiance(&v, &lat, (float[3]){2.0f, 1.2f, 2.0f}, n, 0, out);
    assert_float_equal(out[1], 0.3f * 1.0f + 0.7f * 10.0f, 1e-3f);
    /* Below the lattice's first centres: the clamped edge, still in front. */
    lpv_receive_irradiance(&v, &lat, (float[3]){2.0f, 0.2f, 2.0f}, n, 1, out);
    assert_float_equal(out[1], 1.0f, 1e-4f);
    lpv_volume_free(&v);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_forms),
        cmocka_unit_test(test_reads_the_front_layer),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
