/* gpu_timer: timestamp queries in a ring of frames, read back late (gpu_timer.h). */
#include <stdlib.h>
#include <string.h>

#include "base/xalloc.h"
#include "gpu_timer.h"

enum { RING = 4 };

typedef struct slot {
    GLuint query[2 * GPU_TIMER_STAGES]; /* begin, end per stage */
    const char *name[GPU_TIMER_STAGES];
    int used;
    int pending;                        /* recorded, results not yet collected */
    uint64_t frame;
} slot;

struct gpu_timer {
    const gl_functions *gl;
    slot ring[RING];
    int current;                        /* the slot recording now, -1 before any frame */
    gpu_timer_result last;
    long dropped;
};

gpu_timer *gpu_timer_create(const gl_functions *gl)
{
    gpu_timer *t = xcalloc(1, sizeof *t);
    t->gl = gl;
    t->current = -1;
    for (int i = 0; i < RING; i++)
        gl->GenQueries(2 * GPU_TIMER_STAGES, t->ring[i].query);
    return t;
}

void gpu_timer_destroy(gpu_timer *t)
{
    if (!t)
        return;
    for (int i = 0; i < RING; i++)
        t->gl->DeleteQueries(2 * GPU_TIMER_STAGES, t->ring[i].query);
    free(t);
}

static int arrived(const gpu_timer *t, const slot *s)
{
    for (int i = 0; i < 2 * s->used; i++) {
        GLint ready = 0;
        t->gl->GetQueryObjectiv(s->query[i], GL_QUERY_RESULT_AVAILABLE, &ready);
        if (!ready)
            return 0;
    }
    return 1;
}

/* The slot's stages into last, a repeated name summed; 0 when a reading is implausible
 * (llvmpipe now and then stamps from an undefined start: an end before its begin or a
 * stage over 10 s). */
static int collect(gpu_timer *t, const slot *s)
{
    gpu_timer_result r = {.frame = s->frame};
    for (int i = 0; i < s->used; i++) {
        GLuint64 b = 0, e = 0;
        t->gl->GetQueryObjectui64v(s->query[2 * i], GL_QUERY_RESULT, &b);
        t->gl->GetQueryObjectui64v(s->query[2 * i + 1], GL_QUERY_RESULT, &e);
        if (e < b || e - b > 10000000000ull)
            return 0;
        int k = 0;
        while (k < r.count && strcmp(r.stage[k].name, s->name[i]) != 0)
            k++;
        if (k == r.count)
            r.stage[r.count++] = (gpu_timer_stage){s->name[i], 0, 0};
        r.stage[k].ms += (double)(e - b) * 1e-6;
        r.stage[k].times++;
    }
    t->last = r;
    return 1;
}

void gpu_timer_frame(gpu_timer *t, uint64_t frame)
{
    if (!t)
        return;
    if (t->current >= 0)
        t->ring[t->current].pending = t->ring[t->current].used > 0;
    int next = (t->current + 1) % RING;
    for (int k = 0; k < RING; k++) { /* oldest first: the slot after current */
        slot *s = &t->ring[(next + k) % RING];
        if (s->pending && arrived(t, s)) {
            t->dropped += !collect(t, s);
            s->pending = 0;
        }
    }
    slot *s = &t->ring[next];
    t->dropped += s->pending; /* still out after a whole ring: never waited for */
    s->pending = 0;
    s->used = 0;
    s->frame = frame;
    t->current = next;
}

int gpu_timer_begin(gpu_timer *t, const char *name)
{
    if (!t || t->current < 0 || t->ring[t->current].used == GPU_TIMER_STAGES)
        return -1;
    slot *s = &t->ring[t->current];
    int h = s->used++;
    s->name[h] = name;
    t->gl->QueryCounter(s->query[2 * h], GL_TIMESTAMP);
    t->gl->QueryCounter(s->query[2 * h + 1], GL_TIMESTAMP); /* defined even if never ended */
    return h;
}

void gpu_timer_end(gpu_timer *t, int handle)
{
    if (!t || handle < 0 || t->current < 0)
        return;
    t->gl->QueryCounter(t->ring[t->current].query[2 * handle + 1], GL_TIMESTAMP);
}

const gpu_timer_result *gpu_timer_last(const gpu_timer *t)
{
    return &t->last;
}

double gpu_timer_mean_ms(const gpu_timer_result *r, const char *name)
{
    for (int k = 0; k < r->count; k++)
        if (strcmp(r->stage[k].name, name) == 0)
            return r->stage[k].ms / r->stage[k].times;
    return 0;
}

long gpu_timer_dropped(const gpu_timer *t)
{
    return t->dropped;
}
