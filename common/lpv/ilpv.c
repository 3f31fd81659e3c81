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
    lpv_volume *light[] = {&s->injected, &s->near,  &s->shell,  &s->front[0],
                           &s->front[1], &s->sum,   &s->early,  &s->faded, &s->result};
    for (size_t i = 0; i < sizeof light / sizeof light[0]; i++)
        if (lpv_volume_init(light[i], lat->n, LPV_LIGHT_CHANNELS) != 0) {
            ilpv_free(s);
            return -1;
        }
    if (lpv_volume_init(&s->origin, lat->n, LPV_GEOMETRY_CHANNELS) != 0) {
        ilpv_free(s);
        return -1;
    }
    return 0;
}

void ilpv_free(ilpv *s)
{
    lpv_volume *all[] = {&s->injected, &s->origin, &s->near, &s->shell, &s->front[0],
                         &s->front[1], &s->sum,    &s->early, &s->faded, &s->result};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        lpv_volume_free(all[i]);
    lpv_splat_free(&s->splat);
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

lpv_volume *ilpv_origin(ilpv *s)
{
    return &s->origin;
}

void ilpv_begin_frame(ilpv *s)
{
    lpv_volume_clear(&s->injected);
    lpv_volume_clear(&s->origin);
}

uint64_t ilpv_injection_key(const lpv_volume *injected, const lpv_volume *origin,
                            float absorption, float scattering)
{
    uint32_t bits[2];
    memcpy(&bits[0], &absorption, sizeof bits[0]);
    memcpy(&bits[1], &scattering, sizeof bits[1]);
    uint64_t k = lpv_volume_checksum(injected);
    k = (k ^ lpv_volume_checksum(origin)) * 0x100000001b3ull;
    return (k ^ ((uint64_t)bits[0] << 32 | bits[1])) * 0x100000001b3ull;
}

ilpv_rule ilpv_history_rule(const ilpv_history *h, float lambda_incr, uint64_t key,
                            double emitted_energy)
{
    ilpv_rule r = {1, 0.0f};
    if (!h->have_history || !(lambda_incr > 0.0f))
        return r; /* lambda 0: no temporal reuse at all, every frame a new chain */
    r.restart = key != h->key;
    if (h->previous_energy > 0.0 && emitted_energy >= 0.0 && isfinite(emitted_energy))
        r.keep = (float)(emitted_energy / h->previous_energy); /* else no scale can be trusted */
    return r;
}

void ilpv_history_advance(ilpv_history *h, ilpv_rule r, int steps, uint64_t key,
                          double emitted_energy, double faded_energy)
{
    unsigned n = (unsigned)(steps > 0 ? steps : 0);
    h->chain_steps = r.restart ? n : h->chain_steps + n;
    h->chain_frames = r.restart ? 0u : h->chain_frames + 1u;
    h->have_history = 1;
    h->key = key;
    h->previous_energy = isfinite(emitted_energy) && emitted_energy > 0.0 ? emitted_energy : 0.0;
    h->faded_energy = faded_energy > 0.0 && isfinite(faded_energy) ? faded_energy : 0.0;
}

float ilpv_faded_weight(const ilpv_history *h, float lambda_incr, double sum_energy)
{
    if (!(h->faded_energy > 0.0) || !(lambda_incr > 0.0f))
        return 0.0f;
    double missing = fmin(fmax(1.0 - sum_energy / h->faded_energy, 0.0), 1.0);
    return (float)(pow(lambda_incr, (double)h->chain_frames) * missing);
}

void ilpv_history_settle(ilpv_history *h, ilpv_rule r, float lambda_incr, double sum_energy,
                         float w)
{
    /* lambda 0: every frame is a whole new chain, the same one for the same injection */
    double added = !(lambda_incr > 0.0f) ? 0.0 : r.restart ? sum_energy : sum_energy - h->sum_energy;
    double shown = w > 0.0f ? w * h->faded_energy : 0.0;
    double result = sum_energy + shown;
    h->sum_energy = sum_energy;
    h->pending = result != 0.0 ? (fabs(added) + shown) / fabs(result) : 0.0;
}

double ilpv_pending(const ilpv *s)
{
    return s->history.pending;
}

static double total_energy(const lpv_volume *v)
{
    double e[3];
    lpv_volume_energy(v, e);
    return e[0] + e[1] + e[2];
}

double ilpv_fade(ilpv_rule r, const lpv_volume *shown, const lpv_volume *early,
                 lpv_volume *faded)
{
    if (!(r.keep > 0.0f)) {
        lpv_volume_clear(faded);
        return 0.0;
    }
    fpmode mode = fpmode_enter();
    lpv_volume_copy(faded, shown);
    lpv_volume_add_scaled(faded, early, -1.0f);
    lpv_volume_scale(faded, r.keep);
    double energy = total_energy(faded);
    fpmode_leave(mode);
    return energy;
}

void ilpv_compose(ilpv_history *h, ilpv_rule r, float lambda_incr, const lpv_volume *sum,
                  lpv_volume *early, const lpv_volume *faded, lpv_volume *result)
{
    fpmode mode = fpmode_enter();
    if (r.restart) {
        lpv_volume_copy(early, sum);
        h->early_energy = total_energy(early);
    }
    double sum_energy = total_energy(sum);
    float w = ilpv_faded_weight(h, lambda_incr, sum_energy - h->early_energy);
    ilpv_history_settle(h, r, lambda_incr, sum_energy, w);
    lpv_volume_copy(result, sum);
    if (w > 0.0f)
        lpv_volume_add_scaled(result, faded, w);
    fpmode_leave(mode);
}

int ilpv_frame(ilpv *s, const ilpv_frame_desc *desc)
{
    const lpv_propagate_desc *p = &desc->propagate;
    uint64_t key = ilpv_injection_key(&s->injected, &s->origin, p->absorption, p->scattering);
    ilpv_rule rule = ilpv_history_rule(&s->history, desc->lambda_incr, key, desc->emitted_energy);
    double faded_energy = s->history.faded_energy;
    int rc = 0;
    if (rule.restart) {
        faded_energy = ilpv_fade(rule, &s->result, &s->early, &s->faded);
        lpv_splat_desc sd = {&s->injected, &s->origin, p->blockers, p->absorption, p->pool};
        rc = lpv_splat_run(&s->splat, &sd, &s->near, &s->shell);
        fpmode mode = fpmode_enter();
        lpv_volume_copy(&s->front[0], &s->shell);
        lpv_volume_copy(&s->sum, &s->near);
        lpv_volume_add(&s->sum, &s->shell);
        fpmode_leave(mode);
        s->current = 0;
    }
    lpv_propagate_desc pd = *p;
    pd.accum = &s->sum;
    unsigned first = rule.restart ? 0u : s->history.chain_steps;
    for (int step = 0; step < desc->steps; step++) {
        pd.step = first + (unsigned)step;
        lpv_propagate_step(&pd, &s->front[s->current], &s->front[1 - s->current]);
        s->current = 1 - s->current;
    }
    ilpv_history_advance(&s->history, rule, desc->steps, key, desc->emitted_energy,
                         faded_energy);
    ilpv_compose(&s->history, rule, desc->lambda_incr, &s->sum, &s->early, &s->faded,
                 &s->result);
    return rc;
}

const lpv_volume *ilpv_result(const ilpv *s)
{
    return &s->result;
}
