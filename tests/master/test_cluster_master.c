#define _DEFAULT_SOURCE /* usleep, rand_r */
/* cluster_master over real ZeroMQ sockets: fake nodes (DEALER threads speaking the wire
 * format) join, render and report; the barrier, epoch raise on join, desync report, drop
 * after the barrier timeout, rejoin, config-hash refusal, and garbage, truncated,
 * oversized, multipart and unknown-peer input that must be dropped and counted while
 * the frames go on; a master shutting down answers HELLO with BYE. */
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <zmq.h>
#include <cmocka.h>

#include "gi/gi_settings.h"

#include "cluster_master.h"

/* What a node of this build says in HELLO for cfg (params_session_hash()). */
static uint64_t hello_hash(const cluster_config *cfg)
{
    static params_schema schema;
    if (!schema.count)
        gi_params_schema(&schema);
    return params_session_hash(cfg->hash, &schema);
}

static const char *config_json =
    "{\"master\": {\"bind\": \"tcp://127.0.0.1:*\", \"connect\": \"tcp://127.0.0.1:1\"},"
    " \"security\": {\"mode\": \"insecure\"},"
    " \"timeouts\": {\"barrier_ms\": 300, \"heartbeat_ms\": 50, \"master_ms\": 2000},"
    " \"screens\": [{\"name\": \"s\", \"bottom_left\": [0,0,0], \"bottom_right\": [1,0,0], \"top_left\": [0,1,0]}],"
    " \"nodes\": [{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4]},"
    "            {\"name\": \"b\", \"screens\": [\"s\"], \"resolution\": [4,4]},"
    "            {\"name\": \"c\", \"screens\": [\"s\"], \"resolution\": [4,4]}]}";

static cluster_config cfg;
static cluster_master *master;
static char endpoint[256];

typedef struct fake_node {
    const char *name;
    uint64_t checksum;          /* reported in READY */
    volatile int silent;        /* 1: receive but never answer */
    volatile int refuse;        /* 1: answer a FRAME with REFUSE(params) instead of READY */
    volatile int rejoin;        /* set: send HELLO again, then clear */
    volatile int stop;
    uint64_t config_hash;
    volatile int frames, swaps, snapshots, byes;
    volatile uint32_t last_bye;
    pthread_t thread;
} fake_node;

static void *fake_ctx;

static void *open_dealer_to(const char *ep, const char *id)
{
    void *s = zmq_socket(fake_ctx, ZMQ_DEALER);
    int zero = 0;
    zmq_setsockopt(s, ZMQ_LINGER, &zero, sizeof zero);
    if (id)
        zmq_setsockopt(s, ZMQ_ROUTING_ID, id, strlen(id));
    assert_int_equal(zmq_connect(s, ep), 0);
    return s;
}

static void *open_dealer(const char *id) { return open_dealer_to(endpoint, id); }

static void send_wire(void *s, wire_msg *m, const char *name)
{
    uint8_t buf[WIRE_MAX_MESSAGE];
    if (name)
        snprintf(m->name, sizeof m->name, "%s", name);
    size_t len = wire_encode(m, buf, sizeof buf);
    assert_true(len > 0);
    zmq_send(s, buf, len, 0);
}

static void *fake_node_main(void *arg)
{
    fake_node *n = arg;
    void *s = open_dealer(n->name);
    wire_msg hello = {.type = WIRE_HELLO, .config_hash = n->config_hash};
    send_wire(s, &hello, n->name);
    while (!n->stop) {
        if (n->rejoin) {
            n->rejoin = 0;
            send_wire(s, &hello, n->name);
        }
        zmq_pollitem_t it = {.socket = s, .events = ZMQ_POLLIN};
        if (zmq_poll(&it, 1, 20) <= 0)
            continue;
        uint8_t buf[WIRE_MAX_MESSAGE];
        int len = zmq_recv(s, buf, sizeof buf, 0);
        wire_msg m;
        if (len < 0 || wire_decode(buf, (size_t)len, &m) != WIRE_OK)
            continue;
        if (m.type == WIRE_SNAPSHOT)
            n->snapshots++;
        if (m.type == WIRE_SWAP)
            n->swaps++;
        if (m.type == WIRE_BYE) {
            n->byes++;
            n->last_bye = m.reason;
        }
        if (m.type == WIRE_FRAME && n->refuse) {
            wire_msg r = {.type = WIRE_REFUSE, .reason = WIRE_REFUSE_PARAMS, .version = m.version};
            snprintf(r.text, sizeof r.text, "frame %llu: invalid values", (unsigned long long)m.version);
            send_wire(s, &r, n->name);
        } else if (m.type == WIRE_FRAME && !n->silent) {
            n->frames++;
            wire_msg r = {.type = WIRE_READY, .version = m.version, .checksum = n->checksum,
                          .timings = {0.1f, 1, 2, 3}};
            send_wire(s, &r, n->name);
        }
    }
    zmq_close(s);
    return NULL;
}

static void start_node(fake_node *n, const char *name, uint64_t checksum)
{
    memset(n, 0, sizeof *n);
    n->name = name;
    n->checksum = checksum;
    n->config_hash = hello_hash(&cfg);
    pthread_create(&n->thread, NULL, fake_node_main, n);
}

/* Waits up to 2 s for a fake node's counter to reach want (what the master sent may still
 * be in flight; on a loaded machine 50 ms was not always enough). */
static int wait_count(volatile int *count, int want)
{
    for (int ms = 0; *count < want && ms < 2000; ms += 5)
        usleep(5000);
    return *count;
}

static void stop_node(fake_node *n)
{
    n->stop = 1;
    pthread_join(n->thread, NULL);
}

static int setup(void **state)
{
    char err[512];
    assert_int_equal(cluster_config_parse(config_json, strlen(config_json), "test.json", &cfg, err, sizeof err), 0);
    cluster_master_desc d = {.config = &cfg, .quiet = 1};
    master = cluster_master_create(&d, err, sizeof err);
    assert_non_null(master);
    assert_int_equal(cluster_master_endpoint(master, endpoint, sizeof endpoint), 0);
    fake_ctx = zmq_ctx_new();
    return 0;
}

static int teardown(void **state)
{
    cluster_master_destroy(master);
    zmq_ctx_term(fake_ctx);
    return 0;
}

static void test_barrier_epoch_and_desync(void **state)
{
    fake_node a, b;
    start_node(&a, "a", 7);
    start_node(&b, "b", 7);
    assert_int_equal(cluster_master_wait_nodes(master, 2, 3000), 2);
    cluster_frame_result r;
    for (int i = 0; i < 20; i++) {
        assert_int_equal(cluster_master_frame(master, &r), 0);
        assert_int_equal(r.live, 2);
        assert_int_equal(r.ready, 2);
        assert_int_equal(r.desync, 0);
        /* The joins raise the epoch once, in the first commit after them. */
        assert_int_equal(r.epoch, 1);
        assert_true(r.frame_bytes > WIRE_HEADER_SIZE && r.frame_bytes < 200);
    }
    assert_int_equal(r.version, 20);
    b.checksum = 8;
    assert_int_equal(cluster_master_frame(master, &r), 0);
    assert_int_equal(r.desync, 1);
    cluster_master_stats st;
    cluster_master_stats_get(master, &st);
    assert_int_equal(st.desyncs, 1);
    /* Every READY frame got its SWAP (the last one may still be in flight). */
    assert_int_equal(wait_count(&a.swaps, 21), 21);
    stop_node(&a);
    stop_node(&b);
}

static void test_drop_after_timeout_and_rejoin(void **state)
{
    fake_node a, b;
    cluster_frame_result r;
    start_node(&a, "a", 1);
    start_node(&b, "b", 1);
    /* Both rejoin (same names as before): the store keeps its version. */
    while (a.snapshots == 0 || b.snapshots == 0)
        cluster_master_wait_nodes(master, 3, 20);
    assert_int_equal(cluster_master_frame(master, &r), 0);
    assert_int_equal(r.ready, 2);
    uint32_t epoch = r.epoch;

    b.silent = 1;
    assert_int_equal(cluster_master_frame(master, &r), 0);
    assert_int_equal(r.ready, 1);
    assert_int_equal(r.dropped, 1);
    assert_true(r.barrier_ms >= 250);
    /* The others go on without waiting for the dropped node. */
    for (int i = 0; i < 5; i++) {
        assert_int_equal(cluster_master_frame(master, &r), 0);
        assert_int_equal(r.live, 1);
        assert_int_equal(r.ready, 1);
        assert_true(r.barrier_ms < 250);
    }
    assert_true(wait_count(&b.byes, 1) >= 1);
    assert_int_equal(b.last_bye, WIRE_BYE_DROPPED);

    /* It comes back: snapshot, and the next frame resets every node's history. */
    b.silent = 0;
    b.rejoin = 1;
    while (cluster_master_live_count(master) < 2)
        cluster_master_wait_nodes(master, 2, 20);
    assert_int_equal(cluster_master_frame(master, &r), 0);
    assert_int_equal(r.ready, 2);
    assert_int_equal(r.epoch, epoch + 1);
    stop_node(&a);
    stop_node(&b);
}

/* A node that refuses a frame's parameters leaves the barrier at once (no timeout), its
 * reason is kept, and a frame nobody rendered is not counted as rendered. */
static void test_refusal_leaves_the_barrier(void **state)
{
    /* The previous test's nodes closed their sockets; on a loaded machine the master may
     * not have seen both disconnects yet, and a node still counted live spoils r.live. */
    for (int ms = 0; cluster_master_live_count(master) > 0 && ms < 5000; ms += 20)
        cluster_master_wait_nodes(master, 3, 20);
    assert_int_equal(cluster_master_live_count(master), 0);
    fake_node c;
    start_node(&c, "c", 1);
    while (c.snapshots == 0)
        cluster_master_wait_nodes(master, 3, 20);
    cluster_master_stats before, after;
    cluster_master_stats_get(master, &before);
    c.refuse = 1;
    cluster_frame_result r;
    assert_int_equal(cluster_master_frame(master, &r), 0);
    assert_int_equal(r.live, 1);
    assert_int_equal(r.ready, 0);
    assert_int_equal(r.dropped, 0);
    assert_true(r.barrier_ms < 250); /* the barrier timeout is 300 */
    cluster_master_stats_get(master, &after);
    assert_int_equal(after.refusals, before.refusals + 1);
    assert_int_equal(after.frames_rendered, before.frames_rendered);
    assert_int_equal(after.frames, before.frames + 1);
    cluster_peer_stats ps;
    cluster_master_peer_stats(master, 2, &ps);
    assert_int_equal(ps.refusals, 1);
    assert_int_equal(ps.refused_what, WIRE_REFUSE_PARAMS);
    char want[64];
    snprintf(want, sizeof want, "frame %llu: invalid values", (unsigned long long)r.version);
    assert_string_equal(ps.refusal, want);
    assert_int_equal(cluster_master_live_count(master), 0);
    stop_node(&c);
}

static void test_config_mismatch_refused(void **state)
{
    fake_node c;
    memset(&c, 0, sizeof c);
    c.name = "c";
    c.config_hash = hello_hash(&cfg) ^ 1;
    pthread_create(&c.thread, NULL, fake_node_main, &c);
    for (int i = 0; i < 100 && c.byes == 0; i++)
        cluster_master_wait_nodes(master, 3, 10);
    assert_int_equal(c.last_bye, WIRE_BYE_CONFIG_MISMATCH);
    assert_int_equal(c.snapshots, 0);
    stop_node(&c);
}

static long rss_kib(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    long pages = 0, rss = 0;
    if (f) {
        if (fscanf(f, "%ld %ld", &pages, &rss) != 2)
            rss = 0;
        fclose(f);
    }
    return rss * (sysconf(_SC_PAGESIZE) / 1024);
}

typedef struct attacker {
    volatile int stop;
    int sent;
} attacker;

/* Known name "c" sending garbage of every kind, strangers, oversized and multipart. */
static void *attack_main(void *arg)
{
    attacker *at = arg;
    void *known = open_dealer("c"), *stranger = open_dealer("mallory"), *anon = open_dealer(NULL);
    uint8_t buf[WIRE_MAX_MESSAGE];
    wire_msg ready = {.type = WIRE_READY, .version = 1};
    snprintf(ready.name, sizeof ready.name, "c");
    size_t good = wire_encode(&ready, buf, sizeof buf);
    unsigned seed = 99;
    while (!at->stop && at->sent < 30000) {
        int kind = at->sent % 6;
        uint8_t g[600];
        size_t len = (size_t)(rand_r(&seed) % (int)sizeof g);
        for (size_t i = 0; i < len; i++)
            g[i] = (uint8_t)rand_r(&seed);
        switch (kind) {
        case 0: zmq_send(known, g, len, ZMQ_DONTWAIT); break;                      /* random bytes */
        case 1: zmq_send(known, buf, good - 1 - len % (good - 1), ZMQ_DONTWAIT); break; /* truncated */
        case 2: zmq_send(stranger, buf, good, ZMQ_DONTWAIT); break;                /* unknown peer */
        case 3: zmq_send(anon, g, len, ZMQ_DONTWAIT); break;                       /* no identity */
        case 4: /* multipart */
            zmq_send(known, buf, good, ZMQ_SNDMORE | ZMQ_DONTWAIT);
            zmq_send(known, g, len, ZMQ_DONTWAIT);
            break;
        default: { /* a valid message impersonating node a */
            wire_msg imp = ready;
            snprintf(imp.name, sizeof imp.name, "a");
            uint8_t b2[WIRE_MAX_MESSAGE];
            size_t l2 = wire_encode(&imp, b2, sizeof b2);
            zmq_send(known, b2, l2, ZMQ_DONTWAIT);
        }
        }
        at->sent++;
        if (at->sent % 500 == 0)
            usleep(1000);
    }
    /* Oversized: more than ZMQ_MAXMSGSIZE; the master's ZeroMQ drops the connection. */
    void *big_sock = open_dealer("c");
    static uint8_t big[4 * WIRE_MAX_MESSAGE];
    memset(big, 0x41, sizeof big);
    zmq_send(big_sock, big, sizeof big, 0);
    usleep(100000);
    zmq_close(big_sock);
    zmq_close(known);
    zmq_close(stranger);
    zmq_close(anon);
    return NULL;
}

static void test_garbage_is_dropped_and_counted(void **state)
{
    fake_node a, b;
    start_node(&a, "a", 5);
    start_node(&b, "b", 5);
    while (a.snapshots == 0 || b.snapshots == 0)
        cluster_master_wait_nodes(master, 3, 20);
    cluster_frame_result r;
    assert_int_equal(cluster_master_frame(master, &r), 0);
    long rss0 = rss_kib();
    cluster_master_stats before;
    cluster_master_stats_get(master, &before);

    attacker at = {0};
    pthread_t t;
    pthread_create(&t, NULL, attack_main, &at);
    int frames = 0;
    while (at.sent < 30000) {
        assert_int_equal(cluster_master_frame(master, &r), 0);
        assert_int_equal(r.ready, 2);
        assert_int_equal(r.desync, 0);
        frames++;
    }
    at.stop = 1;
    pthread_join(t, NULL);
    for (int i = 0; i < 10; i++) {
        assert_int_equal(cluster_master_frame(master, &r), 0);
        assert_int_equal(r.ready, 2);
    }
    cluster_master_stats st;
    cluster_master_stats_get(master, &st);
    assert_true(st.malformed > before.malformed + 1000);
    assert_true(st.unknown_peers > before.unknown_peers + 1000);
    assert_int_equal(st.desyncs, before.desyncs);
    assert_int_equal(st.drops, before.drops);
    long grown = rss_kib() - rss0;
    print_message("%d frames during %d hostile messages: %llu malformed, %llu unknown, RSS +%ld KiB\n", frames,
                  at.sent, (unsigned long long)(st.malformed - before.malformed),
                  (unsigned long long)(st.unknown_peers - before.unknown_peers), grown);
    assert_true(grown < 64 * 1024);
    stop_node(&a);
    stop_node(&b);
}

/* A master that is shutting down answers a HELLO with BYE(shutdown) again, never with a
 * snapshot, so no node says "reconnected" to it. Node a's HELLO waits in the queue until
 * destroy() reads it; node b never answers the BYE, so the master reads for its 1 s. */
static void test_shutdown_answers_hello_with_bye(void **state)
{
    char err[512], ep[256];
    cluster_master_desc d = {.config = &cfg, .quiet = 1};
    cluster_master *m = cluster_master_create(&d, err, sizeof err);
    assert_non_null(m);
    assert_int_equal(cluster_master_endpoint(m, ep, sizeof ep), 0);
    void *a = open_dealer_to(ep, "a"), *b = open_dealer_to(ep, "b");
    wire_msg hello = {.type = WIRE_HELLO, .config_hash = hello_hash(&cfg)};
    send_wire(a, &hello, "a");
    send_wire(b, &hello, "b");
    assert_int_equal(cluster_master_wait_nodes(m, 2, 3000), 2);
    send_wire(a, &hello, "a");
    cluster_master_destroy(m);
    int byes = 0, snapshots_after_bye = 0;
    for (;;) {
        zmq_pollitem_t it = {.socket = a, .events = ZMQ_POLLIN};
        if (zmq_poll(&it, 1, 200) <= 0)
            break;
        uint8_t buf[WIRE_MAX_MESSAGE];
        int len = zmq_recv(a, buf, sizeof buf, 0);
        wire_msg msg;
        if (len < 0 || wire_decode(buf, (size_t)len, &msg) != WIRE_OK)
            continue;
        byes += msg.type == WIRE_BYE && msg.reason == WIRE_BYE_SHUTDOWN;
        snapshots_after_bye += msg.type == WIRE_SNAPSHOT && byes > 0;
    }
    zmq_close(a); /* before any assertion: an open socket would hang the teardown */
    zmq_close(b);
    assert_int_equal(snapshots_after_bye, 0);
    assert_int_equal(byes, 2); /* the session's end, and the answer to the late HELLO */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_barrier_epoch_and_desync),
        cmocka_unit_test(test_drop_after_timeout_and_rejoin),
        cmocka_unit_test(test_refusal_leaves_the_barrier),
        cmocka_unit_test(test_config_mismatch_refused),
        cmocka_unit_test(test_garbage_is_dropped_and_counted),
        cmocka_unit_test(test_shutdown_answers_hello_with_bye),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
