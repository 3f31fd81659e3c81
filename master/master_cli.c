/* master_cli: cavelight-master's option table (see master_cli.h). */
#include "master_cli.h"

#include <string.h>

#include "cluster/cluster_config.h"
#include "gi/gi_settings.h"
#include "gi/gi_budget.h"

enum group { G_CLUSTER, G_NODES, G_GI, G_DISPLAY, G_FRAMES, G_OUTPUT, G_INPUT, G_CALIBRATION, G_COUNT };

static const char *const groups[G_COUNT] = {
    "Cluster", "Nodes",
    "GI: indirect light, for every node (also the config's \"settings\"; node's options)",
    "Display, for every node (also the config's \"settings\")",
    "Frames", "Output", "Input", "Calibration (docs/calibration.md)",
};

enum id {
    O_CONFIG, O_BIND, O_ENDPOINT_FILE, O_BARRIER_MS, O_KEYGEN, O_INSECURE_ANYWHERE,
    O_SPAWN_LOCAL, O_SPAWN_REMOTE, O_NODE_EXE, O_NODE_ARGS, O_WAIT_MS, O_RENDER, O_SCENE,
    O_FRAMES, O_DT, O_FPS,
    O_OUTPUT, O_OUT, O_KEEP_FRAMES, O_OVERVIEW, O_REPORT, O_PREVIEW, O_QUIET,
    O_INPUT, O_RECORD,
    O_PATTERN, O_PATTERN_BLEND, O_PRINT_POSES,
    O_CHECK, O_STRICT, O_BUDGET,
    O_SCENE_TRANSFORM, O_ALLOW_OUTSIDE, O_APP,
    O_SETTING = 1000, /* + gi_option index: the GI and display settings (gi_settings.h) */
};

static const cli_option options[] = {
    {O_CONFIG, "config", "FILE", NULL, G_CLUSTER, 0, "the cluster config (required; docs/cluster.md)"},
    {O_BIND, "bind", "ENDPOINT", "the config's master.bind", G_CLUSTER, 0,
     "where nodes connect, e.g. tcp://*:5570 ('*' port: any free one)"},
    {O_ENDPOINT_FILE, "endpoint-file", "FILE", NULL, G_CLUSTER, 0, "write the bound endpoint there"},
    {O_BARRIER_MS, "barrier-ms", "MS", "the config's timeouts.barrier_ms", G_CLUSTER, 0,
     "drop a node not READY this long after FRAME"},
    {O_KEYGEN, "keygen", NULL, NULL, G_CLUSTER, 0,
     "write CURVE key pairs (master and every node) into the\nconfig's security.keys folder, then exit"},
    {O_CHECK, "check", NULL, NULL, G_CLUSTER, 0,
     "validate the config and exit, starting nothing: its keys,\nthe scene, the hosts, the CURVE keys, --input; one line\nper problem, exit 0 or 2"},
    {O_STRICT, "strict", NULL, NULL, G_CLUSTER, 0,
     "a key no part of the cluster or input config reads\n(a misspelling) is an error, not a warning"},
    {O_INSECURE_ANYWHERE, "insecure-anywhere", NULL, NULL, G_CLUSTER, 0,
     "let security \"insecure\" bind outside the loopback range\n(anybody who reaches the port may join or steer)"},
    {O_SPAWN_LOCAL, "spawn-local", NULL, NULL, G_NODES, 0, "start every node on this machine"},
    {O_SPAWN_REMOTE, "spawn-remote", NULL, NULL, G_NODES, 0,
     "start every node on its host through the config's launch\ncommand (ssh by default)"},
    {O_NODE_EXE, "node-exe", "PATH", "cavelight-node beside this program",
     G_NODES, 0, "the node program to start"},
    {O_NODE_ARGS, "node-args", "\"ARGS\"", NULL, G_NODES, 0,
     "more options for every started node, split at spaces"},
    {O_WAIT_MS, "wait-ms", "MS", "the config's timeouts.join_ms", G_NODES, 0,
     "how long to wait for the nodes to join"},
    {O_RENDER, "render", "gl|none", "gl", G_NODES, 0, "started nodes: none renders nothing (tests)"},
    {O_SCENE, "scene", "FILE|NAME", "the config's scene", G_NODES, 0, "the scene every node loads"},
    {O_APP, "app", "FILE.so", NULL, G_NODES, 0,
     "run an application (cavelight/app.h) on the master and\nevery started node (docs/app.md)"},
    {O_SCENE_TRANSFORM, "scene-transform", "JSON", "the config's scene_transform", G_NODES, 0,
     "where the scene stands in the CAVE, e.g. '{\"up\": \"z\",\n\"scale\": 0.01}' or '{\"fit\": true}' (docs/cluster.md)"},
    {O_ALLOW_OUTSIDE, "allow-outside-paths", NULL, NULL, G_NODES, 0,
     "glTF buffers and images from outside the scene file's\nfolder too"},
    {O_BUDGET, "budget-ms", "MS", NULL, G_GI, 0,
     "choose the settings of the frame's method (one with a\nbudget rule, docs/node.md) so that the frame pass takes\nabout MS ms on the slowest node (measured on every node\nbefore the session's frames)"},
    {O_FRAMES, "frames", "N", "0: until stopped; 1 with --pattern --output png", G_FRAMES, 0, "frames to run"},
    {O_DT, "dt", "S", "1/30", G_FRAMES, 0,
     "seconds of the scripted head and light path per frame\n(0: the wall clock)"},
    {O_FPS, "fps", "F", "0: as fast as the nodes go", G_FRAMES, 0, "frames per second at most"},
    {O_OUTPUT, "output", "window|headless|png", "each node's \"output\"", G_OUTPUT, 0,
     "what started nodes do with their images"},
    {O_OUT, "out", "DIR", CLUSTER_DEFAULT_OUT, G_OUTPUT, 0,
     "output folder (created with its parents): images of\nstarted nodes, recordings"},
    {O_KEEP_FRAMES, "keep-frames", NULL, NULL, G_OUTPUT, 0,
     "png output: keep every frame (SCREEN-EYE-NNNNNN.png)"},
    {O_OVERVIEW, "overview", "FILE.png", NULL, G_OUTPUT, 0,
     "at the end, the walls unfolded in one picture"},
    {O_REPORT, "report", "FILE", NULL, G_OUTPUT, 0, "at the end, the JSON report (docs/cluster.md)"},
    {O_PREVIEW, "preview", NULL, NULL, G_OUTPUT, 0,
     "a window here with the walls unfolded as the nodes write\nthem into --out (png output; docs/cluster.md); without a\ndisplay: one line, and the session goes on"},
    {O_QUIET, "quiet", NULL, NULL, G_OUTPUT, 0, "log only errors"},
    {O_INPUT, "input", "CONFIG|RECORDING", "the scripted head and light path", G_INPUT, 0,
     "trackers and wand (configs/input/), or a recording\nto replay (docs/input.md)"},
    {O_RECORD, "record", "FILE", "the input config's \"record\", in --out", G_INPUT, 0,
     "record the merged input there"},
    {O_PATTERN, "pattern", NULL, NULL, G_CALIBRATION, 0,
     "every screen shows a calibration pattern: a grid in CAVE\ncoordinates, screen names and corners, head and wand"},
    {O_PATTERN_BLEND, "pattern-blend", NULL, NULL, G_CALIBRATION, 0,
     "the pattern, and each started node tints where its\nprojectors' blend maps dim them (node --show-blend)"},
    {O_PRINT_POSES, "print-poses", NULL, NULL, G_CALIBRATION, 0,
     "print the head and wand poses (CAVE and tracker space,\npointing direction) and the buttons on stdout, 4 a second"},
};

/* A GI or display setting: checked now, applied over the config's in master_settings(). */
static const char *set_setting(master_options *o, const gi_option *g, const char *v)
{
    if (strcmp(g->row->name, "exposure") == 0 && strcmp(v, "auto") == 0) {
        o->exposure_auto = 1; /* from the scene's light, once it is loaded (exposure.h) */
        return NULL;
    }
    frame_params scratch;
    frame_params_default(&scratch);
    const char *why = gi_set(&scratch, g->row->name, v);
    if (why)
        return why;
    if (o->setting_count == MASTER_MAX_SETTINGS)
        return "one setting too many";
    if (strcmp(g->row->name, "exposure") == 0)
        o->exposure_auto = 0;
    o->setting_name[o->setting_count] = g->row->name;
    o->setting_value[o->setting_count++] = v;
    return NULL;
}

static const char *set(void *user, int id, const char *v)
{
    master_options *o = user;
    const char *why = NULL;
    float f;
    if (id >= O_SETTING)
        return set_setting(o, gi_option_at(id - O_SETTING), v);
    switch ((enum id)id) {
    case O_CONFIG: o->config = v; break;
    case O_BIND: o->bind = v; break;
    case O_ENDPOINT_FILE: o->endpoint_file = v; break;
    case O_BARRIER_MS: why = cli_int(v, 10, 600000, &o->barrier_ms); break;
    case O_KEYGEN: o->keygen = 1; break;
    case O_INSECURE_ANYWHERE: o->insecure_anywhere = 1; break;
    case O_SPAWN_LOCAL: o->spawn_local = 1; break;
    case O_SPAWN_REMOTE: o->spawn_remote = 1; break;
    case O_NODE_EXE: o->node_exe = v; break;
    case O_NODE_ARGS: o->node_args = v; break;
    case O_WAIT_MS: why = cli_int(v, 1, 24 * 3600 * 1000, &o->wait_ms); break;
    case O_RENDER:
        if (strcmp(v, "gl") && strcmp(v, "none"))
            return "gl or none";
        o->render = v;
        break;
    case O_SCENE: o->scene = v; break;
    case O_APP: o->app = v; break;
    case O_SCENE_TRANSFORM:
        if ((why = cluster_scene_transform_option(v, &o->scene_transform)) != NULL)
            break;
        o->scene_transform_text = v;
        o->has_scene_transform = 1;
        break;
    case O_ALLOW_OUTSIDE: o->allow_outside_paths = 1; break;
    case O_FRAMES: why = cli_int(v, 0, 1 << 30, &o->frames); break;
    case O_DT: why = cli_float(v, 0.0f, 10.0f, &f); o->dt = f; break;
    case O_FPS: why = cli_float(v, 0.0f, 1000.0f, &f); o->fps = f; break;
    case O_OUTPUT:
        if (cluster_output_parse(v) < 0)
            return "one of window, headless or png";
        o->output = v;
        break;
    case O_OUT: o->out_dir = v; break;
    case O_KEEP_FRAMES: o->keep_frames = 1; break;
    case O_OVERVIEW: o->overview = v; break;
    case O_REPORT: o->report = v; break;
    case O_PREVIEW: o->preview = 1; break;
    case O_QUIET: o->quiet = 1; break;
    case O_INPUT: o->input = v; break;
    case O_RECORD: o->record = v; break;
    case O_PATTERN: o->pattern = 1; break;
    case O_PATTERN_BLEND: o->pattern = o->pattern_blend = 1; break;
    case O_PRINT_POSES: o->print_poses = 1; break;
    case O_CHECK: o->check = 1; break;
    case O_STRICT: o->strict = 1; break;
    case O_BUDGET: why = cli_float(v, 1e-3f, 1e6f, &o->budget_ms); break;
    case O_SETTING: break;
    }
    return why;
}

cli_result master_cli_parse(int argc, char **argv, master_options *o)
{
    *o = (master_options){.dt = 1.0 / 30, .out_dir = CLUSTER_DEFAULT_OUT, .exposure_auto = -1};
    static cli_option all[CLI_MAX_OPTIONS];
    int count = (int)(sizeof options / sizeof *options);
    memcpy(all, options, sizeof options);
    count = gi_cli_options(all, count, O_SETTING, G_GI, G_DISPLAY, 0);
    cli_program p = {
        .name = "cavelight-master",
        .usage = "usage: cavelight-master --config FILE [--spawn-local | --spawn-remote] [options]\n"
                 "       cavelight-master --config FILE --keygen\n"
                 "       cavelight-master --config FILE --check [--input FILE] [--scene FILE]\n",
        .groups = groups, .group_count = G_COUNT,
        .options = all, .count = count,
        .epilogue = "Without --spawn-*, nodes are started by hand or as services (docs/deploy.md)\n"
                    "and join within --wait-ms.\n",
        .set = set, .user = o,
    };
    int npositional;
    cli_given given;
    cli_result r = cli_parse(&p, argc, argv, NULL, 0, &npositional, &given);
    if (r != CLI_OK)
        return r;
    if (!o->config) {
        fprintf(stderr, "cavelight-master: --config FILE is required (see --help)\n");
        return CLI_ERROR;
    }
    if (o->spawn_local && o->spawn_remote) {
        fprintf(stderr, "cavelight-master: choose one of --spawn-local and --spawn-remote\n");
        return CLI_ERROR;
    }
    if (o->print_poses && !o->input) {
        fprintf(stderr, "cavelight-master: --print-poses prints what the trackers deliver: add --input "
                "CONFIG (e.g. configs/input/art-dtrack.json)\n");
        return CLI_ERROR;
    }
    /* A still pattern written to files needs one frame; on screens it stays until stopped. */
    if (o->pattern && o->output && strcmp(o->output, "png") == 0 && !cli_was_given(&p, &given, O_FRAMES))
        o->frames = 1;
    const int spawn_only[] = {O_NODE_EXE, O_NODE_ARGS, O_RENDER, O_OUTPUT, O_KEEP_FRAMES};
    for (size_t i = 0; i < sizeof spawn_only / sizeof *spawn_only; i++)
        if (!o->spawn_local && !o->spawn_remote && cli_was_given(&p, &given, spawn_only[i])) {
            fprintf(stderr, "cavelight-master: --%s goes to the nodes the master starts: add "
                    "--spawn-local or --spawn-remote (nodes started by hand take it themselves)\n",
                    cli_find(&p, spawn_only[i])->name);
            return CLI_ERROR;
        }
    return CLI_OK;
}

/* gi_budget_check()'s question: was the setting named name given on the command line? */
static int setting_given(void *ctx, const char *name)
{
    const master_options *o = ctx;
    for (int i = 0; i < o->setting_count; i++)
        if (strcmp(o->setting_name[i], name) == 0)
            return 1;
    return 0;
}

int master_exposure_auto(const master_options *o, const cluster_config *cfg)
{
    if (o->exposure_auto >= 0)
        return o->exposure_auto;
    for (int i = 0; i < cfg->setting_count; i++)
        if (strcmp(cfg->settings[i].name, "exposure") == 0)
            return 0;
    return 1;
}

int master_settings(const master_options *o, const cluster_config *cfg, frame_params *out,
                    char *err, size_t errlen)
{
    frame_params_default(out);
    if (gi_set_config(cfg, out, err, errlen) != 0)
        return -1;
    for (int i = 0; i < o->setting_count; i++)
        gi_set(out, o->setting_name[i], o->setting_value[i]); /* checked when parsed */
    const char *why = gi_check(out);
    if (!why)
        why = ao_ambient_check(out);
    if (!why && o->budget_ms > 0)
        why = gi_budget_check(out, setting_given, (void *)o);
    if (why) {
        snprintf(err, errlen, "%s", why);
        return -1;
    }
    return 0;
}
