/* standalone_app: an application in the standalone node (standalone_app.h). */
#include "standalone_app.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app_host.h"
#include "app/session_keys.h"
#include "app_draw.h"
#include "base/xalloc.h"
#include "gi/gi_settings.h"

struct standalone_app {
    const scene *sc;
    glctx *ctx;
    app_host *host;
    app_draw *draw;          /* its points and lines, made at their first call */
    params_schema schema;
    params_store *store;     /* large: on the heap */
    scene_keys objects;
    scene_pose pose;         /* set by its update, persistent like the master's */
    int eye;
};

static int draw_geometry(void *user, const cavelight_draw *d, int mode, const cavelight_vertex *v,
                         int count, float size)
{
    standalone_app *a = user;
    char err[300];
    if (!a->draw && !(a->draw = app_draw_create(glctx_gl(a->ctx), err, sizeof err))) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        return -1;
    }
    app_draw_geometry(a->draw, d, mode, v, count, size);
    return 0;
}

static void *gl_proc(void *user, const char *name)
{
    return (void *)glctx_proc(((standalone_app *)user)->ctx, name);
}

standalone_app *standalone_app_open(const char *path, const scene *sc, glctx *ctx, char *err,
                                    size_t errlen)
{
    standalone_app *a = xcalloc(1, sizeof *a);
    a->sc = sc;
    a->ctx = ctx;
    scene_pose_rest(sc, &a->pose);
    app_host_desc ad = {.path = path, .role = CAVELIGHT_ROLE_NODE, .process = "standalone",
                        .scene = sc, .draw = draw_geometry, .gl_proc = gl_proc, .user = a};
    if (!(a->host = app_host_load(&ad, err, errlen)) || app_host_init(a->host, err, errlen) != 0) {
        standalone_app_close(a);
        return NULL;
    }
    gi_params_schema(&a->schema);
    if (session_keys_add(&a->schema, sc, &a->objects, a->host, err, errlen) != 0) {
        standalone_app_close(a);
        return NULL;
    }
    a->store = xcalloc(1, sizeof *a->store);
    params_init(a->store, &a->schema);
    /* One process: the store it sets is the one it reads. */
    app_host_bind(a->host, a->store, a->store, &a->pose);
    return a;
}

/* renderer_desc.gbuffer_draw: the application's draw for the eye pass under way. */
static void gbuffer_draw(void *user, const frame_view *view, const float vp[16], GLuint fbo, GLuint depth)
{
    standalone_app *a = user;
    cavelight_draw d = {.screen = "window", .eye = a->eye, .width = view->width,
                        .height = view->height, .framebuffer = fbo, .depth_texture = depth};
    memcpy(d.view, view->view, sizeof d.view);
    memcpy(d.projection, view->projection, sizeof d.projection);
    memcpy(d.view_projection, vp, sizeof d.view_projection);
    memcpy(d.eye_position, view->eye_position, sizeof d.eye_position);
    app_host_draw(a->host, &d);
}

void standalone_app_attach(standalone_app *a, renderer *r)
{
    if (app_host_draws(a->host))
        renderer_set_gbuffer_draw(r, gbuffer_draw, a);
}

void standalone_app_step(standalone_app *a, renderer *r, const frame_params *fp, int f)
{
    cavelight_input in = {.frame = (uint64_t)f, .time = fp->time, .dt = 1.0 / 60, .head_valid = 1};
    memcpy(in.head, fp->head, sizeof in.head);
    memcpy(in.wand, fp->wand, sizeof in.wand);
    memcpy(in.navigation, fp->navigation, sizeof in.navigation);
    app_host_update(a->host, &in);
    params_commit(a->store);
    app_host_frame(a->host);
    renderer_set_pose(r, &a->pose);
}

void standalone_app_eye(standalone_app *a, int eye) { a->eye = eye; }

void standalone_app_close(standalone_app *a)
{
    if (!a)
        return;
    app_host_destroy(a->host);
    app_draw_destroy(a->draw);
    free(a->store);
    free(a);
}
