/* master_cli: cavelight-master's command line, one option table (base/cli.h) for the parser
 * and --help. master_cli_parse() fills master_options with every default applied except
 * the ones that come from the cluster config (0 / NULL there). */
#ifndef CAVELIGHT_MASTER_CLI_H
#define CAVELIGHT_MASTER_CLI_H

#include "base/cli.h"
#include "frame/frame_params.h"

typedef struct master_options {
    const char *config;
    int spawn_local, spawn_remote, keygen, quiet;
    int insecure_anywhere;      /* security "insecure" may bind outside the loopback range */
    const char *bind, *endpoint_file;
    int frames;                 /* 0 = until stopped */
    double dt, fps;             /* scripted seconds per frame; pacing (0 = as fast as possible) */
    int wait_ms;                /* for nodes to join; 0 = the config's timeouts.join_ms */
    int barrier_ms;             /* 0 = the config's */
    const char *node_exe, *render, *output, *node_args, *scene;
    const char *out_dir;        /* never NULL: --out or CLUSTER_DEFAULT_OUT */
    const char *report, *overview;
    int keep_frames, pattern, print_poses, preview;
    const char *input, *record;
    frame_gi gi;                /* the GI method the session starts with (0 = ILPV) */
    int gi_given;               /* --gi was given: spawned nodes get it too */
    int vpl_count;              /* vpl's lights per frame; 0 = FRAME_VPL_DEFAULT */
    vpl_selection vpl_selection; /* vpl's selection rule (0 = by flux) */
    float exposure;             /* 0 = the frame default */
    int exposure_auto;          /* --exposure auto */
} master_options;

/* CLI_OK, CLI_HELP (help printed: exit 0) or CLI_ERROR (one line printed: exit 2). */
cli_result master_cli_parse(int argc, char **argv, master_options *o);

#endif
