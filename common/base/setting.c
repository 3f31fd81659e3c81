#include "base/setting.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

setting_value setting_default(const setting *s)
{
    setting_value v;
    if (s->kind == SETTING_FLOAT)
        v.f = (float)s->def;
    else
        v.i = (int32_t)s->def;
    return v;
}

static int is_pow2(long x) { return x > 0 && (x & (x - 1)) == 0; }

static void choices_text(const setting *s, const char *first, const char *between,
                         const char *last, char *buf, size_t cap)
{
    size_t used = (size_t)snprintf(buf, cap, "%s", first);
    for (int i = 0; i < s->choice_count && used < cap; i++)
        used += (size_t)snprintf(buf + used, cap - used, "%s%s",
                                 i == 0 ? "" : i + 1 == s->choice_count ? last : between,
                                 s->choices[i]);
}

const char *setting_parse(const setting *s, const char *text, setting_value *out)
{
    static _Thread_local char why[256];
    char *end;
    errno = 0;
    switch (s->kind) {
    case SETTING_CHOICE:
        for (int i = 0; i < s->choice_count; i++)
            if (strcmp(text, s->choices[i]) == 0) {
                out->i = i;
                return NULL;
            }
        choices_text(s, "one of ", ", ", " or ", why, sizeof why);
        return why;
    case SETTING_INT: {
        long v = strtol(text, &end, 10);
        int pow2 = (s->flags & SETTING_POW2) != 0;
        snprintf(why, sizeof why, "a %s in %.0f..%.0f", pow2 ? "power of two" : "whole number",
                 s->min, s->max);
        if (end == text || *end || errno || v < s->min || v > s->max || (pow2 && !is_pow2(v)))
            return why;
        out->i = (int32_t)v;
        return NULL;
    }
    case SETTING_FLOAT: {
        float v = strtof(text, &end);
        snprintf(why, sizeof why, "a number in [%g, %g]", s->min, s->max);
        if (end == text || *end || errno || !isfinite(v) || v < s->min || v > s->max)
            return why;
        out->f = v;
        return NULL;
    }
    }
    return "an unknown kind of setting";
}

int setting_clamp(const setting *s, setting_value *v)
{
    setting_value before = *v;
    switch (s->kind) {
    case SETTING_CHOICE:
        if (v->i < 0 || v->i >= s->choice_count)
            *v = setting_default(s);
        break;
    case SETTING_INT:
        if (s->min > 0 && v->i <= 0)
            *v = setting_default(s);
        else if (v->i < s->min)
            v->i = (int32_t)s->min;
        else if (v->i > s->max)
            v->i = (int32_t)s->max;
        if ((s->flags & SETTING_POW2) && !is_pow2(v->i)) {
            int32_t p = 1;
            while (p <= v->i / 2)
                p *= 2;
            v->i = p < s->min ? (int32_t)s->min : p;
        }
        break;
    case SETTING_FLOAT:
        if (isnan(v->f) || (s->min > 0 && v->f <= 0))
            *v = setting_default(s);
        else if (v->f < s->min)
            v->f = (float)s->min;
        else if (v->f > s->max)
            v->f = (float)s->max;
        break;
    }
    return memcmp(&before, v, sizeof before) != 0;
}

void setting_format(const setting *s, setting_value v, char *buf, size_t cap)
{
    if (s->kind == SETTING_FLOAT)
        snprintf(buf, cap, "%g", (double)v.f);
    else if (s->kind == SETTING_CHOICE && v.i >= 0 && v.i < s->choice_count)
        snprintf(buf, cap, "%s", s->choices[v.i]);
    else
        snprintf(buf, cap, "%d", (int)v.i);
}

void setting_arg(const setting *s, char *buf, size_t cap)
{
    if (s->kind == SETTING_CHOICE)
        choices_text(s, "", "|", "|", buf, cap);
    else
        snprintf(buf, cap, "%s", s->arg ? s->arg : "X");
}

setting_value setting_load(const setting *s, const void *owner)
{
    setting_value v;
    memcpy(&v, (const char *)owner + s->offset, sizeof v);
    return v;
}

void setting_store(const setting *s, setting_value v, void *owner)
{
    memcpy((char *)owner + s->offset, &v, sizeof v);
}

int setting_find(const setting *rows, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (strcmp(rows[i].name, name) == 0)
            return i;
    return -1;
}
