/* cavelight-bench accuracy caches: the caches method (node/gi/caches/gi_caches.h) per
 * setting row, for scripts/chart.sh, and the high-res RSM paper's comparison.
 *
 * Rows: every RSM size of --rsm (default 256), cache density of --densities (default 0,
 * auto), occlusion of --occlusion (default approx,exact) and VAL count of --vals (default
 * 512,2048,8192), each value checked as the node checks it (gi_set()); with --lightskin
 * (default 1) first a row with every RSM texel as a VAL (caches-selection all: plain
 * LightSkin) per RSM size, density and occlusion but exact (whose rays per texel the
 * settings refuse). Each row renders --frames frames (default 3) of the scene's camera:
 * the GI stages' medians (importance, sat_select, proxy, occlusion, interpolate; gi_ms
 * their sum), the whole frame's ms, the indirect image's relative RMSE, SSIM and best scale
 * against the reference's one-bounce image over the pixels that meet geometry (as every
 * accuracy experiment), the reference's own noise (RMS of its halves' difference / 2 over
 * its mean), and for a selected row the paper's comparison with the every-texel row of
 * the same RSM size, density and occlusion: its relRMSE against that image
 * (rmse_rel_vs_all), the difference of their errors against the reference, and the
 * speed-up (its GI ms over this row's).
 * Writes <out>/caches_<scene>.csv and prints one JSON line per row.
 *
 * With --temporal 1 (the default) also, with the defaults but --temporal-vals VALs
 * (default 2048) and --temporal-frames frames at
 * 60 Hz each (default 30): a static frame computed twice (identical images and checksums?);
 * the light moving at walking speed (0.5 m/s on a 0.5 m circle as accuracy path; a
 * directional light turning so that a point half the scene's diagonal away walks at that
 * speed); the tracked head walking at 1 m/s along the view's right axis while the camera
 * stays, so that every change of the image is the selection following the head (the
 * paper's flicker). Per frame the mean absolute change of the indirect and of the direct
 * image from the frame before over their means: <out>/caches_temporal_<scene>.csv and one
 * JSON line with the largest of each. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "bench_accuracy.h"
#include "gi/caches/caches_settings.h"

enum { MAX_ITEMS = 8, MAX_FRAMES = 64, STAGES = 5 };
static const char *const STAGE_NAMES[STAGES] = {"importance", "sat_select", "proxy",
                                                "occlusion", "interpolate"};

/* A comma list into items (at most MAX_ITEMS of 32 characters); its length, 0 when bad. */
static int split(const char *text, char items[MAX_ITEMS][32])
{
    int n = 0;
    for (const char *c = text; *c; c += strcspn(c, ","), c += *c == ',') {
        size_t len = strcspn(c, ",");
        if (n == MAX_ITEMS || len == 0 || len >= 32)
            return 0;
        memcpy(items[n], c, len);
        items[n++][len] = 0;
    }
    return n;
}

/* One row's figures. */
typedef struct row_result {
    double stage[STAGES], gi_ms, frame_ms;
    image_metrics m;
    double flip;
    size_t caches;
} row_result;

/* frames frames of fp; the last indirect image into image, the medians and metrics. */
static int run(acc_setup *s, renderer *r, const frame_params *fp, int frames,
               const acc_reference *ref, float *image, row_result *out)
{
    double stage[STAGES][MAX_FRAMES], gi_ms[MAX_FRAMES], frame[MAX_FRAMES];
    renderer_image img = {0};
    for (int f = 0; f < frames; f++) {
        renderer_timings t;
        if (acc_frame(s, r, fp, "caches", &img, &t) != 0)
            return -1;
        for (int k = 0; k < STAGES; k++)
            stage[k][f] = gi_stats_value(&t.gi, STAGE_NAMES[k], NULL);
        gi_ms[f] = gi_stats_total_ms(&t.gi);
        frame[f] = t.frame_host_ms + t.eye_host_ms;
        out->caches = (size_t)gi_stats_value(&t.gi, "caches", NULL);
    }
    for (int k = 0; k < STAGES; k++)
        out->stage[k] = acc_median(stage[k], frames);
    out->gi_ms = acc_median(gi_ms, frames);
    out->frame_ms = acc_median(frame, frames);
    memcpy(image, img.indirect, (size_t)s->opt.width * s->opt.height * 3 * sizeof *image);
    image_metrics_desc geometry = {.mask = ref->coverage, .reference_noise = ref->noise_rms_indirect1};
    if (image_metrics_compare(image, ref->indirect1, s->opt.width, s->opt.height, &geometry,
                              &out->m) != 0) {
        fprintf(stderr, "bench accuracy caches: %s: no pixel meets geometry\n", s->opt.scene);
        return -1;
    }
    out->flip = acc_flip(s, ref, image);
    return 0;
}

typedef struct sweep {
    acc_setup *s;
    const acc_reference *ref;
    double noise_rel;       /* the reference's noise over its mean */
    FILE *csv;
    int frames;
    float *image, *all;     /* this row's image, the every-texel row's */
    int have_all;
    row_result all_result;
} sweep;

/* One row: fp (its settings set) on r, a CSV row and a JSON line. */
static int row(sweep *w, renderer *r, const frame_params *fp)
{
    row_result x;
    if (run(w->s, r, fp, w->frames, w->ref, w->image, &x) != 0)
        return -1;
    char rsm[16], density[32], occlusion[16], selection[16], vals[16];
    gi_get_text(fp, "rsm", rsm, sizeof rsm);
    gi_get_text(fp, "caches-density", density, sizeof density);
    gi_get_text(fp, "caches-occlusion", occlusion, sizeof occlusion);
    gi_get_text(fp, "caches-selection", selection, sizeof selection);
    gi_get_text(fp, "caches-vals", vals, sizeof vals);
    int every = strcmp(selection, "all") == 0;
    double vs_all = NAN, diff = NAN, speedup = NAN;
    if (every) {
        memcpy(w->all, w->image, (size_t)w->s->opt.width * w->s->opt.height * 3 * sizeof *w->all);
        w->all_result = x;
        w->have_all = 1;
    } else if (w->have_all) {
        image_metrics m;
        image_metrics_desc geometry = {.mask = w->ref->coverage};
        if (image_metrics_compare(w->image, w->all, w->s->opt.width, w->s->opt.height,
                                  &geometry, &m) == 0)
            vs_all = m.rmse_rel;
        diff = x.m.rmse_rel - w->all_result.m.rmse_rel;
        speedup = x.gi_ms > 0 ? w->all_result.gi_ms / x.gi_ms : NAN;
    }
    const char *name = every ? "all" : vals;
    fprintf(w->csv, "%s,%s,%s,%s,%s,%s,%zu", w->s->opt.scene, name, selection, occlusion,
            density, rsm, x.caches);
    for (int k = 0; k < STAGES; k++)
        fprintf(w->csv, ",%.3f", x.stage[k]);
    fprintf(w->csv, ",%.3f,%.3f,%.6g,%.5f,%.5f,%.6g,%.6g,%.6g,%.4g,%.6g,%.5f\n", x.gi_ms,
            x.frame_ms, x.m.rmse_rel, x.m.ssim, x.m.best_scale, w->noise_rel, vs_all, diff,
            speedup, x.m.rmse_rel_debiased, x.flip);
    printf("{\"bench\":\"accuracy\",\"experiment\":\"caches\",\"scene\":\"%s\",\"width\":%d,"
           "\"height\":%d,\"reference_samples\":%d,\"vals\":\"%s\",\"occlusion\":\"%s\","
           "\"density\":%s,\"rsm\":%s,\"caches\":%zu", w->s->opt.scene, w->s->opt.width,
           w->s->opt.height, 2 * w->ref->samples, name, occlusion, density, rsm, x.caches);
    for (int k = 0; k < STAGES; k++)
        printf(",\"%s_ms\":%.3f", STAGE_NAMES[k], x.stage[k]);
    printf(",\"gi_ms\":%.3f,\"frame_ms\":%.3f,\"rmse_rel\":%.4f,\"rmse_rel_debiased\":%.4f,"
           "\"flip\":%.4f,\"ssim\":%.4f,\"best_scale\":%.4f,\"reference_noise_rel\":%.4f",
           x.gi_ms, x.frame_ms, x.m.rmse_rel, x.m.rmse_rel_debiased, x.flip, x.m.ssim,
           x.m.best_scale, w->noise_rel);
    if (!isnan(speedup))
        printf(",\"rmse_rel_vs_all\":%.4f,\"rmse_rel_minus_all\":%.4f,\"speedup\":%.3f", vs_all,
               diff, speedup);
    printf("}\n");
    fflush(stdout);
    return 0;
}

typedef struct lists {
    char rsm[MAX_ITEMS][32], density[MAX_ITEMS][32], occlusion[MAX_ITEMS][32],
        vals[MAX_ITEMS][32];
    int nr, nd, no, nv, lightskin, temporal;
} lists;

/* Every row of one RSM size and density, with one renderer. */
static int rows_of(sweep *w, const lists *l, const char *rsm, const char *density)
{
    frame_params fp = w->s->base;
    gi_set(&fp, "rsm", rsm);
    gi_set(&fp, "caches-density", density);
    renderer *r = acc_renderer_create(w->s, &(acc_renderer_desc){.gi = "caches"}, &fp);
    int rc = r ? 0 : -1;
    for (int o = 0; o < l->no && rc == 0; o++) {
        gi_set(&fp, "caches-occlusion", l->occlusion[o]);
        w->have_all = 0;
        if (l->lightskin && strcmp(l->occlusion[o], "exact") != 0) {
            gi_set(&fp, "caches-selection", "all");
            rc = row(w, r, &fp);
        }
        gi_set(&fp, "caches-selection", "importance");
        for (int v = 0; v < l->nv && rc == 0; v++) {
            gi_set(&fp, "caches-vals", l->vals[v]);
            rc = row(w, r, &fp);
        }
    }
    if (r)
        renderer_destroy(r);
    return rc;
}

/* Each item of a list as the setting name would take it (the node's own check). */
static int check(const char *name, char items[MAX_ITEMS][32], int n)
{
    frame_params p;
    frame_params_default(&p);
    for (int i = 0; i < n; i++) {
        const char *why = gi_set(&p, name, items[i]);
        if (why) {
            fprintf(stderr, "bench accuracy caches: %s %s: %s\n", name, items[i], why);
            return -1;
        }
    }
    return n ? 0 : -1;
}

static int parse(int argc, char **argv, acc_options *o, lists *l, int *frames, int motion[2])
{
    const char *rsm = "256", *density = "0", *occlusion = "approx,exact",
               *vals = "512,2048,8192";
    l->lightskin = l->temporal = 1;
    const bench_option opts[] = {
        ACC_COMMON_OPTIONS(o),
        BENCH_TEXT("rsm", "N,...", "RSM sizes", &rsm),
        BENCH_TEXT("densities", "D,...", "cache densities per m^2 (0: auto)", &density),
        BENCH_TEXT("occlusion", "approx|exact|off,...", "occlusion variants", &occlusion),
        BENCH_TEXT("vals", "N,...", "VAL counts of the importance selection", &vals),
        BENCH_INT("lightskin", "0|1", "also every RSM texel as a VAL (plain LightSkin)",
                  &l->lightskin, 0, 1),
        BENCH_INT("frames", "N", "frames per row (medians)", frames, 1, MAX_FRAMES),
        BENCH_INT("temporal", "0|1", "also the temporal measures", &l->temporal, 0, 1),
        BENCH_INT("temporal-frames", "N", "frames of each motion", &motion[0], 2, 100000),
        BENCH_INT("temporal-vals", "N", "VALs of the temporal measures", &motion[1],
                  CACHES_VALS_MIN, CACHES_VALS_MAX),
    };
    int rc = BENCH_PARSE("accuracy caches", "the caches method per setting row against the "
                         "reference, and importance-sampled VALs against every RSM texel",
                         opts, argc, argv);
    if (rc)
        return rc;
    l->nr = split(rsm, l->rsm);
    l->nd = split(density, l->density);
    l->no = split(occlusion, l->occlusion);
    l->nv = split(vals, l->vals);
    if (check("rsm", l->rsm, l->nr) || check("caches-density", l->density, l->nd) ||
        check("caches-occlusion", l->occlusion, l->no) || check("caches-vals", l->vals, l->nv))
        return -1;
    return 0;
}

/* Mean |a - b| over mean |b| of two linear images of n floats. */
static double change(const float *a, const float *b, size_t n)
{
    double d = 0, m = 0;
    for (size_t i = 0; i < n; i++) {
        d += fabs((double)a[i] - b[i]);
        m += fabs((double)b[i]);
    }
    return m > 0 ? d / m : 0.0;
}

/* Frame f of a motion: 0 the light moves, 1 the head. */
static void move(const acc_setup *s, frame_params *fp, int motion, int f)
{
    const double speed = 0.5, radius = 0.5, head_speed = 1.0;
    double t = f / 60.0;
    if (motion == 1) {
        for (int k = 0; k < 3; k++) /* the view's right axis (view matrix row 0) */
            fp->head[12 + k] = s->view.eye_position[k] + (float)(head_speed * t) * s->view.view[4 * k];
        return;
    }
    frame_light *l = &fp->lights[0];
    const frame_light *l0 = &s->base.lights[0];
    if (l->type == SCENE_LIGHT_DIRECTIONAL) {
        double a = speed * t / (0.5 * scene_diagonal(&s->sc));
        l->direction[0] = (float)(l0->direction[0] * cos(a) - l0->direction[2] * sin(a));
        l->direction[2] = (float)(l0->direction[0] * sin(a) + l0->direction[2] * cos(a));
        return;
    }
    double a = speed * t / radius;
    l->position[0] = l0->position[0] + (float)(radius * (cos(a) - 1.0));
    l->position[2] = l0->position[2] + (float)(radius * sin(a));
}

/* The temporal measures (see the top). */
static int temporal(acc_setup *s, int frames, int vals)
{
    size_t n = (size_t)s->opt.width * s->opt.height * 3;
    frame_params fp = s->base;
    gi_set_number(&fp, "caches-vals", vals);
    renderer *r = acc_renderer_create(s, &(acc_renderer_desc){.gi = "caches"}, &fp);
    float *prev[2] = {malloc(n * sizeof(float)), malloc(n * sizeof(float))};
    FILE *csv = acc_open_csv(s, "caches_temporal", "scene,motion,frame,change_indirect,change_direct");
    int rc = r && prev[0] && prev[1] && csv ? 0 : -1;
    double largest[2][2] = {{0, 0}, {0, 0}}, static_change = -1;
    uint64_t sums[2] = {0, 0};
    renderer_image img;
    for (int motion = -1; motion < 2 && rc == 0; motion++)
        for (int f = 0; f < (motion < 0 ? 2 : frames) && rc == 0; f++) {
            frame_params p = fp;
            if (motion >= 0)
                move(s, &p, motion, f);
            renderer_frame_pass(r, &p);
            uint64_t sum = renderer_checksum_complete(r); /* READY's GPU part, this frame's */
            if ((rc = renderer_eye_pass(r, &s->view, 1, &img)) != 0)
                break;
            double ci = f ? change(img.indirect, prev[0], n) : 0;
            double cd = f ? change(img.direct, prev[1], n) : 0;
            if (motion < 0) {
                sums[f] = sum;
                static_change = ci;
            } else if (f) {
                largest[motion][0] = fmax(largest[motion][0], ci);
                largest[motion][1] = fmax(largest[motion][1], cd);
                fprintf(csv, "%s,%s,%d,%.6g,%.6g\n", s->opt.scene, motion ? "head" : "light", f,
                        ci, cd);
            }
            memcpy(prev[0], img.indirect, n * sizeof(float));
            memcpy(prev[1], img.direct, n * sizeof(float));
        }
    if (rc == 0)
        printf("{\"bench\":\"accuracy\",\"experiment\":\"caches_temporal\",\"scene\":\"%s\","
               "\"frames\":%d,\"vals\":%d,\"static_identical\":%s,\"static_change_indirect\":%.6g,"
               "\"light_max_change_indirect\":%.6g,\"light_max_change_direct\":%.6g,"
               "\"head_max_change_indirect\":%.6g,\"head_max_change_direct\":%.6g}\n",
               s->opt.scene, frames, vals, sums[0] == sums[1] && static_change == 0 ? "true" : "false",
               static_change, largest[0][0], largest[0][1], largest[1][0], largest[1][1]);
    if (csv)
        fclose(csv);
    free(prev[0]);
    free(prev[1]);
    if (r)
        renderer_destroy(r);
    return rc;
}

int accuracy_caches(int argc, char **argv)
{
    acc_options o = {.scene = "default", .out = "out/chart", .width = 160, .height = 120,
                     .ref_samples = 64};
    lists l;
    int frames = 3, motion[2] = {30, CACHES_VALS_DEFAULT};
    int pr = parse(argc, argv, &o, &l, &frames, motion);
    if (pr)
        return pr > 0 ? 0 : 2;
    acc_setup s;
    if (acc_setup_open(&s, &o) != 0)
        return 1;
    acc_reference ref;
    if (acc_reference_get(&s, &s.base, "a", &ref) != 0) {
        acc_setup_close(&s);
        return 1;
    }
    size_t n = (size_t)o.width * o.height * 3;
    sweep w = {.s = &s, .ref = &ref, .frames = frames, .image = calloc(n, sizeof(float)),
               .all = calloc(n, sizeof(float))};
    double mean = 0; /* over the covered pixels, the relRMSE's divisor */
    size_t covered = 0;
    for (size_t i = 0; i < n; i++)
        if (ref.coverage[i / 3])
            mean += ref.indirect1[i], covered++;
    mean /= (double)(covered ? covered : 1);
    w.noise_rel = mean > 0 ? ref.noise_rms_indirect1 / mean : NAN;
    w.csv = acc_open_csv(&s, "caches",
                         "scene,vals,selection,occlusion,density,rsm,caches,importance_ms,"
                         "sat_select_ms,proxy_ms,occlusion_ms,interpolate_ms,gi_ms,frame_ms,"
                         "rmse_rel_indirect,ssim_indirect,best_scale_indirect,"
                         "reference_noise_rel,rmse_rel_vs_all,rmse_rel_minus_all,speedup,"
                         "rmse_rel_debiased_indirect,flip_indirect");
    int rc = w.image && w.all && w.csv ? 0 : 1;
    for (int k = 0; k < l.nr * l.nd && rc == 0; k++)
        rc = rows_of(&w, &l, l.rsm[k / l.nd], l.density[k % l.nd]) ? 1 : 0;
    if (rc == 0 && l.temporal)
        rc = temporal(&s, motion[0], motion[1]) ? 1 : 0;
    if (w.csv)
        fclose(w.csv);
    free(w.image);
    free(w.all);
    acc_reference_free(&ref);
    acc_setup_close(&s);
    return rc;
}
#else
typedef int accuracy_caches_unused;
#endif
