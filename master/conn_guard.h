/* conn_guard: the bound on the master's connections that no node has spoken on yet.
 *
 * Every connection the master's socket accepts costs a file descriptor, and one that never
 * finishes its handshake (or finishes it and says nothing) held one for libzmq's 30 s
 * handshake timeout: 1100 of them filled the usual 1024 and kept restarted nodes out. The
 * cluster master tells this table about each accepted connection (the socket monitor's
 * ZMQ_EVENT_ACCEPTED, whose value is the descriptor) and forgets it when a node's message
 * arrives on it or it closes. When the table is full, the oldest connection of the address
 * that holds the most entries is shut down (shutdown(2): libzmq notices, closes it and
 * reports it closed), so a flood from one address cannot push out a node connecting from
 * another; a flood from the node's own address only delays it.
 * A descriptor is checked against the peer address recorded when it was accepted before it
 * is shut down, so a descriptor number that was closed and reused is never touched.
 * No sockets of its own, no threads: the master's thread calls it. */
#ifndef CAVELIGHT_CONN_GUARD_H
#define CAVELIGHT_CONN_GUARD_H

#include <stddef.h>

/* Connections without a node's message the master keeps at most (its default): above the
 * 32 nodes of a config joining at once, far below the usual 1024 descriptors. */
enum { CONN_GUARD_DEFAULT = 64 };

typedef struct conn_guard conn_guard;

/* max <= 0: CONN_GUARD_DEFAULT. */
conn_guard *conn_guard_create(int max);
void conn_guard_destroy(conn_guard *g);
/* A connection accepted at now_ms (or one a node no longer speaks on). When the table is
 * full, first shuts the oldest of the busiest address down: returns 1 then, with that
 * address in dropped; 0 otherwise. A descriptor that is no longer connected is ignored. */
int conn_guard_add(conn_guard *g, int fd, double now_ms, char *dropped, size_t cap);
/* A node's message came on fd, or fd closed: no longer counted. */
void conn_guard_forget(conn_guard *g, int fd);
int conn_guard_count(const conn_guard *g);

#endif
