#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image/flip.h"

#define PI 3.14159265358979323846
#define MAX_PPD 1000.0 /* keeps the kernels' radii (3 * 0.041 ppd) sane */

/* Linear sRGB (D65 white) to CIE XYZ: the sRGB primaries' exact matrix. */
static const double rgb_to_xyz[3][3] = {
    {10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0},
};

/* The contrast sensitivity functions of the paper (its Table 1): a1, b1, a2, b2 of
 * a1 sqrt(pi / b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi / b2) exp(-pi^2 x^2 / b2), x in degrees,
 * for the achromatic, red-green and blue-yellow channels. */
static const double csf[3][4] = {
    {1.0, 0.0047, 0.0, 1e-5},
    {1.0, 0.0053, 0.0, 1e-5},
    {34.1, 0.04, 13.5, 0.025},
};
#define CSF_WIDEST_B 0.04
#define FEATURE_WIDTH 0.082 /* degrees: peak to trough of the edge detector, 2 sd */
#define EXPONENT_COLOUR 0.7
#define EXPONENT_FEATURE 0.5
#define REMAP_PC 0.4
#define REMAP_PT 0.95
/* ACES tone curve (Narkowicz's fit) with its 0.6 exposure folded into the coefficients:
 * (k0 x^2 + k1 x) / (k2 x^2 + k3 x + k4). */
static const double aces[5] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};
#define EXPOSURE_TONE 0.85 /* the max maps here at the first exposure, the median at the last */

typedef struct colour_space {
    double to_rgb[3][3]; /* XYZ to linear sRGB */
    double white[3];     /* XYZ of linear (1, 1, 1) */
    double cmax;         /* HyAB(green, blue)^0.7: the largest colour difference */
} colour_space;

typedef struct kernel {
    int r;
    double *w; /* 2r + 1 taps, w[r] the centre */
} kernel;

/* Everything one LDR-FLIP evaluation needs, allocated once for every exposure. */
typedef struct flip_work {
    int w, h;
    size_t n;
    colour_space cs;
    kernel csf_gauss[3][2];   /* each channel's Gaussians, each summing to 1 */
    double csf_weight[3][2];  /* their shares of the channel's filter */
    kernel gauss, edge, point; /* the feature detectors' 1D factors */
    float *ycc[2][3];         /* test and reference in YCxCz, filtered in place */
    float *tmp, *a, *b, *ref_edge, *ref_point, *test_point, *feature;
} flip_work;

static void invert3(const double m[3][3], double out[3][3])
{
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            out[i][j] = (m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]) / det;
        }
}

static void mat3_apply(const double m[3][3], const double v[3], double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
}

static double lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

/* Linear RGB to Hunt-adjusted CIELAB: a* and b* scaled by 0.01 L*. */
static void hunt_lab(const colour_space *cs, const double rgb[3], double lab[3])
{
    double xyz[3];
    mat3_apply(rgb_to_xyz, rgb, xyz);
    double fx = lab_f(xyz[0] / cs->white[0]), fy = lab_f(xyz[1] / cs->white[1]);
    double fz = lab_f(xyz[2] / cs->white[2]);
    lab[0] = 116.0 * fy - 16.0;
    lab[1] = 0.01 * lab[0] * 500.0 * (fx - fy);
    lab[2] = 0.01 * lab[0] * 200.0 * (fy - fz);
}

static double hyab(const double p[3], const double q[3])
{
    return fabs(p[0] - q[0]) + hypot(p[1] - q[1], p[2] - q[2]);
}

static void colour_space_init(colour_space *cs)
{
    const double one[3] = {1, 1, 1}, green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
    invert3(rgb_to_xyz, cs->to_rgb);
    mat3_apply(rgb_to_xyz, one, cs->white);
    double g[3], b[3];
    hunt_lab(cs, green, g);
    hunt_lab(cs, blue, b);
    cs->cmax = pow(hyab(g, b), EXPONENT_COLOUR);
}

/* Linear RGB to YCxCz: CIELAB without its cube root, linear in XYZ. */
static void to_ycxcz(const colour_space *cs, const double rgb[3], double ycc[3])
{
    double xyz[3];
    mat3_apply(rgb_to_xyz, rgb, xyz);
    double x = xyz[0] / cs->white[0], y = xyz[1] / cs->white[1], z = xyz[2] / cs->white[2];
    ycc[0] = 116.0 * y - 16.0;
    ycc[1] = 500.0 * (x - y);
    ycc[2] = 200.0 * (y - z);
}

/* Filtered YCxCz back to linear RGB, clamped to the displayable cube. */
static void from_ycxcz(const colour_space *cs, const double ycc[3], double rgb[3])
{
    double y = (ycc[0] + 16.0) / 116.0;
    double xyz[3] = {(y + ycc[1] / 500.0) * cs->white[0], y * cs->white[1],
                     (y - ycc[2] / 200.0) * cs->white[2]};
    mat3_apply(cs->to_rgb, xyz, rgb);
    for (int c = 0; c < 3; c++)
        rgb[c] = rgb[c] < 0 ? 0 : rgb[c] > 1 ? 1 : rgb[c];
}

static int kernel_alloc(kernel *k, int r)
{
    k->r = r;
    /* not xalloc: sized by the images (files): -1 to the caller */
    k->w = malloc((size_t)(2 * r + 1) * sizeof *k->w);
    return k->w ? 0 : -1;
}

/* Scales k's positive taps to sum to 1 and its negative ones to -1 (a sum that underflowed
 * to 0 is left alone). */
static void kernel_balance(kernel *k)
{
    double pos = 0, neg = 0;
    for (int i = 0; i <= 2 * k->r; i++)
        k->w[i] > 0 ? (pos += k->w[i]) : (neg -= k->w[i]);
    for (int i = 0; i <= 2 * k->r; i++)
        if (k->w[i] > 0 && pos > 0)
            k->w[i] /= pos;
        else if (k->w[i] < 0 && neg > 0)
            k->w[i] /= neg;
}

/* The CSFs as weighted sums of separable, unit-sum Gaussians: a 2D Gaussian's sum is its
 * 1D sum squared, so each term's share of the normalised filter is a sqrt(pi/b) S^2. */
static int csf_kernels(flip_work *wk, double ppd)
{
    int r = (int)ceil(3.0 * sqrt(CSF_WIDEST_B / (2.0 * PI * PI)) * ppd);
    for (int c = 0; c < 3; c++) {
        double total = 0;
        for (int t = 0; t < 2; t++) {
            kernel *k = &wk->csf_gauss[c][t];
            if (kernel_alloc(k, r) != 0)
                return -1;
            double b = csf[c][2 * t + 1], sum = 0;
            for (int i = -r; i <= r; i++)
                sum += k->w[i + r] = exp(-PI * PI * (i / ppd) * (i / ppd) / b);
            for (int i = 0; i <= 2 * r; i++)
                k->w[i] /= sum;
            wk->csf_weight[c][t] = csf[c][2 * t] * sqrt(PI / b) * sum * sum;
            total += wk->csf_weight[c][t];
        }
        for (int t = 0; t < 2; t++)
            wk->csf_weight[c][t] /= total;
    }
    return 0;
}

/* The feature detectors factor into x and y: (-x g(x)) g(y) for edges, (x^2/sd^2 - 1) g(x)
 * g(y) for points; their positive and negative parts are balanced along x (the sign
 * depends on x alone), g along y sums to 1. */
static int feature_kernels(flip_work *wk, double ppd)
{
    double sd = 0.5 * FEATURE_WIDTH * ppd;
    int r = (int)ceil(3.0 * sd);
    if (kernel_alloc(&wk->gauss, r) || kernel_alloc(&wk->edge, r) || kernel_alloc(&wk->point, r))
        return -1;
    double sum = 0;
    for (int i = -r; i <= r; i++) {
        double g = exp(-(double)i * i / (2.0 * sd * sd));
        sum += wk->gauss.w[i + r] = g;
        wk->edge.w[i + r] = -i * g;
        wk->point.w[i + r] = ((double)i * i / (sd * sd) - 1.0) * g;
    }
    for (int i = 0; i <= 2 * r; i++)
        wk->gauss.w[i] /= sum;
    kernel_balance(&wk->edge);
    kernel_balance(&wk->point);
    return 0;
}

static void work_free(flip_work *wk)
{
    for (int c = 0; c < 3; c++)
        for (int t = 0; t < 2; t++)
            free(wk->csf_gauss[c][t].w);
    free(wk->gauss.w);
    free(wk->edge.w);
    free(wk->point.w);
    for (int i = 0; i < 2; i++)
        for (int c = 0; c < 3; c++)
            free(wk->ycc[i][c]);
    free(wk->tmp);
    free(wk->a);
    free(wk->b);
    free(wk->ref_edge);
    free(wk->ref_point);
    free(wk->test_point);
    free(wk->feature);
}

static int work_init(flip_work *wk, int w, int h, double ppd)
{
    memset(wk, 0, sizeof *wk);
    wk->w = w;
    wk->h = h;
    wk->n = (size_t)w * h;
    colour_space_init(&wk->cs);
    int failed = csf_kernels(wk, ppd) || feature_kernels(wk, ppd);
    float **planes[] = {&wk->ycc[0][0], &wk->ycc[0][1], &wk->ycc[0][2], &wk->ycc[1][0],
                        &wk->ycc[1][1], &wk->ycc[1][2], &wk->tmp, &wk->a, &wk->b,
                        &wk->ref_edge, &wk->ref_point, &wk->test_point, &wk->feature};
    /* not xalloc: sized by the images (files): -1 to the caller */
    for (size_t i = 0; i < sizeof planes / sizeof *planes && !failed; i++)
        failed = !(*planes[i] = malloc(wk->n * sizeof(float)));
    if (failed)
        work_free(wk);
    return failed ? -1 : 0;
}

static int clampi(int v, int hi)
{
    return v < 0 ? 0 : v > hi ? hi : v;
}

/* dst = src correlated with kx along rows, then ky along columns; borders replicate. */
static void convolve(const flip_work *wk, const float *src, float *dst, const kernel *kx,
                     const kernel *ky)
{
    int w = wk->w, h = wk->h;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double s = 0;
            for (int i = -kx->r; i <= kx->r; i++)
                s += kx->w[i + kx->r] * src[(size_t)y * w + clampi(x + i, w - 1)];
            wk->tmp[(size_t)y * w + x] = (float)s;
        }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double s = 0;
            for (int i = -ky->r; i <= ky->r; i++)
                s += ky->w[i + ky->r] * wk->tmp[(size_t)clampi(y + i, h - 1) * w + x];
            dst[(size_t)y * w + x] = (float)s;
        }
}

/* |gradient| into edge and |second derivatives| into point, of the luminance Y/Yn, which
 * is (Y' + 16) / 116 of the YCxCz plane y; a, b and tmp are scratch. */
static void features(flip_work *wk, const float *y, float *edge, float *point)
{
    float *lum = point; /* read by all four filters before point is written */
    for (size_t i = 0; i < wk->n; i++)
        lum[i] = (y[i] + 16.0f) / 116.0f;
    convolve(wk, lum, wk->a, &wk->edge, &wk->gauss);
    convolve(wk, lum, wk->b, &wk->gauss, &wk->edge);
    for (size_t i = 0; i < wk->n; i++)
        edge[i] = hypotf(wk->a[i], wk->b[i]);
    convolve(wk, lum, wk->a, &wk->point, &wk->gauss);
    convolve(wk, lum, wk->b, &wk->gauss, &wk->point);
    for (size_t i = 0; i < wk->n; i++)
        point[i] = hypotf(wk->a[i], wk->b[i]);
}

/* dF per pixel into wk->feature, from the unfiltered luminance of both images. */
static void feature_difference(flip_work *wk)
{
    features(wk, wk->ycc[1][0], wk->ref_edge, wk->ref_point);
    features(wk, wk->ycc[0][0], wk->feature, wk->test_point);
    for (size_t i = 0; i < wk->n; i++) {
        double de = fabs(wk->ref_edge[i] - wk->feature[i]);
        double dp = fabs(wk->ref_point[i] - wk->test_point[i]);
        wk->feature[i] = (float)pow((de > dp ? de : dp) / sqrt(2.0), EXPONENT_FEATURE);
    }
}

/* Each channel of both images filtered with its CSF, in place. */
static void csf_filter(flip_work *wk)
{
    for (int im = 0; im < 2; im++)
        for (int c = 0; c < 3; c++) {
            float *p = wk->ycc[im][c];
            double w0 = wk->csf_weight[c][0], w1 = wk->csf_weight[c][1];
            convolve(wk, p, wk->a, &wk->csf_gauss[c][0], &wk->csf_gauss[c][0]);
            if (w1 > 0)
                convolve(wk, p, wk->b, &wk->csf_gauss[c][1], &wk->csf_gauss[c][1]);
            for (size_t i = 0; i < wk->n; i++)
                p[i] = (float)(w0 * wk->a[i] + (w1 > 0 ? w1 * wk->b[i] : 0.0));
        }
}

/* The colour difference of the filtered images, raised to 1 - dF, into map. */
static void colour_map(const flip_work *wk, float *map)
{
    double cmax = wk->cs.cmax, pccmax = REMAP_PC * cmax;
    for (size_t i = 0; i < wk->n; i++) {
        double lab[2][3];
        for (int im = 0; im < 2; im++) {
            double ycc[3] = {wk->ycc[im][0][i], wk->ycc[im][1][i], wk->ycc[im][2][i]}, rgb[3];
            from_ycxcz(&wk->cs, ycc, rgb);
            hunt_lab(&wk->cs, rgb, lab[im]);
        }
        double e = pow(hyab(lab[0], lab[1]), EXPONENT_COLOUR);
        double dc = e < pccmax ? REMAP_PT / pccmax * e
                               : REMAP_PT + (e - pccmax) / (cmax - pccmax) * (1.0 - REMAP_PT);
        map[i] = (float)pow(dc, 1.0 - wk->feature[i]);
    }
}

/* LDR-FLIP of two finite linear RGB images (values in [0, 1]) into map. */
static void flip_linear(flip_work *wk, const float *img, const float *ref, float *map)
{
    const float *src[2] = {img, ref};
    for (int im = 0; im < 2; im++)
        for (size_t i = 0; i < wk->n; i++) {
            double rgb[3] = {src[im][3 * i], src[im][3 * i + 1], src[im][3 * i + 2]}, ycc[3];
            to_ycxcz(&wk->cs, rgb, ycc);
            for (int c = 0; c < 3; c++)
                wk->ycc[im][c][i] = (float)ycc[c];
        }
    feature_difference(wk);
    csf_filter(wk);
    colour_map(wk, map);
}

static int pixel_counts(const flip_desc *d, const float *img, const float *ref, size_t i)
{
    if (d && d->mask && !d->mask[i])
        return 0;
    for (int c = 0; c < 3; c++)
        if (!isfinite(img[3 * i + c]) || !isfinite(ref[3 * i + c]))
            return 0;
    return 1;
}

/* Mean of map over counted pixels into out; -1 when none counts. */
static int mean_of(const flip_desc *d, const float *img, const float *ref, size_t n,
                   const float *map, flip_result *out)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        if (pixel_counts(d, img, ref, i)) {
            sum += map[i];
            out->pixels++;
        }
    out->mean = out->pixels ? sum / (double)out->pixels : 0;
    return out->pixels ? 0 : -1;
}

/* The viewer's ppd, or -1 for an invalid size or ppd. */
static double checked_ppd(int width, int height, const flip_desc *d)
{
    double ppd = d && d->ppd != 0 ? d->ppd : FLIP_DEFAULT_PPD;
    if (width <= 0 || height <= 0 || !(ppd > 0 && ppd <= MAX_PPD))
        return -1;
    return ppd;
}

static float srgb_decode(float v)
{
    double s = isfinite(v) ? (v < 0 ? 0 : v > 1 ? 1 : v) : 0;
    return (float)(s <= 0.04045 ? s / 12.92 : pow((s + 0.055) / 1.055, 2.4));
}

int flip_ldr(const float *img, const float *ref, int width, int height, const flip_desc *d,
             float *map, flip_result *out)
{
    memset(out, 0, sizeof *out);
    double ppd = checked_ppd(width, height, d);
    if (ppd < 0)
        return -1;
    size_t n = (size_t)width * height;
    /* not xalloc: sized by the images (files): -1 to the caller */
    float *lin = malloc(6 * n * sizeof *lin), *m = map ? map : malloc(n * sizeof *m);
    flip_work wk;
    int rc = -1;
    if (lin && m && work_init(&wk, width, height, ppd) == 0) {
        for (size_t i = 0; i < 3 * n; i++) {
            lin[i] = srgb_decode(img[i]);
            lin[3 * n + i] = srgb_decode(ref[i]);
        }
        flip_linear(&wk, lin, lin + 3 * n, m);
        work_free(&wk);
        out->exposures = 1;
        rc = mean_of(d, img, ref, n, m, out);
    }
    free(lin);
    if (m != map)
        free(m);
    return rc;
}

/* The tone curve after exposure: non-finite and negative radiance reads as 0. */
static float tone_map(float v, double scale)
{
    double x = isfinite(v) && v > 0 ? scale * v : 0;
    double y = (aces[0] * x * x + aces[1] * x) / (aces[2] * x * x + aces[3] * x + aces[4]);
    return (float)(isfinite(y) ? (y < 0 ? 0 : y > 1 ? 1 : y) : 1);
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static double median_sorted(const float *v, size_t n)
{
    return n % 2 ? v[n / 2] : 0.5 * ((double)v[n / 2 - 1] + v[n / 2]);
}

/* The exposures' range in stops from the reference's counted luminance: the max tone-maps
 * to 0.85 at the start, the median (of the lit pixels when it is 0) at the stop. */
static int exposure_range(const float *img, const float *ref, size_t n, const flip_desc *d,
                          double *start, double *stop)
{
    /* not xalloc: sized by the images (files): -1 to the caller */
    float *lum = malloc(n * sizeof *lum);
    if (!lum)
        return -1;
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (pixel_counts(d, img, ref, i))
            lum[k++] = (float)fmax(0.0, 0.2126 * ref[3 * i] + 0.7152 * ref[3 * i + 1] +
                                            0.0722 * ref[3 * i + 2]);
    qsort(lum, k, sizeof *lum, cmp_float);
    size_t lit = 0;
    while (lit < k && lum[lit] <= 0)
        lit++;
    *start = *stop = 0;
    if (lit < k) {
        double t = EXPOSURE_TONE, q = aces[0] - aces[2] * t;
        double c0 = (aces[1] - aces[3] * t) / q, c1 = -aces[4] * t / q;
        double x = -0.5 * c0 + sqrt(0.25 * c0 * c0 - c1);
        double median = median_sorted(lum, k);
        if (!(median > 0))
            median = median_sorted(lum + lit, k - lit);
        *start = log2(x / lum[k - 1]);
        *stop = log2(x / median);
    }
    free(lum);
    return k ? 0 : -1;
}

/* Every exposure's LDR-FLIP of the tone-mapped pair, the largest per pixel into map. */
static int hdr_map(const float *img, const float *ref, flip_work *wk, const flip_result *r,
                   float *map)
{
    size_t n = wk->n;
    /* not xalloc: sized by the images (files): -1 to the caller */
    float *tm = malloc(6 * n * sizeof *tm), *ldr = malloc(n * sizeof *ldr);
    double step = (r->stop_exposure - r->start_exposure) / (r->exposures > 1 ? r->exposures - 1 : 1);
    for (int e = 0; e < r->exposures && tm && ldr; e++) {
        double scale = exp2(r->start_exposure + e * step);
        for (size_t i = 0; i < 3 * n; i++) {
            tm[i] = tone_map(img[i], scale);
            tm[3 * n + i] = tone_map(ref[i], scale);
        }
        flip_linear(wk, tm, tm + 3 * n, ldr);
        for (size_t i = 0; i < n; i++)
            map[i] = e == 0 || ldr[i] > map[i] ? ldr[i] : map[i];
    }
    int rc = tm && ldr ? 0 : -1;
    free(tm);
    free(ldr);
    return rc;
}

int flip_hdr(const float *img, const float *ref, int width, int height, const flip_desc *d,
             float *map, flip_result *out)
{
    memset(out, 0, sizeof *out);
    double ppd = checked_ppd(width, height, d);
    if (ppd < 0)
        return -1;
    size_t n = (size_t)width * height;
    if (exposure_range(img, ref, n, d, &out->start_exposure, &out->stop_exposure) != 0)
        return -1;
    double range = out->stop_exposure - out->start_exposure;
    out->exposures = range > 0 ? (int)fmax(2.0, ceil(range)) : 1;
    /* not xalloc: sized by the images (files): -1 to the caller */
    float *m = map ? map : malloc(n * sizeof *m);
    flip_work wk;
    int rc = -1;
    if (m && work_init(&wk, width, height, ppd) == 0) {
        rc = hdr_map(img, ref, &wk, out, m);
        work_free(&wk);
        if (rc == 0)
            rc = mean_of(d, img, ref, n, m, out);
    }
    if (m != map)
        free(m);
    return rc;
}
