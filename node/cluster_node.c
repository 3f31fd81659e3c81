#include "cluster_node.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/session_keys.h"
#include "base/clock.h"
#include "base/ratelog.h"
#include "base/xalloc.h"
#include "scene/scene_load.h"
#include "cluster_client.h"
#include "cluster_view.h"
#include "cluster/params.h"
#include "gi/gi_settings.h"

/* What the node adds to the built-in keys: the scene's objects and an application's. */
typedef struct node_keys {
    scene own;               /* the scene, when no view loaded it (render none) */
    int own_loaded;
    const scene *sc;
    params_schema schema;
    scene_keys objects;
    scene_pose pose;         /* the frame's, read from the store */
    app_host *app;
} node_keys;

static void node_keys_destroy(node_keys *k)
{
    if (!k)
        return;
    app_host_destroy(k->app);
    if (k->own_loaded)
        scene_free(&k->own);
    free(k);
}

/* The scene (the view's, or loaded here as the master places it), the application (its
 * init runs with the node's GL context current) and the schema of both. */
static node_keys *node_keys_create(const cluster_node_desc *d, cluster_view *view, char *err, size_t errlen)
{
    node_keys *k = xcalloc(1, sizeof *k);
    if (view) {
        k->sc = cluster_view_scene(view);
    } else {
        const char *path = d->scene ? d->scene : d->config->scene[0] ? d->config->scene : "default";
        scene_load_desc sd;
        cluster_config_scene_desc(d->config, &sd);
        if (scene_load_with(path, &sd, &k->own, err, errlen) != 0)
            goto fail;
        k->own_loaded = 1;
        k->sc = &k->own;
    }
    scene_pose_rest(k->sc, &k->pose);
    const char *app = d->app ? d->app : d->config->app[0] ? d->config->app : NULL;
    if (app) {
        app_host_desc ad = {.path = app, .role = CAVELIGHT_ROLE_NODE, .process = d->name, .scene = k->sc,
                            .quiet = d->quiet, .draw = view ? cluster_view_app_draw : NULL,
                            .gl_proc = view ? cluster_view_gl_proc : NULL, .user = view};
        if (!(k->app = app_host_load(&ad, err, errlen)) || app_host_init(k->app, err, errlen) != 0)
            goto fail;
        if (view)
            cluster_view_set_app(view, k->app);
    }
    gi_params_schema(&k->schema);
    if (session_keys_add(&k->schema, k->sc, &k->objects, k->app, err, errlen) != 0)
        goto fail;
    return k;
fail:
    node_keys_destroy(k);
    return NULL;
}

/* The frame's objects and the application's frame, before the node renders it. */
static void node_keys_frame(node_keys *k, const params_store *ps, cluster_view *view)
{
    scene_pose_rest(k->sc, &k->pose);
    scene_keys_read(ps, &k->objects, &k->pose);
    if (k->app)
        app_host_frame(k->app);
    if (view)
        cluster_view_set_pose(view, &k->pose);
}

/* Whatever the master sends is range-checked once, by the renderer (gi_frame_sanitize()),
 * never a reason to stop: the clamped fields are logged, rate-limited. */
static void log_clamped(const cluster_node_desc *d, uint64_t version, int fixed, ratelog *log)
{
    uint64_t skipped = 0;
    if (fixed && ratelog_event(log, clock_now_ms(), &skipped))
        fprintf(stderr, "cavelight-node %s: frame %llu: %d parameters from the master out of range, "
                "clamped (%llu frames so far, %llu not logged)\n", d->name,
                (unsigned long long)version, fixed, (unsigned long long)log->count,
                (unsigned long long)skipped);
}

/* FRAME v: the frame pass and every eye pass (or, without GL, the store's checksum), then
 * READY. */
static int render_frame(const cluster_node_desc *d, cluster_view *view, node_keys *keys, cluster_client *client,
                        const cluster_event *ev, ratelog *range_log, cluster_node_stats *st,
                        char *err, size_t errlen)
{
    double t0 = clock_now_ms();
    const params_store *ps = cluster_client_params(client);
    node_keys_frame(keys, ps, view);
    frame_params f;
    params_to_frame(ps, &f);
    uint64_t checksum = params_checksum(ps);
    float timings[WIRE_TIMING_COUNT] = {0};
    int fixed;
    if (view) {
        if (cluster_view_render(view, &f, &checksum, timings, &fixed, err, errlen) != 0) {
            cluster_client_refuse(client, WIRE_REFUSE_SCENE, ev->version, err, 0);
            return -1;
        }
    } else {
        fixed = gi_frame_sanitize(&f);
    }
    log_clamped(d, ev->version, fixed, range_log);
    if (d->fault_checksum_from && ev->version >= d->fault_checksum_from)
        checksum ^= 0x5a5a5a5a5a5a5a5aull;
    timings[WIRE_TIMING_APPLY] = (float)ev->apply_ms;
    timings[WIRE_TIMING_TOTAL] = (float)(ev->apply_ms + clock_now_ms() - t0);
    cluster_client_ready(client, ev->version, checksum, timings);
    st->frames++;
    st->last_version = ev->version;
    st->last_checksum = checksum;
    return 0;
}

/* A node that cannot take part (no scene, no GL context, no renderer) tells the master why,
 * so that it is in the master's output even when the node runs on another host: it waits
 * up to REFUSE_WAIT_MS for a connection, says REFUSE (never HELLO) and leaves. */
enum { REFUSE_WAIT_MS = 3000 };

static void refuse_session(const cluster_node_desc *d, const char *why)
{
    char ignored[512];
    cluster_client_desc cd = {.config = d->config, .name = d->name, .endpoint = d->endpoint, .quiet = 1,
                              .refuse_only = 1};
    cluster_client *client = cluster_client_create(&cd, ignored, sizeof ignored);
    if (client)
        cluster_client_refuse(client, WIRE_REFUSE_SCENE, 0, why, REFUSE_WAIT_MS);
    cluster_client_destroy(client);
}

/* The lines about losing the master and the end of its session (rate-limited with the
 * client's other lines about the master). */
static void say_link(const cluster_node_desc *d, cluster_client *client, const cluster_event *ev)
{
    char note[96];
    if (!cluster_client_log_link(client, note, sizeof note))
        return;
    if (ev->type == CLUSTER_EVENT_SHUTDOWN)
        fprintf(stderr, "cavelight-node %s: the master ended the session%s%s\n", d->name,
                d->exit_with_master ? "" : "; waiting for it to return", note);
    else if (ev->lost == CLUSTER_LOST_CLOSED)
        fprintf(stderr, "cavelight-node %s: master lost: its connection closed (stopped, killed or "
                "unreachable); keeping the output up, reconnecting when one answers%s\n", d->name, note);
    else
        fprintf(stderr, "cavelight-node %s: master lost: nothing heard for %d ms (timeouts.master_ms; hung "
                "or stopped); keeping the output up, reconnecting%s\n", d->name, d->config->master_timeout_ms,
                note);
}

/* The session: frames, swaps and the link's news until a stop, a refusal, the master's end
 * (with exit_with_master) or the window closing. 1 on an error. */
static int serve(const cluster_node_desc *d, cluster_view *view, node_keys *keys, cluster_client *client,
                 cluster_node_stats *st, char *err, size_t errlen)
{
    int lost_reported = 0;
    uint64_t pending_swap = 0;
    ratelog range_log = {0};
    while (!(d->stop && *d->stop)) {
        cluster_event ev;
        switch (cluster_client_poll(client, 100, &ev)) {
        case CLUSTER_EVENT_FRAME:
            if (render_frame(d, view, keys, client, &ev, &range_log, st, err, errlen) != 0)
                return 1;
            pending_swap = ev.version;
            lost_reported = 0;
            break;
        case CLUSTER_EVENT_SWAP:
            if (ev.version != pending_swap)
                break;
            st->swaps++;
            if (view) {
                int pr = cluster_view_present(view, err, errlen);
                if (pr < 0)
                    return 1;
                if (pr > 0) {
                    if (!d->quiet)
                        fprintf(stderr, "cavelight-node %s: window closed: leaving\n", d->name);
                    return 0;
                }
            }
            break;
        case CLUSTER_EVENT_LOST:
            if (!lost_reported)
                say_link(d, client, &ev);
            lost_reported = 1;
            break;
        case CLUSTER_EVENT_SHUTDOWN:
            say_link(d, client, &ev);
            if (d->exit_with_master)
                return 0;
            break;
        case CLUSTER_EVENT_REFUSED:
            snprintf(err, errlen, "cluster node %s: refused by the master (config hash differs from %s)",
                     d->name, d->config->path);
            return 1;
        default:
            break;
        }
    }
    return 0;
}

int cluster_node_run(const cluster_node_desc *d, cluster_node_stats *stats, char *err, size_t errlen)
{
    cluster_node_stats st = {0};
    int node = cluster_config_find_node(d->config, d->name);
    if (node < 0) {
        snprintf(err, errlen, "cluster node: no node named '%s' in %s: pass one of its node names", d->name,
                 d->config->path);
        return 1;
    }
    /* Scene, context and renderer before connecting: a joined node is ready to render. */
    cluster_view *view = NULL;
    if (d->render == CLUSTER_RENDER_GL) {
        cluster_view_desc vd = {.config = d->config, .node = node,
                                .output = d->output >= 0 ? (cluster_output)d->output : d->config->nodes[node].output,
                                .out_dir = d->out_dir, .scene = d->scene, .threads = d->threads,
                                .keep_frames = d->keep_frames, .show_blend = d->show_blend,
                                .quiet = d->quiet};
        view = cluster_view_create(&vd, err, errlen);
        if (!view) {
            refuse_session(d, err);
            return 1;
        }
    }
    node_keys *keys = node_keys_create(d, view, err, errlen);
    if (!keys) { /* no scene or application: the master hears why */
        refuse_session(d, err);
        cluster_view_destroy(view);
        return 1;
    }
    cluster_client_desc cd = {.config = d->config, .name = d->name, .endpoint = d->endpoint, .quiet = d->quiet,
                              .schema = &keys->schema};
    cluster_client *client = cluster_client_create(&cd, err, errlen);
    if (!client) {
        node_keys_destroy(keys);
        cluster_view_destroy(view);
        return 1;
    }
    if (keys->app)
        app_host_bind(keys->app, cluster_client_params(client), NULL, &keys->pose);
    int rc = serve(d, view, keys, client, &st, err, errlen);
    cluster_client_destroy(client);
    node_keys_destroy(keys); /* the application's shutdown, with the GL context still there */
    cluster_view_destroy(view);
    if (stats)
        *stats = st;
    return rc;
}

static volatile sig_atomic_t node_stop;

static void on_signal(int sig)
{
    (void)sig;
    node_stop = 1;
}

int cluster_node_start(const char *config_path, cluster_node_desc *d)
{
    static cluster_config cfg;
    char err[512];
    if (cluster_config_load(config_path, &cfg, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        return 1;
    }
    if (d->has_scene_transform) {
        cfg.scene_transform = d->scene_transform;
        cfg.has_scene_transform = 1;
    }
    cfg.scene_outside_paths = d->allow_outside_paths;
    d->config = &cfg;
    d->stop = &node_stop;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    cluster_node_stats st;
    if (cluster_node_run(d, &st, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        return 1;
    }
    if (!d->quiet)
        fprintf(stderr, "cavelight-node %s: %llu frames, %llu swaps, last version %llu\n", d->name,
                (unsigned long long)st.frames, (unsigned long long)st.swaps, (unsigned long long)st.last_version);
    return 0;
}
