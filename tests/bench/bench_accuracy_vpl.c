/* cavelight-bench accuracy vpl: the vpl method (node/gi_vpl.h) per VPL count: the indirect
 * image's relative RMSE against the reference's one-bounce image over the pixels that meet
 * geometry (as the sweep measures ILPV), its GI milliseconds per frame, and the bias of the
 * disk bound.
 *
 * Each count of --counts (default 64,256,1024) renders with each of --seeds K seeds
 * (default 2) once with the disk bound and once with points (renderer_desc.vpl_point,
 * unbounded). Per count: the mean over the seeds of the disk images' relRMSE; the relRMSE
 * of the seeds' mean image, disk and point (what the seeds do not average away); and the
 * bound's bias, the disk mean image against the point mean image: the level lost,
 * 1 - mean(disk) / mean(point), and the RMS of the difference over the point mean's mean
 * (the point estimate's variance is infinite near its VPLs, so this RMS keeps noise that
 * few seeds do not remove; the level converges much faster). GI ms: selection + shadow
 * maps + gather, the gather being the eye pass's host ms less that of the same view with
 * --gi none; medians over the timed frames. The influence cut's bias (vpl_cluster.h): the
 * first seed's image against the same VPLs with no cut, relRMSE and level. Writes <out>/vpl_<scene>.csv and prints one JSON line per count. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "bench_accuracy.h"

enum { MAX_COUNTS = 8, TIMED = 3 };

typedef struct vpl_timing {
    double select_ms, shadow_ms, eye_ms, frame_ms;
} vpl_timing;

/* TIMED frames of fp from r (timer queries arrive a frame late); the last frame's indirect
 * image copied into last (when given) and its metrics in m; the medians in t. */
static int run(acc_setup *s, renderer *r, const frame_params *fp, const acc_reference *ref,
               float *last, image_metrics *m, vpl_timing *t)
{
    double sel[TIMED], sh[TIMED], eye[TIMED], frame[TIMED];
    renderer_image img = {0};
    for (int f = 0; f < TIMED; f++) {
        renderer_frame_pass(r, fp);
        if (renderer_eye_pass(r, &s->view, 1, &img) != 0) {
            fprintf(stderr, "bench accuracy vpl: %s\n", renderer_last_error(r));
            return -1;
        }
        renderer_timings rt;
        renderer_get_timings(r, &rt);
        sel[f] = rt.inject_ms;
        sh[f] = rt.propagate_ms;
        eye[f] = rt.eye_host_ms;
        frame[f] = rt.frame_host_ms + rt.eye_host_ms;
    }
    *t = (vpl_timing){acc_median(sel, TIMED), acc_median(sh, TIMED), acc_median(eye, TIMED),
                      acc_median(frame, TIMED)};
    size_t n = (size_t)s->opt.width * s->opt.height * 3;
    if (last)
        memcpy(last, img.indirect, n * sizeof *last);
    image_metrics_desc geometry = {.mask = ref->coverage};
    if (m && image_metrics_compare(img.indirect, ref->indirect1, s->opt.width, s->opt.height,
                                   &geometry, m) != 0) {
        fprintf(stderr, "bench accuracy vpl: %s: no pixel of the view meets geometry\n",
                s->opt.scene);
        return -1;
    }
    return 0;
}

/* relRMSE of a against b over the reference's geometry; *level: 1 - mean(a) / mean(b). */
static double compare(const acc_setup *s, const acc_reference *ref, const float *a,
                      const float *b, double *level)
{
    image_metrics m;
    image_metrics_desc geometry = {.mask = ref->coverage};
    if (image_metrics_compare(a, b, s->opt.width, s->opt.height, &geometry, &m) != 0)
        return NAN;
    if (level)
        *level = 1.0 - m.mean / m.reference_mean;
    return m.rmse_rel;
}

/* Per-pixel sums over the seeds of one estimate: its mean and its spread. */
typedef struct seed_sums {
    double *sum, *sq;
} seed_sums;

static void seed_add(seed_sums *a, const float *x, const float *minus, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double v = (double)x[i] - (minus ? minus[i] : 0.0f);
        a->sum[i] += v;
        a->sq[i] += v * v;
    }
}

/* Over the covered pixels, relative to mean: *spread, one seed's standard deviation
 * (RMS over the pixels, from the seeds' sample variance), and the RMS of the seeds' mean
 * less its own noise (var / k): the part of the mean that more seeds do not remove. */
static double seed_bias(const seed_sums *a, const uint8_t *coverage, size_t n, int k,
                        double mean, double *spread)
{
    double var = 0, sq = 0;
    size_t covered = 0;
    for (size_t i = 0; i < n; i++) {
        if (!coverage[i / 3])
            continue;
        double m = a->sum[i] / k;
        var += k > 1 ? (a->sq[i] - k * m * m) / (k - 1) : 0.0;
        sq += m * m;
        covered++;
    }
    var /= (double)covered;
    sq /= (double)covered;
    *spread = sqrt(var) / mean;
    return sqrt(fmax(sq - var / k, 0.0)) / mean;
}

int accuracy_vpl(int argc, char **argv)
{
    acc_options o = {.scene = "default", .out = "out/chart", .width = 160, .height = 120,
                     .ref_samples = 64};
    int counts[MAX_COUNTS] = {64, 256, 1024}, nc = 3, seeds = 2;
    for (int i = 1; i < argc; i++) {
        int bad = 0;
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (acc_parse_common(&o, argc, argv, &i, &bad)) {
        } else if (v && strcmp(a, "--counts") == 0) {
            nc = 0;
            for (const char *c = v; *c && nc < MAX_COUNTS; c += strcspn(c, ","), c += *c == ',')
                bad |= (counts[nc++] = atoi(c)) < FRAME_VPL_MIN || counts[nc - 1] > FRAME_VPL_MAX;
            bad |= nc == 0, i++;
        } else if (v && strcmp(a, "--seeds") == 0) {
            bad = (seeds = atoi(v)) < 1, i++;
        } else {
            bad = 1;
        }
        if (bad) {
            fprintf(stderr, "bench accuracy vpl: bad or unknown option %s (--counts %d..%d)\n", a,
                    FRAME_VPL_MIN, FRAME_VPL_MAX);
            return 2;
        }
    }
    acc_setup s;
    if (acc_setup_open(&s, &o) != 0)
        return 1;
    acc_reference ref;
    if (acc_reference_get(&s, &s.base, "a", &ref) != 0) {
        acc_setup_close(&s);
        return 1;
    }
    size_t n = (size_t)o.width * o.height * 3, covered = 0;
    double mean_ref = 0; /* the reference's mean over the covered pixels: relRMSE's divisor */
    for (size_t i = 0; i < n; i++)
        if (ref.coverage[i / 3]) {
            mean_ref += ref.indirect1[i];
            covered++;
        }
    mean_ref /= covered ? (double)covered : 1.0;
    float *disk = calloc(n, sizeof *disk), *point = calloc(n, sizeof *point);
    float *one[2] = {calloc(n, sizeof(float)), calloc(n, sizeof(float))};
    double *acc = calloc(6 * n, sizeof *acc);
    seed_sums sums[3] = {{acc, acc + n}, {acc + 2 * n, acc + 3 * n}, {acc + 4 * n, acc + 5 * n}};
    renderer *r[3] = {acc_renderer_create(&s, &(acc_renderer_desc){.gi = FRAME_GI_VPL}),
                      acc_renderer_create(&s, &(acc_renderer_desc){.gi = FRAME_GI_VPL,
                                                                   .vpl_point = 1}),
                      acc_renderer_create(&s, &(acc_renderer_desc){.gi = FRAME_GI_VPL,
                                                                   .vpl_cut = -1})};
    FILE *f = acc_open_csv(&s, "vpl",
        "scene,vpl_count,seeds,select_ms,shadow_ms,gather_ms,gi_ms,frame_ms,"
        "rmse_rel_indirect,ssim_indirect,best_scale_indirect,rmse_rel_seed_mean,"
        "rmse_rel_seed_mean_point,bound_level_bias,bound_bias_rms,reference_noise_rel,"
        "vpl_spread_rel,disk_bias_rel,clamp_bias_rel,rmse_rel_truth,beyond_clamp,cut_bias_rel,"
        "cut_level_bias");
    float *uncut = calloc(n, sizeof *uncut);
    int rc = disk && point && one[0] && one[1] && uncut && acc && r[0] && r[1] && r[2] && f ? 0 : 1;
    /* The shading pass without indirect light: the gather's baseline. */
    frame_params fp = s.base;
    fp.gi = FRAME_GI_NONE;
    vpl_timing none;
    if (rc == 0)
        rc = run(&s, r[0], &fp, &ref, NULL, NULL, &none);
    for (int c = 0; c < nc && rc == 0; c++) {
        memset(disk, 0, n * sizeof *disk);
        memset(point, 0, n * sizeof *point);
        memset(acc, 0, 6 * n * sizeof *acc);
        double cut_rel = NAN, cut_level = NAN;
        double err = 0, ssim = 0, scale = 0, sel[64], sh[64], gather[64], frame[64];
        int k = seeds < 64 ? seeds : 64;
        for (int seed = 0; seed < k && rc == 0; seed++) {
            fp = s.base;
            fp.gi = FRAME_GI_VPL;
            fp.vpl_count = counts[c];
            fp.vpl_seed = (uint32_t)seed;
            image_metrics m, unused;
            vpl_timing t, tp;
            rc = run(&s, r[0], &fp, &ref, one[0], &m, &t) ||
                 run(&s, r[1], &fp, &ref, one[1], &unused, &tp);
            if (rc)
                break;
            seed_add(&sums[0], one[0], NULL, n);            /* the disk estimate */
            seed_add(&sums[1], one[1], NULL, n);            /* the point estimate */
            seed_add(&sums[2], one[1], one[0], n);          /* point - disk: the clamp */
            if (seed == 0) {
                vpl_timing tu;
                image_metrics mu;
                rc = run(&s, r[2], &fp, &ref, uncut, &mu, &tu);
                cut_rel = compare(&s, &ref, one[0], uncut, &cut_level);
            }
            err += m.rmse_rel / k;
            ssim += m.ssim / k;
            scale += m.best_scale / k;
            sel[seed] = t.select_ms;
            sh[seed] = t.shadow_ms;
            gather[seed] = t.eye_ms - none.eye_ms;
            frame[seed] = t.frame_ms;
        }
        if (rc)
            break;
        for (size_t i = 0; i < n; i++) {
            disk[i] = (float)(sums[0].sum[i] / k);
            point[i] = (float)(sums[1].sum[i] / k);
        }
        double ms[4] = {acc_median(sel, k), acc_median(sh, k), acc_median(gather, k),
                        acc_median(frame, k)};
        double level = NAN;
        double mean_err = compare(&s, &ref, disk, ref.indirect1, NULL);
        double mean_err_point = compare(&s, &ref, point, ref.indirect1, NULL);
        double bias = compare(&s, &ref, disk, point, &level);
        /* The error's parts, each a relRMSE over the reference's mean: the reference's
         * noise, the seeds' spread (VPL variance), the disk estimate's bias (its seed
         * mean against the reference, less the mean's and the reference's noise), and the
         * clamp's bias (point - disk on the same VPLs, less its seed noise). The goal
         * compares one image's error against the truth (the reference's noise taken out)
         * with the clamp's bias. */
        double spread, spread_point, spread_clamp;
        double ref_noise = ref.noise_rms_indirect1 / mean_ref;
        (void)seed_bias(&sums[0], ref.coverage, n, k, mean_ref, &spread);
        (void)seed_bias(&sums[1], ref.coverage, n, k, mean_ref, &spread_point);
        double clamp = seed_bias(&sums[2], ref.coverage, n, k, mean_ref, &spread_clamp);
        double disk_bias = sqrt(fmax(mean_err * mean_err - spread * spread / k -
                                     ref_noise * ref_noise, 0.0));
        double truth = sqrt(fmax(err * err - ref_noise * ref_noise, 0.0));
        fprintf(f, "%s,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.6g,%.5f,%.5f,%.6g,%.6g,%.6g,%.6g,"
                "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n",
                o.scene, counts[c], k, ms[0], ms[1], ms[2], ms[0] + ms[1] + ms[2], ms[3], err,
                ssim, scale, mean_err, mean_err_point, level, bias, ref_noise, spread,
                disk_bias, clamp, truth, truth - clamp, cut_rel, cut_level);
        printf("{\"bench\":\"accuracy\",\"experiment\":\"vpl\",\"scene\":\"%s\",\"width\":%d,"
               "\"height\":%d,\"reference_samples\":%d,\"reference_noise_indirect1\":%.6g,"
               "\"vpl_count\":%d,\"seeds\":%d,\"select_ms\":%.3f,\"shadow_ms\":%.3f,"
               "\"gather_ms\":%.3f,\"gi_ms\":%.3f,\"frame_ms\":%.3f,\"rmse_rel\":%.4f,"
               "\"ssim\":%.4f,\"best_scale\":%.4f,\"rmse_rel_seed_mean\":%.4f,"
               "\"rmse_rel_seed_mean_point\":%.4f,\"bound_level_bias\":%.4f,"
               "\"bound_bias_rms\":%.4f,\"reference_noise_rel\":%.4f,\"vpl_spread_rel\":%.4f,"
               "\"point_spread_rel\":%.4f,\"disk_bias_rel\":%.4f,\"clamp_bias_rel\":%.4f,"
               "\"rmse_rel_truth\":%.4f,\"beyond_clamp\":%.4f,\"cut_bias_rel\":%.5f,"
               "\"cut_level_bias\":%.5f}\n",
               o.scene, o.width, o.height, 2 * o.ref_samples, ref.noise_indirect1, counts[c], k,
               ms[0], ms[1], ms[2], ms[0] + ms[1] + ms[2], ms[3], err, ssim, scale, mean_err,
               mean_err_point, level, bias, ref_noise, spread, spread_point, disk_bias, clamp,
               truth, truth - clamp, cut_rel, cut_level);
        fflush(stdout);
    }
    if (f)
        fclose(f);
    for (int i = 0; i < 3; i++)
        if (r[i])
            renderer_destroy(r[i]);
    free(disk);
    free(point);
    free(one[0]);
    free(one[1]);
    free(acc);
    free(uncut);
    acc_reference_free(&ref);
    acc_setup_close(&s);
    return rc;
}
#else
typedef int accuracy_vpl_unused;
#endif
