#include "lpv/lpv_transfer.h"

#include <math.h>

#include "lpv/sh.h"

/* z outermost, x fastest. Neighbour j and 25 - j are antipodal, which the sampling uses. */
const int lpv_transfer_offsets[LPV_NEIGHBOURS][3] = {
    {-1, -1, -1}, {0, -1, -1}, {1, -1, -1}, {-1, 0, -1}, {0, 0, -1}, {1, 0, -1},
    {-1, 1, -1},  {0, 1, -1},  {1, 1, -1},  {-1, -1, 0}, {0, -1, 0}, {1, -1, 0},
    {-1, 0, 0},   {1, 0, 0},   {-1, 1, 0},  {0, 1, 0},   {1, 1, 0},  {-1, -1, 1},
    {0, -1, 1},   {1, -1, 1},  {-1, 0, 1},  {0, 0, 1},   {1, 0, 1},  {-1, 1, 1},
    {0, 1, 1},    {1, 1, 1},
};

enum { RANDOM_DISTRIBUTIONS = 64 };

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

static void cosine_lobe_d(const double w[3], double out[4]) /* w unit */
{
    out[0] = SH_COS0;
    out[1] = -SH_COS1 * w[1];
    out[2] = SH_COS1 * w[2];
    out[3] = -SH_COS1 * w[0];
}

/* Mean clamped-cosine lobe towards points uniform in neighbour cell o (source cell centred
 * at the origin, unit cells), keeping only points inside the visibility cone: the cone
 * from the source centre that touches the neighbour's inscribed sphere, half-angle
 * asin(0.5 / |o|) (30 deg for faces, 20.7 for edges, 16.8 for corners). */
static int sample_neighbour(const int o[3], int samples, uint64_t *rng, double out[4])
{
    double len = sqrt((double)(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]));
    double axis[3] = {o[0] / len, o[1] / len, o[2] / len};
    double cos_cone = sqrt(1.0 - 0.25 / (len * len));
    double acc[4] = {0, 0, 0, 0};
    long accepted = 0, tries = 0, max_tries = (long)samples * 1000;
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
        cosine_lobe_d(w, lobe);
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

/* Mean relative energy error of one unblocked step out of a cell holding L, over the
 * random distributions, for transfer vectors kappa * raw. */
static double energy_error(double kappa, const double raw[LPV_NEIGHBOURS][4],
                           const double dist[RANDOM_DISTRIBUTIONS][4], int use_max)
{
    double total = 0.0;
    for (int r = 0; r < RANDOM_DISTRIBUTIONS; r++) {
        const double *L = dist[r];
        double out0 = 0.0;
        for (int j = 0; j < LPV_NEIGHBOURS; j++) {
            double g[4];
            for (int s = 0; s < 4; s++)
                g[s] = kappa * raw[j][s];
            double flux = L[0] * g[0] + L[1] * g[1] + L[2] * g[2] + L[3] * g[3];
            out0 += flux * g[0];
        }
        double e = fabs(out0 - L[0]) / L[0];
        total = use_max ? fmax(total, e) : total + e / RANDOM_DISTRIBUTIONS;
    }
    return total;
}

int lpv_transfer_compute(const lpv_transfer_desc *desc, lpv_transfer *out)
{
    lpv_transfer_desc d = desc ? *desc : (lpv_transfer_desc){0};
    int samples = d.samples_per_neighbour > 0 ? d.samples_per_neighbour : 4096;
    uint64_t rng = d.seed ? d.seed : 0x6361766531696768ull;
    double lo = d.search_lo, hi = d.search_hi;
    if (lo == 0.0 && hi == 0.0) {
        lo = 0.1;
        hi = 0.4;
    }
    double tol = d.tolerance > 0.0 ? d.tolerance : 1e-6;
    if (!(lo > 0.0) || !(hi > lo) || !isfinite(hi))
        return -1;

    /* Sample the 13 neighbours with j >= 13; their antipodes get the mirrored lobe, so
     * the directional parts cancel exactly and energy conservation does not depend on
     * the direction of the light. */
    double raw[LPV_NEIGHBOURS][4];
    for (int j = LPV_NEIGHBOURS / 2; j < LPV_NEIGHBOURS; j++) {
        if (sample_neighbour(lpv_transfer_offsets[j], samples, &rng, raw[j]) != 0)
            return -1;
        int k = LPV_NEIGHBOURS - 1 - j;
        raw[k][0] = raw[j][0];
        for (int s = 1; s < 4; s++)
            raw[k][s] = -raw[j][s];
    }

    /* Random positive distributions: a clamped-cosine lobe of random direction and weight
     * plus a random isotropic part. */
    double dist[RANDOM_DISTRIBUTIONS][4];
    for (int r = 0; r < RANDOM_DISTRIBUTIONS; r++) {
        double z = 2.0 * rng_uniform(&rng) - 1.0, phi = 6.283185307179586 * rng_uniform(&rng);
        double rr = sqrt(fmax(0.0, 1.0 - z * z));
        double w[3] = {rr * cos(phi), rr * sin(phi), z};
        double a = rng_uniform(&rng), b = 0.05 + rng_uniform(&rng);
        cosine_lobe_d(w, dist[r]);
        for (int s = 0; s < 4; s++)
            dist[r][s] *= a;
        dist[r][0] += b;
    }

    /* Golden-section search for the scale that minimizes the mean energy error. */
    const double inv_phi = 0.6180339887498949;
    double a = lo, b = hi;
    double c = b - (b - a) * inv_phi, dd = a + (b - a) * inv_phi;
    double fc = energy_error(c, raw, dist, 0), fd = energy_error(dd, raw, dist, 0);
    int probes = 2;
    while ((b - a) > tol * (fabs(c) + fabs(dd)) && probes < 200) {
        if (fc < fd) {
            b = dd;
            dd = c;
            fd = fc;
            c = b - (b - a) * inv_phi;
            fc = energy_error(c, raw, dist, 0);
        } else {
            a = c;
            c = dd;
            fc = fd;
            dd = a + (b - a) * inv_phi;
            fd = energy_error(dd, raw, dist, 0);
        }
        probes++;
    }
    double kappa = fc < fd ? c : dd;

    double sum0 = 0.0;
    double scaled[LPV_NEIGHBOURS][4];
    for (int j = 0; j < LPV_NEIGHBOURS; j++) {
        for (int s = 0; s < 4; s++) {
            out->gamma[j][s] = (float)(kappa * raw[j][s]);
            scaled[j][s] = out->gamma[j][s];
        }
        sum0 += out->gamma[j][0];
    }
    for (int j = 0; j < LPV_NEIGHBOURS; j++)
        out->outscatter[j] = (float)(out->gamma[j][0] / sum0);
    out->kappa = kappa;
    out->energy_error = energy_error(1.0, scaled, dist, 1); /* with the stored floats */
    out->search_probes = probes;
    return 0;
}

float lpv_transfer_step_probability(float sigma_per_metre, float cell)
{
    double sigma = sigma_per_metre;
    if (!(sigma > 0.0)) /* also NaN */
        return 0.0f;
    if (sigma >= 1.0)
        sigma = 1.0;
    double d = (double)LPV_MEAN_NEIGHBOUR_DISTANCE * cell;
    if (!(d > 0.0))
        return 0.0f;
    return (float)(1.0 - pow(1.0 - sigma, d));
}
