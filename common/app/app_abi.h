/* app_abi: what libcavelight (the library an application links, libcavelight/app.c) and
 * the process that loaded the application (app_host.c) share: the handle behind
 * cavelight_app and the host's operations it forwards to. The library checks arguments
 * and formats nothing; the host owns the keys, the objects and the messages. Both are
 * built from this tree: CAVELIGHT_APP_ABI changes whenever this struct does, and the host
 * refuses a library of another ABI (app_host_load()). */
#ifndef CAVELIGHT_APP_ABI_H
#define CAVELIGHT_APP_ABI_H

#include <stddef.h>
#include <stdint.h>

#include "cavelight/app.h"

#define CAVELIGHT_APP_ABI 1

/* What an object query asks for (app_host_ops.object_get). */
typedef enum app_object_part {
    APP_OBJECT_OFFSET = 0,
    APP_OBJECT_MODEL,
    APP_OBJECT_VISIBLE,     /* out[0]: 1 or 0 */
    APP_OBJECT_BOUNDS,      /* out[0..2] lo, out[3..5] hi */
} app_object_part;

/* Kinds of application keys, as the library asks for them. */
typedef enum app_key_kind {
    APP_KEY_NUMBER = 0,
    APP_KEY_VECTOR,         /* n floats, 2..4 */
    APP_KEY_MATRIX,
    APP_KEY_STRING,
    APP_KEY_BLOB,
} app_key_kind;

typedef struct app_host_ops {
    /* Every call returns -1 (and reports why) when refused. */
    int (*key_add)(void *host, const char *name, app_key_kind kind, int n, size_t capacity,
                   const void *initial);
    int (*key_find)(void *host, const char *name);
    int (*key_set)(void *host, int key, app_key_kind kind, int n, const void *data, size_t len);
    /* The value's bytes (*len) or NULL. A string is NUL-terminated. */
    const void *(*key_get)(void *host, int key, app_key_kind kind, int n, size_t *len);
    int (*object_count)(void *host);
    int (*object_find)(void *host, const char *name);
    const char *(*object_name)(void *host, int object);
    int (*object_set)(void *host, int object, const float *offset, int visible);
    int (*object_get)(void *host, int object, app_object_part part, float *out);
    /* mode 0 points (size in pixels), 1 lines. */
    int (*draw)(void *host, const cavelight_draw *d, int mode, const cavelight_vertex *v, int count,
                float size);
    void *(*gl_proc)(void *host, const char *name);
    const char *(*last_error)(void *host);
    void (*refuse)(void *host, const char *what); /* a bad argument the library caught */
} app_host_ops;

/* libcavelight's ABI (the host compares it with CAVELIGHT_APP_ABI). */
CAVELIGHT_API int cavelight_library_abi(void);

struct cavelight_app {
    int abi;                     /* CAVELIGHT_APP_ABI */
    cavelight_role role;
    const char *process;         /* "master" or the node's name */
    cavelight_app_desc desc;
    const app_host_ops *ops;
    void *host;
};

#endif
