/* session: one cluster session on the master, as a library a test can drive.
 *
 *   session *s = session_create(&desc, err, sizeof err);  bind, load the scene, seed the
 *                                                          parameter store, open the input
 *   session_wait_nodes(s, n, ms, stop);                    HELLO -> SNAPSHOT
 *   per frame: session_frame(s, &result);                  input (or the scripted path) ->
 *                                                          interaction -> store -> FRAME,
 *                                                          barrier, SWAP; statistics kept
 *   session_write_report(s, path, wall_s);                 the JSON report (docs/cluster.md)
 *   session_destroy(s);                                    BYE to every node
 *
 * The store starts from the desc's settings (frame_params_default() and the GI and display
 * settings of the config and the command line) with the scene's lights, the frame a
 * standalone node with the same options starts from. Live or recorded input (docs/input.md), its head and wand
 * poses checked by pose_guard.h (a bad pose never reaches the nodes), drives the
 * interaction layouts; without it the scripted head and light path (script.h) moves at
 * desc.dt seconds per frame (or with the wall clock). The scene's objects
 * (scene_pose.h) move by the file's animations, the wand's grab layout (grab.h) and an
 * application (desc.app: its update runs once per frame, after the interaction, and sets
 * its keys and objects; app_host.h). No processes, no signals, no command line: those are
 * master/main.c's. */
#ifndef CAVELIGHT_SESSION_H
#define CAVELIGHT_SESSION_H

#include <signal.h>
#include <stddef.h>

#include "cluster/cluster_config.h"
#include "cluster_master.h"

typedef struct session session;

typedef struct session_desc {
    const cluster_config *config;
    const char *bind;       /* NULL = the config's */
    int barrier_ms;         /* 0 = the config's */
    int quiet;              /* 1: log only errors */
    int insecure_anywhere;  /* 1: security "insecure" may bind outside the loopback range */
    const char *scene;      /* NULL = the config's scene, or "default" */
    const char *input;      /* input config or recording; NULL = the scripted path */
    const char *record;     /* record the merged input there; NULL = the input config's */
    const char *out_dir;    /* the session's output folder; NULL = CLUSTER_DEFAULT_OUT */
    double dt;              /* scripted seconds per frame; <= 0 = the wall clock */
    int pattern;            /* 1: every screen shows the calibration pattern (pattern.h) */
    int print_poses;        /* 1: the head and wand poses on stdout, 4 lines a second */
    const frame_params *settings; /* the GI and display settings the session starts with
                                     (master_settings()); NULL: the defaults */
    int exposure_auto;      /* 1: exposure_from_light() of the scene (frame/exposure.h) */
    int strict;             /* 1: unknown keys in the input config are errors */
    const char *app;        /* an application's shared object (cavelight/app.h), or NULL */
} session_desc;

typedef enum session_step {
    SESSION_FRAME_DONE = 0, /* committed, barrier passed, SWAP sent */
    SESSION_NO_NODES,       /* no node is live: nothing was sent; wait and try again */
    SESSION_INPUT_ENDED,    /* a stepped recording has ended: the session is over */
    SESSION_INPUT_FAILED,   /* a recording with errors: the session is over, not done */
} session_step;

/* Returns NULL with one line in err (bind, scene or input failed). */
session *session_create(const session_desc *desc, char *err, size_t errlen);
/* Sends BYE to every node and closes. */
void session_destroy(session *s);
cluster_master *session_master(session *s);
/* Waits until count nodes are live, timeout_ms passed or *stop is set (may be NULL),
 * in short steps so that a signal is honoured. Returns the live count. */
int session_wait_nodes(session *s, int count, int timeout_ms, volatile sig_atomic_t *stop);
/* --budget-ms: the ILPV's lattice and steps for every node at once (gi/ilpv/ilpv_budget.h):
 * the plan's measuring frames run on every live node (they do not count as the session's
 * frames), each counted at its slowest node, and the choice goes into the settings of the
 * frames that follow, which start the LPV afresh. Returns 0, or -1 with one line in err
 * (no node was ready, or *stop was set). */
int session_choose_budget(session *s, double budget_ms, volatile sig_atomic_t *stop, char *err, size_t errlen);
/* One frame. result is filled for SESSION_FRAME_DONE. */
session_step session_frame(session *s, cluster_frame_result *result);
/* Frames done and the last committed version. */
int session_frames(const session *s);
uint64_t session_last_version(const session *s);
/* The report: traffic, barrier and per-node figures over the frames so far. Returns 0,
 * or -1 after printing one line. */
int session_write_report(session *s, const char *path, double wall_s);

#endif
