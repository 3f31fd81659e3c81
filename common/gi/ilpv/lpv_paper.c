#include "gi/ilpv/lpv_paper.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>

#include "gi/ilpv/sh.h"

enum { DEFAULT_SAMPLES = 1 << 16, RANDOM_DISTRIBUTIONS = 64, MAX_PROBES = 200 };

/* splitmix64: tiny, portable, the same sequence on every machine. */
static uint64_t rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static double rng_uniform(uint64_t *s) /* [0, 1) */
{
    return (double)(rng_next(s) >> 11) * (1.0 / 9007199254740992.0);
}

static void cosine_lobe(const double w[3], double out[4]) /* w unit */
{
    out[0] = SH_COS0;
    out[1] = -SH_COS1 * w[1];
    out[2] = SH_COS1 * w[2];
    out[3] = -SH_COS1 * w[0];
}

/* Mean clamped-cosine lobe towards points uniform in the unit neighbour cell at offset o
 * (the source cell centred at the origin), keeping the points inside the visibility cone. */
static int sample_neighbour(const int o[3], int samples, uint64_t *rng, double out[4])
{
    double len = sqrt((double)(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]));
    double axis[3] = {o[0] / len, o[1] / len, o[2] / len};
    double cos_cone = sqrt(1.0 - 0.25 / (len * len));
    double acc[4] = {0, 0, 0, 0};
    long accepted = 0, tries = 0, max_tries = (long)samples * 100;
    while (accepted < samples && tries < max_tries) {
        tries++;
        double p[3];
        for (int a = 0; a < 3; a++)
            p[a] = o[a] + rng_uniform(rng) - 0.5;
        double pl = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        double w[3] = {p[0] / pl, p[1] / pl, p[2] / pl};
        if (w[0] * axis[0] + w[1] * axis[1] + w[2] * axis[2] < cos_cone)
            continue;
        double lobe[4];
        cosine_lobe(w, lobe);
        for (int s = 0; s < 4; s++)
            acc[s] += lobe[s];
        accepted++;
    }
    if (accepted < samples)
        return -1;
    for (int s = 0; s < 4; s++)
        out[s] = acc[s] / (double)accepted;
    return 0;
}

/* Mean relative |energy change| of one linear step (the thesis's constraint
 * sum_j <<L|G_j>|1> = <L|1>) out of a cell holding each distribution, for vectors
 * scale * raw. */
static double energy_error(double scale, const double raw[LPV_NEIGHBOURS][4],
                           const double dist[RANDOM_DISTRIBUTIONS][4])
{
    double total = 0.0;
    for (int r = 0; r < RANDOM_DISTRIBUTIONS; r++) {
        const double *L = dist[r];
        double out0 = 0.0;
        for (int j = 0; j < LPV_NEIGHBOURS; j++) {
            const double *g = raw[j];
            double p = scale * scale * (L[0] * g[0] + L[1] * g[1] + L[2] * g[2] + L[3] * g[3]);
            out0 += p * g[0];
        }
        total += fabs(out0 - L[0]) / L[0];
    }
    return total / RANDOM_DISTRIBUTIONS;
}

/* Random positive distributions: a clamped-cosine lobe of random direction and weight
 * plus isotropic light. */
static void random_distributions(uint64_t *rng, double dist[RANDOM_DISTRIBUTIONS][4])
{
    for (int r = 0; r < RANDOM_DISTRIBUTIONS; r++) {
        double z = 2.0 * rng_uniform(rng) - 1.0, phi = 6.283185307179586 * rng_uniform(rng);
        double rr = sqrt(fmax(0.0, 1.0 - z * z));
        double w[3] = {rr * cos(phi), rr * sin(phi), z};
        double a = rng_uniform(rng), b = 0.05 + rng_uniform(rng);
        cosine_lobe(w, dist[r]);
        for (int s = 0; s < 4; s++)
            dist[r][s] *= a;
        dist[r][0] += b;
    }
}

/* Golden-section search (LPV-MATH.md's standard form) for the scale in [lo, hi] with the
 * least energy error. */
static double search_scale(double lo, double hi, double tol, const double raw[LPV_NEIGHBOURS][4],
                           const double dist[RANDOM_DISTRIBUTIONS][4], int *probes)
{
    const double inv_phi = 0.6180339887498949;
    double a = lo, b = hi;
    double c = b - (b - a) * inv_phi, d = a + (b - a) * inv_phi;
    double fc = energy_error(c, raw, dist), fd = energy_error(d, raw, dist);
    int n = 2;
    while ((b - a) > tol * (fabs(c) + fabs(d)) && n < MAX_PROBES) {
        if (fc < fd) {
            b = d;
            d = c;
            fd = fc;
            c = b - (b - a) * inv_phi;
            fc = energy_error(c, raw, dist);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + (b - a) * inv_phi;
            fd = energy_error(d, raw, dist);
        }
        n++;
    }
    *probes = n;
    return fc < fd ? c : d;
}

int lpv_paper_transfer_compute(const lpv_paper_desc *desc, lpv_paper_transfer *out)
{
    lpv_paper_desc d = desc ? *desc : (lpv_paper_desc){0};
    int samples = d.samples_per_neighbour > 0 ? d.samples_per_neighbour : DEFAULT_SAMPLES;
    uint64_t rng = d.seed ? d.seed : LPV_PAPER_DEFAULT_SEED;
    double lo = d.search_lo, hi = d.search_hi;
    if (lo == 0.0 && hi == 0.0) {
        lo = 0.1;
        hi = 0.4;
    }
    double tol = d.tolerance > 0.0 ? d.tolerance : 1e-6;
    if (!(lo > 0.0) || !(hi > lo) || !isfinite(hi) || !isfinite(tol))
        return -1;
    double raw[LPV_NEIGHBOURS][4], dist[RANDOM_DISTRIBUTIONS][4];
    for (int j = 0; j < LPV_NEIGHBOURS; j++)
        if (sample_neighbour(lpv_transfer_offsets[j], samples, &rng, raw[j]) != 0)
            return -1;
    random_distributions(&rng, dist);
    lpv_paper_transfer t;
    t.kappa = search_scale(lo, hi, tol, raw, dist, &t.search_probes);
    double scaled[LPV_NEIGHBOURS][4], sum0 = 0.0, sum00 = 0.0, tilt[3] = {0, 0, 0};
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        for (int s = 0; s < 4; s++) {
            t.gamma[j][s] = (float)(t.kappa * raw[j][s]);
            scaled[j][s] = t.gamma[j][s];
        }
        sum0 += scaled[j][0];
        sum00 += scaled[j][0] * scaled[j][0];
        for (int s = 1; s < 4; s++)
            tilt[s - 1] += scaled[j][0] * scaled[j][s];
    }
    for (int j = 0; j < LPV_NEIGHBOURS; j++)
        t.outscatter[j] = (float)(scaled[j][0] / sum0);
    t.energy_error = energy_error(1.0, scaled, dist);
    t.imbalance = sqrt(tilt[0] * tilt[0] + tilt[1] * tilt[1] + tilt[2] * tilt[2]) / sum00;
    *out = t;
    return 0;
}

static lpv_paper_transfer default_transfer;
static pthread_once_t default_once = PTHREAD_ONCE_INIT;

static void compute_default(void)
{
    if (lpv_paper_transfer_compute(NULL, &default_transfer) != 0) /* cannot fail: fixed desc */
        fprintf(stderr, "lpv_paper: the default transfer vectors failed\n");
}

const lpv_paper_transfer *lpv_paper_transfer_default(void)
{
    pthread_once(&default_once, compute_default);
    return &default_transfer;
}

float lpv_paper_step_probability(float sigma_per_metre, float cell)
{
    return lpv_transfer_step_probability(sigma_per_metre, LPV_MEAN_NEIGHBOUR_DISTANCE * cell);
}

size_t lpv_paper_shader_body(const lpv_paper_transfer *t, char *out, size_t n)
{
    size_t used = 0;
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        const int *o = lpv_transfer_offsets[j];
        const float *g = t->gamma[j];
        int w = snprintf(out + used, n - used,
                         "    gather(cell, ivec3(%d, %d, %d), %d, vec4(%.9g, %.9g, %.9g, "
                         "%.9g), %.9g, ar, ag, ab);\n",
                         o[0], o[1], o[2], j, g[0], g[1], g[2], g[3], t->outscatter[j]);
        if (w < 0 || (size_t)w >= n - used)
            return 0;
        used += (size_t)w;
    }
    return used;
}
