/* cluster_client: a render node's connection to the master (ZeroMQ DEALER, routing id =
 * node name).
 *
 * Says HELLO (name, config hash) and mirrors the master's parameter store: a SNAPSHOT
 * replaces it, FRAME(v, delta) applies on top when the base version matches (otherwise
 * the client asks for a new snapshot). cluster_client_poll() returns one event at a time:
 * FRAME v (render it, then cluster_client_ready()), SWAP v (present), LOST (the master's
 * connection closed, or nothing heard from it for master_ms: keep the window, the client
 * says HELLO as soon as a master answers), SHUTDOWN, REFUSED. It prints one line per join
 * naming what happened (first join, reconnect, new session, resync). A FRAME already overtaken by a newer one in the queue is
 * applied but not returned, so a node that stalled catches up instead of replaying.
 * Parameters that fail params_apply() are refused, logged, and the master is told why
 * (REFUSE). Heartbeats go out while idle. Malformed input is dropped and counted. A socket that
 * stays unconnected and silent for 2 s while not joined is replaced (ZeroMQ gives up on a
 * connection after a protocol error such as an oversized message). */
#ifndef CAVELIGHT_CLUSTER_CLIENT_H
#define CAVELIGHT_CLUSTER_CLIENT_H

#include <stddef.h>
#include <stdint.h>

#include "cluster/cluster_config.h"
#include "cluster/params.h"
#include "cluster/wire.h"

typedef struct cluster_client cluster_client;

typedef struct cluster_client_desc {
    const cluster_config *config;
    const char *name;      /* this node, as named in the config */
    const char *endpoint;  /* NULL = config->master_connect */
    int quiet;             /* 1: log only errors */
    int refuse_only;       /* 1: never say HELLO: a node that only tells the master why it
                              cannot take part (cluster_client_refuse) */
    const params_schema *schema; /* the store's keys (copied); NULL: gi_params_schema() */
} cluster_client_desc;

typedef enum cluster_event_type {
    CLUSTER_EVENT_NONE = 0, /* timeout */
    CLUSTER_EVENT_FRAME,    /* params now hold version `version`: render it */
    CLUSTER_EVENT_SWAP,     /* present the frame `version` */
    CLUSTER_EVENT_LOST,     /* the master's connection closed, or it went silent (lost) */
    CLUSTER_EVENT_JOINED,   /* a snapshot arrived (first join or after LOST/drop) */
    CLUSTER_EVENT_SHUTDOWN, /* the master ended the session */
    CLUSTER_EVENT_REFUSED,  /* the master runs another config */
} cluster_event_type;

typedef enum cluster_lost_reason {
    CLUSTER_LOST_CLOSED = 1, /* the connection closed: killed, crashed, network down */
    CLUSTER_LOST_SILENT,     /* nothing heard for master_ms: hung or stopped */
} cluster_lost_reason;

typedef struct cluster_event {
    cluster_event_type type;
    cluster_lost_reason lost; /* LOST: why */
    uint64_t version;
    double apply_ms;        /* FRAME: time spent applying deltas */
} cluster_event;

typedef struct cluster_client_stats {
    uint64_t frames, skipped, snapshots, swaps, malformed, resyncs, lost, reopens;
    uint64_t handshakes_failed; /* with the master; each logged (rate-limited) with its likely cause */
    uint64_t bytes_sent, bytes_received;
} cluster_client_stats;

cluster_client *cluster_client_create(const cluster_client_desc *desc, char *err, size_t errlen);
/* Sends BYE(leaving) and closes. */
void cluster_client_destroy(cluster_client *c);
/* Waits up to timeout_ms for the next event; returns its type (NONE on timeout). */
cluster_event_type cluster_client_poll(cluster_client *c, int timeout_ms, cluster_event *ev);
const params_store *cluster_client_params(const cluster_client *c);
/* REFUSE: tells the master why this node cannot take the scene (or a version's
 * parameters), waiting up to wait_ms for a connection. why is cut to WIRE_TEXT_MAX
 * printable characters. Returns 0 when it went out. */
int cluster_client_refuse(cluster_client *c, wire_refuse_what what, uint64_t version, const char *why,
                          int wait_ms);
/* READY(version, checksum, timings in ms as in wire_timing). */
int cluster_client_ready(cluster_client *c, uint64_t version, uint64_t checksum,
                         const float timings[WIRE_TIMING_COUNT]);
void cluster_client_stats_get(const cluster_client *c, cluster_client_stats *out);
/* The rate limit of the lines about the link to the master (joins, losses, drops, the end
 * of a session), which a master coming and going, or a stranger posing as one, repeats:
 * returns 1 to print one (never when quiet), with note saying how many were left out. */
int cluster_client_log_link(cluster_client *c, char *note, size_t cap);

#endif
