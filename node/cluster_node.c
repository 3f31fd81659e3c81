#include "cluster_node.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/ratelog.h"
#include "cluster_client.h"
#include "cluster_view.h"
#include "cluster/params.h"

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
                                .out_dir = d->out_dir, .scene = d->scene, .lpv_threads = d->lpv_threads,
                                .lattice_cells = d->lattice_cells, .rsm_size = d->rsm_size,
                                .lpv_mode = d->lpv_mode, .converge_threshold = d->converge_threshold,
                                .gi = d->gi};
        view = cluster_view_create(&vd, err, errlen);
        if (!view)
            return 1;
    }
    cluster_client_desc cd = {.config = d->config, .name = d->name, .endpoint = d->endpoint, .quiet = d->quiet};
    cluster_client *client = cluster_client_create(&cd, err, errlen);
    if (!client) {
        cluster_view_destroy(view);
        return 1;
    }
    int rc = 0, lost_reported = 0;
    uint64_t pending_swap = 0;
    ratelog range_log = {0};
    while (!(d->stop && *d->stop)) {
        cluster_event ev;
        switch (cluster_client_poll(client, 100, &ev)) {
        case CLUSTER_EVENT_FRAME: {
            double t0 = clock_now_ms();
            const params_store *ps = cluster_client_params(client);
            frame_params f;
            params_to_frame(ps, &f);
            /* Whatever the master sends is range-checked, never a reason to stop: the
             * renderer clamps the frame (frame_params_sanitize), the lattice is clamped here. */
            frame_params check = f;
            int fixed = frame_params_sanitize(&check);
            int lattice = params_get_i32(ps, PARAMS_LPV_RESOLUTION);
            if (lattice < 0 || lattice > PARAMS_LPV_RESOLUTION_MAX) {
                lattice = lattice < 0 ? 0 : PARAMS_LPV_RESOLUTION_MAX;
                fixed++;
            }
            uint64_t skipped = 0;
            if (fixed && ratelog_event(&range_log, clock_now_ms(), &skipped))
                fprintf(stderr, "cavelight-node %s: frame %llu: %d parameters from the master out of range, "
                        "clamped (%llu frames so far, %llu not logged)\n", d->name,
                        (unsigned long long)ev.version, fixed, (unsigned long long)range_log.count,
                        (unsigned long long)skipped);
            uint64_t checksum = params_checksum(ps);
            float timings[WIRE_TIMING_COUNT] = {0};
            if (view && cluster_view_render(view, &f, lattice, &checksum, timings, err, errlen) != 0) {
                rc = 1;
                goto out;
            }
            if (d->fault_checksum_from && ev.version >= d->fault_checksum_from)
                checksum ^= 0x5a5a5a5a5a5a5a5aull;
            timings[WIRE_TIMING_APPLY] = (float)ev.apply_ms;
            timings[WIRE_TIMING_TOTAL] = (float)(ev.apply_ms + clock_now_ms() - t0);
            cluster_client_ready(client, ev.version, checksum, timings);
            pending_swap = ev.version;
            st.frames++;
            st.last_version = ev.version;
            st.last_checksum = checksum;
            lost_reported = 0;
            break;
        }
        case CLUSTER_EVENT_SWAP:
            if (ev.version != pending_swap)
                break;
            st.swaps++;
            if (view) {
                int pr = cluster_view_present(view, err, errlen);
                if (pr < 0) {
                    rc = 1;
                    goto out;
                }
                if (pr > 0) {
                    if (!d->quiet)
                        fprintf(stderr, "cavelight-node %s: window closed: leaving\n", d->name);
                    goto out;
                }
            }
            break;
        case CLUSTER_EVENT_LOST:
            if (!lost_reported && !d->quiet)
                fprintf(stderr, "cavelight-node %s: master lost (its connection closed, or nothing heard for %d ms): "
                        "keeping the output up and reconnecting\n", d->name, d->config->master_timeout_ms);
            lost_reported = 1;
            break;
        case CLUSTER_EVENT_SHUTDOWN:
            if (!d->quiet)
                fprintf(stderr, "cavelight-node %s: the master ended the session%s\n", d->name,
                        d->exit_with_master ? "" : "; waiting for it to return");
            if (d->exit_with_master)
                goto out;
            break;
        case CLUSTER_EVENT_REFUSED:
            snprintf(err, errlen, "cluster node %s: refused by the master (config hash differs from %s)",
                     d->name, d->config->path);
            rc = 1;
            goto out;
        default:
            break;
        }
    }
out:
    cluster_client_destroy(client);
    cluster_view_destroy(view);
    if (stats)
        *stats = st;
    return rc;
}

int cluster_node_wanted(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--cluster") == 0)
            return 1;
    return 0;
}

static volatile sig_atomic_t node_stop;

static void on_signal(int sig)
{
    (void)sig;
    node_stop = 1;
}

static void usage(void)
{
    fprintf(stderr,
            "usage: cavelight-node --cluster FILE --name NODE [--master ENDPOINT] [--render gl|none]\n"
            "         [--output window|headless|png] [--out DIR] [--scene FILE] [--lpv-threads N]\n"
            "         [--lattice CELLS] [--rsm SIZE] [--lpv-mode incremental|classic] [--gi " FRAME_GI_NAMES "]\n"
            "         [--converge-threshold R]\n"
            "         [--exit-with-master] [--quiet]\n");
}

int cluster_node_main(int argc, char **argv)
{
    const char *config_path = NULL;
    cluster_node_desc d = {.output = -1, .render = CLUSTER_RENDER_GL, .stop = &node_stop};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = 1;
        if (strcmp(a, "--cluster") == 0 && v)
            config_path = v;
        else if (strcmp(a, "--name") == 0 && v)
            d.name = v;
        else if (strcmp(a, "--master") == 0 && v)
            d.endpoint = v;
        else if (strcmp(a, "--out") == 0 && v)
            d.out_dir = v;
        else if (strcmp(a, "--scene") == 0 && v)
            d.scene = v;
        else if (strcmp(a, "--lpv-threads") == 0 && v)
            d.lpv_threads = atoi(v);
        else if (strcmp(a, "--lattice") == 0 && v)
            d.lattice_cells = atoi(v);
        else if (strcmp(a, "--rsm") == 0 && v)
            d.rsm_size = atoi(v);
        else if (strcmp(a, "--converge-threshold") == 0 && v)
            d.converge_threshold = atof(v);
        else if (strcmp(a, "--lpv-mode") == 0 && v && (strcmp(v, "incremental") == 0 ||
                                                      strcmp(v, "classic") == 0))
            d.lpv_mode = strcmp(v, "classic") == 0 ? RENDERER_LPV_CLASSIC : RENDERER_LPV_INCREMENTAL;
        else if (strcmp(a, "--gi") == 0 && v) {
            frame_gi gi;
            if (frame_gi_parse(v, &gi) != 0) {
                fprintf(stderr, "cavelight-node: --gi %s: use " FRAME_GI_NAMES "\n", v);
                return 2;
            }
            d.gi = gi;
        }
        else if (strcmp(a, "--fault-checksum-from") == 0 && v)
            d.fault_checksum_from = strtoull(v, NULL, 10);
        else if (strcmp(a, "--render") == 0 && v) {
            if (strcmp(v, "none") == 0)
                d.render = CLUSTER_RENDER_NONE;
            else if (strcmp(v, "gl") == 0)
                d.render = CLUSTER_RENDER_GL;
            else {
                fprintf(stderr, "cavelight-node: --render %s: use gl or none\n", v);
                return 2;
            }
        } else if (strcmp(a, "--output") == 0 && v) {
            d.output = cluster_output_parse(v);
            if (d.output < 0) {
                fprintf(stderr, "cavelight-node: --output %s: use window, headless or png\n", v);
                return 2;
            }
        } else {
            takes = 0;
            if (strcmp(a, "--exit-with-master") == 0)
                d.exit_with_master = 1;
            else if (strcmp(a, "--quiet") == 0)
                d.quiet = 1;
            else {
                fprintf(stderr, "cavelight-node: unknown or incomplete option %s\n", a);
                usage();
                return 2;
            }
        }
        i += takes;
    }
    if (!config_path || !d.name) {
        usage();
        return 2;
    }
    static cluster_config cfg;
    char err[512];
    if (cluster_config_load(config_path, &cfg, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        return 1;
    }
    d.config = &cfg;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    cluster_node_stats st;
    if (cluster_node_run(&d, &st, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        return 1;
    }
    if (!d.quiet)
        fprintf(stderr, "cavelight-node %s: %llu frames, %llu swaps, last version %llu\n", d.name,
                (unsigned long long)st.frames, (unsigned long long)st.swaps, (unsigned long long)st.last_version);
    return 0;
}
