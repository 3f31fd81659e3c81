/* cavelight-bench accuracy: speed against accuracy of the LPV, for scripts/chart.sh.
 *
 *   accuracy sweep    every (backend, lattice, steps, lambda_incr) of the lists, plus the
 *                     classic accumulating LPV, each run to its steady state: propagation
 *                     and whole-frame ms against the error versus the path-traced
 *                     reference and versus 32 plain steps (the paper's Fig. 2), for each
 *                     transport of --transports (beams, the thesis's paper). Accuracy is
 *                     the indirect image's relative RMSE against the reference's one-bounce
 *                     image over the pixels that meet geometry; the Pareto front is chosen
 *                     on it. The goal configuration (GOAL_* below, with the frame
 *                     defaults' lambda) is run on the CPU at 16, 32 and 64 cells unless
 *                     --goal 0.
 *   accuracy move     error after an abrupt light move, per lambda_incr (bench_accuracy_motion.c)
 *   accuracy path     frame-to-frame change for a light moving smoothly (same file)
 *   accuracy savings  what skipping converged frames and a fitted lattice save
 *                     (bench_accuracy_savings.c)
 *   accuracy vpl      the vpl method's error and GI ms per VPL count, and the bias of its
 *                     disk bound (bench_accuracy_vpl.c)
 *   accuracy caches   the caches method per setting row, and its importance-sampled VALs
 *                     against every RSM texel (bench_accuracy_caches.c)
 *   accuracy reference  only the path-traced reference and its noise
 *                     (bench_accuracy_reference.c)
 *   accuracy ldm      the layered depth maps: the ldm method's error and GI ms per maps
 *                     configuration, and LDM against screen-space AO per distance limit
 *                     (bench_accuracy_ldm.c)
 *
 * Each writes <out>/<experiment>_<scene>.csv and prints one JSON summary line. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"

#ifdef CAVELIGHT_HAVE_NODE
#include "bench_accuracy.h"

enum { MAX_LIST = 16, SELF_STEPS = 32 };
#define FMT_MS "%.4f"    /* propagation ms in the CSV */
#define FMT_ERROR "%.6g" /* indirect relative RMSE in the CSV */
/* The goal's setting (issue 10): 32 cells on the longest axis, at most 4 steps per frame,
 * the frame defaults otherwise; finer and coarser lattices to see that finer is no worse. */
enum { GOAL_LATTICE = 32, GOAL_MAX_STEPS = 4 };
static const int goal_lattices[3] = {16, 32, 64};

typedef struct sweep_row {
    lpv_transport transport;
    ilpv_backend_choice backend;
    int classic, lattice, n[3], steps, frames;
    float lambda;
    double propagate_ms, frame_pass_ms, eye_ms;
    image_metrics indirect, final;
    double display_mae, self_mae, flip;
    int pareto;
} sweep_row;

/* Comma-separated numbers; "fit" reads as ACC_FITTED (only meaningful for lattices). */
static int parse_list(const char *s, double *out, int max)
{
    int n = 0;
    while (*s && n < max) {
        char *end;
        if (strncmp(s, "fit", 3) == 0) {
            out[n++] = ACC_FITTED;
            end = (char *)s + 3;
        } else {
            out[n++] = strtod(s, &end);
        }
        if (end == s)
            return -1;
        s = *end == ',' ? end + 1 : end;
        if (*end && *end != ',')
            return -1;
    }
    return *s ? -1 : n;
}

/* Runs one configuration from a cleared history to its steady state, then `timing` more
 * frames; the last frame is measured against the reference. */
static int run_config(acc_setup *s, renderer *r, frame_params *fp, const acc_reference *ref,
                      int timing, sweep_row *row, uint8_t *display)
{
    fp->reset_epoch++;
    fp->lpv_steps = row->steps;
    fp->lambda_incr = row->lambda;
    int warm = acc_warm_frames(row->lambda);
    row->frames = warm + timing;
    double prop[64], pass[64], eye[64];
    renderer_image img = {0};
    for (int f = 0; f < row->frames; f++) {
        renderer_frame_pass(r, fp);
        if (f < warm)
            continue;
        if (renderer_eye_pass(r, &s->view, 1, &img) != 0) {
            fprintf(stderr, "bench accuracy: %s\n", renderer_last_error(r));
            return -1;
        }
        renderer_timings t;
        renderer_get_timings(r, &t);
        prop[f - warm] = gi_stats_value(&t.gi, "propagate", NULL);
        pass[f - warm] = t.frame_host_ms;
        eye[f - warm] = t.eye_host_ms;
    }
    row->propagate_ms = acc_median(prop, timing);
    row->frame_pass_ms = acc_median(pass, timing);
    row->eye_ms = acc_median(eye, timing);
    int w = s->opt.width, h = s->opt.height;
    image_metrics_desc geometry = {.mask = ref->coverage, .reference_noise = ref->noise_rms_indirect1};
    if (image_metrics_compare(img.indirect, ref->indirect1, w, h, &geometry, &row->indirect) ||
        image_metrics_compare(img.final, ref->final1, w, h, &geometry, &row->final)) {
        fprintf(stderr, "bench accuracy: %s: no pixel of the view meets geometry\n",
                s->opt.scene);
        return -1;
    }
    memcpy(display, img.rgb, (size_t)w * h * 3);
    row->display_mae = acc_display_mae(display, ref->display, (size_t)w * h);
    row->flip = acc_flip(s, ref, img.indirect);
    return 0;
}

/* x as the CSV prints it with fmt, so the front is marked on the figures it shows. */
static double as_printed(const char *fmt, double x)
{
    char buf[64];
    snprintf(buf, sizeof buf, fmt, x);
    return strtod(buf, NULL);
}

/* A row is on the front when no other row is at least as fast and strictly more accurate,
 * or strictly faster and at least as accurate (indirect relative RMSE; a NaN, no signal,
 * is never on it). */
static void mark_pareto(sweep_row *rows, int n)
{
    for (int i = 0; i < n; i++) {
        double ti = as_printed(FMT_MS, rows[i].propagate_ms);
        double ei = as_printed(FMT_ERROR, rows[i].indirect.rmse_rel);
        rows[i].pareto = !isnan(ei);
        for (int j = 0; j < n && rows[i].pareto; j++) {
            double tj = as_printed(FMT_MS, rows[j].propagate_ms);
            double ej = as_printed(FMT_ERROR, rows[j].indirect.rmse_rel);
            if (j != i && tj <= ti && ej <= ei && (tj < ti || ej < ei))
                rows[i].pareto = 0;
        }
    }
}

static void write_rows(FILE *f, const acc_setup *s, const sweep_row *rows, int n)
{
    for (int i = 0; i < n; i++) {
        const sweep_row *r = &rows[i];
        fprintf(f, "%s,%s,%s,%d,%d,%d,%d,%d,%g,%d," FMT_MS ",%.4f,%.4f,%.4f,"
                   "%.6g," FMT_ERROR ",%.6g,%.5f,%.4f,%.6g,%.6g,%.5f,%.5f,%.5f,%d,%s," FMT_ERROR ",%.5f\n",
                s->opt.scene, r->backend == ILPV_BACKEND_GL ? "gl" : "cpu",
                r->classic ? "classic" : "incremental", r->lattice, r->n[0], r->n[1], r->n[2],
                r->steps, r->lambda, r->frames, r->propagate_ms, r->frame_pass_ms, r->eye_ms,
                r->frame_pass_ms + r->eye_ms, r->indirect.mae, r->indirect.rmse_rel,
                r->indirect.relmse, r->indirect.ssim, r->indirect.best_scale,
                r->indirect.mae_scaled, r->final.mae, r->final.ssim, r->display_mae, r->self_mae,
                r->pareto, lpv_transport_names[r->transport], r->indirect.rmse_rel_debiased,
                r->flip);
    }
}

static const sweep_row *find_row(const sweep_row *rows, int n, lpv_transport t,
                                 ilpv_backend_choice b, int lattice, int classic, int steps,
                                 float lambda)
{
    for (int i = 0; i < n; i++)
        if (rows[i].transport == t && rows[i].backend == b && rows[i].lattice == lattice && rows[i].classic == classic &&
            rows[i].steps == steps && fabsf(rows[i].lambda - lambda) < 1e-6f)
            return &rows[i];
    return NULL;
}

/* The rows of one renderer (transport, backend, lattice, mode): the paper's yardstick (32 plain
 * steps) first, then every steps x lambda (classic: steps only), appended at rows[*n]. */
typedef struct sweep_run {
    acc_setup *s;
    const acc_reference *ref;
    frame_params *fp;
    int timing;
    sweep_row *rows;
    int n;
    uint8_t *display, *self;
} sweep_run;

static int sweep_renderer(sweep_run *run, lpv_transport transport, ilpv_backend_choice backend,
                          int lattice, int mode, const double *steps, int ns,
                          const double *lambdas, int nlam)
{
    acc_renderer_desc d = {.backend = backend, .lattice = lattice, .classic = mode,
                           .transport = transport};
    renderer *r = acc_renderer_create(run->s, &d, run->fp);
    if (!r)
        return 1;
    const lattice_desc *lat = gi_ilpv_lattice(gi_ilpv_of(renderer_gi(r)));
    size_t px = (size_t)run->s->opt.width * run->s->opt.height;
    int rc = 0;
    if (!mode) {
        sweep_row base = {.transport = transport, .backend = backend, .lattice = lattice,
                          .steps = SELF_STEPS};
        rc = run_config(run->s, r, run->fp, run->ref, 1, &base, run->self);
    }
    for (int st = 0; st < ns && rc == 0; st++)
        for (int k = 0; k < (mode ? 1 : nlam) && rc == 0; k++) {
            sweep_row *row = &run->rows[run->n++];
            *row = (sweep_row){.transport = transport, .backend = backend, .classic = mode, .lattice = lattice,
                               .steps = (int)steps[st],
                               .lambda = mode ? 0.0f : (float)lambdas[k]};
            memcpy(row->n, lat->n, sizeof row->n);
            rc = run_config(run->s, r, run->fp, run->ref, run->timing, row, run->display);
            row->self_mae = mode ? NAN : acc_display_mae(run->display, run->self, px);
            fprintf(stderr, "  %s %s %s lattice %d steps %d lambda %.2f: %.2f ms, indirect "
                    "relRMSE %.3f\n", lpv_transport_names[transport],
                    backend == ILPV_BACKEND_GL ? "gl" : "cpu",
                    mode ? "classic" : "ilpv", lattice, row->steps, row->lambda,
                    row->propagate_ms, row->indirect.rmse_rel);
        }
    renderer_destroy(r);
    return rc;
}

/* ,"key":value with value as fmt, or null when it is not finite (no signal). */
static void json_number(const char *key, const char *fmt, double value)
{
    printf(",\"%s\":", key);
    if (isfinite(value))
        printf(fmt, value);
    else
        printf("null");
}

/* The goal's figures as JSON: the CPU ILPV rows at the goal's steps and lambda on 16, 32
 * and 64 cells; "finer_never_worse" when relRMSE does not rise from 16 to 32 to 64. */
static void print_goal(const sweep_row *rows, int n, int steps, float lambda)
{
    const sweep_row *g[3];
    for (int i = 0; i < 3; i++)
        g[i] = find_row(rows, n, LPV_TRANSPORT_BEAMS, ILPV_BACKEND_CPU, goal_lattices[i], 0,
                        steps, lambda);
    const sweep_row *at = g[1];
    int never_worse = 1;
    for (int i = 1; i < 3; i++)
        never_worse &= g[i]->indirect.rmse_rel <= g[i - 1]->indirect.rmse_rel;
    printf(",\"goal\":{\"lattice\":%d,\"steps\":%d,\"lambda\":%g", GOAL_LATTICE, steps,
           lambda);
    json_number("rmse_rel", "%.6g", at->indirect.rmse_rel);
    json_number("rmse_rel_debiased", "%.6g", at->indirect.rmse_rel_debiased);
    json_number("flip", "%.6g", at->flip);
    json_number("ssim", "%.6g", at->indirect.ssim);
    json_number("best_scale", "%.6g", at->indirect.best_scale);
    json_number("propagate_ms", "%.4f", at->propagate_ms);
    printf(",\"no_signal\":%s,\"lattices\":[%d,%d,%d]", at->indirect.no_signal ? "true" : "false",
           goal_lattices[0], goal_lattices[1], goal_lattices[2]);
    for (int i = 0; i < 3; i++) {
        char key[32];
        snprintf(key, sizeof key, "rmse_rel_%d", goal_lattices[i]);
        json_number(key, "%.6g", g[i]->indirect.rmse_rel);
    }
    printf(",\"finer_never_worse\":%s}", never_worse ? "true" : "false");
}

/* One list option's text into out: 1..MAX_LIST numbers, each in [lo, hi]; "fit" (lattices)
 * is ACC_FITTED. Returns the count, or 0 after one line on stderr. */
static int list_option(const char *name, const char *text, double lo, double hi, int fit, double *out)
{
    int n = parse_list(text, out, MAX_LIST);
    for (int i = 0; i < n; i++)
        if (!(fit && out[i] == ACC_FITTED) && !(out[i] >= lo && out[i] <= hi))
            n = -1;
    if (n < 1)
        fprintf(stderr, "cavelight-bench accuracy sweep: --%s %s: expected 1..%d comma-separated numbers "
                "in %g..%g%s\n", name, text, MAX_LIST, lo, hi, fit ? " or fit" : "");
    return n < 1 ? 0 : n;
}

/* The sweep's command line. */
typedef struct sweep_options {
    acc_options o;
    double lattices[MAX_LIST], steps[MAX_LIST], lambdas[MAX_LIST], backends[2];
    int nl, ns, nlam, nb, gl_max_lattice, timing, classic, goal;
    int transports; /* bit t: transport t */
} sweep_options;

/* 0, 1 after --help (exit 0), -1 after one line on stderr (exit 2). */
static int sweep_parse(int argc, char **argv, sweep_options *w)
{
    *w = (sweep_options){.o = {.scene = "default", .out = "out/chart", .width = 160, .height = 120,
                               .ref_samples = 64},
                         .gl_max_lattice = 32, .timing = 3, .classic = 1, .goal = 1};
    static const char *const transport_names[] = {"beams", "paper", "beams,paper"};
    int transport_choice = 2;
    const char *lattice_text = "16,32,64,fit", *steps_text = "1,2,4,8,16,32", *lambda_text = "0,0.5,0.8,0.9";
    int backend_choice = 2;
    static const char *const backend_names[] = {"cpu", "gl", "cpu,gl"};
    const bench_option opts[] = {
        ACC_COMMON_OPTIONS(&w->o),
        BENCH_TEXT("lattices", "N,N,..", "cells along the longest axis; fit: a 32^3 budget fitted "
                   "to\nthe scene's shape", &lattice_text),
        BENCH_TEXT("steps", "S,S,..", "propagation steps per frame", &steps_text),
        BENCH_TEXT("lambdas", "L,L,..", "lambda_incr values, each in [0, 1)", &lambda_text),
        BENCH_CHOICE("backends", "cpu|gl|cpu,gl", "the LPV backends to sweep", &backend_choice, backend_names),
        BENCH_CHOICE("transports", "beams|paper|beams,paper", "the transports to sweep (--lpv-transport)",
                     &transport_choice, transport_names),
        BENCH_INT("gl-max-lattice", "N", "the GL backend only up to this lattice", &w->gl_max_lattice, 2, 1024),
        BENCH_INT("timing-frames", "N", "frames timed after the steady state", &w->timing, 1, 32),
        BENCH_INT("classic", "0|1", "also the classic accumulating LPV", &w->classic, 0, 1),
        BENCH_INT("goal", "0|1", "also issue 10's goal setting at 16, 32 and 64 cells", &w->goal, 0, 1),
    };
    int rc = BENCH_PARSE("accuracy sweep", "every (backend, lattice, steps, lambda_incr) of the lists "
                         "against the path-traced reference,\n  each run to its steady state "
                         "(scripts/chart.sh runs it)", opts, argc, argv);
    if (rc != 0)
        return rc;
    w->nl = list_option("lattices", lattice_text, 2, 512, 1, w->lattices);
    w->ns = w->nl ? list_option("steps", steps_text, 0, 1024, 0, w->steps) : 0;
    w->nlam = w->ns ? list_option("lambdas", lambda_text, 0, 0.999, 0, w->lambdas) : 0;
    w->backends[0] = backend_choice == 1; /* cpu, gl or both (cpu first) */
    w->backends[1] = 1;
    w->nb = backend_choice == 2 ? 2 : 1;
    w->transports = transport_choice == 2 ? 3 : 1 << transport_choice;
    return w->nlam ? 0 : -1;
}

static int accuracy_sweep(int argc, char **argv)
{
    sweep_options w;
    int parsed = sweep_parse(argc, argv, &w);
    if (parsed)
        return parsed > 0 ? 0 : 2;
    const acc_options o = w.o;
    const double *lattices = w.lattices, *steps = w.steps, *lambdas = w.lambdas, *backends = w.backends;
    int nl = w.nl, ns = w.ns, nlam = w.nlam, nb = w.nb, gl_max_lattice = w.gl_max_lattice;
    int timing = w.timing, classic = w.classic, goal = w.goal;
    acc_setup s;
    if (acc_setup_open(&s, &o) != 0)
        return 1;
    acc_reference ref;
    if (acc_reference_get(&s, &s.base, "a", &ref) != 0) {
        acc_setup_close(&s);
        return 1;
    }
    size_t px = (size_t)o.width * o.height;
    frame_params fp = s.base;
    double goal_steps = fp.lpv_steps < GOAL_MAX_STEPS ? fp.lpv_steps : GOAL_MAX_STEPS;
    double goal_lambda = fp.lambda_incr;
    sweep_run run = {.s = &s, .ref = &ref, .fp = &fp, .timing = timing,
                     .rows = calloc((size_t)(2 * nb * nl * (ns * nlam + ns) + 3), sizeof *run.rows),
                     .display = malloc(px * 3), .self = malloc(px * 3)};
    int rc = run.rows && run.display && run.self ? 0 : 1;
    for (int t = 0; t < LPV_TRANSPORT_COUNT && rc == 0; t++)
        for (int b = 0; b < nb && rc == 0 && (w.transports >> t & 1); b++) {
            ilpv_backend_choice backend = backends[b] ? ILPV_BACKEND_GL : ILPV_BACKEND_CPU;
            for (int l = 0; l < nl && rc == 0; l++) {
                int lattice = (int)lattices[l];
                int axis = lattice == ACC_FITTED ? 32 : lattice; /* about a 32^3 cost */
                if (backend == ILPV_BACKEND_GL && axis > gl_max_lattice)
                    continue;
                for (int mode = 0; mode <= classic && rc == 0; mode++)
                    rc = sweep_renderer(&run, (lpv_transport)t, backend, lattice, mode, steps, ns,
                                        lambdas, nlam);
            }
        }
    for (int i = 0; i < 3 && rc == 0 && goal; i++)
        if (!find_row(run.rows, run.n, LPV_TRANSPORT_BEAMS, ILPV_BACKEND_CPU, goal_lattices[i], 0,
                      (int)goal_steps, (float)goal_lambda))
            rc = sweep_renderer(&run, LPV_TRANSPORT_BEAMS, ILPV_BACKEND_CPU, goal_lattices[i], 0,
                                &goal_steps, 1, &goal_lambda, 1);
    if (rc == 0) {
        mark_pareto(run.rows, run.n);
        FILE *f = acc_open_csv(&s, "sweep",
            "scene,backend,mode,lattice,nx,ny,nz,steps,lambda,frames,propagate_ms,"
            "frame_pass_ms,eye_ms,frame_ms,mae_indirect,rmse_rel_indirect,relmse_indirect,"
            "ssim_indirect,best_scale_indirect,mae_scaled_indirect,mae_final,ssim_final,"
            "mae_display,mae_self32,pareto,transport,rmse_rel_debiased_indirect,flip_indirect");
        rc = f ? 0 : 1;
        if (f) {
            write_rows(f, &s, run.rows, run.n);
            fclose(f);
        }
    }
    if (rc == 0) {
        int lat = 32;
        printf("{\"bench\":\"accuracy\",\"experiment\":\"sweep\",\"scene\":\"%s\","
               "\"width\":%d,\"height\":%d,\"configs\":%d,\"reference_samples\":%d,"
               "\"reference_seconds\":%.4g,\"reference_cached\":%s,"
               "\"reference_noise_indirect1\":%.6g,\"reference_noise_rel\":%.6g,"
               "\"reference_mean_indirect1\":%.6g,\"pixels_compared\":%zu",
               o.scene, o.width, o.height, run.n, 2 * ref.samples, ref.seconds,
               ref.cached ? "true" : "false", ref.noise_indirect1,
               ref.noise_rel, ref.mean_indirect1, run.n ? run.rows[0].indirect.pixels : 0);
        /* The paper's comparison per transport: 8 steps with lambda 0.8 against 8 plain
         * steps, 32 cells. */
        printf(",\"paper_lattice\":%d,\"fig2\":{", lat);
        for (int t = 0, first = 1; t < LPV_TRANSPORT_COUNT; t++) {
            const sweep_row *inc = find_row(run.rows, run.n, (lpv_transport)t, ILPV_BACKEND_CPU, lat, 0, 8, 0.8f);
            const sweep_row *plain = find_row(run.rows, run.n, (lpv_transport)t, ILPV_BACKEND_CPU, lat, 0, 8, 0.0f);
            if (!inc || !plain)
                continue;
            printf("%s\"%s\":{\"self32_mae_8_0.8\":%.4f,\"self32_mae_8_0\":%.4f,"
                   "\"reference_mae_8_0.8\":%.4f,\"reference_mae_8_0\":%.4f,"
                   "\"rmse_rel_8_0.8\":%.4f,\"rmse_rel_8_0\":%.4f}", first ? "" : ",",
                   lpv_transport_names[t], inc->self_mae, plain->self_mae, inc->display_mae,
                   plain->display_mae, inc->indirect.rmse_rel, plain->indirect.rmse_rel);
            first = 0;
        }
        printf("}");
        if (goal)
            print_goal(run.rows, run.n, (int)goal_steps, (float)goal_lambda);
        printf("}\n");
    }
    free(run.rows);
    free(run.display);
    free(run.self);
    acc_reference_free(&ref);
    acc_setup_close(&s);
    return rc;
}

int bench_accuracy(int argc, char **argv)
{
    if (argc >= 2 && strcmp(argv[1], "sweep") == 0)
        return accuracy_sweep(argc - 1, argv + 1);
    if (argc >= 2 && strcmp(argv[1], "move") == 0)
        return accuracy_move(argc - 1, argv + 1);
    if (argc >= 2 && strcmp(argv[1], "path") == 0)
        return accuracy_path(argc - 1, argv + 1);
    if (argc >= 2 && strcmp(argv[1], "savings") == 0)
        return accuracy_savings(argc - 1, argv + 1);
    if (argc >= 2 && strcmp(argv[1], "vpl") == 0)
        return accuracy_vpl(argc - 1, argv + 1);
    if (argc >= 2 && strcmp(argv[1], "caches") == 0)
        return accuracy_caches(argc - 1, argv + 1);
    if (argc >= 2 && strcmp(argv[1], "ldm") == 0)
        return accuracy_ldm(argc - 1, argv + 1);
    if (argc >= 2 && strcmp(argv[1], "reference") == 0)
        return accuracy_reference(argc - 1, argv + 1);
    int help = argc >= 2 && strcmp(argv[1], "--help") == 0;
    fprintf(help ? stdout : stderr, "usage: cavelight-bench accuracy sweep|move|path|savings|vpl|caches|ldm|reference [options]\n"
            "  the speed-against-accuracy sweep behind scripts/chart.sh (see there)\n");
    return help ? 0 : 2;
}
#else
int bench_accuracy(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "bench accuracy: this build has no render node (cavelight_node)\n");
    return 1;
}
#endif
