/* cavelight-bench lpv: the CPU propagation step against the scalar reference and against
 * the machine's FMA peak, all measured in the same run on the same thread count. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "base/clock.h"
#include "lpv/lattice.h"
#include "lpv/lpv_geometry.h"
#include "lpv/lpv_inject.h"
#include "lpv/lpv_propagate.h"
#include "lpv_reference.h"
#include "lpv/lpv_volume.h"
#include "base/workpool.h"

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#endif

enum { MIN_REPEATS = 20, PEAK_ITERATIONS = 20000000 };

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* 12 independent chains of 8-wide FMAs per thread: the latency of one FMA is covered by
 * the others, so this runs at the FMA units' throughput. */
static volatile float peak_sink;
static void peak_item(void *ctx, int item)
{
    (void)ctx;
#if defined(__AVX2__) && defined(__FMA__)
    __m256 acc[12], m = _mm256_set1_ps(0.9999999f), a = _mm256_set1_ps(1e-7f);
    for (int k = 0; k < 12; k++)
        acc[k] = _mm256_set1_ps((float)(k + item));
    for (long i = 0; i < PEAK_ITERATIONS; i++)
        for (int k = 0; k < 12; k++)
            acc[k] = _mm256_fmadd_ps(acc[k], m, a);
    float out[8];
    __m256 s = acc[0];
    for (int k = 1; k < 12; k++)
        s = _mm256_add_ps(s, acc[k]);
    _mm256_storeu_ps(out, s);
    peak_sink = out[0];
#else
    float acc[12];
    for (int k = 0; k < 12; k++)
        acc[k] = (float)(k + item);
    for (long i = 0; i < PEAK_ITERATIONS / 8; i++)
        for (int k = 0; k < 12; k++)
            acc[k] = fmaf(acc[k], 0.9999999f, 1e-7f);
    peak_sink = acc[0];
#endif
}

static double peak_gflops(workpool *pool, int threads)
{
#if defined(__AVX2__) && defined(__FMA__)
    double flops_per_thread = (double)PEAK_ITERATIONS * 12 * 8 * 2;
#else
    double flops_per_thread = (double)(PEAK_ITERATIONS / 8) * 12 * 2;
#endif
    double t[5];
    for (int r = 0; r < 5; r++) {
        double t0 = clock_now_ms() * 1e-3;
        workpool_run(pool, threads, peak_item, NULL);
        t[r] = clock_now_ms() * 1e-3 - t0;
    }
    return flops_per_thread * threads / median(t, 5) * 1e-9;
}

static uint64_t rng_state = 0x62656e63686c7076ull;
static float rnd(void) /* [0, 1), xorshift64* */
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (float)((rng_state * 0x2545f4914f6cdd1dull) >> 40) * (1.0f / 16777216.0f);
}

/* The 1-minute load average, so that a reader can tell a busy machine's figures apart. */
static double load_average(void)
{
    double l = -1.0;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &l) != 1)
            l = -1.0;
        fclose(f);
    }
    return l;
}

int bench_lpv(int argc, char **argv)
{
    int res = 64, steps = 8, threads = 0, naive_repeats = 3, transport = LPV_TRANSPORT_BEAMS;
    const bench_option opts[] = {
        BENCH_CHOICE("transport", "beams|paper", "the propagation step measured", &transport,
                     lpv_transport_names),
        BENCH_INT("res", "N", "lattice cells per axis", &res, 2, 512),
        BENCH_INT("steps", "S", "propagation steps", &steps, 1, 1000),
        BENCH_INT("threads", "T", "worker threads (0: all cores)", &threads, 0, 256),
        BENCH_INT("naive-repeats", "R", "repeats of the naive baseline", &naive_repeats, 1, 1000),
    };
    int pr = BENCH_PARSE("lpv", "CPU propagation against a naive baseline", opts, argc, argv);
    if (pr)
        return pr > 0 ? 0 : 2;
    workpool *pool = workpool_create(threads);
    if (!pool) {
        fprintf(stderr, "bench lpv: cannot start the worker threads\n");
        return 1;
    }
    threads = workpool_threads(pool);

    lattice_desc lat = {{0, 0, 0}, 1.0f, {res, res, res}};
    lpv_volume inj, a, b, ref_a, ref_b;
    lpv_blockers geo;
    int n[3] = {res, res, res};
    if (lpv_volume_init(&inj, n, LPV_LIGHT_CHANNELS) ||
        lpv_volume_init(&a, n, LPV_LIGHT_CHANNELS) || lpv_volume_init(&b, n, LPV_LIGHT_CHANNELS) ||
        lpv_volume_init(&ref_a, n, LPV_LIGHT_CHANNELS) ||
        lpv_volume_init(&ref_b, n, LPV_LIGHT_CHANNELS) ||
        lpv_blockers_init(&geo, n)) {
        fprintf(stderr, "bench lpv: out of memory for a %d^3 lattice\n", res);
        return 1;
    }
    /* A scene of sorts: random VPLs and two walls of geometry. */
    size_t vpl_count = (size_t)res * res;
    lpv_vpl *vpls = malloc(vpl_count * sizeof *vpls);
    for (size_t i = 0; i < vpl_count; i++) {
        for (int k = 0; k < 3; k++) {
            vpls[i].position[k] = rnd() * res;
            vpls[i].normal[k] = rnd() - 0.5f;
            vpls[i].flux[k] = rnd();
        }
    }
    lpv_inject_vpls(&inj, NULL, &lat, vpls, vpl_count, NULL);
    free(vpls);
    float r = (float)res;
    float walls[] = {0.3f * r, 0, 0, 0.3f * r, r, 0, 0.3f * r, r, r, 0.3f * r, 0, 0, 0.3f * r, r, r, 0.3f * r, 0, r,
                     0, 0.6f * r, 0, r, 0.6f * r, r, r, 0.6f * r, 0, 0, 0.6f * r, 0, 0, 0.6f * r, r, r, 0.6f * r, r};
    lpv_geometry_add_triangles(&geo, &lat, walls, 12, NULL, 4, NULL);

    lpv_propagate_desc pd = {.transport = (lpv_transport)transport, .blockers = &geo,
                             .absorption = 0.05f, .scattering = 0.02f, .pool = pool};
    if (pd.transport == LPV_TRANSPORT_PAPER)
        lpv_paper_transfer_default(); /* its precomputation is not part of a step */
    int repeats = MIN_REPEATS;
    double *times = malloc((size_t)repeats * sizeof *times);
    for (int rep = -1; rep < repeats; rep++) { /* rep -1 warms the caches up */
        lpv_volume_copy(&a, &inj);
        lpv_volume *s = &a, *d = &b;
        double t0 = clock_now_ms() * 1e-3;
        for (int k = 0; k < steps; k++) {
            lpv_propagate_step(&pd, s, d);
            lpv_volume *t = s;
            s = d;
            d = t;
        }
        if (rep >= 0)
            times[rep] = clock_now_ms() * 1e-3 - t0;
    }
    const lpv_volume *fast = steps % 2 ? &b : &a;
    size_t cells = lattice_cell_count(&lat);
    double fast_s = median(times, repeats);
    double flops = steps * lpv_propagate_flops(pd.transport, cells);

    /* The scalar reference: same steps, same settings, fewer repeats (it is slow). */
    double *naive_times = malloc((size_t)naive_repeats * sizeof *naive_times);
    lpv_propagate_desc rd = pd;
    for (int rep = 0; rep < naive_repeats; rep++) {
        lpv_volume_copy(&ref_a, &inj);
        lpv_volume *s = &ref_a, *d = &ref_b;
        double t0 = clock_now_ms() * 1e-3;
        for (int k = 0; k < steps; k++) {
            lpv_reference_step(&rd, s, d);
            lpv_volume *t = s;
            s = d;
            d = t;
        }
        naive_times[rep] = clock_now_ms() * 1e-3 - t0;
    }
    const lpv_volume *ref = steps % 2 ? &ref_b : &ref_a;
    double naive_s = median(naive_times, naive_repeats);

    /* Largest difference relative to the largest value of the channel. */
    double max_rel = 0.0;
    for (int c = 0; c < LPV_LIGHT_CHANNELS; c++) {
        double scale = 0.0, diff = 0.0;
        for (size_t i = 0; i < cells; i++) {
            scale = fmax(scale, fabs(ref->ch[c][i]));
            diff = fmax(diff, fabs((double)ref->ch[c][i] - fast->ch[c][i]));
        }
        if (scale > 0.0)
            max_rel = fmax(max_rel, diff / scale);
    }
    double peak = peak_gflops(pool, threads);
    double gflops = flops / fast_s * 1e-9;
    printf("{\"bench\":\"lpv\",\"transport\":\"%s\",\"res\":%d,\"steps\":%d,\"threads\":%d,\"repeats\":%d,"
           "\"ms_per_step\":%.4f,\"gflops\":%.3f,\"peak_gflops\":%.3f,\"fraction_of_peak\":%.4f,"
           "\"naive_ms_per_step\":%.4f,\"naive_repeats\":%d,\"speedup_vs_naive\":%.2f,"
           "\"max_rel_diff_vs_naive\":%.3g,\"loadavg_1m\":%.2f,\"checksum\":\"%016llx\"}\n",
           lpv_transport_names[transport], res, steps, threads, repeats, 1e3 * fast_s / steps, gflops, peak, gflops / peak,
           1e3 * naive_s / steps, naive_repeats, naive_s / fast_s, max_rel, load_average(),
           (unsigned long long)lpv_volume_checksum(fast));
    free(times);
    free(naive_times);
    lpv_volume_free(&inj);
    lpv_volume_free(&a);
    lpv_volume_free(&b);
    lpv_volume_free(&ref_a);
    lpv_volume_free(&ref_b);
    lpv_blockers_free(&geo);
    workpool_destroy(pool);
    return max_rel < 1e-4 ? 0 : 1;
}
