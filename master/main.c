/* cavelight-master: runs a cluster session (see docs/cluster.md). */
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>

#include "base/clock.h"
#include "base/ratelog.h"
#include "base/folder.h"
#include "cluster_auth.h"
#include "check.h"
#include "cluster_master.h"
#include "master_cli.h"
#include "launch.h"
#include "overview.h"
#include "preview.h"
#include "session.h"

static volatile sig_atomic_t stop_requested;

static void on_signal(int sig)
{
    (void)sig;
    stop_requested = 1;
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

/* --frames frames (0: until stopped), paced at --fps. Returns 0, or 1 when every node is
 * gone for --wait-ms. */
static int run_frames(session *s, const master_options *o, launch_set *nodes, preview *pv, int wait_ms,
                      double *wall_s)
{
    double start = clock_now_ms();
    int rc = 0;
    ratelog idle_log = {0}; /* nodes that come and go (churn) must not flood the output */
    while ((o->frames == 0 || session_frames(s) < o->frames) && !stop_requested) {
        cluster_frame_result r;
        session_step step = session_frame(s, &r);
        launch_poll(nodes);
        if (pv && preview_update(pv, 0))
            fprintf(stderr, "cavelight-master: preview window closed; the session goes on\n");
        if (step == SESSION_INPUT_ENDED)
            break;
        if (step == SESSION_INPUT_FAILED) {
            rc = 1; /* a recording with errors is no session to report as done */
            break;
        }
        if (step == SESSION_NO_NODES && launch_all_ended(nodes)) {
            fprintf(stderr, "cavelight-master: no node is live and every started node has ended: stopping\n");
            rc = 1;
            break;
        }
        uint64_t skipped = 0;
        if (step == SESSION_NO_NODES) {
            if (ratelog_event(&idle_log, clock_now_ms(), &skipped))
                fprintf(stderr, "cavelight-master: no node is live; waiting up to %d ms for one (%llu times so far, "
                        "%llu not logged)\n", wait_ms, (unsigned long long)idle_log.count,
                        (unsigned long long)skipped);
            if (session_wait_nodes(s, 1, wait_ms, &stop_requested) == 0) {
                fprintf(stderr, "cavelight-master: no node came back: stopping\n");
                rc = 1;
                break;
            }
            continue;
        }
        if (o->fps > 0)
            cluster_master_idle(session_master(s), start + session_frames(s) * 1000.0 / o->fps);
    }
    *wall_s = (clock_now_ms() - start) / 1000.0;
    return rc;
}

/* A session whose nodes refused it, or in which no node rendered any frame, did not show
 * what was asked: each refusing node's last reason, and 1 for the exit status. */
static int session_failed(const cluster_config *cfg, cluster_master *m, const cluster_master_stats *st)
{
    int failed = 0;
    for (int i = 0; i < cfg->node_count; i++) {
        cluster_peer_stats ps;
        cluster_master_peer_stats(m, i, &ps);
        if (!ps.refusals)
            continue;
        fprintf(stderr, "cavelight-master: node %s refused the %s (%u refusals), the last: %s\n", cfg->nodes[i].name,
                ps.refused_what == WIRE_REFUSE_PARAMS ? "parameters" : "scene", ps.refusals, ps.refusal);
        failed = 1;
    }
    if (st->frames > 0 && st->frames_rendered == 0) {
        fprintf(stderr, "cavelight-master: no node rendered any of the %llu frames\n", (unsigned long long)st->frames);
        failed = 1;
    }
    return failed;
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

/* The live preview, or NULL after one line saying why not (the session goes on). */
static preview *open_preview(const master_options *o, const cluster_config *cfg)
{
    char err[1024];
    preview *pv = preview_open(cfg, o->out_dir, err, sizeof err);
    if (!pv) {
        fprintf(stderr, "cavelight-master: warning: %s\n", err);
        return NULL;
    }
    int png = 0;
    for (int n = 0; n < cfg->node_count; n++)
        png |= cfg->nodes[n].output == CLUSTER_OUTPUT_PNG;
    if (o->output ? strcmp(o->output, "png") != 0 : !png)
        fprintf(stderr, "cavelight-master: warning: preview: the nodes write no images into %s (their output "
                "is not png): the walls stay black; add --output png\n", o->out_dir);
    else if (!o->quiet)
        fprintf(stderr, "cavelight-master: preview window open: the walls unfolded from %s\n", o->out_dir);
    return pv;
}

static int keygen(const cluster_config *cfg)
{
    char err[1024];
    if (cluster_keygen(cfg, stderr, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-master: %s\n", err);
        return 1;
    }
    return 0;
}

/* Keys no section of the config reads: warnings, or errors with --strict. 0, or -1. */
static int unknown_keys(const master_options *o, const cluster_config *cfg)
{
    for (int i = 0; i < cfg->unknown_key_count && i < CLUSTER_MAX_UNKNOWN_KEYS; i++)
        if (o->strict || !o->quiet)
            fprintf(stderr, "cavelight-master: %s%s\n", o->strict ? "" : "warning: ", cfg->unknown_keys[i]);
    if (o->strict && cfg->unknown_key_count)
        fprintf(stderr, "cavelight-master: %d unknown key%s in %s: refused (--strict)\n", cfg->unknown_key_count,
                cfg->unknown_key_count == 1 ? "" : "s", cfg->path);
    return o->strict && cfg->unknown_key_count ? -1 : 0;
}

/* Every connection costs a descriptor: take as many as the system allows (the hard limit)
 * and say so, before a handshake flood can reach the usual soft limit of 1024. A hard limit
 * under FD_LIMIT_LOW is named too. The report has the limit either way. */
enum { FD_LIMIT_LOW = 4096 };
static void raise_fd_limit(int quiet)
{
    struct rlimit r;
    if (getrlimit(RLIMIT_NOFILE, &r) != 0)
        return;
    rlim_t before = r.rlim_cur;
    if (r.rlim_cur < r.rlim_max) {
        r.rlim_cur = r.rlim_max == RLIM_INFINITY ? 1 << 20 : r.rlim_max;
        if (setrlimit(RLIMIT_NOFILE, &r) != 0 || getrlimit(RLIMIT_NOFILE, &r) != 0)
            r.rlim_cur = before;
    }
    if (quiet)
        return;
    if (r.rlim_cur > before)
        fprintf(stderr, "cavelight-master: file descriptor limit raised from %llu to %llu (the hard limit)\n",
                (unsigned long long)before, (unsigned long long)r.rlim_cur);
    else if (r.rlim_cur < FD_LIMIT_LOW)
        fprintf(stderr, "cavelight-master: file descriptor limit %llu, the hard limit (LimitNOFILE= or "
                "ulimit -Hn raise it)\n", (unsigned long long)r.rlim_cur);
}

/* The config with the command line's placement applied, and what was fitted said. Returns
 * 0, or -1 after one line. */
static int load_config(const master_options *o, cluster_config *cfg)
{
    char err[1024];
    if (cluster_config_load(o->config, cfg, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-master: %s\n", err);
        return -1;
    }
    if (unknown_keys(o, cfg) != 0)
        return -1;
    if (o->has_scene_transform) { /* spawned nodes get the option too (launch.c) */
        cfg->scene_transform = o->scene_transform;
        cfg->has_scene_transform = 1;
        if (!o->spawn_local && !o->spawn_remote && !o->keygen)
            fprintf(stderr, "cavelight-master: --scene-transform replaces the config's scene_transform: "
                    "start every node with the same --scene-transform\n");
    }
    cfg->scene_outside_paths = o->allow_outside_paths;
    for (int i = 0; i < cfg->screen_count && !o->quiet; i++)
        if (cfg->screens[i].fit_mm >= 0.05f)
            fprintf(stderr, "cavelight-master: screen %s: measured corners fitted to the nearest rectangle, "
                    "the furthest moved %.1f mm (corner_tolerance_mm %g)\n", cfg->screens[i].name,
                    cfg->screens[i].fit_mm, cfg->corner_tolerance_mm);
    return 0;
}

static int master_run(const master_options *o)
{
    static cluster_config cfg;
    static launch_set nodes;
    char err[1024];
    if (load_config(o, &cfg) != 0)
        return 1;
    if (o->keygen)
        return keygen(&cfg);
    static frame_params settings;
    if (master_settings(o, &cfg, &settings, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-master: %s\n", err);
        return 2;
    }
    handle_signals();
    raise_fd_limit(o->quiet);
    session_desc sd = {.config = &cfg, .bind = o->bind, .barrier_ms = o->barrier_ms,
                       .quiet = o->quiet, .insecure_anywhere = o->insecure_anywhere, .scene = o->scene, .input = o->input, .dt = o->dt,
                       .record = o->record, .out_dir = o->out_dir, .pattern = o->pattern,
                       .print_poses = o->print_poses, .settings = &settings,
                       .exposure_auto = master_exposure_auto(o, &cfg), .strict = o->strict,
                       .app = o->app ? o->app : cfg.app[0] ? cfg.app : NULL};
    session *s = session_create(&sd, err, sizeof err);
    if (!s) {
        fprintf(stderr, "cavelight-master: %s\n", err);
        return 1;
    }
    cluster_master *m = session_master(s);
    if ((o->endpoint_file && write_endpoint_file(m, o->endpoint_file) != 0) ||
        ((o->spawn_local || o->spawn_remote) && launch_nodes(o, &cfg, m, &nodes) != 0)) {
        spawn_stop_all(&nodes.spawned, 2000);
        session_destroy(s);
        return 1;
    }
    preview *pv = o->preview ? open_preview(o, &cfg) : NULL;
    int wait_ms = o->wait_ms ? o->wait_ms : cfg.join_timeout_ms;
    int live = launch_wait(s, &cfg, &nodes, wait_ms, o->quiet, &stop_requested);
    if (!o->quiet)
        fprintf(stderr, "cavelight-master: %d node%s live, running %s%d frames\n", live,
                live == 1 ? "" : "s", o->frames ? "" : "until stopped, ", o->frames);
    double wall_s = 0;
    int exit_code = 1;
    if (o->budget_ms > 0 && session_choose_budget(s, o->budget_ms, &stop_requested, err, sizeof err) != 0)
        fprintf(stderr, "cavelight-master: %s\n", err);
    else
        exit_code = run_frames(s, o, &nodes, pv, wait_ms, &wall_s);
    if (o->report && folder_create_for(o->report, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-master: report: %s\n", err);
        exit_code = 1;
    } else if (o->report && session_write_report(s, o->report, wall_s) != 0) {
        exit_code = 1;
    }
    cluster_master_stats st;
    cluster_master_stats_get(m, &st);
    if (session_failed(&cfg, m, &st))
        exit_code = 1;
    session_destroy(s); /* BYE: spawned nodes leave by themselves */
    launch_stop(&nodes);
    /* After the nodes are gone, every image on disk is from the last frame. */
    if (o->overview) {
        if (folder_create_for(o->overview, err, sizeof err) != 0 ||
            overview_compose(&cfg, o->out_dir, o->overview, err, sizeof err) != 0) {
            fprintf(stderr, "cavelight-master: %s\n", err);
            exit_code = 1;
        } else if (!o->quiet) {
            fprintf(stderr, "cavelight-master: wrote %s\n", o->overview);
        }
    }
    if (pv) /* the last frame, now that every image on disk is from it */
        preview_update(pv, 1);
    preview_close(pv);
    print_summary(&st, wall_s);
    return exit_code;
}

int main(int argc, char **argv)
{
    master_options o;
    switch (master_cli_parse(argc, argv, &o)) {
    case CLI_HELP: return 0;
    case CLI_ERROR: return 2;
    default: return o.check ? check_run(&o) : master_run(&o);
    }
}
