/* app_host: an application (cavelight/app.h) loaded into this process, the master or a
 * render node, and the keys and objects it reaches.
 *
 *   app_host *h = app_host_load(&desc, err, sizeof err);  dlopen, cavelight_app_main()
 *   app_host_init(h, err, sizeof err);                     its init: keys registered
 *   app_host_add_keys(h, &schema, err, sizeof err);        "app.NAME" keys into the schema
 *   app_host_bind(h, &store, &store or NULL, &pose);       where values and objects live
 *   per frame: app_host_update(h, &input)  (master)        its update: sets keys, objects
 *              app_host_frame(h)           (node)          its frame: reads them
 *              app_host_draw(h, &draw)     (node)          its draw, per screen and eye
 *   app_host_destroy(h);                                   its shutdown, dlclose
 *
 * A key or object is set only in update on the master: into the bound store (only changed
 * values are stamped) and the bound pose (the caller writes it to the store,
 * cluster/scene_keys.h). Whatever the application gets wrong (a type, a size, a set outside
 * update, a registration outside init) is refused with one line on stderr naming the
 * application, the call and the valid range, rate limited, never a crash of the process.
 * Memory is bounded: APP_MAX_KEYS keys, strings and blobs within the store's arena.
 * No GL: a node passes its drawing and GL loader in the desc. */
#ifndef CAVELIGHT_APP_HOST_H
#define CAVELIGHT_APP_HOST_H

#include <stddef.h>

#include "app/app_abi.h"
#include "cluster/params.h"
#include "scene/scene_pose.h"

enum { APP_MAX_KEYS = 128, APP_DRAW_MAX_VERTICES = 1 << 22 };

typedef struct app_host app_host;

typedef struct app_host_desc {
    const char *path;            /* the application's shared object */
    cavelight_role role;
    const char *process;         /* "master" or the node's name (messages, the app) */
    const scene *scene;          /* its objects; must outlive the host */
    int quiet;                   /* 1: no line when loaded */
    /* A node's: the drawing helpers and GL loader (NULL on the master: refused). */
    int (*draw)(void *user, const cavelight_draw *d, int mode, const cavelight_vertex *v, int count,
                float size);
    void *(*gl_proc)(void *user, const char *name);
    void *user;
} app_host_desc;

/* Returns NULL with one line in err: the file cannot be loaded, has no
 * cavelight_app_main(), or was built for another API or library ABI. */
app_host *app_host_load(const app_host_desc *desc, char *err, size_t errlen);
/* Runs init; returns 0, or -1 with one line in err when a key it registered was refused
 * (the session must not start with half its keys). */
int app_host_init(app_host *h, char *err, size_t errlen);
/* Adds the registered keys to schema (after the scene's); -1 with one line in err. */
int app_host_add_keys(app_host *h, params_schema *schema, char *err, size_t errlen);
/* The store the keys are read from, the one they are set in (the master's; NULL on a
 * node) and the objects' pose. */
void app_host_bind(app_host *h, const params_store *store, params_store *writable, scene_pose *pose);
void app_host_update(app_host *h, const cavelight_input *in);
void app_host_frame(app_host *h);
/* Whether the application draws (has a draw callback). */
int app_host_draws(const app_host *h);
void app_host_draw(app_host *h, const cavelight_draw *d);
/* The buttons the application takes from the interaction layouts (its desc.buttons). */
uint32_t app_host_buttons(const app_host *h);
/* The application's name (desc.name or the file's). */
const char *app_host_name(const app_host *h);
/* Calls shutdown, unloads. NULL is fine. */
void app_host_destroy(app_host *h);

#endif
