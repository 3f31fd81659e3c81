#include "cluster/params.h"

#include "base/byteorder.h"
#include "base/fnv1a.h"

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

static int is_bytes_type(params_type t) { return t == PARAMS_T_STRING || t == PARAMS_T_BLOB; }

static params_key *add(params_schema *s, const char *name, params_type type, size_t offset,
                       const setting *row, int slot)
{
    params_key *k = &s->keys[s->count++];
    snprintf(k->name, sizeof k->name, "%s", name);
    k->type = type;
    k->frame_offset = offset;
    k->setting = row;
    k->gi_slot = slot;
    uint32_t t = (uint32_t)type;
    s->hash = fnv1a64(fnv1a64(s->hash, k->name, strlen(k->name) + 1), &t, sizeof t);
    return k;
}

void params_schema_init(params_schema *s)
{
    memset(s, 0, sizeof *s);
    s->hash = FNV1A64_CLUSTER_SEED;
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
    return fnv1a64(fnv1a64(FNV1A64_CLUSTER_SEED, &config_hash, 8), &s->hash, 8);
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
    case PARAMS_T_VEC4: return 4;
    default: return 1;
    }
}

static size_t type_word_size(params_type t) { return t == PARAMS_T_F64 ? 8 : 4; }

const char *params_type_name(params_type t)
{
    static const char *const names[PARAMS_T_COUNT] = {
        "i32", "u32", "f32", "number", "vec2", "vec3", "pose", "matrix", "vec4", "string", "blob"};
    return (unsigned)t < PARAMS_T_COUNT ? names[t] : "?";
}

int params_schema_add_key(params_schema *s, const char *name, params_type type,
                          size_t capacity, const void *initial, char *err, size_t errlen)
{
    size_t n = strlen(name);
    if (n == 0 || n >= PARAMS_NAME_MAX) {
        snprintf(err, errlen, "key \"%.80s\": a name of 1 to %d bytes", name, PARAMS_NAME_MAX - 1);
        return -1;
    }
    if ((unsigned)type >= PARAMS_T_COUNT) {
        snprintf(err, errlen, "key %s: unknown type %d", name, (int)type);
        return -1;
    }
    if (params_schema_find(s, name) >= 0) {
        snprintf(err, errlen, "key %s: registered twice (names are unique)", name);
        return -1;
    }
    if (s->count >= PARAMS_MAX_KEYS) {
        snprintf(err, errlen, "key %s: the store is full (%d keys at most)", name, PARAMS_MAX_KEYS);
        return -1;
    }
    if (is_bytes_type(type) && (capacity < 1 || capacity > PARAMS_BYTES_KEY_MAX ||
                                capacity > PARAMS_BYTES_MAX - s->bytes_used)) {
        snprintf(err, errlen, "key %s: a %s of %zu bytes does not fit (1 to %d bytes a key, "
                 "%zu of the store's %d left)", name, params_type_name(type), capacity,
                 PARAMS_BYTES_KEY_MAX, (size_t)PARAMS_BYTES_MAX - s->bytes_used, PARAMS_BYTES_MAX);
        return -1;
    }
    params_key *k = add(s, name, type, PARAMS_NO_FRAME, NULL, -1);
    if (is_bytes_type(type)) {
        uint64_t c = capacity;
        s->hash = fnv1a64(s->hash, &c, sizeof c);
        k->capacity = capacity;
        k->bytes_offset = s->bytes_used;
        s->bytes_used += capacity;
    } else if (initial) {
        size_t size = type_words(type) * type_word_size(type);
        memcpy(k->initial, initial, size);
        s->hash = fnv1a64(s->hash, k->initial, size);
    }
    return s->count - 1;
}

static int is_float_type(params_type t)
{
    return t != PARAMS_T_I32 && t != PARAMS_T_U32 && !is_bytes_type(t);
}

size_t params_key_size(const params_store *s, int key)
{
    if (!valid_key(s, key) || is_bytes_type(params_key_type(s, key)))
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
    if (!valid_key(s, key) || is_bytes_type(params_key_type(s, key)) ||
        size != params_key_size(s, key))
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

/* Valid UTF-8 (no overlong forms, no surrogates, at most U+10FFFF) without NUL. */
static int utf8_valid(const uint8_t *p, size_t n)
{
    for (size_t i = 0; i < n;) {
        uint8_t c = p[i];
        size_t more = c < 0x80 ? 0 : (c & 0xe0) == 0xc0 ? 1 : (c & 0xf0) == 0xe0 ? 2 : (c & 0xf8) == 0xf0 ? 3 : 9;
        if (c == 0 || more == 9 || n - i - 1 < more)
            return 0;
        uint32_t cp = more == 0 ? c : more == 1 ? c & 0x1fu : more == 2 ? c & 0x0fu : c & 0x07u;
        for (size_t k = 1; k <= more; k++) {
            if ((p[i + k] & 0xc0) != 0x80)
                return 0;
            cp = (cp << 6) | (p[i + k] & 0x3fu);
        }
        static const uint32_t least[4] = {0, 0x80, 0x800, 0x10000};
        if (cp < least[more] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff))
            return 0;
        i += 1 + more;
    }
    return 1;
}

/* Whether len bytes may be key k's value. */
static int bytes_fit(const params_key *k, const uint8_t *data, size_t len)
{
    return len <= k->capacity && (k->type != PARAMS_T_STRING || utf8_valid(data, len));
}

static uint32_t bytes_len(const params_store *s, int key)
{
    uint32_t n;
    memcpy(&n, s->value[key], 4);
    return n;
}

int params_set_bytes(params_store *s, int key, const void *data, size_t len)
{
    if (!valid_key(s, key) || !is_bytes_type(params_key_type(s, key)))
        return -1;
    const params_key *k = &s->schema->keys[key];
    if (!bytes_fit(k, data, len))
        return -1;
    uint8_t *dst = s->bytes + k->bytes_offset;
    if (bytes_len(s, key) == len && (len == 0 || memcmp(dst, data, len) == 0))
        return 0;
    uint32_t n = (uint32_t)len;
    memcpy(s->value[key], &n, 4);
    if (len)
        memcpy(dst, data, len);
    s->stamp[key] = s->version + 1;
    return 0;
}

const uint8_t *params_get_bytes(const params_store *s, int key, size_t *len)
{
    if (!valid_key(s, key) || !is_bytes_type(params_key_type(s, key)))
        return NULL;
    *len = bytes_len(s, key);
    return s->bytes + s->schema->keys[key].bytes_offset;
}

int params_get(const params_store *s, int key, void *value, size_t size)
{
    if (!valid_key(s, key) || size != params_key_size(s, key) || size == 0)
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
    if (key->frame_offset == PARAMS_NO_FRAME)
        return NULL;
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
    for (int k = 0; k < schema->count; k++)
        if (schema->keys[k].frame_offset == PARAMS_NO_FRAME)
            memcpy(s->value[k], schema->keys[k].initial, params_key_size(s, k));
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
        if (is_bytes_type(t)) {
            size_t len = bytes_len(s, k);
            if (n + 4 + len > cap)
                return PARAMS_ENCODE_TOO_SMALL;
            le_put(buf + n, (uint64_t)k, 2);
            le_put(buf + n + 2, (uint64_t)len, 2);
            if (len)
                memcpy(buf + n + 4, s->bytes + s->schema->keys[k].bytes_offset, len);
            n += 4 + len;
            continue;
        }
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

static int words_finite(const uint8_t *v, size_t word, size_t words)
{
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
            return 0;
    }
    return 1;
}

/* One record at buf[*n]: checked (pass 0) or stored (pass 1). Returns 0, or -1 when it is
 * malformed (checked only in pass 0). */
static int apply_record(params_store *s, int pass, uint64_t version, const uint8_t *buf,
                        size_t len, size_t *n, uint8_t *seen)
{
    if (len - *n < 2)
        return -1;
    int k = (int)le_get(buf + *n, 2);
    *n += 2;
    if (!valid_key(s, k) || (pass == 0 && seen[k]++))
        return -1;
    const params_key *key = &s->schema->keys[k];
    if (is_bytes_type(key->type)) {
        if (len - *n < 2)
            return -1;
        size_t blen = (size_t)le_get(buf + *n, 2);
        const uint8_t *data = buf + *n + 2;
        if (len - *n - 2 < blen || (pass == 0 && !bytes_fit(key, data, blen)))
            return -1;
        *n += 2 + blen;
        if (pass == 1) {
            uint32_t u = (uint32_t)blen;
            memcpy(s->value[k], &u, 4);
            if (blen)
                memcpy(s->bytes + key->bytes_offset, data, blen);
            s->stamp[k] = version;
        }
        return 0;
    }
    size_t word = type_word_size(key->type), words = type_words(key->type);
    if (len - *n < word * words)
        return -1;
    uint8_t v[PARAMS_VALUE_MAX] = {0};
    for (size_t w = 0; w < words; w++)
        get_word(v + w * word, buf + *n + w * word, word);
    *n += word * words;
    if (pass == 0)
        return is_float_type(key->type) && !words_finite(v, word, words) ? -1 : 0;
    memcpy(s->value[k], v, word * words);
    s->stamp[k] = version;
    return 0;
}

int params_apply(params_store *s, uint64_t version, const uint8_t *buf, size_t len)
{
    uint8_t seen[PARAMS_MAX_KEYS];
    memset(seen, 0, sizeof seen);
    /* Pass 1 validates, pass 2 applies: a bad record must not leave a half-applied delta. */
    for (int pass = 0; pass < 2; pass++)
        for (size_t n = 0; n < len;)
            if (apply_record(s, pass, version, buf, len, &n, seen) != 0)
                return -1;
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
        if (key->frame_offset == PARAMS_NO_FRAME)
            continue;
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
    uint64_t h = fnv1a64_le(FNV1A64_CLUSTER_SEED, s->version, 8);
    for (int k = 0; k < s->schema->count; k++) {
        size_t size = params_key_size(s, k);
        const uint8_t *v = s->value[k];
        if (is_bytes_type(params_key_type(s, k))) {
            h = fnv1a64(h, v, 4);
            v = params_get_bytes(s, k, &size);
        }
        h = fnv1a64(h, v, size);
    }
    return h;
}
