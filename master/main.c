/* cavelight-master: runs a cluster session (see docs/cluster.md). */
#define _XOPEN_SOURCE 700 /* realpath */
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
#include "overview.h"
#include "session.h"
#include "spawn.h"

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
            "         [--endpoint-file FILE] [--input CONFIG|RECORDING] [--gi " FRAME_GI_NAMES "] [--vpl-count N] [--quiet]\n"
            "       cavelight-master --config FILE --keygen   (CURVE keys into the config's security.keys)\n");
}

typedef struct options {
    const char *config, *bind, *report, *node_exe, *render, *output, *out_dir, *node_args, *scene, *overview, *endpoint_file, *input, *gi;
    int spawn_local, spawn_remote, frames, wait_ms, barrier_ms, quiet, keygen, vpl_count;
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
        else if (strcmp(a, "--gi") == 0) o->gi = v;
        else if (strcmp(a, "--vpl-count") == 0) o->vpl_count = atoi(v);
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
                              {"--scene", o->scene}, {"--gi", o->gi}};
    for (int i = 0; i < 5; i++)
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

static void sleep_until(double t)
{
    double left = t - clock_now_ms();
    if (left <= 0)
        return;
    struct timespec ts = {(time_t)(left / 1000), (long)(fmod(left, 1000.0) * 1e6)};
    nanosleep(&ts, NULL);
}

static int write_endpoint_file(cluster_master *m, const char *path)
{
    char ep[256];
    FILE *f = fopen(path, "w");
    int ok = f && cluster_master_endpoint(m, ep, sizeof ep) == 0 && fprintf(f, "%s\n", ep) >= 0;
    if (f && fclose(f) != 0)
        ok = 0;
    if (!ok)
        fprintf(stderr, "cavelight-master: cannot write %s\n", path);
    return ok ? 0 : -1;
}

/* One node per configured node: a local child, or the config's launch command. */
static int spawn_nodes(const options *o, const cluster_config *cfg, cluster_master *m,
                       spawn_set *children)
{
    char exe[PATH_MAX], config_abs[PATH_MAX], connect_buf[256], err[1024];
    if (o->node_exe) {
        snprintf(exe, sizeof exe, "%s", o->node_exe);
    } else {
        ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 32);
        exe[n > 0 ? n : 0] = 0;
        char *slash = strrchr(exe, '/');
        snprintf(slash ? slash + 1 : exe, 32, "cavelight-node");
    }
    if (!realpath(o->config, config_abs))
        snprintf(config_abs, sizeof config_abs, "%s", o->config);
    const char *connect = connect_endpoint(m, o->bind, connect_buf, sizeof connect_buf);
    for (int i = 0; i < cfg->node_count; i++) {
        char storage[1024], *nargv[64];
        node_argv(o, config_abs, exe, cfg->nodes[i].name, connect, storage, sizeof storage, nargv, 64);
        int rc;
        if (o->spawn_local) {
            rc = spawn_local(children, cfg->nodes[i].name, nargv, err, sizeof err);
        } else {
            /* exec: the node replaces the remote shell, so signals reach it directly. */
            char cmd[4096] = "exec", q[1024];
            for (int k = 0; nargv[k]; k++) {
                spawn_shell_quote(nargv[k], q, sizeof q);
                snprintf(cmd + strlen(cmd), sizeof cmd - strlen(cmd), " %s", q);
            }
            rc = spawn_remote(children, cfg->nodes[i].name, cfg->launch, cfg->nodes[i].host, cmd,
                              err, sizeof err);
        }
        if (rc != 0) {
            fprintf(stderr, "cavelight-master: %s\n", err);
            return -1;
        }
    }
    return 0;
}

/* --frames frames (0: until stopped), paced at --fps. Returns 0, or 1 when every node is
 * gone for --wait-ms. */
static int run_frames(session *s, const options *o, double *wall_s)
{
    double start = clock_now_ms();
    int rc = 0;
    while ((o->frames == 0 || session_frames(s) < o->frames) && !stop_requested) {
        cluster_frame_result r;
        session_step step = session_frame(s, &r);
        if (step == SESSION_INPUT_ENDED)
            break;
        if (step == SESSION_INPUT_FAILED) {
            rc = 1; /* a recording with errors is no session to report as done */
            break;
        }
        if (step == SESSION_NO_NODES) {
            fprintf(stderr, "cavelight-master: no node is live; waiting up to %d ms for one\n", o->wait_ms);
            if (session_wait_nodes(s, 1, o->wait_ms, &stop_requested) == 0) {
                fprintf(stderr, "cavelight-master: no node came back: stopping\n");
                rc = 1;
                break;
            }
            continue;
        }
        if (o->fps > 0)
            sleep_until(start + session_frames(s) * 1000.0 / o->fps);
    }
    *wall_s = (clock_now_ms() - start) / 1000.0;
    return rc;
}

/* Spawned nodes leave by themselves after BYE; whatever is left gets SIGTERM. */
static void stop_children(spawn_set *children)
{
    if (!children->count)
        return;
    for (int waited = 0; spawn_reap(children) > 0 && waited < 10000; waited += 20)
        sleep_until(clock_now_ms() + 20);
    spawn_stop_all(children, 3000);
    for (int i = 0; i < children->count; i++) {
        int st = children->status[i];
        if (!(WIFEXITED(st) && WEXITSTATUS(st) == 0) && !(WIFSIGNALED(st) && WTERMSIG(st) == SIGTERM))
            fprintf(stderr, "cavelight-master: node %s exited abnormally (status %d)\n",
                    children->label[i], st);
    }
}

static void print_summary(const cluster_master_stats *st, double wall_s)
{
    fprintf(stderr, "cavelight-master: %llu frames in %.2f s, %llu desyncs, %llu drops, %llu joins, "
            "%llu malformed, %llu from unknown peers\n", (unsigned long long)st->frames, wall_s,
            (unsigned long long)st->desyncs, (unsigned long long)st->drops, (unsigned long long)st->joins,
            (unsigned long long)st->malformed, (unsigned long long)st->unknown_peers);
}

static void handle_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);
}

static int keygen(const cluster_config *cfg)
{
    char err[1024];
    if (cluster_keygen(cfg, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-master: %s\n", err);
        return 1;
    }
    fprintf(stderr, "cavelight-master: wrote master.key/.pub and one pair per node into %s; give "
            "each host its own .key and master.pub\n", cfg->keys_dir);
    return 0;
}

static int master_run(const options *o)
{
    static cluster_config cfg;
    static spawn_set children;
    char err[1024];
    if (cluster_config_load(o->config, &cfg, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-master: %s\n", err);
        return 1;
    }
    if (o->keygen)
        return keygen(&cfg);
    handle_signals();
    session_desc sd = {.config = &cfg, .bind = o->bind, .barrier_ms = o->barrier_ms,
                       .quiet = o->quiet, .scene = o->scene, .input = o->input, .dt = o->dt};
    if (o->gi && frame_gi_parse(o->gi, &sd.gi) != 0) {
        fprintf(stderr, "cavelight-master: --gi %s: use " FRAME_GI_NAMES "\n", o->gi);
        return 2;
    }
    if (o->vpl_count && (o->vpl_count < FRAME_VPL_MIN || o->vpl_count > FRAME_VPL_MAX)) {
        fprintf(stderr, "cavelight-master: --vpl-count %d: use %d to %d\n", o->vpl_count,
                FRAME_VPL_MIN, FRAME_VPL_MAX);
        return 2;
    }
    sd.vpl_count = o->vpl_count;
    session *s = session_create(&sd, err, sizeof err);
    if (!s) {
        fprintf(stderr, "cavelight-master: %s\n", err);
        return 1;
    }
    cluster_master *m = session_master(s);
    if ((o->endpoint_file && write_endpoint_file(m, o->endpoint_file) != 0) ||
        ((o->spawn_local || o->spawn_remote) && spawn_nodes(o, &cfg, m, &children) != 0)) {
        spawn_stop_all(&children, 2000);
        session_destroy(s);
        return 1;
    }
    int live = session_wait_nodes(s, cfg.node_count, o->wait_ms, &stop_requested);
    if (live < cfg.node_count)
        fprintf(stderr, "cavelight-master: %d of %d nodes joined within %d ms; going on with them\n", live,
                cfg.node_count, o->wait_ms);
    if (!o->quiet)
        fprintf(stderr, "cavelight-master: %d nodes live, running %s%d frames\n", live,
                o->frames ? "" : "until stopped, ", o->frames);
    double wall_s;
    int exit_code = run_frames(s, o, &wall_s);
    if (o->report && session_write_report(s, o->report, wall_s) != 0)
        exit_code = 1;
    cluster_master_stats st;
    cluster_master_stats_get(m, &st);
    session_destroy(s); /* BYE: spawned nodes leave by themselves */
    stop_children(&children);
    /* After the nodes are gone, every image on disk is from the last frame. */
    if (o->overview) {
        if (overview_compose(&cfg, o->out_dir ? o->out_dir : ".", o->overview, err, sizeof err) != 0) {
            fprintf(stderr, "cavelight-master: %s\n", err);
            exit_code = 1;
        } else if (!o->quiet) {
            fprintf(stderr, "cavelight-master: wrote %s\n", o->overview);
        }
    }
    print_summary(&st, wall_s);
    return exit_code;
}

int main(int argc, char **argv)
{
    options o;
    if (parse_args(argc, argv, &o) != 0) {
        usage();
        return 2;
    }
    return master_run(&o);
}
