#include "session.h"
#include "base/xalloc.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/session_keys.h"
#include "base/clock.h"
#include "gi/gi_settings.h"
#include "grab.h"
#include "input/input.h"
#include "input/input_config.h"
#include "interaction.h"
#include "pose_guard.h"
#include "frame/exposure.h"
#include "gi/gi_cost.h"
#include "gi/gi_settings.h"
#include "gi/gi_budget.h"
#include "scene/scene_load.h"
#include "script.h"

enum { MAX_SAMPLES = 100000 };

/* What the report is made of, gathered frame by frame. */
typedef struct run_stats {
    int n;
    double round_trip[MAX_SAMPLES], barrier[MAX_SAMPLES], frame_bytes[MAX_SAMPLES], timeout[MAX_SAMPLES];
    double nodes_wait_ms;   /* bound to the first wait for nodes ending (-1: not yet) */
    int node_n[CLUSTER_MAX_NODES];
    double ready_ms[CLUSTER_MAX_NODES][MAX_SAMPLES / 10];
    double pass_sum[CLUSTER_MAX_NODES][WIRE_TIMING_COUNT];
    uint64_t pass_frames[CLUSTER_MAX_NODES];
    uint64_t last_ready[CLUSTER_MAX_NODES];
    int live_min, live_max;
} run_stats;

struct session {
    const cluster_config *cfg;
    cluster_master *m;
    frame_params frame;     /* what the input and interaction edit (live input only) */
    script script;
    input *in;              /* NULL: the scripted path */
    pose_guard guard;       /* tracked poses checked before they reach the nodes */
    int print_poses;
    double next_pose_print; /* clock_now_ms() */
    interaction ia;
    scene scene;            /* its objects, their animations, what the grab picks */
    params_schema schema;   /* the built-in keys, the objects', the application's */
    scene_keys objects;
    scene_pose pose;        /* where the objects are: animations, grab, application */
    grab grab;
    app_host *app;          /* NULL: no application */
    double dt, start_ms, created_ms;
    int frames;
    uint64_t last_version;
    run_stats rs;
    float bounds_min[3], bounds_max[3]; /* the scene's */
    double budget_ms;                   /* > 0: the budget chose the method's settings */
    int budget_frames;                  /* its measuring frames */
    gi_budget_choice budget;
};

/* The scene as every node places it, the application (its init registers its keys) and
 * the schema of both, before the store exists. */
static int load_scene_and_app(session *s, const char *scene_path, const session_desc *d, char *err,
                              size_t errlen)
{
    scene_load_desc sd;
    cluster_config_scene_desc(s->cfg, &sd); /* as every node places it */
    if (scene_load_with(scene_path, &sd, &s->scene, err, errlen) != 0)
        return -1;
    if (d->app) {
        app_host_desc ad = {.path = d->app, .role = CAVELIGHT_ROLE_MASTER, .process = "master",
                            .scene = &s->scene, .quiet = d->quiet};
        if (!(s->app = app_host_load(&ad, err, errlen)) || app_host_init(s->app, err, errlen) != 0)
            return -1;
    }
    gi_params_schema(&s->schema);
    return session_keys_add(&s->schema, &s->scene, &s->objects, s->app, err, errlen);
}

/* The nodes' limits on what the GI settings cost (gi_cost.h), checked as they check them:
 * settings they would refuse are refused here, before any node starts. */
static int check_limits(session *s, char *err, size_t errlen)
{
    gi_limits lim = {.memory_mb = s->cfg->gi_memory_mb};
    frame_params_default(&lim.base);
    char why[256];
    if (gi_set_config(s->cfg, &lim.base, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s", why);
        return -1;
    }
    memcpy(lim.bounds_min, s->bounds_min, sizeof lim.bounds_min);
    memcpy(lim.bounds_max, s->bounds_max, sizeof lim.bounds_max);
    if (gi_cost_within(&lim, &s->frame, why, sizeof why))
        return 0;
    snprintf(err, errlen, "%s: every node would refuse it; give heavier settings in the config's \"settings\", "
             "which sets up the wall", why);
    return -1;
}

/* The frame every node starts from: the defaults and the scene's lights. */
static int seed(session *s, const char *scene_path, const session_desc *d, char *err,
                size_t errlen)
{
    const scene sc = s->scene;
    if (sc.warning[0]) /* the nodes load it too; the master says it once */
        fprintf(stderr, "cavelight-master: warning: scene %s: %s\n", scene_path, sc.warning);
    char note[400];
    if (scene_light_note(&sc, scene_path, note, sizeof note))
        fprintf(stderr, "cavelight-master: warning: %s\n", note);
    if (d->settings)
        s->frame = *d->settings;
    else
        frame_params_default(&s->frame);
    frame_params_lights_from_scene(&s->frame, &sc);
    s->frame.pattern = d->pattern;
    script_init(&s->script, d->config);
    if (d->exposure_auto) {
        /* The lights of the first frame: the scripted path's lamp when it plays. */
        frame_params first = s->frame;
        if (!d->input)
            script_frame(&s->script, 0.0, &first);
        s->frame.exposure = exposure_from_light(&first, &sc);
        if (!d->quiet)
            fprintf(stderr, "cavelight-master: exposure %.3g from the scene's light\n", s->frame.exposure);
    }
    memcpy(s->bounds_min, sc.bounds_min, sizeof s->bounds_min);
    memcpy(s->bounds_max, sc.bounds_max, sizeof s->bounds_max);
    scene_pose_rest(&s->scene, &s->pose);
    params_set_from_frame(cluster_master_params(s->m), &s->frame);
    /* The nodes' own check, before any node is started: a scene no node can take is
     * refused here, not reported as a session of frames nobody rendered. */
    char why[300];
    if (cluster_master_check_params(s->m, why, sizeof why) != 0) {
        snprintf(err, errlen, "scene %s: %s; check its size and its lights", scene_path, why);
        return -1;
    }
    return check_limits(s, err, errlen);
}

static void input_warning(void *user, const char *line)
{
    if (!((const session_desc *)user)->quiet)
        fprintf(stderr, "cavelight-master: warning: %s\n", line);
}

session *session_create(const session_desc *d, char *err, size_t errlen)
{
    session *s = xcalloc(1, sizeof *s); /* large (the statistics): never on the stack */
    s->cfg = d->config;
    s->dt = d->dt;
    s->print_poses = d->print_poses;
    cluster_master_desc md = {.config = d->config, .bind = d->bind,
                              .barrier_timeout_ms = d->barrier_ms, .quiet = d->quiet,
                              .insecure_anywhere = d->insecure_anywhere, .schema = &s->schema};
    const char *scene_path = d->scene ? d->scene : d->config->scene[0] ? d->config->scene : "default";
    if (load_scene_and_app(s, scene_path, d, err, errlen) != 0 ||
        !(s->m = cluster_master_create(&md, err, errlen)) || seed(s, scene_path, d, err, errlen) != 0)
        goto fail;
    if (s->app)
        app_host_bind(s->app, cluster_master_params(s->m), cluster_master_params(s->m), &s->pose);
    grab_init(&s->grab);
    s->created_ms = clock_now_ms();
    s->rs.nodes_wait_ms = -1;
    if (d->input) {
        input_desc idesc = {.path = d->input, .record_path = d->record, .out_dir = d->out_dir,
                            .strict = d->strict, .warn = input_warning, .warn_user = (void *)d};
        memcpy(idesc.tracker_to_cave, d->config->observer.tracker_to_cave,
               sizeof idesc.tracker_to_cave);
        if (!(s->in = input_open(&idesc, err, errlen)))
            goto fail;
        interaction_init(&s->ia, &(interaction_desc){.grab = s->scene.object_count > 0});
        pose_guard_init(&s->guard, d->config);
    }
    return s;
fail:
    session_destroy(s);
    return NULL;
}

void session_destroy(session *s)
{
    if (!s)
        return;
    if (s->in)
        input_close(s->in);
    if (s->m)
        cluster_master_destroy(s->m);
    app_host_destroy(s->app);
    scene_free(&s->scene);
    free(s);
}

cluster_master *session_master(session *s) { return s->m; }
int session_frames(const session *s) { return s->frames; }
uint64_t session_last_version(const session *s) { return s->last_version; }

int session_wait_nodes(session *s, int count, int timeout_ms, volatile sig_atomic_t *stop)
{
    int live = cluster_master_live_count(s->m);
    for (double until = clock_now_ms() + timeout_ms;
         !(stop && *stop) && clock_now_ms() < until && live < count;)
        live = cluster_master_wait_nodes(s->m, count, 200);
    if (s->rs.nodes_wait_ms < 0)
        s->rs.nodes_wait_ms = clock_now_ms() - s->created_ms;
    return live;
}

/* A CAVE-space point back in tracker space: the inverse of tracker_to_cave (a rotation
 * times a uniform scale, then a translation): M^T (p - t) / s^2. */
static void cave_to_tracker(const float m[16], const float p[3], double out[3])
{
    double s2 = (double)m[0] * m[0] + (double)m[1] * m[1] + (double)m[2] * m[2];
    for (int c = 0; c < 3; c++) {
        out[c] = 0;
        for (int r = 0; r < 3; r++)
            out[c] += (double)m[c * 4 + r] * (p[r] - m[12 + r]);
        out[c] /= s2;
    }
}

/* One line on stdout per PRINT_POSES_MS: what a person measuring corners or the
 * tracker-to-CAVE transform reads (docs/calibration.md). */
static void print_poses(session *s, const input_state *ist)
{
    enum { PRINT_POSES_MS = 250 };
    double now = clock_now_ms();
    if (now < s->next_pose_print)
        return;
    s->next_pose_print = now + PRINT_POSES_MS;
    const float *m = s->cfg->observer.tracker_to_cave;
    const input_pose *pose[2] = {&ist->head, &ist->wand};
    printf("t %.2f", ist->time);
    for (int k = 0; k < 2; k++) {
        const input_pose *p = pose[k];
        if (!p->valid) {
            printf("  %s -", k ? "wand" : "head");
            continue;
        }
        double tr[3];
        cave_to_tracker(m, p->position, tr);
        /* The pointing direction: -Z of the pose, in CAVE space. */
        printf("  %s cave %.4f %.4f %.4f tracker %.4f %.4f %.4f dir %.3f %.3f %.3f", k ? "wand" : "head",
               p->position[0], p->position[1], p->position[2], tr[0], tr[1], tr[2], 0.0f - p->rotation[6],
               0.0f - p->rotation[7], 0.0f - p->rotation[8]); /* 0 - x: no "-0.000" */
    }
    printf("  buttons %02x\n", (unsigned)ist->buttons);
    fflush(stdout);
}

/* The session's frame into the store: only the keys whose values changed get the new
 * version. */
static void publish(session *s, params_store *store)
{
    s->frame.reset_epoch = params_get_u32(store, PARAMS_RESET_EPOCH); /* the master owns it */
    params_set_from_frame(store, &s->frame);
    scene_keys_write(store, &s->objects, &s->pose);
}

/* What the application's update gets: the merged input, or the scripted head (no wand,
 * no buttons) when there is none. */
static void app_input(const session *s, const input_state *ist, cavelight_input *in)
{
    memset(in, 0, sizeof *in);
    in->frame = (uint64_t)s->frames;
    in->time = s->frame.time;
    in->dt = s->in ? ist->dt : s->dt;
    memcpy(in->head, s->frame.head, sizeof in->head);
    memcpy(in->wand, s->frame.wand, sizeof in->wand);
    memcpy(in->navigation, s->frame.navigation, sizeof in->navigation);
    in->head_valid = !s->in || ist->head.valid;
    in->wand_valid = s->in && ist->wand.valid;
    if (s->in) {
        in->buttons = ist->buttons;
        in->pressed = ist->pressed;
        memcpy(in->axes, ist->axes, sizeof in->axes);
    }
}

/* The objects, in this order: the file's animations by the session's clock, the wand's
 * grab, the application (which sees and may override both). */
static void move_objects(session *s, const input_state *ist)
{
    scene_pose_animate(&s->scene, s->frame.time, &s->pose);
    if (s->in)
        grab_update(&s->grab, &s->scene, &s->pose, &s->frame, ist, s->ia.layout == INTERACTION_GRAB);
    if (s->app) {
        cavelight_input in;
        app_input(s, ist, &in);
        app_host_update(s->app, &in);
    }
}

/* Live or recorded input through the interaction layouts into the session's frame. Returns
 * SESSION_FRAME_DONE (go on), SESSION_INPUT_ENDED or SESSION_INPUT_FAILED. */
static session_step apply_input(session *s, input_state *out)
{
    input_state ist;
    char err[1024];
    if (input_poll(s->in, &ist, err, sizeof err) != 0)
        fprintf(stderr, "cavelight-master: %s\n", err); /* a warning or notice; the session goes on */
    if (ist.failed)
        return SESSION_INPUT_FAILED;
    if (ist.finished)
        return SESSION_INPUT_ENDED;
    double now = clock_now_ms();
    pose_guard_apply(&s->guard, &s->guard.head, &ist.head, now);
    pose_guard_apply(&s->guard, &s->guard.wand, &ist.wand, now);
    if (s->print_poses)
        print_poses(s, &ist);
    input_state layouts = ist; /* without the buttons the application takes */
    layouts.buttons &= ~app_host_buttons(s->app);
    layouts.pressed &= ~app_host_buttons(s->app);
    interaction_update(&s->ia, &layouts, ist.dt, &s->frame);
    s->frame.time = ist.time;
    *out = ist;
    return SESSION_FRAME_DONE;
}

static void record(session *s, const cluster_frame_result *r)
{
    run_stats *rs = &s->rs;
    if (rs->n < MAX_SAMPLES) {
        rs->round_trip[rs->n] = r->round_trip_ms;
        rs->barrier[rs->n] = r->barrier_ms;
        rs->frame_bytes[rs->n] = (double)r->frame_bytes;
        rs->timeout[rs->n] = r->timeout_ms;
        rs->n++;
    }
    if (rs->n == 1 || r->live < rs->live_min)
        rs->live_min = r->live;
    if (r->live > rs->live_max)
        rs->live_max = r->live;
    for (int i = 0; i < s->cfg->node_count; i++) {
        cluster_peer_stats ps;
        cluster_master_peer_stats(s->m, i, &ps);
        if (ps.frames_ready == rs->last_ready[i])
            continue;
        rs->last_ready[i] = ps.frames_ready;
        if (rs->node_n[i] < MAX_SAMPLES / 10)
            rs->ready_ms[i][rs->node_n[i]++] = ps.ready_ms;
        for (int k = 0; k < WIRE_TIMING_COUNT; k++)
            rs->pass_sum[i][k] += ps.timings[k];
        rs->pass_frames[i]++;
    }
}

session_step session_frame(session *s, cluster_frame_result *result)
{
    params_store *store = cluster_master_params(s->m);
    if (s->frames == 0 && s->start_ms == 0)
        s->start_ms = clock_now_ms();
    input_state ist;
    memset(&ist, 0, sizeof ist);
    if (s->in) {
        session_step step = apply_input(s, &ist);
        if (step != SESSION_FRAME_DONE)
            return step;
    } else {
        double t = s->dt > 0 ? s->frames * s->dt : (clock_now_ms() - s->start_ms) / 1000.0;
        script_frame(&s->script, t, &s->frame);
    }
    move_objects(s, &ist);
    publish(s, store);
    if (cluster_master_frame(s->m, result) != 0)
        return SESSION_NO_NODES;
    s->frames++;
    s->last_version = result->version;
    record(s, result);
    return SESSION_FRAME_DONE;
}

/* One measuring frame of the budget plan on every live node: the slowest frame pass of the
 * nodes that were READY in time, or -1 when none was. */
static double budget_frame(session *s, const frame_params *f)
{
    params_store *store = cluster_master_params(s->m);
    frame_params g = *f;
    g.reset_epoch = params_get_u32(store, PARAMS_RESET_EPOCH);
    params_set_from_frame(store, &g);
    cluster_frame_result r;
    if (cluster_master_frame(s->m, &r) != 0)
        return -1;
    double slowest = -1;
    for (int i = 0; i < s->cfg->node_count; i++) {
        cluster_peer_stats ps;
        cluster_master_peer_stats(s->m, i, &ps);
        if (ps.state == CLUSTER_PEER_LIVE && ps.version == r.version)
            slowest = fmax(slowest, ps.timings[WIRE_TIMING_FRAME]);
    }
    return slowest;
}

int session_choose_budget(session *s, double budget_ms, volatile sig_atomic_t *stop, char *err, size_t errlen)
{
    gi_budget_plan *plan = gi_budget_plan_create(&s->frame, s->bounds_min, s->bounds_max);
    int rc = 0, frames = gi_budget_plan_frames(plan);
    for (int i = 0; rc == 0 && i < frames; i++) {
        frame_params f;
        gi_budget_plan_frame(plan, i, &f);
        double ms = stop && *stop ? -1 : budget_frame(s, &f);
        if (ms < 0) {
            snprintf(err, errlen, "--budget-ms: no node was ready in measuring frame %d of %d", i + 1,
                     frames);
            rc = -1;
        }
        gi_budget_plan_record(plan, i, ms);
    }
    char why[256];
    if (rc == 0 && gi_budget_plan_choose(plan, budget_ms, &s->frame, &s->budget, why, sizeof why) != 0) {
        snprintf(err, errlen, "--budget-ms: %s", why);
        rc = -1;
    }
    gi_budget_plan_destroy(plan);
    if (rc != 0)
        return -1;
    /* Every node starts the chosen lattice afresh, whatever the plan left in its history. */
    params_store *store = cluster_master_params(s->m);
    params_set_u32(store, PARAMS_RESET_EPOCH, params_get_u32(store, PARAMS_RESET_EPOCH) + 1);
    s->budget_ms = budget_ms;
    s->budget_frames = frames;
    const gi_budget_choice *c = &s->budget;
    fprintf(stderr, "cavelight-master: budget %.3g ms: %s, predicted %.3g ms per frame on the "
            "slowest node%s\n", budget_ms, c->summary, c->predicted_ms,
            c->fits ? "" : ", over budget even at the cheapest choice");
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double percentile(double *v, int n, double p)
{
    if (n <= 0)
        return 0;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    int i = (int)ceil(p * n) - 1;
    return v[i < 0 ? 0 : i >= n ? n - 1 : i];
}

static cJSON *stat_obj(double *v, int n)
{
    cJSON *o = cJSON_CreateObject();
    double sum = 0;
    for (int i = 0; i < n; i++)
        sum += v[i];
    cJSON_AddNumberToObject(o, "mean", n ? sum / n : 0);
    cJSON_AddNumberToObject(o, "median", percentile(v, n, 0.5));
    cJSON_AddNumberToObject(o, "p99", percentile(v, n, 0.99));
    cJSON_AddNumberToObject(o, "max", n ? v[n - 1] : 0);
    return o;
}

/* What a joining node receives: one SNAPSHOT message of the whole store. */
static size_t snapshot_bytes(session *s)
{
    static uint8_t snap[PARAMS_ENCODED_MAX], msg[WIRE_MAX_MESSAGE]; /* 115 KB: not on the stack */
    wire_msg sm = {.type = WIRE_SNAPSHOT, .version = s->last_version, .params = snap};
    sm.params_len = params_encode_snapshot(cluster_master_params(s->m), snap, sizeof snap);
    return wire_encode(&sm, msg, sizeof msg);
}

/* The report's per_node[i]. */
static cJSON *node_report(session *s, int i)
{
    static const char *const pass_names[WIRE_TIMING_COUNT] = {"apply", "frame_pass", "eye_passes", "total"};
    run_stats *rs = &s->rs;
    cluster_peer_stats ps;
    cluster_master_peer_stats(s->m, i, &ps);
    cJSON *n = cJSON_CreateObject();
    cJSON_AddStringToObject(n, "name", s->cfg->nodes[i].name);
    cJSON_AddStringToObject(n, "state", ps.state == CLUSTER_PEER_LIVE ? "live" :
                            ps.state == CLUSTER_PEER_DROPPED ? "dropped" : "absent");
    cJSON_AddNumberToObject(n, "frames_ready", (double)ps.frames_ready);
    cJSON_AddNumberToObject(n, "joins", ps.joins);
    cJSON_AddNumberToObject(n, "drops", ps.drops);
    cJSON_AddNumberToObject(n, "refusals", ps.refusals);
    cJSON_AddStringToObject(n, "last_refusal", ps.refusal);
    char hex[20];
    snprintf(hex, sizeof hex, "%016llx", (unsigned long long)ps.checksum);
    cJSON_AddStringToObject(n, "last_checksum", hex);
    cJSON *pass = cJSON_AddObjectToObject(n, "pass_ms_mean");
    for (int k = 0; k < WIRE_TIMING_COUNT; k++)
        cJSON_AddNumberToObject(pass, pass_names[k], rs->pass_frames[i] ? rs->pass_sum[i][k] / rs->pass_frames[i] : 0);
    cJSON_AddItemToObject(n, "ready_after_frame_ms", stat_obj(rs->ready_ms[i], rs->node_n[i]));
    return n;
}

/* root printed to path, and freed. */
static int write_report(cJSON *root, const char *path)
{
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    FILE *f = text ? fopen(path, "w") : NULL;
    int ok = f && fputs(text, f) >= 0 && fputc('\n', f) != EOF;
    if (f && fclose(f) != 0)
        ok = 0;
    free(text);
    if (!ok)
        fprintf(stderr, "cavelight-master: cannot write report %s: %s\n", path, strerror(errno));
    return ok ? 0 : -1;
}

int session_write_report(session *s, const char *path, double wall_s)
{
    const cluster_config *cfg = s->cfg;
    cluster_master *m = s->m;
    run_stats *rs = &s->rs;
    uint64_t last_version = s->last_version;
    size_t snap_bytes = snapshot_bytes(s);
    cluster_master_stats st;
    cluster_master_stats_get(m, &st);
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "config", cfg->path);
    cJSON_AddNumberToObject(root, "frames", (double)st.frames);
    cJSON_AddNumberToObject(root, "last_version", (double)last_version);
    cJSON_AddNumberToObject(root, "wall_seconds", wall_s);
    cJSON_AddNumberToObject(root, "nodes_configured", cfg->node_count);
    cJSON_AddNumberToObject(root, "nodes_live_min", rs->live_min);
    cJSON_AddNumberToObject(root, "nodes_live_max", rs->live_max);
    cJSON_AddNumberToObject(root, "desyncs", (double)st.desyncs);
    cJSON_AddNumberToObject(root, "joins", (double)st.joins);
    cJSON_AddNumberToObject(root, "drops", (double)st.drops);
    cJSON_AddNumberToObject(root, "malformed_messages", (double)st.malformed);
    cJSON_AddNumberToObject(root, "unknown_peer_messages", (double)st.unknown_peers);
    cJSON_AddNumberToObject(root, "refused_connections", (double)st.refused);
    cJSON_AddNumberToObject(root, "bytes_sent", (double)st.bytes_sent);
    cJSON_AddNumberToObject(root, "bytes_received", (double)st.bytes_received);
    cJSON_AddNumberToObject(root, "messages_sent", (double)st.messages_sent);
    cJSON_AddNumberToObject(root, "snapshot_bytes", (double)snap_bytes);
    cJSON_AddItemToObject(root, "frame_bytes", stat_obj(rs->frame_bytes, rs->n));
    cJSON_AddItemToObject(root, "round_trip_ms", stat_obj(rs->round_trip, rs->n));
    cJSON_AddItemToObject(root, "barrier_wait_ms", stat_obj(rs->barrier, rs->n));
    cJSON_AddItemToObject(root, "stall_timeout_ms", stat_obj(rs->timeout, rs->n));
    cJSON_AddNumberToObject(root, "nodes_wait_ms", rs->nodes_wait_ms);
    if (s->budget_ms > 0) {
        cJSON *b = cJSON_AddObjectToObject(root, "budget");
        cJSON_AddNumberToObject(b, "budget_ms", s->budget_ms);
        cJSON_AddNumberToObject(b, "frames", s->budget_frames); /* measuring, among "frames" */
        for (int i = 0; i < s->budget.figure_count; i++)
            cJSON_AddNumberToObject(b, s->budget.figure[i].name, s->budget.figure[i].value);
        cJSON_AddNumberToObject(b, "predicted_ms", s->budget.predicted_ms);
        cJSON_AddBoolToObject(b, "fits", s->budget.fits);
    }
    cJSON_AddNumberToObject(root, "disconnects", (double)st.disconnects);
    cJSON_AddNumberToObject(root, "handshakes_failed", (double)st.handshakes_failed);
    cJSON_AddNumberToObject(root, "frames_rendered", (double)st.frames_rendered);
    cJSON_AddNumberToObject(root, "refusals", (double)st.refusals);
    cJSON_AddNumberToObject(root, "unauthenticated_dropped", (double)st.unauthenticated_dropped);
    cJSON_AddNumberToObject(root, "accept_failures", (double)st.accept_failures);
    cJSON_AddNumberToObject(root, "fd_limit", (double)st.fd_limit);
    cJSON *nodes = cJSON_AddArrayToObject(root, "per_node");
    for (int i = 0; i < cfg->node_count; i++)
        cJSON_AddItemToArray(nodes, node_report(s, i));
    return write_report(root, path);
}
