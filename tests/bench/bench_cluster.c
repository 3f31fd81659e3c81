/* cavelight-bench cluster: the frame barrier plus delta round trip (master commits, sends
 * FRAME to every node, waits for every READY, sends SWAP) with N nodes in stub render
 * mode over TCP loopback, next to a raw TCP ping-pong of the same message size measured
 * in the same run; and the bytes of a head-tracked FRAME versus a full SNAPSHOT.
 * --transport ipc uses a Unix socket instead of TCP loopback (the baseline stays TCP).
 * --app FILE runs an application (cavelight/app.h) on the master and every node: its
 * update each frame, then the FRAME's bytes beyond the head-tracked ones are split into
 * the values of the application's and the objects' changed keys and what each key costs
 * on top (app_key_overhead_bytes).
 * Nodes are threads running the real node loop (cluster_node_run), each with its own
 * ZeroMQ context, as separate processes would have. */
#define _DEFAULT_SOURCE
#include <arpa/inet.h>
#include <math.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "bench.h"

#if defined(CAVELIGHT_HAVE_MASTER) && defined(CAVELIGHT_HAVE_NODE)
#include "app/session_keys.h"
#include "base/clock.h"
#include "cluster_master.h"
#include "cluster_node.h"
#include "gi/gi_settings.h"
#include "scene/scene_load.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double pct(double *v, int n, double p)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    int i = (int)ceil(p * n) - 1;
    return v[i < 0 ? 0 : i >= n ? n - 1 : i];
}

typedef struct node_thread {
    pthread_t t;
    cluster_node_desc d;
    char name[16];
    int rc;
} node_thread;

static void *node_main(void *arg)
{
    node_thread *n = arg;
    char err[256];
    n->rc = cluster_node_run(&n->d, NULL, err, sizeof err);
    if (n->rc)
        fprintf(stderr, "bench node %s: %s\n", n->name, err);
    return NULL;
}

/* Raw TCP: an echo thread on loopback, TCP_NODELAY on both ends. */
typedef struct echo {
    int listen_fd, port, bytes;
} echo;

static int read_full(int fd, char *buf, int n)
{
    for (int got = 0; got < n;) {
        ssize_t r = read(fd, buf + got, (size_t)(n - got));
        if (r <= 0)
            return -1;
        got += (int)r;
    }
    return 0;
}

static void *echo_main(void *arg)
{
    echo *e = arg;
    int fd = accept(e->listen_fd, NULL, NULL);
    int one = 1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    char buf[4096];
    while (read_full(fd, buf, e->bytes) == 0)
        if (write(fd, buf, (size_t)e->bytes) != e->bytes)
            break;
    close(fd);
    return NULL;
}

static int tcp_ping_pong(int bytes, int rounds, double *median, double *p99)
{
    echo e = {.bytes = bytes};
    e.listen_fd = socket(AF_INET, SOCK_STREAM, 0);
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t len = sizeof a;
    if (bind(e.listen_fd, (struct sockaddr *)&a, sizeof a) || listen(e.listen_fd, 1) ||
        getsockname(e.listen_fd, (struct sockaddr *)&a, &len))
        return -1;
    pthread_t t;
    pthread_create(&t, NULL, echo_main, &e);
    int fd = socket(AF_INET, SOCK_STREAM, 0), one = 1;
    if (connect(fd, (struct sockaddr *)&a, sizeof a))
        return -1;
    setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    char buf[4096];
    memset(buf, 1, sizeof buf);
    double *rt = malloc(sizeof *rt * (size_t)rounds);
    for (int i = 0; i < rounds + 100; i++) {
        double t0 = clock_now_ms();
        if (write(fd, buf, (size_t)bytes) != bytes || read_full(fd, buf, bytes))
            return -1;
        if (i >= 100)
            rt[i - 100] = clock_now_ms() - t0;
    }
    close(fd);
    pthread_join(t, NULL);
    close(e.listen_fd);
    *median = pct(rt, rounds, 0.5);
    *p99 = pct(rt, rounds, 0.99);
    free(rt);
    return 0;
}

/* The master's side of the keys: the nodes' scene (its objects), the application. */
typedef struct bench_keys {
    scene sc;
    params_schema schema;
    scene_keys objects;
    scene_pose pose;
    app_host *app;
    int first_app_key;      /* keys from here on are the objects' and the application's */
} bench_keys;

static int bench_keys_make(bench_keys *k, const cluster_config *cfg, const char *app, char *err, size_t errlen)
{
    scene_load_desc sd;
    cluster_config_scene_desc(cfg, &sd);
    if (scene_load_with(cfg->scene[0] ? cfg->scene : "default", &sd, &k->sc, err, errlen) != 0)
        return -1;
    scene_pose_rest(&k->sc, &k->pose);
    if (app) {
        app_host_desc ad = {.path = app, .role = CAVELIGHT_ROLE_MASTER, .process = "master", .scene = &k->sc,
                            .quiet = 1};
        if (!(k->app = app_host_load(&ad, err, errlen)) || app_host_init(k->app, err, errlen) != 0)
            return -1;
    }
    gi_params_schema(&k->schema);
    k->first_app_key = k->schema.count;
    return session_keys_add(&k->schema, &k->sc, &k->objects, k->app, err, errlen);
}

/* The application's update of frame f (the head-tracked input and time), its keys and
 * objects into the store. Returns the value bytes of the keys it changed, *changed their
 * count. */
static size_t bench_keys_frame(bench_keys *k, params_store *p, int f, const float head[16], int *changed)
{
    cavelight_input in = {.frame = (uint64_t)(f + 100), .time = f / 60.0, .dt = 1 / 60.0, .head_valid = 1};
    memcpy(in.head, head, sizeof in.head);
    for (int i = 0; i < 16; i += 5)
        in.wand[i] = in.navigation[i] = 1.0f;
    if (k->app)
        app_host_update(k->app, &in);
    scene_keys_write(p, &k->objects, &k->pose);
    size_t bytes = 0;
    *changed = 0;
    for (int key = k->first_app_key; key < k->schema.count; key++)
        if (p->stamp[key] == p->version + 1) {
            size_t len = params_key_size(p, key);
            if (!len)
                params_get_bytes(p, key, &len);
            bytes += len;
            ++*changed;
        }
    return bytes;
}

typedef struct bench_run {
    int frames, nodes, incomplete;
    size_t head_bytes, frame_bytes, value_bytes;
    int changed_keys;
    double *rt;
} bench_run;

/* Head-tracked frames (100 unmeasured first); with an application, its keys too. */
static void run_frames(cluster_master *m, bench_keys *k, bench_run *b)
{
    params_store *p = cluster_master_params(m);
    for (int f = -100; f < b->frames; f++) {
        /* A head-tracked frame: the head pose and the time change, nothing else. */
        float head[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.1f * sinf(f * 0.01f), 1.7f, 0, 1};
        params_set_mat4(p, PARAMS_HEAD, head);
        params_set_f64(p, PARAMS_TIME, f / 60.0);
        int changed = 0;
        size_t values = bench_keys_frame(k, p, f, head, &changed);
        /* The same frame without the application's keys: what they add. */
        static uint8_t delta[PARAMS_ENCODED_MAX]; /* too large for a stack frame */
        cluster_frame_result r;
        size_t all = params_encode_delta(p, p->version, delta, sizeof delta);
        if (cluster_master_frame(m, &r) != 0)
            break;
        b->incomplete += r.ready != b->nodes;
        if (f >= 0) {
            b->rt[f] = r.round_trip_ms;
            b->frame_bytes = r.frame_bytes;
            b->head_bytes = r.frame_bytes - (all - (2 + 64 + 2 + 8)); /* head (mat4) and time (f64) only */
            b->value_bytes = values;
            b->changed_keys = changed;
        }
    }
}

int bench_cluster(int argc, char **argv)
{
    int nodes = 10, frames = 2000, transport_index = 0;
    const char *app = NULL;
    static const char *const transports[] = {"tcp", "ipc"};
    const bench_option opts[] = {
        BENCH_INT("nodes", "N", "stub nodes (threads, no GL)", &nodes, 1, CLUSTER_MAX_NODES),
        BENCH_INT("frames", "F", "frames through the barrier", &frames, 10, 10000000),
        BENCH_CHOICE("transport", "tcp|ipc", "ZeroMQ transport", &transport_index, transports),
        BENCH_TEXT("app", "FILE.so", "an application on the master and every node", &app),
    };
    int pr = BENCH_PARSE("cluster", "frame round trips of a master and stub nodes", opts, argc, argv);
    if (pr)
        return pr > 0 ? 0 : 2;
    const char *transport = transports[transport_index];
    /* A config with N one-screen nodes on an ephemeral loopback port. */
    static char json[16384];
    int n = snprintf(json, sizeof json,
                     "{\"master\": {\"bind\": \"tcp://127.0.0.1:*\", \"connect\": \"tcp://127.0.0.1:1\"},"
                     " \"security\": {\"mode\": \"insecure\"},"
                     " \"timeouts\": {\"barrier_ms\": 5000, \"heartbeat_ms\": 250, \"master_ms\": 10000},"
                     " \"screens\": [{\"name\": \"s\", \"bottom_left\": [0,0,0], \"bottom_right\": [1,0,0],"
                     " \"top_left\": [0,1,0]}], \"nodes\": [");
    for (int i = 0; i < nodes; i++)
        n += snprintf(json + n, sizeof json - (size_t)n, "%s{\"name\": \"n%d\", \"screens\": [\"s\"], \"resolution\": [4,4]}",
                      i ? "," : "", i);
    snprintf(json + n, sizeof json - (size_t)n, "]}");
    static cluster_config cfg;
    static bench_keys keys;
    char err[512], ep[256];
    if (cluster_config_parse(json, strlen(json), "(bench)", &cfg, err, sizeof err) ||
        bench_keys_make(&keys, &cfg, app, err, sizeof err)) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    char ipc[128];
    snprintf(ipc, sizeof ipc, "ipc:///tmp/cavelight-bench-%d", (int)getpid());
    int use_ipc = strcmp(transport, "ipc") == 0;
    cluster_master_desc md = {.config = &cfg, .quiet = 1, .bind = use_ipc ? ipc : NULL, .schema = &keys.schema};
    cluster_master *m = cluster_master_create(&md, err, sizeof err);
    if (!m) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    if (keys.app)
        app_host_bind(keys.app, cluster_master_params(m), cluster_master_params(m), &keys.pose);
    cluster_master_endpoint(m, ep, sizeof ep);
    static volatile sig_atomic_t stop;
    static node_thread th[CLUSTER_MAX_NODES];
    for (int i = 0; i < nodes; i++) {
        snprintf(th[i].name, sizeof th[i].name, "n%d", i);
        th[i].d = (cluster_node_desc){.config = &cfg, .name = th[i].name, .endpoint = ep,
                                      .render = CLUSTER_RENDER_NONE, .output = -1, .quiet = 1, .stop = &stop,
                                      .app = app};
        pthread_create(&th[i].t, NULL, node_main, &th[i]);
    }
    int live = cluster_master_wait_nodes(m, nodes, 10000);
    params_store *p = cluster_master_params(m);
    bench_run b = {.frames = frames, .nodes = nodes, .rt = malloc(sizeof *b.rt * (size_t)frames)};
    run_frames(m, &keys, &b);
    static uint8_t snap[PARAMS_ENCODED_MAX], msg[WIRE_MAX_MESSAGE];
    wire_msg sm = {.type = WIRE_SNAPSHOT, .version = p->version, .params = snap};
    sm.params_len = params_encode_snapshot(p, snap, sizeof snap);
    size_t snap_bytes = wire_encode(&sm, msg, sizeof msg);
    cluster_master_stats st;
    cluster_master_stats_get(m, &st);
    stop = 1;
    for (int i = 0; i < nodes; i++)
        pthread_join(th[i].t, NULL);
    cluster_master_destroy(m);
    app_host_destroy(keys.app);
    scene_free(&keys.sc);

    double tcp_med = 0, tcp_p99 = 0;
    if (tcp_ping_pong((int)b.head_bytes, frames, &tcp_med, &tcp_p99) != 0)
        fprintf(stderr, "cavelight-bench cluster: raw TCP baseline failed\n");
    double med = pct(b.rt, frames, 0.5), p99 = pct(b.rt, frames, 0.99), max = pct(b.rt, frames, 1.0);
    if (use_ipc)
        unlink(ipc + 6);
    size_t extra = b.frame_bytes - b.head_bytes;
    printf("{\"bench\": \"cluster\", \"transport\": \"%s\", \"nodes\": %d, \"nodes_live\": %d, \"frames\": %d, \"incomplete_frames\": %d, "
           "\"desyncs\": %llu, \"round_trip_ms\": {\"median\": %.4f, \"p99\": %.4f, \"max\": %.4f}, "
           "\"tcp_ping_pong_ms\": {\"median\": %.4f, \"p99\": %.4f, \"bytes\": %zu}, "
           "\"round_trip_over_tcp\": %.2f, \"bytes_per_frame_head_tracked\": %zu, "
           "\"bytes_per_frame_all_nodes\": %zu, \"snapshot_bytes\": %zu, \"app\": \"%s\", "
           "\"bytes_per_frame\": %zu, \"app_keys_changed_per_frame\": %d, \"app_value_bytes\": %zu, "
           "\"app_key_overhead_bytes\": %.2f}\n",
           use_ipc ? "ipc" : "tcp", nodes, live, frames, b.incomplete, (unsigned long long)st.desyncs, med, p99, max, tcp_med,
           tcp_p99, b.head_bytes, tcp_med > 0 ? med / tcp_med : 0, b.head_bytes, b.head_bytes * (size_t)nodes, snap_bytes,
           app ? app : "", b.frame_bytes, b.changed_keys, b.value_bytes,
           b.changed_keys ? (double)(extra - b.value_bytes) / b.changed_keys : 0.0);
    free(b.rt);
    return b.incomplete || live != nodes ? 1 : 0;
}
#else
int bench_cluster(int argc, char **argv)
{
    fprintf(stderr, "cavelight-bench cluster: built without the master or node library\n");
    return 2;
}
#endif
