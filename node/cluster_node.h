/* cluster_node: the render node's cluster mode (cavelight-node --cluster FILE --name N).
 *
 * Runs the frame loop against the master: FRAME v -> params_to_frame -> frame pass once
 * and an eye pass per (screen, eye) -> READY(v, the frame's GI checksum, timings) -> SWAP v ->
 * present or write. With render "none" no GL is touched and the checksum is the
 * parameter store's (params_checksum): the stub used by the benchmark and fast tests.
 * cluster_node_run() is a library call (the benchmark runs nodes as threads);
 * cluster_node_start() is the program's cluster mode (the command line is node_cli.h's). */
#ifndef CAVELIGHT_CLUSTER_NODE_H
#define CAVELIGHT_CLUSTER_NODE_H

#include <signal.h>
#include <stddef.h>
#include <stdint.h>

#include "cluster/cluster_config.h"

typedef enum cluster_render_mode {
    CLUSTER_RENDER_GL = 0, /* the renderer on a GL context */
    CLUSTER_RENDER_NONE,   /* no GL: checksum of the applied parameters */
} cluster_render_mode;

typedef struct cluster_node_desc {
    const cluster_config *config;
    const char *name;
    const char *endpoint;       /* NULL = config master.connect */
    cluster_render_mode render;
    int output;                 /* cluster_output, or -1 for the config's */
    const char *out_dir;        /* png output folder, NULL = CLUSTER_DEFAULT_OUT */
    const char *scene;          /* NULL = config scene or the built-in default */
    int has_scene_transform;    /* --scene-transform: replaces the config's */
    scene_transform scene_transform;
    int allow_outside_paths;    /* --allow-outside-paths */
    int threads;                /* CPU threads of the GI methods, 0 = all cores (the GI
                                   method and its settings come from the master) */
    int exit_with_master;       /* 1: leave when the master ends the session */
    int keep_frames;            /* png output: also SCREEN-EYE-NNNNNN.png for every frame */
    int show_blend;             /* the pattern tints the projectors' blend regions */
    int quiet;
    const char *app;            /* an application's shared object; NULL: the config's "app" */
    uint64_t fault_checksum_from; /* test hook: report a wrong checksum from this version */
    volatile sig_atomic_t *stop;  /* set to leave the loop, may be NULL */
} cluster_node_desc;

typedef struct cluster_node_stats {
    uint64_t frames, swaps;
    uint64_t last_version, last_checksum;
} cluster_node_stats;

/* Returns 0 on a clean exit, 1 on error (message in err). */
int cluster_node_run(const cluster_node_desc *desc, cluster_node_stats *stats, char *err, size_t errlen);
/* cavelight-node --cluster: loads the config, runs until the master ends the session or a
 * signal (SIGINT, SIGTERM) arrives. d comes from node_cli_parse(). Returns the exit status. */
int cluster_node_start(const char *config_path, cluster_node_desc *d);

#endif
