#include "cluster/cluster_config.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fnv1a.h"
#include "base/json_depth.h"
#include "base/json_keys.h"
#include "base/mat4.h"
#include "warp/mpcdi.h"
#include "warp/warp_mesh.h"
#include "base/textfile.h"
#include "frame/frame_view.h"
#include "frame/screen_fit.h"
#include "cluster/wire.h"

typedef struct parse_ctx {
    json_keys *keys; /* every member is read through it: the unknown ones are reported */
    const char *path;       /* NULL: not a file (a command line's JSON) */
    char *err;
    size_t errlen;
    int failed;
} parse_ctx;

static void fail(parse_ctx *c, const char *field, const char *fmt, ...)
{
    if (c->failed)
        return;
    c->failed = 1;
    char msg[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (c->path)
        snprintf(c->err, c->errlen, "cluster config %s: field %s: %s", c->path, field, msg);
    else
        snprintf(c->err, c->errlen, "%s: %s", field, msg);
}

static const char *const eyes_names[] = {"mono", "stereo", "left", "right"};
static const char *const output_names[] = {"window", "headless", "png"};
static const char *const stereo_names[] = {"quad", "side-by-side", "top-bottom", "window-per-eye", "anaglyph"};
static const char *const security_names[] = {"curve", "insecure"};

static int lookup(const char *s, const char *const *names, int n)
{
    for (int i = 0; i < n; i++)
        if (strcmp(s, names[i]) == 0)
            return i;
    return -1;
}

const char *cluster_eyes_name(cluster_eyes e) { return (unsigned)e < 4 ? eyes_names[e] : "?"; }
const char *cluster_output_name(cluster_output o) { return (unsigned)o < 3 ? output_names[o] : "?"; }
const char *cluster_stereo_name(cluster_stereo s) { return (unsigned)s < 5 ? stereo_names[s] : "?"; }
const char *cluster_security_name(cluster_security s) { return (unsigned)s < 2 ? security_names[s] : "?"; }
int cluster_output_parse(const char *s) { return lookup(s, output_names, 3); }
int cluster_stereo_parse(const char *s) { return lookup(s, stereo_names, 5); }

/* A required member absent from obj: what it must be, and the member that misspelt it. */
static void fail_missing(parse_ctx *c, const cJSON *obj, const char *key, const char *field,
                         const char *what)
{
    const char *near = json_keys_misspelt(obj, key);
    if (near)
        fail(c, field, "missing (%s; \"%s\" here is \"%s\" misspelt?)", what, near, key);
    else
        fail(c, field, "missing (%s)", what);
}

/* Each getter: absent -> default (or an error when required); wrong type -> error. */
static void get_string(parse_ctx *c, const cJSON *obj, const char *key, const char *field,
                       char *out, size_t cap, const char *def)
{
    const cJSON *v = json_keys_get(c->keys, obj, key);
    if (!v) {
        if (!def)
            fail_missing(c, obj, key, field, "a string is required");
        else
            snprintf(out, cap, "%s", def);
        return;
    }
    if (!cJSON_IsString(v) || !v->valuestring) {
        fail(c, field, "must be a string");
        return;
    }
    if (strlen(v->valuestring) >= cap) {
        fail(c, field, "longer than %zu characters", cap - 1);
        return;
    }
    snprintf(out, cap, "%s", v->valuestring);
}

static double get_number(parse_ctx *c, const cJSON *obj, const char *key, const char *field,
                         double def, int required, double lo, double hi)
{
    const cJSON *v = json_keys_get(c->keys, obj, key);
    if (!v) {
        if (required)
            fail_missing(c, obj, key, field, "a number is required");
        return def;
    }
    if (!cJSON_IsNumber(v) || !isfinite(v->valuedouble)) {
        fail(c, field, "must be a number");
        return def;
    }
    if (v->valuedouble < lo || v->valuedouble > hi) {
        fail(c, field, "%g is outside [%g, %g]", v->valuedouble, lo, hi);
        return def;
    }
    return v->valuedouble;
}

static int get_vector(parse_ctx *c, const cJSON *v, const char *field, float *out, int n,
                      double lo, double hi)
{
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != n) {
        fail(c, field, "must be an array of %d numbers", n);
        return -1;
    }
    for (int i = 0; i < n; i++) {
        const cJSON *e = cJSON_GetArrayItem(v, i);
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble) || e->valuedouble < lo || e->valuedouble > hi) {
            fail(c, field, "element %d must be a number in [%g, %g]", i, lo, hi);
            return -1;
        }
        out[i] = (float)e->valuedouble;
    }
    return 0;
}

static int get_enum(parse_ctx *c, const cJSON *obj, const char *key, const char *field,
                    const char *const *names, int n, int def)
{
    const cJSON *v = json_keys_get(c->keys, obj, key);
    if (!v)
        return def;
    int i = cJSON_IsString(v) ? lookup(v->valuestring, names, n) : -1;
    if (i < 0) {
        char list[160] = "";
        for (int k = 0; k < n; k++)
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? ", " : "", names[k]);
        fail(c, field, "must be one of: %s", list);
        return def;
    }
    return i;
}

static void identity(float m[16])
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = m[15] = 1;
}

/* {"translation", "rotation_deg", "scale"} at field (absent: identity). */
static void parse_transform(parse_ctx *c, const cJSON *t, const char *field, float m[16])
{
    identity(m);
    if (!t)
        return;
    char f[96];
    if (!cJSON_IsObject(t)) {
        fail(c, field, "must be an object with translation, rotation_deg, scale");
        return;
    }
    float tr[3] = {0, 0, 0}, rot[3] = {0, 0, 0};
    const cJSON *v;
    snprintf(f, sizeof f, "%s.translation", field);
    if ((v = json_keys_get(c->keys, t, "translation")))
        get_vector(c, v, f, tr, 3, -1e4, 1e4);
    snprintf(f, sizeof f, "%s.rotation_deg", field);
    if ((v = json_keys_get(c->keys, t, "rotation_deg")))
        get_vector(c, v, f, rot, 3, -360, 360);
    snprintf(f, sizeof f, "%s.scale", field);
    float scale = (float)get_number(c, t, "scale", f, 1, 0, 1e-6, 1e3);
    mat4_from_trs_deg(tr, rot, scale, m);
}

static void parse_observer(parse_ctx *c, const cJSON *o, cluster_observer *obs)
{
    obs->eye_separation = FRAME_VIEW_EYE_SEPARATION;
    obs->home[1] = 1.7f;
    identity(obs->tracker_to_cave);
    if (!o)
        return;
    if (!cJSON_IsObject(o)) {
        fail(c, "observer", "must be an object");
        return;
    }
    obs->eye_separation = (float)get_number(c, o, "eye_separation", "observer.eye_separation", FRAME_VIEW_EYE_SEPARATION, 0, 0, 0.2);
    const cJSON *h = json_keys_get(c->keys, o, "head_to_eye");
    if (h)
        get_vector(c, h, "observer.head_to_eye", obs->head_to_eye, 3, -1, 1);
    const cJSON *home = json_keys_get(c->keys, o, "home");
    if (home)
        get_vector(c, home, "observer.home", obs->home, 3, -1e4, 1e4);
    parse_transform(c, json_keys_get(c->keys, o, "tracker_to_cave"), "observer.tracker_to_cave",
                    obs->tracker_to_cave);
}

/* "scene_transform" (scene/scene_transform.h): checked here, once, for the file and for
 * --scene-transform alike; every program applies it through scene_load_with(). */
static void parse_scene_transform(parse_ctx *c, const cJSON *o, scene_transform *t)
{
    static const char *const keys[] = {"scale", "up", "anchor", "fit", "rotation_deg", "translation"};
    memset(t, 0, sizeof *t);
    if (!cJSON_IsObject(o)) {
        fail(c, "scene_transform", "must be an object with scale, up, anchor, fit, rotation_deg, translation");
        return;
    }
    for (const cJSON *e = o->child; e; e = e->next)
        if (lookup(e->string, keys, 6) < 0) {
            char field[96];
            snprintf(field, sizeof field, "scene_transform.%.60s", e->string);
            fail(c, field, "unknown (scale, up, anchor, fit, rotation_deg or translation)");
            return;
        }
    t->scale = (float)get_number(c, o, "scale", "scene_transform.scale", 0, 0, SCENE_TRANSFORM_SCALE_MIN,
                                 SCENE_TRANSFORM_SCALE_MAX);
    t->up = (scene_up)get_enum(c, o, "up", "scene_transform.up", scene_up_names, SCENE_UP_COUNT, SCENE_UP_Y);
    t->anchor = (scene_anchor)get_enum(c, o, "anchor", "scene_transform.anchor", scene_anchor_names,
                                       SCENE_ANCHOR_COUNT, SCENE_ANCHOR_AUTO);
    const cJSON *v = json_keys_get(c->keys, o, "fit");
    if (v && !cJSON_IsBool(v))
        fail(c, "scene_transform.fit", "must be true or false");
    t->fit = v && cJSON_IsTrue(v);
    if ((v = json_keys_get(c->keys, o, "rotation_deg")))
        get_vector(c, v, "scene_transform.rotation_deg", t->rotation_deg, 3, -360, 360);
    if ((v = json_keys_get(c->keys, o, "translation")))
        get_vector(c, v, "scene_transform.translation", t->translation, 3, -SCENE_TRANSFORM_TRANSLATION_MAX,
                   SCENE_TRANSFORM_TRANSLATION_MAX);
    if (!c->failed && t->fit &&
        (json_keys_get(c->keys, o, "scale") || json_keys_get(c->keys, o, "anchor")))
        fail(c, "scene_transform.fit", "chooses the scale and the anchor: give fit, or scale and anchor");
}

int cluster_scene_transform_parse(const char *json, scene_transform *out, char *err, size_t errlen)
{
    parse_ctx c = {.err = err, .errlen = errlen};
    if (json_depth_check(json, strlen(json), err, errlen) != 0)
        return -1;
    cJSON *root = cJSON_Parse(json);
    if (!root) {
        snprintf(err, errlen, "not valid JSON; give one such as '{\"up\": \"z\", \"scale\": 0.01}'");
        return -1;
    }
    c.keys = json_keys_create();
    parse_scene_transform(&c, root, out);
    json_keys_destroy(c.keys);
    cJSON_Delete(root);
    return c.failed ? -1 : 0;
}

const char *cluster_scene_transform_option(const char *json, scene_transform *out)
{
    static char reason[400];
    char why[300];
    if (cluster_scene_transform_parse(json, out, why, sizeof why) == 0)
        return NULL;
    snprintf(reason, sizeof reason, "a scene_transform object (%s)", why);
    return reason;
}

void cluster_config_scene_desc(const cluster_config *c, scene_load_desc *out)
{
    memset(out, 0, sizeof *out);
    out->transform = c->has_scene_transform ? &c->scene_transform : NULL;
    out->allow_outside_paths = c->scene_outside_paths;
    memcpy(out->stage.home, c->observer.home, sizeof out->stage.home);
    for (int i = 0; i < c->screen_count; i++) {
        const cluster_screen *sc = &c->screens[i];
        for (int k = 0; k < 4; k++)
            for (int a = 0; a < 3; a++) {
                float x = k == 0 ? sc->bottom_left[a] : k == 1 ? sc->bottom_right[a] : k == 2 ? sc->top_left[a]
                          : sc->bottom_right[a] + sc->top_left[a] - sc->bottom_left[a];
                out->stage.box_min[a] = i == 0 && k == 0 ? x : fminf(out->stage.box_min[a], x);
                out->stage.box_max[a] = i == 0 && k == 0 ? x : fmaxf(out->stage.box_max[a], x);
            }
    }
}

/* A path the config names (key folder, warp file): relative ones are relative to the config
 * file's folder, like a scene's files to its glTF. */
static void beside_config(parse_ctx *c, const char *path, const char *field, char out[CLUSTER_TEXT_MAX])
{
    const char *slash = strrchr(c->path, '/');
    int folder = slash && path[0] != '/' ? (int)(slash - c->path) + 1 : 0;
    if (snprintf(out, CLUSTER_TEXT_MAX, "%.*s%s", folder, c->path, path) >= CLUSTER_TEXT_MAX)
        fail(c, field, "the path beside the config is longer than %d characters", CLUSTER_TEXT_MAX - 1);
}

/* The default key folder is NAME.keys beside the config (NAME: file name less .json). */
static void parse_security(parse_ctx *c, const cJSON *o, cluster_config *cfg)
{
    if (o && !cJSON_IsObject(o)) {
        fail(c, "security", "must be an object ({\"mode\": \"curve\", \"keys\": DIR} or {\"mode\": \"insecure\"})");
        return;
    }
    cfg->security = (cluster_security)get_enum(c, o, "mode", "security.mode", security_names, 2,
                                               CLUSTER_SECURITY_CURVE);
    const char *slash = strrchr(c->path, '/');
    int folder = slash ? (int)(slash - c->path) + 1 : 0;
    const char *base = c->path + folder;
    int stem = (int)strlen(base);
    if (stem > 5 && strcmp(base + stem - 5, ".json") == 0)
        stem -= 5;
    char keys[CLUSTER_TEXT_MAX], def[CLUSTER_TEXT_MAX];
    snprintf(def, sizeof def, "%.*s.keys", stem, base);
    get_string(c, o, "keys", "security.keys", keys, sizeof keys, def);
    if (!c->failed)
        beside_config(c, keys, "security.keys", cfg->keys_dir);
}

/* Entry index of a list of named objects ("screens", "nodes"): an object whose name is
 * valid and differs from the earlier entries' (their names stride bytes apart from
 * earlier). Leaves "list[index].name" in field. 0, or -1 after fail(). */
static int parse_entry_name(parse_ctx *c, const cJSON *obj, const char *list, int index,
                            const char *earlier, size_t stride, char *name, size_t size,
                            char field[96])
{
    snprintf(field, 96, "%s[%d]", list, index);
    if (!cJSON_IsObject(obj)) {
        fail(c, field, "must be an object");
        return -1;
    }
    snprintf(field, 96, "%s[%d].name", list, index);
    get_string(c, obj, "name", field, name, size, NULL);
    if (c->failed)
        return -1;
    if (!wire_name_valid(name)) {
        fail(c, field, "'%s' must be 1..%d characters of A-Z a-z 0-9 _ . -", name, WIRE_NAME_MAX);
        return -1;
    }
    for (int i = 0; i < index; i++)
        if (strcmp(earlier + (size_t)i * stride, name) == 0) {
            fail(c, field, "'%s' is used twice", name);
            return -1;
        }
    return 0;
}

static void parse_screen(parse_ctx *c, const cJSON *s, int index, cluster_config *cfg)
{
    char field[96];
    cluster_screen *scr = &cfg->screens[index];
    if (parse_entry_name(c, s, "screens", index, cfg->screens[0].name, sizeof cfg->screens[0],
                         scr->name, sizeof scr->name, field) != 0)
        return;
    static const char *const corner[3] = {"bottom_left", "bottom_right", "top_left"};
    float *dst[3] = {scr->bottom_left, scr->bottom_right, scr->top_left};
    for (int k = 0; k < 3; k++) {
        snprintf(field, sizeof field, "screens[%d].%s", index, corner[k]);
        const cJSON *v = json_keys_get(c->keys, s, corner[k]);
        if (!v) {
            fail_missing(c, s, corner[k], field, "three corners in CAVE space are required");
            return;
        }
        if (get_vector(c, v, field, dst[k], 3, -1e4, 1e4))
            return;
    }
    /* Measured corners: the nearest rectangle, within the tolerance. */
    float top_right[3];
    const cJSON *tr = json_keys_get(c->keys, s, "top_right");
    snprintf(field, sizeof field, "screens[%d].top_right", index);
    if (tr && get_vector(c, tr, field, top_right, 3, -1e4, 1e4))
        return;
    snprintf(field, sizeof field, "screens[%d]", index);
    screen_fit fit;
    if (screen_fit_rectangle(scr->bottom_left, scr->bottom_right, scr->top_left, tr ? top_right : NULL, &fit) != 0 ||
        fit.deviation * 1000 > cfg->corner_tolerance_mm) {
        if (fit.deviation * 1000 > cfg->corner_tolerance_mm)
            fail(c, field, "'%s' corners are %.1f mm from the nearest rectangle, more than corner_tolerance_mm "
                 "%g: measure them again (docs/calibration.md)", scr->name, fit.deviation * 1000,
                 cfg->corner_tolerance_mm);
        else
            fail(c, field, "'%s' corners span no rectangle (zero width or height, or on one line)", scr->name);
        return;
    }
    scr->fit_mm = (float)(fit.deviation * 1000);
    /* A rectangle as given (to float precision) stays bit for bit what the file says. */
    if (fit.deviation > SCREEN_EXACT_M) {
        memcpy(scr->bottom_left, fit.bottom_left, sizeof fit.bottom_left);
        memcpy(scr->bottom_right, fit.bottom_right, sizeof fit.bottom_right);
        memcpy(scr->top_left, fit.top_left, sizeof fit.top_left);
    }
    scr->overview[0] = scr->overview[1] = -1;
    const cJSON *o = json_keys_get(c->keys, s, "overview");
    if (o) {
        float xy[2];
        snprintf(field, sizeof field, "screens[%d].overview", index);
        if (get_vector(c, o, field, xy, 2, 0, 65536) == 0) {
            scr->overview[0] = (int)xy[0];
            scr->overview[1] = (int)xy[1];
        }
    }
}

static int parse_resolution(parse_ctx *c, const cJSON *v, const char *field, int *w, int *h)
{
    float r[2];
    if (get_vector(c, v, field, r, 2, 1, 16384))
        return -1;
    if (r[0] != floorf(r[0]) || r[1] != floorf(r[1])) {
        fail(c, field, "must be whole pixels");
        return -1;
    }
    *w = (int)r[0];
    *h = (int)r[1];
    return 0;
}

/* ---- display hardware (cluster_window, cluster_warp): the keys in one place ------------- */

/* One monitor: an index or an output's name. */
static void parse_monitor(parse_ctx *c, const cJSON *v, const char *field, int *index, char *name)
{
    if (cJSON_IsString(v) && v->valuestring[0] && strlen(v->valuestring) <= CLUSTER_NAME_MAX)
        snprintf(name, CLUSTER_NAME_MAX + 1, "%s", v->valuestring);
    else if (cJSON_IsNumber(v) && v->valuedouble >= 0 && v->valuedouble <= 64 && v->valuedouble == floor(v->valuedouble))
        *index = (int)v->valuedouble;
    else
        fail(c, field, "must be a monitor index 0..64 or an output's name of 1..%d characters (as xrandr "
             "lists them, e.g. \"DP-1\")", CLUSTER_NAME_MAX);
}

/* A flag or a whole number in lo..hi ("vsync": true, false or an interval). */
static int get_flag_or_int(parse_ctx *c, const cJSON *obj, const char *key, const char *field, int def,
                           int lo, int hi)
{
    const cJSON *v = json_keys_get(c->keys, obj, key);
    if (!v)
        return def;
    if (cJSON_IsBool(v))
        return cJSON_IsTrue(v);
    if (!cJSON_IsNumber(v) || v->valuedouble != floor(v->valuedouble) || v->valuedouble < lo || v->valuedouble > hi) {
        fail(c, field, "must be true, false or a whole number in %d..%d", lo, hi);
        return def;
    }
    return (int)v->valuedouble;
}

void cluster_window_default(cluster_window *w)
{
    *w = (cluster_window){.monitor = {0, 1}, .swap_interval = 1};
}

static void parse_window(parse_ctx *c, const cJSON *n, int index, cluster_window *w)
{
    char field[96];
    cluster_window_default(w);
    const cJSON *m = json_keys_get(c->keys, n, "monitor");
    snprintf(field, sizeof field, "nodes[%d].monitor", index);
    if (cJSON_IsArray(m) && cJSON_GetArraySize(m) == 2) {
        for (int e = 0; e < 2; e++)
            parse_monitor(c, cJSON_GetArrayItem(m, e), field, &w->monitor[e], w->monitor_name[e]);
    } else if (m) {
        parse_monitor(c, m, field, &w->monitor[0], w->monitor_name[0]);
        w->monitor[1] = w->monitor[0] + 1; /* the right eye's window: the next monitor */
    }
    const cJSON *fs = json_keys_get(c->keys, n, "fullscreen");
    snprintf(field, sizeof field, "nodes[%d].fullscreen", index);
    if (fs && !cJSON_IsBool(fs))
        fail(c, field, "must be true or false");
    w->fullscreen = fs && cJSON_IsTrue(fs);
    float xy[2];
    const cJSON *v = json_keys_get(c->keys, n, "position");
    snprintf(field, sizeof field, "nodes[%d].position", index);
    if (v && get_vector(c, v, field, xy, 2, -65536, 65536) == 0) {
        w->position[0] = (int)xy[0];
        w->position[1] = (int)xy[1];
        w->have_position = 1;
    }
    v = json_keys_get(c->keys, n, "size");
    snprintf(field, sizeof field, "nodes[%d].size", index);
    if (v)
        parse_resolution(c, v, field, &w->size[0], &w->size[1]);
    snprintf(field, sizeof field, "nodes[%d].vsync", index);
    w->swap_interval = get_flag_or_int(c, n, "vsync", field, 1, 0, 8);
    snprintf(field, sizeof field, "nodes[%d].swap_group", index);
    w->swap_group = (int)get_number(c, n, "swap_group", field, 0, 0, 0, 1 << 20);
    snprintf(field, sizeof field, "nodes[%d].swap_barrier", index);
    w->swap_barrier = (int)get_number(c, n, "swap_barrier", field, 0, 0, 0, 1 << 20);
    if (!c->failed && w->swap_barrier && !w->swap_group)
        fail(c, field, "binds a swap group to a barrier: give swap_group too");
}

/* A screen's projector: {"mpcdi": FILE, "region": ID, "to_cave": {...}} or {"mesh": FILE}. */
static int parse_warp(parse_ctx *c, const cJSON *w, const char *field, cluster_warp *out)
{
    identity(out->to_cave);
    if (!w)
        return 0;
    const cJSON *mpcdi = cJSON_IsObject(w) ? json_keys_get(c->keys, w, "mpcdi") : NULL;
    const cJSON *mesh = cJSON_IsObject(w) ? json_keys_get(c->keys, w, "mesh") : NULL;
    if (!mpcdi == !mesh || !cJSON_IsString(mpcdi ? mpcdi : mesh) || !(mpcdi ? mpcdi : mesh)->valuestring[0]) {
        fail(c, field, "must be {\"mpcdi\": FILE, \"region\": ID} or {\"mesh\": FILE}");
        return -1;
    }
    out->kind = mpcdi ? CLUSTER_WARP_MPCDI : CLUSTER_WARP_MESH;
    char f[128];
    snprintf(f, sizeof f, "%s.%s", field, mpcdi ? "mpcdi" : "mesh");
    beside_config(c, (mpcdi ? mpcdi : mesh)->valuestring, f, out->path);
    snprintf(f, sizeof f, "%s.region", field);
    get_string(c, w, "region", f, out->region, sizeof out->region, "");
    snprintf(f, sizeof f, "%s.to_cave", field);
    parse_transform(c, json_keys_get(c->keys, w, "to_cave"), f, out->to_cave);
    if (!c->failed && mesh && (out->region[0] || json_keys_get(c->keys, w, "to_cave")))
        fail(c, field, "region and to_cave belong to an MPCDI file, not a warp mesh");
    return c->failed ? -1 : 0;
}

/* nodes[index].screens[i]: a screen name, or {"name", "resolution", "warp"}; dw x dh is
 * the node's resolution. -1 after a failure. */
static int parse_node_screen(parse_ctx *c, const cJSON *e, int index, int i, int dw, int dh,
                             cluster_config *cfg)
{
    char field[96];
    cluster_node_screen *ns = &cfg->nodes[index].screens[i];
    const char *sname = NULL;
    ns->width = dw;
    ns->height = dh;
    snprintf(field, sizeof field, "nodes[%d].screens[%d]", index, i);
    if (cJSON_IsString(e)) {
        sname = e->valuestring;
    } else if (cJSON_IsObject(e)) {
        const cJSON *nm = json_keys_get(c->keys, e, "name");
        sname = cJSON_IsString(nm) ? nm->valuestring : NULL;
        const cJSON *r = json_keys_get(c->keys, e, "resolution");
        snprintf(field, sizeof field, "nodes[%d].screens[%d].resolution", index, i);
        if (r && parse_resolution(c, r, field, &ns->width, &ns->height))
            return -1;
        snprintf(field, sizeof field, "nodes[%d].screens[%d].warp", index, i);
        if (parse_warp(c, json_keys_get(c->keys, e, "warp"), field, &ns->warp))
            return -1;
        snprintf(field, sizeof field, "nodes[%d].screens[%d]", index, i);
    }
    if (!sname) {
        fail(c, field, "must be a screen name or {\"name\", \"resolution\"}");
        return -1;
    }
    ns->screen = cluster_config_find_screen(cfg, sname);
    if (ns->screen < 0) {
        fail(c, field, "unknown screen '%s' (define it under \"screens\")", sname);
        return -1;
    }
    if (ns->width <= 0) {
        fail(c, field, "no resolution (give nodes[%d].resolution or one per screen)", index);
        return -1;
    }
    return 0;
}

/* eyes, output, stereo, window, and the launch texts (exe, workdir, config, display). */
static void parse_node_options(parse_ctx *c, const cJSON *n, int index, cluster_node *node)
{
    char field[96];
    snprintf(field, sizeof field, "nodes[%d].eyes", index);
    node->eyes = (cluster_eyes)get_enum(c, n, "eyes", field, eyes_names, 4, CLUSTER_EYES_MONO);
    snprintf(field, sizeof field, "nodes[%d].output", index);
    node->output = (cluster_output)get_enum(c, n, "output", field, output_names, 3, CLUSTER_OUTPUT_WINDOW);
    snprintf(field, sizeof field, "nodes[%d].stereo", index);
    node->stereo = (cluster_stereo)get_enum(c, n, "stereo", field, stereo_names, 5, CLUSTER_STEREO_SIDE_BY_SIDE);
    parse_window(c, n, index, &node->window);
    static const struct { const char *key; size_t offset; const char *def; } texts[] = {
        {"exe", offsetof(cluster_node, exe), ""},
        {"workdir", offsetof(cluster_node, workdir), ""},
        {"config", offsetof(cluster_node, config), ""},
        {"display", offsetof(cluster_node, display), ":0"},
    };
    for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++) {
        snprintf(field, sizeof field, "nodes[%d].%s", index, texts[i].key);
        get_string(c, n, texts[i].key, field, (char *)node + texts[i].offset, CLUSTER_TEXT_MAX, texts[i].def);
    }
}

static void parse_node(parse_ctx *c, const cJSON *n, int index, cluster_config *cfg)
{
    char field[96];
    cluster_node *node = &cfg->nodes[index];
    if (parse_entry_name(c, n, "nodes", index, cfg->nodes[0].name, sizeof cfg->nodes[0],
                         node->name, sizeof node->name, field) != 0)
        return;
    if (strcmp(node->name, "master") == 0) {
        fail(c, field, "'master' is the master's own name (its key file is master.key): pick another");
        return;
    }
    snprintf(field, sizeof field, "nodes[%d].host", index);
    get_string(c, n, "host", field, node->host, sizeof node->host, "localhost");

    int dw = 0, dh = 0;
    const cJSON *res = json_keys_get(c->keys, n, "resolution");
    snprintf(field, sizeof field, "nodes[%d].resolution", index);
    if (res && parse_resolution(c, res, field, &dw, &dh))
        return;

    const cJSON *screens = json_keys_get(c->keys, n, "screens");
    snprintf(field, sizeof field, "nodes[%d].screens", index);
    if (!screens) {
        fail_missing(c, n, "screens", field, "an array of screen names is required");
        return;
    }
    if (!cJSON_IsArray(screens) || cJSON_GetArraySize(screens) < 1 ||
        cJSON_GetArraySize(screens) > CLUSTER_NODE_MAX_SCREENS) {
        fail(c, field, "must be an array of 1..%d screen names", CLUSTER_NODE_MAX_SCREENS);
        return;
    }
    node->screen_count = cJSON_GetArraySize(screens);
    for (int i = 0; i < node->screen_count; i++)
        if (parse_node_screen(c, cJSON_GetArrayItem(screens, i), index, i, dw, dh, cfg) != 0)
            return;
    parse_node_options(c, n, index, node);
}

/* "settings": {"NAME": value, ...}: kept as text; the programs that know the names check
 * them (cavelight-master at start and with --check, every node when it builds its first
 * frame), so none of them is an unknown key here. */
static void parse_settings(parse_ctx *c, const cJSON *o, cluster_config *cfg)
{
    if (!o || c->failed)
        return;
    if (!cJSON_IsObject(o)) {
        fail(c, "settings", "must be an object of option names and values ({\"gi\": \"vpl\", ...})");
        return;
    }
    const cJSON *v;
    cJSON_ArrayForEach(v, o)
    {
        json_keys_get(c->keys, o, v->string); /* its name is the master's to check */
        char field[CLUSTER_NAME_MAX + 16];
        snprintf(field, sizeof field, "settings.%.*s", CLUSTER_NAME_MAX, v->string);
        if (cfg->setting_count == CLUSTER_MAX_SETTINGS) {
            fail(c, field, "more than %d settings", (int)CLUSTER_MAX_SETTINGS);
            return;
        }
        cluster_setting *st = &cfg->settings[cfg->setting_count];
        if (strlen(v->string) > CLUSTER_NAME_MAX) {
            fail(c, "settings", "a name longer than %d characters", (int)CLUSTER_NAME_MAX);
            return;
        }
        snprintf(st->name, sizeof st->name, "%s", v->string);
        if (cJSON_IsString(v) && strlen(v->valuestring) < sizeof st->value)
            snprintf(st->value, sizeof st->value, "%s", v->valuestring);
        else if (cJSON_IsNumber(v))
            snprintf(st->value, sizeof st->value, "%.9g", v->valuedouble);
        else {
            fail(c, field, "must be a number or a short string, as the option takes it");
            return;
        }
        cfg->setting_count++;
    }
}

/* An unknown key: one line kept for the program to warn with (or refuse, --strict). */
static void note_unknown(void *user, const char *field, const char *key, const char *nearest, const char *valid)
{
    cluster_config *cfg = user;
    if (cfg->unknown_key_count < CLUSTER_MAX_UNKNOWN_KEYS) {
        char words[CLUSTER_TEXT_MAX], line[CLUSTER_LINE_MAX];
        json_keys_describe(key, nearest, valid, words, sizeof words);
        snprintf(line, sizeof line, "cluster config %.160s: field %.100s: %.200s", cfg->path, field, words);
        memcpy(cfg->unknown_keys[cfg->unknown_key_count], line, sizeof line);
    }
    cfg->unknown_key_count++;
}

/* A file cJSON could not parse: the line it stopped at. */
static void syntax_error(const char *text, size_t len, const char *end, const char *path, char *err,
                         size_t errlen)
{
    size_t off = end ? (size_t)(end - text) : 0;
    int line = 1;
    for (size_t i = 0; i < off && i < len; i++)
        line += text[i] == '\n';
    snprintf(err, errlen, "cluster config %s: not valid JSON near line %d: fix the syntax", path, line);
}

/* name, scene, app, launch and scene_transform. */
static void parse_top(parse_ctx *c, const cJSON *root, cluster_config *cfg)
{
    get_string(c, root, "name", "name", cfg->name, sizeof cfg->name, "");
    get_string(c, root, "scene", "scene", cfg->scene, sizeof cfg->scene, "");
    get_string(c, root, "app", "app", cfg->app, sizeof cfg->app, "");
    get_string(c, root, "launch", "launch", cfg->launch, sizeof cfg->launch, "ssh -n {host} {command}");
    const cJSON *st = json_keys_get(c->keys, root, "scene_transform");
    cfg->has_scene_transform = st != NULL;
    if (st)
        parse_scene_transform(c, st, &cfg->scene_transform);
}

/* -1 when "master" is missing: nothing after it is read. */
static int parse_master(parse_ctx *c, const cJSON *root, cluster_config *cfg)
{
    const cJSON *m = json_keys_get(c->keys, root, "master");
    if (!m)
        fail_missing(c, root, "master", "master",
                     "an object is required: {\"bind\": ..., \"connect\": ...}");
    if (!cJSON_IsObject(m)) {
        fail(c, "master", "missing or not an object (give {\"bind\": ..., \"connect\": ...})");
        return -1;
    }
    get_string(c, m, "bind", "master.bind", cfg->master_bind, sizeof cfg->master_bind, NULL);
    get_string(c, m, "connect", "master.connect", cfg->master_connect, sizeof cfg->master_connect, NULL);
    if (!c->failed && strncmp(cfg->master_bind, "tcp://", 6) && strncmp(cfg->master_bind, "ipc://", 6))
        fail(c, "master.bind", "'%s' must start with tcp:// or ipc://", cfg->master_bind);
    if (!c->failed && strncmp(cfg->master_connect, "tcp://", 6) && strncmp(cfg->master_connect, "ipc://", 6))
        fail(c, "master.connect", "'%s' must start with tcp:// or ipc://", cfg->master_connect);
    return 0;
}

static void parse_timeouts(parse_ctx *c, const cJSON *t, cluster_config *cfg)
{
    if (t && !cJSON_IsObject(t))
        fail(c, "timeouts", "must be an object");
    cfg->barrier_timeout_ms = (int)get_number(c, t, "barrier_ms", "timeouts.barrier_ms", 2000, 0, 10, 600000);
    cfg->heartbeat_ms = (int)get_number(c, t, "heartbeat_ms", "timeouts.heartbeat_ms", 100, 0, 10, 60000);
    /* The master sends something every heartbeat_ms: a node that misses a few in a row
     * (MASTER_SILENT_BEATS) reports it lost, well under a second at the default. */
    enum { MASTER_SILENT_BEATS = 4 };
    cfg->master_timeout_ms = (int)get_number(c, t, "master_ms", "timeouts.master_ms",
                                             MASTER_SILENT_BEATS * cfg->heartbeat_ms, 0, 10, 600000);
    if (!c->failed && cfg->master_timeout_ms < 2 * cfg->heartbeat_ms)
        fail(c, "timeouts.master_ms", "%d is less than twice timeouts.heartbeat_ms (%d): nodes would lose "
             "a master that is only between heartbeats; leave master_ms out for %d x heartbeat_ms",
             cfg->master_timeout_ms, cfg->heartbeat_ms, (int)MASTER_SILENT_BEATS);
    cfg->stall_min_ms = (int)get_number(c, t, "stall_min_ms", "timeouts.stall_min_ms", 250, 0, 10, 600000);
    cfg->join_timeout_ms = (int)get_number(c, t, "join_ms", "timeouts.join_ms", 15000, 0, 100, 3600000);
}

/* screens[] then nodes[]; -1 when either is not an array of a valid length. */
static int parse_screens_and_nodes(parse_ctx *c, const cJSON *root, cluster_config *cfg)
{
    const cJSON *screens = json_keys_get(c->keys, root, "screens");
    if (!screens)
        fail_missing(c, root, "screens", "screens", "an array of screens is required");
    if (!c->failed && (!cJSON_IsArray(screens) || cJSON_GetArraySize(screens) < 1 ||
                       cJSON_GetArraySize(screens) > CLUSTER_MAX_SCREENS)) {
        fail(c, "screens", "must be an array of 1..%d screens", CLUSTER_MAX_SCREENS);
        return -1;
    }
    for (int i = 0; !c->failed && i < cJSON_GetArraySize(screens); i++) {
        parse_screen(c, cJSON_GetArrayItem(screens, i), i, cfg);
        cfg->screen_count = i + 1;
    }
    const cJSON *nodes = json_keys_get(c->keys, root, "nodes");
    if (!nodes)
        fail_missing(c, root, "nodes", "nodes", "an array of nodes is required");
    if (!c->failed && (!cJSON_IsArray(nodes) || cJSON_GetArraySize(nodes) < 1 ||
                       cJSON_GetArraySize(nodes) > CLUSTER_MAX_NODES)) {
        fail(c, "nodes", "must be an array of 1..%d nodes", CLUSTER_MAX_NODES);
        return -1;
    }
    for (int i = 0; !c->failed && i < cJSON_GetArraySize(nodes); i++) {
        parse_node(c, cJSON_GetArrayItem(nodes, i), i, cfg);
        cfg->node_count = i + 1;
    }
    return 0;
}

int cluster_config_parse(const char *text, size_t len, const char *path, cluster_config *cfg,
                         char *err, size_t errlen)
{
    parse_ctx c = {.keys = json_keys_create(), .path = path, .err = err, .errlen = errlen};
    memset(cfg, 0, sizeof *cfg);
    snprintf(cfg->path, sizeof cfg->path, "%s", path);
    cfg->hash = fnv1a64(FNV1A64_CLUSTER_SEED, text, len);

    char deep[120];
    if (json_depth_check(text, len, deep, sizeof deep) != 0) {
        snprintf(err, errlen, "cluster config %s: %s", path, deep);
        json_keys_destroy(c.keys);
        return -1;
    }
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(text, len, &end, 0);
    if (!root) {
        syntax_error(text, len, end, path, err, errlen);
        json_keys_destroy(c.keys);
        return -1;
    }
    if (!cJSON_IsObject(root)) {
        fail(&c, "(top level)", "must be a JSON object");
        goto done;
    }
    parse_top(&c, root, cfg);
    if (parse_master(&c, root, cfg) != 0)
        goto done;
    parse_timeouts(&c, json_keys_get(c.keys, root, "timeouts"), cfg);
    cfg->corner_tolerance_mm = get_number(&c, root, "corner_tolerance_mm", "corner_tolerance_mm", 20, 0, 0, 1000);
    cfg->gi_memory_mb = get_number(&c, json_keys_get(c.keys, root, "limits"), "gi_memory_mb", "limits.gi_memory_mb",
                                   CLUSTER_GI_MEMORY_MB, 0, 16, 1 << 20);
    parse_observer(&c, json_keys_get(c.keys, root, "observer"), &cfg->observer);
    parse_security(&c, json_keys_get(c.keys, root, "security"), cfg);
    parse_settings(&c, json_keys_get(c.keys, root, "settings"), cfg);
    if (parse_screens_and_nodes(&c, root, cfg) != 0)
        goto done;
    if (!c.failed)
        json_keys_unknown(c.keys, root, note_unknown, cfg);
done:
    json_keys_destroy(c.keys);
    cJSON_Delete(root);
    return c.failed ? -1 : 0;
}

int cluster_config_load(const char *path, cluster_config *out, char *err, size_t errlen)
{
    enum { MAX_FILE = 1 << 20 };
    char why[128];
    size_t len = 0;
    char *text = textfile_read_max(path, MAX_FILE - 1, &len, why, sizeof why);
    if (!text) {
        snprintf(err, errlen, "cluster config %s: %s", path, why);
        return -1;
    }
    int rc = cluster_config_parse(text, len, path, out, err, errlen);
    free(text);
    return rc;
}

int cluster_config_find_node(const cluster_config *c, const char *name)
{
    for (int i = 0; i < c->node_count; i++)
        if (strcmp(c->nodes[i].name, name) == 0)
            return i;
    return -1;
}

int cluster_config_find_screen(const cluster_config *c, const char *name)
{
    for (int i = 0; i < c->screen_count; i++)
        if (strcmp(c->screens[i].name, name) == 0)
            return i;
    return -1;
}

int cluster_warp_load(const cluster_warp *w, warp_map *out, char *err, size_t errlen)
{
    if (w->kind == CLUSTER_WARP_MPCDI)
        return mpcdi_load(w->path, w->region, out, err, errlen);
    if (w->kind == CLUSTER_WARP_MESH)
        return warp_mesh_load(w->path, out, err, errlen);
    return 0;
}
