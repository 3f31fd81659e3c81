/* Shared by the system tests: a 2-node insecure config on one small screen, and a node
 * run in a thread of the test's process (cluster_node_run()). */
#ifndef CAVELIGHT_SYSTEM_UTIL_H
#define CAVELIGHT_SYSTEM_UTIL_H

#include <pthread.h>

#include "cluster/cluster_config.h"
#include "cluster_node.h"

static const char *config_json =
    "{\"master\": {\"bind\": \"tcp://127.0.0.1:*\", \"connect\": \"tcp://127.0.0.1:1\"},"
    " \"security\": {\"mode\": \"insecure\"},"
    " \"timeouts\": {\"barrier_ms\": 10000, \"heartbeat_ms\": 50, \"master_ms\": 10000},"
    " \"observer\": {\"home\": [0, 1.7, 0]},"
    " \"screens\": [{\"name\": \"s\", \"bottom_left\": [-1,0,-1], \"bottom_right\": [1,0,-1], \"top_left\": [-1,2,-1]}],"
    " \"nodes\": [{\"name\": \"a\", \"screens\": [\"s\"], \"resolution\": [8,8]},"
    "            {\"name\": \"b\", \"screens\": [\"s\"], \"resolution\": [8,8]}]}";

static cluster_config cfg;

typedef struct node_thread {
    cluster_node_desc desc;
    cluster_node_stats stats;
    char endpoint[256], err[256];
    int rc;
    pthread_t thread;
} node_thread;

static void *node_main(void *arg)
{
    node_thread *n = arg;
    n->rc = cluster_node_run(&n->desc, &n->stats, n->err, sizeof n->err);
    return NULL;
}

#endif
