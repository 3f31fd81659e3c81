#include "gi/vpl/vpl_select.h"

#include "base/fnv1a.h"

#include "base/fnv1a.h"

#include <math.h>
#include <string.h>

const char *const vpl_selection_names[VPL_SELECT_COUNT] = {"flux", "view", "regular"};

static double flux_sum(const vpl *v)
{
    double f = (double)v->flux[0] + v->flux[1] + v->flux[2];
    return f > 0 && isfinite(f) ? f : 0.0;
}

/* What q_j needs beyond the candidate (vpl_select.h): 1 / F and 1 / S of the view rule,
 * the texels' mean flux of the regular rule. */
typedef struct rule_sums {
    double f_over, v_over, texel_flux;
} rule_sums;

static rule_sums sums_of(const vpl_select_desc *d)
{
    rule_sums r = {0, 0, 0};
    double flux = 0, seen = 0, texel = 0;
    size_t lit = 0;
    for (size_t j = 0; j < d->count; j++) {
        double f = flux_sum(&d->candidates[j]);
        flux += f;
        if (d->rule == VPL_SELECT_VIEW && d->view[j] > 0 && isfinite(d->view[j]))
            seen += f * d->view[j];
        if (j < d->texels && f > 0) {
            texel += f;
            lit++;
        }
    }
    r.f_over = flux > 0 ? 1.0 / flux : 0.0;
    r.v_over = seen > 0 ? 1.0 / seen : 0.0; /* nothing seen: the flux rule */
    r.texel_flux = lit ? texel / (double)lit : 0.0;
    return r;
}

static double importance(const vpl_select_desc *d, const rule_sums *r, size_t j)
{
    double f = flux_sum(&d->candidates[j]);
    if (d->rule == VPL_SELECT_REGULAR && j < d->texels)
        return f > 0 ? r->texel_flux : 0.0;
    if (d->rule == VPL_SELECT_VIEW) {
        double v = d->view[j];
        return f * (r->f_over + (v > 0 && isfinite(v) ? v * r->v_over : 0.0));
    }
    return f;
}

int vpl_select(const vpl_select_desc *d, double *cdf, vpl *out, size_t *chosen)
{
    rule_sums r = sums_of(d);
    double total = 0;
    for (size_t j = 0; j < d->count; j++)
        cdf[j] = total += importance(d, &r, j);
    int n = d->n;
    if (!(total > 0) || n <= 0)
        return 0;
    size_t j = 0;
    double shared = vpl_slot_random(d->seed, 0, 0); /* the regular pattern's one offset */
    for (int i = 0; i < n; i++) {
        /* The first candidate whose sum exceeds the target owns it (its interval is not
         * empty). Targets increase with i, so one forward walk finds them all. */
        double u = d->rule == VPL_SELECT_REGULAR ? shared : vpl_slot_random(d->seed, i, 0);
        double target = ((double)i + u) / n * total;
        while (j + 1 < d->count && cdf[j] <= target)
            j++;
        while (importance(d, &r, j) == 0) /* a target rounded up to the total */
            j--;
        const vpl *c = &d->candidates[j];
        double scale = total / ((double)n * importance(d, &r, j)); /* 1 / (n p_j) */
        out[i] = *c;
        for (int k = 0; k < 3; k++)
            out[i].flux[k] = (float)(c->flux[k] * scale);
        out[i].area = (float)(c->area * scale);
        if (chosen)
            chosen[i] = j;
    }
    return n;
}

void vpl_view_term(const vpl *candidates, size_t count, size_t texels, const float *samples,
                   int nsamples, size_t stride, double *out)
{
    const double pi = 3.14159265358979323846;
    if (stride < 1)
        stride = 1;
    for (size_t j = 0; j < count; j++) {
        if ((j < texels ? j : j - texels) % stride) {
            out[j] = out[j - 1];
            continue;
        }
        const vpl *c = &candidates[j];
        double sum = 0;
        for (int s = 0; s < nsamples; s++) {
            const float *x = samples + 6 * s;
            double d[3] = {x[0] - c->position[0], x[1] - c->position[1], x[2] - c->position[2]};
            double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if (!(r2 > 0))
                continue;
            double r = sqrt(r2);
            double cos_l = (c->normal[0] * d[0] + c->normal[1] * d[1] + c->normal[2] * d[2]) / r;
            double cos_x = -(x[3] * d[0] + x[4] * d[1] + x[5] * d[2]) / r;
            if (cos_l > 0 && cos_x > 0)
                sum += cos_l * cos_x / (c->area + pi * r2);
        }
        out[j] = nsamples > 0 ? sum / nsamples : 0.0;
    }
}

uint64_t vpl_checksum(const vpl *v, int n)
{
    uint64_t h = FNV1A64_OFFSET;
    for (int i = 0; i < n; i++) {
        const float *f[4] = {v[i].position, v[i].normal, v[i].flux, &v[i].area};
        const int len[4] = {3, 3, 3, 1};
        for (int a = 0; a < 4; a++)
            for (int k = 0; k < len[a]; k++) {
                uint32_t bits;
                memcpy(&bits, &f[a][k], sizeof bits);
                h = fnv1a64_le(h, bits, 4);
            }
    }
    return h;
}
