/* master_cli: cavelight-master's command line, one option table (base/cli.h) for the parser
 * and --help. master_cli_parse() fills master_options with every default applied except
 * the ones that come from the cluster config (0 / NULL there). */
#ifndef CAVELIGHT_MASTER_CLI_H
#define CAVELIGHT_MASTER_CLI_H

#include "base/cli.h"
#include "frame/frame_params.h"
#include "cluster/cluster_config.h"

enum { MASTER_MAX_SETTINGS = 96 };
#include "scene/scene_transform.h"

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
    const char *app;            /* --app: an application's shared object, or NULL */
    const char *out_dir;        /* never NULL: --out or CLUSTER_DEFAULT_OUT */
    const char *report, *overview;
    int keep_frames, pattern, print_poses, preview;
    int pattern_blend;  /* --pattern-blend: the pattern, and started nodes tint their blend regions */
    const char *input, *record;
    /* The GI and display settings given (gi_settings.h), as name and text in the order
     * given, each checked already: the session applies them over the config's "settings". */
    int setting_count;
    const char *setting_name[MASTER_MAX_SETTINGS], *setting_value[MASTER_MAX_SETTINGS];
    int exposure_auto;          /* --exposure auto 1, --exposure N 0, not given -1 */
    float budget_ms;            /* > 0: --budget-ms, every node measured (session.h) */
    int check;                  /* --check: validate the config and exit (check.h) */
    int strict;                 /* unknown keys in the cluster or input config are errors */
    const char *scene_transform_text; /* --scene-transform JSON, passed on to spawned nodes */
    int has_scene_transform;
    scene_transform scene_transform;  /* its parse; replaces the config's */
    int allow_outside_paths;    /* --allow-outside-paths (spawned nodes get it too) */
} master_options;

/* CLI_OK, CLI_HELP (help printed: exit 0) or CLI_ERROR (one line printed: exit 2). */
cli_result master_cli_parse(int argc, char **argv, master_options *o);
/* Whether the session derives the exposure from the scene's light (frame/exposure.h): the
 * default, unless the config's "settings" or --exposure give a number (--exposure auto
 * over a config's number: auto). */
int master_exposure_auto(const master_options *o, const cluster_config *cfg);
/* The session's first frame settings: the defaults, the config's "settings", then the
 * command line's (gi_check() over all of them). 0, or -1 with one line in err. */
int master_settings(const master_options *o, const cluster_config *cfg, frame_params *out,
                    char *err, size_t errlen);

#endif
