/* check: a cluster config validated without starting anything (check.h). */
#include "check.h"

#include <netdb.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>

#include "cluster/cluster_config.h"
#include "cluster_auth.h"
#include "gi/gi_settings.h"
#include "input/input_config.h"
#include "scene/scene.h"

typedef struct check_ctx {
    const master_options *o;
    const cluster_config *cfg;
    int problems;
    char summary[512];   /* what passed, for the last line */
} check_ctx;

static void problem(check_ctx *c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "cavelight-master: check: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    c->problems++;
}

static void passed(check_ctx *c, const char *fmt, ...)
{
    size_t used = strlen(c->summary);
    va_list ap;
    va_start(ap, fmt);
    used += (size_t)snprintf(c->summary + used, sizeof c->summary - used, "%s", used ? ", " : "");
    if (used < sizeof c->summary)
        vsnprintf(c->summary + used, sizeof c->summary - used, fmt, ap);
    va_end(ap);
}

static void check_keys(check_ctx *c)
{
    for (int i = 0; i < c->cfg->unknown_key_count && i < CLUSTER_MAX_UNKNOWN_KEYS; i++)
        problem(c, "%s", c->cfg->unknown_keys[i]);
    if (c->cfg->unknown_key_count > CLUSTER_MAX_UNKNOWN_KEYS)
        problem(c, "cluster config %s: %d more unknown keys", c->cfg->path,
                c->cfg->unknown_key_count - CLUSTER_MAX_UNKNOWN_KEYS);
    if (!c->cfg->unknown_key_count)
        passed(c, "every key known");
}

/* The session's GI and display settings: the config's "settings" and the command line's. */
static void check_settings(check_ctx *c)
{
    frame_params settings;
    char err[1024];
    if (master_settings(c->o, c->cfg, &settings, err, sizeof err) != 0)
        problem(c, "%s", err);
    else
        passed(c, "GI %s", gi_method_at(settings.gi)->name);
}

static void check_scene(check_ctx *c)
{
    const char *path = c->o->scene ? c->o->scene : c->cfg->scene[0] ? c->cfg->scene : "default";
    scene sc;
    char err[1024];
    if (scene_load(path, &sc, err, sizeof err) != 0) {
        problem(c, "%s", err);
        return;
    }
    passed(c, "scene %s (%zu triangles)", path, sc.triangle_count);
    scene_free(&sc);
}

static void check_hosts(check_ctx *c)
{
    int hosts = 0;
    for (int n = 0; n < c->cfg->node_count; n++) {
        const char *host = c->cfg->nodes[n].host;
        int seen = 0;
        for (int k = 0; k < n && !seen; k++)
            seen = strcmp(c->cfg->nodes[k].host, host) == 0;
        if (seen)
            continue;
        hosts++;
        struct addrinfo hints = {.ai_socktype = SOCK_STREAM}, *res = NULL;
        int rc = getaddrinfo(host, NULL, &hints, &res);
        if (rc != 0)
            problem(c, "cluster config %s: field nodes[%d].host: '%s' does not resolve (%s)", c->cfg->path, n,
                    host, gai_strerror(rc));
        else
            freeaddrinfo(res);
    }
    passed(c, "%d nodes on %d hosts", c->cfg->node_count, hosts);
}

/* What the master reads at start in curve mode: its secret key and every node's public key. */
static void check_security(check_ctx *c)
{
    if (c->cfg->security != CLUSTER_SECURITY_CURVE) {
        passed(c, "security %s", cluster_security_name(c->cfg->security));
        return;
    }
    char err[1024];
    if (cluster_auth_check_keys(c->cfg, err, sizeof err) != 0)
        problem(c, "%s", err);
    else
        passed(c, "curve keys in %s", c->cfg->keys_dir);
}

/* Every screen's projector warp, read as its node reads it at start. */
static void check_warps(check_ctx *c)
{
    int warps = 0, before = c->problems;
    for (int n = 0; n < c->cfg->node_count; n++)
        for (int s = 0; s < c->cfg->nodes[n].screen_count; s++) {
            const cluster_warp *w = &c->cfg->nodes[n].screens[s].warp;
            warp_map map = {0};
            char err[1024];
            if (w->kind == CLUSTER_WARP_NONE)
                continue;
            warps++;
            if (cluster_warp_load(w, &map, err, sizeof err) != 0)
                problem(c, "node %s: %s", c->cfg->nodes[n].name, err);
            warp_map_free(&map);
        }
    if (warps && c->problems == before)
        passed(c, "%d projector warp%s", warps, warps == 1 ? "" : "s");
}

static void input_warning(void *user, const char *line)
{
    problem(user, "%s", line);
}

static void check_input(check_ctx *c)
{
    if (!c->o->input)
        return;
    char err[1024];
    int before = c->problems;
    input_desc d = {.path = c->o->input, .warn = input_warning, .warn_user = c};
    if (input_config_check(&d, err, sizeof err) != 0)
        problem(c, "%s", err);
    else if (c->problems == before)
        passed(c, "input %s", c->o->input);
}

int check_run(const master_options *o)
{
    static cluster_config cfg;
    char err[1024];
    if (cluster_config_load(o->config, &cfg, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-master: check: %s\n", err);
        return 2;
    }
    check_ctx c = {.o = o, .cfg = &cfg};
    passed(&c, "%d screens", cfg.screen_count);
    static void (*const checks[])(check_ctx *) = {check_keys, check_settings, check_scene,
                                                  check_warps, check_hosts, check_security, check_input};
    for (size_t i = 0; i < sizeof checks / sizeof *checks; i++)
        checks[i](&c);
    if (c.problems) {
        fprintf(stderr, "cavelight-master: check: %s: %d problem%s\n", o->config, c.problems,
                c.problems == 1 ? "" : "s");
        return 2;
    }
    fprintf(stderr, "cavelight-master: check: %s: ok (%s)\n", o->config, c.summary);
    return 0;
}
