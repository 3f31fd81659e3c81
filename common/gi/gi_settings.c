/* gi_settings: the registry's settings as one list of options (see gi_settings.h). */
#include "gi/gi_settings.h"

#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "base/cli.h"

#define GI_METHOD(name) extern const gi_method_settings name##_settings_table;
#include "gi/gi_methods.def"
#undef GI_METHOD

static const gi_method_settings *const methods[] = {
#define GI_METHOD(name) &name##_settings_table,
#include "gi/gi_methods.def"
#undef GI_METHOD
};
enum { METHODS = sizeof methods / sizeof methods[0], MAX_OPTIONS = 96 };

/* Built once: the method names, the "gi" row and the option list. */
static struct {
    const char *names[METHODS];
    char gi_help[512];
    setting gi_row;
    gi_option options[MAX_OPTIONS];
    int count;
} reg;
static pthread_once_t reg_once = PTHREAD_ONCE_INIT;

static void add_option(const setting *row, int method, int slot, int display)
{
    if (reg.count == MAX_OPTIONS) { /* a registry larger than this build allows */
        fprintf(stderr, "cavelight: more than %d GI options: raise MAX_OPTIONS\n", MAX_OPTIONS);
        return;
    }
    reg.options[reg.count++] = (gi_option){row, method, slot, display};
}

static void build(void)
{
    size_t used = (size_t)snprintf(reg.gi_help, sizeof reg.gi_help, "indirect-light method:");
    for (int m = 0; m < METHODS; m++) {
        reg.names[m] = methods[m]->name;
        used += (size_t)snprintf(reg.gi_help + used, sizeof reg.gi_help - used, "\n%s: %s",
                                 methods[m]->name, methods[m]->summary);
    }
    reg.gi_row = (setting){"gi", NULL, SETTING_CHOICE, 0, 0, 0, reg.names, METHODS, SETTING_REBUILD,
                           offsetof(frame_params, gi), reg.gi_help};
    for (int i = 0; i < frame_transport_setting_count; i++)
        add_option(&frame_transport_settings[i], -1, -1, 0);
    add_option(&reg.gi_row, -1, -1, 0);
    int slot = 0;
    for (int m = 0; m < METHODS; m++)
        for (int i = 0; i < methods[m]->count; i++) {
            if (slot == FRAME_GI_SETTINGS_MAX) {
                fprintf(stderr, "cavelight: more than %d GI method settings: raise "
                        "FRAME_GI_SETTINGS_MAX\n", FRAME_GI_SETTINGS_MAX);
                return;
            }
            add_option(&methods[m]->rows[i], m, slot++, 0);
        }
    for (int i = 0; i < frame_display_setting_count; i++)
        add_option(&frame_display_settings[i], -1, -1, 1);
}

static void ready(void) { pthread_once(&reg_once, build); }

int gi_method_count(void) { return METHODS; }

const gi_method_settings *gi_method_at(int method)
{
    return method >= 0 && method < METHODS ? methods[method] : NULL;
}

int gi_method_find(const char *name)
{
    for (int m = 0; m < METHODS; m++)
        if (strcmp(methods[m]->name, name) == 0)
            return m;
    return -1;
}

const char *const *gi_method_names(void)
{
    ready();
    return reg.names;
}

int gi_option_count(void)
{
    ready();
    return reg.count;
}

const gi_option *gi_option_at(int i)
{
    ready();
    return i >= 0 && i < reg.count ? &reg.options[i] : NULL;
}

const gi_option *gi_option_find(const char *name)
{
    ready();
    for (int i = 0; i < reg.count; i++)
        if (strcmp(reg.options[i].row->name, name) == 0)
            return &reg.options[i];
    return NULL;
}

setting_value gi_option_get(const gi_option *o, const frame_params *p)
{
    if (o->slot < 0)
        return setting_load(o->row, p);
    const frame_gi_setting *g = &p->gi_settings[o->slot];
    return g->set ? g->value : setting_default(o->row);
}

void gi_option_put(const gi_option *o, setting_value v, frame_params *p)
{
    if (o->slot < 0) {
        setting_store(o->row, v, p);
        return;
    }
    p->gi_settings[o->slot].set = 1;
    p->gi_settings[o->slot].value = v;
}

int gi_option_is_set(const gi_option *o, const frame_params *p)
{
    return o->slot < 0 || p->gi_settings[o->slot].set;
}

const char *gi_set(frame_params *p, const char *name, const char *text)
{
    static _Thread_local char why[160];
    const gi_option *o = gi_option_find(name);
    if (!o) {
        const char *names[MAX_OPTIONS];
        for (int i = 0; i < reg.count; i++)
            names[i] = reg.options[i].row->name;
        const char *close = cli_nearest(name, names, reg.count);
        snprintf(why, sizeof why, "not a setting%s%s%s", close ? " (did you mean " : "",
                 close ? close : "", close ? "?)" : "");
        return why;
    }
    setting_value v;
    const char *refused = setting_parse(o->row, text, &v);
    if (refused)
        return refused;
    gi_option_put(o, v, p);
    return NULL;
}

const char *gi_set_number(frame_params *p, const char *name, double value)
{
    char text[64];
    snprintf(text, sizeof text, "%.9g", value);
    return gi_set(p, name, text);
}

const char *gi_get_text(const frame_params *p, const char *name, char *buf, size_t cap)
{
    const gi_option *o = gi_option_find(name);
    if (!o) {
        snprintf(buf, cap, "%s", "");
        return buf;
    }
    setting_format(o->row, gi_option_get(o, p), buf, cap);
    return buf;
}

int gi_set_config(const cluster_config *cfg, frame_params *p, char *err, size_t errlen)
{
    for (int i = 0; i < cfg->setting_count; i++) {
        const cluster_setting *st = &cfg->settings[i];
        const char *why = gi_set(p, st->name, st->value);
        if (why) {
            snprintf(err, errlen, "cluster config %s: settings.%s: %s: %s", cfg->path, st->name,
                     st->value, why);
            return -1;
        }
    }
    const char *why = gi_check(p);
    if (why) {
        snprintf(err, errlen, "cluster config %s: settings: %s", cfg->path, why);
        return -1;
    }
    return 0;
}

const char *gi_check(const frame_params *p)
{
    for (int m = 0; m < METHODS; m++) {
        const char *why = methods[m]->check ? methods[m]->check(p) : NULL;
        if (why)
            return why;
    }
    return NULL;
}

int gi_cli_options(cli_option *rows, int count, int first_id, int gi_group, int display_group,
                   unsigned modes)
{
    ready();
    static cli_setting_text texts[MAX_OPTIONS]; /* the same for every caller */
    for (int i = 0; i < reg.count && count < CLI_MAX_OPTIONS; i++)
        cli_option_from_setting(reg.options[i].row, first_id + i,
                                reg.options[i].display ? display_group : gi_group, modes,
                                &texts[i], &rows[count++]);
    return count;
}

void gi_settings_read(int method, const frame_params *p, void *out)
{
    ready();
    if (method < 0 || method >= METHODS)
        return;
    memset(out, 0, methods[method]->struct_size);
    for (int i = 0; i < reg.count; i++)
        if (reg.options[i].method == method)
            setting_store(reg.options[i].row, gi_option_get(&reg.options[i], p), out);
}

int gi_rebuild_needed(int method, const frame_params *a, const frame_params *b)
{
    ready();
    for (int i = 0; i < reg.count; i++) {
        const gi_option *o = &reg.options[i];
        if (o->method != method || !(o->row->flags & SETTING_REBUILD))
            continue;
        setting_value va = gi_option_get(o, a), vb = gi_option_get(o, b);
        if (memcmp(&va, &vb, sizeof va) != 0)
            return 1;
    }
    return 0;
}

int gi_frame_sanitize(frame_params *p)
{
    ready();
    int changed = frame_params_sanitize(p);
    if (p->gi < 0 || p->gi >= METHODS) {
        p->gi = 0;
        changed++;
    }
    for (int i = 0; i < reg.count; i++) {
        const gi_option *o = &reg.options[i];
        if (o->slot < 0 || !p->gi_settings[o->slot].set)
            continue;
        changed += setting_clamp(o->row, &p->gi_settings[o->slot].value);
    }
    return changed;
}

void gi_params_schema(params_schema *s)
{
    ready();
    params_schema_init(s);
    for (int i = 0; i < reg.count; i++) {
        const gi_option *o = &reg.options[i];
        if (o->slot >= 0 || o->row == &reg.gi_row)
            params_schema_add(s, o->row, o->row->offset, o->slot);
    }
}
