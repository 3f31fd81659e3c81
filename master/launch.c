#define _XOPEN_SOURCE 700 /* realpath */
#include "launch.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "base/clock.h"
#include "base/folder.h"

/* The node command line for one node: exe, its options, then --node-args split at spaces. */
static int node_argv(const master_options *o, const char *config, const char *exe, const char *name,
                     const char *connect, const char *out_dir, const char *app, char *storage, size_t cap,
                     char **argv, int max)
{
    int n = 0;
    const char *fixed[] = {exe, "--cluster", config, "--name", name, "--exit-with-master"};
    for (size_t i = 0; i < sizeof fixed / sizeof *fixed; i++)
        argv[n++] = (char *)fixed[i];
    if (connect) {
        argv[n++] = "--master";
        argv[n++] = (char *)connect;
    }
    const char *pairs[][2] = {{"--render", o->render}, {"--output", o->output}, {"--out", out_dir},
                              {"--scene", o->scene}, {"--app", app},
                              {"--scene-transform", o->scene_transform_text}};
    for (size_t i = 0; i < sizeof pairs / sizeof *pairs; i++)
        if (pairs[i][1]) {
            argv[n++] = (char *)pairs[i][0];
            argv[n++] = (char *)pairs[i][1];
        }
    if (o->quiet)
        argv[n++] = "--quiet";
    if (o->keep_frames)
        argv[n++] = "--keep-frames";
    if (o->pattern_blend)
        argv[n++] = "--show-blend";
    if (o->allow_outside_paths)
        argv[n++] = "--allow-outside-paths";
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

int launch_nodes(const master_options *o, const cluster_config *cfg, cluster_master *m, launch_set *l)
{
    spawn_set *children = &l->spawned;
    char exe[PATH_MAX], config_abs[PATH_MAX], out_abs[PATH_MAX], app_abs[PATH_MAX], logs[PATH_MAX],
        connect_buf[256], err[1024];
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
    snprintf(logs, sizeof logs, "%s/logs", o->out_dir);
    if (folder_create(logs, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-master: node logs: %s\n", err);
        return -1;
    }
    /* Local nodes may run elsewhere (their workdir): they get the output folder whole. */
    if (!realpath(o->out_dir, out_abs))
        snprintf(out_abs, sizeof out_abs, "%s", o->out_dir);
    /* The application too; remote hosts get the path as given (the same on every host). */
    const char *app = o->app && o->spawn_local && realpath(o->app, app_abs) ? app_abs : o->app;
    if (!o->quiet)
        fprintf(stderr, "cavelight-master: node logs in %s/NODE.log\n", logs);
    const char *connect = connect_endpoint(m, o->bind, connect_buf, sizeof connect_buf);
    for (int i = 0; i < cfg->node_count; i++) {
        const cluster_node *node = &cfg->nodes[i];
        char storage[1024], *nargv[64], log[PATH_MAX + 64];
        snprintf(log, sizeof log, "%s/%s.log", logs, node->name);
        const char *node_exe = !o->node_exe && node->exe[0] ? node->exe : exe;
        const char *config = node->config[0] ? node->config : config_abs;
        node_argv(o, config, node_exe, node->name, connect, o->spawn_local ? out_abs : o->out_dir, app,
                  storage, sizeof storage, nargv, 64);
        int rc;
        if (o->spawn_local) {
            rc = spawn_local(children, node->name, nargv, node->workdir[0] ? node->workdir : NULL, log, err,
                             sizeof err);
        } else {
            /* exec: the node replaces the remote shell, so signals reach it directly. */
            char cmd[4096] = "", q[1024];
            if (node->workdir[0]) {
                spawn_shell_quote(node->workdir, q, sizeof q);
                snprintf(cmd, sizeof cmd, "cd %s && ", q);
            }
            snprintf(cmd + strlen(cmd), sizeof cmd - strlen(cmd), "exec");
            for (int k = 0; nargv[k]; k++) {
                spawn_shell_quote(nargv[k], q, sizeof q);
                snprintf(cmd + strlen(cmd), sizeof cmd - strlen(cmd), " %s", q);
            }
            rc = spawn_remote(children, node->name, cfg->launch, node->host, cmd, log, err, sizeof err);
        }
        if (rc != 0) {
            fprintf(stderr, "cavelight-master: %s\n", err);
            return -1;
        }
    }
    return 0;
}

/* How child i ended: "exited with status N" or "was killed by signal N (NAME)". */
static void describe_end(int status, char *buf, size_t cap)
{
    if (WIFEXITED(status))
        snprintf(buf, cap, "exited with status %d", WEXITSTATUS(status));
    else if (WIFSIGNALED(status))
        snprintf(buf, cap, "was killed by signal %d (%s)", WTERMSIG(status), strsignal(WTERMSIG(status)));
    else
        snprintf(buf, cap, "ended with wait status %d", status);
}

/* A node that ended: how, and the end of its log. */
static void report_end(launch_set *l, int i, const char *when)
{
    spawn_set *c = &l->spawned;
    char how[128];
    describe_end(c->status[i], how, sizeof how);
    fprintf(stderr, "cavelight-master: node %s %s%s%s%s\n", c->label[i], how, when,
            c->log[i][0] ? "; the end of its log " : "", c->log[i]);
    char prefix[96];
    snprintf(prefix, sizeof prefix, "  %s| ", c->label[i]);
    spawn_log_tail(c, i, 5, prefix, stderr);
    l->told[i] = 1;
}

void launch_poll(launch_set *l)
{
    if (!l->spawned.count)
        return;
    spawn_reap(&l->spawned);
    for (int i = 0; i < l->spawned.count; i++)
        if (l->spawned.exited[i] && !l->told[i])
            report_end(l, i, " during the session; going on with the others");
}

int launch_wait(session *s, const cluster_config *cfg, launch_set *l, int wait_ms, int quiet,
                volatile sig_atomic_t *stop)
{
    enum { PROGRESS_MS = 5000 };
    cluster_master *m = session_master(s);
    double start = clock_now_ms(), next_progress = start + PROGRESS_MS;
    for (;;) {
        int live = session_wait_nodes(s, cfg->node_count, 200, stop);
        spawn_reap(&l->spawned);
        int waiting = 0;
        char missing[1024] = "";
        for (int i = 0; i < cfg->node_count; i++) {
            cluster_peer_stats ps;
            cluster_master_peer_stats(m, i, &ps);
            if (ps.state == CLUSTER_PEER_LIVE)
                continue;
            int c = spawn_find(&l->spawned, cfg->nodes[i].name);
            if (c >= 0 && l->spawned.exited[c]) {
                if (!l->told[c])
                    report_end(l, c, " before joining");
                continue; /* it will not join: no reason to wait for it */
            }
            waiting++;
            size_t used = strlen(missing);
            snprintf(missing + used, sizeof missing - used, "%s%s (%s)", used ? ", " : "", cfg->nodes[i].name,
                     cfg->nodes[i].host);
        }
        double now = clock_now_ms();
        if (live == cfg->node_count || waiting == 0 || (stop && *stop) || now - start >= wait_ms) {
            if (live < cfg->node_count && missing[0])
                fprintf(stderr, "cavelight-master: %d of %d nodes joined within %d ms; missing: %s; going on "
                        "without them (a longer wait: timeouts.join_ms or --wait-ms)\n", live, cfg->node_count,
                        (int)(now - start), missing);
            return live;
        }
        if (now >= next_progress && !quiet) {
            fprintf(stderr, "cavelight-master: %d of %d nodes joined; waiting up to %d s more for %s\n", live,
                    cfg->node_count, (int)((wait_ms - (now - start)) / 1000), missing);
            next_progress = now + PROGRESS_MS;
        }
    }
}

int launch_all_ended(launch_set *l)
{
    return l->spawned.count > 0 && spawn_reap(&l->spawned) == 0;
}

void launch_stop(launch_set *l)
{
    spawn_set *c = &l->spawned;
    if (!c->count)
        return;
    struct timespec step = {0, 20 * 1000 * 1000};
    for (int waited = 0; spawn_reap(c) > 0 && waited < 10000; waited += 20)
        nanosleep(&step, NULL);
    spawn_stop_all(c, 3000);
    for (int i = 0; i < c->count; i++) {
        int st = c->status[i];
        if (!l->told[i] && !(WIFEXITED(st) && WEXITSTATUS(st) == 0) && !(WIFSIGNALED(st) && WTERMSIG(st) == SIGTERM))
            report_end(l, i, "");
    }
}
