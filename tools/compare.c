/* cavelight-compare: error metrics of one image against a reference, as one JSON line.
 *
 * PFM files are linear radiance; PNG files are display images, read as 8-bit values / 255
 * with no linearisation (compare PNGs only with PNGs). Exit 0; 2 with one line on stderr
 * naming the file or argument at fault; 3 when the reference has no signal (black over the
 * compared pixels: relative RMSE and SSIM are undefined, printed as null) unless
 * --allow-no-signal. --flip adds the mean FLIP (common/image/flip.h): LDR-FLIP of two PNGs
 * (sRGB), HDR-FLIP of two PFMs. */
#include <cjson/cJSON.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/cli.h"
#include "image/flip.h"
#include "image/image.h"
#include "image/image_metrics.h"

enum { O_MASK_BACKGROUND, O_SSIM_RANGE, O_CROP, O_ALLOW_NO_SIGNAL, O_FLIP, O_PPD };

static const cli_option options[] = {
    {O_MASK_BACKGROUND, "mask-background", NULL, NULL, 0, 0,
     "count only pixels where the reference is not 0 in all channels"},
    {O_SSIM_RANGE, "ssim-range", "L", "the largest reference luminance", 0, 0, "SSIM dynamic range"},
    {O_CROP, "crop", "x,y,w,h", "the whole image", 0, 0, "compare only this rectangle (top-left origin)"},
    {O_ALLOW_NO_SIGNAL, "allow-no-signal", NULL, NULL, 0, 0,
     "exit 0 even when the reference is black (no signal)"},
    {O_FLIP, "flip", NULL, NULL, 0, 0,
     "also the mean FLIP (Andersson et al.): LDR-FLIP of PNGs, HDR-FLIP of PFMs"},
    {O_PPD, "ppd", "P", "67.02 (0.7 m from a 0.7 m wide 4K monitor)", 0, 0,
     "FLIP's pixels per degree of visual angle"},
};

typedef struct compare_options {
    int mask_background, allow_no_signal, cropping, flip;
    int crop[4];
    double ppd;
    image_metrics_desc desc;
} compare_options;

static const char *set(void *user, int id, const char *v)
{
    compare_options *o = user;
    char extra;
    switch (id) {
    case O_MASK_BACKGROUND: o->mask_background = 1; break;
    case O_ALLOW_NO_SIGNAL: o->allow_no_signal = 1; break;
    case O_FLIP: o->flip = 1; break;
    case O_PPD:
        if (sscanf(v, "%lf%c", &o->ppd, &extra) != 1 || !(o->ppd > 0 && o->ppd <= 1000))
            return "a number in (0, 1000]";
        break;
    case O_SSIM_RANGE:
        if (sscanf(v, "%lf%c", &o->desc.ssim_range, &extra) != 1 || !(o->desc.ssim_range > 0))
            return "a positive number";
        break;
    case O_CROP:
        if (sscanf(v, "%d,%d,%d,%d%c", &o->crop[0], &o->crop[1], &o->crop[2], &o->crop[3], &extra) != 4 ||
            o->crop[0] < 0 || o->crop[1] < 0 || o->crop[2] <= 0 || o->crop[3] <= 0)
            return "x,y,w,h with x,y >= 0 and w,h > 0";
        o->cropping = 1;
        break;
    }
    return NULL;
}

/* Reads a PFM or PNG (told apart by their magic bytes) into linear-layout floats. */
static int read_image(const char *role, const char *path, int *w, int *h, float **rgb, int *png)
{
    char err[512];
    unsigned char magic[2] = {0};
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "cavelight-compare: %s %s: cannot open (%s)\n", role, path,
                strerror(errno));
        return -1;
    }
    size_t got = fread(magic, 1, 2, f);
    fclose(f);
    if (got == 2 && magic[0] == 'P' && magic[1] == 'F') {
        if (image_read_pfm(path, w, h, rgb, err, sizeof err) == 0)
            return 0;
    } else if (got == 2 && magic[0] == 0x89 && magic[1] == 'P') {
        uint8_t *bytes = NULL;
        *png = 1;
        if (image_read_png(path, w, h, &bytes, err, sizeof err) == 0) {
            size_t n = (size_t)*w * *h * 3;
            /* not xalloc: the image file's size: refused naming the file */
            *rgb = malloc(n * sizeof **rgb);
            if (*rgb)
                for (size_t i = 0; i < n; i++)
                    (*rgb)[i] = bytes[i] / 255.0f;
            free(bytes);
            if (*rgb)
                return 0;
            snprintf(err, sizeof err, "%s: out of memory", path);
        }
    } else {
        snprintf(err, sizeof err, "%s: neither a PFM nor a PNG file", path);
    }
    fprintf(stderr, "cavelight-compare: %s %s\n", role, err);
    return -1;
}

/* Copies the rectangle (x, y, cw, ch) of a w-wide image into a new buffer. */
static float *crop_image(const float *rgb, int w, int x, int y, int cw, int ch)
{
    /* not xalloc: the image's size: NULL is refused by the caller */
    float *out = malloc((size_t)cw * ch * 3 * sizeof *out);
    if (out)
        for (int r = 0; r < ch; r++)
            memcpy(out + (size_t)r * cw * 3, rgb + ((size_t)(y + r) * w + x) * 3,
                   (size_t)cw * 3 * sizeof *out);
    return out;
}

/* Both images at one size, cropped when asked. 0, or -1 after one line on stderr. */
static int load_pair(const char *const paths[2], const compare_options *opt, int *width, int *height,
                     float *rgb[2], int png[2])
{
    int w[2], h[2];
    if (read_image("image", paths[0], &w[0], &h[0], &rgb[0], &png[0]) != 0 ||
        read_image("reference", paths[1], &w[1], &h[1], &rgb[1], &png[1]) != 0)
        return -1;
    if (opt->flip && png[0] != png[1]) {
        fprintf(stderr, "cavelight-compare: --flip: image %s is a %s but reference %s a %s; "
                        "give two PNGs (LDR-FLIP) or two PFMs (HDR-FLIP)\n", paths[0],
                png[0] ? "PNG" : "PFM", paths[1], png[1] ? "PNG" : "PFM");
        return -1;
    }
    if (w[0] != w[1] || h[0] != h[1]) {
        fprintf(stderr, "cavelight-compare: size mismatch: image %s is %dx%d but reference "
                        "%s is %dx%d; render both at the same size\n",
                paths[0], w[0], h[0], paths[1], w[1], h[1]);
        return -1;
    }
    *width = w[0];
    *height = h[0];
    if (!opt->cropping)
        return 0;
    const int *crop = opt->crop;
    if (crop[0] + crop[2] > *width || crop[1] + crop[3] > *height) {
        fprintf(stderr, "cavelight-compare: --crop %d,%d,%d,%d does not fit in the "
                        "%dx%d images\n", crop[0], crop[1], crop[2], crop[3], *width, *height);
        return -1;
    }
    for (int k = 0; k < 2; k++) {
        float *c = crop_image(rgb[k], *width, crop[0], crop[1], crop[2], crop[3]);
        if (!c) {
            fprintf(stderr, "cavelight-compare: out of memory cropping %s\n", paths[k]);
            return -1;
        }
        free(rgb[k]);
        rgb[k] = c;
    }
    *width = crop[2];
    *height = crop[3];
    return 0;
}

/* --mask-background: the pixels where the reference is not exactly 0 (the rasterizer
 * writes 0 where no geometry is); NULL when the reference is all black, so that every
 * pixel is compared and no signal is reported. *failed on out of memory. */
static uint8_t *background_mask(const float *reference, size_t n, int *failed)
{
    /* not xalloc: the image's size: refused in one line */
    uint8_t *mask = malloc(n);
    if (!mask) {
        fprintf(stderr, "cavelight-compare: out of memory for the mask\n");
        *failed = 1;
        return NULL;
    }
    size_t kept = 0;
    for (size_t i = 0; i < n; i++)
        kept += mask[i] = reference[i * 3] != 0 || reference[i * 3 + 1] != 0 || reference[i * 3 + 2] != 0;
    if (kept)
        return mask;
    free(mask);
    return NULL;
}

/* The metrics as one JSON line on stdout. Returns the exit code: 0, 2 (out of memory)
 * or 3 (no signal, unless allowed). */
/* The FLIP fields: mean, mode and viewer; HDR-FLIP's exposures. */
static void add_flip(cJSON *o, const flip_result *f, int hdr, double ppd)
{
    cJSON_AddNumberToObject(o, "flip", f->mean);
    cJSON_AddStringToObject(o, "flip_mode", hdr ? "hdr" : "ldr");
    cJSON_AddNumberToObject(o, "flip_ppd", ppd);
    if (hdr) {
        cJSON_AddNumberToObject(o, "flip_start_exposure", f->start_exposure);
        cJSON_AddNumberToObject(o, "flip_stop_exposure", f->stop_exposure);
        cJSON_AddNumberToObject(o, "flip_exposures", f->exposures);
    }
}

static int print_metrics(const char *const paths[2], int width, int height, const image_metrics *m,
                         const compare_options *opt, const flip_result *flip, int hdr)
{
    int allow_no_signal = opt->allow_no_signal;
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "image", paths[0]);
    cJSON_AddStringToObject(o, "reference", paths[1]);
    cJSON_AddNumberToObject(o, "width", width);
    cJSON_AddNumberToObject(o, "height", height);
    cJSON_AddNumberToObject(o, "pixels", (double)m->pixels);
    cJSON_AddNumberToObject(o, "nonfinite", (double)m->nonfinite);
    cJSON_AddNumberToObject(o, "mae", m->mae);
    cJSON_AddNumberToObject(o, "rmse_rel", m->rmse_rel);
    cJSON_AddNumberToObject(o, "relmse", m->relmse);
    cJSON_AddNumberToObject(o, "ssim", m->ssim);
    cJSON_AddNumberToObject(o, "mean", m->mean);
    cJSON_AddNumberToObject(o, "reference_mean", m->reference_mean);
    cJSON_AddNumberToObject(o, "best_scale", m->best_scale);
    cJSON_AddNumberToObject(o, "mae_scaled", m->mae_scaled);
    cJSON_AddBoolToObject(o, "signal", !m->no_signal);
    if (flip)
        add_flip(o, flip, hdr, opt->ppd ? opt->ppd : FLIP_DEFAULT_PPD);
    char *text = cJSON_PrintUnformatted(o);
    int rc = 2;
    if (text) {
        printf("%s\n", text);
        rc = 0;
        if (m->no_signal && !allow_no_signal) {
            fprintf(stderr, "cavelight-compare: no signal: reference %s is black over the %zu "
                            "compared pixels (image mean %g), so relative RMSE and SSIM are "
                            "undefined; give --allow-no-signal to accept\n",
                    paths[1], m->pixels, m->mean);
            rc = 3;
        }
    } else {
        fprintf(stderr, "cavelight-compare: out of memory printing JSON\n");
    }
    cJSON_free(text);
    cJSON_Delete(o);
    return rc;
}

int main(int argc, char **argv)
{
    static const char *const groups[] = {"Options"};
    compare_options opt = {0};
    cli_program p = {
        .name = "cavelight-compare",
        .usage = "usage: cavelight-compare IMAGE REFERENCE [options]\n"
                 "  IMAGE, REFERENCE  PFM (linear) or PNG (8-bit display values / 255, not linearised)\n",
        .groups = groups, .group_count = 1,
        .options = options, .count = (int)(sizeof options / sizeof *options),
        .epilogue = "Prints one JSON object with the metrics of common/image/image_metrics.h\n"
                    "(and with --flip those of common/image/flip.h).\n"
                    "Exit 0; 2 on bad input; 3 when the reference has no signal.\n",
        .set = set, .user = &opt,
    };
    const char *paths[2] = {NULL, NULL};
    int npaths;
    cli_given given;
    switch (cli_parse(&p, argc, argv, paths, 2, &npaths, &given)) {
    case CLI_HELP: return 0;
    case CLI_ERROR: return 2;
    default: break;
    }
    if (npaths != 2) {
        fprintf(stderr, "cavelight-compare: give IMAGE and REFERENCE (see --help)\n");
        return 2;
    }
    int width, height, failed = 0, rc = 2;
    float *rgb[2] = {NULL, NULL};
    int png[2] = {0, 0};
    uint8_t *mask = NULL;
    if (load_pair(paths, &opt, &width, &height, rgb, png) != 0)
        goto done;
    image_metrics_desc desc = opt.desc;
    if (opt.mask_background && !(desc.mask = mask = background_mask(rgb[1], (size_t)width * height, &failed)) &&
        failed)
        goto done;
    image_metrics m;
    if (image_metrics_compare(rgb[0], rgb[1], width, height, &desc, &m) != 0) {
        fprintf(stderr, "cavelight-compare: no pixel to compare in %s against %s (%zu with "
                        "NaN/inf%s)\n", paths[0], paths[1], m.nonfinite,
                opt.mask_background ? ", the rest background" : "");
        goto done;
    }
    flip_result flip;
    flip_desc fd = {.ppd = opt.ppd, .mask = desc.mask};
    if (opt.flip && (png[0] ? flip_ldr : flip_hdr)(rgb[0], rgb[1], width, height, &fd, NULL, &flip) != 0) {
        fprintf(stderr, "cavelight-compare: --flip: out of memory comparing %s against %s\n",
                paths[0], paths[1]);
        goto done;
    }
    rc = print_metrics(paths, width, height, &m, &opt, opt.flip ? &flip : NULL, !png[0]);
done:
    free(rgb[0]);
    free(rgb[1]);
    free(mask);
    return rc;
}
