/* The master's session driven frame by frame, with two real render nodes
 * (cluster_node_run() without GL, in threads) over ZeroMQ: no node yet means no frame;
 * then every frame passes the barrier on both nodes with equal checksums, the scripted
 * head moves at dt per frame, the report counts what happened, and the nodes leave when
 * the session ends. A bad input path fails the session's creation in one line. */
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cjson/cJSON.h>
#include <cmocka.h>

#include "base/textfile.h"
#include "cluster_node.h"
#include "session.h"
#include "system_util.h"

static void start_node(node_thread *n, const char *name, const char *endpoint)
{
    memset(n, 0, sizeof *n);
    snprintf(n->endpoint, sizeof n->endpoint, "%s", endpoint);
    n->desc = (cluster_node_desc){.config = &cfg, .name = name, .endpoint = n->endpoint,
                                  .render = CLUSTER_RENDER_NONE, .output = -1,
                                  .exit_with_master = 1, .quiet = 1};
    assert_int_equal(pthread_create(&n->thread, NULL, node_main, n), 0);
}

static double head_x(session *s)
{
    float head[16];
    params_get(cluster_master_params(session_master(s)), PARAMS_HEAD, head, sizeof head);
    return head[12];
}

static void test_frames_with_two_nodes(void **state)
{
    (void)state;
    char err[512], endpoint[256];
    session_desc sd = {.config = &cfg, .quiet = 1, .dt = 0.25};
    session *s = session_create(&sd, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    cluster_frame_result r;
    assert_int_equal(session_frame(s, &r), SESSION_NO_NODES);
    assert_int_equal(session_frames(s), 0);

    assert_int_equal(cluster_master_endpoint(session_master(s), endpoint, sizeof endpoint), 0);
    node_thread nodes[2];
    start_node(&nodes[0], "a", endpoint);
    start_node(&nodes[1], "b", endpoint);
    assert_int_equal(session_wait_nodes(s, 2, 10000, NULL), 2);
    double last_x = head_x(s);
    uint64_t last_version = 0;
    for (int f = 0; f < 6; f++) {
        assert_int_equal(session_frame(s, &r), SESSION_FRAME_DONE);
        assert_int_equal(r.live, 2);
        assert_int_equal(r.ready, 2);
        assert_int_equal(r.desync, 0);
        assert_true(r.version > last_version);
        last_version = r.version;
        double t;
        params_get(cluster_master_params(session_master(s)), PARAMS_TIME, &t, sizeof t);
        assert_true(t == f * 0.25);
        if (f > 0) /* the scripted head walks */
            assert_true(head_x(s) != last_x);
        last_x = head_x(s);
    }
    assert_int_equal(session_frames(s), 6);
    assert_int_equal(session_last_version(s), last_version);

    char path[] = "/tmp/cavelight-session-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    assert_int_equal(session_write_report(s, path, 1.0), 0);
    char *text = textfile_read(path, NULL, err, sizeof err);
    assert_non_null(text);
    cJSON *report = cJSON_Parse(text);
    assert_non_null(report);
    assert_int_equal(cJSON_GetObjectItem(report, "frames")->valuedouble, 6);
    assert_int_equal(cJSON_GetObjectItem(report, "desyncs")->valuedouble, 0);
    cJSON *per_node = cJSON_GetObjectItem(report, "per_node");
    assert_int_equal(cJSON_GetArraySize(per_node), 2);
    for (int i = 0; i < 2; i++)
        assert_int_equal(cJSON_GetObjectItem(cJSON_GetArrayItem(per_node, i), "frames_ready")->valuedouble, 6);
    cJSON_Delete(report);
    free(text);
    unlink(path);

    session_destroy(s); /* BYE: the nodes leave by themselves */
    for (int i = 0; i < 2; i++) {
        pthread_join(nodes[i].thread, NULL);
        assert_int_equal(nodes[i].rc, 0);
        assert_int_equal(nodes[i].stats.frames, 6);
        assert_int_equal(nodes[i].stats.last_version, last_version);
    }
}

static void test_bad_input_fails_creation(void **state)
{
    (void)state;
    char err[512] = "";
    session_desc sd = {.config = &cfg, .quiet = 1, .input = "/nonexistent/input.json"};
    assert_null(session_create(&sd, err, sizeof err));
    printf("bad input: %s\n", err);
    assert_non_null(strstr(err, "/nonexistent/input.json"));
    assert_null(strchr(err, '\n'));
}

static int setup(void **state)
{
    (void)state;
    char err[512];
    return cluster_config_parse(config_json, strlen(config_json), "session.json", &cfg, err, sizeof err);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_frames_with_two_nodes),
        cmocka_unit_test(test_bad_input_fails_creation),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
