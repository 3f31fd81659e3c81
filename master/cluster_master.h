/* cluster_master: the master's side of the frame barrier over a ZeroMQ ROUTER socket.
 *
 * Nodes (DEALER, routing id = node name from the config) say HELLO and get a SNAPSHOT at
 * the current version; the next commit raises the history-reset epoch so every node's
 * incremental LPV restarts from the same frame. cluster_master_frame() commits the
 * parameter store as version v, sends FRAME(v, delta since each node's version), waits
 * for READY(v) from every live node until the stall timeout, drops the late ones,
 * compares the frame's GI checksums (a difference is a desync) and sends SWAP(v).
 * The stall timeout adapts: 4 x the p99 READY latency of the last 64 frames, at least
 * timeouts.stall_min_ms and at most barrier_ms. A node whose connection closes (killed,
 * crashed, heartbeats unanswered) is dropped at once from the socket's disconnect event.
 * Every live node hears from the master at least every heartbeat_ms (FRAME, or HEARTBEAT
 * while it waits), so nodes notice a hung master within master_ms.
 * A node that cannot take the scene or a version's parameters says why (REFUSE): logged,
 * counted per node with its last reason, and the node leaves the barrier.
 * Malformed messages and unknown peers are dropped, counted and logged (rate-limited).
 * Handshakes must finish within WIRE_HANDSHAKE_MS, and at most pending_max connections may
 * wait for a node's first message (conn_guard.h): a flood of unfinished handshakes cannot
 * take every descriptor, and a restarted node gets in while one runs.
 * Queues are bounded by high-water marks and a maximum message size; every wait times out. */
#ifndef CAVELIGHT_CLUSTER_MASTER_H
#define CAVELIGHT_CLUSTER_MASTER_H

#include <stddef.h>
#include <stdint.h>

#include "cluster/cluster_config.h"
#include "cluster/params.h"
#include "cluster/wire.h"

typedef struct cluster_master cluster_master;

typedef struct cluster_master_desc {
    const cluster_config *config;
    const char *bind;        /* NULL = config->master_bind */
    int barrier_timeout_ms;  /* 0 = config->barrier_timeout_ms */
    int quiet;               /* 1: log only errors */
    int insecure_anywhere;   /* 1: security "insecure" may bind outside the loopback range */
    int pending_max;         /* connections no node has spoken on yet, at most (conn_guard.h;
                                0 = CONN_GUARD_DEFAULT); the oldest beyond it is shut down */
    const params_schema *schema; /* the store's keys (copied); NULL: gi_params_schema() */
} cluster_master_desc;

typedef enum cluster_peer_state {
    CLUSTER_PEER_ABSENT = 0, /* never said HELLO (or left) */
    CLUSTER_PEER_LIVE,       /* takes part in the barrier */
    CLUSTER_PEER_DROPPED,    /* missed a barrier; must say HELLO again */
} cluster_peer_state;

typedef struct cluster_peer_stats {
    cluster_peer_state state;
    uint64_t version;        /* last version the node applied (snapshot or READY) */
    uint64_t checksum;       /* the frame's GI checksum of its last READY */
    uint64_t frames_ready;
    uint32_t joins, drops;
    uint32_t refusals;       /* REFUSE messages: it could not take the scene or parameters */
    uint32_t refused_what;   /* of the last one: wire_refuse_what */
    char refusal[WIRE_TEXT_MAX + 1]; /* the last one's reason, as the node gave it */
    float timings[WIRE_TIMING_COUNT]; /* of the last READY */
    double ready_ms;         /* FRAME sent to READY received, last frame */
} cluster_peer_stats;

typedef struct cluster_master_stats {
    uint64_t frames, desyncs;
    uint64_t frames_rendered; /* frames with at least one node READY */
    uint64_t refusals;       /* REFUSE messages from nodes */
    uint64_t malformed, unknown_peers, stale;
    uint64_t bytes_sent, bytes_received, messages_sent, messages_received;
    uint64_t joins, drops;
    uint64_t refused;        /* connections refused for an unknown CURVE key */
    uint64_t disconnects;    /* live nodes dropped when their connection closed */
    uint64_t handshakes_failed;
    uint64_t unauthenticated_dropped; /* connections shut down by the pending_max bound */
    uint64_t accept_failures; /* connections the socket could not accept (no descriptor left) */
    long fd_limit;           /* the process's descriptor limit when the master started */
} cluster_master_stats;

typedef struct cluster_frame_result {
    uint64_t version;
    int live;                /* nodes in the barrier */
    int ready;               /* of them, READY in time (and swapped) */
    int dropped;             /* dropped at this barrier */
    int desync;              /* 1 when READY checksums differed */
    uint32_t epoch;          /* history-reset epoch of this version */
    double barrier_ms;       /* FRAME sends to the last READY (or the timeout) */
    int timeout_ms;          /* the stall timeout this barrier used (adaptive) */
    double round_trip_ms;    /* commit to SWAP sent */
    size_t frame_bytes;      /* bytes of one FRAME message (to a node at v-1) */
} cluster_frame_result;

/* Returns NULL with a one-line reason in err: among them security "insecure" on an
 * endpoint outside the loopback range (127.0.0.0/8, ::1, ipc) without insecure_anywhere. */
cluster_master *cluster_master_create(const cluster_master_desc *desc, char *err, size_t errlen);
/* Sends BYE(shutdown) to every live node, then closes. */
void cluster_master_destroy(cluster_master *m);
/* The store to set keys in before each cluster_master_frame(). */
params_store *cluster_master_params(cluster_master *m);
/* Handles HELLO/HEARTBEAT/BYE for up to timeout_ms or until `count` nodes are live.
 * Returns the number of live nodes. */
int cluster_master_wait_nodes(cluster_master *m, int count, int timeout_ms);
/* Between paced frames: handles messages and keeps the heartbeats going until the
 * clock_now_ms() time until_ms (a sleep would let nodes think the master is gone). */
void cluster_master_idle(cluster_master *m, double until_ms);
/* One frame: commit, FRAME, barrier, SWAP. Returns 0, or -1 when no node is live. */
int cluster_master_frame(cluster_master *m, cluster_frame_result *out);
void cluster_master_stats_get(const cluster_master *m, cluster_master_stats *out);
void cluster_master_peer_stats(const cluster_master *m, int node, cluster_peer_stats *out);
int cluster_master_live_count(const cluster_master *m);
/* 0 when every node would take a snapshot of the store as it is (params_apply(), the
 * nodes' own check); else -1 with the first key they would refuse and its value in err. */
int cluster_master_check_params(cluster_master *m, char *err, size_t errlen);
/* The endpoint actually bound (resolves a wildcard port such as tcp://127.0.0.1:*). */
int cluster_master_endpoint(const cluster_master *m, char *buf, size_t cap);

#endif
