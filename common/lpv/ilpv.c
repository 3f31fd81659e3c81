#include "lpv/ilpv.h"

#include "base/fpmode.h"

#include <math.h>
#include <string.h>

int ilpv_init(ilpv *s, const lattice_desc *lat)
{
    memset(s, 0, sizeof *s);
    if (!lat || !(lat->cell > 0.0f) || !isfinite(lat->cell))
        return -1;
    s->lattice = *lat;
    if (lpv_volume_init(&s->injected, lat->n, LPV_LIGHT_CHANNELS) != 0 ||
        lpv_volume_init(&s->volume[0], lat->n, LPV_LIGHT_CHANNELS) != 0 ||
        lpv_volume_init(&s->volume[1], lat->n, LPV_LIGHT_CHANNELS) != 0) {
        ilpv_free(s);
        return -1;
    }
    return 0;
}

void ilpv_free(ilpv *s)
{
    lpv_volume_free(&s->injected);
    lpv_volume_free(&s->volume[0]);
    lpv_volume_free(&s->volume[1]);
    memset(s, 0, sizeof *s);
}

void ilpv_reset(ilpv *s)
{
    s->history = (ilpv_history){0};
}

lpv_volume *ilpv_injection(ilpv *s)
{
    return &s->injected;
}

void ilpv_begin_frame(ilpv *s)
{
    lpv_volume_clear(&s->injected);
}

typedef struct merge_job {
    const lpv_volume *history, *injected;
    lpv_volume *out;
    float a, b;
    int with_history;
} merge_job;

/* One z slice of L = a * history + b * injected, in place over the history. */
static void merge_slice(void *ctx, int z)
{
    const merge_job *m = ctx;
    fpmode mode = fpmode_enter();
    size_t plane = (size_t)m->out->n[0] * m->out->n[1], lo = (size_t)z * plane;
    for (int c = 0; c < LPV_LIGHT_CHANNELS; c++) {
        const float *h = m->history->ch[c] + lo, *in = m->injected->ch[c] + lo;
        float *o = m->out->ch[c] + lo;
        if (m->with_history)
            for (size_t i = 0; i < plane; i++)
                o[i] = m->a * h[i] + m->b * in[i];
        else /* no history: never touch stale values, which may be anything */
            for (size_t i = 0; i < plane; i++)
                o[i] = m->b * in[i];
    }
    fpmode_leave(mode);
}

ilpv_merge ilpv_merge_factors(const ilpv_history *h, float lambda_incr, double emitted_energy)
{
    double lambda = lambda_incr;
    if (!(lambda > 0.0) || !h->have_history || !(h->previous_energy > 0.0) ||
        !(emitted_energy >= 0.0) || !isfinite(emitted_energy))
        lambda = 0.0; /* also for a negative or NaN energy: no scale can be trusted */
    ilpv_merge m;
    m.with_history = lambda > 0.0;
    m.a = m.with_history ? (float)(emitted_energy / h->previous_energy * lambda) : 0.0f;
    m.b = (float)(1.0 - lambda);
    return m;
}

void ilpv_history_advance(ilpv_history *h, double emitted_energy)
{
    h->have_history = 1;
    h->previous_energy = isfinite(emitted_energy) && emitted_energy > 0.0 ? emitted_energy : 0.0;
}

void ilpv_frame(ilpv *s, const ilpv_frame_desc *desc)
{
    ilpv_merge f = ilpv_merge_factors(&s->history, desc->lambda_incr, desc->emitted_energy);
    merge_job m;
    m.history = &s->volume[s->current];
    m.injected = &s->injected;
    m.out = &s->volume[s->current];
    m.a = f.a;
    m.b = f.b;
    m.with_history = f.with_history;
    workpool_run(desc->propagate.pool, s->lattice.n[2], merge_slice, &m);

    lpv_propagate_desc pd = desc->propagate;
    int use_blocking = pd.use_blocking;
    for (int step = 0; step < desc->steps; step++) {
        pd.use_blocking = step > 0 && use_blocking; /* fresh injection: no self-blocking */
        lpv_propagate_step(&pd, &s->volume[s->current], &s->volume[1 - s->current]);
        s->current = 1 - s->current;
    }
    ilpv_history_advance(&s->history, desc->emitted_energy);
}

const lpv_volume *ilpv_result(const ilpv *s)
{
    return &s->volume[s->current];
}
