/* app_host: the loaded application and the operations libcavelight forwards (app_host.h,
 * app_abi.h). */
#include "app/app_host.h"

#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/ratelog.h"
#include "base/xalloc.h"

typedef enum app_phase { PHASE_NONE = 0, PHASE_INIT, PHASE_UPDATE, PHASE_FRAME, PHASE_DRAW } app_phase;

typedef struct app_key {
    char name[PARAMS_NAME_MAX];  /* as the application named it (the store's is "app." + it) */
    app_key_kind kind;
    int n;                       /* floats of a vector */
    size_t capacity;             /* a string's or blob's */
    union { double d; float f[16]; uint8_t b[PARAMS_VALUE_MAX]; } initial, scratch;
    int store_key;               /* -1 until app_host_add_keys() */
    char *text;                  /* a string's NUL-terminated copy (capacity + 1) */
} app_key;

struct app_host {
    app_host_desc desc;
    char path[512], name[64], who[96];
    void *so;
    cavelight_app app;
    app_phase phase;
    app_key keys[APP_MAX_KEYS];
    int key_count, key_refused;
    size_t bytes_registered;
    const params_store *store;   /* read */
    params_store *writable;      /* set (the master's), or NULL */
    scene_pose *pose;
    float (*bounds)[6];          /* per object, its own triangles at rest */
    float models[SCENE_MAX_OBJECTS][16];
    uint8_t shown[SCENE_MAX_OBJECTS];
    char error[400];
    char refused_key[400];       /* init's first refused registration */
    ratelog log;
};

/* One line on stderr (rate limited) and in cavelight_last_error(). */
static int refusal(app_host *h, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(h->error, sizeof h->error, fmt, ap);
    va_end(ap);
    uint64_t skipped = 0;
    if (ratelog_event(&h->log, clock_now_ms(), &skipped))
        fprintf(stderr, "%s: app %s: %s%s\n", h->who, h->name, h->error,
                skipped ? " (more such lines left out)" : "");
    /* Only a refused registration stops the session; another call in init (an object
     * query) only returns -1 to the application. */
    if (h->phase == PHASE_INIT && strncmp(h->error, "cavelight_key_", 14) == 0 && !h->key_refused) {
        h->key_refused = 1;
        snprintf(h->refused_key, sizeof h->refused_key, "%s", h->error);
    }
    return -1;
}

static void host_refuse(void *host, const char *what) { refusal(host, "%s", what); }
static const char *host_last_error(void *host) { return ((app_host *)host)->error; }

/* ---- keys ------------------------------------------------------------------------- */

static params_type key_type(const app_key *k)
{
    static const params_type vec[5] = {PARAMS_T_VEC2, PARAMS_T_VEC2, PARAMS_T_VEC2, PARAMS_T_VEC3, PARAMS_T_VEC4};
    switch (k->kind) {
    case APP_KEY_NUMBER: return PARAMS_T_F64;
    case APP_KEY_VECTOR: return vec[k->n];
    case APP_KEY_MATRIX: return PARAMS_T_MAT4;
    case APP_KEY_STRING: return PARAMS_T_STRING;
    default: return PARAMS_T_BLOB;
    }
}

static const char *kind_name(app_key_kind kind)
{
    static const char *const names[] = {"number", "vector", "matrix", "string", "blob"};
    return (unsigned)kind <= APP_KEY_BLOB ? names[kind] : "?";
}

static size_t fixed_size(const app_key *k)
{
    return k->kind == APP_KEY_NUMBER ? sizeof(double) : (size_t)k->n * sizeof(float);
}

static int all_finite(const app_key *k, const void *v)
{
    if (k->kind == APP_KEY_NUMBER) {
        double d;
        memcpy(&d, v, sizeof d);
        return isfinite(d) != 0;
    }
    for (int i = 0; i < k->n; i++) {
        float f;
        memcpy(&f, (const char *)v + 4 * i, 4);
        if (!isfinite(f))
            return 0;
    }
    return 1;
}

static int name_ok(const char *name)
{
    size_t n = strlen(name);
    for (size_t i = 0; i < n; i++)
        if (name[i] <= 0x20 || name[i] >= 0x7f)
            return 0;
    return n > 0 && n + 4 < PARAMS_NAME_MAX;
}

static int host_key_find(void *host, const char *name)
{
    app_host *h = host;
    for (int i = 0; i < h->key_count; i++)
        if (strcmp(h->keys[i].name, name) == 0)
            return i;
    return -1;
}

static int host_key_add(void *host, const char *name, app_key_kind kind, int n, size_t capacity,
                        const void *initial)
{
    app_host *h = host;
    const char *what = kind_name(kind);
    if (h->phase != PHASE_INIT)
        return refusal(h, "cavelight_key_%s(%.60s): keys are registered in init only", what, name);
    if (!name_ok(name))
        return refusal(h, "cavelight_key_%s(\"%.60s\"): a name is 1 to %d printable characters without "
                       "spaces", what, name, PARAMS_NAME_MAX - 5);
    if (host_key_find(h, name) >= 0)
        return refusal(h, "cavelight_key_%s(%s): registered twice", what, name);
    if (h->key_count >= APP_MAX_KEYS)
        return refusal(h, "cavelight_key_%s(%s): %d keys at most", what, name, APP_MAX_KEYS);
    int bytes = kind == APP_KEY_STRING || kind == APP_KEY_BLOB;
    if (bytes && (capacity < 1 || capacity > PARAMS_BYTES_KEY_MAX ||
                  capacity > PARAMS_BYTES_MAX - h->bytes_registered))
        return refusal(h, "cavelight_key_%s(%s): capacity %zu out of range (1 to %d bytes, %zu left of the "
                       "%d all strings and blobs share)", what, name, capacity, PARAMS_BYTES_KEY_MAX,
                       (size_t)PARAMS_BYTES_MAX - h->bytes_registered, PARAMS_BYTES_MAX);
    app_key *k = &h->keys[h->key_count];
    memset(k, 0, sizeof *k);
    snprintf(k->name, sizeof k->name, "%s", name);
    k->kind = kind;
    k->n = kind == APP_KEY_VECTOR ? n : kind == APP_KEY_MATRIX ? 16 : 1;
    k->capacity = bytes ? capacity : 0;
    k->store_key = -1;
    if (!bytes && initial) {
        memcpy(k->initial.b, initial, fixed_size(k));
        if (!all_finite(k, k->initial.b))
            return refusal(h, "cavelight_key_%s(%s): the initial value is not finite", what, name);
    }
    if (kind == APP_KEY_STRING)
        k->text = xcalloc(1, capacity + 1);
    h->bytes_registered += k->capacity;
    return h->key_count++;
}

/* The key if it is of the kind (and size) asked for; NULL after a refusal. call is
 * "set" or "get". */
static app_key *typed(app_host *h, const char *call, int key, app_key_kind kind, int n)
{
    const char *what = kind_name(kind);
    if (key < 0 || key >= h->key_count || h->keys[key].store_key < 0 || !h->store) {
        refusal(h, "cavelight_%s_%s(): no key %d (this application registered %d)", call, what, key,
                h->key_count);
        return NULL;
    }
    app_key *k = &h->keys[key];
    if (k->kind != kind)
        return refusal(h, "cavelight_%s_%s(%s): the key is a %s", call, what, k->name, kind_name(k->kind)), NULL;
    if (kind == APP_KEY_VECTOR && k->n != n)
        return refusal(h, "cavelight_%s_vector(%s): %d floats, the key has %d", call, k->name, n, k->n), NULL;
    return k;
}

static int settable(app_host *h, const char *call, const char *what)
{
    static const char *const phases[] = {"no callback", "init", "update", "frame", "draw"};
    if (h->writable && h->phase == PHASE_UPDATE)
        return 1;
    return refusal(h, "%s%s: keys and objects are set on the master in update only (this is %s, in %s)", call,
                   what, h->app.process, phases[h->phase]), 0;
}

static int host_key_set(void *host, int key, app_key_kind kind, int n, const void *data, size_t len)
{
    app_host *h = host;
    app_key *k = settable(h, "cavelight_set_", kind_name(kind)) ? typed(h, "set", key, kind, n) : NULL;
    if (!k)
        return -1;
    if (kind == APP_KEY_STRING || kind == APP_KEY_BLOB) {
        if (params_set_bytes(h->writable, k->store_key, data, len) == 0)
            return 0;
        return refusal(h, "cavelight_set_%s(%s): %zu bytes %s (at most %zu%s)", kind_name(kind), k->name, len,
                       len > k->capacity ? "too many" : "not UTF-8 without NUL", k->capacity,
                       kind == APP_KEY_STRING ? " of UTF-8 without NUL" : "");
    }
    if (!all_finite(k, data))
        return refusal(h, "cavelight_set_%s(%s): not a finite value", kind_name(kind), k->name);
    return params_set(h->writable, k->store_key, data, fixed_size(k));
}

static const void *host_key_get(void *host, int key, app_key_kind kind, int n, size_t *len)
{
    app_host *h = host;
    app_key *k = typed(h, "get", key, kind, n);
    if (!k)
        return NULL;
    if (kind == APP_KEY_STRING || kind == APP_KEY_BLOB) {
        const uint8_t *b = params_get_bytes(h->store, k->store_key, len);
        if (kind == APP_KEY_BLOB)
            return b;
        memcpy(k->text, b, *len);
        k->text[*len] = '\0';
        return k->text;
    }
    *len = fixed_size(k);
    params_get(h->store, k->store_key, k->scratch.b, *len);
    return k->scratch.b;
}

/* ---- objects ---------------------------------------------------------------------- */

static int host_object_count(void *host) { return ((app_host *)host)->desc.scene->object_count; }

static int host_object_find(void *host, const char *name)
{
    return scene_object_find(((app_host *)host)->desc.scene, name);
}

/* An object's rest bounds need no pose (valid in init); the rest reads or sets it. */
static int object_ok(app_host *h, const char *call, int o, int pose)
{
    int count = h->desc.scene->object_count;
    if (o >= 0 && o < count && (h->pose || !pose))
        return 1;
    if (o >= 0 && o < count)
        return refusal(h, "%s: object %d's pose is there from update on (init has its bounds)",
                       call, o), 0;
    return refusal(h, "%s: no object %d (the scene has %d)", call, o, count), 0;
}

static const char *host_object_name(void *host, int o)
{
    app_host *h = host;
    return o >= 0 && o < h->desc.scene->object_count ? h->desc.scene->objects[o].name : NULL;
}

static int host_object_set(void *host, int o, const float *offset, int visible)
{
    app_host *h = host;
    const char *call = offset ? "cavelight_object_set_offset" : "cavelight_object_set_visible";
    if (!settable(h, call, "") || !object_ok(h, call, o, 1))
        return -1;
    if (offset) {
        for (int i = 0; i < 16; i++)
            if (!isfinite(offset[i]))
                return refusal(h, "%s(%s): not a finite matrix", call, h->desc.scene->objects[o].name);
        memcpy(h->pose->offset[o], offset, sizeof h->pose->offset[o]);
    } else {
        h->pose->visible[o] = visible;
    }
    return 0;
}

static int host_object_get(void *host, int o, app_object_part part, float *out)
{
    app_host *h = host;
    if (!object_ok(h, part == APP_OBJECT_BOUNDS ? "cavelight_object_bounds" : "cavelight_object_*", o,
                   part != APP_OBJECT_BOUNDS))
        return -1;
    switch (part) {
    case APP_OBJECT_OFFSET:
        memcpy(out, h->pose->offset[o], sizeof h->pose->offset[o]);
        break;
    case APP_OBJECT_MODEL:
        scene_pose_models(h->desc.scene, h->pose, h->models, h->shown);
        memcpy(out, h->models[o], sizeof h->models[o]);
        break;
    case APP_OBJECT_VISIBLE:
        out[0] = (float)(h->pose->visible[o] != 0);
        break;
    default:
        memcpy(out, h->bounds[o], sizeof h->bounds[o]);
    }
    return 0;
}

/* ---- drawing ---------------------------------------------------------------------- */

static int host_draw(void *host, const cavelight_draw *d, int mode, const cavelight_vertex *v, int count,
                     float size)
{
    app_host *h = host;
    const char *what = mode ? "lines" : "points";
    if (h->phase != PHASE_DRAW || !h->desc.draw)
        return refusal(h, "cavelight_draw_%s(): only in draw, on a render node", what);
    if (count > APP_DRAW_MAX_VERTICES)
        return refusal(h, "cavelight_draw_%s(): %d vertices, at most %d a call", what, count, APP_DRAW_MAX_VERTICES);
    return h->desc.draw(h->desc.user, d, mode, v, count, size);
}

static void *host_gl_proc(void *host, const char *name)
{
    app_host *h = host;
    return h->desc.gl_proc ? h->desc.gl_proc(h->desc.user, name) : NULL;
}

static const app_host_ops ops = {
    .key_add = host_key_add, .key_find = host_key_find, .key_set = host_key_set, .key_get = host_key_get,
    .object_count = host_object_count, .object_find = host_object_find, .object_name = host_object_name,
    .object_set = host_object_set, .object_get = host_object_get, .draw = host_draw,
    .gl_proc = host_gl_proc, .last_error = host_last_error, .refuse = host_refuse,
};

/* ---- life cycle ------------------------------------------------------------------- */

static void object_bounds(app_host *h)
{
    const scene *s = h->desc.scene;
    h->bounds = xcalloc((size_t)(s->object_count ? s->object_count : 1), sizeof *h->bounds);
    for (int o = 0; o < s->object_count; o++)
        for (int a = 0; a < 3; a++) {
            h->bounds[o][a] = INFINITY;
            h->bounds[o][3 + a] = -INFINITY;
        }
    for (size_t t = 0; s->triangle_object && t < s->triangle_count; t++) {
        int o = s->triangle_object[t];
        for (int v = 0; o >= 0 && v < 3; v++)
            for (int a = 0; a < 3; a++) {
                float x = s->positions[9 * t + 3 * v + a];
                h->bounds[o][a] = fminf(h->bounds[o][a], x);
                h->bounds[o][3 + a] = fmaxf(h->bounds[o][3 + a], x);
            }
    }
}

app_host *app_host_load(const app_host_desc *desc, char *err, size_t errlen)
{
    app_host *h = xcalloc(1, sizeof *h);
    h->desc = *desc;
    snprintf(h->path, sizeof h->path, "%s", desc->path);
    h->desc.path = h->path;
    snprintf(h->who, sizeof h->who, desc->role == CAVELIGHT_ROLE_MASTER ? "cavelight-master" : "cavelight-node %s",
             desc->process);
    const char *slash = strrchr(h->path, '/');
    snprintf(h->name, sizeof h->name, "%.63s", slash ? slash + 1 : h->path);
    /* A path without a slash would be searched in the library path: name it as a file. */
    char file[520];
    snprintf(file, sizeof file, "%s%s", strchr(h->path, '/') ? "" : "./", h->path);
    h->so = dlopen(file, RTLD_NOW | RTLD_LOCAL);
    if (!h->so) {
        snprintf(err, errlen, "app %s: cannot load it (%s)", h->path, dlerror());
        goto fail;
    }
    cavelight_app_desc (*entry)(void);
    *(void **)&entry = dlsym(h->so, "cavelight_app_main");
    int (*abi)(void);
    *(void **)&abi = dlsym(h->so, "cavelight_library_abi");
    if (!entry) {
        snprintf(err, errlen, "app %s: no cavelight_app_main() (an application defines it: cavelight/app.h)",
                 h->path);
        goto fail;
    }
    if (abi && abi() != CAVELIGHT_APP_ABI) {
        snprintf(err, errlen, "app %s: linked with a libcavelight of ABI %d, this program has %d (link it with "
                 "this build's libcavelight)", h->path, abi(), CAVELIGHT_APP_ABI);
        goto fail;
    }
    h->app = (cavelight_app){.abi = CAVELIGHT_APP_ABI, .role = desc->role, .process = desc->process,
                             .desc = entry(), .ops = &ops, .host = h};
    int version = h->app.desc.version ? h->app.desc.version : CAVELIGHT_APP_VERSION;
    if (version != CAVELIGHT_APP_VERSION) {
        snprintf(err, errlen, "app %s: written for API version %d, this program has %d", h->path, version,
                 CAVELIGHT_APP_VERSION);
        goto fail;
    }
    if (h->app.desc.name && h->app.desc.name[0])
        snprintf(h->name, sizeof h->name, "%s", h->app.desc.name);
    object_bounds(h);
    return h;
fail:
    if (h->so)
        dlclose(h->so);
    free(h);
    return NULL;
}

int app_host_init(app_host *h, char *err, size_t errlen)
{
    h->phase = PHASE_INIT;
    if (h->app.desc.init)
        h->app.desc.init(&h->app);
    h->phase = PHASE_NONE;
    if (h->key_refused) {
        snprintf(err, errlen, "app %s: init registered a key that was refused (%s)", h->name,
                 h->refused_key);
        return -1;
    }
    if (!h->desc.quiet)
        fprintf(stderr, "%s: app %s loaded: %d keys\n", h->who, h->name, h->key_count);
    return 0;
}

int app_host_add_keys(app_host *h, params_schema *schema, char *err, size_t errlen)
{
    for (int i = 0; i < h->key_count; i++) {
        app_key *k = &h->keys[i];
        char name[PARAMS_NAME_MAX + 8], why[300];
        snprintf(name, sizeof name, "app.%s", k->name);
        k->store_key = params_schema_add_key(schema, name, key_type(k), k->capacity, k->initial.b, why,
                                             sizeof why);
        if (k->store_key < 0) {
            snprintf(err, errlen, "app %s: %s", h->name, why);
            return -1;
        }
    }
    return 0;
}

void app_host_bind(app_host *h, const params_store *store, params_store *writable, scene_pose *pose)
{
    h->store = store;
    h->writable = writable;
    h->pose = pose;
}

void app_host_update(app_host *h, const cavelight_input *in)
{
    if (!h->app.desc.update)
        return;
    h->phase = PHASE_UPDATE;
    h->app.desc.update(&h->app, in);
    h->phase = PHASE_NONE;
}

void app_host_frame(app_host *h)
{
    if (!h->app.desc.frame)
        return;
    h->phase = PHASE_FRAME;
    h->app.desc.frame(&h->app);
    h->phase = PHASE_NONE;
}

int app_host_draws(const app_host *h) { return h && h->app.desc.draw; }

void app_host_draw(app_host *h, const cavelight_draw *d)
{
    if (!h->app.desc.draw)
        return;
    h->phase = PHASE_DRAW;
    h->app.desc.draw(&h->app, d);
    h->phase = PHASE_NONE;
}

const char *app_host_name(const app_host *h) { return h->name; }
uint32_t app_host_buttons(const app_host *h) { return h ? h->app.desc.buttons : 0; }

void app_host_destroy(app_host *h)
{
    if (!h)
        return;
    if (h->app.desc.shutdown)
        h->app.desc.shutdown(&h->app);
    for (int i = 0; i < h->key_count; i++)
        free(h->keys[i].text);
    free(h->bounds);
    dlclose(h->so);
    free(h);
}
