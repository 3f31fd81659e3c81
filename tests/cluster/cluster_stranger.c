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
 *   flood      holds --count plain TCP connections (from --source ADDR when given) that send
 *              only the start of a ZMTP greeting and never finish the handshake, opening a
 *              new one whenever the master closes one, for --listen-ms
 * Every loop is bounded by --count and --listen-ms. Only loopback endpoints are meant. */
#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <netinet/in.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>
#include <zmq.h>

#include "base/clock.h"
#include "cluster/cluster_config.h"
#include "cluster/cluster_keys.h"
#include "cluster/params.h"
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
} stranger;

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

static void hello(stranger *s, void *sock, int bad_hash)
{
    wire_msg m = {.type = WIRE_HELLO, .config_hash = s->cfg.hash ^ (bad_hash ? 1u : 0u)};
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
    params_store p;
    params_init(&p);
    params_set_i32(&p, PARAMS_LPV_RESOLUTION, 100000);
    params_set_f32(&p, params_light_key(0, PARAMS_LIGHT_INTENSITY), s->nonfinite ? INFINITY : 1e30f);
    params_set_i32(&p, PARAMS_LPV_STEPS, 1 << 30);
    uint64_t v = params_commit(&p) + 1000000;
    uint8_t enc[PARAMS_ENCODED_MAX];
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

/* --count unfinished handshakes held for --listen-ms; each one the master closes is
 * opened again at once. */
static void flood(stranger *s)
{
    struct sockaddr_in to = {.sin_family = AF_INET};
    const char *host = strstr(s->endpoint, "://"), *colon = strrchr(s->endpoint, ':');
    char addr[64] = "";
    if (host && colon && colon - (host + 3) < (long)sizeof addr)
        memcpy(addr, host + 3, (size_t)(colon - (host + 3)));
    if (inet_pton(AF_INET, addr, &to.sin_addr) != 1) {
        fprintf(stderr, "cluster_stranger: flood needs a tcp://IPV4:PORT endpoint, not %s\n", s->endpoint);
        exit(2);
    }
    to.sin_port = htons((uint16_t)atoi(colon + 1));
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
        fprintf(stderr, "usage: cluster_stranger --config C --endpoint EP --attack takeover|read|ready|hello|badhello|churn|master|flood "
                "[--victim NAME] [--key none|wrong|insider] [--count N] [--listen-ms MS] [--source ADDR] [--nonfinite 1]\n");
        return 2;
    }
    if (!s.victim)
        s.victim = s.cfg.nodes[0].name;
    s.curve = strcmp(key, "wrong") == 0 || strcmp(key, "insider") == 0;
    if (s.curve && strcmp(attack, "master") != 0 &&
        cluster_key_read(&s.cfg, NULL, "master", CLUSTER_KEY_PUBLIC, s.master_key, err, sizeof err) != 0) {
        fprintf(stderr, "cluster_stranger: %s\n", err);
        return 1;
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
    printf("stranger %s key=%s attempts=%ld replies=%ld received=%ld closed=%ld refusals=%ld why=\"%s\"\n", attack,
           key, s.attempts, s.replies, s.received, s.closed, s.refusals, s.why);
    return 0;
}
