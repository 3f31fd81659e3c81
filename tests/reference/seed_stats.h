/* seed_stats: how the vpl benchmark (cavelight-bench accuracy vpl) and test_vpl_reference
 * take a vpl image's error against the path tracer apart, one definition for both: the
 * per-pixel sums of one estimate over K seeds, its spread and the part of its mean that
 * more seeds do not remove, and one image's error against the truth. Test code only. */
#ifndef CAVELIGHT_SEED_STATS_H
#define CAVELIGHT_SEED_STATS_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

/* Per-pixel sums over the seeds of one estimate: its mean and its spread. */
typedef struct seed_sums {
    double *sum, *sq;
} seed_sums;

/* Adds x - minus (minus NULL: x) to the sums, n floats. */
static inline void seed_add(seed_sums *a, const float *x, const float *minus, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double v = (double)x[i] - (minus ? minus[i] : 0.0f);
        a->sum[i] += v;
        a->sq[i] += v * v;
    }
}

/* Over the covered pixels (coverage: one byte per RGB pixel), relative to mean: *spread,
 * one seed's standard deviation (RMS over the pixels, from the seeds' sample variance),
 * and the RMS of the seeds' mean less its own noise (var / k): the part of the mean that
 * more seeds do not remove. */
static inline double seed_bias(const seed_sums *a, const uint8_t *coverage, size_t n, int k,
                               double mean, double *spread)
{
    double var = 0, sq = 0;
    size_t covered = 0;
    for (size_t i = 0; i < n; i++) {
        if (!coverage[i / 3])
            continue;
        double m = a->sum[i] / k;
        var += k > 1 ? (a->sq[i] - k * m * m) / (k - 1) : 0.0;
        sq += m * m;
        covered++;
    }
    var /= (double)(covered ? covered : 1);
    sq /= (double)(covered ? covered : 1);
    *spread = sqrt(var) / mean;
    return sqrt(fmax(sq - var / k, 0.0)) / mean;
}

/* One image's relRMSE against the truth: err, its mean relRMSE against the reference over
 * the seeds, with the reference's own noise (ref_noise, relative) taken out. */
static inline double seed_error_vs_truth(double err, double ref_noise)
{
    return sqrt(fmax(err * err - ref_noise * ref_noise, 0.0));
}

#endif
