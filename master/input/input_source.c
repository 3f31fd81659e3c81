/* input_source: helpers shared by the input sources. */
#include "input_source.h"
#include "base/xalloc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void *input_source_alloc(size_t size, const char *name, const char *fallback,
                         input_source_poll_fn poll, input_source_close_fn close)
{
    input_source *s = xcalloc(1, size);
    snprintf(s->name, sizeof s->name, "%s", name ? name : fallback);
    s->poll = poll;
    s->close = close;
    return s;
}

/* One line of the source's loss and recovery story, unless the rate limit leaves it out. */
static int outage_line(input_source *s, double now, char *err, size_t errlen, const char *text)
{
    uint64_t skipped = 0;
    if (!ratelog_event(&s->log, now * 1000.0, &skipped))
        return 0;
    if (skipped)
        snprintf(err, errlen, "input %s: %s (%llu such lines left out)", s->name, text,
                 (unsigned long long)skipped);
    else
        snprintf(err, errlen, "input %s: %s", s->name, text);
    return 1;
}

int input_source_lost(input_source *s, double now, const char *why, char *err, size_t errlen)
{
    input_source_set_buttons(&s->st, 0, now);
    s->next_attempt = now + s->retry_interval;
    if (s->outage_reported)
        return 0;
    s->outage_reported = 1;
    s->outage_since = now;
    char text[512];
    if (s->retry_interval > 0)
        snprintf(text, sizeof text, "%s; retrying every %g s", why, s->retry_interval);
    else
        snprintf(text, sizeof text, "%s", why);
    return outage_line(s, now, err, errlen, text) ? -1 : 0;
}

int input_source_retry_due(const input_source *s, double now)
{
    return s->retry_interval > 0 && now >= s->next_attempt;
}

int input_source_up(input_source *s, double now, const char *what, char *err, size_t errlen)
{
    char text[512];
    int say = 1;
    if (s->outage_reported)
        snprintf(text, sizeof text, "%s again after %.1f s", what, now - s->outage_since);
    else if (s->ups == 0)
        snprintf(text, sizeof text, "%s", what);
    else
        say = 0;
    s->outage_reported = 0;
    s->ups++;
    return say && outage_line(s, now, err, errlen, text);
}

void input_source_set_buttons(input_source_state *st, uint32_t held, double t)
{
    uint32_t down = held & ~st->buttons;
    if (held != st->buttons)
        st->buttons_time = t;
    st->pressed |= down;
    st->buttons = held;
}

void input_source_set_axes(input_source_state *st, const float *axes, int count, double t)
{
    int changed = 0;
    for (int i = 0; i < INPUT_AXIS_COUNT; i++) {
        float v = i < count ? axes[i] : 0.0f;
        if (isnan(v))
            v = 0.0f;
        v = v < -1.0f ? -1.0f : v > 1.0f ? 1.0f : v;
        if (v != st->axes[i]) {
            st->axes[i] = v;
            changed = 1;
        }
    }
    if (changed)
        st->axes_time = t;
}

uint32_t input_map_buttons(const input_map *m, uint32_t raw)
{
    if (!m->set)
        return raw & ((1u << INPUT_BUTTON_COUNT) - 1u);
    uint32_t out = 0;
    for (int i = 0; i < INPUT_MAP_SIZE; i++)
        if ((raw >> i) & 1u && m->to[i] >= 0 && m->to[i] < INPUT_BUTTON_COUNT)
            out |= 1u << m->to[i];
    return out;
}

void input_map_axes(const input_map *m, const float *raw, int count, float out[INPUT_AXIS_COUNT])
{
    for (int i = 0; i < INPUT_AXIS_COUNT; i++)
        out[i] = 0.0f;
    for (int i = 0; i < count && i < INPUT_MAP_SIZE; i++) {
        int to = m->set ? m->to[i] : i;
        if (to >= 0 && to < INPUT_AXIS_COUNT)
            out[to] = raw[i];
    }
}
