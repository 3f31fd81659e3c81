/* cavelight-master: runs a cluster session (see docs/cluster.md). */
#define _XOPEN_SOURCE 700 /* realpath */
#include <cjson/cJSON.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/clock.h"
#include "cluster_auth.h"
#include "cluster_master.h"
#include "input.h"
#include "interaction.h"
#include "overview.h"
#include "scene/scene.h"
#include "spawn.h"
#include "script.h"

static volatile sig_atomic_t stop_requested;

static void on_signal(int sig)
{
    (void)sig;
    stop_requested = 1;
}

static void usage(void)
{
    fprintf(stderr,
            "usage: cavelight-master --config FILE [--spawn-local | --spawn-remote] [--bind EP] [--frames N]\n"
            "         [--dt S] [--fps F] [--wait-ms MS] [--report FILE] [--node-exe PATH]\n"
            "         [--render gl|none] [--output window|headless|png] [--out DIR] [--node-args \"...\"]\n"
            "         [--barrier-ms MS] [--scene FILE|default] [--overview FILE.png]\n"
            "         [--endpoint-file FILE] [--input CONFIG|RECORDING] [--quiet]\n"
            "       cavelight-master --config FILE --keygen   (CURVE keys into the config's security.keys)\n");
}

typedef struct options {
    const char *config, *bind, *report, *node_exe, *render, *output, *out_dir, *node_args, *scene, *overview, *endpoint_file, *input;
    int spawn_local, spawn_remote, frames, wait_ms, barrier_ms, quiet, keygen;
    double dt, fps;
} options;

static int parse_args(int argc, char **argv, options *o)
{
    memset(o, 0, sizeof *o);
    o->dt = 1.0 / 30;
    o->wait_ms = 30000;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--spawn-local") == 0) { o->spawn_local = 1; continue; }
        if (strcmp(a, "--spawn-remote") == 0) { o->spawn_remote = 1; continue; }
        if (strcmp(a, "--quiet") == 0) { o->quiet = 1; continue; }
        if (strcmp(a, "--keygen") == 0) { o->keygen = 1; continue; }
        if (!v) {
            fprintf(stderr, "cavelight-master: unknown or incomplete option %s\n", a);
            return -1;
        }
        i++;
        if (strcmp(a, "--config") == 0) o->config = v;
        else if (strcmp(a, "--bind") == 0) o->bind = v;
        else if (strcmp(a, "--report") == 0) o->report = v;
        else if (strcmp(a, "--node-exe") == 0) o->node_exe = v;
        else if (strcmp(a, "--render") == 0) o->render = v;
        else if (strcmp(a, "--output") == 0) o->output = v;
        else if (strcmp(a, "--out") == 0) o->out_dir = v;
        else if (strcmp(a, "--node-args") == 0) o->node_args = v;
        else if (strcmp(a, "--scene") == 0) o->scene = v;
        else if (strcmp(a, "--overview") == 0) o->overview = v;
        else if (strcmp(a, "--endpoint-file") == 0) o->endpoint_file = v;
        else if (strcmp(a, "--input") == 0) o->input = v;
        else if (strcmp(a, "--frames") == 0) o->frames = atoi(v);
        else if (strcmp(a, "--wait-ms") == 0) o->wait_ms = atoi(v);
        else if (strcmp(a, "--barrier-ms") == 0) o->barrier_ms = atoi(v);
        else if (strcmp(a, "--dt") == 0) o->dt = atof(v);
        else if (strcmp(a, "--fps") == 0) o->fps = atof(v);
        else {
            fprintf(stderr, "cavelight-master: unknown option %s\n", a);
            return -1;
        }
    }
    if (!o->config) {
        fprintf(stderr, "cavelight-master: --config FILE is required\n");
        return -1;
    }
    if (o->spawn_local && o->spawn_remote) {
        fprintf(stderr, "cavelight-master: choose one of --spawn-local and --spawn-remote\n");
        return -1;
    }
    return 0;
}

/* The node command line for one node: exe, its options, then --node-args split at spaces. */
static int node_argv(const options *o, const char *config_abs, const char *exe, const char *name,
                     const char *connect, char *storage, size_t cap, char **argv, int max)
{
    int n = 0;
    const char *fixed[] = {exe, "--cluster", config_abs, "--name", name, "--exit-with-master"};
    for (size_t i = 0; i < sizeof fixed / sizeof *fixed; i++)
        argv[n++] = (char *)fixed[i];
    if (connect) {
        argv[n++] = "--master";
        argv[n++] = (char *)connect;
    }
    const char *pairs[][2] = {{"--render", o->render}, {"--output", o->output}, {"--out", o->out_dir},
                              {"--scene", o->scene}};
    for (int i = 0; i < 4; i++)
        if (pairs[i][1]) {
            argv[n++] = (char *)pairs[i][0];
            argv[n++] = (char *)pairs[i][1];
        }
    if (o->quiet)
        argv[n++] = "--quiet";
    if (o->node_args) {
        snprintf(storage, cap, "%s", o->node_args);
        for (char *tok = strtok(storage, " "); tok && n < max - 1; tok = strtok(NULL, " "))
            argv[n++] = tok;
    }
    argv[n] = NULL;
    return n;
}

/* The endpoint spawned nodes connect to when --bind overrides the config: the address
 * actually bound (a wildcard port resolved), with a wildcard host replaced by loopback. */
static const char *connect_endpoint(const cluster_master *m, const char *bind, char *buf, size_t cap)
{
    if (!bind || cluster_master_endpoint(m, buf, cap) != 0)
        return NULL;
    char *any = strstr(buf, "://0.0.0.0:");
    if (any) {
        char port[64];
        snprintf(port, sizeof port, "%s", any + 11);
        snprintf(any, cap - (size_t)(any - buf), "://127.0.0.1:%s", port);
    }
    return buf;
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

enum { MAX_SAMPLES = 100000 };

typedef struct run_stats {
    int n;
    double round_trip[MAX_SAMPLES], barrier[MAX_SAMPLES], frame_bytes[MAX_SAMPLES];
    int node_n[CLUSTER_MAX_NODES];
    double ready_ms[CLUSTER_MAX_NODES][MAX_SAMPLES / 10];
    double pass_sum[CLUSTER_MAX_NODES][WIRE_TIMING_COUNT];
    uint64_t pass_frames[CLUSTER_MAX_NODES];
    uint64_t last_ready[CLUSTER_MAX_NODES];
    int live_min, live_max;
    uint64_t dropped_events;
} run_stats;

static void record(run_stats *rs, cluster_master *m, const cluster_config *cfg, const cluster_frame_result *r)
{
    if (rs->n < MAX_SAMPLES) {
        rs->round_trip[rs->n] = r->round_trip_ms;
        rs->barrier[rs->n] = r->barrier_ms;
        rs->frame_bytes[rs->n] = (double)r->frame_bytes;
        rs->n++;
    }
    if (rs->n == 1 || r->live < rs->live_min)
        rs->live_min = r->live;
    if (r->live > rs->live_max)
        rs->live_max = r->live;
    for (int i = 0; i < cfg->node_count; i++) {
        cluster_peer_stats ps;
        cluster_master_peer_stats(m, i, &ps);
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

static int write_report(const char *path, const cluster_config *cfg, cluster_master *m, run_stats *rs,
                        double wall_s, uint64_t last_version, size_t snapshot_bytes)
{
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
    cJSON_AddNumberToObject(root, "snapshot_bytes", (double)snapshot_bytes);
    cJSON_AddItemToObject(root, "frame_bytes", stat_obj(rs->frame_bytes, rs->n));
    cJSON_AddItemToObject(root, "round_trip_ms", stat_obj(rs->round_trip, rs->n));
    cJSON_AddItemToObject(root, "barrier_wait_ms", stat_obj(rs->barrier, rs->n));
    cJSON *nodes = cJSON_AddArrayToObject(root, "per_node");
    static const char *const pass_names[WIRE_TIMING_COUNT] = {"apply", "frame_pass", "eye_passes", "total"};
    for (int i = 0; i < cfg->node_count; i++) {
        cluster_peer_stats ps;
        cluster_master_peer_stats(m, i, &ps);
        cJSON *n = cJSON_CreateObject();
        cJSON_AddStringToObject(n, "name", cfg->nodes[i].name);
        cJSON_AddStringToObject(n, "state", ps.state == CLUSTER_PEER_LIVE ? "live" :
                                ps.state == CLUSTER_PEER_DROPPED ? "dropped" : "absent");
        cJSON_AddNumberToObject(n, "frames_ready", (double)ps.frames_ready);
        cJSON_AddNumberToObject(n, "joins", ps.joins);
        cJSON_AddNumberToObject(n, "drops", ps.drops);
        char hex[20];
        snprintf(hex, sizeof hex, "%016llx", (unsigned long long)ps.checksum);
        cJSON_AddStringToObject(n, "last_checksum", hex);
        cJSON *pass = cJSON_AddObjectToObject(n, "pass_ms_mean");
        for (int k = 0; k < WIRE_TIMING_COUNT; k++)
            cJSON_AddNumberToObject(pass, pass_names[k], rs->pass_frames[i] ? rs->pass_sum[i][k] / rs->pass_frames[i] : 0);
        cJSON_AddItemToObject(n, "ready_after_frame_ms", stat_obj(rs->ready_ms[i], rs->node_n[i]));
        cJSON_AddItemToArray(nodes, n);
    }
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

static void sleep_until(double t)
{
    double left = t - clock_now_ms();
    if (left <= 0)
        return;
    struct timespec ts = {(time_t)(left / 1000), (long)(fmod(left, 1000.0) * 1e6)};
    nanosleep(&ts, NULL);
}

int main(int argc, char **argv)
{
    options o;
    if (parse_args(argc, argv, &o) != 0) {
        usage();
        return 2;
    }
    static cluster_config cfg;
    char err[1024];
    if (cluster_config_load(o.config, &cfg, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-master: %s\n", err);
        return 1;
    }
    if (o.keygen) {
        if (cluster_keygen(&cfg, err, sizeof err) != 0) {
            fprintf(stderr, "cavelight-master: %s\n", err);
            return 1;
        }
        fprintf(stderr, "cavelight-master: wrote master.key/.pub and one pair per node into %s; give "
                "each host its own .key and master.pub\n", cfg.keys_dir);
        return 0;
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);

    cluster_master_desc md = {.config = &cfg, .bind = o.bind, .barrier_timeout_ms = o.barrier_ms, .quiet = o.quiet};
    cluster_master *m = cluster_master_create(&md, err, sizeof err);
    if (!m) {
        fprintf(stderr, "cavelight-master: %s\n", err);
        return 1;
    }

    if (o.endpoint_file) {
        char ep[256];
        FILE *f = fopen(o.endpoint_file, "w");
        if (!f || cluster_master_endpoint(m, ep, sizeof ep) != 0 || fprintf(f, "%s\n", ep) < 0) {
            fprintf(stderr, "cavelight-master: cannot write %s\n", o.endpoint_file);
            cluster_master_destroy(m);
            return 1;
        }
        fclose(f);
    }
    /* The master holds the scene too: its lights and defaults seed the parameter store. */
    scene sc_start;
    const char *scene_path = o.scene ? o.scene : cfg.scene[0] ? cfg.scene : "default";
    if (scene_load(scene_path, &sc_start, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-master: %s\n", err);
        cluster_master_destroy(m);
        return 1;
    }
    if (sc_start.light_added) {
        char note[400];
        scene_light_added_note(&sc_start, scene_path, note, sizeof note);
        fprintf(stderr, "cavelight-master: warning: %s\n", note);
    }
    frame_params fp;
    frame_params_default(&fp);
    frame_params_lights_from_scene(&fp, &sc_start);
    scene_free(&sc_start);
    params_set_from_frame(cluster_master_params(m), &fp);

    static spawn_set children;
    if (o.spawn_local || o.spawn_remote) {
        char exe[PATH_MAX], config_abs[PATH_MAX], connect_buf[256];
        if (o.node_exe) {
            snprintf(exe, sizeof exe, "%s", o.node_exe);
        } else {
            ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 32);
            exe[n > 0 ? n : 0] = 0;
            char *slash = strrchr(exe, '/');
            snprintf(slash ? slash + 1 : exe, 32, "cavelight-node");
        }
        if (!realpath(o.config, config_abs))
            snprintf(config_abs, sizeof config_abs, "%s", o.config);
        const char *connect = connect_endpoint(m, o.bind, connect_buf, sizeof connect_buf);
        for (int i = 0; i < cfg.node_count; i++) {
            char storage[1024], *nargv[64];
            node_argv(&o, config_abs, exe, cfg.nodes[i].name, connect, storage, sizeof storage, nargv, 64);
            int rc;
            if (o.spawn_local) {
                rc = spawn_local(&children, cfg.nodes[i].name, nargv, err, sizeof err);
            } else {
                /* exec: the node replaces the remote shell, so signals reach it directly. */
                char cmd[4096] = "exec", q[1024];
                for (int k = 0; nargv[k]; k++) {
                    spawn_shell_quote(nargv[k], q, sizeof q);
                    snprintf(cmd + strlen(cmd), sizeof cmd - strlen(cmd), " %s", q);
                }
                rc = spawn_remote(&children, cfg.nodes[i].name, cfg.launch, cfg.nodes[i].host, cmd, err, sizeof err);
            }
            if (rc != 0) {
                fprintf(stderr, "cavelight-master: %s\n", err);
                spawn_stop_all(&children, 2000);
                cluster_master_destroy(m);
                return 1;
            }
        }
    }

    int exit_code = 0;
    /* Wait in short steps so that SIGTERM is honoured while nodes are still missing. */
    int live = 0;
    for (double until = clock_now_ms() + o.wait_ms; !stop_requested && clock_now_ms() < until && live < cfg.node_count;)
        live = cluster_master_wait_nodes(m, cfg.node_count, 200);
    if (live < cfg.node_count)
        fprintf(stderr, "cavelight-master: %d of %d nodes joined within %d ms; going on with them\n", live,
                cfg.node_count, o.wait_ms);
    if (!o.quiet)
        fprintf(stderr, "cavelight-master: %d nodes live, running %s%d frames\n", live,
                o.frames ? "" : "until stopped, ", o.frames);

    static run_stats rs;
    script sc;
    script_init(&sc, &cfg, cluster_master_params(m));
    /* Live or recorded input (docs/input.md) replaces the scripted path. */
    input *in = NULL;
    interaction ia;
    if (o.input) {
        input_desc idesc = {.path = o.input};
        memcpy(idesc.tracker_to_cave, cfg.observer.tracker_to_cave, sizeof idesc.tracker_to_cave);
        if (!(in = input_open(&idesc, err, sizeof err))) {
            fprintf(stderr, "cavelight-master: %s\n", err);
            exit_code = 1;
            stop_requested = 1;
        }
        interaction_init(&ia, &(interaction_desc){0});
    }
    double start = clock_now_ms();
    uint64_t last_version = 0;
    for (int frame = 0; (o.frames == 0 || frame < o.frames) && !stop_requested; frame++) {
        params_store *store = cluster_master_params(m);
        if (in) {
            input_state ist;
            if (input_poll(in, &ist, err, sizeof err) != 0)
                fprintf(stderr, "cavelight-master: %s\n", err); /* a source failed; the others go on */
            if (ist.failed) {
                exit_code = 1; /* a recording with errors is no session to report as done */
                break;
            }
            if (ist.finished)
                break; /* a stepped recording has ended */
            interaction_update(&ia, &ist, ist.dt, &fp);
            fp.time = ist.time;
            fp.reset_epoch = params_get_u32(store, PARAMS_RESET_EPOCH); /* the master owns the epoch */
            params_set_from_frame(store, &fp);
            params_set_i32(store, PARAMS_LPV_RESOLUTION, interaction_pipeline(&ia) ? 64 : 0);
        } else {
            double t = o.dt > 0 ? frame * o.dt : (clock_now_ms() - start) / 1000.0;
            script_apply(&sc, t, store);
        }
        cluster_frame_result r;
        if (cluster_master_frame(m, &r) != 0) {
            fprintf(stderr, "cavelight-master: no node is live; waiting up to %d ms for one\n", o.wait_ms);
            if (cluster_master_wait_nodes(m, 1, o.wait_ms) == 0) {
                fprintf(stderr, "cavelight-master: no node came back: stopping\n");
                exit_code = 1;
                break;
            }
            frame--;
            continue;
        }
        last_version = r.version;
        record(&rs, m, &cfg, &r);
        if (o.fps > 0)
            sleep_until(start + (frame + 1) * 1000.0 / o.fps);
    }
    double wall = (clock_now_ms() - start) / 1000.0;

    /* What a joining node receives: one SNAPSHOT message. */
    static uint8_t snap[PARAMS_ENCODED_MAX], snap_msg[WIRE_MAX_MESSAGE];
    wire_msg sm = {.type = WIRE_SNAPSHOT, .version = last_version, .params = snap};
    sm.params_len = params_encode_snapshot(cluster_master_params(m), snap, sizeof snap);
    size_t snap_bytes = wire_encode(&sm, snap_msg, sizeof snap_msg);
    cluster_master_stats st;
    cluster_master_stats_get(m, &st);
    if (o.report && write_report(o.report, &cfg, m, &rs, wall, last_version, snap_bytes) != 0)
        exit_code = 1;
    if (in)
        input_close(in);
    cluster_master_destroy(m); /* BYE: spawned nodes leave by themselves */
    if (children.count) {
        for (int waited = 0; spawn_reap(&children) > 0 && waited < 10000; waited += 20)
            sleep_until(clock_now_ms() + 20);
        spawn_stop_all(&children, 3000);
        for (int i = 0; i < children.count; i++) {
            int s = children.status[i];
            if (!(WIFEXITED(s) && WEXITSTATUS(s) == 0) && !(WIFSIGNALED(s) && WTERMSIG(s) == SIGTERM)) {
                fprintf(stderr, "cavelight-master: node %s exited abnormally (status %d)\n", children.label[i], s);
            }
        }
    }
    /* After the nodes are gone, every image on disk is from the last frame. */
    if (o.overview) {
        if (overview_compose(&cfg, o.out_dir ? o.out_dir : ".", o.overview, err, sizeof err) != 0) {
            fprintf(stderr, "cavelight-master: %s\n", err);
            exit_code = 1;
        } else if (!o.quiet) {
            fprintf(stderr, "cavelight-master: wrote %s\n", o.overview);
        }
    }
    fprintf(stderr, "cavelight-master: %llu frames in %.2f s, %llu desyncs, %llu drops, %llu joins, "
            "%llu malformed, %llu from unknown peers\n", (unsigned long long)st.frames, wall,
            (unsigned long long)st.desyncs, (unsigned long long)st.drops, (unsigned long long)st.joins,
            (unsigned long long)st.malformed, (unsigned long long)st.unknown_peers);
    return exit_code;
}
