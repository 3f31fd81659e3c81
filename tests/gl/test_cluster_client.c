/* cluster_client (the node side) against a fake master on a real ROUTER socket: it says
 * HELLO, drops and counts garbage, truncated, oversized, multipart and wrong-direction
 * messages, joins from a snapshot, applies deltas, asks for a snapshot on a gap, and
 * reports the master lost after master_ms of silence. */
#define _DEFAULT_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zmq.h>
#include <cmocka.h>

#include "gi/gi_settings.h"

#include "cluster_client.h"

static const char *config_json =
    "{\"master\": {\"bind\": \"tcp://127.0.0.1:1\", \"connect\": \"tcp://127.0.0.1:1\"},"
    " \"security\": {\"mode\": \"insecure\"},"
    " \"timeouts\": {\"heartbeat_ms\": 50, \"master_ms\": 1500},"
    " \"screens\": [{\"name\": \"s\", \"bottom_left\": [0,0,0], \"bottom_right\": [1,0,0], \"top_left\": [0,1,0]}],"
    " \"nodes\": [{\"name\": \"n\", \"screens\": [\"s\"], \"resolution\": [4,4]}]}";

static void *ctx, *router;

static void send_raw(const void *data, size_t len, int more)
{
    zmq_send(router, "n", 1, ZMQ_SNDMORE);
    zmq_send(router, data, len, more ? ZMQ_SNDMORE : 0);
}

static void send_wire(const wire_msg *m)
{
    uint8_t buf[WIRE_MAX_MESSAGE];
    size_t len = wire_encode(m, buf, sizeof buf);
    assert_true(len > 0);
    send_raw(buf, len, 0);
}

/* Next message of `type` from the node within timeout_ms (others are skipped). */
static int expect_from_node(cluster_client *c, int type, int timeout_ms, wire_msg *out)
{
    static uint8_t buf[WIRE_MAX_MESSAGE];
    for (int t = 0; t < timeout_ms; t += 10) {
        cluster_event ev;
        cluster_client_poll(c, 10, &ev);
        char id[64];
        while (zmq_recv(router, id, sizeof id, ZMQ_DONTWAIT) >= 0) {
            int len = zmq_recv(router, buf, sizeof buf, 0);
            if (len > 0 && wire_decode(buf, (size_t)len, out) == WIRE_OK && (int)out->type == type)
                return 0;
        }
    }
    return -1;
}

static cluster_event_type poll_until(cluster_client *c, cluster_event_type want, int timeout_ms, cluster_event *ev)
{
    for (int t = 0; t < timeout_ms; t += 10)
        if (cluster_client_poll(c, 10, ev) == want)
            return want;
    return CLUSTER_EVENT_NONE;
}

static void test_client_against_fake_master(void **state)
{
    static cluster_config cfg;
    char err[512], ep[256];
    assert_int_equal(cluster_config_parse(config_json, strlen(config_json), "c.json", &cfg, err, sizeof err), 0);
    ctx = zmq_ctx_new();
    router = zmq_socket(ctx, ZMQ_ROUTER);
    int zero = 0, one = 1;
    zmq_setsockopt(router, ZMQ_LINGER, &zero, sizeof zero);
    zmq_setsockopt(router, ZMQ_ROUTER_HANDOVER, &one, sizeof one); /* as the real master, insecure */
    assert_int_equal(zmq_bind(router, "tcp://127.0.0.1:*"), 0);
    size_t eplen = sizeof ep;
    zmq_getsockopt(router, ZMQ_LAST_ENDPOINT, ep, &eplen);

    cluster_client_desc cd = {.config = &cfg, .name = "n", .endpoint = ep, .quiet = 1};
    cluster_client *c = cluster_client_create(&cd, err, sizeof err);
    assert_non_null(c);
    wire_msg hello;
    assert_int_equal(expect_from_node(c, WIRE_HELLO, 3000, &hello), 0);
    assert_string_equal(hello.name, "n");
    static params_schema schema;
    gi_params_schema(&schema);
    assert_int_equal(hello.config_hash, params_session_hash(cfg.hash, &schema));

    /* Hostile input: nothing of it may produce an event or change the store. */
    static params_store master;
    params_init(&master, &schema);
    float head[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.3f, 1.7f, 0, 1};
    params_set_mat4(&master, PARAMS_HEAD, head);
    params_commit(&master);
    static uint8_t snap[PARAMS_ENCODED_MAX], buf[WIRE_MAX_MESSAGE];
    wire_msg sm = {.type = WIRE_SNAPSHOT, .version = 1, .params = snap};
    sm.params_len = params_encode_snapshot(&master, snap, sizeof snap);
    size_t snap_len = wire_encode(&sm, buf, sizeof buf);
    unsigned seed = 7;
    int hostile = 0;
    for (int i = 0; i < 300; i++, hostile++) {
        uint8_t g[300];
        size_t len = (size_t)(rand_r(&seed) % (int)sizeof g);
        for (size_t k = 0; k < len; k++)
            g[k] = (uint8_t)rand_r(&seed);
        if (i % 3 == 0)
            send_raw(g, len, 0);                             /* random bytes */
        else if (i % 3 == 1)
            send_raw(buf, 1 + len % (snap_len - 1), 0);     /* truncated snapshot */
        else {
            send_raw(buf, snap_len, 1);                      /* multipart */
            send_raw(g, len, 0);
            hostile++;
        }
    }
    wire_msg wrong = {.type = WIRE_READY, .version = 1};
    snprintf(wrong.name, sizeof wrong.name, "master");
    send_wire(&wrong);                                       /* node-to-master type */
    hostile++;
    cluster_event ev;
    for (int i = 0; i < 30; i++) {
        cluster_event_type t = cluster_client_poll(c, 10, &ev);
        assert_true(t == CLUSTER_EVENT_NONE);
    }
    cluster_client_stats st;
    cluster_client_stats_get(c, &st);
    assert_true(st.malformed >= 300);
    assert_int_equal(cluster_client_params(c)->version, 0);

    /* Oversized: the node's ZeroMQ drops the connection for good; after master_ms of
     * silence the node opens a new socket and says HELLO again. A HELLO the node repeated
     * on the old connection may arrive first (late under load): only the new socket's
     * counts, or the snapshot below would go down the dead connection. */
    static uint8_t big[4 * WIRE_MAX_MESSAGE];
    memset(big, 1, sizeof big);
    cluster_client_stats_get(c, &st);
    uint64_t reopens = st.reopens;
    send_raw(big, sizeof big, 0);
    for (int t = 0; t < 5000 && st.reopens == reopens; t += 10) {
        expect_from_node(c, -1, 10, &hello); /* polls the node, drains the old connection */
        cluster_client_stats_get(c, &st);
    }
    assert_true(st.reopens > reopens);
    assert_int_equal(expect_from_node(c, WIRE_HELLO, 5000, &hello), 0);

    /* A real snapshot, then a delta. */
    send_raw(buf, snap_len, 0);
    assert_int_equal(poll_until(c, CLUSTER_EVENT_JOINED, 2000, &ev), CLUSTER_EVENT_JOINED);
    assert_int_equal(params_checksum(cluster_client_params(c)), params_checksum(&master));
    head[12] = 0.5f;
    params_set_mat4(&master, PARAMS_HEAD, head);
    params_commit(&master);
    static uint8_t delta[PARAMS_ENCODED_MAX];
    wire_msg fm = {.type = WIRE_FRAME, .version = 2, .base_version = 1, .params = delta};
    fm.params_len = params_encode_delta(&master, 1, delta, sizeof delta);
    send_wire(&fm);
    assert_int_equal(poll_until(c, CLUSTER_EVENT_FRAME, 2000, &ev), CLUSTER_EVENT_FRAME);
    assert_int_equal(ev.version, 2);
    assert_int_equal(params_checksum(cluster_client_params(c)), params_checksum(&master));
    wire_msg sw = {.type = WIRE_SWAP, .version = 2};
    send_wire(&sw);
    assert_int_equal(poll_until(c, CLUSTER_EVENT_SWAP, 2000, &ev), CLUSTER_EVENT_SWAP);

    /* A gap in the chain (base 5, the node holds 2): no frame, a HELLO asking for a snapshot. */
    fm.version = 6;
    fm.base_version = 5;
    send_wire(&fm);
    assert_int_equal(expect_from_node(c, WIRE_HELLO, 2000, &hello), 0);
    assert_int_equal(cluster_client_params(c)->version, 2);

    /* Silence: LOST after master_ms. */
    send_raw(buf, snap_len, 0);
    assert_int_equal(poll_until(c, CLUSTER_EVENT_JOINED, 2000, &ev), CLUSTER_EVENT_JOINED);
    assert_int_equal(poll_until(c, CLUSTER_EVENT_LOST, 5000, &ev), CLUSTER_EVENT_LOST);
    cluster_client_stats_get(c, &st);
    assert_true(st.reopens >= 1);
    print_message("%d hostile messages, %llu counted malformed\n", hostile, (unsigned long long)st.malformed);

    cluster_client_destroy(c);
    zmq_close(router);
    zmq_ctx_term(ctx);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_client_against_fake_master),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
