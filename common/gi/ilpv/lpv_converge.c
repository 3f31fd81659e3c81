#include "gi/ilpv/lpv_converge.h"

#include "base/fpmode.h"
#include "gi/gi_reuse.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int lpv_converge_init(lpv_converge *c, const int n[3], double threshold)
{
    memset(c, 0, sizeof *c);
    if (lpv_volume_init(&c->previous, n, LPV_LIGHT_CHANNELS) != 0)
        return -1;
    /* not xalloc: the lattice's size (a setting): -1 to the caller */
    c->slice_sums = malloc(2 * (size_t)n[2] * sizeof *c->slice_sums);
    if (!c->slice_sums) {
        lpv_converge_free(c);
        return -1;
    }
    c->threshold = threshold == 0.0 ? LPV_CONVERGE_DEFAULT_THRESHOLD : threshold;
    c->residual = INFINITY;
    return 0;
}

void lpv_converge_free(lpv_converge *c)
{
    lpv_volume_free(&c->previous);
    free(c->slice_sums);
    memset(c, 0, sizeof *c);
}

int lpv_converge_inputs_equal(const frame_params *a, const frame_params *b)
{
    return gi_reuse_inputs_equal(a, b) && a->lpv_steps == b->lpv_steps &&
           a->lambda_incr == b->lambda_incr;
}

int lpv_converge_begin(lpv_converge *c, const frame_params *p)
{
    c->skipped = c->threshold > 0.0 && c->have_last && c->residual < c->threshold &&
                 lpv_converge_inputs_equal(p, &c->last);
    c->last = *p;
    c->have_last = 1;
    c->frames_skipped += c->skipped;
    return c->skipped;
}

void lpv_converge_forget(lpv_converge *c)
{
    c->have_previous = 0;
    c->residual = INFINITY;
}

typedef struct residual_job {
    const lpv_volume *cur;
    lpv_volume *prev;
    double *sums;
    int compare;
} residual_job;

/* One z slice: both sums, then the slice of the result becomes the previous one. */
static void residual_slice(void *ctx, int z)
{
    const residual_job *j = ctx;
    fpmode mode = fpmode_enter();
    size_t plane = (size_t)j->cur->n[0] * j->cur->n[1], lo = (size_t)z * plane;
    double diff = 0.0, total = 0.0;
    for (int c = 0; c < LPV_LIGHT_CHANNELS; c++) {
        const float *a = j->cur->ch[c] + lo;
        float *b = j->prev->ch[c] + lo;
        for (size_t i = 0; i < plane; i++) {
            total += fabs((double)a[i]);
            if (j->compare)
                diff += fabs((double)a[i] - (double)b[i]);
            b[i] = a[i];
        }
    }
    j->sums[2 * z] = diff;
    j->sums[2 * z + 1] = total;
    fpmode_leave(mode);
}

double lpv_converge_end(lpv_converge *c, const lpv_volume *result, double pending,
                        workpool *pool)
{
    residual_job j = {result, &c->previous, c->slice_sums, c->have_previous};
    workpool_run(pool, result->n[2], residual_slice, &j);
    double diff = 0.0, total = 0.0;
    for (int z = 0; z < result->n[2]; z++) {
        diff += c->slice_sums[2 * z];
        total += c->slice_sums[2 * z + 1];
    }
    if (!c->have_previous)
        c->residual = INFINITY;
    else if (diff == 0.0)
        c->residual = isfinite(total) ? 0.0 : NAN; /* also a black result after a black one */
    else
        c->residual = diff / total; /* NaN stays NaN: never below the threshold */
    if (pending > c->residual || pending != pending)
        c->residual = pending;
    c->have_previous = 1;
    return c->residual;
}
