#include "cluster/params.h"

#include "base/byteorder.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char *const global_names[PARAMS_LIGHT_BASE] = {
    "head", "wand", "navigation", "time", "reset_epoch", "lpv_steps", "lambda_incr",
    "absorption", "scattering", "lpv_resolution", "environment", "display_gamma",
    "exposure", "hud_layout", "pattern", "gi", "vpl_count", "vpl_seed", "vpl_selection",
    "light_count",
};
static const params_type global_types[PARAMS_LIGHT_BASE] = {
    PARAMS_T_MAT4, PARAMS_T_MAT4, PARAMS_T_MAT4, PARAMS_T_F64, PARAMS_T_U32, PARAMS_T_I32,
    PARAMS_T_F32, PARAMS_T_F32, PARAMS_T_F32, PARAMS_T_I32, PARAMS_T_I32, PARAMS_T_F32,
    PARAMS_T_F32, PARAMS_T_I32, PARAMS_T_I32, PARAMS_T_I32, PARAMS_T_I32, PARAMS_T_U32,
    PARAMS_T_I32, PARAMS_T_I32,
};
static const char *const light_names[PARAMS_LIGHT_FIELDS] = {
    "enabled", "pose", "color", "intensity", "cone", "type",
};
static const params_type light_types[PARAMS_LIGHT_FIELDS] = {
    PARAMS_T_I32, PARAMS_T_POSE, PARAMS_T_VEC3, PARAMS_T_F32, PARAMS_T_VEC2, PARAMS_T_I32,
};

int params_light_key(int light, int field)
{
    if (light < 0 || light >= FRAME_MAX_LIGHTS || field < 0 || field >= PARAMS_LIGHT_FIELDS)
        return -1;
    return PARAMS_LIGHT_BASE + light * PARAMS_LIGHT_FIELDS + field;
}

params_type params_key_type(int key)
{
    if (key < PARAMS_LIGHT_BASE)
        return global_types[key];
    return light_types[(key - PARAMS_LIGHT_BASE) % PARAMS_LIGHT_FIELDS];
}

/* Values are arrays of 4- or 8-byte words; the word size drives byte-order conversion. */
static size_t type_words(params_type t)
{
    switch (t) {
    case PARAMS_T_VEC2: return 2;
    case PARAMS_T_VEC3: return 3;
    case PARAMS_T_POSE: return 6;
    case PARAMS_T_MAT4: return 16;
    default: return 1;
    }
}

static size_t type_word_size(params_type t) { return t == PARAMS_T_F64 ? 8 : 4; }

static int is_float_type(params_type t) { return t != PARAMS_T_I32 && t != PARAMS_T_U32; }

size_t params_key_size(int key)
{
    if (key < 0 || key >= PARAMS_KEY_COUNT)
        return 0;
    params_type t = params_key_type(key);
    return type_words(t) * type_word_size(t);
}

const char *params_key_name(int key)
{
    static _Thread_local char buf[32];
    if (key < 0 || key >= PARAMS_KEY_COUNT)
        return "?";
    if (key < PARAMS_LIGHT_BASE)
        return global_names[key];
    int l = (key - PARAMS_LIGHT_BASE) / PARAMS_LIGHT_FIELDS;
    snprintf(buf, sizeof buf, "light%d.%s", l, light_names[(key - PARAMS_LIGHT_BASE) % PARAMS_LIGHT_FIELDS]);
    return buf;
}

int params_set(params_store *s, int key, const void *value, size_t size)
{
    if (key < 0 || key >= PARAMS_KEY_COUNT || size != params_key_size(key))
        return -1;
    if (memcmp(s->value[key], value, size) != 0) {
        memcpy(s->value[key], value, size);
        s->stamp[key] = s->version + 1;
    }
    return 0;
}

static int set_typed(params_store *s, int key, params_type t, const void *v, size_t size)
{
    if (key < 0 || key >= PARAMS_KEY_COUNT || params_key_type(key) != t)
        return -1;
    return params_set(s, key, v, size);
}

int params_set_i32(params_store *s, int key, int32_t v) { return set_typed(s, key, PARAMS_T_I32, &v, 4); }
int params_set_u32(params_store *s, int key, uint32_t v) { return set_typed(s, key, PARAMS_T_U32, &v, 4); }
int params_set_f32(params_store *s, int key, float v) { return set_typed(s, key, PARAMS_T_F32, &v, 4); }
int params_set_f64(params_store *s, int key, double v) { return set_typed(s, key, PARAMS_T_F64, &v, 8); }
int params_set_mat4(params_store *s, int key, const float m[16]) { return set_typed(s, key, PARAMS_T_MAT4, m, 64); }

int params_get(const params_store *s, int key, void *value, size_t size)
{
    if (key < 0 || key >= PARAMS_KEY_COUNT || size != params_key_size(key))
        return -1;
    memcpy(value, s->value[key], size);
    return 0;
}

int32_t params_get_i32(const params_store *s, int key)
{
    int32_t v = 0;
    params_get(s, key, &v, 4);
    return v;
}

uint32_t params_get_u32(const params_store *s, int key)
{
    uint32_t v = 0;
    params_get(s, key, &v, 4);
    return v;
}

float params_get_f32(const params_store *s, int key)
{
    float v = 0;
    params_get(s, key, &v, 4);
    return v;
}

static void set_light(params_store *s, int i, const frame_light *l)
{
    float pose[6] = {l->position[0], l->position[1], l->position[2],
                     l->direction[0], l->direction[1], l->direction[2]};
    float cone[2] = {l->outer_angle, l->inner_angle};
    params_set_i32(s, params_light_key(i, PARAMS_LIGHT_ENABLED), l->enabled);
    params_set(s, params_light_key(i, PARAMS_LIGHT_POSE), pose, sizeof pose);
    params_set(s, params_light_key(i, PARAMS_LIGHT_COLOR), l->color, 12);
    params_set_f32(s, params_light_key(i, PARAMS_LIGHT_INTENSITY), l->intensity);
    params_set(s, params_light_key(i, PARAMS_LIGHT_CONE), cone, sizeof cone);
    params_set_i32(s, params_light_key(i, PARAMS_LIGHT_TYPE), (int32_t)l->type);
}

void params_set_from_frame(params_store *s, const frame_params *f)
{
    params_set_mat4(s, PARAMS_HEAD, f->head);
    params_set_mat4(s, PARAMS_WAND, f->wand);
    params_set_mat4(s, PARAMS_NAVIGATION, f->navigation);
    params_set_f64(s, PARAMS_TIME, f->time);
    params_set_u32(s, PARAMS_RESET_EPOCH, f->reset_epoch);
    params_set_i32(s, PARAMS_LPV_STEPS, f->lpv_steps);
    params_set_f32(s, PARAMS_LAMBDA_INCR, f->lambda_incr);
    params_set_f32(s, PARAMS_ABSORPTION, f->absorption);
    params_set_f32(s, PARAMS_SCATTERING, f->scattering);
    params_set_i32(s, PARAMS_ENVIRONMENT, (int32_t)f->environment);
    params_set_f32(s, PARAMS_DISPLAY_GAMMA, f->display_gamma);
    params_set_f32(s, PARAMS_EXPOSURE, f->exposure);
    params_set_i32(s, PARAMS_HUD_LAYOUT, f->hud_layout);
    params_set_i32(s, PARAMS_PATTERN, f->pattern);
    params_set_i32(s, PARAMS_GI, (int32_t)f->gi);
    params_set_i32(s, PARAMS_VPL_COUNT, f->vpl_count);
    params_set_u32(s, PARAMS_VPL_SEED, f->vpl_seed);
    params_set_i32(s, PARAMS_VPL_SELECTION, (int32_t)f->vpl_selection);
    params_set_i32(s, PARAMS_LIGHT_COUNT, f->light_count);
    for (int i = 0; i < f->light_count && i < FRAME_MAX_LIGHTS; i++)
        set_light(s, i, &f->lights[i]);
}

void params_init(params_store *s)
{
    memset(s, 0, sizeof *s);
    frame_params f;
    frame_params_default(&f);
    params_set_from_frame(s, &f);
    /* Defaults are version 0: a fresh store and a snapshot of it agree without a commit. */
    memset(s->stamp, 0, sizeof s->stamp);
}

uint64_t params_commit(params_store *s) { return ++s->version; }

int params_changed_count(const params_store *s, uint64_t since)
{
    int n = 0;
    for (int k = 0; k < PARAMS_KEY_COUNT; k++)
        n += s->stamp[k] > since;
    return n;
}

/* A value word (4 or 8 bytes, host order in the store) to and from little-endian bytes. */
static void put_word(uint8_t *p, const uint8_t *v, size_t word)
{
    uint64_t x = 0;
    if (word == 8) {
        memcpy(&x, v, 8);
    } else {
        uint32_t y;
        memcpy(&y, v, 4);
        x = y;
    }
    le_put(p, x, (int)word);
}

static void get_word(uint8_t *v, const uint8_t *p, size_t word)
{
    uint64_t x = le_get(p, (int)word);
    if (word == 8) {
        memcpy(v, &x, 8);
    } else {
        uint32_t y = (uint32_t)x;
        memcpy(v, &y, 4);
    }
}

static size_t encode(const params_store *s, int all, uint64_t since, uint8_t *buf, size_t cap)
{
    size_t n = 0;
    for (int k = 0; k < PARAMS_KEY_COUNT; k++) {
        if (!all && s->stamp[k] <= since)
            continue;
        params_type t = params_key_type(k);
        size_t word = type_word_size(t), words = type_words(t);
        if (n + 2 + word * words > cap)
            return PARAMS_ENCODE_TOO_SMALL;
        le_put(buf + n, (uint64_t)k, 2);
        n += 2;
        for (size_t w = 0; w < words; w++, n += word)
            put_word(buf + n, s->value[k] + w * word, word);
    }
    return n;
}

size_t params_encode_delta(const params_store *s, uint64_t since, uint8_t *buf, size_t cap)
{
    return encode(s, 0, since, buf, cap);
}

size_t params_encode_snapshot(const params_store *s, uint8_t *buf, size_t cap)
{
    return encode(s, 1, 0, buf, cap);
}

int params_apply(params_store *s, uint64_t version, const uint8_t *buf, size_t len)
{
    uint8_t seen[PARAMS_KEY_COUNT];
    memset(seen, 0, sizeof seen);
    /* Pass 1 validates, pass 2 applies: a bad record must not leave a half-applied delta. */
    for (int pass = 0; pass < 2; pass++) {
        size_t n = 0;
        while (n < len) {
            if (len - n < 2)
                return -1;
            int k = (int)le_get(buf + n, 2);
            n += 2;
            if (k >= PARAMS_KEY_COUNT)
                return -1;
            params_type t = params_key_type(k);
            size_t word = type_word_size(t), words = type_words(t);
            if (len - n < word * words)
                return -1;
            uint8_t v[PARAMS_VALUE_MAX];
            for (size_t w = 0; w < words; w++)
                get_word(v + w * word, buf + n + w * word, word);
            n += word * words;
            if (pass == 0) {
                if (seen[k]++)
                    return -1;
                if (is_float_type(t)) {
                    for (size_t w = 0; w < words; w++) {
                        double d;
                        if (word == 8) {
                            memcpy(&d, v + w * 8, 8);
                        } else {
                            float f;
                            memcpy(&f, v + w * 4, 4);
                            d = f;
                        }
                        if (!isfinite(d))
                            return -1;
                    }
                }
            } else {
                memcpy(s->value[k], v, word * words);
                s->stamp[k] = version;
            }
        }
    }
    s->version = version;
    return 0;
}

void params_to_frame(const params_store *s, frame_params *f)
{
    memset(f, 0, sizeof *f);
    f->version = s->version;
    params_get(s, PARAMS_HEAD, f->head, 64);
    params_get(s, PARAMS_WAND, f->wand, 64);
    params_get(s, PARAMS_NAVIGATION, f->navigation, 64);
    params_get(s, PARAMS_TIME, &f->time, 8);
    f->reset_epoch = params_get_u32(s, PARAMS_RESET_EPOCH);
    f->lpv_steps = params_get_i32(s, PARAMS_LPV_STEPS);
    f->lambda_incr = params_get_f32(s, PARAMS_LAMBDA_INCR);
    f->absorption = params_get_f32(s, PARAMS_ABSORPTION);
    f->scattering = params_get_f32(s, PARAMS_SCATTERING);
    f->environment = (frame_environment)params_get_i32(s, PARAMS_ENVIRONMENT);
    f->display_gamma = params_get_f32(s, PARAMS_DISPLAY_GAMMA);
    f->exposure = params_get_f32(s, PARAMS_EXPOSURE);
    f->hud_layout = params_get_i32(s, PARAMS_HUD_LAYOUT);
    f->pattern = params_get_i32(s, PARAMS_PATTERN);
    f->gi = (frame_gi)params_get_i32(s, PARAMS_GI);
    f->vpl_count = params_get_i32(s, PARAMS_VPL_COUNT);
    f->vpl_seed = params_get_u32(s, PARAMS_VPL_SEED);
    f->vpl_selection = (vpl_selection)params_get_i32(s, PARAMS_VPL_SELECTION);
    f->light_count = params_get_i32(s, PARAMS_LIGHT_COUNT);
    for (int i = 0; i < f->light_count && i < FRAME_MAX_LIGHTS; i++) {
        frame_light *l = &f->lights[i];
        float pose[6] = {0}, cone[2] = {0};
        l->enabled = params_get_i32(s, params_light_key(i, PARAMS_LIGHT_ENABLED));
        params_get(s, params_light_key(i, PARAMS_LIGHT_POSE), pose, sizeof pose);
        memcpy(l->position, pose, 12);
        memcpy(l->direction, pose + 3, 12);
        params_get(s, params_light_key(i, PARAMS_LIGHT_COLOR), l->color, 12);
        l->intensity = params_get_f32(s, params_light_key(i, PARAMS_LIGHT_INTENSITY));
        params_get(s, params_light_key(i, PARAMS_LIGHT_CONE), cone, sizeof cone);
        l->outer_angle = cone[0];
        l->inner_angle = cone[1];
        l->type = (scene_light_type)params_get_i32(s, params_light_key(i, PARAMS_LIGHT_TYPE));
    }
}

uint64_t params_checksum(const params_store *s)
{
    uint64_t h = 1469598103934665603ull;
    for (int i = 0; i < 8; i++)
        h = (h ^ ((s->version >> (8 * i)) & 0xff)) * 1099511628211ull;
    for (int k = 0; k < PARAMS_KEY_COUNT; k++) {
        size_t size = params_key_size(k);
        for (size_t i = 0; i < size; i++)
            h = (h ^ s->value[k][i]) * 1099511628211ull;
    }
    return h;
}
