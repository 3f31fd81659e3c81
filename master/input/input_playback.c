/* input_playback: recording file writer and reader (format in input_playback.h). */
#include "input_playback.h"
#include "base/xalloc.h"
#include "base/regular_file.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { LINE_MAX_CHARS = 1024, MAX_TOKENS = 20 };

/* ---- reading ---- */

typedef struct block {
    int has_head, has_wand, has_buttons, has_axes;
    input_pose head, wand;
    uint32_t held, pressed;
    double buttons_time;
    float axes[INPUT_AXIS_COUNT];
    double axes_time;
    double time, dt;
} block;

typedef struct playback_source {
    input_source base;
    input_playback_desc desc;
    char path[4096];
    FILE *f;
    int line;
    int polls;           /* poll records read since the file's start */
    int eof;
    int pending;         /* realtime: a block read but not yet due */
    block next;
    double first_time;   /* realtime: poll time of the first block */
    double start;        /* realtime: input clock at the first poll, -1 before */
} playback_source;

static int parse_double(const char *s, double *out)
{
    char *e;
    errno = 0;
    double v = strtod(s, &e);
    if (*e != '\0' || e == s || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

static int parse_float(const char *s, float *out)
{
    char *e;
    float v = strtof(s, &e);
    if (*e != '\0' || e == s || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

static int parse_mask(const char *s, uint32_t *out)
{
    char *e;
    errno = 0;
    unsigned long v = strtoul(s, &e, 16);
    if (*e != '\0' || e == s || errno || v > 0xffffffffUL)
        return -1;
    *out = (uint32_t)v;
    return 0;
}

static int parse_pose(char **tok, int n, input_pose *p)
{
    if (n != 14 || parse_double(tok[1], &p->time))
        return -1;
    for (int i = 0; i < 3; i++)
        if (parse_float(tok[2 + i], &p->position[i]))
            return -1;
    for (int i = 0; i < 9; i++)
        if (parse_float(tok[5 + i], &p->rotation[i]))
            return -1;
    p->valid = 1;
    return 0;
}

/* Reads one block up to its poll line. Returns 1 read, 0 end of file, -1 malformed. */
static int read_block(playback_source *pb, block *b, char *err, size_t errlen)
{
    memset(b, 0, sizeof *b);
    char line[LINE_MAX_CHARS];
    while (fgets(line, sizeof line, pb->f)) {
        pb->line++;
        size_t len = strlen(line);
        if (len == sizeof line - 1 && line[len - 1] != '\n') {
            snprintf(err, errlen, "input playback %s:%d: line too long", pb->path, pb->line);
            return -1;
        }
        char *tok[MAX_TOKENS], *save = NULL;
        int n = 0;
        for (char *t = strtok_r(line, " \t\r\n", &save); t; t = strtok_r(NULL, " \t\r\n", &save)) {
            if (n == MAX_TOKENS) {
                n = -1;
                break;
            }
            tok[n++] = t;
        }
        if (n < 0) {
            snprintf(err, errlen, "input playback %s:%d: too many values", pb->path, pb->line);
            return -1;
        }
        if (n == 0 || tok[0][0] == '#')
            continue;
        int bad = 0;
        if (strcmp(tok[0], "head") == 0) {
            bad = parse_pose(tok, n, &b->head);
            b->has_head = 1;
        } else if (strcmp(tok[0], "wand") == 0) {
            bad = parse_pose(tok, n, &b->wand);
            b->has_wand = 1;
        } else if (strcmp(tok[0], "buttons") == 0) {
            bad = n != 4 || parse_double(tok[1], &b->buttons_time) ||
                  parse_mask(tok[2], &b->held) || parse_mask(tok[3], &b->pressed);
            b->has_buttons = 1;
        } else if (strcmp(tok[0], "axes") == 0) {
            bad = n != 2 + INPUT_AXIS_COUNT || parse_double(tok[1], &b->axes_time);
            for (int i = 0; !bad && i < INPUT_AXIS_COUNT; i++)
                bad = parse_float(tok[2 + i], &b->axes[i]) || fabsf(b->axes[i]) > 1.0f;
            b->has_axes = 1;
        } else if (strcmp(tok[0], "poll") == 0) {
            if (n != 3 || parse_double(tok[1], &b->time) || parse_double(tok[2], &b->dt)) {
                bad = 1;
            } else if (!(b->dt > 0 || (b->dt == 0 && pb->polls == 0)) ||
                       b->dt > INPUT_PLAYBACK_MAX_DT) {
                snprintf(err, errlen, "input playback %s:%d: poll dt %s out of range (0 < dt <= "
                         "%g s; 0 only on the first poll)", pb->path, pb->line, tok[2],
                         INPUT_PLAYBACK_MAX_DT);
                return -1;
            } else {
                pb->polls++;
                return 1;
            }
        } else if (strcmp(tok[0], "cavelight-input") == 0 && pb->line == 1) {
            continue;
        } else {
            snprintf(err, errlen, "input playback %s:%d: unknown record \"%s\" (head, wand, "
                     "buttons, axes, poll)", pb->path, pb->line, tok[0]);
            return -1;
        }
        if (bad) {
            snprintf(err, errlen, "input playback %s:%d: malformed \"%s\" record", pb->path,
                     pb->line, tok[0]);
            return -1;
        }
    }
    return 0;
}

static void apply_block(const block *b, input_source_state *st, int keep_times, double now)
{
    if (b->has_head) {
        st->head = b->head;
        if (!keep_times)
            st->head.time = now;
    }
    if (b->has_wand) {
        st->wand = b->wand;
        if (!keep_times)
            st->wand.time = now;
    }
    if (b->has_buttons) {
        st->buttons = b->held;
        st->pressed |= b->pressed;
        st->buttons_time = keep_times ? b->buttons_time : now;
    }
    if (b->has_axes) {
        memcpy(st->axes, b->axes, sizeof st->axes);
        st->axes_time = keep_times ? b->axes_time : now;
    }
}

static void rewind_file(playback_source *pb)
{
    rewind(pb->f);
    pb->line = 0;
    pb->polls = 0;
    pb->eof = 0;
}

static int playback_poll(input_source *s, double now, char *err, size_t errlen)
{
    playback_source *pb = (playback_source *)s;
    if (pb->eof)
        return 0;
    if (!pb->desc.realtime) {
        block b;
        int r = read_block(pb, &b, err, errlen);
        if (r <= 0) {
            pb->eof = 1;
            s->finished = 1;
            s->failed = r < 0;
            s->step_dt = 0.0;
            return r;
        }
        apply_block(&b, &s->st, 1, now);
        s->step_time = b.time;
        s->step_dt = b.dt;
        return 0;
    }
    if (pb->start < 0)
        pb->start = now;
    for (;;) {
        if (!pb->pending) {
            int r = read_block(pb, &pb->next, err, errlen);
            if (r < 0) {
                pb->eof = 1;
                s->failed = 1;
                return -1;
            }
            if (r == 0) {
                if (!pb->desc.loop || pb->line == 0) {
                    pb->eof = 1;
                    return 0;
                }
                rewind_file(pb);
                pb->start = now;
                pb->first_time = -1.0;
                continue;
            }
            pb->pending = 1;
            if (pb->first_time < 0)
                pb->first_time = pb->next.time;
        }
        if (pb->next.time - pb->first_time > now - pb->start)
            return 0;
        apply_block(&pb->next, &s->st, 0, now);
        pb->pending = 0;
    }
}

static void playback_close(input_source *s)
{
    playback_source *pb = (playback_source *)s;
    fclose(pb->f);
    free(pb);
}

int input_playback_is_recording(const char *path)
{
    char why[128];
    FILE *f = regular_fopen(path, why, sizeof why);
    if (!f)
        return 0;
    char line[64] = {0};
    int ok = fgets(line, sizeof line, f) &&
             strncmp(line, INPUT_PLAYBACK_MAGIC, strlen(INPUT_PLAYBACK_MAGIC)) == 0;
    fclose(f);
    return ok;
}

input_source *input_playback_open(const input_playback_desc *desc, char *err, size_t errlen)
{
    if (!input_playback_is_recording(desc->path)) {
        snprintf(err, errlen, "input playback %s: cannot open, or first line is not \"%s\"",
                 desc->path, INPUT_PLAYBACK_MAGIC);
        return NULL;
    }
    playback_source *pb = xcalloc(1, sizeof *pb);
    snprintf(pb->path, sizeof pb->path, "%s", desc->path);
    pb->desc = *desc;
    pb->desc.path = pb->path;
    pb->desc.name = NULL;
    char why[128];
    pb->f = regular_fopen(desc->path, why, sizeof why);
    if (!pb->f) {
        snprintf(err, errlen, "input playback %s: %s", desc->path, why);
        free(pb);
        return NULL;
    }
    snprintf(pb->base.name, sizeof pb->base.name, "%s", desc->name ? desc->name : "playback");
    pb->base.cave_space = 1;
    pb->base.stepped = !desc->realtime;
    pb->start = -1.0;
    pb->first_time = -1.0;
    pb->base.poll = playback_poll;
    pb->base.close = playback_close;
    return &pb->base;
}

/* ---- writing ---- */

struct input_playback_recorder {
    FILE *f;
    char path[4096];
    input_state prev;
    int first;
};

input_playback_recorder *input_playback_record_open(const char *path, char *err, size_t errlen)
{
    input_playback_recorder *r = xcalloc(1, sizeof *r);
    r->f = fopen(path, "wb");
    if (!r->f) {
        snprintf(err, errlen, "input record %s: cannot create: %s", path, strerror(errno));
        free(r);
        return NULL;
    }
    snprintf(r->path, sizeof r->path, "%s", path);
    r->first = 1;
    time_t now = time(NULL);
    struct tm tm;
    char when[64] = "";
    if (gmtime_r(&now, &tm))
        strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &tm);
    fprintf(r->f, "%s\n# recorded %s by cavelight-master; format in docs/input.md\n",
            INPUT_PLAYBACK_MAGIC, when);
    return r;
}

static int pose_changed(const input_pose *a, const input_pose *b)
{
    return a->valid && (!b->valid || a->time != b->time ||
                        memcmp(a->position, b->position, sizeof a->position) ||
                        memcmp(a->rotation, b->rotation, sizeof a->rotation));
}

static void write_pose(FILE *f, const char *kind, const input_pose *p)
{
    fprintf(f, "%s %.17g", kind, p->time);
    for (int i = 0; i < 3; i++)
        fprintf(f, " %.9g", (double)p->position[i]);
    for (int i = 0; i < 9; i++)
        fprintf(f, " %.9g", (double)p->rotation[i]);
    fputc('\n', f);
}

int input_playback_record(input_playback_recorder *r, const input_state *s, char *err,
                          size_t errlen)
{
    if (pose_changed(&s->head, &r->prev.head))
        write_pose(r->f, "head", &s->head);
    if (pose_changed(&s->wand, &r->prev.wand))
        write_pose(r->f, "wand", &s->wand);
    if (s->buttons != r->prev.buttons || s->pressed)
        fprintf(r->f, "buttons %.17g %x %x\n", s->buttons_time, s->buttons, s->pressed);
    if (s->axes_time != r->prev.axes_time || (r->first && s->axes_time > 0)) {
        fprintf(r->f, "axes %.17g", s->axes_time);
        for (int i = 0; i < INPUT_AXIS_COUNT; i++)
            fprintf(r->f, " %.9g", (double)s->axes[i]);
        fputc('\n', r->f);
    }
    fprintf(r->f, "poll %.17g %.17g\n", s->time, s->dt);
    r->prev = *s;
    r->first = 0;
    /* Flush every poll so that a crashed session still leaves a usable recording. */
    if (fflush(r->f) || ferror(r->f)) {
        snprintf(err, errlen, "input record %s: write failed: %s", r->path, strerror(errno));
        return -1;
    }
    return 0;
}

void input_playback_record_close(input_playback_recorder *r)
{
    if (!r)
        return;
    fclose(r->f);
    free(r);
}
