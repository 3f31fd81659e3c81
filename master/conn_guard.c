#include "conn_guard.h"
#include "base/xalloc.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>

typedef struct entry {
    int fd;
    double since;
    struct sockaddr_storage peer;
    socklen_t peer_len;
} entry;

struct conn_guard {
    int max, count;
    entry *e;
};

conn_guard *conn_guard_create(int max)
{
    conn_guard *g = xcalloc(1, sizeof *g);
    g->max = max > 0 ? max : CONN_GUARD_DEFAULT;
    g->e = xcalloc((size_t)g->max, sizeof *g->e);
    return g;
}

void conn_guard_destroy(conn_guard *g)
{
    if (!g)
        return;
    free(g->e);
    free(g);
}

int conn_guard_count(const conn_guard *g) { return g->count; }

static void remove_at(conn_guard *g, int i) { g->e[i] = g->e[--g->count]; }

/* The host part of an address (the port left out); 0 when a and b are the same host. */
static int host_cmp(const struct sockaddr_storage *a, const struct sockaddr_storage *b)
{
    if (a->ss_family != b->ss_family)
        return 1;
    if (a->ss_family == AF_INET)
        return memcmp(&((const struct sockaddr_in *)a)->sin_addr, &((const struct sockaddr_in *)b)->sin_addr,
                      sizeof(struct in_addr));
    if (a->ss_family == AF_INET6)
        return memcmp(&((const struct sockaddr_in6 *)a)->sin6_addr, &((const struct sockaddr_in6 *)b)->sin6_addr,
                      sizeof(struct in6_addr));
    return 0; /* ipc: one host */
}

static void host_text(const struct sockaddr_storage *a, char *out, size_t cap)
{
    const void *addr = a->ss_family == AF_INET ? (const void *)&((const struct sockaddr_in *)a)->sin_addr
                                               : (const void *)&((const struct sockaddr_in6 *)a)->sin6_addr;
    if ((a->ss_family != AF_INET && a->ss_family != AF_INET6) || !inet_ntop(a->ss_family, addr, out, (socklen_t)cap))
        snprintf(out, cap, "this machine");
}

/* The oldest entry of the host with the most entries (of equal ones, the oldest entry). */
static int victim(const conn_guard *g)
{
    int oldest = 0, n = 0;
    for (int i = 1; i < g->count; i++)
        if (g->e[i].since < g->e[oldest].since)
            oldest = i;
    for (int k = 0; k < g->count; k++)
        n += host_cmp(&g->e[oldest].peer, &g->e[k].peer) == 0;
    if (2 * n > g->count) /* a flood from one address: one pass */
        return oldest;
    int best = oldest, best_n = n;
    for (int i = 0; i < g->count; i++) {
        int own = 0, first = i;
        for (int k = 0; k < g->count; k++)
            if (host_cmp(&g->e[i].peer, &g->e[k].peer) == 0) {
                own++;
                if (g->e[k].since < g->e[first].since)
                    first = k;
            }
        if (own > best_n || (own == best_n && g->e[first].since < g->e[best].since)) {
            best_n = own;
            best = first;
        }
    }
    return best;
}

/* Shuts entry i's connection down if its descriptor still has the peer it was accepted
 * with (else it closed meanwhile, and the number may be another connection's now). */
static void shut(conn_guard *g, int i)
{
    struct sockaddr_storage now;
    socklen_t len = sizeof now;
    const entry *e = &g->e[i];
    if (getpeername(e->fd, (struct sockaddr *)&now, &len) == 0 && len == e->peer_len &&
        memcmp(&now, &e->peer, len) == 0)
        shutdown(e->fd, SHUT_RDWR);
}

int conn_guard_add(conn_guard *g, int fd, double now_ms, char *dropped, size_t cap)
{
    entry fresh = {.fd = fd, .since = now_ms, .peer_len = sizeof fresh.peer};
    if (fd < 0 || getpeername(fd, (struct sockaddr *)&fresh.peer, &fresh.peer_len) != 0)
        return 0;
    conn_guard_forget(g, fd); /* a number seen before belongs to this connection now */
    int shed = 0;
    if (g->count == g->max) {
        int i = victim(g);
        host_text(&g->e[i].peer, dropped, cap);
        shut(g, i);
        remove_at(g, i);
        shed = 1;
    }
    g->e[g->count++] = fresh;
    return shed;
}

void conn_guard_forget(conn_guard *g, int fd)
{
    for (int i = 0; i < g->count; i++)
        if (g->e[i].fd == fd) {
            remove_at(g, i);
            return;
        }
}
