/* The common ground of the accuracy subcommands: scene, context, camera, the cached
 * path-traced reference, and the small measurements they all take. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "bench_accuracy.h"
#include "image/flip.h"
#include "image/image.h"
#include "frame/frame_view.h"
#include "reference/reference.h"
#include "image/tonemap.h"

int acc_parse_common(acc_options *o, int argc, char **argv, int *i, int *bad)
{
    const char *a = argv[*i], *v = *i + 1 < argc ? argv[*i + 1] : NULL;
    if (strcmp(a, "--scene") && strcmp(a, "--out") && strcmp(a, "--width") &&
        strcmp(a, "--height") && strcmp(a, "--ref-samples") && strcmp(a, "--threads"))
        return 0;
    if (!v) {
        *bad = 1;
        return 1;
    }
    if (strcmp(a, "--scene") == 0) o->scene = v;
    else if (strcmp(a, "--out") == 0) o->out = v;
    else if (strcmp(a, "--width") == 0) *bad = (o->width = atoi(v)) < 8;
    else if (strcmp(a, "--height") == 0) *bad = (o->height = atoi(v)) < 8;
    else if (strcmp(a, "--ref-samples") == 0) *bad = (o->ref_samples = atoi(v)) < 1;
    else *bad = (o->threads = atoi(v)) < 0;
    (*i)++;
    return 1;
}

int acc_setup_open(acc_setup *s, const acc_options *o)
{
    memset(s, 0, sizeof *s);
    s->opt = *o;
    char err[512], *end = NULL;
    s->ref_noise = o->ref_noise ? strtod(o->ref_noise, &end) : 0.0;
    if (o->ref_noise && (end == o->ref_noise || *end || !(s->ref_noise >= 0 && s->ref_noise < 1))) {
        fprintf(stderr, "bench accuracy: --ref-noise %s: expected a number in [0, 1)\n", o->ref_noise);
        return -1;
    }
    if (mkdir(o->out, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "bench accuracy: cannot create %s (%s)\n", o->out, strerror(errno));
        return -1;
    }
    if (scene_load(o->scene, &s->sc, err, sizeof err) != 0) {
        fprintf(stderr, "bench accuracy: %s\n", err);
        return -1;
    }
    glctx_desc gd = {.backend = GLCTX_EGL};
    s->ctx = glctx_create(&gd, err, sizeof err);
    if (!s->ctx) {
        fprintf(stderr, "bench accuracy: %s\n", err);
        scene_free(&s->sc);
        return -1;
    }
    scene_camera cam;
    scene_default_camera(&s->sc, &cam);
    frame_view_scene_camera(&cam, cam.position, scene_far_plane(&s->sc), o->width, o->height,
                            &s->view);
    frame_params_default(&s->base);
    frame_params_lights_from_scene(&s->base, &s->sc);
    memcpy(s->base.head + 12, cam.position, sizeof cam.position); /* the vpl view rule's viewer */
    s->encoding_gamma = frame_params_e2e_gamma(s->base.environment) / s->base.display_gamma;
    return 0;
}

void acc_setup_close(acc_setup *s)
{
    if (s->ctx)
        glctx_destroy(s->ctx);
    scene_free(&s->sc);
}

/* Cache file names: <out>/ref_<scene>_<tag>_<w>x<h>_<spp>[_n<noise>]_<kind> */
static void ref_path(const acc_setup *s, const char *tag, const char *kind, char *out, size_t n)
{
    const char *base = strrchr(s->opt.scene, '/');
    base = base ? base + 1 : s->opt.scene;
    char noise[32] = "";
    if (s->ref_noise > 0)
        snprintf(noise, sizeof noise, "_n%g", s->ref_noise);
    snprintf(out, n, "%s/ref_%.*s_%s_%dx%d_%d%s_%s", s->opt.out, (int)strcspn(base, "."),
             base, tag, s->opt.width, s->opt.height, s->opt.ref_samples, noise, kind);
}

/* The coverage mask is cached as a PFM of 0s and 1s. */
static int read_coverage(const char *path, const acc_setup *s, uint8_t **out)
{
    char err[256];
    int w, h;
    float *v = NULL;
    size_t n = (size_t)s->opt.width * s->opt.height;
    if (image_read_pfm(path, &w, &h, &v, err, sizeof err) != 0)
        return -1;
    *out = w == s->opt.width && h == s->opt.height ? malloc(n) : NULL;
    for (size_t i = 0; *out && i < n; i++)
        (*out)[i] = v[3 * i] != 0;
    free(v);
    return *out ? 0 : -1;
}

static int write_coverage(const char *path, const acc_setup *s, const uint8_t *coverage)
{
    char err[256];
    size_t n = (size_t)s->opt.width * s->opt.height;
    float *v = malloc(n * 3 * sizeof *v);
    if (!v)
        return -1;
    for (size_t i = 0; i < 3 * n; i++)
        v[i] = coverage[i / 3];
    int rc = image_write_pfm(path, s->opt.width, s->opt.height, v, err, sizeof err);
    free(v);
    return rc;
}

static int read_cached(const acc_setup *s, const char *tag, acc_reference *out)
{
    char path[4200], err[256];
    int w, h;
    ref_path(s, tag, "direct.pfm", path, sizeof path);
    if (image_read_pfm(path, &w, &h, &out->direct, err, sizeof err) != 0)
        return -1;
    ref_path(s, tag, "indirect1.pfm", path, sizeof path);
    if (w != s->opt.width || h != s->opt.height ||
        image_read_pfm(path, &w, &h, &out->indirect1, err, sizeof err) != 0)
        return -1;
    ref_path(s, tag, "coverage.pfm", path, sizeof path);
    if (read_coverage(path, s, &out->coverage) != 0)
        return -1;
    ref_path(s, tag, "noise.txt", path, sizeof path);
    FILE *f = fopen(path, "r");
    out->samples = s->opt.ref_samples; /* a cache written before the count was kept */
    int ok = f && fscanf(f, "%lf %lf %lf %d", &out->noise_indirect1, &out->seconds,
                         &out->noise_rms_indirect1, &out->samples) >= 3;
    out->cached = 1;
    if (f)
        fclose(f);
    return ok && w == s->opt.width && h == s->opt.height ? 0 : -1;
}

enum { REF_MAX_SAMPLES = 1 << 16 }; /* per half: where a scene whose noise will not fall stops */

/* acc = (acc * had + add * n) / (had + n): the running mean of a half over its rounds. */
static void blend(float *acc, const float *add, size_t values, int had, int n)
{
    for (size_t i = 0; i < values; i++)
        acc[i] = (float)(((double)acc[i] * had + (double)add[i] * n) / (had + n));
}

/* The noise of the halves' average, from their difference: MAE over all samples, RMS over
 * the covered ones (the averaged image's standard deviation) and that over the covered mean. */
static double halves_noise(const reference_images h[2], size_t values, double *mae, double *rms)
{
    double abs_sum = 0, sq = 0, sum = 0;
    size_t covered = 0;
    for (size_t i = 0; i < values; i++) {
        double e = (double)h[0].indirect1[i] - h[1].indirect1[i];
        abs_sum += fabs(e);
        if (h[0].coverage[i / 3]) {
            sq += e * e;
            sum += 0.5 * ((double)h[0].indirect1[i] + h[1].indirect1[i]);
            covered++;
        }
    }
    *mae = values ? abs_sum / (2.0 * (double)values) : 0;
    *rms = covered ? sqrt(sq / (double)covered) / 2.0 : 0;
    return sum > 0 ? *rms / (sum / (double)covered) : NAN;
}

/* Paths per half of the next round: by noise ~ 1/sqrt(paths), enough for 0.9 of the target
 * (the estimate is itself noisy), at most 8 times the paths so far. */
static int next_round(int total, double noise_rel, double target)
{
    double want = total * (noise_rel / (0.9 * target)) * (noise_rel / (0.9 * target));
    double n = fmin(ceil(want) - total, 7.0 * total);
    return (int)fmax(1.0, fmin(n, (double)(REF_MAX_SAMPLES - total)));
}

/* The two halves, in rounds of independent seeds (1 and 2, then 3 and 4, ...) until their
 * noise relRMSE is at most s->ref_noise (one round when it is 0). */
static int render_halves(acc_setup *s, reference *ref, const frame_params *p,
                         reference_images half[2], acc_reference *out)
{
    char err[512];
    size_t values = (size_t)s->opt.width * s->opt.height * 3;
    int total = 0, n = s->opt.ref_samples;
    for (uint64_t seed = 1;; seed += 2) {
        reference_images round[2] = {{0}};
        for (int h = 0; h < 2; h++) {
            reference_images *into = total ? &round[h] : &half[h];
            reference_render_desc d = {.params = p, .view = &s->view, .samples = n,
                                       .seed = seed + (uint64_t)h};
            if (reference_render(ref, &d, into, err, sizeof err) != 0) {
                fprintf(stderr, "bench accuracy: reference: %s\n", err);
                reference_images_free(&round[0]);
                return -1;
            }
            out->seconds += into->render_ms / 1000.0;
        }
        for (int h = 0; total && h < 2; h++) {
            blend(half[h].direct, round[h].direct, values, total, n);
            blend(half[h].indirect1, round[h].indirect1, values, total, n);
            reference_images_free(&round[h]);
        }
        total += n;
        double rel = halves_noise(half, values, &out->noise_indirect1, &out->noise_rms_indirect1);
        if (!(s->ref_noise > 0 && rel > s->ref_noise && total < REF_MAX_SAMPLES))
            break;
        n = next_round(total, rel, s->ref_noise);
        fprintf(stderr, "bench accuracy: %s: reference noise relRMSE %.4f at %d paths per half; "
                "%d more\n", s->opt.scene, rel, total, n);
    }
    out->samples = total;
    return 0;
}

static int write_reference(acc_setup *s, const char *tag, const acc_reference *out)
{
    char path[4200], err[512];
    int rc = 0;
    ref_path(s, tag, "direct.pfm", path, sizeof path);
    rc |= image_write_pfm(path, s->opt.width, s->opt.height, out->direct, err, sizeof err);
    ref_path(s, tag, "indirect1.pfm", path, sizeof path);
    rc |= image_write_pfm(path, s->opt.width, s->opt.height, out->indirect1, err, sizeof err);
    ref_path(s, tag, "coverage.pfm", path, sizeof path);
    rc |= write_coverage(path, s, out->coverage);
    ref_path(s, tag, "noise.txt", path, sizeof path);
    FILE *f = fopen(path, "w");
    if (f) {
        fprintf(f, "%.9g %.3f %.9g %d\n", out->noise_indirect1, out->seconds,
                out->noise_rms_indirect1, out->samples);
        fclose(f);
    }
    return rc || !f ? -1 : 0;
}

/* Two independent halves, averaged; their difference estimates the noise. */
static int render_reference(acc_setup *s, const frame_params *p, const char *tag,
                            acc_reference *out)
{
    char err[512];
    reference *ref = reference_create(&s->sc, s->opt.threads, err, sizeof err);
    if (!ref) {
        fprintf(stderr, "bench accuracy: %s\n", err);
        return -1;
    }
    reference_images half[2] = {{0}};
    int rc = render_halves(s, ref, p, half, out);
    reference_destroy(ref);
    if (rc == 0) {
        size_t values = (size_t)s->opt.width * s->opt.height * 3;
        for (size_t i = 0; i < values; i++) {
            half[0].direct[i] = 0.5f * (half[0].direct[i] + half[1].direct[i]);
            half[0].indirect1[i] = 0.5f * (half[0].indirect1[i] + half[1].indirect1[i]);
        }
        out->direct = half[0].direct; /* the images pass to out */
        out->indirect1 = half[0].indirect1;
        out->coverage = half[0].coverage;
        half[0].direct = half[0].indirect1 = NULL;
        half[0].coverage = NULL;
        rc = write_reference(s, tag, out);
    }
    reference_images_free(&half[0]);
    reference_images_free(&half[1]);
    return rc;
}

int acc_reference_get(acc_setup *s, const frame_params *p, const char *tag, acc_reference *out)
{
    memset(out, 0, sizeof *out);
    if (read_cached(s, tag, out) != 0) {
        acc_reference_free(out);
        if (render_reference(s, p, tag, out) != 0) {
            acc_reference_free(out);
            return -1;
        }
    }
    size_t px = (size_t)s->opt.width * s->opt.height;
    out->final1 = malloc(px * 3 * sizeof(float));
    out->display = malloc(px * 3);
    if (!out->final1 || !out->display) {
        acc_reference_free(out);
        return -1;
    }
    double sum = 0, covered_sum = 0;
    size_t covered = 0;
    for (size_t i = 0; i < px * 3; i++) {
        out->final1[i] = out->direct[i] + out->indirect1[i];
        sum += out->indirect1[i];
        covered_sum += out->coverage[i / 3] ? out->indirect1[i] : 0.0;
        covered += out->coverage[i / 3];
    }
    out->mean_indirect1 = sum / (double)(px * 3);
    out->noise_rel = covered_sum > 0 ? out->noise_rms_indirect1 / (covered_sum / (double)covered) : NAN;
    tonemap_rgb8(out->final1, px, s->encoding_gamma, out->display);
    return 0;
}

void acc_reference_free(acc_reference *r)
{
    free(r->direct);
    free(r->indirect1);
    free(r->final1);
    free(r->display);
    free(r->coverage);
    memset(r, 0, sizeof *r);
}

/* d's settings into fp, every one checked. */
static const char *settings(const acc_renderer_desc *d, frame_params *fp)
{
    const char *backends[] = {"auto", "cpu", "gl"};
    const struct { const char *name, *text; double number; } set[] = {
        {"gi", d->gi ? d->gi : "ilpv", 0},
        {"lpv", backends[d->backend], 0},
        {"lpv-mode", d->classic ? "classic" : "incremental", 0},
        {"lpv-transport", lpv_transport_names[d->transport], 0},
        {"lattice", NULL, d->lattice == ACC_FITTED ? 32 : d->lattice},
        {"lattice-cells", NULL, d->lattice == ACC_FITTED ? ACC_FITTED_CELLS : 0},
        {"vpl-bound", d->vpl_point ? "point" : "disk", 0},
        {"vpl-visibility", d->vpl_visibility ? d->vpl_visibility : "exact", 0},
        {"ism-size", NULL, d->ism_size ? d->ism_size : 32},
        {"ism-points", NULL, d->ism_points ? d->ism_points : 1024},
        {"vpl-cut", NULL, d->vpl_cut == 0 ? 1.0 : d->vpl_cut},
        {"vpl-interleave", NULL, d->vpl_interleave},
    };
    for (size_t i = 0; i < sizeof set / sizeof set[0]; i++) {
        const char *why = set[i].text ? gi_set(fp, set[i].name, set[i].text)
                                      : gi_set_number(fp, set[i].name, set[i].number);
        if (why)
            return why;
    }
    return NULL;
}

renderer *acc_renderer_create(acc_setup *s, const acc_renderer_desc *d, frame_params *fp)
{
    char err[512];
    const char *why = settings(d, fp);
    if (why) {
        fprintf(stderr, "bench accuracy: %s\n", why);
        return NULL;
    }
    renderer_desc rd = {.gl = glctx_gl(s->ctx), .scene = &s->sc, .first = fp,
                        .threads = s->opt.threads, .no_reuse = !d->skip_converged};
    renderer *r = renderer_create(&rd, err, sizeof err);
    if (!r)
        fprintf(stderr, "bench accuracy: %s\n", err);
    return r;
}

double acc_flip(const acc_setup *s, const acc_reference *ref, const float *indirect)
{
    flip_desc d = {.mask = ref->coverage};
    flip_result r;
    return flip_hdr(indirect, ref->indirect1, s->opt.width, s->opt.height, &d, NULL, &r) == 0
               ? r.mean : NAN;
}

double acc_display_mae(const uint8_t *a, const uint8_t *b, size_t pixels)
{
    double sum = 0;
    for (size_t i = 0; i < pixels * 3; i++)
        sum += abs((int)a[i] - (int)b[i]);
    return pixels ? sum / (255.0 * (double)(pixels * 3)) : 0;
}

double acc_linear_mae(const float *a, const float *b, size_t pixels)
{
    double sum = 0;
    for (size_t i = 0; i < pixels * 3; i++)
        sum += fabs((double)a[i] - (double)b[i]);
    return pixels ? sum / (double)(pixels * 3) : 0;
}

int acc_warm_frames(float lambda)
{
    return lambda > 0 ? (int)ceil(log(1e-3) / log(lambda)) : 1;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double acc_median(double *v, int n)
{
    if (n <= 0)
        return 0;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int acc_frame(acc_setup *s, renderer *r, const frame_params *fp, const char *what,
              renderer_image *img, renderer_timings *t)
{
    renderer_frame_pass(r, fp);
    if (renderer_eye_pass(r, &s->view, 1, img) != 0) {
        fprintf(stderr, "bench accuracy %s: %s\n", what, renderer_last_error(r));
        return -1;
    }
    renderer_get_timings(r, t);
    return 0;
}

FILE *acc_open_csv(const acc_setup *s, const char *name, const char *header)
{
    char path[4200];
    const char *base = strrchr(s->opt.scene, '/');
    base = base ? base + 1 : s->opt.scene;
    snprintf(path, sizeof path, "%s/%s_%.*s.csv", s->opt.out, name, (int)strcspn(base, "."), base);
    FILE *f = fopen(path, "w");
    if (!f)
        fprintf(stderr, "bench accuracy: cannot write %s (%s)\n", path, strerror(errno));
    else
        fprintf(f, "%s\n", header);
    return f;
}
