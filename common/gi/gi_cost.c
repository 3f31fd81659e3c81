/* gi_cost: see gi_cost.h. */
#include "gi/gi_cost.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "frame/light_view.h"
#include "frame/ldm_limits.h"
#include "gi/gi_settings.h"

void gi_cost_method(const frame_params *p, const float bounds_min[3], const float bounds_max[3], gi_cost *out)
{
    *out = (gi_cost){0};
    const gi_method_settings *m = gi_method_at(p->gi);
    if (m && m->cost)
        m->cost(p, bounds_min, bounds_max, out);
}

/* Position, normal and flux, RGBA32F each, per texel of every light view. */
enum { RSM_BYTES_PER_TEXEL = 3 * 16 };

void gi_cost_rsm(const frame_params *p, gi_cost *out)
{
    int views = 0;
    for (int i = 0; i < p->light_count && i < FRAME_MAX_LIGHTS; i++)
        if (p->lights[i].enabled)
            views += p->lights[i].type == SCENE_LIGHT_POINT ? LIGHT_VIEW_CUBE_FACES : 1;
    double texels = (double)p->rsm_size * p->rsm_size * views;
    *out = (gi_cost){.work = texels, .memory_bytes = texels * RSM_BYTES_PER_TEXEL};
}

void gi_cost_ao(const frame_params *p, gi_cost *out)
{
    *out = (gi_cost){0};
    if (p->ao != FRAME_AO_LDM) /* ssao: a pass over the screen, like the frame itself */
        return;
    out->work = (double)p->ao_directions * p->ao_resolution * p->ao_resolution * p->ldm_layers;
    out->memory_bytes = ldm_limits_memory_bytes(p->ao_directions, p->ao_resolution, p->ldm_layers);
}

/* The larger cost of the set-up settings and the defaults, for this frame's method, AO and
 * lights: costs[0] the method, [1] the RSMs, [2] the AO. */
static void reference_costs(const gi_limits *l, const frame_params *p, gi_cost costs[3])
{
    frame_params ref[2];
    ref[0] = l->base;
    frame_params_default(&ref[1]);
    memset(costs, 0, 3 * sizeof *costs);
    for (int i = 0; i < 2; i++) {
        ref[i].gi = p->gi;
        ref[i].ao = p->ao;
        memcpy(ref[i].lights, p->lights, sizeof ref[i].lights);
        ref[i].light_count = p->light_count;
        gi_cost c[3];
        gi_cost_method(&ref[i], l->bounds_min, l->bounds_max, &c[0]);
        gi_cost_rsm(&ref[i], &c[1]);
        gi_cost_ao(&ref[i], &c[2]);
        for (int k = 0; k < 3; k++)
            costs[k].work = fmax(costs[k].work, c[k].work);
    }
}

int gi_cost_within(const gi_limits *l, const frame_params *p, char *why, size_t cap)
{
    gi_cost m, r, a, ref[3];
    gi_cost_method(p, l->bounds_min, l->bounds_max, &m);
    gi_cost_rsm(p, &r);
    gi_cost_ao(p, &a);
    reference_costs(l, p, ref);
    const char *name = gi_method_at(p->gi) ? gi_method_at(p->gi)->name : "?";
    double mb_total = (m.memory_bytes + r.memory_bytes + a.memory_bytes) / (1024.0 * 1024.0);
    if (m.work > GI_COST_WORK_LIMIT * ref[0].work)
        snprintf(why, cap, "the %s settings would take %.0f times the work of the config's (at most %d)",
                 name, m.work / (ref[0].work > 0 ? ref[0].work : 1), GI_COST_WORK_LIMIT);
    else if (r.work > GI_COST_WORK_LIMIT * ref[1].work)
        snprintf(why, cap, "--rsm %d would take %.0f times the RSM work of the config's (at most %d)",
                 p->rsm_size, r.work / (ref[1].work > 0 ? ref[1].work : 1), GI_COST_WORK_LIMIT);
    else if (a.work > GI_COST_WORK_LIMIT * ref[2].work)
        snprintf(why, cap, "--ao ldm with %d directions of %d^2 texels x %d layers would take %.0f "
                 "times the AO work of the config's (at most %d)", p->ao_directions,
                 p->ao_resolution, p->ldm_layers, a.work / (ref[2].work > 0 ? ref[2].work : 1),
                 GI_COST_WORK_LIMIT);
    else if (mb_total > l->memory_mb)
        snprintf(why, cap, "%s with its RSMs%s would take %.0f MB, over the limit of %.0f MB "
                 "(limits.gi_memory_mb)", name, a.memory_bytes > 0 ? " and AO maps" : "",
                 mb_total, l->memory_mb);
    else
        return 1;
    return 0;
}

void gi_cost_keep_settings(const frame_params *from, frame_params *to)
{
    to->gi = from->gi;
    memcpy(to->gi_settings, from->gi_settings, sizeof to->gi_settings);
    to->lpv_steps = from->lpv_steps;
    to->rsm_size = from->rsm_size;
    to->ao = from->ao;
    to->ao_directions = from->ao_directions;
    to->ao_resolution = from->ao_resolution;
    to->ldm_layers = from->ldm_layers;
    to->ldm_memory_mb = from->ldm_memory_mb;
}
