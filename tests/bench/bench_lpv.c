/* cavelight-bench lpv: one transport's propagation step (--transport beams|paper) on the
 * CPU against the scalar reference and against the machine's FMA peak, all measured in the
 * same run on the same thread count; or (--backend gl) its GL compute shader, run directly
 * (tests/reference/lpv_gl_steps.h), against the CPU step's result. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "base/clock.h"
#include "gi/ilpv/lattice.h"
#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_inject.h"
#include "gi/ilpv/lpv_propagate.h"
#include "lpv_reference.h"
#include "gi/ilpv/lpv_volume.h"
#include "base/workpool.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "gl/glctx.h"
#include "lpv_gl_steps.h"
#endif

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

/* The bench's scene: N^2 random VPLs injected into an N^3 lattice and two walls. */
typedef struct scene_lpv {
    int n[3];
    lpv_volume inj, a, b;
    lpv_blockers geo;
} scene_lpv;

static int scene_open(scene_lpv *sc, int res)
{
    lattice_desc lat = {{0, 0, 0}, 1.0f, {res, res, res}};
    for (int k = 0; k < 3; k++)
        sc->n[k] = res;
    if (lpv_volume_init(&sc->inj, sc->n, LPV_LIGHT_CHANNELS) ||
        lpv_volume_init(&sc->a, sc->n, LPV_LIGHT_CHANNELS) ||
        lpv_volume_init(&sc->b, sc->n, LPV_LIGHT_CHANNELS) || lpv_blockers_init(&sc->geo, sc->n)) {
        fprintf(stderr, "bench lpv: out of memory for a %d^3 lattice\n", res);
        return -1;
    }
    size_t vpl_count = (size_t)res * res;
    lpv_vpl *vpls = malloc(vpl_count * sizeof *vpls);
    for (size_t i = 0; vpls && i < vpl_count; i++) {
        for (int k = 0; k < 3; k++) {
            vpls[i].position[k] = rnd() * res;
            vpls[i].normal[k] = rnd() - 0.5f;
            vpls[i].flux[k] = rnd();
        }
    }
    lpv_inject_vpls(&sc->inj, NULL, &lat, vpls, vpls ? vpl_count : 0, NULL);
    free(vpls);
    float r = (float)res;
    float walls[] = {0.3f * r, 0, 0, 0.3f * r, r, 0, 0.3f * r, r, r, 0.3f * r, 0, 0, 0.3f * r, r, r, 0.3f * r, 0, r,
                     0, 0.6f * r, 0, r, 0.6f * r, r, r, 0.6f * r, 0, 0, 0.6f * r, 0, 0, 0.6f * r, r, r, 0.6f * r, r};
    lpv_geometry_add_triangles(&sc->geo, &lat, walls, 12, NULL, 4, NULL);
    return 0;
}

static void scene_close(scene_lpv *sc)
{
    lpv_volume_free(&sc->inj);
    lpv_volume_free(&sc->a);
    lpv_volume_free(&sc->b);
    lpv_blockers_free(&sc->geo);
}

typedef void (*step_fn)(const lpv_propagate_desc *d, const lpv_volume *src, lpv_volume *dst);

/* Median seconds of `steps` steps of fn from the injection over `repeats` runs (after one
 * run that warms the caches up when warm); *out is the volume holding the last result. */
static double time_steps(scene_lpv *sc, step_fn fn, const lpv_propagate_desc *pd, int steps,
                         int repeats, int warm, const lpv_volume **out)
{
    double *times = malloc((size_t)repeats * sizeof *times);
    for (int rep = warm ? -1 : 0; times && rep < repeats; rep++) {
        lpv_volume_copy(&sc->a, &sc->inj);
        lpv_volume *s = &sc->a, *d = &sc->b;
        double t0 = clock_now_ms() * 1e-3;
        lpv_propagate_desc step = *pd;
        for (int k = 0; k < steps; k++) {
            step.step = (unsigned)k; /* beams: the split axis of a chain's k-th step */
            fn(&step, s, d);
            lpv_volume *t = s;
            s = d;
            d = t;
        }
        if (rep >= 0)
            times[rep] = clock_now_ms() * 1e-3 - t0;
    }
    *out = steps % 2 ? &sc->b : &sc->a;
    double m = times ? median(times, repeats) : 0.0;
    free(times);
    return m;
}

static int bench_cpu(scene_lpv *sc, lpv_propagate_desc *pd, int steps, int naive_repeats)
{
    int threads = workpool_threads(pd->pool), res = sc->n[0];
    lpv_volume fast;
    const lpv_volume *last;
    double fast_s = time_steps(sc, lpv_propagate_step, pd, steps, MIN_REPEATS, 1, &last);
    if (lpv_volume_init(&fast, sc->n, LPV_LIGHT_CHANNELS) != 0)
        return 1;
    lpv_volume_copy(&fast, last);
    /* The scalar reference: same steps, same settings, fewer repeats (it is slow). */
    double naive_s = time_steps(sc, lpv_reference_step, pd, steps, naive_repeats, 0, &last);
    double max_rel = lpv_reference_rel_diff(&fast, last);
    double flops = steps * lpv_propagate_flops(pd->transport, fast.cells);
    double peak = peak_gflops(pd->pool, threads), gflops = flops / fast_s * 1e-9;
    printf("{\"bench\":\"lpv\",\"backend\":\"cpu\",\"transport\":\"%s\",\"res\":%d,"
           "\"steps\":%d,\"threads\":%d,\"repeats\":%d,\"ms_per_step\":%.4f,\"gflops\":%.3f,"
           "\"peak_gflops\":%.3f,\"fraction_of_peak\":%.4f,\"naive_ms_per_step\":%.4f,"
           "\"naive_repeats\":%d,\"speedup_vs_naive\":%.2f,\"max_rel_diff_vs_naive\":%.3g,"
           "\"loadavg_1m\":%.2f,\"checksum\":\"%016llx\"}\n",
           lpv_transport_names[pd->transport], res, steps, threads, MIN_REPEATS,
           1e3 * fast_s / steps, gflops, peak, gflops / peak, 1e3 * naive_s / steps,
           naive_repeats, naive_s / fast_s, max_rel, load_average(),
           (unsigned long long)lpv_volume_checksum(&fast));
    lpv_volume_free(&fast);
    return max_rel < 1e-4 ? 0 : 1;
}

#ifdef CAVELIGHT_HAVE_NODE
/* The transport's compute shader on an EGL context: the median of MIN_REPEATS runs of
 * `steps` steps (glFinish before and after), its result against the CPU step's. */
static int bench_gl(scene_lpv *sc, lpv_propagate_desc *pd, int steps)
{
    char err[512];
    glctx *ctx = glctx_create(&(glctx_desc){.backend = GLCTX_EGL}, err, sizeof err);
    lpv_gl_steps gs;
    if (!ctx || lpv_gl_steps_init(&gs, glctx_gl(ctx), sc->n, &sc->geo, NULL, err, sizeof err)) {
        fprintf(stderr, "bench lpv: %s\n", err);
        if (ctx)
            glctx_destroy(ctx);
        return 1;
    }
    const gl_functions *gl = glctx_gl(ctx);
    GLuint tex[2][3];
    lpv_gl_volume_textures(&gs, tex[0]);
    lpv_gl_volume_textures(&gs, tex[1]);
    double times[MIN_REPEATS];
    for (int rep = -1; rep < MIN_REPEATS; rep++) {
        lpv_gl_upload(&gs, &sc->inj, tex[0]);
        gl->Finish();
        double t0 = clock_now_ms() * 1e-3;
        for (int k = 0; k < steps; k++) {
            lpv_propagate_desc d = *pd;
            d.step = (unsigned)k;
            lpv_gl_step(&gs, &d, tex[k & 1], tex[1 - (k & 1)]);
        }
        gl->Finish();
        if (rep >= 0)
            times[rep] = clock_now_ms() * 1e-3 - t0;
    }
    lpv_volume gpu;
    const lpv_volume *cpu;
    int rc = lpv_volume_init(&gpu, sc->n, LPV_LIGHT_CHANNELS) != 0;
    if (rc == 0) {
        lpv_gl_download(&gs, tex[steps & 1], &gpu);
        time_steps(sc, lpv_propagate_step, pd, steps, 1, 0, &cpu);
        double diff = lpv_reference_rel_diff(&gpu, cpu), s = median(times, MIN_REPEATS);
        printf("{\"bench\":\"lpv\",\"backend\":\"gl\",\"transport\":\"%s\",\"res\":%d,"
               "\"steps\":%d,\"renderer\":\"%s\",\"repeats\":%d,\"ms_per_step\":%.4f,"
               "\"max_rel_diff_vs_cpu\":%.3g,\"loadavg_1m\":%.2f}\n",
               lpv_transport_names[pd->transport], sc->n[0], steps, glctx_renderer(ctx),
               MIN_REPEATS, 1e3 * s / steps, diff, load_average());
        rc = diff < 1e-3 ? 0 : 1;
        lpv_volume_free(&gpu);
    }
    gl->DeleteTextures(3, tex[0]);
    gl->DeleteTextures(3, tex[1]);
    lpv_gl_steps_free(&gs);
    glctx_destroy(ctx);
    return rc;
}
#endif

int bench_lpv(int argc, char **argv)
{
    int res = 64, steps = 8, threads = 0, naive_repeats = 3, transport = LPV_TRANSPORT_BEAMS;
    int backend = 0;
    static const char *const backends[] = {"cpu", "gl"};
    const bench_option opts[] = {
        BENCH_CHOICE("transport", "beams|paper", "the propagation step measured", &transport,
                     lpv_transport_names),
        BENCH_CHOICE("backend", "cpu|gl", "CPU step, or its GL compute shader (EGL)", &backend,
                     backends),
        BENCH_INT("res", "N", "lattice cells per axis", &res, 2, 512),
        BENCH_INT("steps", "S", "propagation steps", &steps, 1, 1000),
        BENCH_INT("threads", "T", "worker threads (0: all cores)", &threads, 0, 256),
        BENCH_INT("naive-repeats", "R", "repeats of the naive baseline", &naive_repeats, 1, 1000),
    };
    int pr = BENCH_PARSE("lpv", "one transport's propagation step against a baseline", opts,
                         argc, argv);
    if (pr)
        return pr > 0 ? 0 : 2;
    workpool *pool = workpool_create(threads);
    if (!pool) {
        fprintf(stderr, "bench lpv: cannot start the worker threads\n");
        return 1;
    }
    scene_lpv sc;
    int rc = scene_open(&sc, res) != 0;
    lpv_propagate_desc pd = {.transport = (lpv_transport)transport, .blockers = &sc.geo,
                             .absorption = 0.05f, .scattering = 0.02f, .pool = pool};
    lpv_paper_transfer_default(); /* its precomputation is not part of a step */
    if (rc == 0 && backend == 0)
        rc = bench_cpu(&sc, &pd, steps, naive_repeats);
    else if (rc == 0) {
#ifdef CAVELIGHT_HAVE_NODE
        rc = bench_gl(&sc, &pd, steps);
#else
        fprintf(stderr, "bench lpv: --backend gl needs the node library (GL)\n");
        rc = 2;
#endif
    }
    scene_close(&sc);
    workpool_destroy(pool);
    return rc;
}
