#include "gi/ilpv/lpv_paper_frame.h"

#include <math.h>
#include <string.h>

#include "base/fpmode.h"

lpv_paper_merge lpv_paper_merge_factors(const lpv_paper_history *h, float lambda_incr,
                                        double emitted_energy)
{
    lpv_paper_merge m = {0.0f, 1.0f};
    if (!(lambda_incr > 0.0f) || !h->have_history || !(h->previous_energy > 0.0) ||
        !(emitted_energy >= 0.0) || !isfinite(emitted_energy))
        return m; /* also for a negative or NaN energy: no scale can be trusted */
    m.a = (float)(emitted_energy / h->previous_energy * lambda_incr);
    m.b = 1.0f - lambda_incr;
    return m;
}

void lpv_paper_history_advance(lpv_paper_history *h, double emitted_energy)
{
    h->have_history = 1;
    h->previous_energy = isfinite(emitted_energy) && emitted_energy > 0.0 ? emitted_energy : 0.0;
}

typedef struct merge_job {
    const lpv_volume *history, *injected;
    lpv_volume *out;
    lpv_paper_merge m;
} merge_job;

/* One z slice of out = a history + b injected. */
static void merge_slice(void *ctx, int z)
{
    const merge_job *j = ctx;
    fpmode mode = fpmode_enter();
    size_t plane = (size_t)j->out->n[0] * j->out->n[1], lo = (size_t)z * plane;
    for (int c = 0; c < LPV_LIGHT_CHANNELS; c++) {
        const float *h = j->history->ch[c] + lo, *in = j->injected->ch[c] + lo;
        float *o = j->out->ch[c] + lo;
        if (j->m.a != 0.0f)
            for (size_t i = 0; i < plane; i++)
                o[i] = j->m.a * h[i] + j->m.b * in[i];
        else /* no history: never read it, it may hold anything */
            for (size_t i = 0; i < plane; i++)
                o[i] = j->m.b * in[i];
    }
    fpmode_leave(mode);
}

void lpv_paper_merge_run(lpv_paper_merge m, const lpv_volume *history,
                         const lpv_volume *injected, lpv_volume *out, workpool *pool)
{
    merge_job j = {history, injected, out, m};
    workpool_run(pool, out->n[2], merge_slice, &j);
}

/* The injection and the two volumes of the merge and the ping-pong. */
enum { PAPER_VOLUMES = 3 };

double lpv_paper_state_bytes(const lattice_desc *lat)
{
    return (double)lattice_cell_count(lat) * PAPER_VOLUMES * LPV_LIGHT_CHANNELS * sizeof(float);
}

int lpv_paper_init(lpv_paper_lpv *s, const lattice_desc *lat)
{
    memset(s, 0, sizeof *s);
    if (!lat || !(lat->cell > 0.0f) || !isfinite(lat->cell))
        return -1;
    s->lattice = *lat;
    if (lpv_volume_init(&s->injected, lat->n, LPV_LIGHT_CHANNELS) != 0 ||
        lpv_volume_init(&s->volume[0], lat->n, LPV_LIGHT_CHANNELS) != 0 ||
        lpv_volume_init(&s->volume[1], lat->n, LPV_LIGHT_CHANNELS) != 0) {
        lpv_paper_free(s);
        return -1;
    }
    return 0;
}

void lpv_paper_free(lpv_paper_lpv *s)
{
    lpv_volume_free(&s->injected);
    lpv_volume_free(&s->volume[0]);
    lpv_volume_free(&s->volume[1]);
    memset(s, 0, sizeof *s);
}

void lpv_paper_reset(lpv_paper_lpv *s)
{
    s->history = (lpv_paper_history){0};
}

lpv_volume *lpv_paper_injection(lpv_paper_lpv *s)
{
    return &s->injected;
}

void lpv_paper_begin_frame(lpv_paper_lpv *s)
{
    lpv_volume_clear(&s->injected);
}

void lpv_paper_frame(lpv_paper_lpv *s, const lpv_paper_frame_desc *desc)
{
    lpv_propagate_desc pd = desc->propagate;
    lpv_paper_merge m = lpv_paper_merge_factors(&s->history, desc->lambda_incr,
                                                desc->emitted_energy);
    lpv_paper_merge_run(m, &s->volume[s->current], &s->injected, &s->volume[s->current], pd.pool);
    pd.transport = LPV_TRANSPORT_PAPER;
    pd.accum = NULL;
    const lpv_blockers *blockers = pd.blockers;
    for (int step = 0; step < desc->steps; step++) {
        pd.blockers = step > 0 ? blockers : NULL; /* a fresh injection does not block itself */
        lpv_propagate_step(&pd, &s->volume[s->current], &s->volume[1 - s->current]);
        s->current = 1 - s->current;
    }
    lpv_paper_history_advance(&s->history, desc->emitted_energy);
}

const lpv_volume *lpv_paper_result(const lpv_paper_lpv *s)
{
    return &s->volume[s->current];
}
