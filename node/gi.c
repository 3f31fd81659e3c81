/* gi: the method table and the calls through it (see gi.h). */
#include "gi.h"

#include <stdio.h>
#include <stdlib.h>

#include "base/xalloc.h"
#include "gi_ilpv.h"
#include "gi_none.h"

static const gi_method *const methods[FRAME_GI_COUNT] = {
    [FRAME_GI_ILPV] = &gi_ilpv_method,
    [FRAME_GI_NONE] = &gi_none_method,
};

struct gi {
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
void gi_eye_bind(gi *g, const gi_eye *eye) { g->m->eye_bind(g->state, eye); }
void gi_stats_get(const gi *g, gi_stats *out) { g->m->stats(g->state, out); }
void *gi_state(const gi *g) { return g->state; }
