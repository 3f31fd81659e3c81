/* cluster_auth: the master's CurveZMQ security (cluster_config.security == curve).
 *
 * cluster_auth_start() reads master.key and every node's public key (cluster_keys.h),
 * makes the ROUTER a CURVE server and answers ZeroMQ's authentication requests (ZAP,
 * RFC 27) on a thread of its own: a peer is admitted only with a configured node's public
 * key, and every message it sends then carries that node's name as its "User-Id". The
 * master takes the User-Id, never the routing id, as the sender (cluster_auth_node()), so
 * a name cannot be borrowed, not even by a peer holding another node's key. Refused keys
 * are counted and logged, rate-limited. In insecure mode nothing is set up and every
 * routing id is believed.
 * At start every key file the master holds is checked (cluster_keys.h): its own pair, each
 * node's public key, and each node's pair whose secret key is in the folder too.
 * cluster_keygen() writes a fresh key pair for the master and each node, and each host's
 * bundle. */
#ifndef CAVELIGHT_CLUSTER_AUTH_H
#define CAVELIGHT_CLUSTER_AUTH_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <zmq.h>

#include "cluster/cluster_config.h"

typedef struct cluster_auth cluster_auth;

/* Call before binding sock. Returns NULL with one line in err. */
cluster_auth *cluster_auth_start(void *ctx, void *sock, const cluster_config *cfg, int quiet,
                                 char *err, size_t errlen);
/* The node that sent msg, or -1: in curve mode the node whose key its connection
 * authenticated with (the routing id does not matter); insecure, the node named by the
 * routing id (routing_name; NULL when it is not a valid name). */
int cluster_auth_node(const cluster_auth *a, zmq_msg_t *msg, const char *routing_name);
/* Connections refused for an unknown key so far. */
uint64_t cluster_auth_refused(const cluster_auth *a);
/* Call after closing every socket of ctx, before zmq_ctx_term(ctx). NULL is fine. */
void cluster_auth_stop(cluster_auth *a);

/* The key files cluster_auth_start() reads, checked as it checks them, without a socket
 * (cavelight-master --check). Returns 0, or -1 with one line in err. */
int cluster_auth_check_keys(const cluster_config *cfg, char *err, size_t errlen);

/* Writes master.{key,pub} and NODE.{key,pub} for every node into cfg->keys_dir (created if
 * missing) and one bundle per host, KEYS/hosts/HOST/, with the pairs of the host's nodes and
 * master.pub; says on say which bundle goes where (the key folder as that host's copy of
 * the config names it). Refuses to overwrite a secret key. Returns 0, or -1 with one line
 * in err. */
int cluster_keygen(const cluster_config *cfg, FILE *say, char *err, size_t errlen);

#endif
