/* vpl_select: under every rule (flux, view, regular) the estimate over the chosen VPLs is
 * unbiased (mean over many seeds equals the sum over all candidates within its statistical
 * bound); the flux rule's chosen flux adds up to the total exactly; the choice is
 * deterministic and coherent when one light changes a little; the view rule puts more VPLs
 * where the viewer looks, the regular one spaces them evenly; the view term against its
 * closed form; texel areas of a flat grid and its edges. */
#include <math.h>
#include <stdio.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "gi/vpl/vpl_select.h"
#include "gi/vpl_source.h"

enum { COUNT = 500, N = 64 };

/* vpl_select() over candidates c[0..count) (all RSM texels) by rule. */
static int choose(const vpl *c, size_t count, vpl_selection rule, const double *view, int n,
                  uint32_t seed, double *cdf, vpl *out, size_t *chosen)
{
    vpl_select_desc d = {.candidates = c, .count = count, .texels = count, .rule = rule,
                         .view = view, .n = n, .seed = seed};
    return vpl_select(&d, cdf, out, chosen);
}

static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

/* Candidates with uneven fluxes (a tenth of them dark), colours and areas. */
static void candidates(vpl *c)
{
    uint32_t s = 7;
    for (int j = 0; j < COUNT; j++) {
        for (int k = 0; k < 3; k++) {
            c[j].position[k] = (float)(lcg(&s) % 1000) / 100.0f;
            c[j].normal[k] = k == 1 ? 1.0f : 0.0f;
        }
        float level = j % 10 == 3 ? 0.0f : (float)(1 + lcg(&s) % 100) / 10.0f;
        c[j].flux[0] = level;
        c[j].flux[1] = level * (float)(lcg(&s) % 100) / 100.0f;
        c[j].flux[2] = level * 0.25f;
        c[j].area = (float)(1 + lcg(&s) % 50) / 1000.0f;
    }
}

/* What a receiver would gather, linear in flux: red flux weighted by position, and area. */
static double red_moment(const vpl *v, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += v[i].flux[0] * (1.0 + v[i].position[0]) / (1.0 + v[i].position[2]);
    return s;
}

/* Area of the candidates that send light (a dark one is never chosen, nor needed). */
static double area_sum(const vpl *v, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += v[i].flux[0] + v[i].flux[1] + v[i].flux[2] > 0 ? v[i].area : 0.0;
    return s;
}

/* View samples: points on the plane y = 2 facing down over the first fifth of the
 * candidates' x range, so the view term is large for some candidates and 0 for many. */
enum { SAMPLES = 16 };
static void view_samples(float *out)
{
    for (int s = 0; s < SAMPLES; s++) {
        float *x = out + 6 * s;
        x[0] = 0.5f * (float)(s % 4);
        x[1] = 2.0f;
        x[2] = 2.5f * (float)(s / 4);
        x[3] = 0;
        x[4] = -1;
        x[5] = 0;
    }
}

static void test_unbiased(void **state)
{
    (void)state;
    static vpl c[COUNT];
    static double cdf[COUNT], view[COUNT];
    float samples[6 * SAMPLES];
    vpl out[N];
    candidates(c);
    for (int j = 0; j < COUNT; j += 7) /* some candidates face away from every sample */
        c[j].normal[1] = -1.0f;
    view_samples(samples);
    vpl_view_term(c, COUNT, COUNT, samples, SAMPLES, 1, view);
    const double want[2] = {red_moment(c, COUNT), area_sum(c, COUNT)};
    enum { SEEDS = 4000 };
    for (int rule = 0; rule < VPL_SELECT_COUNT; rule++) {
        double sum[2] = {0}, sq[2] = {0};
        for (uint32_t seed = 0; seed < SEEDS; seed++) {
            assert_int_equal(choose(c, COUNT, (vpl_selection)rule, view, N, seed, cdf, out,
                                        NULL), N);
            double e[2] = {red_moment(out, N), area_sum(out, N)};
            for (int m = 0; m < 2; m++) {
                sum[m] += e[m];
                sq[m] += e[m] * e[m];
            }
        }
        for (int m = 0; m < 2; m++) {
            double mean = sum[m] / SEEDS, var = sq[m] / SEEDS - mean * mean;
            double se = sqrt(fmax(var, 0.0) / SEEDS);
            printf("%s, moment %d: all candidates %.6g, mean of %d seeds %.6g, standard error "
                   "%.2g\n", vpl_selection_names[rule], m, want[m], SEEDS, mean, se);
            /* 5 standard errors: a false alarm about once in 3.5 million runs. */
            assert_true(fabs(mean - want[m]) <= 5.0 * se + 1e-9 * want[m]);
            assert_true(se > 0); /* the estimate does vary with the seed */
        }
    }
}

/* The view rule puts more slots on the candidates the samples see (x < 2, facing up)
 * than the flux rule; the regular rule's slots are evenly spaced in candidate order. */
static void test_view_and_regular_patterns(void **state)
{
    (void)state;
    static vpl c[COUNT];
    static double cdf[COUNT], view[COUNT];
    float samples[6 * SAMPLES];
    vpl out[N];
    size_t chosen[N];
    candidates(c);
    view_samples(samples);
    vpl_view_term(c, COUNT, COUNT, samples, SAMPLES, 1, view);
    int near[2] = {0, 0};
    for (int r = 0; r < 2; r++)
        for (uint32_t seed = 0; seed < 200; seed++) {
            choose(c, COUNT, r ? VPL_SELECT_VIEW : VPL_SELECT_FLUX, view, N, seed, cdf, out,
                       NULL);
            for (int i = 0; i < N; i++)
                near[r] += out[i].position[0] < 2.0f;
        }
    printf("slots with x < 2 over 200 seeds: flux %d, view %d\n", near[0], near[1]);
    assert_true(near[1] > near[0] * 5 / 4);
    int lit = 0;
    for (int j = 0; j < COUNT; j++)
        lit += c[j].flux[0] + c[j].flux[1] + c[j].flux[2] > 0;
    choose(c, COUNT, VPL_SELECT_REGULAR, NULL, N, 3, cdf, out, chosen);
    for (int i = 1; i < N; i++) { /* lit / N candidates apart, give or take a dark one */
        size_t lit_between = 0;
        for (size_t j = chosen[i - 1]; j < chosen[i]; j++)
            lit_between += c[j].flux[0] + c[j].flux[1] + c[j].flux[2] > 0;
        assert_true(fabs((double)lit_between - (double)lit / N) <= 1.0);
    }
}

/* The regular rule with emitters after the texels: two emitters holding half the flux get
 * half the slots (each its flux share, within a slot), the texels the rest, and the
 * estimate stays unbiased over the offset. */
static void test_regular_with_emitters(void **state)
{
    (void)state;
    static vpl c[COUNT + 2];
    static double cdf[COUNT + 2];
    vpl out[N];
    size_t chosen[N];
    candidates(c);
    double texel_flux = 0;
    for (int j = 0; j < COUNT; j++)
        texel_flux += (double)c[j].flux[0] + c[j].flux[1] + c[j].flux[2];
    for (int e = 0; e < 2; e++) { /* a quarter of the total each */
        c[COUNT + e] = c[1];
        float f = (float)(texel_flux / 2 / 3);
        c[COUNT + e].flux[0] = c[COUNT + e].flux[1] = c[COUNT + e].flux[2] = f;
    }
    vpl_select_desc d = {.candidates = c, .count = COUNT + 2, .texels = COUNT,
                         .rule = VPL_SELECT_REGULAR, .n = N, .seed = 9};
    assert_int_equal(vpl_select(&d, cdf, out, chosen), N);
    int slots[2] = {0, 0};
    for (int i = 0; i < N; i++)
        if (chosen[i] >= COUNT)
            slots[chosen[i] - COUNT]++;
    printf("regular: emitter slots %d and %d of %d\n", slots[0], slots[1], N);
    assert_true(abs(slots[0] - N / 4) <= 1 && abs(slots[1] - N / 4) <= 1);
    double want = red_moment(c, COUNT + 2), sum = 0, sq = 0;
    enum { SEEDS = 2000 };
    for (uint32_t seed = 0; seed < SEEDS; seed++) {
        d.seed = seed;
        vpl_select(&d, cdf, out, NULL);
        double e = red_moment(out, N);
        sum += e;
        sq += e * e;
    }
    double mean = sum / SEEDS, se = sqrt(fmax(sq / SEEDS - mean * mean, 0.0) / SEEDS);
    printf("regular with emitters: all %.6g, mean of %d offsets %.6g, standard error %.2g\n",
           want, SEEDS, mean, se);
    assert_true(fabs(mean - want) <= 5.0 * se + 1e-9 * want && se > 0);
}

/* One candidate at the origin facing +y: a sample 2 m above facing down gets
 * 1 / (A + 4 pi); one beside it at 45 degrees cos^2 / (A + 8 pi); one below or facing away
 * 0. With stride 2 the odd texels copy the even ones, but an emitter after a texel
 * gets its own (the one far off: 0). */
static void test_view_term_closed_form(void **state)
{
    (void)state;
    const double pi = 3.14159265358979323846;
    vpl c[2] = {{.normal = {0, 1, 0}, .flux = {1, 1, 1}, .area = 0.5f},
                {.position = {9, 9, 9}, .normal = {0, 1, 0}, .flux = {1, 1, 1}, .area = 0.5f}};
    const float above[6] = {0, 2, 0, 0, -1, 0}, diagonal[6] = {2, 2, 0, 0, -1, 0},
                below[6] = {0, -2, 0, 0, 1, 0}, away[6] = {0, 2, 0, 0, 1, 0};
    double v[2];
    vpl_view_term(c, 1, 1, above, 1, 1, v);
    assert_float_equal(v[0], 1.0 / (0.5 + 4 * pi), 1e-12);
    vpl_view_term(c, 1, 1, diagonal, 1, 1, v);
    assert_float_equal(v[0], 0.5 / (0.5 + 8 * pi), 1e-9);
    float two[12];
    memcpy(two, below, sizeof below);
    memcpy(two + 6, away, sizeof away);
    vpl_view_term(c, 1, 1, two, 2, 1, v);
    assert_float_equal(v[0], 0.0, 0.0);
    vpl_view_term(c, 2, 2, above, 1, 2, v);
    assert_float_equal(v[1], v[0], 0.0);
    vpl_view_term(c, 2, 1, above, 1, 2, v); /* the second an emitter: its own term */
    assert_true(v[0] > 0 && v[1] == 0.0);
}

/* The flux rule's chosen fluxes add up to the total (each slot carries total / n). */
static void test_total_flux_exact(void **state)
{
    (void)state;
    static vpl c[COUNT];
    static double cdf[COUNT];
    vpl out[N];
    candidates(c);
    double total = 0;
    for (int j = 0; j < COUNT; j++)
        total += (double)c[j].flux[0] + c[j].flux[1] + c[j].flux[2];
    for (uint32_t seed = 0; seed < 50; seed++) {
        choose(c, COUNT, VPL_SELECT_FLUX, NULL, N, seed, cdf, out, NULL);
        double got = 0;
        for (int i = 0; i < N; i++) {
            got += (double)out[i].flux[0] + out[i].flux[1] + out[i].flux[2];
            assert_true(out[i].flux[0] + out[i].flux[1] + out[i].flux[2] > 0); /* no dark one */
        }
        assert_true(fabs(got - total) <= 1e-5 * total);
    }
}

static int changed_slots(const vpl *a, const vpl *b)
{
    int changed = 0;
    for (int i = 0; i < N; i++)
        changed += memcmp(a[i].position, b[i].position, sizeof a[i].position) != 0;
    return changed;
}

static void test_deterministic_and_coherent(void **state)
{
    (void)state;
    static vpl c[COUNT];
    static double cdf[COUNT];
    vpl a[N], b[N], other[N];
    candidates(c);
    size_t chosen[N];
    choose(c, COUNT, VPL_SELECT_FLUX, NULL, N, 11, cdf, a, chosen);
    choose(c, COUNT, VPL_SELECT_FLUX, NULL, N, 11, cdf, b, NULL);
    assert_memory_equal(a, b, sizeof a);
    for (int i = 0; i < N; i++) /* each slot names the candidate it copied */
        assert_memory_equal(a[i].position, c[chosen[i]].position, sizeof a[i].position);
    assert_int_equal(vpl_checksum(a, N), vpl_checksum(b, N));
    choose(c, COUNT, VPL_SELECT_FLUX, NULL, N, 12, cdf, other, NULL);
    assert_true(vpl_checksum(other, N) != vpl_checksum(a, N));
    int fresh = changed_slots(a, other);
    /* One candidate a percent brighter (a light moved a little): few slots move. */
    c[200].flux[0] *= 1.01f;
    choose(c, COUNT, VPL_SELECT_FLUX, NULL, N, 11, cdf, b, NULL);
    int moved = changed_slots(a, b);
    assert_true(moved <= N / 10);
    assert_true(fresh >= N / 2);
}

static void test_no_flux(void **state)
{
    (void)state;
    vpl c[4];
    memset(c, 0, sizeof c);
    double cdf[4];
    vpl out[N];
    memset(out, 0x5a, sizeof out);
    assert_int_equal(choose(c, 4, VPL_SELECT_FLUX, NULL, N, 1, cdf, out, NULL), 0);
    assert_int_equal(((unsigned char *)out)[0], 0x5a);
    assert_int_equal(choose(c, 0, VPL_SELECT_FLUX, NULL, N, 1, cdf, out, NULL), 0);
}

static void test_slot_random_range(void **state)
{
    (void)state;
    double mean = 0;
    for (int i = 0; i < 10000; i++) {
        double u = vpl_slot_random(3, i, 0);
        assert_true(u >= 0.0 && u < 1.0);
        mean += u / 10000;
    }
    assert_true(fabs(mean - 0.5) < 0.02);
    assert_true(vpl_slot_random(3, 5, 0) != vpl_slot_random(4, 5, 0));
}

/* Points placed on an emitter's triangle from slot random numbers lie in it, and their
 * mean is its centroid (uniform in area) within 5 standard errors. */
static void test_emitter_point(void **state)
{
    (void)state;
    vpl_emitter e = {.corner = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}}};
    enum { M = 20000 };
    double sum[2] = {0, 0}, sq[2] = {0, 0};
    for (int i = 0; i < M; i++) {
        float p[3];
        vpl_emitter_point(&e, vpl_slot_random(5, i, 1), vpl_slot_random(5, i, 2), p);
        assert_true(p[0] >= 0 && p[1] >= 0 && p[0] / 2 + p[1] <= 1.0f + 1e-6f && p[2] == 0);
        for (int k = 0; k < 2; k++) {
            sum[k] += p[k];
            sq[k] += (double)p[k] * p[k];
        }
    }
    const double centroid[2] = {2.0 / 3.0, 1.0 / 3.0};
    for (int k = 0; k < 2; k++) {
        double mean = sum[k] / M, se = sqrt((sq[k] / M - mean * mean) / M);
        assert_true(fabs(mean - centroid[k]) < 5 * se);
    }
}

/* A 4x4 map: a floor (y = 0, texel step 0.1 x 0.2) in columns 0..2, a wall (x = 0.5, normal
 * -x) in column 3, and no geometry at (3, 3). */
static void test_texel_area(void **state)
{
    (void)state;
    enum { S = 4 };
    float pos[S * S * 4], nrm[S * S * 4];
    for (int y = 0; y < S; y++)
        for (int x = 0; x < S; x++) {
            float *p = pos + 4 * (y * S + x), *n = nrm + 4 * (y * S + x);
            if (x < 3) {
                p[0] = 0.1f * x; p[1] = 0; p[2] = 0.2f * y; p[3] = 1;
                n[0] = 0; n[1] = 1; n[2] = 0;
            } else {
                p[0] = 0.5f; p[1] = 0.3f * y; p[2] = 0; p[3] = y == 3 ? 0.0f : 1.0f;
                n[0] = -1; n[1] = 0; n[2] = 0;
            }
            n[3] = 0;
        }
    assert_float_equal(vpl_texel_area(pos, nrm, S, 0, 0), 0.02f, 1e-6f);
    assert_float_equal(vpl_texel_area(pos, nrm, S, 2, 3), 0.02f, 1e-6f); /* backward steps */
    /* The wall column: no neighbour along x on its plane, 0.3 along y: a square of it. */
    assert_float_equal(vpl_texel_area(pos, nrm, S, 3, 1), 0.09f, 1e-6f);
    /* (3, 2): its only wall neighbour is (3, 1) since (3, 3) is empty. */
    assert_float_equal(vpl_texel_area(pos, nrm, S, 3, 2), 0.09f, 1e-6f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_unbiased),
        cmocka_unit_test(test_view_and_regular_patterns),
        cmocka_unit_test(test_view_term_closed_form),
        cmocka_unit_test(test_regular_with_emitters),
        cmocka_unit_test(test_total_flux_exact),
        cmocka_unit_test(test_deterministic_and_coherent),
        cmocka_unit_test(test_no_flux),
        cmocka_unit_test(test_slot_random_range),
        cmocka_unit_test(test_emitter_point),
        cmocka_unit_test(test_texel_area),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
