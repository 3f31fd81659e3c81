/* input: the source list, merging, recording (input.h). */
#include "input.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/folder.h"
#include "base/xalloc.h"
#include "input_playback.h"
#include "input_source.h"

enum { INPUT_MAX_SOURCES = 16 };

struct input {
    input_source *src[INPUT_MAX_SOURCES];
    int count;
    float tracker_to_cave[16];
    double t0_ms; /* clock_now_ms() at creation */
    int polled;
    double last_time;
    input_playback_recorder *rec;
};

input *input_create(const input_desc *desc, char *err, size_t errlen)
{
    input *in = xcalloc(1, sizeof *in);
    memcpy(in->tracker_to_cave, desc->tracker_to_cave, sizeof in->tracker_to_cave);
    in->t0_ms = clock_now_ms();
    if (desc->record_path) {
        char why[300];
        if (folder_create_for(desc->record_path, why, sizeof why) != 0) {
            snprintf(err, errlen, "input record %s: %s", desc->record_path, why);
            free(in);
            return NULL;
        }
        in->rec = input_playback_record_open(desc->record_path, err, errlen);
        if (!in->rec) {
            free(in);
            return NULL;
        }
    }
    return in;
}

int input_add_source(input *in, input_source *src, char *err, size_t errlen)
{
    if (in->count == INPUT_MAX_SOURCES) {
        snprintf(err, errlen, "input %s: too many sources (at most %d)", src->name,
                 INPUT_MAX_SOURCES);
        src->close(src);
        return -1;
    }
    in->src[in->count++] = src;
    return 0;
}

static void take_pose(input_pose *best, const input_pose *p, const float xf[16], int transform)
{
    if (!p->valid || (best->valid && best->time > p->time))
        return;
    /* Field by field, so that padding stays zero and states compare bytewise. */
    best->valid = 1;
    best->time = p->time;
    memcpy(best->position, p->position, sizeof best->position);
    memcpy(best->rotation, p->rotation, sizeof best->rotation);
    if (transform)
        input_pose_transform(best, xf);
}

int input_poll(input *in, input_state *out, char *err, size_t errlen)
{
    double now = (clock_now_ms() - in->t0_ms) / 1000.0;
    int rc = 0;
    char e[512];
    size_t used = 0;
    if (errlen)
        err[0] = '\0';
    /* Every source's line, joined into one: a warning (-1) outranks a notice (1). */
    for (int i = 0; i < in->count; i++) {
        int r = in->src[i]->poll(in->src[i], now, e, sizeof e);
        if (r == 0)
            continue;
        if (used < errlen)
            used += (size_t)snprintf(err + used, errlen - used, "%s%s", used ? "; " : "", e);
        rc = r < 0 || rc < 0 ? -1 : 1;
    }
    memset(out, 0, sizeof *out);
    out->time = now;
    out->dt = in->polled ? now - in->last_time : 0.0;
    for (int i = 0; i < in->count; i++) {
        input_source *s = in->src[i];
        if (s->stepped) {
            /* A stepped recording drives the clock so that replay is deterministic. */
            out->time = s->step_time;
            out->dt = s->step_dt;
            out->finished |= s->finished;
        }
        out->failed |= s->failed;
    }
    double axes_time = -1.0;
    for (int i = 0; i < in->count; i++) {
        input_source_state *st = &in->src[i]->st;
        int xf = !in->src[i]->cave_space;
        take_pose(&out->head, &st->head, in->tracker_to_cave, xf);
        take_pose(&out->wand, &st->wand, in->tracker_to_cave, xf);
        out->buttons |= st->buttons;
        out->pressed |= st->pressed;
        st->pressed = 0;
        if (st->buttons_time > out->buttons_time)
            out->buttons_time = st->buttons_time;
        if (st->axes_time > 0.0 && st->axes_time > axes_time) {
            axes_time = st->axes_time;
            memcpy(out->axes, st->axes, sizeof out->axes);
            out->axes_time = st->axes_time;
        }
    }
    in->polled = 1;
    in->last_time = out->time;
    /* A stepped recording's end is no poll of its own: recorded, it would replay as a
     * poll with no time elapsed, which playback refuses. */
    if (in->rec && !out->finished && input_playback_record(in->rec, out, e, sizeof e)) {
        if (used < errlen)
            snprintf(err + used, errlen - used, "%s%s", used ? "; " : "", e);
        rc = -1;
    }
    return rc;
}

void input_close(input *in)
{
    if (!in)
        return;
    for (int i = 0; i < in->count; i++)
        in->src[i]->close(in->src[i]);
    if (in->rec)
        input_playback_record_close(in->rec);
    free(in);
}
