#include "cluster/params.h"

#include "base/byteorder.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

/* The core keys: name, type and place in a frame_params. */
static const struct {
    const char *name;
    params_type type;
    size_t offset;
} core[PARAMS_LIGHT_BASE] = {
    {"head", PARAMS_T_MAT4, offsetof(frame_params, head)},
    {"wand", PARAMS_T_MAT4, offsetof(frame_params, wand)},
    {"navigation", PARAMS_T_MAT4, offsetof(frame_params, navigation)},
    {"time", PARAMS_T_F64, offsetof(frame_params, time)},
    {"reset_epoch", PARAMS_T_U32, offsetof(frame_params, reset_epoch)},
    {"hud_layout", PARAMS_T_I32, offsetof(frame_params, hud_layout)},
    {"pattern", PARAMS_T_I32, offsetof(frame_params, pattern)},
    {"light_count", PARAMS_T_I32, offsetof(frame_params, light_count)},
};
static const struct {
    const char *name;
    params_type type;
    size_t offset;
} light_fields[PARAMS_LIGHT_FIELDS] = {
    {"enabled", PARAMS_T_I32, offsetof(frame_light, enabled)},
    {"pose", PARAMS_T_POSE, offsetof(frame_light, position)}, /* position, then direction */
    {"color", PARAMS_T_VEC3, offsetof(frame_light, color)},
    {"intensity", PARAMS_T_F32, offsetof(frame_light, intensity)},
    {"cone", PARAMS_T_VEC2, offsetof(frame_light, outer_angle)}, /* outer, then inner */
    {"type", PARAMS_T_I32, offsetof(frame_light, type)},
};
_Static_assert(offsetof(frame_light, direction) == offsetof(frame_light, position) + 12,
               "a light's pose key is its position and direction, in a row");
_Static_assert(offsetof(frame_light, inner_angle) == offsetof(frame_light, outer_angle) + 4,
               "a light's cone key is its outer and inner angle, in a row");

int params_light_key(int light, int field)
{
    if (light < 0 || light >= FRAME_MAX_LIGHTS || field < 0 || field >= PARAMS_LIGHT_FIELDS)
        return -1;
    return PARAMS_LIGHT_BASE + light * PARAMS_LIGHT_FIELDS + field;
}

static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const uint8_t *b = data;
    for (size_t i = 0; i < n; i++)
        h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

static void add(params_schema *s, const char *name, params_type type, size_t offset,
                const setting *row, int slot)
{
    params_key *k = &s->keys[s->count++];
    snprintf(k->name, sizeof k->name, "%s", name);
    k->type = type;
    k->frame_offset = offset;
    k->setting = row;
    k->gi_slot = slot;
    uint32_t t = (uint32_t)type;
    s->hash = fnv(fnv(s->hash, k->name, strlen(k->name) + 1), &t, sizeof t);
}

void params_schema_init(params_schema *s)
{
    memset(s, 0, sizeof *s);
    s->hash = 1469598103934665603ull;
    for (int k = 0; k < PARAMS_LIGHT_BASE; k++)
        add(s, core[k].name, core[k].type, core[k].offset, NULL, -1);
    for (int l = 0; l < FRAME_MAX_LIGHTS; l++)
        for (int f = 0; f < PARAMS_LIGHT_FIELDS; f++) {
            char name[PARAMS_NAME_MAX];
            snprintf(name, sizeof name, "light%d.%s", l, light_fields[f].name);
            add(s, name, light_fields[f].type,
                offsetof(frame_params, lights) + (size_t)l * sizeof(frame_light) + light_fields[f].offset,
                NULL, -1);
        }
    for (int i = 0; i < frame_transport_setting_count; i++)
        params_schema_add(s, &frame_transport_settings[i], frame_transport_settings[i].offset, -1);
    for (int i = 0; i < frame_display_setting_count; i++)
        params_schema_add(s, &frame_display_settings[i], frame_display_settings[i].offset, -1);
}

int params_schema_find(const params_schema *s, const char *name)
{
    for (int k = 0; k < s->count; k++)
        if (strcmp(s->keys[k].name, name) == 0)
            return k;
    return -1;
}

uint64_t params_session_hash(uint64_t config_hash, const params_schema *s)
{
    return fnv(fnv(1469598103934665603ull, &config_hash, 8), &s->hash, 8);
}

int params_schema_add(params_schema *s, const setting *row, size_t frame_offset, int gi_slot)
{
    if (s->count >= PARAMS_MAX_KEYS || params_schema_find(s, row->name) >= 0 ||
        strlen(row->name) >= PARAMS_NAME_MAX)
        return -1;
    add(s, row->name, row->kind == SETTING_FLOAT ? PARAMS_T_F32 : PARAMS_T_I32, frame_offset, row,
        gi_slot);
    return s->count - 1;
}

static int valid_key(const params_store *s, int key)
{
    return key >= 0 && key < s->schema->count;
}

params_type params_key_type(const params_store *s, int key)
{
    return s->schema->keys[key].type;
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

size_t params_key_size(const params_store *s, int key)
{
    if (!valid_key(s, key))
        return 0;
    params_type t = params_key_type(s, key);
    return type_words(t) * type_word_size(t);
}

const char *params_key_name(const params_store *s, int key)
{
    return valid_key(s, key) ? s->schema->keys[key].name : "?";
}

int params_set(params_store *s, int key, const void *value, size_t size)
{
    if (!valid_key(s, key) || size != params_key_size(s, key))
        return -1;
    if (memcmp(s->value[key], value, size) != 0) {
        memcpy(s->value[key], value, size);
        s->stamp[key] = s->version + 1;
    }
    return 0;
}

static int set_typed(params_store *s, int key, params_type t, const void *v, size_t size)
{
    if (!valid_key(s, key) || params_key_type(s, key) != t)
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
    if (!valid_key(s, key) || size != params_key_size(s, key))
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

/* Where key k's value lives in f, or NULL (a light beyond the light count). A GI setting
 * left unset holds its default for as long as it is read. */
static const void *frame_value(const params_store *s, int k, const frame_params *f,
                               setting_value *scratch)
{
    const params_key *key = &s->schema->keys[k];
    if (key->gi_slot >= 0) {
        const frame_gi_setting *g = &f->gi_settings[key->gi_slot];
        *scratch = g->set ? g->value : setting_default(key->setting);
        return scratch;
    }
    if (k >= PARAMS_LIGHT_BASE && k < PARAMS_CORE_KEYS &&
        (k - PARAMS_LIGHT_BASE) / PARAMS_LIGHT_FIELDS >= f->light_count)
        return NULL;
    return (const char *)f + key->frame_offset;
}

void params_set_from_frame(params_store *s, const frame_params *f)
{
    for (int k = 0; k < s->schema->count; k++) {
        setting_value scratch;
        const void *v = frame_value(s, k, f, &scratch);
        if (v)
            params_set(s, k, v, params_key_size(s, k));
    }
}

void params_init(params_store *s, const params_schema *schema)
{
    memset(s, 0, sizeof *s);
    s->schema = schema;
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
    for (int k = 0; k < s->schema->count; k++)
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
    for (int k = 0; k < s->schema->count; k++) {
        if (!all && s->stamp[k] <= since)
            continue;
        params_type t = params_key_type(s, k);
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
    uint8_t seen[PARAMS_MAX_KEYS];
    memset(seen, 0, sizeof seen);
    /* Pass 1 validates, pass 2 applies: a bad record must not leave a half-applied delta. */
    for (int pass = 0; pass < 2; pass++) {
        size_t n = 0;
        while (n < len) {
            if (len - n < 2)
                return -1;
            int k = (int)le_get(buf + n, 2);
            n += 2;
            if (!valid_key(s, k))
                return -1;
            params_type t = params_key_type(s, k);
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
    /* The light count first: it says which lights' keys mean something. */
    f->light_count = params_get_i32(s, PARAMS_LIGHT_COUNT);
    for (int k = 0; k < s->schema->count; k++) {
        const params_key *key = &s->schema->keys[k];
        size_t size = params_key_size(s, k);
        if (key->gi_slot >= 0) {
            f->gi_settings[key->gi_slot].set = 1;
            memcpy(&f->gi_settings[key->gi_slot].value, s->value[k], size);
        } else if (k < PARAMS_LIGHT_BASE || k >= PARAMS_CORE_KEYS ||
                   (k - PARAMS_LIGHT_BASE) / PARAMS_LIGHT_FIELDS < f->light_count) {
            memcpy((char *)f + key->frame_offset, s->value[k], size);
        }
    }
}

uint64_t params_checksum(const params_store *s)
{
    uint64_t h = 1469598103934665603ull;
    for (int i = 0; i < 8; i++)
        h = (h ^ ((s->version >> (8 * i)) & 0xff)) * 1099511628211ull;
    for (int k = 0; k < s->schema->count; k++) {
        size_t size = params_key_size(s, k);
        for (size_t i = 0; i < size; i++)
            h = (h ^ s->value[k][i]) * 1099511628211ull;
    }
    return h;
}
