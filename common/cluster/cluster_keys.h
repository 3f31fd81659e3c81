/* cluster_keys: where a cluster's CurveZMQ key files live, reading them, and checking them.
 *
 * In curve mode (cluster_config.security) the config's key folder holds, for the master
 * and for every node NAME: NAME.pub, its public key, and NAME.key, its secret key, each
 * 40 Z85 characters and a newline (cavelight-master --keygen writes them, and one bundle
 * per host under hosts/HOST/ with exactly what that host needs). The master needs
 * master.key, master.pub and every node's .pub; a node needs its own .pub and .key and
 * master.pub. A secret key file must be readable by its owner only, and must derive the
 * public key beside it (a pair from two keygen runs, or two nodes' files swapped, fail
 * every handshake with nothing said). Every error is one line naming the file and what
 * the one who reads it (the master, or a node) should do.
 * This module reads and checks text; the keys themselves go to libzmq as they are, and
 * the one piece of CURVE maths it needs (secret to public) is the caller's, since common/
 * links no libzmq: pass zmq_curve_public. */
#ifndef CAVELIGHT_CLUSTER_KEYS_H
#define CAVELIGHT_CLUSTER_KEYS_H

#include <stddef.h>

#include "cluster/cluster_config.h"

enum { CLUSTER_KEY_Z85 = 40 };

typedef enum cluster_key_kind { CLUSTER_KEY_PUBLIC = 0, CLUSTER_KEY_SECRET } cluster_key_kind;

/* zmq_curve_public(): the public key of a secret one (Z85 both). Returns 0 or -1. */
typedef int (*cluster_key_derive_fn)(char *z85_public, const char *z85_secret);

/* KEYS/WHO.pub or KEYS/WHO.key. Returns 0, or -1 when the path does not fit. */
int cluster_key_path(const cluster_config *c, const char *who, cluster_key_kind kind, char *out,
                     size_t cap);
/* Reads WHO's key into z85 (NUL-terminated). reader is who needs it: NULL for the master,
 * else the node's name. Returns 0, or -1 with one line naming the file and what to do. */
int cluster_key_read(const cluster_config *c, const char *reader, const char *who, cluster_key_kind kind,
                     char z85[CLUSTER_KEY_Z85 + 1], char *err, size_t errlen);
/* Reads WHO's public and secret key and checks that the secret one derives the public one.
 * Returns 0, or -1 with one line naming both files. */
int cluster_key_read_pair(const cluster_config *c, const char *reader, const char *who,
                          cluster_key_derive_fn derive, char pub[CLUSTER_KEY_Z85 + 1],
                          char secret[CLUSTER_KEY_Z85 + 1], char *err, size_t errlen);
/* KEYS/hosts/HOST: the bundle of one host ('/' in a host name becomes '_'). Returns 0 or -1. */
int cluster_keys_bundle_dir(const cluster_config *c, const char *host, char *out, size_t cap);
/* The key folder as a node whose copy of the config is at config_there sees it (NULL or
 * "": at this config's own path). A key folder inside the config's folder is taken as
 * relative to the config, as security.keys is. Returns 0 or -1. */
int cluster_keys_dir_for(const cluster_config *c, const char *config_there, char *out, size_t cap);

#endif
