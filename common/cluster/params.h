/* params: the versioned parameter store the master commits and every node mirrors.
 *
 * Keys come from a schema both sides build alike (params_schema): the core keys (head,
 * wand, navigation, time, history-reset epoch, HUD layout, pattern, the lights' poses,
 * colours, intensities, cones and types), every frame setting (frame_params.h: steps,
 * lambda, medium, RSM size, tone mapping) and whatever settings a program adds (node/gi's
 * methods), each a typed key that lives at a fixed place of frame_params. Setting a key to
 * a new value stamps it with the version the next params_commit() creates; a delta since
 * version b carries exactly the keys stamped after b, a snapshot carries every key.
 * Beyond those, a program may add keys that live outside frame_params
 * (params_schema_add_key()): the scene's objects (cluster/scene_keys.h) and an
 * application's own keys (app/app_keys.h), numbers, vectors, matrices, and strings and
 * blobs of a bounded size, all in one fixed arena, so that no update can grow the store.
 * Encodings are little-endian records (u16 key, fixed-size value; a string or blob: u16
 * length, then its bytes); params_apply() validates a whole buffer before changing
 * anything, so a malformed delta leaves the store untouched. No allocation: the store and
 * the schema are plain structs the caller owns. */
#ifndef CAVELIGHT_PARAMS_H
#define CAVELIGHT_PARAMS_H

#include <stddef.h>
#include <stdint.h>

#include "base/setting.h"
#include "frame/frame_params.h"

typedef enum params_type {
    PARAMS_T_I32 = 0,
    PARAMS_T_U32,
    PARAMS_T_F32,
    PARAMS_T_F64,
    PARAMS_T_VEC2,
    PARAMS_T_VEC3,
    PARAMS_T_POSE,  /* position vec3 + unit direction vec3 */
    PARAMS_T_MAT4,  /* column-major */
    PARAMS_T_VEC4,
    PARAMS_T_STRING, /* UTF-8 without NUL, at most the key's capacity in bytes */
    PARAMS_T_BLOB,   /* any bytes, at most the key's capacity */
    PARAMS_T_COUNT
} params_type;

/* The core keys, first in every schema. */
enum {
    PARAMS_HEAD = 0,       /* mat4, tracked head pose in CAVE space */
    PARAMS_WAND,           /* mat4, wand pose in CAVE space */
    PARAMS_NAVIGATION,     /* mat4, CAVE-to-world */
    PARAMS_TIME,           /* f64, seconds */
    PARAMS_RESET_EPOCH,    /* u32, raised to drop every node's LPV history */
    PARAMS_HUD_LAYOUT,     /* i32 */
    PARAMS_PATTERN,        /* i32, 1: the screens show the calibration pattern */
    PARAMS_LIGHT_COUNT,    /* i32, 0..FRAME_MAX_LIGHTS */
    PARAMS_LIGHT_BASE      /* first per-light key, see params_light_key() */
};

enum {
    PARAMS_LIGHT_ENABLED = 0, /* i32 */
    PARAMS_LIGHT_POSE,        /* pose: position, direction */
    PARAMS_LIGHT_COLOR,       /* vec3, linear RGB */
    PARAMS_LIGHT_INTENSITY,   /* f32 */
    PARAMS_LIGHT_CONE,        /* vec2: outer, inner half angle (radians) */
    PARAMS_LIGHT_TYPE,        /* i32, scene_light_type: spot, point, directional */
    PARAMS_LIGHT_FIELDS
};

enum {
    PARAMS_CORE_KEYS = PARAMS_LIGHT_BASE + FRAME_MAX_LIGHTS * PARAMS_LIGHT_FIELDS,
    PARAMS_MAX_KEYS = 512,
    PARAMS_NAME_MAX = 64,
    PARAMS_VALUE_MAX = 64,  /* largest fixed-size value (mat4) in bytes */
    PARAMS_BYTES_MAX = 16384,    /* the arena all string and blob keys share */
    PARAMS_BYTES_KEY_MAX = 4096, /* one string or blob key's capacity at most */
    /* Largest encoding: every key with its id (and a length). */
    PARAMS_ENCODED_MAX = PARAMS_MAX_KEYS * (4 + PARAMS_VALUE_MAX) + PARAMS_BYTES_MAX,
};
/* A key that lives outside frame_params (params_schema_add_key()). */
#define PARAMS_NO_FRAME ((size_t)-1)

typedef struct params_key {
    char name[PARAMS_NAME_MAX];   /* "head", "light3.pose", "vpl-count", "app.angle" */
    params_type type;
    size_t frame_offset;          /* where the value lives in a frame_params, or
                                     PARAMS_NO_FRAME */
    size_t capacity;              /* a string or blob: its most bytes */
    uint8_t initial[PARAMS_VALUE_MAX]; /* a fixed-size key outside frame_params: its value
                                     in a fresh store (params_init()) */
    size_t bytes_offset;          /* a string or blob: where it lives in the arena */
    const setting *setting;       /* a setting's key: its row (NULL for the core keys) */
    int gi_slot;                  /* >= 0: a GI method's setting, in frame_params.gi_settings[] */
} params_key;

typedef struct params_schema {
    int count;
    params_key keys[PARAMS_MAX_KEYS];
    size_t bytes_used;            /* of the arena, by string and blob keys */
    uint64_t hash;                /* FNV-1a of the names, types and capacities: HELLO
                                     carries it */
} params_schema;

/* The core keys and the frame settings (frame_transport_settings[],
 * frame_display_settings[]). */
void params_schema_init(params_schema *s);
/* Adds a setting's key: its value at frame_offset of a frame_params, or, gi_slot >= 0, in
 * frame_params.gi_settings[gi_slot] (frame_offset unused). Returns the key, or -1 when the
 * schema is full or the name taken. */
int params_schema_add(params_schema *s, const setting *row, size_t frame_offset, int gi_slot);
/* Adds a key outside frame_params: any type; capacity is a string's or blob's most bytes
 * (1..PARAMS_BYTES_KEY_MAX, and room left in the arena), ignored otherwise. A fresh store
 * holds initial there (a fixed-size key: its size in bytes, host order; NULL: zeros); a
 * string or blob starts empty. The hash covers the initial value too. Returns the key, or
 * -1 with one line in err (a name that is empty, too long or taken, a full schema, a bad
 * type or capacity). */
int params_schema_add_key(params_schema *s, const char *name, params_type type,
                          size_t capacity, const void *initial, char *err, size_t errlen);
/* "number", "vec3", "string", ... */
const char *params_type_name(params_type t);
/* The key named name, or -1. */
int params_schema_find(const params_schema *s, const char *name);
/* What HELLO carries: the cluster config's hash and the schema's, so that a node of
 * another build (other keys) is refused like a node of another config. */
uint64_t params_session_hash(uint64_t config_hash, const params_schema *s);

typedef struct params_store {
    const params_schema *schema;
    uint64_t version;                          /* last committed (or applied) version */
    uint8_t value[PARAMS_MAX_KEYS][PARAMS_VALUE_MAX]; /* a string or blob: its length, u32 */
    uint64_t stamp[PARAMS_MAX_KEYS];           /* version in which each key last changed */
    uint8_t bytes[PARAMS_BYTES_MAX];           /* the strings' and blobs' contents */
} params_store;

/* Every key at frame_params_default()'s value (no lights: the master seeds them from its
 * scene; GI settings at their defaults), as version 0. The schema must outlive the store. */
void params_init(params_store *s, const params_schema *schema);
/* Every key from a frame (the lights of its light count; a GI setting left unset in the
 * frame: its default); stamps what changed. */
void params_set_from_frame(params_store *s, const frame_params *f);

int params_light_key(int light, int field);
params_type params_key_type(const params_store *s, int key);
/* A fixed-size key's size in bytes; 0 for a string or blob (params_set_bytes()). */
size_t params_key_size(const params_store *s, int key);
const char *params_key_name(const params_store *s, int key); /* "head", "light3.pose", ... */

/* Typed setters: return 0, or -1 when key is out of range or of another type.
 * A value equal to the current one does not stamp the key. */
int params_set(params_store *s, int key, const void *value, size_t size);
int params_set_i32(params_store *s, int key, int32_t v);
int params_set_u32(params_store *s, int key, uint32_t v);
int params_set_f32(params_store *s, int key, float v);
int params_set_f64(params_store *s, int key, double v);
int params_set_mat4(params_store *s, int key, const float m[16]);
/* A string or blob key: len bytes (a string: valid UTF-8 without NUL, no terminator
 * counted). Returns 0, or -1 when key is of another type, len exceeds its capacity or a
 * string is not valid UTF-8. */
int params_set_bytes(params_store *s, int key, const void *data, size_t len);
/* A string or blob key's bytes and length (*len), or NULL for another type. */
const uint8_t *params_get_bytes(const params_store *s, int key, size_t *len);
int params_get(const params_store *s, int key, void *value, size_t size);
int32_t params_get_i32(const params_store *s, int key);
uint32_t params_get_u32(const params_store *s, int key);
float params_get_f32(const params_store *s, int key);

/* Makes the pending changes version s->version + 1 and returns it. */
uint64_t params_commit(params_store *s);
/* Number of keys changed after version since (since = 0 means all stamped keys). */
int params_changed_count(const params_store *s, uint64_t since);

/* Encode the keys changed after `since` (a delta) or all keys (snapshot) into buf.
 * Return the byte count (0: nothing changed), or PARAMS_ENCODE_TOO_SMALL when cap is too
 * small (PARAMS_ENCODED_MAX always fits). */
#define PARAMS_ENCODE_TOO_SMALL ((size_t)-1)
size_t params_encode_delta(const params_store *s, uint64_t since, uint8_t *buf, size_t cap);
size_t params_encode_snapshot(const params_store *s, uint8_t *buf, size_t cap);
/* Applies an encoding as `version`. Returns 0, or -1 (store unchanged) on an unknown
 * key, a truncated record, a duplicate key, a non-finite float, a string or blob longer
 * than its key's capacity or a string that is not UTF-8 without NUL. */
int params_apply(params_store *s, uint64_t version, const uint8_t *buf, size_t len);

/* All keys as a frame_params (version, epoch, time, poses, lights of the light count,
 * every setting; a GI setting's slot is marked set), as stored: out-of-range values are
 * the renderer's to fix (gi_frame_sanitize()), not this. */
void params_to_frame(const params_store *s, frame_params *out);
/* FNV-1a over version and every value: what a node with no renderer reports as its
 * checksum, and a cheap equality test between stores. */
uint64_t params_checksum(const params_store *s);

#endif
