/* image_metrics: how far a rendered image is from a reference (no GL).
 *
 * Both images are width*height*3 linear floats, top row first (image_read_pfm's layout).
 * A pixel counts when the mask lets it in and all six of its channels (img and ref) are
 * finite; a masked-in pixel with a NaN/inf channel is left out and counted in nonfinite.
 * Means below run over counted pixels and the 3 channels unless said otherwise.
 *
 *   mae        = mean |img - ref|
 *   rmse_rel   = sqrt(mean (img - ref)^2) / mean(ref)
 *   relmse     = mean (img - ref)^2 / (ref^2 + epsilon)     (per channel, Rousselle et al.)
 *   ssim       = mean over counted pixels of SSIM (Wang et al. 2004) on Rec. 709 luminance
 *   mean, reference_mean = mean img, mean ref
 *   best_scale = sum(img*ref) / sum(img^2): the gain that best fits img to ref (1 if img is 0)
 *   mae_scaled = mean |best_scale*img - ref|: error left once the level is corrected
 *   rmse_rel_debiased = sqrt(max(mean (img - ref)^2 - noise^2, 0)) / mean(ref), noise the
 *              reference's own standard deviation (desc.reference_noise): a noisy reference
 *              adds its variance to the expected squared difference, and this takes it out
 *
 * SSIM: 11x11 Gaussian window, sigma 1.5, C1 = (0.01 L)^2, C2 = (0.03 L)^2; the window is
 * centred on every counted pixel, loses the taps that fall outside the image or on uncounted
 * pixels, and is renormalised to weigh 1 (so borders and mask edges need no padding).
 * Local means, variances and covariance are the window-weighted moments (no Bessel term).
 * L defaults to the maximum reference luminance over counted pixels (1 if that is not
 * positive).
 *
 * No signal: when the reference's mean over counted pixels is 0 (both images black, or a
 * black reference) there is nothing for rmse_rel and ssim to be relative to; no_signal is
 * set and both are NAN rather than a "perfect" 0 and 1. The absolute figures (mae, means,
 * relmse) stay defined and say how much light the image has where the reference has none.
 *
 * Allocates a width*height byte map of counted pixels and (6 * 11 + 3) * width doubles of
 * filter scratch, and frees both before returning. */
#ifndef CAVELIGHT_IMAGE_METRICS_H
#define CAVELIGHT_IMAGE_METRICS_H

#include <stddef.h>
#include <stdint.h>

typedef struct image_metrics_desc {
    const uint8_t *mask;   /* width*height, nonzero = pixel counts; NULL = all pixels */
    double ssim_range;     /* dynamic range L of SSIM's constants; 0 = max reference luminance */
    double relmse_epsilon; /* relMSE denominator ref^2 + epsilon; 0 = 1e-2 */
    double reference_noise; /* RMS over the counted samples of the reference's standard
                               deviation (reference_noise.indirect1_rms); 0 = exact */
} image_metrics_desc;

typedef struct image_metrics {
    double mae;            /* mean over counted pixels and the 3 channels of |img - ref| */
    double rmse_rel;       /* sqrt(mean (img-ref)^2) / mean(ref) */
    double rmse_rel_debiased; /* the same less the reference's noise (see above) */
    double relmse;         /* mean (img-ref)^2 / (ref^2 + epsilon) */
    double ssim;           /* mean SSIM of luminance (Rec. 709 weights) */
    double mean, reference_mean;
    double best_scale;     /* s minimising sum (s*img - ref)^2: how far off the level is */
    double mae_scaled;     /* MAE of best_scale * img */
    size_t pixels;         /* counted pixels */
    size_t nonfinite;      /* pixels of img or ref with a NaN/inf channel: excluded, and counted */
    int no_signal;         /* the reference's mean is 0: rmse_rel and ssim are NAN */
} image_metrics;

/* img and ref: width*height*3 linear floats (same layout as image_read_pfm). NULL desc = defaults.
 * Returns 0, or -1 if sizes are invalid or no pixel counts (out is then zero but for
 * nonfinite) or the scratch cannot be allocated. */
int image_metrics_compare(const float *img, const float *ref, int width, int height,
                          const image_metrics_desc *desc, image_metrics *out);

#endif
