/* An application's shared state across a real session: the master's session runs
 * tests/apps/allkeys.so (a key of every type, all changed every frame) with a render node
 * running it too (cluster_node_run() without GL, in a thread); a node that joins late
 * (a cluster client with the same application's keys) gets every application key in its
 * snapshot, equal to the master's, and the stores' checksums agree; what the application
 * gets wrong on the master (a type, a size, NaN, a key or object that does not exist, a
 * registration outside init) is refused, and a node's attempt to set a key changes
 * nothing (its READY checksums agree with the master's every frame). A node whose
 * application registered other keys is refused: HELLO's hash differs. */
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "app/session_keys.h"
#include "cluster_client.h"
#include "cluster_node.h"
#include "gi/gi_settings.h"
#include "scene/scene_load.h"
#include "session.h"
#include "system_util.h"

#define ALLKEYS CAVELIGHT_BINARY_DIR "/tests/apps/allkeys.so"
#define MOVE CAVELIGHT_BINARY_DIR "/examples/move.so"

/* What a late node holds: a client whose schema has the scene's and the application's
 * keys, as cluster_node_run() builds it. */
typedef struct late_node {
    scene sc;
    app_host *app;
    params_schema schema;
    scene_keys objects;
    cluster_client *client;
} late_node;

static void late_open(late_node *n, const char *app, const char *endpoint)
{
    char err[512];
    scene_load_desc sd;
    cluster_config_scene_desc(&cfg, &sd);
    assert_int_equal(scene_load_with("default", &sd, &n->sc, err, sizeof err), 0);
    app_host_desc ad = {.path = app, .role = CAVELIGHT_ROLE_NODE, .process = "b", .scene = &n->sc, .quiet = 1};
    if (!(n->app = app_host_load(&ad, err, sizeof err)) || app_host_init(n->app, err, sizeof err) != 0)
        fail_msg("%s", err);
    gi_params_schema(&n->schema);
    assert_int_equal(session_keys_add(&n->schema, &n->sc, &n->objects, n->app, err, sizeof err), 0);
    cluster_client_desc cd = {.config = &cfg, .name = "b", .endpoint = endpoint, .quiet = 1, .schema = &n->schema};
    assert_non_null(n->client = cluster_client_create(&cd, err, sizeof err));
}

static void late_close(late_node *n)
{
    cluster_client_destroy(n->client);
    app_host_destroy(n->app);
    scene_free(&n->sc);
}

/* Polls the client while the session waits for it; the event that ended the wait. */
static cluster_event_type late_join(late_node *n, session *s)
{
    cluster_event ev;
    for (int i = 0; i < 300; i++) {
        cluster_event_type t = cluster_client_poll(n->client, 20, &ev);
        if (t == CLUSTER_EVENT_JOINED || t == CLUSTER_EVENT_REFUSED)
            return t;
        session_wait_nodes(s, 2, 20, NULL);
    }
    return CLUSTER_EVENT_NONE;
}

static session *start(const char *app, node_thread *a, char *endpoint)
{
    char err[512];
    session_desc sd = {.config = &cfg, .quiet = 1, .dt = 0.25, .app = app};
    session *s = session_create(&sd, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    assert_int_equal(cluster_master_endpoint(session_master(s), endpoint, 256), 0);
    memset(a, 0, sizeof *a);
    snprintf(a->endpoint, sizeof a->endpoint, "%s", endpoint);
    a->desc = (cluster_node_desc){.config = &cfg, .name = "a", .endpoint = a->endpoint, .render = CLUSTER_RENDER_NONE,
                                  .output = -1, .exit_with_master = 1, .quiet = 1, .app = app};
    assert_int_equal(pthread_create(&a->thread, NULL, node_main, a), 0);
    assert_int_equal(session_wait_nodes(s, 1, 20000, NULL), 1);
    return s;
}

static void frames(session *s, int n)
{
    for (int i = 0; i < n; i++) {
        cluster_frame_result r;
        assert_int_equal(session_frame(s, &r), SESSION_FRAME_DONE);
        assert_int_equal(r.desync, 0);
    }
}

static void test_late_joiner_gets_every_application_key(void **state)
{
    (void)state;
    char endpoint[256];
    node_thread a;
    session *s = start(ALLKEYS, &a, endpoint);
    frames(s, 5);
    static late_node late;
    late_open(&late, ALLKEYS, endpoint);
    assert_int_equal(late_join(&late, s), CLUSTER_EVENT_JOINED);
    const params_store *m = cluster_master_params(session_master(s)), *b = cluster_client_params(late.client);
    int app_keys = 0;
    for (int k = 0; k < m->schema->count; k++) {
        if (strncmp(m->schema->keys[k].name, "app.", 4) != 0)
            continue;
        app_keys++;
        assert_int_equal(b->stamp[k] != 0 || m->stamp[k] == 0, 1);
        size_t lm, lb;
        const uint8_t *vm = params_get_bytes(m, k, &lm), *vb = params_get_bytes(b, k, &lb);
        if (vm) {
            assert_int_equal(lm, lb);
            assert_memory_equal(vm, vb, lm);
        } else {
            assert_memory_equal(m->value[k], b->value[k], params_key_size(m, k));
        }
    }
    assert_int_equal(app_keys, 8);
    assert_int_equal(params_checksum(m), params_checksum(b));
    /* The string and the blob of frame 4, the misbehaviour's refusals of frame 1. */
    size_t len;
    const uint8_t *text = params_get_bytes(b, params_schema_find(b->schema, "app.text"), &len);
    assert_int_equal(len, strlen("frame 4 \xc3\xa4"));
    assert_memory_equal(text, "frame 4 \xc3\xa4", len);
    const uint8_t *r = params_get_bytes(b, params_schema_find(b->schema, "app.refusals"), &len);
    assert_int_equal(len, 9 * sizeof(int));
    for (int i = 0; i < 9; i++) {
        int refused;
        memcpy(&refused, r + i * sizeof(int), sizeof refused);
        if (!refused)
            fail_msg("try %d of allkeys.c's misbehave() was not refused", i);
    }
    printf("late node: %d application keys equal the master's, store checksum %016llx\n", app_keys,
           (unsigned long long)params_checksum(b));
    late_close(&late);
    session_destroy(s);
    pthread_join(a.thread, NULL);
    assert_int_equal(a.rc, 0);
    assert_int_equal(a.stats.frames, 5);
}

static void test_node_of_another_application_refused(void **state)
{
    (void)state;
    char endpoint[256];
    node_thread a;
    session *s = start(ALLKEYS, &a, endpoint);
    frames(s, 1);
    static late_node late;
    late_open(&late, MOVE, endpoint); /* no keys of its own: another schema */
    assert_int_equal(late_join(&late, s), CLUSTER_EVENT_REFUSED);
    late_close(&late);
    session_destroy(s);
    pthread_join(a.thread, NULL);
}

static int setup(void **state)
{
    (void)state;
    char err[512];
    return cluster_config_parse(config_json, strlen(config_json), "app_keys.json", &cfg, err, sizeof err);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_late_joiner_gets_every_application_key),
        cmocka_unit_test(test_node_of_another_application_refused),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
