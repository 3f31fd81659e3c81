/* flip: the FLIP image difference (no GL).
 *
 * LDR-FLIP: Andersson et al. 2020, "FLIP: A Difference Evaluator for Alternating Images".
 * HDR-FLIP: Andersson et al. 2021, "Visualizing Errors in Rendered High Dynamic Range
 * Images". Per pixel a value in [0, 1]: how visible the difference is when one flips
 * between the two images at ppd pixels per degree of visual angle.
 *
 *   colour:   linear RGB -> XYZ (D65) -> YCxCz; each opponent channel filtered with its
 *             contrast sensitivity function (sums of Gaussians, the paper's a and b);
 *             back to linear RGB, clamped to [0, 1]; CIELAB, a* and b* scaled by 0.01 L*
 *             (Hunt); HyAB distance |dL| + |d(a, b)|, raised to 0.7 and remapped so that
 *             0.4 of the largest (green against blue) lands on 0.95.
 *   features: on the luminance Y/Yn, first (edges) and second (points) derivatives of a
 *             Gaussian of standard deviation 0.041 ppd, positive weights summing to 1 and
 *             negative to -1; dF = (max(|d |edge||, |d |point||) / sqrt 2)^0.5.
 *   FLIP    = colour ^ (1 - dF).
 *
 * Borders replicate the edge pixel. LDR inputs are sRGB-encoded values in [0, 1].
 * HDR inputs are linear radiance: the reference's luminance sets exposures from
 * log2(x / max) to log2(x / median), x where the ACES tone curve (Narkowicz's fit,
 * exposure 0.6 folded in) reaches 0.85; max(2, ceil(range)) exposures evenly over that
 * range (one when it is empty); each exposure tone-maps both images, and a pixel's HDR-FLIP
 * is its largest LDR-FLIP. The median is that of the counted pixels' luminance (the lit
 * ones' when more than half are black).
 *
 * A pixel counts in the mean when the mask lets it in and its six channels are finite;
 * non-finite channels are read as 0 by the filters. The map, when given, gets every
 * pixel's value. LDR-FLIP is symmetric in its two images; HDR-FLIP is not (the
 * reference sets the exposures). */
#ifndef CAVELIGHT_FLIP_H
#define CAVELIGHT_FLIP_H

#include <stddef.h>
#include <stdint.h>

/* 0.7 m from a 0.7 m wide monitor of 3840 pixels: the paper's default viewer. */
#define FLIP_DEFAULT_PPD (3840.0 * 3.14159265358979323846 / 180.0)

typedef struct flip_desc {
    double ppd;          /* pixels per degree of visual angle; 0 = FLIP_DEFAULT_PPD */
    const uint8_t *mask; /* width*height, nonzero = pixel counts in the mean; NULL = all */
} flip_desc;

typedef struct flip_result {
    double mean;                          /* mean FLIP over counted pixels, in [0, 1] */
    size_t pixels;                        /* counted pixels */
    double start_exposure, stop_exposure; /* HDR: the exposures' range in stops; LDR: 0 */
    int exposures;                        /* HDR: how many; LDR: 1 */
} flip_result;

/* img and ref: width*height*3 floats, top row first (image_read_pfm's layout); map: NULL or
 * width*height floats. Returns 0, or -1 when the size or ppd is invalid, no pixel counts
 * or memory runs out. */
int flip_ldr(const float *img, const float *ref, int width, int height, const flip_desc *d,
             float *map, flip_result *out);
int flip_hdr(const float *img, const float *ref, int width, int height, const flip_desc *d,
             float *map, flip_result *out);

#endif
