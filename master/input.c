/* input: source list, merging, config loading, recording. */
#include "input.h"
#include "base/xalloc.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/folder.h"
#include "cluster/cluster_config.h"
#include "input_desk.h"
#include "input_dtrack.h"
#include "input_playback.h"
#include "input_source.h"
#include "input_usb.h"
#include "input_vrpn.h"
#include "base/textfile.h"

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

/* ---- the input handle ---- */

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
    if (in->rec && input_playback_record(in->rec, out, e, sizeof e)) {
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

/* ---- config ---- */

static int parse_map(const cJSON *arr, const char *const *names, int name_count,
                     input_map *m, const char *path, const char *field, const char *hint,
                     char *err, size_t errlen)
{
    if (!arr)
        return 0;
    if (!cJSON_IsArray(arr) || cJSON_GetArraySize(arr) > INPUT_MAP_SIZE) {
        snprintf(err, errlen, "input config %s: \"%s\" must be an array of at most %d names",
                 path, field, INPUT_MAP_SIZE);
        return -1;
    }
    memset(m->to, -1, sizeof m->to);
    m->set = 1;
    int i = 0;
    const cJSON *it;
    cJSON_ArrayForEach(it, arr) {
        if (cJSON_IsString(it)) {
            int found = -1;
            for (int k = 0; k < name_count; k++)
                if (strcmp(it->valuestring, names[k]) == 0)
                    found = k;
            if (found < 0) {
                snprintf(err, errlen, "input config %s: \"%s\"[%d] is \"%s\"; use %s or null",
                         path, field, i, it->valuestring, hint);
                return -1;
            }
            m->to[i] = (int8_t)found;
        } else if (!cJSON_IsNull(it)) {
            snprintf(err, errlen, "input config %s: \"%s\"[%d] must be a name or null", path,
                     field, i);
            return -1;
        }
        i++;
    }
    return 0;
}

static const char *const button_names[] = {"L", "M", "R", "C", "AUX"};

const char *input_button_name(int button)
{
    return button >= 0 && button < (int)(sizeof button_names / sizeof *button_names) ? button_names[button] : NULL;
}
static const char *const axis_names[] = {"X", "Y", "Z", "W"};

static int get_int(const cJSON *o, const char *key, int def)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(v) ? (int)v->valuedouble : def;
}

static const char *get_str(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsString(v) ? v->valuestring : NULL;
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

/* A number, or a string in C notation ("0x046d"). */
static int get_id(const cJSON *o, const char *key, long *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
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

static int name_index(const char *s, const char *const *names, int n)
{
    for (int i = 0; s && i < n; i++)
        if (strcmp(s, names[i]) == 0)
            return i;
    return -1;
}

static int parse_usb(const cJSON *j, const char *path, int index, input_usb_desc *d, char *err,
                     size_t errlen)
{
    long vendor, product;
    if (get_id(j, "vendor", &vendor) || get_id(j, "product", &product) || vendor < 0 ||
        vendor > 0xffff || product < 0 || product > 0xffff) {
        snprintf(err, errlen, "input config %s: sources[%d] (usb) needs \"vendor\" and "
                 "\"product\" ids, e.g. \"0x046d\" (see lsusb)", path, index);
        return -1;
    }
    d->vendor = (uint16_t)vendor;
    d->product = (uint16_t)product;
    d->interface_number = get_int(j, "interface", 0);
    long ep = 0;
    if (cJSON_GetObjectItemCaseSensitive(j, "endpoint") && get_id(j, "endpoint", &ep) == 0)
        d->endpoint = (uint8_t)ep;
    const cJSON *it;
    cJSON_ArrayForEach(it, cJSON_GetObjectItemCaseSensitive(j, "buttons")) {
        int to = name_index(get_str(it, "to"), button_names, 5);
        if (d->button_count == INPUT_USB_MAX_BUTTONS || to < 0) {
            snprintf(err, errlen, "input config %s: sources[%d].buttons[%d]: \"to\" must be L, "
                     "M, R, C or AUX (at most %d buttons)", path, index, d->button_count,
                     INPUT_USB_MAX_BUTTONS);
            return -1;
        }
        d->buttons[d->button_count++] = (input_usb_button){.byte = get_int(it, "byte", 0),
                                                           .bit = get_int(it, "bit", 0), .to = to};
    }
    static const char *const formats[] = {"u8", "s8", "u16", "s16"};
    cJSON_ArrayForEach(it, cJSON_GetObjectItemCaseSensitive(j, "axes")) {
        int to = name_index(get_str(it, "to"), axis_names, 4);
        const char *fs = get_str(it, "format");
        int format = fs ? name_index(fs, formats, 4) : 0;
        if (d->axis_count == INPUT_USB_MAX_AXES || to < 0 || format < 0) {
            snprintf(err, errlen, "input config %s: sources[%d].axes[%d]: \"to\" must be X, Y, Z "
                     "or W and \"format\" u8, s8, u16 or s16 (got \"%s\")", path, index,
                     d->axis_count, fs ? fs : "");
            return -1;
        }
        const cJSON *mn = cJSON_GetObjectItemCaseSensitive(it, "min");
        const cJSON *mx = cJSON_GetObjectItemCaseSensitive(it, "max");
        d->axes[d->axis_count++] = (input_usb_axis){
            .byte = get_int(it, "byte", 0), .format = (input_usb_format)format,
            .min = cJSON_IsNumber(mn) ? (float)mn->valuedouble : 0.0f,
            .max = cJSON_IsNumber(mx) ? (float)mx->valuedouble : 0.0f, .to = to,
            .invert = cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(it, "invert"))};
    }
    return 0;
}

static input_source *open_source(const cJSON *j, const char *path, int index, char *err,
                                 size_t errlen)
{
    const char *type = get_str(j, "type");
    char name[64];
    snprintf(name, sizeof name, "%s", get_str(j, "name") ? get_str(j, "name") : "");
    if (!name[0])
        snprintf(name, sizeof name, "source%d", index);
    if (!type) {
        snprintf(err, errlen, "input config %s: sources[%d] has no \"type\" (dtrack, vrpn, usb, "
                 "desk or playback)", path, index);
        return NULL;
    }
    if (strcmp(type, "dtrack") == 0) {
        input_dtrack_desc d = {.name = name,
                               .port = get_int(j, "port", INPUT_DTRACK_DEFAULT_PORT),
                               .bind = get_str(j, "bind"), .sender = get_str(j, "sender"),
                               .head_id = get_int(j, "head", 0),
                               .wand_id = get_int(j, "wand", 0)};
        const char *kind = get_str(j, "wand_kind");
        if (kind && strcmp(kind, "body") == 0)
            d.wand_kind = INPUT_DTRACK_WAND_BODY;
        else if (kind && strcmp(kind, "flystick") != 0) {
            snprintf(err, errlen, "input config %s: sources[%d].wand_kind is \"%s\"; use "
                     "\"flystick\" or \"body\"", path, index, kind);
            return NULL;
        }
        if (parse_map(cJSON_GetObjectItemCaseSensitive(j, "buttons"), button_names, 5,
                      &d.buttons, path, "buttons", "L, M, R, C, AUX", err, errlen) ||
            parse_map(cJSON_GetObjectItemCaseSensitive(j, "axes"), axis_names, 4, &d.axes,
                      path, "axes", "X, Y, Z, W", err, errlen))
            return NULL;
        return input_dtrack_open(&d, err, errlen);
    }
    if (strcmp(type, "vrpn") == 0) {
        /* "tracker": "Tracker0@host:port" as VRPN users write it, or name, host, port apart. */
        char tracker[64] = "Tracker0", host[256] = "localhost";
        int port = get_int(j, "port", INPUT_VRPN_DEFAULT_PORT);
        const char *t = get_str(j, "tracker");
        if (t) {
            const char *at = strchr(t, '@');
            snprintf(tracker, sizeof tracker, "%.*s", at ? (int)(at - t) : (int)strlen(t), t);
            if (at) {
                const char *colon = strrchr(at + 1, ':');
                snprintf(host, sizeof host, "%.*s", colon ? (int)(colon - at - 1) : (int)strlen(at + 1),
                         at + 1);
                if (colon)
                    port = atoi(colon + 1);
            }
        }
        if (get_str(j, "host"))
            snprintf(host, sizeof host, "%s", get_str(j, "host"));
        const cJSON *rc = cJSON_GetObjectItemCaseSensitive(j, "reconnect");
        input_vrpn_desc d = {.name = name, .host = host, .port = port, .tracker = tracker,
                             .sensors_set = 1, .head_sensor = get_int(j, "head", 0),
                             .wand_sensor = get_int(j, "wand", 1),
                             .buttons = get_str(j, "button_device"),
                             .analog = get_str(j, "analog_device"),
                             .reconnect_interval = cJSON_IsNumber(rc) ? rc->valuedouble : 0};
        if (parse_map(cJSON_GetObjectItemCaseSensitive(j, "buttons"), button_names, 5,
                      &d.button_map, path, "buttons", "L, M, R, C, AUX", err, errlen) ||
            parse_map(cJSON_GetObjectItemCaseSensitive(j, "axes"), axis_names, 4, &d.axis_map,
                      path, "axes", "X, Y, Z, W", err, errlen))
            return NULL;
        return input_vrpn_open(&d, err, errlen);
    }
    if (strcmp(type, "desk") == 0) {
        input_desk_desc d = {.name = name, .width = get_int(j, "width", 0),
                             .height = get_int(j, "height", 0)};
        return input_desk_open(&d, err, errlen);
    }
    if (strcmp(type, "usb") == 0) {
        const cJSON *rc = cJSON_GetObjectItemCaseSensitive(j, "reconnect");
        input_usb_desc d = {.name = name, .retry_interval = cJSON_IsNumber(rc) ? rc->valuedouble : 0};
        if (parse_usb(j, path, index, &d, err, errlen))
            return NULL;
        return input_usb_open(&d);
    }
    if (strcmp(type, "playback") == 0) {
        const char *file = get_str(j, "file");
        if (!file) {
            snprintf(err, errlen, "input config %s: sources[%d] (playback) needs \"file\"", path,
                     index);
            return NULL;
        }
        char full[4096];
        resolve_path(path, file, full, sizeof full);
        const cJSON *rt = cJSON_GetObjectItemCaseSensitive(j, "realtime");
        const cJSON *lp = cJSON_GetObjectItemCaseSensitive(j, "loop");
        input_playback_desc d = {.name = name, .path = full, .realtime = cJSON_IsTrue(rt),
                                 .loop = cJSON_IsTrue(lp)};
        return input_playback_open(&d, err, errlen);
    }
    snprintf(err, errlen, "input config %s: sources[%d] has unknown type \"%s\" (dtrack, "
             "vrpn, usb, desk, playback)", path, index, type);
    return NULL;
}

input *input_open(const input_desc *desc, char *err, size_t errlen)
{
    if (!desc->path) {
        snprintf(err, errlen, "input: no input config or recording given");
        return NULL;
    }
    if (input_playback_is_recording(desc->path)) {
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
    char why[128];
    char *text = textfile_read(desc->path, NULL, why, sizeof why);
    if (!text) {
        snprintf(err, errlen, "input config %s: %s", desc->path, why);
        return NULL;
    }
    cJSON *root = cJSON_Parse(text);
    free(text);
    if (!root || !cJSON_IsObject(root)) {
        snprintf(err, errlen, "input config %s: not a JSON object nor a recording (first line "
                 "\"%s\")", desc->path, INPUT_PLAYBACK_MAGIC);
        cJSON_Delete(root);
        return NULL;
    }
    input_desc d = *desc;
    char rec[4096];
    const char *record = get_str(root, "record");
    if (!d.record_path && record) {
        const char *dir = desc->out_dir ? desc->out_dir : CLUSTER_DEFAULT_OUT;
        if (record[0] == '/')
            snprintf(rec, sizeof rec, "%s", record);
        else
            snprintf(rec, sizeof rec, "%s/%s", dir, record);
        d.record_path = rec;
    }
    const cJSON *sources = cJSON_GetObjectItemCaseSensitive(root, "sources");
    if (!cJSON_IsArray(sources) || cJSON_GetArraySize(sources) == 0) {
        snprintf(err, errlen, "input config %s: \"sources\" must be a non-empty array",
                 desc->path);
        cJSON_Delete(root);
        return NULL;
    }
    input *in = input_create(&d, err, errlen);
    if (!in) {
        cJSON_Delete(root);
        return NULL;
    }
    int i = 0;
    const cJSON *it;
    cJSON_ArrayForEach(it, sources) {
        input_source *s = open_source(it, desc->path, i++, err, errlen);
        if (!s || input_add_source(in, s, err, errlen)) {
            input_close(in);
            cJSON_Delete(root);
            return NULL;
        }
    }
    cJSON_Delete(root);
    return in;
}
