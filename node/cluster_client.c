#include "cluster_client.h"
#include "gi/gi_settings.h"
#include "base/xalloc.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zmq.h>

#include "base/clock.h"
#include "base/ratelog.h"
#include "cluster/cluster_keys.h"

typedef enum client_state { STATE_HELLO, STATE_JOINED, STATE_LOST } client_state;
/* HELLO repeats and socket reopens while not joined. A fallback only (every new handshake
 * says HELLO at once), and slow on purpose: each HELLO a master reads after the session
 * started is a rejoin that resets every node's LPV history. */
enum { RETRY_MS = 2000 };
/* A master that closes every CURVE handshake for this long (and this many times) is most
 * likely not the one whose key master.pub holds: a master shedding connections under a
 * flood (conn_guard) closes a node's handshakes too, but lets one through within seconds
 * (3.6 s at most in the outside check's flood of 100k-200k connections). */
enum { KEY_EVIDENCE_MS = 6000, KEY_EVIDENCE_CLOSES = 10 };
/* The socket's connection to the master, from its monitor's events. */
typedef enum link_state { LINK_OPENING, LINK_UP, LINK_DOWN } link_state;

struct cluster_client {
    const cluster_config *cfg;
    char name[WIRE_NAME_MAX + 1];
    void *ctx, *sock, *monitor;
    int monitors;            /* sockets opened so far: names each one's monitor */
    link_state link;         /* DOWN: closed, and no handshake has succeeded since */
    const char *endpoint;
    double opened;
    int quiet, refuse_only;
    client_state state;
    int ended;               /* the master ended the session (BYE) and no new one joined */
    double lost_at;          /* when the master was lost or ended the session (ms clock) */
    params_schema schema;    /* the store's keys (gi_params_schema()) */
    params_store params;
    /* curve: this node's key pair and the one master key it accepts */
    char public_key[CLUSTER_KEY_Z85 + 1], secret_key[CLUSTER_KEY_Z85 + 1], master_key[CLUSTER_KEY_Z85 + 1];
    ratelog malformed_log, refused_log;
    ratelog link_log;        /* joins, losses, drops, the session's end: cluster_client_log_link() */
    ratelog handshake_log;   /* failed handshakes with the master */
    /* CURVE handshakes the master closed since the last one that succeeded: how many, since
     * when; key_taken: one succeeded with master.pub; key_named: the key was named */
    int closes, key_taken, key_named;
    double closes_since;
    double last_heard, last_sent, last_hello;
    cluster_client_stats st;
    uint8_t buf[WIRE_MAX_MESSAGE];
};

static int send_msg(cluster_client *c, wire_msg *msg)
{
    snprintf(msg->name, sizeof msg->name, "%s", c->name);
    size_t len = wire_encode(msg, c->buf, sizeof c->buf);
    if (len == 0)
        return -1;
    /* ZMQ_IMMEDIATE: with no connection this fails at once instead of queueing stale HELLOs. */
    if (zmq_send(c->sock, c->buf, len, ZMQ_DONTWAIT) < 0)
        return -1;
    c->st.bytes_sent += len;
    c->last_sent = clock_now_ms();
    return 0;
}

static void send_hello(cluster_client *c)
{
    if (c->refuse_only)
        return;
    wire_msg m = {.type = WIRE_HELLO, .config_hash = params_session_hash(c->cfg->hash, &c->schema),
                  .version = c->params.version};
    /* Not yet connected (ZMQ_IMMEDIATE): the next housekeeping round tries again. */
    if (send_msg(c, &m) == 0)
        c->last_hello = clock_now_ms();
}

static void close_socket(cluster_client *c)
{
    if (c->sock) {
        zmq_socket_monitor(c->sock, NULL, 0);
        zmq_close(c->sock);
        c->sock = NULL;
    }
    if (c->monitor) {
        zmq_close(c->monitor);
        c->monitor = NULL;
    }
}

/* Connection events: a closed connection (master killed, heartbeats unanswered) means the
 * master is lost now, not after master_ms; a new handshake means one answers: say HELLO. */
static int watch_socket(cluster_client *c)
{
    char ep[96];
    snprintf(ep, sizeof ep, "inproc://cavelight-node-monitor-%p-%d", (void *)c, c->monitors++);
    int zero = 0;
    int events = ZMQ_EVENT_DISCONNECTED | ZMQ_EVENT_HANDSHAKE_SUCCEEDED | ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL |
                 ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL | ZMQ_EVENT_HANDSHAKE_FAILED_AUTH;
    if (zmq_socket_monitor(c->sock, ep, events) != 0)
        return -1;
    c->monitor = zmq_socket(c->ctx, ZMQ_PAIR);
    if (!c->monitor)
        return -1;
    zmq_setsockopt(c->monitor, ZMQ_LINGER, &zero, sizeof zero);
    return zmq_connect(c->monitor, ep);
}

static int open_socket(cluster_client *c, char *err, size_t errlen)
{
    c->sock = zmq_socket(c->ctx, ZMQ_DEALER);
    if (!c->sock) {
        snprintf(err, errlen, "cluster node: cannot create a ZeroMQ socket: %s", zmq_strerror(errno));
        return -1;
    }
    int one = 1, zero = 0, hwm = 1000, ivl = 100, ivl_max = 250, handshake = WIRE_HANDSHAKE_MS;
    int64_t maxmsg = WIRE_MAX_MESSAGE;
    /* Insecure: the routing id names the node. Curve: the key does, and ROUTER's own
     * unique ids mean nobody can squat on this node's name. */
    if (c->cfg->security == CLUSTER_SECURITY_INSECURE)
        zmq_setsockopt(c->sock, ZMQ_ROUTING_ID, c->name, strlen(c->name));
    zmq_setsockopt(c->sock, ZMQ_LINGER, &zero, sizeof zero);
    zmq_setsockopt(c->sock, ZMQ_SNDHWM, &hwm, sizeof hwm);
    zmq_setsockopt(c->sock, ZMQ_RCVHWM, &hwm, sizeof hwm);
    zmq_setsockopt(c->sock, ZMQ_MAXMSGSIZE, &maxmsg, sizeof maxmsg);
    zmq_setsockopt(c->sock, ZMQ_IMMEDIATE, &one, sizeof one);
    zmq_setsockopt(c->sock, ZMQ_RECONNECT_IVL, &ivl, sizeof ivl);
    zmq_setsockopt(c->sock, ZMQ_RECONNECT_IVL_MAX, &ivl_max, sizeof ivl_max);
    zmq_setsockopt(c->sock, ZMQ_HANDSHAKE_IVL, &handshake, sizeof handshake);
    /* curve: the handshake fails against any master without the configured key. */
    if (c->cfg->security == CLUSTER_SECURITY_CURVE &&
        (zmq_setsockopt(c->sock, ZMQ_CURVE_SERVERKEY, c->master_key, CLUSTER_KEY_Z85) != 0 ||
         zmq_setsockopt(c->sock, ZMQ_CURVE_PUBLICKEY, c->public_key, CLUSTER_KEY_Z85) != 0 ||
         zmq_setsockopt(c->sock, ZMQ_CURVE_SECRETKEY, c->secret_key, CLUSTER_KEY_Z85) != 0)) {
        snprintf(err, errlen, "cluster node %s: cannot set up CURVE security: %s", c->name, zmq_strerror(errno));
        zmq_close(c->sock);
        c->sock = NULL;
        return -1;
    }
    if (watch_socket(c) != 0) {
        snprintf(err, errlen, "cluster node %s: cannot watch the connection: %s", c->name, zmq_strerror(errno));
        close_socket(c);
        return -1;
    }
    if (zmq_connect(c->sock, c->endpoint) != 0) {
        snprintf(err, errlen, "cluster node %s: cannot connect to %s (%s): check master.connect in %s",
                 c->name, c->endpoint, zmq_strerror(errno), c->cfg->path);
        close_socket(c);
        return -1;
    }
    c->opened = clock_now_ms();
    c->link = LINK_OPENING;
    return 0;
}

/* A fresh socket, and so a fresh connection; HELLO goes out once its handshake succeeds. */
static void reopen(cluster_client *c)
{
    char err[256], note[96];
    close_socket(c);
    if (open_socket(c, err, sizeof err) != 0) {
        if (cluster_client_log_link(c, note, sizeof note))
            fprintf(stderr, "%s%s\n", err, note);
        return;
    }
    c->st.reopens++;
    send_hello(c);
}

/* ZeroMQ does not reconnect after a protocol error (e.g. an oversized message): a node
 * with no connection that has heard nothing for RETRY_MS since its socket opened starts
 * a fresh one. A connection that is up is kept for twice as long: its master has our HELLO,
 * and a fresh socket would lose a late answer and make the master count a second join;
 * but a connection whose HELLOs go unanswered that long leads nowhere (in insecure mode a
 * stranger may have taken over our name on the master's side). */
static void reopen_if_dead(cluster_client *c, double now)
{
    double since = now - (c->last_heard > c->opened ? c->last_heard : c->opened);
    if (since >= (c->link == LINK_UP ? 2 * RETRY_MS : RETRY_MS))
        reopen(c);
}

cluster_client *cluster_client_create(const cluster_client_desc *desc, char *err, size_t errlen)
{
    if (cluster_config_find_node(desc->config, desc->name) < 0) {
        snprintf(err, errlen, "cluster node: no node named '%s' in %s: pass one of its node names",
                 desc->name, desc->config->path);
        return NULL;
    }
    cluster_client *c = xcalloc(1, sizeof *c);
    c->cfg = desc->config;
    c->quiet = desc->quiet;
    c->refuse_only = desc->refuse_only;
    snprintf(c->name, sizeof c->name, "%s", desc->name);
    if (desc->schema)
        c->schema = *desc->schema;
    else
        gi_params_schema(&c->schema);
    params_init(&c->params, &c->schema);
    c->ctx = zmq_ctx_new();
    c->endpoint = desc->endpoint ? desc->endpoint : c->cfg->master_connect;
    if (c->cfg->security == CLUSTER_SECURITY_CURVE) {
        if (!zmq_has("curve")) {
            snprintf(err, errlen, "cluster node %s: this libzmq has no CURVE security", c->name);
            cluster_client_destroy(c);
            return NULL;
        }
        if (cluster_key_read_pair(c->cfg, c->name, c->name, zmq_curve_public, c->public_key, c->secret_key, err,
                                  errlen) != 0 ||
            cluster_key_read(c->cfg, c->name, "master", CLUSTER_KEY_PUBLIC, c->master_key, err, errlen) != 0) {
            cluster_client_destroy(c);
            return NULL;
        }
    } else if (!c->quiet) {
        fprintf(stderr, "cavelight-node %s: security \"insecure\" in %s: the master is not "
                "authenticated (local runs and tests only)\n", c->name, c->cfg->path);
    }
    if (!c->ctx || open_socket(c, err, errlen) != 0) {
        cluster_client_destroy(c);
        return NULL;
    }
    c->state = STATE_HELLO;
    c->last_heard = clock_now_ms();
    send_hello(c);
    return c;
}

void cluster_client_destroy(cluster_client *c)
{
    if (!c)
        return;
    if (c->sock) {
        wire_msg bye = {.type = WIRE_BYE, .reason = WIRE_BYE_LEAVING};
        send_msg(c, &bye);
        int linger = 200; /* let the BYE leave, but never wait long for a dead master */
        zmq_setsockopt(c->sock, ZMQ_LINGER, &linger, sizeof linger);
    }
    close_socket(c);
    if (c->ctx)
        zmq_ctx_term(c->ctx);
    free(c);
}

const params_store *cluster_client_params(const cluster_client *c) { return &c->params; }

void cluster_client_stats_get(const cluster_client *c, cluster_client_stats *out) { *out = c->st; }

int cluster_client_ready(cluster_client *c, uint64_t version, uint64_t checksum,
                         const float timings[WIRE_TIMING_COUNT])
{
    wire_msg m = {.type = WIRE_READY, .version = version, .checksum = checksum};
    memcpy(m.timings, timings, sizeof m.timings);
    return send_msg(c, &m);
}

/* Heartbeats while joined. */
static void heartbeat(cluster_client *c, double now)
{
    if (c->state == STATE_JOINED && now - c->last_sent >= c->cfg->heartbeat_ms) {
        wire_msg hb = {.type = WIRE_HEARTBEAT, .version = c->params.version};
        send_msg(c, &hb);
    }
}

/* A HELLO goes out on every new connection (connection_event()) and again when one
 * could not be sent (no connection yet). One that went out is repeated only after
 * RETRY_MS without an answer: a master under load (or stopped) answers late.
 * Called with the receive queue empty, so an answer that already arrived counts. */
static void hello_again(cluster_client *c, double now)
{
    if (c->state != STATE_JOINED && now - c->last_hello >= RETRY_MS)
        send_hello(c);
}

/* Parameters that fail params_apply() (non-finite values, bad layout) change nothing. */
static void refuse_params(cluster_client *c, const char *what, uint64_t version)
{
    c->st.malformed++;
    uint64_t skipped = 0;
    char why[WIRE_TEXT_MAX + 1];
    snprintf(why, sizeof why, "%s %llu: invalid values (a number that is not finite, or a malformed encoding)",
             what, (unsigned long long)version);
    cluster_client_refuse(c, WIRE_REFUSE_PARAMS, version, why, 0);
    if (ratelog_event(&c->refused_log, clock_now_ms(), &skipped))
        fprintf(stderr, "cavelight-node %s: %s from the master refused, and the master told (%llu so far, "
                "%llu not logged)\n", c->name, why, (unsigned long long)c->refused_log.count,
                (unsigned long long)skipped);
}

/* At most one HELLO per 100 ms however many reasons arrive together. */
static void ask_snapshot(cluster_client *c)
{
    c->state = c->state == STATE_LOST ? STATE_LOST : STATE_HELLO;
    if (clock_now_ms() - c->last_hello >= 100)
        send_hello(c);
}

/* 1 when the master has closed every CURVE handshake long and often enough to blame the
 * key (KEY_EVIDENCE_MS): a close alone looks the same from here for both causes. */
static int key_evidence(const cluster_client *c)
{
    return c->closes >= KEY_EVIDENCE_CLOSES && clock_now_ms() - c->closes_since >= KEY_EVIDENCE_MS;
}

/* A handshake the master closed (not refused, not timed out) counts towards the evidence. */
static int closed_by_master(const cluster_client *c, uint16_t event, uint32_t value)
{
    return c->cfg->security == CLUSTER_SECURITY_CURVE && event != ZMQ_EVENT_HANDSHAKE_FAILED_AUTH &&
           !(event == ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL && value == ZMQ_PROTOCOL_ERROR_ZMTP_MECHANISM_MISMATCH) &&
           !(event == ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL && value == EAGAIN);
}

/* The likely cause of a failed handshake with the master, from the socket's event and
 * its value (a ZAP status, a ZMQ_PROTOCOL_ERROR_* or an errno). */
static void handshake_cause(const cluster_client *c, uint16_t event, uint32_t value, char *out, size_t cap)
{
    int curve = c->cfg->security == CLUSTER_SECURITY_CURVE;
    if (event == ZMQ_EVENT_HANDSHAKE_FAILED_AUTH)
        snprintf(out, cap, "the master refused this node's key (status %u): %s/%s.pub is not the key the "
                 "master has for node %s; copy this host's bundle again from the master's key folder", value,
                 c->cfg->keys_dir, c->name, c->name);
    else if (event == ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL && value == ZMQ_PROTOCOL_ERROR_ZMTP_MECHANISM_MISMATCH)
        snprintf(out, cap, "the master uses another security mode than this node's \"%s\" (%s): give master "
                 "and nodes the same config", cluster_security_name(c->cfg->security), c->cfg->path);
    else if (event == ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL && value == EAGAIN)
        snprintf(out, cap, "no answer within %d ms: a stopped or overloaded master, or no cavelight master at "
                 "%s", WIRE_HANDSHAKE_MS, c->endpoint);
    else if (curve && c->key_taken)
        snprintf(out, cap, "the master closed the connection in the CURVE handshake, though it took %s/master.pub "
                 "before: a master shedding connections under a flood (its log says so), or one restarted with "
                 "new keys", c->cfg->keys_dir);
    else if (curve && key_evidence(c))
        snprintf(out, cap, "the master closed the connection in the CURVE handshake: most likely %s/master.pub "
                 "is not this master's key (a newer --keygen on its host?): copy master.pub from the master's "
                 "key folder; or the master uses another security mode (%s) (every handshake for %.0f s, %d of "
                 "them, closed)", c->cfg->keys_dir, c->cfg->path, (clock_now_ms() - c->closes_since) / 1000,
                 c->closes);
    else if (curve)
        snprintf(out, cap, "the master closed the connection in the CURVE handshake (%d in a row): a master "
                 "shedding connections under a flood, or %s/master.pub is not this master's key, or the master "
                 "uses another security mode (%s) (the key is named as the likely cause if it goes on for %d s)",
                 c->closes, c->cfg->keys_dir, c->cfg->path, KEY_EVIDENCE_MS / 1000);
    else
        snprintf(out, cap, "the master closed the connection in the handshake (%#x): a master with security "
                 "\"curve\" (this node has \"insecure\" from %s), or no cavelight master at %s", value, c->cfg->path,
                 c->endpoint);
}

static void handshake_failed(cluster_client *c, uint16_t event, uint32_t value)
{
    uint64_t skipped = 0;
    c->st.handshakes_failed++;
    if (closed_by_master(c, event, value) && c->closes++ == 0)
        c->closes_since = clock_now_ms();
    /* the first time the evidence names the key is said, whatever the rate limit */
    int verdict = !c->key_taken && !c->key_named && closed_by_master(c, event, value) && key_evidence(c);
    c->key_named |= verdict;
    if (!ratelog_event(&c->handshake_log, clock_now_ms(), &skipped) && !verdict)
        return;
    char cause[1024];
    handshake_cause(c, event, value, cause, sizeof cause);
    fprintf(stderr, "cavelight-node %s: handshake with the master at %s failed (%llu so far, %llu not logged): %s\n",
            c->name, c->endpoint, (unsigned long long)c->st.handshakes_failed, (unsigned long long)skipped, cause);
}

/* Reads one connection event; returns 1 if there was one. */
static int connection_event(cluster_client *c)
{
    zmq_msg_t ev, ep;
    zmq_msg_init(&ev);
    zmq_msg_init(&ep);
    int got = 0;
    if (c->monitor && zmq_msg_recv(&ev, c->monitor, ZMQ_DONTWAIT) >= 0) {
        got = 1;
        if (zmq_msg_more(&ev))
            zmq_msg_recv(&ep, c->monitor, 0);
        uint16_t event = 0;
        uint32_t value = 0;
        if (zmq_msg_size(&ev) >= 6) {
            memcpy(&event, zmq_msg_data(&ev), 2);
            memcpy(&value, (const uint8_t *)zmq_msg_data(&ev) + 2, 4);
        }
        if (event & (ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL | ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL |
                     ZMQ_EVENT_HANDSHAKE_FAILED_AUTH)) {
            handshake_failed(c, event, value);
        } else if (event == ZMQ_EVENT_DISCONNECTED) {
            c->link = LINK_DOWN;
        } else if (event == ZMQ_EVENT_HANDSHAKE_SUCCEEDED) {
            c->link = LINK_UP;
            c->closes = 0;
            c->key_taken = 1;
            if (c->state != STATE_JOINED && clock_now_ms() - c->last_hello >= 100)
                send_hello(c); /* unless one just went out on this connection */
        }
    }
    zmq_msg_close(&ev);
    zmq_msg_close(&ep);
    return got;
}

int cluster_client_refuse(cluster_client *c, wire_refuse_what what, uint64_t version, const char *why,
                          int wait_ms)
{
    for (double until = clock_now_ms() + wait_ms; c->link != LINK_UP && clock_now_ms() < until;) {
        zmq_pollitem_t it = {.socket = c->monitor, .events = ZMQ_POLLIN};
        zmq_poll(&it, c->monitor ? 1 : 0, 50);
        while (connection_event(c))
            ;
    }
    wire_msg m = {.type = WIRE_REFUSE, .reason = what, .version = version};
    size_t n = 0;
    for (; why[n] && n < WIRE_TEXT_MAX; n++) /* one printable line */
        m.text[n] = why[n] >= 0x20 && why[n] < 0x7f ? why[n] : '?';
    m.text[n] = 0;
    return send_msg(c, &m);
}

/* Counts and logs (rate limited) a message that failed to decode, and drains the rest of
 * a multipart one; closes msg. */
static void drop_malformed(cluster_client *c, zmq_msg_t *msg, wire_error e)
{
    c->st.malformed++;
    uint64_t skipped = 0;
    if (ratelog_event(&c->malformed_log, clock_now_ms(), &skipped))
        fprintf(stderr, "cavelight-node %s: malformed message from the master dropped (%s; %llu so far, "
                "%llu not logged)\n", c->name, wire_error_string(e), (unsigned long long)c->st.malformed,
                (unsigned long long)skipped);
    while (zmq_msg_more(msg)) {
        zmq_msg_close(msg);
        zmq_msg_init(msg);
        if (zmq_msg_recv(msg, c->sock, 0) < 0)
            break;
    }
    zmq_msg_close(msg);
}

int cluster_client_log_link(cluster_client *c, char *note, size_t cap)
{
    uint64_t skipped = 0;
    note[0] = 0;
    if (c->quiet || !ratelog_event(&c->link_log, clock_now_ms(), &skipped))
        return 0;
    if (skipped)
        snprintf(note, cap, " (%llu lines about the master not logged)", (unsigned long long)skipped);
    return 1;
}

/* The join line names what happened: a first join, the next session after the master ended
 * one, a reconnect after a loss (to the same session, or to a new master whose versions
 * restarted), or a resync (dropped, or a gap in the deltas). */
static void say_joined(cluster_client *c, const wire_msg *m)
{
    char note[96];
    if (!cluster_client_log_link(c, note, sizeof note))
        return;
    unsigned long long v = (unsigned long long)m->version;
    double gap = clock_now_ms() - c->lost_at;
    if (c->st.snapshots == 0)
        fprintf(stderr, "cavelight-node %s: joined the master at version %llu%s\n", c->name, v, note);
    else if (c->ended)
        fprintf(stderr, "cavelight-node %s: joined the master's new session at version %llu, %.0f ms after "
                "the last one ended%s\n", c->name, v, gap, note);
    else if (c->state == STATE_LOST && m->version < c->params.version)
        fprintf(stderr, "cavelight-node %s: reconnected to a new master at version %llu, %.0f ms after "
                "losing the old one%s\n", c->name, v, gap, note);
    else if (c->state == STATE_LOST)
        fprintf(stderr, "cavelight-node %s: reconnected to the master at version %llu, %.0f ms after "
                "losing it%s\n", c->name, v, gap, note);
    else
        fprintf(stderr, "cavelight-node %s: resynchronized with the master at version %llu (snapshot)%s\n",
                c->name, v, note);
}

/* A SNAPSHOT replaces the store: 1 when it applied (the node has joined), 0 when refused. */
static int join(cluster_client *c, const wire_msg *m)
{
    params_store fresh;
    params_init(&fresh, &c->schema);
    if (params_apply(&fresh, m->version, m->params, m->params_len) != 0) {
        refuse_params(c, "snapshot", m->version);
        return 0;
    }
    say_joined(c, m);
    c->params = fresh;
    c->state = STATE_JOINED;
    c->ended = 0;
    c->st.snapshots++;
    return 1;
}

/* Joined, and the master is gone: its connection closed, or it went silent. A silent
 * master's connection is replaced at once: a stopped master takes the new one when it
 * continues, and a connection that the master's side no longer reads (in insecure mode a
 * stranger's message under our name takes our routing id over) leads nowhere. */
static cluster_event_type lose_master(cluster_client *c, cluster_lost_reason why, cluster_event *ev)
{
    c->state = STATE_LOST;
    c->lost_at = clock_now_ms();
    c->st.lost++;
    if (why == CLUSTER_LOST_SILENT)
        reopen(c);
    ev->type = CLUSTER_EVENT_LOST;
    ev->lost = why;
    return ev->type;
}

/* BYE from the master: dropped (rejoin; NONE), refused (another config) or the end of the
 * session (acknowledged). */
static cluster_event_type on_bye(cluster_client *c, const wire_msg *m)
{
    char note[96];
    if (m->reason == WIRE_BYE_DROPPED) {
        if (cluster_client_log_link(c, note, sizeof note))
            fprintf(stderr, "cavelight-node %s: dropped by the master (too slow for the barrier); rejoining%s\n",
                    c->name, note);
        c->state = STATE_HELLO;
        ask_snapshot(c);
        return CLUSTER_EVENT_NONE;
    }
    if (m->reason == WIRE_BYE_CONFIG_MISMATCH) {
        fprintf(stderr, "cavelight-node %s: the master refused %s (another config hash: the config, the "
                "scene, the application or the build differ): give master and nodes the same file, scene "
                "and --app\n", c->name, c->cfg->path);
        return CLUSTER_EVENT_REFUSED;
    }
    /* Acknowledge, so that the master knows its last messages arrived. A master that is
     * shutting down answers our HELLO with BYE again: the same end, said once. */
    wire_msg ack = {.type = WIRE_BYE, .reason = WIRE_BYE_LEAVING};
    send_msg(c, &ack);
    if (c->ended)
        return CLUSTER_EVENT_NONE;
    c->state = STATE_LOST;
    c->ended = 1;
    c->lost_at = clock_now_ms();
    return CLUSTER_EVENT_SHUTDOWN;
}

/* Reads one message from the master into msg and decodes it into m (whose params point into
 * msg). Returns 1 (valid: the caller closes msg), 0 (none waiting) or -1 (malformed: counted,
 * logged and dropped). */
static int recv_decoded(cluster_client *c, zmq_msg_t *msg, wire_msg *m)
{
    zmq_msg_init(msg);
    if (zmq_msg_recv(msg, c->sock, ZMQ_DONTWAIT) < 0) {
        zmq_msg_close(msg);
        return 0;
    }
    size_t len = zmq_msg_size(msg);
    c->st.bytes_received += len;
    wire_error e = zmq_msg_more(msg) ? WIRE_E_PAYLOAD : wire_decode(zmq_msg_data(msg), len, m);
    if (e == WIRE_OK && (m->type == WIRE_HELLO || m->type == WIRE_READY))
        e = WIRE_E_TYPE; /* node-to-master messages */
    if (e != WIRE_OK) {
        drop_malformed(c, msg, e);
        return -1;
    }
    return 1;
}

/* FRAME(v, delta): applied on top when its base is our version, else a snapshot is asked
 * for. *pending: a FRAME applied and not yet overtaken. */
static void on_frame(cluster_client *c, const wire_msg *m, int *pending, cluster_event *ev)
{
    if (c->state != STATE_JOINED) {
        *pending = 0; /* a snapshot is on its way */
        return;
    }
    if (m->base_version != c->params.version) {
        /* A gap in the chain of deltas: only a snapshot can repair it. */
        c->st.resyncs++;
        ask_snapshot(c);
        *pending = 0;
        return;
    }
    double t0 = clock_now_ms();
    if (params_apply(&c->params, m->version, m->params, m->params_len) != 0) {
        refuse_params(c, "frame", m->version);
        ask_snapshot(c);
        *pending = 0;
        return;
    }
    ev->apply_ms += clock_now_ms() - t0;
    if (*pending)
        c->st.skipped++;
    c->st.frames++;
    *pending = 1;
    ev->version = m->version;
}

/* One valid message from the master. Returns the event to hand to the caller, or NONE to
 * read on. */
static cluster_event_type on_message(cluster_client *c, const wire_msg *m, int *pending, cluster_event *ev)
{
    c->last_heard = clock_now_ms();
    /* The master is back: resync, unless a HELLO already went out since the loss (it
     * waits in the master's queue; a second one would be a second rejoin). */
    if (c->state == STATE_LOST && m->type != WIRE_SNAPSHOT && m->type != WIRE_BYE && c->last_hello < c->lost_at)
        ask_snapshot(c);
    switch (m->type) {
    case WIRE_SNAPSHOT:
        if (!join(c, m))
            return CLUSTER_EVENT_NONE;
        ev->version = m->version;
        return ev->type = CLUSTER_EVENT_JOINED;
    case WIRE_FRAME:
        on_frame(c, m, pending, ev);
        return CLUSTER_EVENT_NONE;
    case WIRE_SWAP:
        if (*pending)
            return CLUSTER_EVENT_NONE;
        c->st.swaps++;
        ev->version = m->version;
        return ev->type = CLUSTER_EVENT_SWAP;
    case WIRE_BYE:
        *pending = 0;
        return ev->type = on_bye(c, m);
    default: /* HEARTBEAT */
        return CLUSTER_EVENT_NONE;
    }
}

/* Nothing queued. A joined node whose master went silent has lost it (silence counts only
 * once the queue is empty: a node that was stalled reads what the master sent before it
 * decides); one not joined says HELLO again or opens a fresh socket. Then waits for the
 * next message until the deadline. Returns LOST, or NONE with *expired set at the deadline. */
static cluster_event_type wait_idle(cluster_client *c, double now, double deadline, cluster_event *ev,
                                    int *expired)
{
    if (c->state == STATE_JOINED && now - c->last_heard > c->cfg->master_timeout_ms)
        return lose_master(c, CLUSTER_LOST_SILENT, ev);
    if (c->state != STATE_JOINED) {
        hello_again(c, now);
        reopen_if_dead(c, now);
    }
    if (now >= deadline) {
        *expired = 1;
        return CLUSTER_EVENT_NONE;
    }
    double wait = deadline - now;
    if (wait > c->cfg->heartbeat_ms)
        wait = c->cfg->heartbeat_ms;
    zmq_pollitem_t items[2] = {{.socket = c->sock, .events = ZMQ_POLLIN},
                               {.socket = c->monitor, .events = ZMQ_POLLIN}};
    zmq_poll(items, c->monitor ? 2 : 1, (long)(wait + 0.999));
    return CLUSTER_EVENT_NONE;
}

cluster_event_type cluster_client_poll(cluster_client *c, int timeout_ms, cluster_event *ev)
{
    memset(ev, 0, sizeof *ev);
    double deadline = clock_now_ms() + timeout_ms;
    int pending = 0; /* a FRAME applied and not yet overtaken */
    for (;;) {
        double now = clock_now_ms();
        heartbeat(c, now);
        for (int k = 0; k < 8 && connection_event(c); k++) /* a few at a time: never starves messages */
            ;
        if (c->link == LINK_DOWN && c->state == STATE_JOINED && !pending)
            return lose_master(c, CLUSTER_LOST_CLOSED, ev);
        zmq_msg_t msg;
        wire_msg m;
        int got = recv_decoded(c, &msg, &m);
        if (got == 0 && pending)
            return ev->type = CLUSTER_EVENT_FRAME;
        if (got == 0) {
            int expired = 0;
            if (wait_idle(c, now, deadline, ev, &expired) != CLUSTER_EVENT_NONE || expired)
                return ev->type;
            continue;
        }
        if (got > 0) {
            cluster_event_type t = on_message(c, &m, &pending, ev);
            zmq_msg_close(&msg);
            if (t != CLUSTER_EVENT_NONE)
                return t;
        }
        if (!pending && clock_now_ms() >= deadline)
            return CLUSTER_EVENT_NONE; /* a flood cannot hold the caller past its timeout */
    }
}
