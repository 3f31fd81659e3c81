/* One frame rule, three paths: a default-constructed parameter store, a standalone node
 * and a cluster node must start from the same frame_params. The cluster path is the real
 * one: the master's session seeds its store from the scene, sends the SNAPSHOT over
 * ZeroMQ, and a node's cluster client turns it into frame_params as cluster_node_run()
 * does. The standalone path is node_cli_parse() and standalone_frame_params(), what
 * cavelight-node --standalone runs. Compared field by field, bytes and all. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "app/session_keys.h"
#include "gi/gi_settings.h"
#include "scene/scene_load.h"

#include "cluster_client.h"
#include "session.h"
#include "node_cli.h"

static const char *config_json =
    "{\"master\": {\"bind\": \"tcp://127.0.0.1:*\", \"connect\": \"tcp://127.0.0.1:1\"},"
    " \"security\": {\"mode\": \"insecure\"},"
    " \"timeouts\": {\"barrier_ms\": 5000, \"heartbeat_ms\": 50, \"master_ms\": 5000},"
    " \"screens\": [{\"name\": \"s\", \"bottom_left\": [-1,0,-1], \"bottom_right\": [1,0,-1], \"top_left\": [-1,2,-1]}],"
    " \"nodes\": [{\"name\": \"n\", \"screens\": [\"s\"], \"resolution\": [8,8]}]}";

static void standalone_frame(const char *scene_name, frame_params *out)
{
    /* The exposure fixed as the session's (exposure_auto 0): the automatic one follows
     * each side's first lights, which the master's scripted lamp changes. */
    char *argv[] = {"cavelight-node", "--standalone", "--scene", (char *)scene_name, "--exposure", "1"};
    static node_cli cli;
    assert_int_equal(node_cli_parse(6, argv, &cli), CLI_OK);
    const node_options o = cli.standalone;
    scene sc;
    char err[256];
    assert_int_equal(scene_load(scene_name, &sc, err, sizeof err), 0);
    renderer_view first_eye = {0}; /* the HUD is off: the wand is not placed */
    standalone_frame_params(&o, &sc, &first_eye, out);
    scene_free(&sc);
}

static void cluster_node_frame(const char *scene_name, frame_params *out)
{
    static cluster_config cfg;
    char err[512], endpoint[256];
    assert_int_equal(cluster_config_parse(config_json, strlen(config_json), "agree.json", &cfg, err,
                                          sizeof err), 0);
    session_desc sd = {.config = &cfg, .quiet = 1, .scene = scene_name, .dt = 1.0 / 30};
    session *s = session_create(&sd, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    assert_int_equal(cluster_master_endpoint(session_master(s), endpoint, sizeof endpoint), 0);
    /* A node's keys: the built-in ones and the scene's objects, as cluster_node_run() has. */
    static params_schema schema;
    static scene_keys objects;
    scene sc;
    scene_load_desc sld;
    cluster_config_scene_desc(&cfg, &sld);
    assert_int_equal(scene_load_with(scene_name, &sld, &sc, err, sizeof err), 0);
    gi_params_schema(&schema);
    assert_int_equal(session_keys_add(&schema, &sc, &objects, NULL, err, sizeof err), 0);
    scene_free(&sc);
    cluster_client_desc cd = {.config = &cfg, .name = "n", .endpoint = endpoint, .quiet = 1, .schema = &schema};
    cluster_client *c = cluster_client_create(&cd, err, sizeof err);
    if (!c)
        fail_msg("%s", err);
    /* One thread plays both sides: the client says HELLO from its poll, the master
     * answers with the SNAPSHOT from its wait. */
    cluster_event ev;
    int joined = 0;
    for (int i = 0; i < 200 && !joined; i++) {
        joined = cluster_client_poll(c, 20, &ev) == CLUSTER_EVENT_JOINED;
        session_wait_nodes(s, 1, 20, NULL);
    }
    assert_true(joined);
    params_to_frame(cluster_client_params(c), out);
    cluster_client_destroy(c);
    session_destroy(s);
}

/* f with every GI setting resolved (set, at its value or default): a standalone frame
 * leaves the defaults unset, a store's frame holds them. */
static void resolve(frame_params *f)
{
    for (int i = 0; i < gi_option_count(); i++)
        gi_option_put(gi_option_at(i), gi_option_get(gi_option_at(i), f), f);
}

static void test_default_store_standalone_and_cluster_agree(void **state)
{
    (void)state;
    const char *scenes[2] = {"default", "corridor"};
    for (int i = 0; i < 2; i++) {
        frame_params standalone, cluster, store, unlit;
        memset(&standalone, 0xee, sizeof standalone); /* padding too: compared as bytes */
        memset(&cluster, 0x11, sizeof cluster);
        standalone_frame(scenes[i], &standalone);
        cluster_node_frame(scenes[i], &cluster);
        assert_true(standalone.light_count > 0);
        resolve(&standalone);
        assert_memory_equal(&standalone, &cluster, sizeof standalone);
        /* A fresh store has no scene: the same frame without its lights. */
        static params_schema schema;
        static params_store ps;
        gi_params_schema(&schema);
        params_init(&ps, &schema);
        params_to_frame(&ps, &store);
        unlit = standalone;
        unlit.light_count = 0;
        memset(unlit.lights, 0, sizeof unlit.lights);
        assert_memory_equal(&store, &unlit, sizeof store);
        printf("%s: standalone, cluster node and default store agree (%d light%s, lambda %g, "
               "environment %d)\n", scenes[i], standalone.light_count,
               standalone.light_count == 1 ? "" : "s", standalone.lambda_incr, standalone.environment);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_store_standalone_and_cluster_agree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
