/* launch: the render nodes the master starts, and the wait for every node to join.
 *
 * launch_nodes() starts one node per configured node, on this machine (--spawn-local) or
 * on its host through the config's launch template (--spawn-remote, ssh by default), with
 * the node's "exe", "workdir" and "config" from the config where given (the master's
 * otherwise), and its output in OUT/logs/NODE.log. launch_wait() waits up to wait_ms for
 * every node to join (started by it or by hand, e.g. as services): it says every few
 * seconds which are missing (name and host), reports a started node that exits with the
 * end of its log and stops waiting for it, and at the end names the ones still missing.
 * launch_poll() reports a node that ends during the session; launch_stop() lets the nodes
 * leave after BYE, then stops what is left and reports any that ended abnormally. The
 * master's output shows each node's output too. */
#ifndef CAVELIGHT_LAUNCH_H
#define CAVELIGHT_LAUNCH_H

#include <signal.h>

#include "cluster/cluster_config.h"
#include "cluster_master.h"
#include "master_cli.h"
#include "session.h"
#include "spawn.h"

/* The started nodes, and which of their ends were reported. */
typedef struct launch_set {
    spawn_set spawned;
    int told[SPAWN_MAX];
} launch_set;

/* Returns 0, or -1 after one line. */
int launch_nodes(const master_options *o, const cluster_config *cfg, cluster_master *m, launch_set *l);
/* Returns the live count. stop (may be NULL) ends the wait when set. */
int launch_wait(session *s, const cluster_config *cfg, launch_set *l, int wait_ms, int quiet,
                volatile sig_atomic_t *stop);
/* Reports each started node that ended since the last call (name, status or signal, the
 * end of its log); the session goes on with the others. Cheap enough for every frame. */
void launch_poll(launch_set *l);
/* 1 when nodes were started and every one has ended (none can come back by itself). */
int launch_all_ended(launch_set *l);
void launch_stop(launch_set *l);

#endif
