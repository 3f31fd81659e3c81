/* cluster_stranger: a hostile peer for the security tests and measurements. It knows the
 * cluster config (names, config hash) and the master's public key, but holds no node key:
 * it connects without CURVE or with a key pair of its own and tries one attack N times,
 * then prints one line: what it tried and how many messages it got back. As an insider
 * (--key insider) it holds another node's real key pair and attacks the victim with it.
 *
 *   takeover   a new connection per attempt under the victim's name, saying HELLO
 *   read       one connection under the victim's name, HELLO, then listen for --listen-ms
 *   ready      forged READY messages for versions 1..N under the victim's name
 *   hello      a HELLO flood under the victim's name
 *   badhello   the same with another config hash (each one a refusal)
 *   churn      connects and disconnects N times, sending nothing (the master's memory)
 *   master     binds --endpoint as a fake master (own CURVE key, or none) and answers any
 *              message with a SNAPSHOT of hostile parameters for --listen-ms (with
 *              --nonfinite, one of them infinite: a node refuses it and says why, REFUSE)
 *   replay     a TCP relay between a real node and the master (the node connects to the
 *              endpoint written to --endpoint-file): it records what the node sends and,
 *              once the node has been joined for a second, sends that recording (CURVE
 *              handshake, HELLO, READYs) to the master again on --count new connections,
 *              counting what comes back on each; it relays for --listen-ms at most
 *   flood      holds --count plain TCP connections (from --source ADDR when given) that send
 *              only the start of a ZMTP greeting and never finish the handshake, opening a
 *              new one whenever the master closes one, for --listen-ms
 * --key stolen: a node's real public key (another node than the victim) with a random
 * secret key, as one who copied a .pub file but not its .key would have.
 * Every loop is bounded by --count and --listen-ms. Only loopback endpoints are meant. */
#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>
#include <zmq.h>

#include "app/session_keys.h"
#include "base/clock.h"
#include "cluster/cluster_config.h"
#include "cluster/cluster_keys.h"
#include "cluster/params.h"
#include "gi/gi_settings.h"
#include "scene/scene_load.h"
#include "cluster/wire.h"

typedef struct stranger {
    cluster_config cfg;
    const char *endpoint, *victim, *endpoint_file, *source;
    int curve, count, listen_ms;
    char master_key[CLUSTER_KEY_Z85 + 1];
    char own_public[CLUSTER_KEY_Z85 + 1], own_secret[CLUSTER_KEY_Z85 + 1]; /* insider: a node's */
    void *ctx;
    long attempts, replies, received;
    long closed;           /* flood: connections the master closed */
    int nonfinite;         /* master: an infinite light intensity */
    long refusals;         /* master: REFUSE messages from nodes */
    char why[WIRE_TEXT_MAX + 1]; /* the last one's text */
    int stolen;            /* own_public is a node's, own_secret a random one */
    const char *attack, *key;
} stranger;

/* The one line a run ends with: what was tried, and what came back. */
static void report(const stranger *s)
{
    printf("stranger %s key=%s attempts=%ld replies=%ld received=%ld closed=%ld refusals=%ld why=\"%s\"\n", s->attack,
           s->key, s->attempts, s->replies, s->received, s->closed, s->refusals, s->why);
    fflush(stdout);
}

static void *open_dealer(stranger *s)
{
    void *sock = zmq_socket(s->ctx, ZMQ_DEALER);
    int zero = 0;
    zmq_setsockopt(sock, ZMQ_LINGER, &zero, sizeof zero);
    zmq_setsockopt(sock, ZMQ_ROUTING_ID, s->victim, strlen(s->victim));
    if (s->curve) { /* a key pair of its own (or an insider's), and the master's real public key */
        char pub[41], secret[41];
        if (s->own_public[0]) {
            memcpy(pub, s->own_public, sizeof pub);
            memcpy(secret, s->own_secret, sizeof secret);
        } else {
            zmq_curve_keypair(pub, secret);
        }
        zmq_setsockopt(sock, ZMQ_CURVE_SERVERKEY, s->master_key, CLUSTER_KEY_Z85);
        zmq_setsockopt(sock, ZMQ_CURVE_PUBLICKEY, pub, CLUSTER_KEY_Z85);
        zmq_setsockopt(sock, ZMQ_CURVE_SECRETKEY, secret, CLUSTER_KEY_Z85);
    }
    zmq_connect(sock, s->endpoint);
    return sock;
}

static void send_wire(void *sock, const wire_msg *m)
{
    uint8_t buf[WIRE_MAX_MESSAGE];
    size_t len = wire_encode(m, buf, sizeof buf);
    zmq_send(sock, buf, len, ZMQ_DONTWAIT);
}

/* The node's schema: the built-in keys and the config's scene's objects (no application),
 * so that its HELLO's hash is a real node's. */
static const params_schema *node_schema(const stranger *s)
{
    static params_schema schema;
    static scene sc;
    static scene_keys objects;
    char err[256];
    if (schema.count)
        return &schema;
    scene_load_desc sd;
    cluster_config_scene_desc(&s->cfg, &sd);
    gi_params_schema(&schema);
    if (scene_load_with(s->cfg.scene[0] ? s->cfg.scene : "default", &sd, &sc, err, sizeof err) != 0 ||
        session_keys_add(&schema, &sc, &objects, NULL, err, sizeof err) != 0) {
        fprintf(stderr, "cluster_stranger: %s\n", err);
        exit(1);
    }
    return &schema;
}

static void hello(stranger *s, void *sock, int bad_hash)
{
    const params_schema *schema = node_schema(s);
    wire_msg m = {.type = WIRE_HELLO,
                  .config_hash = params_session_hash(s->cfg.hash, schema) ^ (bad_hash ? 1u : 0u)};
    snprintf(m.name, sizeof m.name, "%s", s->victim);
    send_wire(sock, &m);
}

/* Counts what arrives on sock within ms. */
static long drain(void *sock, int ms)
{
    long n = 0;
    double end = clock_now_ms() + ms;
    for (double left = ms; left > 0; left = end - clock_now_ms()) {
        zmq_pollitem_t it = {.socket = sock, .events = ZMQ_POLLIN};
        if (zmq_poll(&it, 1, (long)left) <= 0)
            continue;
        char buf[WIRE_MAX_MESSAGE];
        while (zmq_recv(sock, buf, sizeof buf, ZMQ_DONTWAIT) >= 0)
            n++;
    }
    return n;
}

static void fake_master(stranger *s)
{
    void *sock = zmq_socket(s->ctx, ZMQ_ROUTER);
    int zero = 0, one = 1;
    zmq_setsockopt(sock, ZMQ_LINGER, &zero, sizeof zero);
    if (s->curve) {
        char pub[41], secret[41];
        zmq_curve_keypair(pub, secret);
        zmq_setsockopt(sock, ZMQ_CURVE_SERVER, &one, sizeof one);
        zmq_setsockopt(sock, ZMQ_CURVE_SECRETKEY, secret, CLUSTER_KEY_Z85);
    }
    if (zmq_bind(sock, s->endpoint) != 0) {
        fprintf(stderr, "cluster_stranger: cannot bind %s\n", s->endpoint);
        exit(1);
    }
    if (s->endpoint_file) {
        char ep[256];
        size_t len = sizeof ep;
        zmq_getsockopt(sock, ZMQ_LAST_ENDPOINT, ep, &len);
        FILE *f = fopen(s->endpoint_file, "w");
        fprintf(f, "%s\n", ep);
        fclose(f);
    }
    /* Parameters no node should take: a huge lattice and step count, a blinding light. */
    static params_schema schema;
    static params_store p;
    gi_params_schema(&schema);
    params_init(&p, &schema);
    params_set_i32(&p, params_schema_find(&schema, "lattice"), 100000);
    params_set_f32(&p, params_light_key(0, PARAMS_LIGHT_INTENSITY), s->nonfinite ? INFINITY : 1e30f);
    params_set_i32(&p, params_schema_find(&schema, "steps"), 1 << 30);
    uint64_t v = params_commit(&p) + 1000000;
    static uint8_t enc[PARAMS_ENCODED_MAX];
    size_t n = params_encode_snapshot(&p, enc, sizeof enc);
    double end = clock_now_ms() + s->listen_ms;
    while (clock_now_ms() < end) {
        zmq_pollitem_t it = {.socket = sock, .events = ZMQ_POLLIN};
        if (zmq_poll(&it, 1, 50) <= 0)
            continue;
        char id[256], body[WIRE_MAX_MESSAGE];
        int idlen = zmq_recv(sock, id, sizeof id, ZMQ_DONTWAIT);
        if (idlen < 0)
            continue;
        int blen = zmq_recv(sock, body, sizeof body, ZMQ_DONTWAIT);
        s->received++;
        wire_msg in;
        if (blen > 0 && wire_decode((const uint8_t *)body, (size_t)blen, &in) == WIRE_OK && in.type == WIRE_REFUSE) {
            s->refusals++;
            snprintf(s->why, sizeof s->why, "%s", in.text);
            continue;
        }
        wire_msg m = {.type = WIRE_SNAPSHOT, .version = v, .params = enc, .params_len = n};
        uint8_t buf[WIRE_MAX_MESSAGE];
        size_t len = wire_encode(&m, buf, sizeof buf);
        zmq_send(sock, id, (size_t)(idlen < (int)sizeof id ? idlen : (int)sizeof id), ZMQ_SNDMORE | ZMQ_DONTWAIT);
        zmq_send(sock, buf, len, ZMQ_DONTWAIT);
        /* and a frame on top of it, so that a node that took the snapshot renders it */
        wire_msg f = {.type = WIRE_FRAME, .version = v + 1, .base_version = v, .params = enc, .params_len = 0};
        len = wire_encode(&f, buf, sizeof buf);
        zmq_send(sock, id, (size_t)(idlen < (int)sizeof id ? idlen : (int)sizeof id), ZMQ_SNDMORE | ZMQ_DONTWAIT);
        zmq_send(sock, buf, len, ZMQ_DONTWAIT);
        s->attempts++;
    }
    zmq_close(sock);
}

/* A TCP connection to the endpoint's host and port that sends the 10-byte start of a ZMTP
 * greeting (signature) and nothing more; -1 when it cannot be opened. */
static int open_unfinished(const stranger *s, const struct sockaddr_in *to)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0)
        return -1;
    if (s->source) {
        struct sockaddr_in from = {.sin_family = AF_INET};
        inet_pton(AF_INET, s->source, &from.sin_addr);
        if (bind(fd, (struct sockaddr *)&from, sizeof from) != 0) {
            close(fd);
            return -1;
        }
    }
    /* Never blocks long: a master whose backlog is full leaves the connect pending. */
    static const unsigned char greeting[10] = {0xff, 0, 0, 0, 0, 0, 0, 0, 1, 0x7f};
    fcntl(fd, F_SETFL, O_NONBLOCK);
    struct pollfd out = {.fd = fd, .events = POLLOUT};
    int err = 0;
    socklen_t len = sizeof err;
    if ((connect(fd, (const struct sockaddr *)to, sizeof *to) != 0 && errno != EINPROGRESS) ||
        poll(&out, 1, 200) != 1 || getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len) != 0 || err ||
        write(fd, greeting, sizeof greeting) != 10) {
        close(fd);
        return -1;
    }
    return fd;
}

/* The master's address from a tcp://IPV4:PORT endpoint (plain sockets need one). */
static struct sockaddr_in master_address(const stranger *s)
{
    struct sockaddr_in to = {.sin_family = AF_INET};
    const char *host = strstr(s->endpoint, "://"), *colon = strrchr(s->endpoint, ':');
    char addr[64] = "";
    if (host && colon && colon - (host + 3) < (long)sizeof addr)
        memcpy(addr, host + 3, (size_t)(colon - (host + 3)));
    if (inet_pton(AF_INET, addr, &to.sin_addr) != 1) {
        fprintf(stderr, "cluster_stranger: this attack needs a tcp://IPV4:PORT endpoint, not %s\n", s->endpoint);
        exit(2);
    }
    to.sin_port = htons((uint16_t)atoi(colon + 1));
    return to;
}

/* --count unfinished handshakes held for --listen-ms; each one the master closes is
 * opened again at once. */
static void flood(stranger *s)
{
    struct sockaddr_in to = master_address(s);
    struct pollfd *fds = calloc((size_t)s->count, sizeof *fds);
    for (int i = 0; i < s->count; i++, s->attempts++)
        fds[i] = (struct pollfd){.fd = open_unfinished(s, &to), .events = POLLIN};
    double end = clock_now_ms() + s->listen_ms;
    while (clock_now_ms() < end) {
        if (poll(fds, (nfds_t)s->count, 20) < 0 && errno != EINTR)
            break;
        for (int i = 0; i < s->count; i++) {
            char buf[256];
            if (fds[i].fd >= 0 && !(fds[i].revents & (POLLIN | POLLHUP | POLLERR)))
                continue;
            if (fds[i].fd >= 0 && read(fds[i].fd, buf, sizeof buf) > 0)
                continue; /* the master's greeting: never answered */
            if (fds[i].fd >= 0) {
                close(fds[i].fd);
                s->closed++;
            }
            fds[i].fd = open_unfinished(s, &to);
            s->attempts++;
        }
    }
    for (int i = 0; i < s->count; i++)
        if (fds[i].fd >= 0)
            close(fds[i].fd);
    free(fds);
}

/* The relay of the replay attack: node <-> master, what the node sends recorded. */
typedef struct relay {
    int node, master;
    volatile int stop, ended;
    double started;          /* when the node connected (ms clock) */
    unsigned char rec[65536];
    volatile size_t rec_len;
} relay;

static int pass(int from, int to, relay *r, int record)
{
    unsigned char buf[4096];
    ssize_t n = read(from, buf, sizeof buf);
    if (n <= 0 || write(to, buf, (size_t)n) != n)
        return -1;
    if (record && r->rec_len + (size_t)n <= sizeof r->rec) {
        memcpy(r->rec + r->rec_len, buf, (size_t)n);
        r->rec_len += (size_t)n;
    }
    return 0;
}

static void *relay_main(void *arg)
{
    relay *r = arg;
    struct pollfd p[2] = {{.fd = r->node, .events = POLLIN}, {.fd = r->master, .events = POLLIN}};
    while (!r->stop) {
        if (poll(p, 2, 50) <= 0)
            continue;
        if ((p[0].revents && pass(r->node, r->master, r, 1) != 0) ||
            (p[1].revents && pass(r->master, r->node, r, 0) != 0))
            break;
    }
    r->ended = 1;
    return NULL;
}

/* One replay of the recording on a fresh connection, kept until the master closes it
 * (500 ms at most). What it sends back before that is its greeting and a fresh cookie:
 * whether the replay got in shows in the master's joins and failed handshakes. */
static void replay_once(const struct sockaddr_in *to, const relay *r)
{
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd >= 0 && connect(fd, (const struct sockaddr *)to, sizeof *to) == 0 &&
        write(fd, r->rec, r->rec_len) == (ssize_t)r->rec_len) {
        double end = clock_now_ms() + 500;
        for (double left = 500; left > 0; left = end - clock_now_ms()) {
            struct pollfd p = {.fd = fd, .events = POLLIN};
            char buf[4096];
            if (poll(&p, 1, (int)left) <= 0 || read(fd, buf, sizeof buf) <= 0)
                break;
        }
    }
    if (fd >= 0)
        close(fd);
}

static void replay(stranger *s)
{
    struct sockaddr_in to = master_address(s), here = {.sin_family = AF_INET};
    socklen_t len = sizeof here;
    here.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    static relay r;
    int lfd = socket(AF_INET, SOCK_STREAM, 0);
    if (lfd < 0 || bind(lfd, (struct sockaddr *)&here, sizeof here) != 0 || listen(lfd, 1) != 0 ||
        getsockname(lfd, (struct sockaddr *)&here, &len) != 0) {
        fprintf(stderr, "cluster_stranger: cannot listen\n");
        exit(1);
    }
    FILE *f = fopen(s->endpoint_file, "w");
    fprintf(f, "tcp://127.0.0.1:%d\n", ntohs(here.sin_port));
    fclose(f);
    struct pollfd p = {.fd = lfd, .events = POLLIN};
    if (poll(&p, 1, s->listen_ms) != 1 || (r.node = accept(lfd, NULL, NULL)) < 0 ||
        (r.master = socket(AF_INET, SOCK_STREAM, 0)) < 0 ||
        connect(r.master, (struct sockaddr *)&to, sizeof to) != 0) {
        fprintf(stderr, "cluster_stranger: no node to relay\n");
        exit(1);
    }
    r.started = clock_now_ms();
    double end = r.started + s->listen_ms;
    pthread_t t;
    pthread_create(&t, NULL, relay_main, &r);
    while (clock_now_ms() < r.started + 1000 && !r.ended)
        poll(NULL, 0, 10);
    for (int i = 0; i < s->count && !r.ended; i++, s->attempts++)
        replay_once(&to, &r);
    s->received = (long)r.rec_len;
    report(s); /* the replays are done; the relay goes on until the session ends */
    while (clock_now_ms() < end && !r.ended)
        poll(NULL, 0, 10);
    r.stop = 1;
    pthread_join(t, NULL);
    close(r.node);
    close(r.master);
    close(lfd);
}

int main(int argc, char **argv)
{
    static stranger s = {.count = 100, .listen_ms = 1000};
    const char *config = NULL, *attack = NULL, *key = "none";
    for (int i = 1; i + 1 < argc; i += 2) {
        const char *a = argv[i], *v = argv[i + 1];
        if (strcmp(a, "--config") == 0) config = v;
        else if (strcmp(a, "--endpoint") == 0) s.endpoint = v;
        else if (strcmp(a, "--attack") == 0) attack = v;
        else if (strcmp(a, "--victim") == 0) s.victim = v;
        else if (strcmp(a, "--key") == 0) key = v;
        else if (strcmp(a, "--count") == 0) s.count = atoi(v);
        else if (strcmp(a, "--listen-ms") == 0) s.listen_ms = atoi(v);
        else if (strcmp(a, "--endpoint-file") == 0) s.endpoint_file = v;
        else if (strcmp(a, "--source") == 0) s.source = v;
        else if (strcmp(a, "--nonfinite") == 0) s.nonfinite = atoi(v);
    }
    char err[512];
    if (!config || !s.endpoint || !attack || cluster_config_load(config, &s.cfg, err, sizeof err) != 0) {
        fprintf(stderr, "usage: cluster_stranger --config C --endpoint EP --attack takeover|read|ready|hello|badhello|"
                "churn|master|flood|replay [--victim NAME] [--key none|wrong|insider|stolen] [--count N] "
                "[--listen-ms MS] [--endpoint-file F] [--source ADDR] [--nonfinite 1]\n");
        return 2;
    }
    if (!s.victim)
        s.victim = s.cfg.nodes[0].name;
    s.attack = attack;
    s.key = key;
    s.curve = strcmp(key, "wrong") == 0 || strcmp(key, "insider") == 0 || strcmp(key, "stolen") == 0;
    s.stolen = strcmp(key, "stolen") == 0;
    if (s.curve && strcmp(attack, "master") != 0 &&
        cluster_key_read(&s.cfg, NULL, "master", CLUSTER_KEY_PUBLIC, s.master_key, err, sizeof err) != 0) {
        fprintf(stderr, "cluster_stranger: %s\n", err);
        return 1;
    }
    if (s.stolen) { /* the first other node's public key, a secret key of its own */
        const char *own = NULL;
        for (int i = 0; i < s.cfg.node_count && !own; i++)
            if (strcmp(s.cfg.nodes[i].name, s.victim) != 0)
                own = s.cfg.nodes[i].name;
        char unused[CLUSTER_KEY_Z85 + 1];
        if (!own || cluster_key_read(&s.cfg, NULL, own, CLUSTER_KEY_PUBLIC, s.own_public, err, sizeof err) != 0) {
            fprintf(stderr, "cluster_stranger: a stolen key needs another node's .pub: %s\n", own ? err : "none");
            return 1;
        }
        zmq_curve_keypair(unused, s.own_secret);
    }
    if (strcmp(key, "insider") == 0) { /* the first other node's key pair */
        const char *own = NULL;
        for (int i = 0; i < s.cfg.node_count && !own; i++)
            if (strcmp(s.cfg.nodes[i].name, s.victim) != 0)
                own = s.cfg.nodes[i].name;
        if (!own || cluster_key_read(&s.cfg, NULL, own, CLUSTER_KEY_PUBLIC, s.own_public, err, sizeof err) != 0 ||
            cluster_key_read(&s.cfg, NULL, own, CLUSTER_KEY_SECRET, s.own_secret, err, sizeof err) != 0) {
            fprintf(stderr, "cluster_stranger: an insider needs another node's keys: %s\n", own ? err : "none");
            return 1;
        }
    }
    s.ctx = zmq_ctx_new();
    if (strcmp(attack, "master") == 0) {
        fake_master(&s);
    } else if (strcmp(attack, "flood") == 0) {
        flood(&s);
    } else if (strcmp(attack, "replay") == 0) {
        replay(&s);
        zmq_ctx_term(s.ctx);
        return 0;
    } else if (strcmp(attack, "takeover") == 0 || strcmp(attack, "churn") == 0) {
        int say_hello = strcmp(attack, "takeover") == 0;
        for (int i = 0; i < s.count; i++, s.attempts++) {
            void *sock = open_dealer(&s);
            if (say_hello)
                hello(&s, sock, 0);
            s.replies += drain(sock, 5); /* the connection and its handshake run meanwhile */
            zmq_close(sock);
        }
    } else {
        void *sock = open_dealer(&s);
        drain(sock, 100); /* let the handshake run */
        for (int i = 0; i < s.count; i++, s.attempts++) {
            if (strcmp(attack, "ready") == 0) {
                wire_msg m = {.type = WIRE_READY, .version = (uint64_t)i + 1, .checksum = 0xbad0bad0ull + i};
                snprintf(m.name, sizeof m.name, "%s", s.victim);
                send_wire(sock, &m);
            } else {
                hello(&s, sock, strcmp(attack, "badhello") == 0); /* read, hello, badhello */
            }
            if (i % 100 == 99)
                s.replies += drain(sock, 1);
        }
        s.replies += drain(sock, strcmp(attack, "read") == 0 ? s.listen_ms : 200);
        zmq_close(sock);
    }
    zmq_ctx_term(s.ctx);
    report(&s);
    return 0;
}
