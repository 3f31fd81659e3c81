/* The calibration pattern's grid lines meet across every seam of the 5-sided CAVE:
 *
 *   cavelight-master --config configs/clusters/cave5-local.json --spawn-local --output png --pattern
 *
 * runs with real node processes; then every pair of screen edges that lie on one line and
 * overlap (19 seams in cave5: the middle of each wall, the wall corners, the floor's and
 * the ceiling's edges) is walked on both images, and every grid line that crosses the seam
 * on one side must meet one on the other side within a pixel. The same check fails on a
 * pattern drawn with one screen's corners 4 cm off, so it can tell. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cluster/cluster_config.h"
#include "frame/pattern.h"
#include "image/image.h"

typedef struct screen_image {
    int w, h;
    uint8_t *rgb;
    float corner[4][3]; /* bl, br, tl, tr: where the screen really is */
} screen_image;

enum { EDGE_BOTTOM, EDGE_TOP, EDGE_LEFT, EDGE_RIGHT };
static const int edge_ends[4][2] = {{0, 1}, {2, 3}, {0, 2}, {1, 3}};

enum { PX_BACKGROUND, PX_LINE, PX_OTHER };

static int classify(const uint8_t *p)
{
    if (!memcmp(p, PATTERN_LINE, 3) || !memcmp(p, PATTERN_METRE_LINE, 3))
        return PX_LINE;
    return memcmp(p, PATTERN_BACKGROUND, 3) ? PX_OTHER : PX_BACKGROUND;
}

/* Pixel (x, y) at position i along an edge, depth d pixels in from it. */
static void edge_pixel(const screen_image *s, int edge, int i, int d, int *x, int *y)
{
    switch (edge) {
    case EDGE_BOTTOM: *x = i; *y = s->h - 1 - d; break;
    case EDGE_TOP: *x = i; *y = d; break;
    case EDGE_LEFT: *x = d; *y = s->h - 1 - i; break;
    default: *x = s->w - 1 - d; *y = s->h - 1 - i; break;
    }
}

typedef struct sample {
    int n;
    double pos[4096];   /* metres along the seam, from its start */
    int kind[4096];
} sample;

/* The pixels along one screen's edge, in metres along the seam line (origin o, unit
 * direction u), at the first depth (0..2) that is not one line all along: a grid line
 * lying on the seam itself covers the edge pixels of one side. */
static void sample_edge(const screen_image *s, int edge, const double o[3], const double u[3], sample *out)
{
    const float *a = s->corner[edge_ends[edge][0]], *b = s->corner[edge_ends[edge][1]];
    int n = edge <= EDGE_TOP ? s->w : s->h;
    for (int d = 0; d < 3; d++) {
        int lines = 0, other = 0;
        out->n = n;
        for (int i = 0; i < n; i++) {
            double t = (i + 0.5) / n, p = 0;
            for (int k = 0; k < 3; k++)
                p += (a[k] + t * (b[k] - a[k]) - o[k]) * u[k];
            int x, y;
            edge_pixel(s, edge, i, d, &x, &y);
            out->pos[i] = p;
            out->kind[i] = classify(s->rgb + ((size_t)y * s->w + x) * 3);
            lines += out->kind[i] == PX_LINE;
            other += out->kind[i] == PX_OTHER;
        }
        if (lines < (n - other) * 9 / 10)
            return;
    }
}

/* Centres of the runs of line pixels inside [lo, hi]. */
static int crossings(const sample *s, double lo, double hi, double *out)
{
    int n = 0;
    for (int i = 0; i < s->n;) {
        if (s->kind[i] != PX_LINE) {
            i++;
            continue;
        }
        int j = i;
        while (j + 1 < s->n && s->kind[j + 1] == PX_LINE)
            j++;
        double c = 0.5 * (s->pos[i] + s->pos[j]);
        if (c > lo && c < hi)
            out[n++] = c;
        i = j + 1;
    }
    return n;
}

/* The kind of pixel at position p along the seam (the nearest sample). */
static int kind_at(const sample *s, double p)
{
    int best = 0;
    for (int i = 1; i < s->n; i++)
        if (fabs(s->pos[i] - p) < fabs(s->pos[best] - p))
            best = i;
    return s->kind[best];
}

/* Every crossing on one side meets one on the other within tol, unless a label or a marker
 * covers the other side there. Returns the matches, or -1 on a miss. */
static int match(const sample *a, const sample *b, double lo, double hi, double tol, char *why, size_t cap)
{
    double ca[512], cb[512];
    int na = crossings(a, lo, hi, ca), nb = crossings(b, lo, hi, cb), matched = 0;
    for (int pass = 0; pass < 2; pass++) {
        const double *x = pass ? cb : ca, *y = pass ? ca : cb;
        int nx = pass ? nb : na, ny = pass ? na : nb;
        const sample *other = pass ? a : b;
        for (int i = 0; i < nx; i++) {
            int ok = 0;
            for (int j = 0; j < ny && !ok; j++)
                ok = fabs(x[i] - y[j]) <= tol;
            if (!ok && kind_at(other, x[i]) == PX_OTHER)
                continue;
            if (!ok) {
                snprintf(why, cap, "a line at %.3f m along the seam meets none on the other side", x[i]);
                return -1;
            }
            matched += pass == 0;
        }
    }
    return matched;
}

typedef struct seam_result {
    int seams, crossings;
    char failure[256];
} seam_result;

static void check_seams(const cluster_config *cfg, screen_image *img, seam_result *r)
{
    memset(r, 0, sizeof *r);
    static sample sa, sb;
    for (int a = 0; a < cfg->screen_count; a++)
        for (int b = a + 1; b < cfg->screen_count; b++)
            for (int ea = 0; ea < 4; ea++)
                for (int eb = 0; eb < 4; eb++) {
                    const float *p0 = img[a].corner[edge_ends[ea][0]], *p1 = img[a].corner[edge_ends[ea][1]];
                    const float *q0 = img[b].corner[edge_ends[eb][0]], *q1 = img[b].corner[edge_ends[eb][1]];
                    double o[3], u[3], len = 0;
                    for (int k = 0; k < 3; k++) {
                        o[k] = p0[k];
                        u[k] = p1[k] - p0[k];
                        len += u[k] * u[k];
                    }
                    len = sqrt(len);
                    for (int k = 0; k < 3; k++)
                        u[k] /= len;
                    /* B's edge on A's line? Then the overlap of the two, in metres along u. */
                    double t0 = 0, t1 = 0, off = 0;
                    for (int k = 0; k < 3; k++) {
                        t0 += (q0[k] - o[k]) * u[k];
                        t1 += (q1[k] - o[k]) * u[k];
                    }
                    for (int k = 0; k < 3; k++) {
                        double d0 = q0[k] - o[k] - t0 * u[k], d1 = q1[k] - o[k] - t1 * u[k];
                        off = fmax(off, fmax(fabs(d0), fabs(d1)));
                    }
                    double lo = fmax(0, fmin(t0, t1)), hi = fmin(len, fmax(t0, t1));
                    if (off > 1e-4 || hi - lo < 0.01)
                        continue;
                    sample_edge(&img[a], ea, o, u, &sa);
                    sample_edge(&img[b], eb, o, u, &sb);
                    double pitch_a = len / (ea <= EDGE_TOP ? img[a].w : img[a].h);
                    double pitch_b = fabs(t1 - t0) / (eb <= EDGE_TOP ? img[b].w : img[b].h);
                    char why[200];
                    /* Lines at the seam's ends run along the screens' other edges. */
                    double tol = fmax(pitch_a, pitch_b) + 1e-6;
                    int m = match(&sa, &sb, lo + tol, hi - tol, tol, why, sizeof why);
                    if (m < 0 && !r->failure[0])
                        snprintf(r->failure, sizeof r->failure, "seam %s/%s: %s", cfg->screens[a].name,
                                 cfg->screens[b].name, why);
                    if (m < 3 && !r->failure[0])
                        snprintf(r->failure, sizeof r->failure, "seam %s/%s: only %d lines cross it",
                                 cfg->screens[a].name, cfg->screens[b].name, m);
                    r->seams++;
                    r->crossings += m > 0 ? m : 0;
                }
}

static cluster_config cfg;

static void screen_corners(const cluster_screen *s, float c[4][3])
{
    for (int k = 0; k < 3; k++) {
        c[0][k] = s->bottom_left[k];
        c[1][k] = s->bottom_right[k];
        c[2][k] = s->top_left[k];
        c[3][k] = s->bottom_right[k] + s->top_left[k] - s->bottom_left[k];
    }
}

/* The image size each screen has in the config. */
static void screen_size(int screen, int *w, int *h)
{
    for (int n = 0; n < cfg.node_count; n++)
        for (int s = 0; s < cfg.nodes[n].screen_count; s++)
            if (cfg.nodes[n].screens[s].screen == screen) {
                *w = cfg.nodes[n].screens[s].width;
                *h = cfg.nodes[n].screens[s].height;
            }
}

static void test_master_pattern_meets_at_every_seam(void **state)
{
    (void)state;
    char config[1024], out[] = "/tmp/cavelight-pattern-XXXXXX", cmd[4096], err[512];
    snprintf(config, sizeof config, "%s/configs/clusters/cave5-local.json", CAVELIGHT_SOURCE_DIR);
    assert_non_null(mkdtemp(out));
    assert_int_equal(cluster_config_load(config, &cfg, err, sizeof err), 0);
    snprintf(cmd, sizeof cmd, "%s/cavelight-master --config %s --spawn-local --output png --pattern "
             "--bind 'tcp://127.0.0.1:*' --out %s --lattice 8 --rsm 32 --node-args '--threads 1' --quiet",
             CAVELIGHT_BINARY_DIR, config, out);
    assert_int_equal(system(cmd), 0);
    static screen_image img[CLUSTER_MAX_SCREENS];
    for (int s = 0; s < cfg.screen_count; s++) {
        char path[2048];
        snprintf(path, sizeof path, "%s/%s-left.png", out, cfg.screens[s].name);
        if (image_read_png(path, &img[s].w, &img[s].h, &img[s].rgb, err, sizeof err) != 0)
            fail_msg("%s", err);
        screen_corners(&cfg.screens[s], img[s].corner);
    }
    seam_result r;
    check_seams(&cfg, img, &r);
    printf("pattern: %d seams, %d grid lines crossing them, all meeting\n", r.seams, r.crossings);
    if (r.failure[0])
        fail_msg("%s", r.failure);
    assert_int_equal(r.seams, 19);

    /* The check can fail: front-r drawn as if its corners were 4 cm higher than the
     * screen really is (a wrong measurement) breaks its seams. */
    int fr = cluster_config_find_screen(&cfg, "front-r");
    cluster_screen wrong = cfg.screens[fr];
    wrong.bottom_left[1] += 0.04f;
    wrong.bottom_right[1] += 0.04f;
    wrong.top_left[1] += 0.04f;
    pattern_desc pd = {.bottom_left = wrong.bottom_left, .bottom_right = wrong.bottom_right,
                       .top_left = wrong.top_left, .name = wrong.name};
    pattern_draw(&pd, img[fr].w, img[fr].h, img[fr].rgb);
    check_seams(&cfg, img, &r);
    assert_true(r.failure[0] != 0);
    printf("with front-r 4 cm off: %s\n", r.failure);

    /* And drawn right, the same images meet again (the check is about the corners only). */
    int w = 0, h = 0;
    screen_size(fr, &w, &h);
    pd = (pattern_desc){.bottom_left = cfg.screens[fr].bottom_left, .bottom_right = cfg.screens[fr].bottom_right,
                        .top_left = cfg.screens[fr].top_left, .name = cfg.screens[fr].name};
    pattern_draw(&pd, w, h, img[fr].rgb);
    check_seams(&cfg, img, &r);
    assert_true(r.failure[0] == 0);
    for (int s = 0; s < cfg.screen_count; s++)
        free(img[s].rgb);
    snprintf(cmd, sizeof cmd, "rm -rf %s", out);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_master_pattern_meets_at_every_seam),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
