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
                           &s->front[1], &s->sum,   &s->faded,  &s->result};
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
                         &s->front[1], &s->sum,    &s->faded, &s->result};
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
    if (!h->have_history)
        return r;
    r.restart = key != h->key;
    if (lambda_incr > 0.0f && h->previous_energy > 0.0 && emitted_energy >= 0.0 &&
        isfinite(emitted_energy)) /* a negative or NaN energy: no scale can be trusted */
        r.fade = (float)(emitted_energy / h->previous_energy * lambda_incr);
    return r;
}

void ilpv_history_advance(ilpv_history *h, ilpv_rule r, int steps, uint64_t key,
                          double emitted_energy)
{
    h->chain_steps = (r.restart ? 0u : h->chain_steps) + (unsigned)(steps > 0 ? steps : 0);
    h->have_history = 1;
    h->key = key;
    h->previous_energy = isfinite(emitted_energy) && emitted_energy > 0.0 ? emitted_energy : 0.0;
}

int ilpv_frame(ilpv *s, const ilpv_frame_desc *desc)
{
    const lpv_propagate_desc *p = &desc->propagate;
    uint64_t key = ilpv_injection_key(&s->injected, &s->origin, p->absorption, p->scattering);
    ilpv_rule rule = ilpv_history_rule(&s->history, desc->lambda_incr, key, desc->emitted_energy);
    int rc = 0;
    fpmode mode = fpmode_enter();
    if (!s->history.have_history || rule.fade == 0.0f) {
        lpv_volume_clear(&s->faded); /* never read a stale history: it may hold anything */
    } else {
        if (rule.restart)
            lpv_volume_add(&s->faded, &s->sum);
        lpv_volume_scale(&s->faded, rule.fade);
    }
    fpmode_leave(mode);
    if (rule.restart) {
        lpv_splat_desc sd = {&s->injected, &s->origin, p->blockers, p->absorption, p->pool};
        rc = lpv_splat_run(&s->splat, &sd, &s->near, &s->shell);
        mode = fpmode_enter();
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
    mode = fpmode_enter();
    lpv_volume_copy(&s->result, &s->sum);
    lpv_volume_add(&s->result, &s->faded);
    fpmode_leave(mode);
    ilpv_history_advance(&s->history, rule, desc->steps, key, desc->emitted_energy);
    return rc;
}

const lpv_volume *ilpv_result(const ilpv *s)
{
    return &s->result;
}
