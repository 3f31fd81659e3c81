/* The common ground of the accuracy subcommands: scene, context, camera, the cached
 * path-traced reference, and the small measurements they all take. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "bench_accuracy.h"
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
    char err[512];
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

/* Cache file names: <out>/ref_<scene>_<tag>_<w>x<h>_<spp>_<kind> */
static void ref_path(const acc_setup *s, const char *tag, const char *kind, char *out, size_t n)
{
    const char *base = strrchr(s->opt.scene, '/');
    base = base ? base + 1 : s->opt.scene;
    snprintf(out, n, "%s/ref_%.*s_%s_%dx%d_%d_%s", s->opt.out, (int)strcspn(base, "."),
             base, tag, s->opt.width, s->opt.height, s->opt.ref_samples, kind);
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
    int ok = f && fscanf(f, "%lf %lf %lf", &out->noise_indirect1, &out->seconds,
                         &out->noise_rms_indirect1) == 3;
    out->cached = 1;
    if (f)
        fclose(f);
    return ok && w == s->opt.width && h == s->opt.height ? 0 : -1;
}

/* Two independent halves (seeds 1 and 2), averaged; their difference estimates the noise. */
static int render_reference(acc_setup *s, const frame_params *p, const char *tag,
                            acc_reference *out)
{
    char err[512];
    reference *ref = reference_create(&s->sc, s->opt.threads, err, sizeof err);
    if (!ref) {
        fprintf(stderr, "bench accuracy: %s\n", err);
        return -1;
    }
    reference_images img = {0};
    reference_noise noise;
    reference_render_desc d = {.params = p, .view = &s->view, .samples = s->opt.ref_samples,
                               .seed = 1};
    int rc = reference_render_averaged(ref, &d, &img, &noise, err, sizeof err);
    reference_destroy(ref);
    if (rc != 0) {
        fprintf(stderr, "bench accuracy: reference: %s\n", err);
        return -1;
    }
    out->seconds = img.render_ms / 1000.0;
    out->noise_indirect1 = noise.indirect1;
    out->noise_rms_indirect1 = noise.indirect1_rms;
    out->direct = img.direct;       /* the images pass to out; img.indirect is not needed */
    out->indirect1 = img.indirect1;
    out->coverage = img.coverage;
    free(img.indirect);
    char path[4200];
    ref_path(s, tag, "direct.pfm", path, sizeof path);
    rc |= image_write_pfm(path, s->opt.width, s->opt.height, out->direct, err, sizeof err);
    ref_path(s, tag, "indirect1.pfm", path, sizeof path);
    rc |= image_write_pfm(path, s->opt.width, s->opt.height, out->indirect1, err, sizeof err);
    ref_path(s, tag, "coverage.pfm", path, sizeof path);
    rc |= write_coverage(path, s, out->coverage);
    ref_path(s, tag, "noise.txt", path, sizeof path);
    FILE *f = fopen(path, "w");
    if (f) {
        fprintf(f, "%.9g %.3f %.9g\n", out->noise_indirect1, out->seconds,
                out->noise_rms_indirect1);
        fclose(f);
    }
    return rc || !f ? -1 : 0;
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
    double sum = 0;
    for (size_t i = 0; i < px * 3; i++) {
        out->final1[i] = out->direct[i] + out->indirect1[i];
        sum += out->indirect1[i];
    }
    out->mean_indirect1 = sum / (double)(px * 3);
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
