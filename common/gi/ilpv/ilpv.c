#include "gi/ilpv/ilpv.h"

#include "base/fnv1a.h"
#include "base/fpmode.h"
#include "base/xalloc.h"
#include "gi/ilpv/lpv_propagate.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Light volumes of the driver (ilpv_init()) and of a backend's chain (front, next, sum:
 * ilpv_cpu_create(), the GL backend's images likewise), and the origins' volume. */
enum { ILPV_LIGHT_VOLUMES = 6, ILPV_CHAIN_VOLUMES = 3 };

double ilpv_state_bytes(const lattice_desc *lat)
{
    double channels = (ILPV_LIGHT_VOLUMES + ILPV_CHAIN_VOLUMES) * LPV_LIGHT_CHANNELS + LPV_GEOMETRY_CHANNELS;
    return (double)lattice_cell_count(lat) * channels * sizeof(float);
}

int ilpv_init(ilpv *s, const ilpv_desc *d)
{
    const lattice_desc *lat = d->lattice;
    memset(s, 0, sizeof *s);
    s->blockers = d->blockers;
    s->pool = d->pool;
    if (d->backend)
        s->backend = *d->backend;
    else if (lat) {
        ilpv_cpu *own = ilpv_cpu_create(lat, d->blockers, d->pool);
        if (own)
            s->backend = ilpv_cpu_backend(own);
    }
    if (!lat || !(lat->cell > 0.0f) || !isfinite(lat->cell) || !s->backend.state) {
        ilpv_free(s);
        return -1;
    }
    s->lattice = *lat;
    lpv_volume *light[ILPV_LIGHT_VOLUMES] = {&s->injected, &s->near, &s->shell, &s->early, &s->faded,
                                             &s->result};
    for (size_t i = 0; i < ILPV_LIGHT_VOLUMES; i++)
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
    lpv_volume *all[] = {&s->injected, &s->origin, &s->near, &s->shell,
                         &s->early,    &s->faded,  &s->result};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        lpv_volume_free(all[i]);
    lpv_splat_free(&s->splat);
    if (s->backend.destroy && s->backend.state)
        s->backend.destroy(s->backend.state);
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
    k = fnv1a64_word(k, lpv_volume_checksum(origin));
    return fnv1a64_word(k, (uint64_t)bits[0] << 32 | bits[1]);
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

/* At a restart under rule r: faded = r.keep (shown - early), the far part of the picture
 * shown last in this frame's power, or cleared when nothing is kept (a stale history may
 * hold anything). Returns <faded|1>, all colours. */
static double fade(ilpv_rule r, const lpv_volume *shown, const lpv_volume *early,
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

/* After the frame's steps and ilpv_history_advance(): at a restart early = sum; then the
 * history settles and result = sum + w faded (ilpv_faded_weight()). */
static void compose(ilpv_history *h, ilpv_rule r, float lambda_incr, const lpv_volume *sum,
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

/* A new chain from this frame's splat. */
static int start_chain(ilpv *s, const ilpv_frame_desc *d)
{
    lpv_splat_desc sd = {&s->injected, &s->origin, s->blockers, d->absorption, s->pool};
    int rc = lpv_splat_run(&s->splat, &sd, &s->near, &s->shell);
    s->backend.start(s->backend.state, &s->near, &s->shell);
    return rc;
}

int ilpv_frame(ilpv *s, const ilpv_frame_desc *d)
{
    ilpv_backend *b = &s->backend;
    if (d->classic) {
        int rc = start_chain(s, d);
        b->steps(b->state, d->steps, 0u, d->absorption, d->scattering);
        fpmode mode = fpmode_enter();
        lpv_volume_copy(&s->result, b->sum(b->state));
        fpmode_leave(mode);
        s->history = (ilpv_history){0};
        return rc;
    }
    uint64_t key = ilpv_injection_key(&s->injected, &s->origin, d->absorption, d->scattering);
    ilpv_rule rule = ilpv_history_rule(&s->history, d->lambda_incr, key, d->emitted_energy);
    double faded_energy = s->history.faded_energy;
    int rc = 0;
    if (rule.restart) {
        faded_energy = fade(rule, &s->result, &s->early, &s->faded);
        rc = start_chain(s, d);
    }
    b->steps(b->state, d->steps, rule.restart ? 0u : s->history.chain_steps, d->absorption,
             d->scattering);
    ilpv_history_advance(&s->history, rule, d->steps, key, d->emitted_energy, faded_energy);
    compose(&s->history, rule, d->lambda_incr, b->sum(b->state), &s->early, &s->faded,
            &s->result);
    return rc;
}

const lpv_volume *ilpv_result(const ilpv *s)
{
    return &s->result;
}

const lpv_volume *ilpv_sum(ilpv *s)
{
    return s->backend.sum(s->backend.state);
}

/* ---- the CPU backend ---------------------------------------------------------------- */

struct ilpv_cpu {
    lpv_volume front[2];     /* the chain's oldest light, ping-pong */
    lpv_volume sum;          /* near + every age of the chain so far */
    int current;             /* index of the front volume */
    const lpv_blockers *blockers;
    workpool *pool;
};

static void cpu_destroy(void *state)
{
    ilpv_cpu *c = state;
    lpv_volume_free(&c->front[0]);
    lpv_volume_free(&c->front[1]);
    lpv_volume_free(&c->sum);
    free(c);
}

static void cpu_start(void *state, const lpv_volume *near, const lpv_volume *shell)
{
    ilpv_cpu *c = state;
    fpmode mode = fpmode_enter();
    lpv_volume_copy(&c->front[0], shell);
    lpv_volume_copy(&c->sum, near);
    lpv_volume_add(&c->sum, shell);
    fpmode_leave(mode);
    c->current = 0;
}

static void cpu_steps(void *state, int steps, unsigned first, float absorption, float scattering)
{
    ilpv_cpu *c = state;
    lpv_propagate_desc pd = {.blockers = c->blockers, .accum = &c->sum, .absorption = absorption,
                             .scattering = scattering, .pool = c->pool};
    for (int step = 0; step < steps; step++) {
        pd.step = first + (unsigned)step;
        lpv_propagate_step(&pd, &c->front[c->current], &c->front[1 - c->current]);
        c->current = 1 - c->current;
    }
}

static const lpv_volume *cpu_sum(void *state)
{
    return &((ilpv_cpu *)state)->sum;
}

ilpv_cpu *ilpv_cpu_create(const lattice_desc *lat, const lpv_blockers *blockers, workpool *pool)
{
    ilpv_cpu *c = xcalloc(1, sizeof *c);
    c->blockers = blockers;
    c->pool = pool;
    if (lpv_volume_init(&c->front[0], lat->n, LPV_LIGHT_CHANNELS) != 0 ||
        lpv_volume_init(&c->front[1], lat->n, LPV_LIGHT_CHANNELS) != 0 ||
        lpv_volume_init(&c->sum, lat->n, LPV_LIGHT_CHANNELS) != 0) {
        cpu_destroy(c);
        return NULL;
    }
    return c;
}

ilpv_backend ilpv_cpu_backend(ilpv_cpu *c)
{
    return (ilpv_backend){.state = c, .start = cpu_start, .steps = cpu_steps, .sum = cpu_sum,
                          .destroy = cpu_destroy};
}
