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
 * --gi none; medians over the timed frames.
 * The visibility is swept too: --visibility exact,ism,ism-splat (default exact), the
 * imperfect maps for each of --ism-sizes and --ism-points (default the renderer's); the
 * bound's bias is measured with exact visibility only (its columns are empty otherwise).
 * With exact visibility the error is also taken apart, each part a relRMSE over the
 * reference's mean: the reference's noise (RMS of its halves' difference / 2), the seeds'
 * spread (VPL variance), the disk estimate's bias (its seed mean against the reference,
 * less both noises), the clamp's bias (point - disk on the same VPLs, its seed mean less
 * its own noise), one image's error against the truth (the reference's noise taken out)
 * and that less the clamp's bias (the accuracy goal's figure); and the influence cut's
 * bias (vpl_cluster.h): the first seed's image against the same VPLs with no cut.
 * And --interleave 0,4,...: interleaved sampling in k x k blocks (0: off; default 0), and
 * --selection flux,view,regular: how the VPLs are chosen (frame_params.vpl_selection;
 * default flux; the bound's bias is measured under flux only).
 * Writes <out>/vpl_<scene>.csv and prints one JSON line per count and visibility. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "bench_accuracy.h"
#include "seed_stats.h"
#include "gi/vpl/vpl_settings.h"

enum { MAX_COUNTS = 8, MAX_LIST = 4, TIMED = 3 };

/* A comma-separated list of at most max whole numbers in [lo, hi] into out; its length, or
 * 0 when bad. */
static int int_list(const char *v, int lo, int hi, int *out, int max)
{
    int n = 0;
    for (const char *c = v; *c; c += strcspn(c, ","), c += *c == ',') {
        char *end;
        long x = strtol(c, &end, 10);
        if (n == max || end == c || (*end && *end != ',') || x < lo || x > hi)
            return 0;
        out[n++] = (int)x;
    }
    return n;
}

/* A comma list of names (at most count of them) as indices into names; 0 when one is
 * unknown or the list is empty. */
static int name_list(const char *v, const char *const *names, int count, int *out)
{
    int n = 0;
    for (const char *c = v; *c; c += strcspn(c, ","), c += *c == ',') {
        size_t len = strcspn(c, ",");
        int k = 0;
        while (k < count && (strlen(names[k]) != len || strncmp(c, names[k], len) != 0))
            k++;
        if (k == count || n == count)
            return 0;
        out[n++] = k;
    }
    return n;
}

typedef struct vpl_timing {
    double select_ms, shadow_ms, eye_ms, frame_ms;
} vpl_timing;

/* TIMED frames of fp from r (timer queries arrive a frame late); the last frame's indirect
 * image added into sum (when given) and its metrics in m; the medians in t. */
static int run(acc_setup *s, renderer *r, const frame_params *fp, const acc_reference *ref,
               float *last, image_metrics *m, vpl_timing *t)
{
    double sel[TIMED], sh[TIMED], eye[TIMED], frame[TIMED];
    renderer_image img = {0};
    for (int f = 0; f < TIMED; f++) {
        renderer_timings rt;
        if (acc_frame(s, r, fp, "vpl", &img, &rt) != 0)
            return -1;
        sel[f] = gi_stats_value(&rt.gi, "select", NULL);
        sh[f] = gi_stats_value(&rt.gi, "shadow", NULL);
        eye[f] = rt.eye_host_ms;
        frame[f] = rt.frame_host_ms + rt.eye_host_ms;
    }
    *t = (vpl_timing){acc_median(sel, TIMED), acc_median(sh, TIMED), acc_median(eye, TIMED),
                      acc_median(frame, TIMED)};
    size_t n = (size_t)s->opt.width * s->opt.height * 3;
    if (last)
        memcpy(last, img.indirect, n * sizeof *last);
    image_metrics_desc geometry = {.mask = ref->coverage, .reference_noise = ref->noise_rms_indirect1};
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

/* x with 4 decimals, or null when not measured (NaN). */
static const char *json_number(double x, char buf[32])
{
    snprintf(buf, 32, isnan(x) ? "null" : "%.4f", x);
    return buf;
}

/* settings (a renderer's, acc_renderer_create()) with count VPLs chosen by rule with seed. */
static frame_params vpl_frame(const frame_params *settings, int count, int seed,
                              vpl_selection rule)
{
    frame_params fp = *settings;
    gi_set_number(&fp, "vpl-count", count);
    gi_set_number(&fp, "vpl-seed", seed);
    gi_set(&fp, "vpl-selection", vpl_selection_names[rule]);
    return fp;
}

/* One count of VPLs with r[0] (the disk bound) and, when given, r[1] (points) and r[2] (no
 * cut), each with its settings: one CSV row and one JSON line. disk and point are scratch
 * images. */
static int measure(acc_setup *s, const acc_reference *ref, renderer *const r[3],
                   const frame_params settings[3], int count, int seeds, const vpl_timing *none,
                   float *disk, float *point, FILE *f, const acc_renderer_desc *rd,
                   vpl_selection rule)
{
    size_t n = (size_t)s->opt.width * s->opt.height * 3;
    memset(disk, 0, n * sizeof *disk);
    memset(point, 0, n * sizeof *point);
    double err = 0, err_debiased = 0, flip = 0, ssim = 0, scale = 0, sel[64], sh[64], gather[64], frame[64];
    int k = seeds < 64 ? seeds : 64;
    double *acc = calloc(6 * n, sizeof *acc), mean_ref = 0, cut_rel = NAN, cut_level = NAN;
    float *one[3] = {calloc(n, sizeof(float)), calloc(n, sizeof(float)), calloc(n, sizeof(float))};
    seed_sums sums[3] = {{acc, acc + n}, {acc + 2 * n, acc + 3 * n}, {acc + 4 * n, acc + 5 * n}};
    size_t covered = 0;
    for (size_t i = 0; i < n; i++) /* the relRMSE's divisor: the covered pixels' mean */
        if (ref->coverage[i / 3]) {
            mean_ref += ref->indirect1[i];
            covered++;
        }
    mean_ref /= (double)(covered ? covered : 1);
    int rc = acc && one[0] && one[1] && one[2] ? 0 : -1;
    for (int seed = 0; seed < k && rc == 0; seed++) {
        frame_params fp[3];
        for (int i = 0; i < 3; i++)
            fp[i] = vpl_frame(&settings[i], count, seed, rule);
        image_metrics m, unused;
        vpl_timing t, tp;
        if (run(s, r[0], &fp[0], ref, one[0], &m, &t) ||
            (r[1] && run(s, r[1], &fp[1], ref, one[1], &unused, &tp))) {
            rc = -1;
            break;
        }
        seed_add(&sums[0], one[0], NULL, n);      /* the disk estimate */
        if (r[1]) {
            seed_add(&sums[1], one[1], NULL, n);  /* the point estimate */
            seed_add(&sums[2], one[1], one[0], n); /* point - disk: the clamp */
        }
        if (seed == 0 && r[2]) {
            image_metrics mu;
            vpl_timing tu;
            if (run(s, r[2], &fp[2], ref, one[2], &mu, &tu) != 0) {
                rc = -1;
                break;
            }
            cut_rel = compare(s, ref, one[0], one[2], &cut_level);
        }
        err += m.rmse_rel / k;
        err_debiased += m.rmse_rel_debiased / k;
        flip += acc_flip(s, ref, one[0]) / k;
        ssim += m.ssim / k;
        scale += m.best_scale / k;
        sel[seed] = t.select_ms;
        sh[seed] = t.shadow_ms;
        gather[seed] = t.eye_ms - none->eye_ms;
        frame[seed] = t.frame_ms;
    }
    if (rc != 0) {
        free(acc);
        for (int i = 0; i < 3; i++)
            free(one[i]);
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        disk[i] = (float)(sums[0].sum[i] / k);
        point[i] = (float)(sums[1].sum[i] / k);
    }
    double ms[4] = {acc_median(sel, k), acc_median(sh, k), acc_median(gather, k),
                    acc_median(frame, k)};
    double level = NAN, mean_err_point = NAN, bias = NAN;
    double mean_err = compare(s, ref, disk, ref->indirect1, NULL);
    double ref_noise = ref->noise_rms_indirect1 / mean_ref, spread, spread_point = NAN;
    double disk_bias = NAN, clamp = NAN, truth = NAN;
    (void)seed_bias(&sums[0], ref->coverage, n, k, mean_ref, &spread);
    if (r[1]) {
        mean_err_point = compare(s, ref, point, ref->indirect1, NULL);
        bias = compare(s, ref, disk, point, &level);
        double spread_clamp;
        (void)seed_bias(&sums[1], ref->coverage, n, k, mean_ref, &spread_point);
        clamp = seed_bias(&sums[2], ref->coverage, n, k, mean_ref, &spread_clamp);
        disk_bias = sqrt(fmax(mean_err * mean_err - spread * spread / k - ref_noise * ref_noise,
                              0.0));
        truth = seed_error_vs_truth(err, ref_noise);
    }
    free(acc);
    for (int i = 0; i < 3; i++)
        free(one[i]);
    const char *vis = rd->vpl_visibility;
    char j[11][32];
    int ism = strcmp(rd->vpl_visibility, "exact") != 0;
    int size = ism ? rd->ism_size : 0, points = ism ? rd->ism_points : 0;
    fprintf(f, "%s,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.6g,%.5f,%.5f,%.6g,%.6g,%.6g,%.6g,%s,%d,%d,%d,"
            "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%s,%.6g,%.5f\n",
            s->opt.scene, count, k, ms[0], ms[1], ms[2], ms[0] + ms[1] + ms[2], ms[3], err, ssim,
            scale, mean_err, mean_err_point, level, bias, vis, size, points, rd->vpl_interleave,
            ref_noise, spread, disk_bias, clamp, truth, truth - clamp, cut_rel, cut_level,
            vpl_selection_names[rule], err_debiased, flip);
    printf("{\"bench\":\"accuracy\",\"experiment\":\"vpl\",\"scene\":\"%s\",\"width\":%d,"
           "\"height\":%d,\"reference_samples\":%d,\"reference_noise_indirect1\":%.6g,"
           "\"vpl_count\":%d,\"seeds\":%d,\"visibility\":\"%s\",\"ism_size\":%d,"
           "\"ism_points\":%d,\"interleave\":%d,\"select_ms\":%.3f,\"shadow_ms\":%.3f,"
           "\"gather_ms\":%.3f,\"gi_ms\":%.3f,\"frame_ms\":%.3f,\"rmse_rel\":%.4f,"
           "\"rmse_rel_debiased\":%.4f,\"flip\":%.4f,\"ssim\":%.4f,\"best_scale\":%.4f,\"rmse_rel_seed_mean\":%.4f,"
           "\"rmse_rel_seed_mean_point\":%s,\"bound_level_bias\":%s,"
           "\"bound_bias_rms\":%s,\"reference_noise_rel\":%.4f,\"vpl_spread_rel\":%.4f,"
           "\"point_spread_rel\":%s,\"disk_bias_rel\":%s,\"clamp_bias_rel\":%s,"
           "\"rmse_rel_truth\":%s,\"beyond_clamp\":%s,\"cut_bias_rel\":%s,"
           "\"cut_level_bias\":%s,\"selection\":\"%s\"}\n",
           s->opt.scene, s->opt.width, s->opt.height, 2 * ref->samples,
           ref->noise_indirect1, count, k, vis, size, points, rd->vpl_interleave, ms[0], ms[1], ms[2],
           ms[0] + ms[1] + ms[2], ms[3], err, err_debiased, flip, ssim, scale, mean_err,
           json_number(mean_err_point, j[0]), json_number(level, j[1]), json_number(bias, j[2]),
           ref_noise, spread, json_number(spread_point, j[3]), json_number(disk_bias, j[4]),
           json_number(clamp, j[5]), json_number(truth, j[6]), json_number(truth - clamp, j[7]),
           json_number(cut_rel, j[8]), json_number(cut_level, j[9]), vpl_selection_names[rule]);
    fflush(stdout);
    return 0;
}

int accuracy_vpl(int argc, char **argv)
{
    acc_options o = {.scene = "default", .out = "out/chart", .width = 160, .height = 120,
                     .ref_samples = 64};
    int counts[MAX_COUNTS] = {64, 256, 1024}, nc = 3, seeds = 2;
    static const char *const visibility_names[3] = {"exact", "ism", "ism-splat"};
    int vis[3] = {VPL_VISIBILITY_EXACT}, nv = 1;
    int sizes[MAX_LIST] = {32}, ns = 1;
    int points[MAX_LIST] = {1024}, np = 1;
    int blocks[MAX_LIST] = {0}, ni = 1;
    int rules[VPL_SELECT_COUNT] = {VPL_SELECT_FLUX}, nr = 1;
    const char *counts_text = "64,256,1024", *vis_text = "exact", *rules_text = "flux", *sizes_text = "32",
               *points_text = "1024", *blocks_text = "0";
    const bench_option opts[] = {
        ACC_COMMON_OPTIONS(&o),
        BENCH_TEXT("counts", "N,N,..", "VPL counts (each 64..4096)", &counts_text),
        BENCH_INT("seeds", "K", "seeds per setting (the error's spread)", &seeds, 1, 64),
        BENCH_TEXT("visibility", "V,V,..", "exact, ism, ism-splat", &vis_text),
        BENCH_TEXT("selection", "R,R,..", "flux, view, regular", &rules_text),
        BENCH_TEXT("ism-sizes", "N,N,..", "imperfect maps' sides (powers of two, 8..256)", &sizes_text),
        BENCH_TEXT("ism-points", "N,N,..", "points per imperfect map (64..16384)", &points_text),
        BENCH_TEXT("interleave", "K,K,..", "interleaving blocks (0..8; 0: none)", &blocks_text),
    };
    int parsed = BENCH_PARSE("accuracy vpl", "the vpl method's indirect error and GI ms per setting against "
                         "the path-traced reference\n  (scripts/chart.sh runs it)", opts, argc, argv);
    if (parsed != 0)
        return parsed > 0 ? 0 : 2;
    const char *bad = NULL;
    if (!(nc = int_list(counts_text, VPL_COUNT_MIN, VPL_COUNT_MAX, counts, MAX_COUNTS)))
        bad = "--counts";
    else if (!(nv = name_list(vis_text, visibility_names, 3, vis)))
        bad = "--visibility";
    else if (!(nr = name_list(rules_text, vpl_selection_names, VPL_SELECT_COUNT, rules)))
        bad = "--selection";
    else if (!(ns = int_list(sizes_text, VPL_ISM_SIZE_MIN, VPL_ISM_SIZE_MAX, sizes, MAX_LIST)))
        bad = "--ism-sizes";
    else if (!(np = int_list(points_text, VPL_ISM_POINTS_MIN, VPL_ISM_POINTS_MAX, points, MAX_LIST)))
        bad = "--ism-points";
    else if (!(ni = int_list(blocks_text, 0, VPL_INTERLEAVE_MAX, blocks, MAX_LIST)))
        bad = "--interleave";
    for (int k = 0; !bad && k < ns; k++)
        if (sizes[k] & (sizes[k] - 1))
            bad = "--ism-sizes";
    if (bad) {
        fprintf(stderr, "bench accuracy vpl: %s: a value out of range or unknown (see --help)\n", bad);
        return 2;
    }
    acc_setup s;
    if (acc_setup_open(&s, &o) != 0)
        return 1;
    acc_reference ref;
    if (acc_reference_get(&s, &s.base, "a", &ref) != 0) {
        acc_setup_close(&s);
        return 1;
    }
    size_t n = (size_t)o.width * o.height * 3;
    float *disk = calloc(n, sizeof *disk), *point = calloc(n, sizeof *point);
    frame_params fp = s.base;
    renderer *none_r = acc_renderer_create(&s, &(acc_renderer_desc){.gi = "none"}, &fp);
    FILE *f = acc_open_csv(&s, "vpl",
        "scene,vpl_count,seeds,select_ms,shadow_ms,gather_ms,gi_ms,frame_ms,"
        "rmse_rel_indirect,ssim_indirect,best_scale_indirect,rmse_rel_seed_mean,"
        "rmse_rel_seed_mean_point,bound_level_bias,bound_bias_rms,visibility,ism_size,"
        "ism_points,interleave,reference_noise_rel,vpl_spread_rel,disk_bias_rel,clamp_bias_rel,"
        "rmse_rel_truth,beyond_clamp,cut_bias_rel,cut_level_bias,selection,"
        "rmse_rel_debiased_indirect,flip_indirect");
    int rc = disk && point && none_r && f ? 0 : 1;
    /* The shading pass without indirect light: the gather's baseline. */
    vpl_timing none;
    if (rc == 0)
        rc = run(&s, none_r, &fp, &ref, NULL, NULL, &none);
    for (int c = 0; c < nr * nv * ns * np * ni && rc == 0; c++) {
        vpl_selection rule = (vpl_selection)rules[c / (nv * ns * np * ni)];
        acc_renderer_desc rd = {.gi = "vpl",
                                .vpl_visibility = visibility_names[vis[c / (ns * np * ni) % nv]],
                                .ism_size = sizes[c / (np * ni) % ns],
                                .ism_points = points[c / ni % np],
                                .vpl_interleave = blocks[c % ni]};
        int exact = strcmp(rd.vpl_visibility, "exact") == 0;
        if (exact && c / ni % (ns * np) != 0)
            continue; /* the ISM settings do not change exact maps */
        int bias = exact && rd.vpl_interleave == 0 && rule == VPL_SELECT_FLUX;
        frame_params settings[3] = {s.base, s.base, s.base};
        renderer *r[3] = {acc_renderer_create(&s, &rd, &settings[0]), NULL, NULL};
        if (bias) {
            acc_renderer_desc as_points = rd, uncut = rd;
            as_points.vpl_point = 1;
            uncut.vpl_cut = -1;
            r[1] = acc_renderer_create(&s, &as_points, &settings[1]);
            r[2] = acc_renderer_create(&s, &uncut, &settings[2]);
        }
        rc = r[0] && ((r[1] && r[2]) || !bias) ? 0 : 1;
        for (int k = 0; k < nc && rc == 0; k++)
            rc = measure(&s, &ref, r, settings, counts[k], seeds, &none, disk, point, f, &rd,
                         rule);
        for (int i = 0; i < 3; i++)
            if (r[i])
                renderer_destroy(r[i]);
    }
    if (f)
        fclose(f);
    if (none_r)
        renderer_destroy(none_r);
    free(disk);
    free(point);
    acc_reference_free(&ref);
    acc_setup_close(&s);
    return rc;
}
#else
typedef int accuracy_vpl_unused;
#endif
