#include "cluster_master.h"
#include "gi/gi_settings.h"
#include "base/xalloc.h"

#include <arpa/inet.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <zmq.h>

#include "base/clock.h"
#include "base/ratelog.h"
#include "cluster_auth.h"
#include "conn_guard.h"

typedef struct peer {
    cluster_peer_stats s;
    int in_barrier;          /* got FRAME(v) of the current barrier */
    int ready;               /* sent READY(v) for it */
    int framed;              /* sent a FRAME since it joined */
    ratelog log;             /* lines about it: joins, leaves, drops, refusals */
    double frame_sent;       /* ms clock */
    double last_heard;
    int fd;                  /* connection its last message came on (-1 unknown) */
    uint8_t rid[256];        /* ROUTER routing id of that connection: where to send */
    size_t rid_len;          /* 0: never heard */
} peer;

/* The stall timeout adapts to the READY latencies of recent frames (ring of samples). */
enum { STALL_SAMPLES = 64, STALL_MIN_SAMPLES = 16, STALL_FACTOR = 4 };
/* Messages read before a closed connection drops its node (a bound: a flood cannot hold it). */
enum { DRAIN_BEFORE_DROP = 64 };

struct cluster_master {
    const cluster_config *cfg;
    void *ctx, *sock, *monitor;
    cluster_auth *auth;
    conn_guard *guard;       /* connections no node has spoken on yet */
    ratelog unknown_log, malformed_log, handshake_log, desync_log, guard_log, accept_log;
    int closing;             /* destroy() runs: a HELLO gets BYE(shutdown), not a snapshot */
    double ready_ring[STALL_SAMPLES];
    int ready_count;
    params_schema schema;    /* the store's keys (gi_params_schema()) */
    params_store params;
    uint64_t hello_hash;     /* what a node's HELLO must carry (params_session_hash()) */
    int barrier_timeout_ms;
    int quiet;
    int raise_epoch;         /* a node joined: the next commit resets LPV history */
    peer peers[CLUSTER_MAX_NODES];
    cluster_master_stats st;
    double last_heartbeat;   /* last time every live node was sent something */
    uint8_t buf[WIRE_MAX_MESSAGE];
    uint8_t params_buf[PARAMS_ENCODED_MAX];
    uint8_t common_buf[PARAMS_ENCODED_MAX]; /* the delta shared by nodes at v-1 (50 KB: not on the stack) */
};

static int send_to(cluster_master *m, int node, const wire_msg *msg)
{
    size_t len = wire_encode(msg, m->buf, sizeof m->buf);
    if (len == 0)
        return -1;
    const peer *p = &m->peers[node];
    /* ROUTER drops a message for a peer that is gone or whose queue is full: never blocks. */
    if (p->rid_len == 0 || zmq_send(m->sock, p->rid, p->rid_len, ZMQ_SNDMORE | ZMQ_DONTWAIT) < 0)
        return -1;
    if (zmq_send(m->sock, m->buf, len, ZMQ_DONTWAIT) < 0)
        return -1;
    m->st.bytes_sent += len;
    m->st.messages_sent++;
    return 0;
}

static void send_snapshot(cluster_master *m, int node)
{
    size_t n = params_encode_snapshot(&m->params, m->params_buf, sizeof m->params_buf);
    wire_msg msg = {.type = WIRE_SNAPSHOT, .version = m->params.version,
                    .params = m->params_buf, .params_len = n};
    send_to(m, node, &msg);
}

static void send_bye(cluster_master *m, int node, uint32_t reason)
{
    wire_msg msg = {.type = WIRE_BYE, .reason = reason};
    snprintf(msg.name, sizeof msg.name, "master");
    send_to(m, node, &msg);
}

static int live_count(const cluster_master *m)
{
    int n = 0;
    for (int i = 0; i < m->cfg->node_count; i++)
        n += m->peers[i].s.state == CLUSTER_PEER_LIVE;
    return n;
}

int cluster_master_live_count(const cluster_master *m) { return live_count(m); }

/* Lines about a node's membership follow what peers send (a HELLO flood is a join or a
 * refusal each): rate-limited per node. Returns 1 to print, with note saying how many
 * lines were left out before this one. */
static int node_log(cluster_master *m, int node, char *note, size_t cap)
{
    uint64_t skipped = 0;
    note[0] = 0;
    if (!ratelog_event(&m->peers[node].log, clock_now_ms(), &skipped))
        return 0;
    if (skipped)
        snprintf(note, cap, " (%llu lines about node %s not logged)", (unsigned long long)skipped,
                 m->cfg->nodes[node].name);
    return 1;
}

static void join(cluster_master *m, int node, const wire_msg *msg)
{
    peer *p = &m->peers[node];
    char note[96];
    if (msg->config_hash != m->hello_hash) {
        if (node_log(m, node, note, sizeof note))
            fprintf(stderr, "cavelight-master: node %s runs another cluster config, scene, application "
                    "or build (hash %016llx, master %s has %016llx): refused, give both the same "
                    "file, scene, --app and cavelight version%s\n",
                    m->cfg->nodes[node].name, (unsigned long long)msg->config_hash, m->cfg->path,
                    (unsigned long long)m->hello_hash, note);
        send_bye(m, node, WIRE_BYE_CONFIG_MISMATCH);
        return;
    }
    /* A HELLO again before any frame (the answer crossed it, or it came on a fresh
     * connection): the snapshot again, not a second join that resets every node's LPV
     * history once frames run. */
    if (p->s.state == CLUSTER_PEER_LIVE && !p->framed) {
        p->s.version = m->params.version;
        send_snapshot(m, node);
        return;
    }
    int rejoin = p->s.joins > 0;
    p->s.state = CLUSTER_PEER_LIVE;
    p->s.version = m->params.version;
    p->s.joins++;
    p->in_barrier = 0;
    p->ready = 0;
    p->framed = 0;
    m->st.joins++;
    m->raise_epoch = 1;
    send_snapshot(m, node);
    if (!m->quiet && node_log(m, node, note, sizeof note))
        fprintf(stderr, "cavelight-master: node %s %s at version %llu%s\n", m->cfg->nodes[node].name,
                rejoin ? "rejoined" : "joined", (unsigned long long)m->params.version, note);
}

/* Reads one ROUTER message, [routing id][body], into id and body. Frames beyond the second
 * are read and discarded so that the next message starts clean. Returns how many frames the
 * message had, 0 when none was waiting. */
static int recv_message(cluster_master *m, zmq_msg_t *id, zmq_msg_t *body)
{
    if (zmq_msg_recv(id, m->sock, ZMQ_DONTWAIT) < 0)
        return 0;
    int parts = 1;
    if (zmq_msg_more(id) && zmq_msg_recv(body, m->sock, 0) >= 0) {
        parts++;
        while (zmq_msg_more(body)) {
            zmq_msg_t extra;
            zmq_msg_init(&extra);
            int rc = zmq_msg_recv(&extra, m->sock, 0);
            int more = rc >= 0 && zmq_msg_more(&extra);
            zmq_msg_close(&extra);
            parts++;
            if (!more)
                break;
        }
    }
    return parts;
}

/* Who sent it: in curve mode the key's node, whatever the routing id; insecure, the
 * routing id's name. -1 (counted and logged) for anybody else. */
static int sender(cluster_master *m, zmq_msg_t *id, zmq_msg_t *body)
{
    char rid_name[WIRE_NAME_MAX + 1] = "";
    size_t idlen = zmq_msg_size(id);
    if (idlen <= WIRE_NAME_MAX) {
        memcpy(rid_name, zmq_msg_data(id), idlen);
        rid_name[idlen] = 0;
    }
    int node = cluster_auth_node(m->auth, body, wire_name_valid(rid_name) ? rid_name : NULL);
    uint64_t skipped = 0;
    if (node < 0) {
        m->st.unknown_peers++;
        if (ratelog_event(&m->unknown_log, clock_now_ms(), &skipped))
            fprintf(stderr, "cavelight-master: message from unknown or unauthenticated peer '%s' dropped "
                    "(%llu so far, %llu not logged): only nodes named in %s may connect\n",
                    wire_name_valid(rid_name) ? rid_name : "?", (unsigned long long)m->st.unknown_peers,
                    (unsigned long long)skipped, m->cfg->path);
    }
    return node;
}

/* Decodes a node's message into msg: 0, or -1 (counted and logged) when it is malformed,
 * of a master-to-node type, or speaks for another node. */
static int decode_from(cluster_master *m, int node, int parts, zmq_msg_t *body, wire_msg *msg)
{
    const char *name = m->cfg->nodes[node].name;
    wire_error e = parts == 2 ? wire_decode(zmq_msg_data(body), zmq_msg_size(body), msg) : WIRE_E_PAYLOAD;
    if (e == WIRE_OK && (msg->type == WIRE_SNAPSHOT || msg->type == WIRE_FRAME || msg->type == WIRE_SWAP))
        e = WIRE_E_TYPE; /* master-to-node messages */
    if (e == WIRE_OK && strcmp(msg->name, name) != 0)
        e = WIRE_E_PAYLOAD; /* a node speaking for another */
    if (e == WIRE_OK)
        return 0;
    m->st.malformed++;
    uint64_t skipped = 0;
    if (ratelog_event(&m->malformed_log, clock_now_ms(), &skipped))
        fprintf(stderr, "cavelight-master: malformed message from node %s dropped (%s; %llu so far, "
                "%llu not logged)\n", name, wire_error_string(e), (unsigned long long)m->st.malformed,
                (unsigned long long)skipped);
    return -1;
}

/* A node that cannot take the scene (it leaves) or a version's parameters (it asks again
 * later): its reason, as it gave it, in the log and the statistics; out of the barrier. */
static void on_refuse(cluster_master *m, int node, const wire_msg *msg)
{
    peer *p = &m->peers[node];
    char note[96];
    m->st.refusals++;
    p->s.refusals++;
    p->s.refused_what = msg->reason;
    snprintf(p->s.refusal, sizeof p->s.refusal, "%s", msg->text);
    p->s.state = CLUSTER_PEER_ABSENT;
    p->in_barrier = 0;
    if (!node_log(m, node, note, sizeof note))
        return;
    if (msg->reason == WIRE_REFUSE_PARAMS)
        fprintf(stderr, "cavelight-master: node %s refused the parameters of version %llu: %s%s\n",
                m->cfg->nodes[node].name, (unsigned long long)msg->version, msg->text, note);
    else
        fprintf(stderr, "cavelight-master: node %s refused the scene: %s%s\n", m->cfg->nodes[node].name, msg->text,
                note);
}

static void on_ready(cluster_master *m, peer *p, const wire_msg *msg)
{
    if (p->s.state != CLUSTER_PEER_LIVE || !p->in_barrier || p->ready || msg->version != m->params.version) {
        m->st.stale++;
        return;
    }
    p->ready = 1;
    p->s.version = msg->version;
    p->s.checksum = msg->checksum;
    p->s.frames_ready++;
    memcpy(p->s.timings, msg->timings, sizeof p->s.timings);
    p->s.ready_ms = p->last_heard - p->frame_sent;
    m->ready_ring[m->ready_count++ % STALL_SAMPLES] = p->s.ready_ms;
}

/* A valid message of a node: where it came from (its newest connection, where answers go)
 * and what it says. */
static void dispatch(cluster_master *m, int node, zmq_msg_t *id, zmq_msg_t *body, const wire_msg *msg)
{
    peer *p = &m->peers[node];
    p->last_heard = clock_now_ms();
    int fd = (int)zmq_msg_get(body, ZMQ_SRCFD);
    if (fd != p->fd) {
        /* The node speaks on fd now; a connection it spoke on before (still open) is
         * nobody's again, and counts against the bound like a new one. */
        char shed[64];
        if (p->fd >= 0 && conn_guard_add(m->guard, p->fd, p->last_heard, shed, sizeof shed))
            m->st.unauthenticated_dropped++;
        conn_guard_forget(m->guard, fd);
        p->fd = fd;
    }
    size_t idlen = zmq_msg_size(id);
    if (idlen <= sizeof p->rid) { /* a restart makes a new connection */
        memcpy(p->rid, zmq_msg_data(id), idlen);
        p->rid_len = idlen;
    }
    switch (msg->type) {
    case WIRE_HELLO:
        if (m->closing)
            send_bye(m, node, WIRE_BYE_SHUTDOWN); /* no new session with a master that is leaving */
        else
            join(m, node, msg);
        break;
    case WIRE_READY:
        on_ready(m, p, msg);
        break;
    case WIRE_REFUSE:
        on_refuse(m, node, msg);
        break;
    case WIRE_BYE: {
        char note[96];
        if (p->s.state == CLUSTER_PEER_LIVE && !m->quiet && node_log(m, node, note, sizeof note))
            fprintf(stderr, "cavelight-master: node %s left%s\n", m->cfg->nodes[node].name, note);
        p->s.state = CLUSTER_PEER_ABSENT;
        p->in_barrier = 0;
        break;
    }
    default: /* HEARTBEAT: last_heard is enough */
        break;
    }
}

/* Receives one message if any is queued. Returns 1 when a message was handled (valid or
 * not), 0 when none was waiting. */
static int handle_one(cluster_master *m)
{
    zmq_msg_t id, body;
    zmq_msg_init(&id);
    zmq_msg_init(&body);
    int parts = recv_message(m, &id, &body);
    if (parts > 0) {
        m->st.messages_received++;
        m->st.bytes_received += zmq_msg_size(&body);
        wire_msg msg;
        int node = sender(m, &id, &body);
        if (node >= 0 && decode_from(m, node, parts, &body, &msg) == 0)
            dispatch(m, node, &id, &body, &msg);
    }
    zmq_msg_close(&id);
    zmq_msg_close(&body);
    return parts > 0;
}

/* A node whose connection closed (process killed or crashed, heartbeat timed out) leaves
 * the barrier at once instead of after the timeout. */
static void drop_disconnected(cluster_master *m, int fd)
{
    for (int i = 0; i < m->cfg->node_count; i++) {
        peer *p = &m->peers[i];
        if (p->fd != fd)
            continue;
        p->fd = -1;
        if (p->s.state != CLUSTER_PEER_LIVE)
            continue;
        if (m->closing) { /* the session's end: nodes leave after our BYE, nobody is dropped */
            p->s.state = CLUSTER_PEER_ABSENT;
            continue;
        }
        p->s.state = CLUSTER_PEER_DROPPED;
        p->s.drops++;
        m->st.drops++;
        m->st.disconnects++;
        char note[96];
        if (node_log(m, i, note, sizeof note))
            fprintf(stderr, "cavelight-master: node %s disconnected: dropped, the others go on%s\n",
                    m->cfg->nodes[i].name, note);
    }
}

/* A connection accepted on fd: counted against the bound until a node speaks on it
 * (a node's first message may have come before the event: then it is the node's already). */
static void on_accepted(cluster_master *m, int fd)
{
    for (int i = 0; i < m->cfg->node_count; i++)
        if (m->peers[i].fd == fd)
            return;
    char shed[64];
    uint64_t skipped = 0;
    if (!conn_guard_add(m->guard, fd, clock_now_ms(), shed, sizeof shed))
        return;
    m->st.unauthenticated_dropped++;
    if (ratelog_event(&m->guard_log, clock_now_ms(), &skipped))
        fprintf(stderr, "cavelight-master: %d connections wait for a node's first message: shut the oldest from %s "
                "down (%llu so far, %llu not logged); a flood of unfinished handshakes? nodes still get in\n",
                conn_guard_count(m->guard), shed, (unsigned long long)m->st.unauthenticated_dropped,
                (unsigned long long)skipped);
}

static void on_handshake_failed(cluster_master *m, uint16_t event)
{
    uint64_t skipped = 0;
    m->st.handshakes_failed++;
    if (ratelog_event(&m->handshake_log, clock_now_ms(), &skipped))
        fprintf(stderr, "cavelight-master: a connection failed its handshake (%s; %llu so far, %llu "
                "not logged): a peer without this cluster's security settings\n",
                event == ZMQ_EVENT_HANDSHAKE_FAILED_AUTH ? "authentication" : "protocol, mechanism or timeout",
                (unsigned long long)m->st.handshakes_failed, (unsigned long long)skipped);
}

static int event_pending(cluster_master *m)
{
    int events = 0;
    size_t len = sizeof events;
    return zmq_getsockopt(m->monitor, ZMQ_EVENTS, &events, &len) == 0 && (events & ZMQ_POLLIN);
}

/* Socket events: [u16 event, u32 value (a descriptor, or an error)] then the endpoint. */
static int handle_event(cluster_master *m)
{
    zmq_msg_t ev, ep;
    zmq_msg_init(&ev);
    zmq_msg_init(&ep);
    int got = zmq_msg_recv(&ev, m->monitor, ZMQ_DONTWAIT) >= 0;
    if (got && zmq_msg_more(&ev))
        zmq_msg_recv(&ep, m->monitor, 0);
    if (got && zmq_msg_size(&ev) >= 6) {
        uint16_t event;
        uint32_t value;
        memcpy(&event, zmq_msg_data(&ev), 2);
        memcpy(&value, (const uint8_t *)zmq_msg_data(&ev) + 2, 4);
        uint64_t skipped = 0;
        if (event == ZMQ_EVENT_ACCEPTED) {
            on_accepted(m, (int)value);
        } else if (event == ZMQ_EVENT_DISCONNECTED) {
            conn_guard_forget(m->guard, (int)value);
            /* What came before the close is read first: a node that said BYE has left. Up
             * to the next event only: a new connection on the same descriptor number has
             * its ACCEPTED event before its messages, which must not count as the old one's. */
            for (int k = 0; k < DRAIN_BEFORE_DROP && !event_pending(m) && handle_one(m); k++)
                ;
            drop_disconnected(m, (int)value);
        } else if (event == ZMQ_EVENT_ACCEPT_FAILED) {
            m->st.accept_failures++;
            if (ratelog_event(&m->accept_log, clock_now_ms(), &skipped))
                fprintf(stderr, "cavelight-master: cannot accept a connection: %s (%llu so far, %llu not logged; "
                        "descriptor limit %ld)\n", zmq_strerror((int)value), (unsigned long long)m->st.accept_failures,
                        (unsigned long long)skipped, m->st.fd_limit);
        } else if (event & (ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL | ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL |
                            ZMQ_EVENT_HANDSHAKE_FAILED_AUTH)) {
            on_handshake_failed(m, event);
        }
    }
    zmq_msg_close(&ev);
    zmq_msg_close(&ep);
    return got;
}

/* Every live node hears from the master at least every heartbeat_ms (a FRAME counts as
 * one), through barrier waits, paced frames and waits for nodes, so that nodes can tell a
 * stopped master within master_ms. A closing master stays silent: its BYE was the end. */
static void heartbeat(cluster_master *m, double now)
{
    if (m->closing || now - m->last_heartbeat < m->cfg->heartbeat_ms)
        return;
    m->last_heartbeat = now;
    wire_msg hb = {.type = WIRE_HEARTBEAT, .version = m->params.version};
    snprintf(hb.name, sizeof hb.name, "master");
    for (int i = 0; i < m->cfg->node_count; i++)
        if (m->peers[i].s.state == CLUSTER_PEER_LIVE)
            send_to(m, i, &hb);
}

/* Handles messages and socket events, and sends heartbeats, until the deadline or until
 * done(m) holds. */
static void pump(cluster_master *m, double deadline, int (*done)(cluster_master *, void *), void *arg)
{
    for (;;) {
        /* The deadline and the heartbeats hold even under a flood of messages. */
        while (handle_event(m) || handle_one(m)) {
            heartbeat(m, clock_now_ms());
            if ((done && done(m, arg)) || clock_now_ms() >= deadline)
                return;
        }
        if (done && done(m, arg))
            return;
        double now = clock_now_ms();
        heartbeat(m, now);
        double left = deadline - now;
        if (left <= 0)
            return;
        double beat = m->last_heartbeat + m->cfg->heartbeat_ms - now;
        if (!m->closing && beat < left)
            left = beat > 0 ? beat : 0;
        zmq_pollitem_t items[2] = {{.socket = m->sock, .events = ZMQ_POLLIN},
                                   {.socket = m->monitor, .events = ZMQ_POLLIN}};
        if (zmq_poll(items, 2, (long)(left + 0.999)) < 0 && errno != EINTR)
            return;
    }
}

/* How long the barrier waits: STALL_FACTOR x the p99 READY latency of recent frames,
 * at least stall_min_ms and at most barrier_ms; barrier_ms until there are samples. */
static int stall_timeout_ms(const cluster_master *m)
{
    int n = m->ready_count < STALL_SAMPLES ? m->ready_count : STALL_SAMPLES;
    if (n < STALL_MIN_SAMPLES)
        return m->barrier_timeout_ms;
    double v[STALL_SAMPLES];
    memcpy(v, m->ready_ring, (size_t)n * sizeof *v);
    for (int i = 1; i < n; i++) /* insertion sort: 64 values */
        for (int k = i; k > 0 && v[k - 1] > v[k]; k--) {
            double t = v[k];
            v[k] = v[k - 1];
            v[k - 1] = t;
        }
    double p99 = v[(int)(0.99 * (n - 1) + 0.5)];
    double t = STALL_FACTOR * p99;
    if (t < m->cfg->stall_min_ms)
        t = m->cfg->stall_min_ms;
    return t < m->barrier_timeout_ms ? (int)t : m->barrier_timeout_ms;
}

/* 1 when a bound endpoint is reachable from this machine only: ipc, inproc, or tcp on
 * 127.0.0.0/8 or ::1 (an IPv4-mapped 127.x too). */
static int endpoint_is_local(const char *ep)
{
    if (strncmp(ep, "ipc://", 6) == 0 || strncmp(ep, "inproc://", 9) == 0)
        return 1;
    if (strncmp(ep, "tcp://", 6) != 0)
        return 0;
    char host[256];
    const char *colon = strrchr(ep, ':');
    size_t len = colon && colon > ep + 6 ? (size_t)(colon - (ep + 6)) : 0;
    if (len == 0 || len >= sizeof host)
        return 0;
    memcpy(host, ep + 6, len);
    host[len] = 0;
    if (host[0] == '[' && host[len - 1] == ']') {
        memmove(host, host + 1, len - 2);
        host[len - 2] = 0;
    }
    struct in_addr a4;
    struct in6_addr a6;
    if (inet_pton(AF_INET, host, &a4) == 1)
        return (ntohl(a4.s_addr) >> 24) == 127;
    if (inet_pton(AF_INET6, host, &a6) != 1)
        return 0;
    return IN6_IS_ADDR_LOOPBACK(&a6) || (IN6_IS_ADDR_V4MAPPED(&a6) && a6.s6_addr[12] == 127);
}

/* Insecure mode trusts anybody who reaches the port: refused outside the loopback range
 * unless asked for, and always said, naming the endpoint actually bound. */
static int check_insecure(cluster_master *m, const cluster_master_desc *desc, char *err, size_t errlen)
{
    char ep[256] = "?";
    cluster_master_endpoint(m, ep, sizeof ep);
    int local = endpoint_is_local(ep);
    if (!local && !desc->insecure_anywhere) {
        snprintf(err, errlen, "cluster master: security \"insecure\" in %s, and %s (from %s) is outside the "
                 "loopback range: any host that reaches it could join as a node or steer the nodes; bind "
                 "127.0.0.1, use security \"curve\" (--keygen), or pass --insecure-anywhere", m->cfg->path, ep,
                 desc->bind ? "--bind" : "master.bind");
        return -1;
    }
    if (!m->quiet)
        fprintf(stderr, "cavelight-master: security \"insecure\" in %s: any peer that reaches %s may join as a "
                "node (%s)\n", m->cfg->path, ep, local ? "local runs and tests only" : "--insecure-anywhere");
    return 0;
}

cluster_master *cluster_master_create(const cluster_master_desc *desc, char *err, size_t errlen)
{
    cluster_master *m = xcalloc(1, sizeof *m);
    m->cfg = desc->config;
    m->quiet = desc->quiet;
    m->barrier_timeout_ms = desc->barrier_timeout_ms > 0 ? desc->barrier_timeout_ms : m->cfg->barrier_timeout_ms;
    if (desc->schema)
        m->schema = *desc->schema;
    else
        gi_params_schema(&m->schema);
    params_init(&m->params, &m->schema);
    m->hello_hash = params_session_hash(m->cfg->hash, &m->schema);
    m->ctx = zmq_ctx_new();
    m->sock = m->ctx ? zmq_socket(m->ctx, ZMQ_ROUTER) : NULL;
    const char *ep = desc->bind ? desc->bind : m->cfg->master_bind;
    if (!m->sock) {
        snprintf(err, errlen, "cluster master: cannot create a ZeroMQ socket: %s", zmq_strerror(errno));
        cluster_master_destroy(m);
        return NULL;
    }
    int zero = 0, hwm = 1000, handshake = WIRE_HANDSHAKE_MS;
    int64_t maxmsg = WIRE_MAX_MESSAGE;
    zmq_setsockopt(m->sock, ZMQ_LINGER, &zero, sizeof zero);
    zmq_setsockopt(m->sock, ZMQ_SNDHWM, &hwm, sizeof hwm);
    zmq_setsockopt(m->sock, ZMQ_RCVHWM, &hwm, sizeof hwm);
    zmq_setsockopt(m->sock, ZMQ_MAXMSGSIZE, &maxmsg, sizeof maxmsg);
    zmq_setsockopt(m->sock, ZMQ_HANDSHAKE_IVL, &handshake, sizeof handshake);
    m->guard = conn_guard_create(desc->pending_max);
    struct rlimit fds;
    m->st.fd_limit = getrlimit(RLIMIT_NOFILE, &fds) == 0 ? (long)fds.rlim_cur : -1;
    /* Insecure, the routing id is the node's name: a restarted node's new connection
     * takes it over (ZMQ_ROUTER_HANDOVER), as anybody's could. Curve: no handover, so a
     * peer holding one node's key cannot displace another; nodes set no routing ids (ROUTER
     * makes unique ones), the key names the node, and a restarted node's new connection is
     * found from its first message. */
    if (m->cfg->security == CLUSTER_SECURITY_INSECURE) {
        int one = 1;
        zmq_setsockopt(m->sock, ZMQ_ROUTER_HANDOVER, &one, sizeof one);
    }
    /* No ZMTP heartbeats (ZMQ_HEARTBEAT_IVL): with them libzmq 4.3.4 aborts
     * (stream_engine_base.cpp:331 !_io_error) when a peer sends garbage. A peer that goes
     * silent without closing is caught by the stall timeout and the protocol's HEARTBEAT. */
    m->auth = cluster_auth_start(m->ctx, m->sock, m->cfg, m->quiet, err, errlen);
    if (!m->auth) {
        cluster_master_destroy(m);
        return NULL;
    }
    char mon[64];
    snprintf(mon, sizeof mon, "inproc://cavelight-master-monitor-%p", (void *)m);
    int events = ZMQ_EVENT_ACCEPTED | ZMQ_EVENT_ACCEPT_FAILED | ZMQ_EVENT_DISCONNECTED |
                 ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL | ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL |
                 ZMQ_EVENT_HANDSHAKE_FAILED_AUTH;
    if (zmq_socket_monitor(m->sock, mon, events) != 0 ||
        !(m->monitor = zmq_socket(m->ctx, ZMQ_PAIR)) || zmq_setsockopt(m->monitor, ZMQ_LINGER, &zero, sizeof zero) != 0 ||
        zmq_connect(m->monitor, mon) != 0) {
        snprintf(err, errlen, "cluster master: cannot watch the socket's connections: %s", zmq_strerror(errno));
        cluster_master_destroy(m);
        return NULL;
    }
    for (int i = 0; i < CLUSTER_MAX_NODES; i++)
        m->peers[i].fd = -1;
    if (zmq_bind(m->sock, ep) != 0) {
        snprintf(err, errlen, "cluster master: cannot bind %s (%s, from %s): free the port or pass --bind",
                 ep, zmq_strerror(errno), desc->bind ? "--bind" : m->cfg->path);
        cluster_master_destroy(m);
        return NULL;
    }
    if (m->cfg->security == CLUSTER_SECURITY_INSECURE && check_insecure(m, desc, err, errlen) != 0) {
        cluster_master_destroy(m);
        return NULL;
    }
    return m;
}

static int no_live_node(cluster_master *m, void *arg)
{
    (void)arg;
    return live_count(m) == 0;
}

void cluster_master_destroy(cluster_master *m)
{
    if (!m)
        return;
    if (m->sock) {
        for (int i = 0; m->cfg && i < m->cfg->node_count; i++)
            if (m->peers[i].s.state != CLUSTER_PEER_ABSENT)
                send_bye(m, i, WIRE_BYE_SHUTDOWN);
        /* ZeroMQ may drop what is still queued when the socket closes, linger or not (seen
         * here under load: the last SWAP and the BYE never reached a node). Live nodes
         * answer the BYE with theirs, so wait for that, briefly, before closing. */
        m->quiet = 1;
        m->closing = 1;
        if (m->cfg && m->monitor)
            pump(m, clock_now_ms() + 1000, no_live_node, NULL);
        int linger = 200;
        zmq_setsockopt(m->sock, ZMQ_LINGER, &linger, sizeof linger);
        zmq_socket_monitor(m->sock, NULL, 0);
        zmq_close(m->sock);
    }
    if (m->monitor)
        zmq_close(m->monitor);
    cluster_auth_stop(m->auth);
    conn_guard_destroy(m->guard);
    if (m->ctx)
        zmq_ctx_term(m->ctx);
    free(m);
}

params_store *cluster_master_params(cluster_master *m) { return &m->params; }

typedef struct wait_arg {
    int count;
} wait_arg;

static int enough_live(cluster_master *m, void *arg)
{
    return live_count(m) >= ((wait_arg *)arg)->count;
}

int cluster_master_wait_nodes(cluster_master *m, int count, int timeout_ms)
{
    double deadline = clock_now_ms() + timeout_ms;
    wait_arg a = {count};
    pump(m, deadline, enough_live, &a);
    return live_count(m);
}

void cluster_master_idle(cluster_master *m, double until_ms) { pump(m, until_ms, NULL, NULL); }

static int all_ready(cluster_master *m, void *arg)
{
    for (int i = 0; i < m->cfg->node_count; i++)
        if (m->peers[i].s.state == CLUSTER_PEER_LIVE && m->peers[i].in_barrier && !m->peers[i].ready)
            return 0;
    return 1;
}

/* FRAME v to every live node: those at v-1 (the usual case) share one encoded delta. */
static void send_frames(cluster_master *m, uint64_t v, cluster_frame_result *out)
{
    uint8_t *common = m->common_buf;
    size_t common_len = params_encode_delta(&m->params, v - 1, common, sizeof m->common_buf);
    for (int i = 0; i < m->cfg->node_count; i++) {
        peer *p = &m->peers[i];
        p->in_barrier = p->ready = 0;
        if (p->s.state != CLUSTER_PEER_LIVE)
            continue;
        wire_msg msg = {.type = WIRE_FRAME, .version = v, .base_version = p->s.version};
        if (p->s.version == v - 1) {
            msg.params = common;
            msg.params_len = common_len;
        } else {
            msg.params = m->params_buf;
            msg.params_len = params_encode_delta(&m->params, p->s.version, m->params_buf, sizeof m->params_buf);
        }
        p->frame_sent = clock_now_ms();
        if (send_to(m, i, &msg) == 0) {
            p->in_barrier = p->framed = 1;
            out->live++;
            if (msg.params == common)
                out->frame_bytes = wire_encode(&msg, m->buf, sizeof m->buf);
        }
    }
}

/* After the barrier: nodes not ready are dropped; the ready ones' checksums must agree. */
static void collect_ready(cluster_master *m, uint64_t v, int timeout, cluster_frame_result *out)
{
    uint64_t first = 0;
    int have_first = 0;
    for (int i = 0; i < m->cfg->node_count; i++) {
        peer *p = &m->peers[i];
        if (!p->in_barrier)
            continue;
        if (!p->ready) {
            if (p->s.state == CLUSTER_PEER_LIVE) {
                char note[96];
                if (node_log(m, i, note, sizeof note))
                    fprintf(stderr, "cavelight-master: node %s not ready for frame %llu within %d ms: "
                            "dropped, the others go on%s\n", m->cfg->nodes[i].name, (unsigned long long)v,
                            timeout, note);
                p->s.state = CLUSTER_PEER_DROPPED;
                p->s.drops++;
                m->st.drops++;
                out->dropped++;
                send_bye(m, i, WIRE_BYE_DROPPED);
            }
            continue;
        }
        out->ready++;
        if (!have_first) {
            first = p->s.checksum;
            have_first = 1;
        } else if (p->s.checksum != first) {
            out->desync = 1;
        }
    }
}

static void log_desync(cluster_master *m, uint64_t v)
{
    uint64_t skipped = 0;
    if (!ratelog_event(&m->desync_log, clock_now_ms(), &skipped))
        return;
    fprintf(stderr, "cavelight-master: desync in frame %llu (%llu so far, %llu not logged): GI checksums "
            "differ:", (unsigned long long)v, (unsigned long long)m->st.desyncs, (unsigned long long)skipped);
    for (int i = 0; i < m->cfg->node_count; i++)
        if (m->peers[i].in_barrier && m->peers[i].ready)
            fprintf(stderr, " %s=%016llx", m->cfg->nodes[i].name, (unsigned long long)m->peers[i].s.checksum);
    fprintf(stderr, "\n");
}

int cluster_master_frame(cluster_master *m, cluster_frame_result *out)
{
    memset(out, 0, sizeof *out);
    double t0 = clock_now_ms();
    pump(m, t0, NULL, NULL); /* joins and leaves that arrived since the last frame */
    if (live_count(m) == 0)
        return -1;
    if (m->raise_epoch) {
        params_set_u32(&m->params, PARAMS_RESET_EPOCH, params_get_u32(&m->params, PARAMS_RESET_EPOCH) + 1);
        m->raise_epoch = 0;
    }
    uint64_t v = params_commit(&m->params);
    out->version = v;
    out->epoch = params_get_u32(&m->params, PARAMS_RESET_EPOCH);
    send_frames(m, v, out);
    double tb = clock_now_ms();
    m->last_heartbeat = tb; /* the FRAME was every live node's heartbeat */
    int timeout = stall_timeout_ms(m);
    out->timeout_ms = timeout;
    pump(m, tb + timeout, all_ready, NULL);
    out->barrier_ms = clock_now_ms() - tb;

    collect_ready(m, v, timeout, out);
    if (out->desync)
        m->st.desyncs++;
    if (out->ready > 0)
        m->st.frames_rendered++;
    if (out->desync)
        log_desync(m, v);
    wire_msg swap = {.type = WIRE_SWAP, .version = v};
    for (int i = 0; i < m->cfg->node_count; i++)
        if (m->peers[i].in_barrier && m->peers[i].ready)
            send_to(m, i, &swap);
    m->st.frames++;
    out->round_trip_ms = clock_now_ms() - t0;
    return 0;
}

void cluster_master_stats_get(const cluster_master *m, cluster_master_stats *out)
{
    *out = m->st;
    out->refused = m->auth ? cluster_auth_refused(m->auth) : 0;
}

void cluster_master_peer_stats(const cluster_master *m, int node, cluster_peer_stats *out)
{
    *out = m->peers[node].s;
}

/* Would a node take key k's value alone? params_apply() on a one-key delta of it. */
static int key_acceptable(const params_store *from, int k)
{
    static params_store probe, fresh;
    uint8_t value[PARAMS_VALUE_MAX], enc[2 + PARAMS_VALUE_MAX];
    params_init(&probe, from->schema);
    params_init(&fresh, from->schema);
    uint64_t base = params_commit(&probe);
    size_t size = params_key_size(from, k);
    params_get(from, k, value, size);
    params_set(&probe, k, value, size);
    uint64_t v = params_commit(&probe);
    size_t n = params_encode_delta(&probe, base, enc, sizeof enc);
    return n == PARAMS_ENCODE_TOO_SMALL || params_apply(&fresh, v, enc, n) == 0;
}

int cluster_master_check_params(cluster_master *m, char *err, size_t errlen)
{
    static params_store fresh;
    params_init(&fresh, &m->schema);
    size_t n = params_encode_snapshot(&m->params, m->params_buf, sizeof m->params_buf);
    if (params_apply(&fresh, m->params.version, m->params_buf, n) == 0)
        return 0;
    for (int k = 0; k < m->schema.count; k++) {
        if (key_acceptable(&m->params, k))
            continue;
        float f[PARAMS_VALUE_MAX / 4];
        double d = 0;
        char values[160] = "";
        size_t size = params_key_size(&m->params, k);
        params_get(&m->params, k, f, size);
        memcpy(&d, f, sizeof d);
        int f64 = params_key_type(&m->params, k) == PARAMS_T_F64;
        if (f64)
            snprintf(values, sizeof values, "%g", d);
        for (size_t i = 0; !f64 && i < size / 4 && strlen(values) < sizeof values - 20; i++)
            snprintf(values + strlen(values), sizeof values - strlen(values), "%s%g", i ? " " : "", f[i]);
        snprintf(err, errlen, "parameter %s is %s: every node would refuse every frame (the nodes take "
                 "finite numbers only)", params_key_name(&m->params, k), values);
        return -1;
    }
    snprintf(err, errlen, "the parameters would be refused by every node");
    return -1;
}

int cluster_master_endpoint(const cluster_master *m, char *buf, size_t cap)
{
    size_t len = cap;
    return zmq_getsockopt(m->sock, ZMQ_LAST_ENDPOINT, buf, &len);
}
