/* cavelight-bench accuracy ldm: the layered depth maps (issue 23) against the path-traced
 * reference, for scripts/chart.sh.
 *
 *   indirect  the ldm method (node/gi/ldm/gi_ldm.h) for each maps configuration of
 *             --configs (directions:resolution, default 16:64,32:128,64:128) at
 *             --photons (default 32): the indirect image's relative RMSE against the
 *             reference's one-bounce image over the pixels that meet geometry (as the
 *             sweep measures ILPV and vpl), its GI ms (frame pass: maps rebuilt every
 *             frame as a moving scene needs them, photons, split; plus the eye pass's
 *             splat) and whole-frame ms, medians of TIMED frames; the maps' MB.
 *   ao        ambient occlusion (frame/ao.h) at each distance limit of --distances
 *             (metres, default 0.25,0.5,1,2; occlusion): the screen-space baseline and
 *             the LDM AO for each configuration of --ao-configs (default 32:64,64:128,
 *             128:128), each the AO image's relative RMSE and MAE against the path
 *             tracer's AO (the same distance and falloff, 2 x --ref-samples rays) over the
 *             covered pixels, and the eye pass's AO ms (median); LDM: its maps' build ms
 *             (once) and MB.
 * Writes <out>/ldm_<scene>.csv and <out>/ao_<scene>.csv and prints one JSON line per row. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "bench_accuracy.h"
#include "gi/ldm/ldm_directions.h"
#include "gi/ldm/ldm_map.h"
#include "reference/reference.h"

enum { MAX_CONFIGS = 8, TIMED = 3 };

/* "16:64,32:128": pairs of directions and resolution in their ranges; how many, 0 if bad. */
static int pairs(const char *v, int (*out)[2])
{
    int n = 0;
    for (const char *c = v; *c; c += strcspn(c, ","), c += *c == ',') {
        int d, r, used = 0;
        if (n == MAX_CONFIGS || sscanf(c, "%d:%d%n", &d, &r, &used) != 2 ||
            (c[used] && c[used] != ',') || d < LDM_DIRECTIONS_MIN || d > LDM_DIRECTIONS_MAX ||
            r < LDM_RESOLUTION_MIN || r > LDM_RESOLUTION_MAX)
            return 0;
        out[n][0] = d;
        out[n++][1] = r;
    }
    return n;
}

/* Positive numbers, comma separated; how many, 0 if bad. */
static int numbers(const char *v, double *out)
{
    int n = 0;
    for (const char *c = v; *c; c += strcspn(c, ","), c += *c == ',') {
        char *end;
        double x = strtod(c, &end);
        if (n == MAX_CONFIGS || end == c || (*end && *end != ',') || !(x > 0))
            return 0;
        out[n++] = x;
    }
    return n;
}

typedef struct timing {
    double gi_ms, frame_ms, ao_ms;
    gi_stats last;
    renderer_ao_stats ao;
} timing;

/* TIMED frames of fp; the last frame's indirect and AO images copied out (when given). */
static int run(acc_setup *s, renderer *r, const frame_params *fp, float *indirect, float *ao,
               timing *t)
{
    double gims[TIMED], frame[TIMED], aoms[TIMED];
    renderer_image img = {0};
    for (int f = 0; f < TIMED; f++) {
        renderer_timings rt;
        if (acc_frame(s, r, fp, "ldm", &img, &rt) != 0)
            return -1;
        gims[f] = gi_stats_total_ms(&rt.gi) + gi_stats_value(&rt.gi, "splat_ms", NULL);
        frame[f] = rt.frame_host_ms + rt.eye_host_ms;
        aoms[f] = rt.ao.eye_ms;
        t->last = rt.gi;
        t->ao = rt.ao;
    }
    t->gi_ms = acc_median(gims, TIMED);
    t->frame_ms = acc_median(frame, TIMED);
    t->ao_ms = acc_median(aoms, TIMED);
    size_t n = (size_t)s->opt.width * s->opt.height * 3;
    if (indirect)
        memcpy(indirect, img.indirect, n * sizeof *indirect);
    if (ao && img.ao)
        memcpy(ao, img.ao, n * sizeof *ao);
    return 0;
}

static renderer *create(acc_setup *s, const frame_params *fp)
{
    char err[512];
    renderer_desc rd = {.gl = glctx_gl(s->ctx), .scene = &s->sc, .first = fp,
                        .threads = s->opt.threads, .no_reuse = 1};
    renderer *r = renderer_create(&rd, err, sizeof err);
    if (!r)
        fprintf(stderr, "bench accuracy ldm: %s\n", err);
    return r;
}

static int indirect_rows(acc_setup *s, const acc_reference *ref, const int (*cfg)[2], int n,
                         int photons, const char *spread, float *img)
{
    FILE *f = acc_open_csv(s, "ldm", "scene,directions,resolution,photons,construct_ms,"
                           "photons_ms,trace_ms,splat_ms,gi_ms,frame_ms,memory_mb,"
                           "rmse_rel_indirect,ssim_indirect,best_scale_indirect,"
                           "rmse_rel_debiased_indirect,flip_indirect");
    int rc = f ? 0 : -1;
    for (int c = 0; c < n && rc == 0; c++) {
        frame_params fp = s->base;
        gi_set(&fp, "gi", "ldm");
        gi_set_number(&fp, "ldm-directions", cfg[c][0]);
        gi_set_number(&fp, "ldm-resolution", cfg[c][1]);
        gi_set_number(&fp, "ldm-photons", photons);
        renderer *r = create(s, &fp);
        timing t;
        image_metrics m;
        image_metrics_desc geometry = {.mask = ref->coverage,
                                       .reference_noise = ref->noise_rms_indirect1};
        rc = !r || run(s, r, &fp, img, NULL, &t) ||
             image_metrics_compare(img, ref->indirect1, s->opt.width, s->opt.height, &geometry, &m);
        if (r)
            renderer_destroy(r);
        if (rc)
            break;
        double fl = acc_flip(s, ref, img);
        const gi_stats *g = &t.last;
        double st[4] = {gi_stats_value(g, "construct", NULL), gi_stats_value(g, "photons", NULL),
                        gi_stats_value(g, "trace", NULL), gi_stats_value(g, "splat_ms", NULL)};
        double mb = gi_stats_value(g, "memory_mb", NULL);
        fprintf(f, "%s,%d,%d,%d,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.6g,%.6g,%.5f,%.5f,%.6g,%.5f\n",
                s->opt.scene, cfg[c][0], cfg[c][1], photons, st[0], st[1], st[2], st[3], t.gi_ms,
                t.frame_ms, mb, m.rmse_rel, m.ssim, m.best_scale, m.rmse_rel_debiased, fl);
        printf("{\"bench\":\"accuracy\",\"experiment\":\"ldm\",\"scene\":\"%s\",\"width\":%d,"
               "\"height\":%d,\"directions\":%d,\"resolution\":%d,\"photons\":%d,\"spread\":\"%s\","
               "\"construct_ms\":%.3f,\"photons_ms\":%.3f,\"trace_ms\":%.3f,\"splat_ms\":%.3f,"
               "\"gi_ms\":%.3f,\"frame_ms\":%.3f,\"memory_mb\":%.6g,\"rmse_rel\":%.4f,"
               "\"rmse_rel_debiased\":%.4f,\"flip\":%.4f,\"ssim\":%.4f,\"best_scale\":%.4f}\n", s->opt.scene,
               s->opt.width, s->opt.height, cfg[c][0], cfg[c][1], photons, spread, st[0], st[1],
               st[2], st[3], t.gi_ms, t.frame_ms, mb, m.rmse_rel, m.rmse_rel_debiased, fl, m.ssim,
               m.best_scale);
        fflush(stdout);
    }
    if (f)
        fclose(f);
    return rc;
}

/* The path tracer's AO of fp's distance and falloff, and its coverage, into ao / mask. */
static int reference_ao(acc_setup *s, const frame_params *fp, float *ao, uint8_t *mask)
{
    char err[512];
    reference *ref = reference_create(&s->sc, s->opt.threads, err, sizeof err);
    reference_images img = {0};
    reference_noise noise;
    reference_render_desc rd = {.params = fp, .view = &s->view, .samples = s->opt.ref_samples,
                                .max_bounces = 1, .seed = 1};
    int rc = !ref || reference_render_averaged(ref, &rd, &img, &noise, err, sizeof err);
    if (rc) {
        fprintf(stderr, "bench accuracy ldm: %s\n", err);
    } else {
        size_t px = (size_t)s->opt.width * s->opt.height;
        memcpy(ao, img.ao, px * 3 * sizeof *ao);
        memcpy(mask, img.coverage, px);
    }
    reference_images_free(&img);
    reference_destroy(ref);
    return rc ? -1 : 0;
}

/* One AO row: method ("ssao" or "ldm", its maps cfg) at distance d against want. */
static int ao_row(acc_setup *s, FILE *f, const char *method, const int *cfg, double d,
                  const float *want, const uint8_t *mask, float *img)
{
    frame_params fp = s->base;
    gi_set(&fp, "gi", "none");
    gi_set(&fp, "ao", method);
    gi_set_number(&fp, "ao-distance", d);
    if (cfg) {
        gi_set_number(&fp, "ao-directions", cfg[0]);
        gi_set_number(&fp, "ao-resolution", cfg[1]);
    }
    renderer *r = create(s, &fp);
    timing t;
    image_metrics m;
    image_metrics_desc geometry = {.mask = mask};
    int rc = !r || run(s, r, &fp, NULL, img, &t) ||
             image_metrics_compare(img, want, s->opt.width, s->opt.height, &geometry, &m);
    if (r)
        renderer_destroy(r);
    if (rc)
        return -1;
    int dirs = cfg ? cfg[0] : 0, res = cfg ? cfg[1] : 0;
    fprintf(f, "%s,%s,%g,%d,%d,%.3f,%.3f,%.6g,%.6g,%.6g,%.5f\n", s->opt.scene, method, d, dirs,
            res, t.ao_ms, t.ao.build_ms, t.ao.memory_mb, m.rmse_rel, m.mae, m.ssim);
    printf("{\"bench\":\"accuracy\",\"experiment\":\"ao\",\"scene\":\"%s\",\"method\":\"%s\","
           "\"distance\":%g,\"directions\":%d,\"resolution\":%d,\"ao_ms\":%.3f,"
           "\"build_ms\":%.3f,\"memory_mb\":%.6g,\"rmse_rel\":%.4f,\"mae\":%.4f,\"ssim\":%.4f}\n",
           s->opt.scene, method, d, dirs, res, t.ao_ms, t.ao.build_ms, t.ao.memory_mb,
           m.rmse_rel, m.mae, m.ssim);
    fflush(stdout);
    return 0;
}

static int ao_rows(acc_setup *s, const int (*cfg)[2], int n, const double *dist, int nd,
                   float *img)
{
    size_t px = (size_t)s->opt.width * s->opt.height;
    float *want = malloc(px * 3 * sizeof *want);
    uint8_t *mask = malloc(px);
    FILE *f = acc_open_csv(s, "ao", "scene,method,distance,directions,resolution,ao_ms,"
                           "build_ms,memory_mb,rmse_rel,mae,ssim");
    int rc = want && mask && f ? 0 : -1;
    for (int k = 0; k < nd && rc == 0; k++) {
        frame_params fp = s->base;
        gi_set(&fp, "ao", "ldm");
        gi_set_number(&fp, "ao-distance", dist[k]);
        rc = reference_ao(s, &fp, want, mask);
        if (rc == 0)
            rc = ao_row(s, f, "ssao", NULL, dist[k], want, mask, img);
        for (int c = 0; c < n && rc == 0; c++)
            rc = ao_row(s, f, "ldm", cfg[c], dist[k], want, mask, img);
    }
    if (f)
        fclose(f);
    free(want);
    free(mask);
    return rc;
}

int accuracy_ldm(int argc, char **argv)
{
    acc_options o = {.scene = "default", .out = "out/chart", .width = 160, .height = 120,
                     .ref_samples = 64};
    const char *configs = "16:64,32:128,64:128", *ao_configs = "32:64,64:128,128:128";
    const char *distances = "0.25,0.5,1,2";
    int photons = 32;
    const char *spread = NULL; /* the method's default */
    const bench_option opts[] = {
        ACC_COMMON_OPTIONS(&o),
        BENCH_TEXT("configs", "D:R,...", "the ldm method's maps: directions:resolution", &configs),
        BENCH_INT("photons", "N", "the ldm method's photons per side of a light view", &photons,
                  4, 256),
        BENCH_TEXT("spread", "light|cell", "the ldm method's footprint widening (ldm-spread); "
                   "none: the node's default", &spread),
        BENCH_TEXT("ao-configs", "D:R,...", "the LDM AO's maps: directions:resolution",
                   &ao_configs),
        BENCH_TEXT("distances", "M,...", "AO distance limits, metres", &distances),
    };
    int parsed = BENCH_PARSE("accuracy ldm", "layered depth maps: indirect light and AO against "
                             "the path tracer", opts, argc, argv);
    if (parsed != 0)
        return parsed > 0 ? 0 : 2;
    int cfg[MAX_CONFIGS][2], ao_cfg[MAX_CONFIGS][2];
    double dist[MAX_CONFIGS];
    int n = pairs(configs, cfg), na = pairs(ao_configs, ao_cfg), nd = numbers(distances, dist);
    if (!n || !na || !nd) {
        fprintf(stderr, "bench accuracy ldm: --configs and --ao-configs take directions:resolution "
                "pairs (%d..%d, %d..%d), --distances positive metres\n", LDM_DIRECTIONS_MIN,
                LDM_DIRECTIONS_MAX, LDM_RESOLUTION_MIN, LDM_RESOLUTION_MAX);
        return 2;
    }
    acc_setup s;
    if (acc_setup_open(&s, &o) != 0)
        return 1;
    const char *why = spread ? gi_set(&s.base, "ldm-spread", spread) : NULL;
    if (why) {
        fprintf(stderr, "bench accuracy ldm: --spread %s: %s\n", spread, why);
        acc_setup_close(&s);
        return 2;
    }
    char spread_name[32];
    spread = gi_get_text(&s.base, "ldm-spread", spread_name, sizeof spread_name);
    acc_reference ref;
    if (acc_reference_get(&s, &s.base, "a", &ref) != 0) {
        acc_setup_close(&s);
        return 1;
    }
    float *img = malloc((size_t)o.width * o.height * 3 * sizeof *img);
    int rc = !img || indirect_rows(&s, &ref, (const int (*)[2])cfg, n, photons, spread, img) ||
             ao_rows(&s, (const int (*)[2])ao_cfg, na, dist, nd, img);
    free(img);
    acc_reference_free(&ref);
    acc_setup_close(&s);
    return rc ? 1 : 0;
}
#else
typedef int accuracy_ldm_unused;
#endif
