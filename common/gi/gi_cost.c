/* gi_cost: see gi_cost.h. */
#include "gi/gi_cost.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "frame/light_view.h"
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

/* The larger cost of the set-up settings and the defaults, for this frame's method and
 * lights. */
static void reference_costs(const gi_limits *l, const frame_params *p, gi_cost *method, gi_cost *rsm)
{
    frame_params ref[2];
    ref[0] = l->base;
    frame_params_default(&ref[1]);
    *method = *rsm = (gi_cost){0};
    for (int i = 0; i < 2; i++) {
        ref[i].gi = p->gi;
        memcpy(ref[i].lights, p->lights, sizeof ref[i].lights);
        ref[i].light_count = p->light_count;
        gi_cost m, r;
        gi_cost_method(&ref[i], l->bounds_min, l->bounds_max, &m);
        gi_cost_rsm(&ref[i], &r);
        method->work = fmax(method->work, m.work);
        rsm->work = fmax(rsm->work, r.work);
    }
}

int gi_cost_within(const gi_limits *l, const frame_params *p, char *why, size_t cap)
{
    gi_cost m, r, mb, rb;
    gi_cost_method(p, l->bounds_min, l->bounds_max, &m);
    gi_cost_rsm(p, &r);
    reference_costs(l, p, &mb, &rb);
    const char *name = gi_method_at(p->gi) ? gi_method_at(p->gi)->name : "?";
    double mb_total = (m.memory_bytes + r.memory_bytes) / (1024.0 * 1024.0);
    if (m.work > GI_COST_WORK_LIMIT * mb.work)
        snprintf(why, cap, "the %s settings would take %.0f times the work of the config's (at most %d)",
                 name, m.work / (mb.work > 0 ? mb.work : 1), GI_COST_WORK_LIMIT);
    else if (r.work > GI_COST_WORK_LIMIT * rb.work)
        snprintf(why, cap, "--rsm %d would take %.0f times the RSM work of the config's (at most %d)",
                 p->rsm_size, r.work / (rb.work > 0 ? rb.work : 1), GI_COST_WORK_LIMIT);
    else if (mb_total > l->memory_mb)
        snprintf(why, cap, "%s with its RSMs would take %.0f MB, over the limit of %.0f MB (limits.gi_memory_mb)",
                 name, mb_total, l->memory_mb);
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
}
