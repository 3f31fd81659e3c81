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
    lpv_volume *light[] = {&s->injected, &s->near, &s->shell, &s->volume[0], &s->volume[1],
                           &s->result};
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
    lpv_volume *all[] = {&s->injected, &s->origin, &s->near, &s->shell, &s->volume[0],
                         &s->volume[1], &s->result};
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

ilpv_merge ilpv_merge_factors(const ilpv_history *h, float lambda_incr, int lights_moved,
                              double emitted_energy)
{
    ilpv_merge m = {0.0f, 0};
    if (!(lambda_incr > 0.0f) || !h->have_history || !(h->previous_energy > 0.0) ||
        !(emitted_energy >= 0.0) || !isfinite(emitted_energy))
        return m; /* also for a negative or NaN energy: no scale can be trusted */
    m.with_history = 1;
    m.a = (float)(emitted_energy / h->previous_energy * (lights_moved ? lambda_incr : 1.0));
    return m;
}

void ilpv_history_advance(ilpv_history *h, ilpv_merge m, int steps, double emitted_energy)
{
    h->steps = (m.with_history ? h->steps : 0u) + (unsigned)(steps > 0 ? steps : 0);
    h->have_history = 1;
    h->previous_energy = isfinite(emitted_energy) && emitted_energy > 0.0 ? emitted_energy : 0.0;
}

int ilpv_frame(ilpv *s, const ilpv_frame_desc *desc)
{
    const lpv_propagate_desc *p = &desc->propagate;
    lpv_splat_desc sd = {&s->injected, &s->origin, p->blockers, p->absorption, p->pool};
    int rc = lpv_splat_run(&s->splat, &sd, &s->near, &s->shell);
    ilpv_merge m = ilpv_merge_factors(&s->history, desc->lambda_incr, desc->lights_moved,
                                      desc->emitted_energy);
    fpmode mode = fpmode_enter();
    lpv_volume *x = &s->volume[s->current];
    if (!m.with_history) /* never read a stale history: it may hold anything */
        lpv_volume_clear(x);
    else if (m.a != 1.0f)
        lpv_volume_scale(x, m.a);
    lpv_propagate_desc pd = *p;
    pd.source = &s->shell;
    unsigned first = m.with_history ? s->history.steps : 0u;
    for (int step = 0; step < desc->steps; step++) {
        pd.step = first + (unsigned)step;
        lpv_propagate_step(&pd, &s->volume[s->current], &s->volume[1 - s->current]);
        s->current = 1 - s->current;
    }
    lpv_volume_copy(&s->result, &s->near);
    lpv_volume_add(&s->result, &s->volume[s->current]);
    fpmode_leave(mode);
    ilpv_history_advance(&s->history, m, desc->steps, desc->emitted_energy);
    return rc;
}

const lpv_volume *ilpv_result(const ilpv *s)
{
    return &s->result;
}
