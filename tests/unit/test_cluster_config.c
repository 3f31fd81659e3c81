/* cluster_config: the shipped configs load with the expected shape; broken configs fail
 * with one line naming the file and the field. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "cluster/cluster_config.h"

static cluster_config cfg;

static void load_shipped(const char *name)
{
    char path[512], err[512] = "";
    snprintf(path, sizeof path, "%s/configs/clusters/%s.json", CAVELIGHT_SOURCE_DIR, name);
    if (cluster_config_load(path, &cfg, err, sizeof err) != 0)
        fail_msg("%s", err);
}

static float dist(const float *a, const float *b)
{
    float d = 0;
    for (int i = 0; i < 3; i++)
        d += (a[i] - b[i]) * (a[i] - b[i]);
    return sqrtf(d);
}

static void test_shipped_configs(void **state)
{
    static const char *const names[] = {"desktop", "desktop-local", "powerwall-2x2",
                                        "powerwall-2x2-local", "cave5", "cave5-local"};
    static const int nodes[] = {1, 1, 4, 4, 10, 10};
    for (int i = 0; i < 6; i++) {
        load_shipped(names[i]);
        assert_int_equal(cfg.node_count, nodes[i]);
        assert_int_equal(cfg.nodes[0].eyes, i < 2 ? CLUSTER_EYES_MONO : CLUSTER_EYES_STEREO);
        if (strstr(names[i], "-local"))
            assert_non_null(strstr(cfg.master_connect, "127.0.0.1"));
    }
    /* The CAVE: 10 half walls of 1.5 x 3 m (walls) or 3 x 1.5 m (floor and ceiling). */
    load_shipped("cave5-local");
    assert_int_equal(cfg.screen_count, 10);
    for (int s = 0; s < 10; s++) {
        const cluster_screen *sc = &cfg.screens[s];
        float w = dist(sc->bottom_left, sc->bottom_right), h = dist(sc->bottom_left, sc->top_left);
        assert_float_equal(w * h, 4.5f, 1e-5);
        assert_int_equal(cfg.nodes[s].screens[0].screen, s);
        /* Pixels are square: resolution follows the screen's aspect. */
        assert_float_equal((float)cfg.nodes[s].screens[0].width / cfg.nodes[s].screens[0].height, w / h, 1e-3);
    }
    assert_float_equal(cfg.observer.eye_separation, 0.064f, 1e-6);
    assert_float_equal(cfg.observer.home[1], 1.7f, 1e-6);
    assert_float_equal(cfg.observer.tracker_to_cave[0], 1.0f, 1e-6);
    assert_int_equal(cluster_config_find_node(&cfg, "n10"), 9);
    assert_int_equal(cluster_config_find_node(&cfg, "n11"), -1);
}

static const char *good_head =
    "{\"master\": {\"bind\": \"tcp://*:5570\", \"connect\": \"tcp://h:5570\"},"
    " \"screens\": [{\"name\": \"s\", \"bottom_left\": [0,0,0], \"bottom_right\": [1,0,0], \"top_left\": [0,1,0]}],";

static void expect_error(const char *json, const char *field)
{
    char err[512] = "";
    int rc = cluster_config_parse(json, strlen(json), "bad.json", &cfg, err, sizeof err);
    if (rc == 0)
        fail_msg("accepted: %s", json);
    if (!strstr(err, "bad.json") || !strstr(err, field))
        fail_msg("error '%s' does not name the file and field '%s'", err, field);
    assert_null(strchr(err, '\n'));
}

static void test_bad_configs(void **state)
{
    char buf[2048];
    expect_error("{", "line 1");
    expect_error("[]", "top level");
    expect_error("{\"screens\": []}", "master");
    expect_error("{\"master\": {\"bind\": \"tcp://*:1\"}}", "master.connect");
    expect_error("{\"master\": {\"bind\": \"udp://x\", \"connect\": \"tcp://h:1\"}}", "master.bind");
#define NODES(x) (snprintf(buf, sizeof buf, "%s \"nodes\": [%s]}", good_head, x), buf)
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"nope\"], \"resolution\": [4,4]}"), "nodes[0].screens[0]");
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"s\"]}"), "nodes[0].screens[0]");
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [0,4]}"), "nodes[0].resolution");
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4], \"eyes\": \"three\"}"), "nodes[0].eyes");
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4], \"output\": 3}"), "nodes[0].output");
    expect_error(NODES("{\"name\": \"a b\", \"screens\": [\"s\"], \"resolution\": [4,4]}"), "nodes[0].name");
    expect_error(NODES("{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4]},"
                       "{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [4,4]}"), "nodes[1].name");
    expect_error(NODES(""), "nodes");
    snprintf(buf, sizeof buf, "%s \"observer\": {\"eye_separation\": 5}, \"nodes\": []}", good_head);
    expect_error(buf, "observer.eye_separation");
    snprintf(buf, sizeof buf, "%s \"timeouts\": {\"barrier_ms\": \"x\"}, \"nodes\": []}", good_head);
    expect_error(buf, "timeouts.barrier_ms");
    expect_error("{\"master\": {\"bind\": \"tcp://*:1\", \"connect\": \"tcp://h:1\"}, \"screens\": "
                 "[{\"name\": \"s\", \"bottom_left\": [0,0,0], \"bottom_right\": [1,0,0], \"top_left\": [1,1,0]}]}",
                 "screens[0]");
    expect_error("{\"master\": {\"bind\": \"tcp://*:1\", \"connect\": \"tcp://h:1\"}, \"screens\": "
                 "[{\"name\": \"s\", \"bottom_left\": [0,0], \"bottom_right\": [1,0,0], \"top_left\": [0,1,0]}]}",
                 "screens[0].bottom_left");

    /* A good minimal config, for contrast, with per-screen resolution. */
    char err[512] = "";
    const char *ok = NODES("{\"name\": \"a\", \"screens\": [{\"name\": \"s\", \"resolution\": [8, 6]}]}");
    assert_int_equal(cluster_config_parse(ok, strlen(ok), "ok.json", &cfg, err, sizeof err), 0);
    assert_int_equal(cfg.nodes[0].screens[0].width, 8);
    assert_int_equal(cfg.nodes[0].output, CLUSTER_OUTPUT_WINDOW);
    assert_int_equal(cfg.barrier_timeout_ms, 2000);
    assert_string_equal(cfg.nodes[0].host, "localhost");
}

static void test_missing_file(void **state)
{
    char err[512] = "";
    assert_int_equal(cluster_config_load("/nonexistent/x.json", &cfg, err, sizeof err), -1);
    assert_non_null(strstr(err, "/nonexistent/x.json"));
}

static void test_tracker_transform(void **state)
{
    char buf[2048], err[512] = "";
    snprintf(buf, sizeof buf, "%s \"observer\": {\"tracker_to_cave\": {\"translation\": [1,2,3],"
             " \"rotation_deg\": [0, 90, 0], \"scale\": 0.001}}, \"nodes\": [{\"name\": \"a\","
             " \"screens\": [\"s\"], \"resolution\": [4,4]}]}", good_head);
    assert_int_equal(cluster_config_parse(buf, strlen(buf), "t.json", &cfg, err, sizeof err), 0);
    const float *m = cfg.observer.tracker_to_cave;
    /* x axis of the tracker (1000 mm) maps to -z in the CAVE after a 90 degree yaw. */
    float x = m[0] * 1000 + m[12], z = m[2] * 1000 + m[14];
    assert_float_equal(x, 1.0f, 1e-5);
    assert_float_equal(z, 2.0f, 1e-5);
    assert_float_equal(m[13], 2.0f, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shipped_configs),
        cmocka_unit_test(test_bad_configs),
        cmocka_unit_test(test_missing_file),
        cmocka_unit_test(test_tracker_transform),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
