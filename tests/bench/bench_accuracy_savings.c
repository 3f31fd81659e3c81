/* cavelight-bench accuracy savings: what modelling no more than the scene needs saves.
 *
 *   static light  the same frames with and without skipping converged frame passes: frame-
 *                 pass milliseconds spent, frames skipped, and whether the image differs.
 *   fitted lattice one propagation step on the lattice fitted to the scene's bounds against
 *                 the cube with the same cell count along the longest axis (same cell size,
 *                 so the same light where the scene is), median of repeats. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "bench_accuracy.h"
#include "base/clock.h"
#include "gi/ilpv/lpv_propagate.h"
#include "gi/ilpv/lpv_propagate.h"
#include "base/workpool.h"

enum { REPEATS = 7 };

/* Total frame-pass ms over `frames` static frames; the last frame's image in rgb. */
static int static_run(acc_setup *s, int skip, int frames, int lattice, double *total_ms,
                      long *skipped, uint8_t *rgb)
{
    acc_renderer_desc d = {.backend = ILPV_BACKEND_CPU, .lattice = lattice,
                           .skip_converged = skip};
    frame_params fp = s->base;
    renderer *r = acc_renderer_create(s, &d, &fp);
    if (!r)
        return -1;
    fp.lambda_incr = 0.8f;
    *total_ms = 0;
    for (int f = 0; f < frames; f++) {
        double t0 = clock_now_ms();
        renderer_frame_pass(r, &fp);
        *total_ms += clock_now_ms() - t0;
    }
    gi_ilpv_stats st;
    gi_ilpv_stats_get(gi_ilpv_of(renderer_gi(r)), &st);
    *skipped = st.frames_skipped;
    renderer_image img;
    int rc = renderer_eye_pass(r, &s->view, 0, &img);
    if (rc == 0)
        memcpy(rgb, img.rgb, (size_t)s->opt.width * s->opt.height * 3);
    renderer_destroy(r);
    return rc;
}

/* Median ms of one propagation step on an n[0] x n[1] x n[2] lattice with blocking. */
static double step_ms(const int n[3], workpool *pool)
{
    lpv_volume a, b;
    lpv_blockers g;
    if (lpv_volume_init(&a, n, LPV_LIGHT_CHANNELS) || lpv_volume_init(&b, n, LPV_LIGHT_CHANNELS) ||
        lpv_blockers_init(&g, n))
        return NAN;
    for (size_t i = 0; i < a.cells; i++)
        a.ch[0][i] = a.ch[4][i] = a.ch[8][i] = 1.0f;
    lpv_propagate_desc pd = {.blockers = &g, .pool = pool};
    double ms[REPEATS];
    lpv_propagate_step(&pd, &a, &b);
    for (int k = 0; k < REPEATS; k++) {
        double t0 = clock_now_ms();
        lpv_propagate_step(&pd, &a, &b);
        ms[k] = clock_now_ms() - t0;
    }
    lpv_volume_free(&a);
    lpv_volume_free(&b);
    lpv_blockers_free(&g);
    return acc_median(ms, REPEATS);
}

int accuracy_savings(int argc, char **argv)
{
    acc_options o = {.scene = "default", .out = "out/chart", .width = 160, .height = 120,
                     .ref_samples = 1};
    int frames = 300, lattice = 32;
    const bench_option opts[] = {
        ACC_COMMON_OPTIONS(&o),
        BENCH_INT("frames", "N", "frames of the static scene", &frames, 2, 100000),
        BENCH_INT("lattice", "N", "cells along the longest axis", &lattice, 2, 512),
    };
    int parsed = BENCH_PARSE("accuracy savings", "what skipping converged frames and a fitted lattice save "
                             "(scripts/chart.sh runs it)", opts, argc, argv);
    if (parsed)
        return parsed > 0 ? 0 : 2;
    acc_setup s;
    if (acc_setup_open(&s, &o) != 0)
        return 1;
    size_t px = (size_t)o.width * o.height;
    uint8_t *with = malloc(px * 3), *without = malloc(px * 3);
    double ms_skip = 0, ms_all = 0;
    long skipped = 0, skipped_off = 0;
    int rc = with && without ? 0 : 1;
    if (rc == 0)
        rc = static_run(&s, 1, frames, lattice, &ms_skip, &skipped, with) ||
             static_run(&s, 0, frames, lattice, &ms_all, &skipped_off, without);

    /* Fitted against cubic lattice, the CPU core alone. */
    acc_renderer_desc d = {.backend = ILPV_BACKEND_CPU, .lattice = lattice};
    frame_params fp = s.base;
    renderer *r = rc == 0 ? acc_renderer_create(&s, &d, &fp) : NULL;
    workpool *pool = workpool_create(o.threads);
    if (!r || !pool)
        rc = 1;
    if (rc == 0) {
        const int *fit = gi_ilpv_lattice(gi_ilpv_of(renderer_gi(r)))->n;
        int longest = fit[0] > fit[1] ? fit[0] : fit[1];
        longest = fit[2] > longest ? fit[2] : longest;
        const int cube[3] = {longest, longest, longest};
        double fit_ms = step_ms(fit, pool), cube_ms = step_ms(cube, pool);
        printf("{\"bench\":\"accuracy\",\"experiment\":\"savings\",\"scene\":\"%s\","
               "\"static_frames\":%d,\"lambda\":0.8,\"steps\":%d,\"frame_pass_ms_total_skip\":%.1f,"
               "\"frame_pass_ms_total_no_skip\":%.1f,\"frames_skipped\":%ld,"
               "\"frames_skipped_when_off\":%ld,\"image_mae_skip_vs_no_skip\":%.6f,"
               "\"lattice\":[%d,%d,%d],\"cells\":%ld,\"cube_cells\":%ld,"
               "\"step_ms_fitted\":%.3f,\"step_ms_cube\":%.3f}\n",
               o.scene, frames, s.base.lpv_steps, ms_skip, ms_all, skipped, skipped_off,
               acc_display_mae(with, without, px), fit[0], fit[1], fit[2],
               (long)fit[0] * fit[1] * fit[2], (long)longest * longest * longest, fit_ms,
               cube_ms);
    }
    if (r)
        renderer_destroy(r);
    if (pool)
        workpool_destroy(pool);
    free(with);
    free(without);
    acc_setup_close(&s);
    return rc ? 1 : 0;
}
#else
typedef int accuracy_savings_unused;
#endif
