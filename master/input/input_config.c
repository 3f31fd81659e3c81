/* input_config: an input config's sources, read, validated, then opened (input_config.h). */
#include "input_config.h"

#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/json_depth.h"
#include "base/json_keys.h"
#include "base/textfile.h"
#include "base/xalloc.h"
#include "cluster/cluster_config.h"
#include "input_desk.h"
#include "input_dtrack.h"
#include "input_playback.h"
#include "input_source.h"
#include "input_usb.h"
#include "input_vrpn.h"

/* Reading one config: every member through keys, faults as one line in err. */
typedef struct cfg_ctx {
    json_keys *keys;
    const char *path;
    int index;          /* sources[index] is being read */
    char *err;
    size_t errlen;
} cfg_ctx;

static const cJSON *item(cfg_ctx *c, const cJSON *o, const char *key)
{
    return json_keys_get(c->keys, o, key);
}

static int get_int(cfg_ctx *c, const cJSON *o, const char *key, int def)
{
    const cJSON *v = item(c, o, key);
    return cJSON_IsNumber(v) ? (int)v->valuedouble : def;
}

static const char *get_str(cfg_ctx *c, const cJSON *o, const char *key)
{
    const cJSON *v = item(c, o, key);
    return cJSON_IsString(v) ? v->valuestring : NULL;
}

/* A number, or a string in C notation ("0x046d"). */
static int get_id(cfg_ctx *c, const cJSON *o, const char *key, long *out)
{
    const cJSON *v = item(c, o, key);
    if (cJSON_IsNumber(v)) {
        *out = (long)v->valuedouble;
        return 0;
    }
    if (cJSON_IsString(v)) {
        char *e;
        *out = strtol(v->valuestring, &e, 0);
        return *e ? -1 : 0;
    }
    return -1;
}

/* The index whose name(i) is s, for i in [0, n); -1 when none (or s is NULL). */
static int name_index(const char *s, const char *(*name)(int), int n)
{
    for (int i = 0; s && i < n; i++)
        if (strcmp(s, name(i)) == 0)
            return i;
    return -1;
}

/* Resolves rel against the directory of the config file. */
static void resolve_path(const char *config, const char *rel, char *out, size_t n)
{
    const char *slash = strrchr(config, '/');
    if (rel[0] == '/' || !slash)
        snprintf(out, n, "%s", rel);
    else
        snprintf(out, n, "%.*s/%s", (int)(slash - config), config, rel);
}

/* A raw-to-logical map: an array of logical names (name(0..n-1)) or null. */
static int parse_map(cfg_ctx *c, const cJSON *j, const char *field, const char *(*name)(int), int n,
                     const char *hint, input_map *m)
{
    const cJSON *arr = item(c, j, field);
    if (!arr)
        return 0;
    if (!cJSON_IsArray(arr) || cJSON_GetArraySize(arr) > INPUT_MAP_SIZE) {
        snprintf(c->err, c->errlen, "input config %s: \"%s\" must be an array of at most %d names",
                 c->path, field, INPUT_MAP_SIZE);
        return -1;
    }
    memset(m->to, -1, sizeof m->to);
    m->set = 1;
    int i = 0;
    const cJSON *it;
    cJSON_ArrayForEach(it, arr) {
        if (cJSON_IsString(it)) {
            int found = name_index(it->valuestring, name, n);
            if (found < 0) {
                snprintf(c->err, c->errlen, "input config %s: \"%s\"[%d] is \"%s\"; use %s or null",
                         c->path, field, i, it->valuestring, hint);
                return -1;
            }
            m->to[i] = (int8_t)found;
        } else if (!cJSON_IsNull(it)) {
            snprintf(c->err, c->errlen, "input config %s: \"%s\"[%d] must be a name or null", c->path,
                     field, i);
            return -1;
        }
        i++;
    }
    return 0;
}

/* One source as the config describes it, before anything is opened. */
typedef struct source_spec {
    int type;                 /* index into source_types[] */
    char name[64];
    char text[2][4096];       /* strings the desc points at, beyond the JSON's own */
    union {
        input_dtrack_desc dtrack;
        input_vrpn_desc vrpn;
        input_usb_desc usb;
        input_desk_desc desk;
        input_playback_desc playback;
    } d;
} source_spec;

static int parse_dtrack(cfg_ctx *c, const cJSON *j, source_spec *s)
{
    input_dtrack_desc *d = &s->d.dtrack;
    *d = (input_dtrack_desc){.name = s->name, .port = get_int(c, j, "port", INPUT_DTRACK_DEFAULT_PORT),
                             .bind = get_str(c, j, "bind"), .sender = get_str(c, j, "sender"),
                             .head_id = get_int(c, j, "head", 0), .wand_id = get_int(c, j, "wand", 0)};
    const char *kind = get_str(c, j, "wand_kind");
    if (kind && strcmp(kind, "body") == 0) {
        d->wand_kind = INPUT_DTRACK_WAND_BODY;
    } else if (kind && strcmp(kind, "flystick") != 0) {
        snprintf(c->err, c->errlen, "input config %s: sources[%d].wand_kind is \"%s\"; use "
                 "\"flystick\" or \"body\"", c->path, c->index, kind);
        return -1;
    }
    return parse_map(c, j, "buttons", input_button_name, INPUT_BUTTON_NAMED, "L, M, R, C, AUX", &d->buttons) ||
           parse_map(c, j, "axes", input_axis_name, INPUT_AXIS_COUNT, "X, Y, Z, W", &d->axes);
}

static int parse_vrpn(cfg_ctx *c, const cJSON *j, source_spec *s)
{
    /* "tracker": "Tracker0@host:port" as VRPN users write it, or name, host, port apart. */
    char *tracker = s->text[0], *host = s->text[1];
    snprintf(tracker, sizeof s->text[0], "Tracker0");
    snprintf(host, sizeof s->text[1], "localhost");
    int port = get_int(c, j, "port", INPUT_VRPN_DEFAULT_PORT);
    const char *t = get_str(c, j, "tracker");
    if (t) {
        const char *at = strchr(t, '@');
        snprintf(tracker, 64, "%.*s", at ? (int)(at - t) : (int)strlen(t), t);
        if (at) {
            const char *colon = strrchr(at + 1, ':');
            snprintf(host, 256, "%.*s", colon ? (int)(colon - at - 1) : (int)strlen(at + 1), at + 1);
            if (colon)
                port = atoi(colon + 1);
        }
    }
    if (get_str(c, j, "host"))
        snprintf(host, 256, "%s", get_str(c, j, "host"));
    const cJSON *rc = item(c, j, "reconnect");
    input_vrpn_desc *d = &s->d.vrpn;
    *d = (input_vrpn_desc){.name = s->name, .host = host, .port = port, .tracker = tracker,
                           .sensors_set = 1, .head_sensor = get_int(c, j, "head", 0),
                           .wand_sensor = get_int(c, j, "wand", 1),
                           .buttons = get_str(c, j, "button_device"),
                           .analog = get_str(c, j, "analog_device"),
                           .reconnect_interval = cJSON_IsNumber(rc) ? rc->valuedouble : 0};
    return parse_map(c, j, "buttons", input_button_name, INPUT_BUTTON_NAMED, "L, M, R, C, AUX", &d->button_map) ||
           parse_map(c, j, "axes", input_axis_name, INPUT_AXIS_COUNT, "X, Y, Z, W", &d->axis_map);
}

static int parse_usb_buttons(cfg_ctx *c, const cJSON *j, input_usb_desc *d)
{
    const cJSON *it;
    cJSON_ArrayForEach(it, item(c, j, "buttons")) {
        int to = name_index(get_str(c, it, "to"), input_button_name, INPUT_BUTTON_NAMED);
        if (d->button_count == INPUT_USB_MAX_BUTTONS || to < 0) {
            snprintf(c->err, c->errlen, "input config %s: sources[%d].buttons[%d]: \"to\" must be L, "
                     "M, R, C or AUX (at most %d buttons)", c->path, c->index, d->button_count,
                     INPUT_USB_MAX_BUTTONS);
            return -1;
        }
        d->buttons[d->button_count++] = (input_usb_button){
            .byte = get_int(c, it, "byte", 0), .bit = get_int(c, it, "bit", 0), .to = to};
    }
    return 0;
}

static const char *usb_format_name(int i)
{
    static const char *const formats[] = {"u8", "s8", "u16", "s16"};
    return formats[i];
}

static int parse_usb_axes(cfg_ctx *c, const cJSON *j, input_usb_desc *d)
{
    const cJSON *it;
    cJSON_ArrayForEach(it, item(c, j, "axes")) {
        int to = name_index(get_str(c, it, "to"), input_axis_name, INPUT_AXIS_COUNT);
        const char *fs = get_str(c, it, "format");
        int format = fs ? name_index(fs, usb_format_name, 4) : 0;
        if (d->axis_count == INPUT_USB_MAX_AXES || to < 0 || format < 0) {
            snprintf(c->err, c->errlen, "input config %s: sources[%d].axes[%d]: \"to\" must be X, Y, Z "
                     "or W and \"format\" u8, s8, u16 or s16 (got \"%s\")", c->path, c->index,
                     d->axis_count, fs ? fs : "");
            return -1;
        }
        const cJSON *mn = item(c, it, "min"), *mx = item(c, it, "max");
        d->axes[d->axis_count++] = (input_usb_axis){
            .byte = get_int(c, it, "byte", 0), .format = (input_usb_format)format,
            .min = cJSON_IsNumber(mn) ? (float)mn->valuedouble : 0.0f,
            .max = cJSON_IsNumber(mx) ? (float)mx->valuedouble : 0.0f, .to = to,
            .invert = cJSON_IsTrue(item(c, it, "invert"))};
    }
    return 0;
}

static int parse_usb(cfg_ctx *c, const cJSON *j, source_spec *s)
{
    input_usb_desc *d = &s->d.usb;
    const cJSON *rc = item(c, j, "reconnect");
    *d = (input_usb_desc){.name = s->name, .retry_interval = cJSON_IsNumber(rc) ? rc->valuedouble : 0};
    long vendor, product;
    if (get_id(c, j, "vendor", &vendor) || get_id(c, j, "product", &product) || vendor < 0 ||
        vendor > 0xffff || product < 0 || product > 0xffff) {
        snprintf(c->err, c->errlen, "input config %s: sources[%d] (usb) needs \"vendor\" and "
                 "\"product\" ids, e.g. \"0x046d\" (see lsusb)", c->path, c->index);
        return -1;
    }
    d->vendor = (uint16_t)vendor;
    d->product = (uint16_t)product;
    d->interface_number = get_int(c, j, "interface", 0);
    long ep = 0;
    if (item(c, j, "endpoint") && get_id(c, j, "endpoint", &ep) == 0)
        d->endpoint = (uint8_t)ep;
    return parse_usb_buttons(c, j, d) || parse_usb_axes(c, j, d);
}

static int parse_desk(cfg_ctx *c, const cJSON *j, source_spec *s)
{
    s->d.desk = (input_desk_desc){.name = s->name, .width = get_int(c, j, "width", 0),
                                  .height = get_int(c, j, "height", 0)};
    return 0;
}

static int parse_playback(cfg_ctx *c, const cJSON *j, source_spec *s)
{
    const char *file = get_str(c, j, "file");
    if (!file) {
        snprintf(c->err, c->errlen, "input config %s: sources[%d] (playback) needs \"file\"", c->path,
                 c->index);
        return -1;
    }
    resolve_path(c->path, file, s->text[0], sizeof s->text[0]);
    s->d.playback = (input_playback_desc){.name = s->name, .path = s->text[0],
                                          .realtime = cJSON_IsTrue(item(c, j, "realtime")),
                                          .loop = cJSON_IsTrue(item(c, j, "loop"))};
    return 0;
}

static input_source *open_dtrack(const source_spec *s, char *err, size_t n) { return input_dtrack_open(&s->d.dtrack, err, n); }
static input_source *open_vrpn(const source_spec *s, char *err, size_t n) { return input_vrpn_open(&s->d.vrpn, err, n); }
static input_source *open_usb(const source_spec *s, char *err, size_t n) { (void)err, (void)n; return input_usb_open(&s->d.usb); }
static input_source *open_desk(const source_spec *s, char *err, size_t n) { return input_desk_open(&s->d.desk, err, n); }
static input_source *open_playback(const source_spec *s, char *err, size_t n) { return input_playback_open(&s->d.playback, err, n); }

/* The source types: each reads its keys, then opens its source. */
static const struct source_type {
    const char *name;
    int (*parse)(cfg_ctx *c, const cJSON *j, source_spec *s);
    input_source *(*open)(const source_spec *s, char *err, size_t errlen);
} source_types[] = {
    {"dtrack", parse_dtrack, open_dtrack},
    {"vrpn", parse_vrpn, open_vrpn},
    {"usb", parse_usb, open_usb},
    {"desk", parse_desk, open_desk},
    {"playback", parse_playback, open_playback},
};
enum { SOURCE_TYPES = sizeof source_types / sizeof *source_types };

static const char *source_type_name(int i) { return source_types[i].name; }

static int parse_source(cfg_ctx *c, const cJSON *j, source_spec *s)
{
    const char *type = get_str(c, j, "type"), *name = get_str(c, j, "name");
    snprintf(s->name, sizeof s->name, "%s", name ? name : "");
    if (!s->name[0])
        snprintf(s->name, sizeof s->name, "source%d", c->index);
    if (!type) {
        snprintf(c->err, c->errlen, "input config %s: sources[%d] has no \"type\" (dtrack, vrpn, usb, "
                 "desk or playback)", c->path, c->index);
        return -1;
    }
    s->type = name_index(type, source_type_name, SOURCE_TYPES);
    if (s->type < 0) {
        snprintf(c->err, c->errlen, "input config %s: sources[%d] has unknown type \"%s\" (dtrack, "
                 "vrpn, usb, desk, playback)", c->path, c->index, type);
        return -1;
    }
    return source_types[s->type].parse(c, j, s);
}

/* A parsed config: its document (the specs point into it), the sources, the record path. */
typedef struct parsed_config {
    cJSON *root;
    source_spec *specs;
    int count;
    char record[4096];   /* "" = none */
} parsed_config;

static void parsed_free(parsed_config *p)
{
    cJSON_Delete(p->root);
    free(p->specs);
}

typedef struct unknown_ctx {
    const input_desc *desc;
    const char *path;
    char *err;
    size_t errlen;
    int count;
} unknown_ctx;

static void note_unknown(void *user, const char *field, const char *key, const char *nearest, const char *valid)
{
    unknown_ctx *u = user;
    char words[512], line[1024];
    json_keys_describe(key, nearest, valid, words, sizeof words);
    snprintf(line, sizeof line, "input config %s: field %s: %s", u->path, field, words);
    if (u->desc->strict) { /* an error: the first one, and how many more */
        if (u->count == 0)
            snprintf(u->err, u->errlen, "%s", line);
    } else if (u->desc->warn) {
        u->desc->warn(u->desc->warn_user, line);
    } else {
        fprintf(stderr, "warning: %s\n", line);
    }
    u->count++;
}

/* The record path: the config's "record" in desc->out_dir, unless desc names one. */
static void record_path(const input_desc *desc, const char *record, char *out, size_t cap)
{
    const char *dir = desc->out_dir ? desc->out_dir : CLUSTER_DEFAULT_OUT;
    out[0] = '\0';
    if (desc->record_path || !record)
        return;
    if (record[0] == '/')
        snprintf(out, cap, "%s", record);
    else
        snprintf(out, cap, "%s/%s", dir, record);
}

/* Reads desc->path (a JSON config, not a recording) into p. 0, or -1 with err. */
static int parse_config(const input_desc *desc, parsed_config *p, char *err, size_t errlen)
{
    memset(p, 0, sizeof *p);
    char why[128];
    char *text = textfile_read_max(desc->path, (size_t)1 << 20, NULL, why, sizeof why);
    if (!text) {
        snprintf(err, errlen, "input config %s: %s", desc->path, why);
        return -1;
    }
    if (json_depth_check(text, strlen(text), why, sizeof why) != 0) {
        free(text);
        snprintf(err, errlen, "input config %s: %s", desc->path, why);
        return -1;
    }
    p->root = cJSON_Parse(text);
    free(text);
    if (!p->root || !cJSON_IsObject(p->root)) {
        snprintf(err, errlen, "input config %s: not a JSON object nor a recording (first line "
                 "\"%s\")", desc->path, INPUT_PLAYBACK_MAGIC);
        return -1;
    }
    cfg_ctx c = {.keys = json_keys_create(), .path = desc->path, .err = err, .errlen = errlen};
    record_path(desc, get_str(&c, p->root, "record"), p->record, sizeof p->record);
    const cJSON *sources = item(&c, p->root, "sources");
    int rc = 0;
    if (!cJSON_IsArray(sources) || cJSON_GetArraySize(sources) == 0) {
        snprintf(err, errlen, "input config %s: \"sources\" must be a non-empty array", desc->path);
        rc = -1;
    } else {
        p->specs = xcalloc((size_t)cJSON_GetArraySize(sources), sizeof *p->specs);
        const cJSON *it;
        cJSON_ArrayForEach(it, sources) {
            c.index = p->count;
            if ((rc = parse_source(&c, it, &p->specs[p->count++])) != 0)
                break;
        }
    }
    if (rc == 0) {
        unknown_ctx u = {.desc = desc, .path = desc->path, .err = err, .errlen = errlen};
        json_keys_unknown(c.keys, p->root, note_unknown, &u);
        if (desc->strict && u.count > 1) {
            size_t used = strlen(err);
            snprintf(err + used, errlen - used, " (and %d more unknown keys)", u.count - 1);
        }
        rc = desc->strict && u.count ? -1 : 0;
    }
    json_keys_destroy(c.keys);
    return rc;
}

static input *open_recording(const input_desc *desc, char *err, size_t errlen)
{
    input *in = input_create(desc, err, errlen);
    if (!in)
        return NULL;
    input_playback_desc pd = {.name = "playback", .path = desc->path};
    input_source *s = input_playback_open(&pd, err, errlen);
    if (!s || input_add_source(in, s, err, errlen)) {
        input_close(in);
        return NULL;
    }
    return in;
}

input *input_open(const input_desc *desc, char *err, size_t errlen)
{
    if (!desc->path) {
        snprintf(err, errlen, "input: no input config or recording given");
        return NULL;
    }
    if (input_playback_is_recording(desc->path))
        return open_recording(desc, err, errlen);
    parsed_config p;
    if (parse_config(desc, &p, err, errlen) != 0) {
        parsed_free(&p);
        return NULL;
    }
    input_desc d = *desc;
    if (p.record[0])
        d.record_path = p.record;
    input *in = input_create(&d, err, errlen);
    for (int i = 0; in && i < p.count; i++) {
        input_source *s = source_types[p.specs[i].type].open(&p.specs[i], err, errlen);
        if (!s || input_add_source(in, s, err, errlen)) {
            input_close(in);
            in = NULL;
        }
    }
    parsed_free(&p);
    return in;
}

int input_config_check(const input_desc *desc, char *err, size_t errlen)
{
    if (!desc->path) {
        snprintf(err, errlen, "input: no input config or recording given");
        return -1;
    }
    if (input_playback_is_recording(desc->path))
        return 0;
    parsed_config p;
    int rc = parse_config(desc, &p, err, errlen);
    parsed_free(&p);
    return rc;
}
