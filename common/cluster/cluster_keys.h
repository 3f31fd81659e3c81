/* cluster_keys: where a cluster's CurveZMQ key files live, and reading them.
 *
 * In curve mode (cluster_config.security) the config's key folder holds, for the master
 * and for every node NAME: NAME.pub, its public key, and NAME.key, its secret key, each
 * 40 Z85 characters and a newline (cavelight-master --keygen writes them). The master
 * needs master.key and every node's .pub; a node needs its own .pub and .key and
 * master.pub. A secret key file must be readable by its owner only.
 * This module reads and checks text; the keys themselves go to libzmq as they are. */
#ifndef CAVELIGHT_CLUSTER_KEYS_H
#define CAVELIGHT_CLUSTER_KEYS_H

#include <stddef.h>

#include "cluster/cluster_config.h"

enum { CLUSTER_KEY_Z85 = 40 };

typedef enum cluster_key_kind { CLUSTER_KEY_PUBLIC = 0, CLUSTER_KEY_SECRET } cluster_key_kind;

/* KEYS/WHO.pub or KEYS/WHO.key. Returns 0, or -1 when the path does not fit. */
int cluster_key_path(const cluster_config *c, const char *who, cluster_key_kind kind, char *out,
                     size_t cap);
/* Reads one key into z85 (NUL-terminated). Returns 0, or -1 with one line naming the file
 * and what to do. */
int cluster_key_read(const cluster_config *c, const char *who, cluster_key_kind kind,
                     char z85[CLUSTER_KEY_Z85 + 1], char *err, size_t errlen);

#endif
