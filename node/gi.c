/* gi: the method table and the calls through it (see gi.h). */
#include "gi.h"

#include <stdio.h>
#include <stdlib.h>

#include "base/xalloc.h"
#include "gi_ilpv.h"
#include "gi_none.h"
#include "gi_vpl.h"

static const gi_method *const methods[FRAME_GI_COUNT] = {
    [FRAME_GI_ILPV] = &gi_ilpv_method,
    [FRAME_GI_NONE] = &gi_none_method,
    [FRAME_GI_VPL] = &gi_vpl_method,
};

struct gi {
    const gl_functions *gl;
    frame_gi active;
    const gi_method *m;
    void *state;
};

gi *gi_create(frame_gi method, const gi_desc *desc, char *err, size_t errlen)
{
    if ((unsigned)method >= FRAME_GI_COUNT) {
        snprintf(err, errlen, "renderer: unknown GI method %d", (int)method);
        return NULL;
    }
    gi *g = xcalloc(1, sizeof *g);
    g->gl = desc->gl;
    g->active = method;
    g->m = methods[method];
    if (!(g->state = g->m->create(desc, err, errlen))) {
        free(g);
        return NULL;
    }
    return g;
}

void gi_destroy(gi *g)
{
    if (!g)
        return;
    g->m->destroy(g->state);
    free(g);
}

frame_gi gi_active(const gi *g) { return g->active; }
int gi_reuse(gi *g, const frame_params *p) { return g->m->reuse(g->state, p); }
uint64_t gi_frame(gi *g, const frame_params *p, const gi_rsm *rsm) { return g->m->frame(g->state, p, rsm); }

/* Every method's lookup off and its samplers on their own units; then the active one. */
void gi_eye_bind(gi *g, const gi_eye *eye)
{
    const gl_functions *gl = g->gl;
    GLuint prog = eye->program;
    const char *samplers[] = {"u_lpv_r", "u_lpv_g", "u_lpv_b", "u_vpls", "u_vpl_shadow", "u_ism",
                              "u_vpl_irradiance", "u_vpl_cluster_first", "u_vpl_cluster_index"};
    const int units[] = {GI_UNIT_LPV, GI_UNIT_LPV + 1, GI_UNIT_LPV + 2, GI_UNIT_VPL_DATA,
                         GI_UNIT_VPL_SHADOW, GI_UNIT_ISM, GI_UNIT_VPL_IRRADIANCE,
                         GI_UNIT_VPL_CLUSTERS, GI_UNIT_VPL_LISTS};
    for (int i = 0; i < 9; i++)
        gl->Uniform1i(gl->GetUniformLocation(prog, samplers[i]), eye->first_unit + units[i]);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_lpv_enabled"), 0);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_vpl_count"), 0);
    g->m->eye_bind(g->state, eye);
}

void gi_screen(gi *g, const frame_view *views, int n)
{
    if (g->m->screen)
        g->m->screen(g->state, views, n);
}

void gi_stats_get(const gi *g, gi_stats *out) { g->m->stats(g->state, out); }
void *gi_state(const gi *g) { return g->state; }
