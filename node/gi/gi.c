/* gi: the method table and the calls through it (see gi.h). */
#include "gi/gi.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/xalloc.h"
#include "gi/gi_settings.h"
#include "gl/gltools.h"

#define GI_METHOD(name) extern const gi_method gi_##name##_method;
#include "gi/gi_methods.def"
#undef GI_METHOD

static const gi_method *const methods[] = {
#define GI_METHOD(name) &gi_##name##_method,
#include "gi/gi_methods.def"
#undef GI_METHOD
};
enum { METHODS = sizeof methods / sizeof methods[0] };

struct gi {
    const gl_functions *gl;
    int active;
    const gi_method *m;
    void *state;
    frame_params built_for;  /* the settings it was made with */
    GLuint shade;
};

gi *gi_create(const gi_desc *desc, char *err, size_t errlen)
{
    int method = desc->frame->gi;
    if (method < 0 || method >= METHODS || method >= gi_method_count()) {
        snprintf(err, errlen, "renderer: unknown GI method %d", method);
        return NULL;
    }
    gi *g = xcalloc(1, sizeof *g);
    g->gl = desc->gl;
    g->active = method;
    g->m = methods[method];
    g->built_for = *desc->frame;
    const char *frags[4] = {"shade.frag"};
    int files = 1;
    for (int i = 0; i < 3 && g->m->shade[i]; i++)
        frags[files++] = g->m->shade[i];
    const char *defines = g->m->glossy ? "#define GI_GLOSSY 1\n" : NULL;
    g->shade = gltools_program_parts(g->gl, "fullscreen.vert", frags, files, defines, err,
                                     errlen);
    if (!g->shade || !(g->state = g->m->create(desc, err, errlen))) {
        gi_destroy(g);
        return NULL;
    }
    return g;
}

void gi_destroy(gi *g)
{
    if (!g)
        return;
    if (g->state)
        g->m->destroy(g->state);
    if (g->shade)
        g->gl->DeleteProgram(g->shade);
    free(g);
}

int gi_active(const gi *g) { return g->active; }

int gi_needs_rebuild(const gi *g, const frame_params *p)
{
    return p->gi != g->active || gi_rebuild_needed(g->active, p, &g->built_for);
}

int gi_reuse(gi *g, const frame_params *p) { return g->m->reuse(g->state, p); }
uint64_t gi_frame(gi *g, const frame_params *p, const gi_rsm *rsm) { return g->m->frame(g->state, p, rsm); }
GLuint gi_shade_program(const gi *g) { return g->shade; }
void gi_eye_bind(gi *g, const gi_eye *eye) { g->m->eye_bind(g->state, eye); }

void gi_objects_moved(gi *g, const gi_objects *o)
{
    if (g->m->objects)
        g->m->objects(g->state, o);
}

void gi_screen(gi *g, const frame_view *views, int n)
{
    if (g->m->screen)
        g->m->screen(g->state, views, n);
}

void gi_stats_get(const gi *g, gi_stats *out)
{
    memset(out, 0, sizeof *out);
    g->m->stats(g->state, out);
}

void *gi_state(const gi *g) { return g->state; }

double gi_stats_value(const gi_stats *s, const char *name, int *found)
{
    const gi_stat *lists[2] = {s->stage, s->figure};
    const int counts[2] = {s->stage_count, s->figure_count};
    for (int l = 0; l < 2; l++)
        for (int i = 0; i < counts[l]; i++)
            if (strcmp(lists[l][i].name, name) == 0) {
                if (found)
                    *found = 1;
                return lists[l][i].value;
            }
    if (found)
        *found = 0;
    return 0.0;
}

double gi_stats_total_ms(const gi_stats *s)
{
    double ms = 0;
    for (int i = 0; i < s->stage_count; i++)
        ms += s->stage[i].value;
    return ms;
}
