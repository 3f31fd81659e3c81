#define _XOPEN_SOURCE 700 /* realpath */
#include "cluster_auth.h"
#include "base/xalloc.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/clock.h"
#include "base/ratelog.h"
#include "cluster/cluster_keys.h"

#define ZAP_ENDPOINT "inproc://zeromq.zap.01"
#define ZAP_DOMAIN "cavelight"

struct cluster_auth {
    const cluster_config *cfg;
    void *ctx, *zap;
    int quiet, running;
    pthread_t thread;
    uint8_t node_key[CLUSTER_MAX_NODES][32];
    atomic_uint_fast64_t refused;
    ratelog refused_log;
};

static int recv_frame(void *sock, char *buf, size_t cap, size_t *len, int *more)
{
    int n = zmq_recv(sock, buf, cap, 0);
    if (n < 0)
        return -1;
    *len = (size_t)n < cap ? (size_t)n : cap;
    int m = 0;
    size_t ms = sizeof m;
    zmq_getsockopt(sock, ZMQ_RCVMORE, &m, &ms);
    *more = m;
    return 0;
}

/* One ZAP request: version, request id, domain, address, routing id, mechanism, then the
 * credentials (CURVE: the client's 32-byte public key). */
static void answer(cluster_auth *a, void *zap)
{
    enum { FRAMES = 7 };
    char f[FRAMES][256];
    size_t len[FRAMES] = {0};
    int more = 1, n = 0;
    while (more) {
        char scratch[256];
        size_t l;
        char *dst = n < FRAMES ? f[n] : scratch;
        if (recv_frame(zap, dst, sizeof f[0], &l, &more) != 0)
            return;
        if (n < FRAMES)
            len[n] = l;
        n++;
    }
    int node = -1;
    if (n == FRAMES && len[5] == 5 && memcmp(f[5], "CURVE", 5) == 0 && len[6] == 32)
        for (int i = 0; i < a->cfg->node_count && node < 0; i++)
            if (memcmp(a->node_key[i], f[6], 32) == 0)
                node = i;
    const char *status = node >= 0 ? "200" : "400";
    const char *text = node >= 0 ? "OK" : "unknown key";
    const char *user = node >= 0 ? a->cfg->nodes[node].name : "";
    zmq_send(zap, "1.0", 3, ZMQ_SNDMORE);
    zmq_send(zap, f[1], n > 1 ? len[1] : 0, ZMQ_SNDMORE);
    zmq_send(zap, status, 3, ZMQ_SNDMORE);
    zmq_send(zap, text, strlen(text), ZMQ_SNDMORE);
    zmq_send(zap, user, strlen(user), ZMQ_SNDMORE);
    zmq_send(zap, "", 0, 0);
    if (node >= 0)
        return;
    atomic_fetch_add(&a->refused, 1);
    uint64_t skipped = 0;
    if (ratelog_event(&a->refused_log, clock_now_ms(), &skipped)) {
        char addr[64];
        snprintf(addr, sizeof addr, "%.*s", n > 3 ? (int)(len[3] < 63 ? len[3] : 63) : 0, f[3]);
        fprintf(stderr, "cavelight-master: connection from %s refused: its key is none of the nodes' "
                "in %s (%llu refused so far, %llu not logged)\n", addr[0] ? addr : "?", a->cfg->path,
                (unsigned long long)a->refused_log.count, (unsigned long long)skipped);
    }
}

/* Owns a->zap from its start (bound before, so no handshake can come first). */
static void *zap_thread(void *arg)
{
    cluster_auth *a = arg;
    void *zap = a->zap;
    for (;;) {
        zmq_pollitem_t item = {.socket = zap, .events = ZMQ_POLLIN};
        if (zmq_poll(&item, 1, -1) < 0) {
            if (errno == EINTR)
                continue;
            break; /* ETERM: the context is shutting down */
        }
        answer(a, zap);
    }
    zmq_close(zap);
    return NULL;
}

/* The master's key pair (its secret key into secret), every node's public key (into a's
 * table when a is not NULL), and every node's pair whose secret key is here too (a keygen
 * folder, or a cluster on one machine): a pair that does not match is named at start
 * instead of failing each handshake. */
static int check_keys(const cluster_config *cfg, cluster_auth *a, char secret[CLUSTER_KEY_Z85 + 1], char *err,
                      size_t errlen)
{
    char pub[CLUSTER_KEY_Z85 + 1], other[CLUSTER_KEY_Z85 + 1], path[CLUSTER_TEXT_MAX + 64];
    if (cluster_key_read_pair(cfg, NULL, "master", zmq_curve_public, pub, secret, err, errlen) != 0)
        return -1;
    for (int i = 0; i < cfg->node_count; i++) {
        const char *name = cfg->nodes[i].name;
        int has_secret = cluster_key_path(cfg, name, CLUSTER_KEY_SECRET, path, sizeof path) == 0 &&
                         access(path, F_OK) == 0;
        if ((has_secret ? cluster_key_read_pair(cfg, NULL, name, zmq_curve_public, pub, other, err, errlen)
                        : cluster_key_read(cfg, NULL, name, CLUSTER_KEY_PUBLIC, pub, err, errlen)) != 0)
            return -1;
        uint8_t key[32];
        if (!zmq_z85_decode(key, pub)) {
            snprintf(err, errlen, "cluster keys %s/%s.pub: not a key", cfg->keys_dir, name);
            return -1;
        }
        if (a)
            memcpy(a->node_key[i], key, sizeof key);
    }
    return 0;
}

int cluster_auth_check_keys(const cluster_config *cfg, char *err, size_t errlen)
{
    char secret[CLUSTER_KEY_Z85 + 1];
    return check_keys(cfg, NULL, secret, err, errlen);
}

cluster_auth *cluster_auth_start(void *ctx, void *sock, const cluster_config *cfg, int quiet,
                                 char *err, size_t errlen)
{
    cluster_auth *a = xcalloc(1, sizeof *a);
    a->cfg = cfg;
    a->ctx = ctx;
    a->quiet = quiet;
    if (cfg->security == CLUSTER_SECURITY_INSECURE)
        return a; /* cluster_master says so, naming the endpoint it bound */
    if (!zmq_has("curve")) {
        snprintf(err, errlen, "cluster master: this libzmq has no CURVE security; install one that "
                 "has (Debian's libzmq5 does)");
        free(a);
        return NULL;
    }
    char secret[CLUSTER_KEY_Z85 + 1];
    if (check_keys(cfg, a, secret, err, errlen) != 0) {
        free(a);
        return NULL;
    }
    int one = 1, zero = 0;
    a->zap = zmq_socket(ctx, ZMQ_REP);
    if (!a->zap || zmq_setsockopt(a->zap, ZMQ_LINGER, &zero, sizeof zero) != 0 ||
        zmq_bind(a->zap, ZAP_ENDPOINT) != 0 || pthread_create(&a->thread, NULL, zap_thread, a) != 0) {
        snprintf(err, errlen, "cluster master: cannot start the authentication handler: %s",
                 zmq_strerror(errno));
        if (a->zap)
            zmq_close(a->zap);
        free(a);
        return NULL;
    }
    a->running = 1;
    /* libzmq admits any CURVE key when no handler is bound (ZMQ_ZAP_ENFORCE_DOMAIN is a
     * draft option Debian's build lacks): the handler is bound before sock and lives until
     * after it is closed. */
    if (zmq_setsockopt(sock, ZMQ_CURVE_SERVER, &one, sizeof one) != 0 ||
        zmq_setsockopt(sock, ZMQ_CURVE_SECRETKEY, secret, CLUSTER_KEY_Z85) != 0 ||
        zmq_setsockopt(sock, ZMQ_ZAP_DOMAIN, ZAP_DOMAIN, strlen(ZAP_DOMAIN)) != 0) {
        snprintf(err, errlen, "cluster master: cannot set up CURVE security: %s", zmq_strerror(errno));
        zmq_ctx_shutdown(ctx);
        cluster_auth_stop(a);
        return NULL;
    }
    return a;
}

int cluster_auth_node(const cluster_auth *a, zmq_msg_t *msg, const char *routing_name)
{
    if (a->cfg->security == CLUSTER_SECURITY_INSECURE)
        return routing_name ? cluster_config_find_node(a->cfg, routing_name) : -1;
    const char *user = zmq_msg_gets(msg, "User-Id"); /* set by answer() from the key */
    return user ? cluster_config_find_node(a->cfg, user) : -1;
}

uint64_t cluster_auth_refused(const cluster_auth *a) { return atomic_load(&a->refused); }

void cluster_auth_stop(cluster_auth *a)
{
    if (!a)
        return;
    if (a->running) {
        zmq_ctx_shutdown(a->ctx); /* wakes the handler with ETERM */
        pthread_join(a->thread, NULL);
    }
    free(a);
}

static int write_key(const char *path, const char *z85, int secret, char *err, size_t errlen)
{
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, secret ? 0600 : 0644);
    if (fd < 0) {
        snprintf(err, errlen, "cluster keygen %s: %s%s", path, strerror(errno),
                 errno == EEXIST ? " (remove the old keys first to make new ones)" : "");
        return -1;
    }
    char line[CLUSTER_KEY_Z85 + 2];
    snprintf(line, sizeof line, "%s\n", z85);
    int ok = write(fd, line, strlen(line)) == (ssize_t)strlen(line);
    ok &= close(fd) == 0;
    if (!ok)
        snprintf(err, errlen, "cluster keygen %s: write failed: %s", path, strerror(errno));
    return ok ? 0 : -1;
}

static int make_dir(const char *path, char *err, size_t errlen)
{
    if (mkdir(path, 0700) == 0 || errno == EEXIST)
        return 0;
    snprintf(err, errlen, "cluster keygen %s: %s", path, strerror(errno));
    return -1;
}

/* Fresh key pairs: [0] the master's, [1 + i] node i's. */
typedef struct key_set {
    char pub[CLUSTER_MAX_NODES + 1][CLUSTER_KEY_Z85 + 1], secret[CLUSTER_MAX_NODES + 1][CLUSTER_KEY_Z85 + 1];
} key_set;

/* WHO's pair into folder dir. */
static int write_pair(const char *dir, const char *who, const key_set *k, int i, int with_secret, char *err,
                      size_t errlen)
{
    char key[CLUSTER_TEXT_MAX + 240], pub[CLUSTER_TEXT_MAX + 240];
    if (snprintf(key, sizeof key, "%s/%s.key", dir, who) >= (int)sizeof key ||
        snprintf(pub, sizeof pub, "%s/%s.pub", dir, who) >= (int)sizeof pub) {
        snprintf(err, errlen, "cluster keygen %s: path too long", dir);
        return -1;
    }
    if (with_secret && write_key(key, k->secret[i], 1, err, errlen) != 0)
        return -1;
    return write_key(pub, k->pub[i], 0, err, errlen);
}

/* Where a host's bundle goes: the key folder as the config there names it, the config's
 * path there being the node's "config" (in its "workdir" when relative), or this one's. */
static void bundle_target(const cluster_config *cfg, const cluster_node *n, char *out, size_t cap)
{
    char there[2 * CLUSTER_TEXT_MAX + 2] = "", abs_keys[PATH_MAX];
    if (n->config[0] && n->config[0] != '/' && n->workdir[0])
        snprintf(there, sizeof there, "%s/%s", n->workdir, n->config);
    else if (n->config[0])
        snprintf(there, sizeof there, "%s", n->config);
    if (there[0] && cluster_keys_dir_for(cfg, there, out, cap) == 0)
        return;
    snprintf(out, cap, "%s", realpath(cfg->keys_dir, abs_keys) ? abs_keys : cfg->keys_dir);
}

/* One bundle per host, with its nodes' pairs and master.pub, and one line saying where it
 * goes. The first node of each host writes it. */
static int write_bundles(const cluster_config *cfg, const key_set *k, FILE *say, char *err, size_t errlen)
{
    char hosts[CLUSTER_TEXT_MAX + 16];
    snprintf(hosts, sizeof hosts, "%s/hosts", cfg->keys_dir);
    if (make_dir(hosts, err, errlen) != 0)
        return -1;
    for (int i = 0; i < cfg->node_count; i++) {
        const char *host = cfg->nodes[i].host;
        int first = 1;
        for (int j = 0; j < i && first; j++)
            first = strcmp(cfg->nodes[j].host, host) != 0;
        if (!first)
            continue;
        char dir[CLUSTER_TEXT_MAX + 160], files[1024] = "", names[512] = "", target[PATH_MAX];
        int count = 0;
        if (cluster_keys_bundle_dir(cfg, host, dir, sizeof dir) != 0 || make_dir(dir, err, errlen) != 0 ||
            write_pair(dir, "master", k, 0, 0, err, errlen) != 0)
            return -1;
        for (int j = i; j < cfg->node_count; j++) {
            const char *name = cfg->nodes[j].name;
            if (strcmp(cfg->nodes[j].host, host) != 0)
                continue;
            if (write_pair(dir, name, k, 1 + j, 1, err, errlen) != 0)
                return -1;
            size_t f = strlen(files), nn = strlen(names);
            snprintf(files + f, sizeof files - f, "%s.key, %s.pub, ", name, name);
            snprintf(names + nn, sizeof names - nn, "%s%s", nn ? ", " : "", name);
            count++;
        }
        bundle_target(cfg, &cfg->nodes[i], target, sizeof target);
        fprintf(say, "  %s (node%s %s): %s/{%smaster.pub} -> %s:%s/\n", host, count > 1 ? "s" : "", names, dir,
                files, host, target);
    }
    return 0;
}

int cluster_keygen(const cluster_config *cfg, FILE *say, char *err, size_t errlen)
{
    if (!zmq_has("curve")) {
        snprintf(err, errlen, "cluster keygen: this libzmq has no CURVE security");
        return -1;
    }
    static key_set k;
    for (int i = 0; i <= cfg->node_count; i++)
        if (zmq_curve_keypair(k.pub[i], k.secret[i]) != 0) {
            snprintf(err, errlen, "cluster keygen %s: cannot make a key pair", cfg->keys_dir);
            return -1;
        }
    if (make_dir(cfg->keys_dir, err, errlen) != 0)
        return -1;
    for (int i = -1; i < cfg->node_count; i++)
        if (write_pair(cfg->keys_dir, i < 0 ? "master" : cfg->nodes[i].name, &k, i + 1, 1, err, errlen) != 0)
            return -1;
    fprintf(say, "cavelight-master: wrote the key pairs of the master and %d nodes into %s; the master reads "
            "master.key, master.pub and every node's .pub there. Copy each host's bundle into the key folder "
            "its config names (security.keys), .key files readable by their owner only, and no other host's "
            ".key files:\n", cfg->node_count, cfg->keys_dir);
    return write_bundles(cfg, &k, say, err, errlen);
}
