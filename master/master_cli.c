/* master_cli: cavelight-master's option table (see master_cli.h). */
#include "master_cli.h"

#include <string.h>

#include "cluster/cluster_config.h"

enum group { G_CLUSTER, G_NODES, G_FRAMES, G_OUTPUT, G_INPUT, G_CALIBRATION, G_COUNT };

static const char *const groups[G_COUNT] = {
    "Cluster", "Nodes", "Frames", "Output", "Input", "Calibration (docs/calibration.md)",
};

enum id {
    O_CONFIG, O_BIND, O_ENDPOINT_FILE, O_BARRIER_MS, O_KEYGEN, O_INSECURE_ANYWHERE,
    O_SPAWN_LOCAL, O_SPAWN_REMOTE, O_NODE_EXE, O_NODE_ARGS, O_WAIT_MS, O_RENDER, O_SCENE, O_GI,
    O_VPL_COUNT, O_VPL_SELECTION,
    O_FRAMES, O_DT, O_FPS,
    O_OUTPUT, O_OUT, O_KEEP_FRAMES, O_OVERVIEW, O_REPORT, O_PREVIEW, O_QUIET, O_EXPOSURE,
    O_INPUT, O_RECORD,
    O_PATTERN, O_PRINT_POSES,
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
    {O_GI, "gi", "ilpv|none|vpl", "ilpv", G_NODES, 0,
     "the indirect-light method every node starts with (the\nsettings layout switches it live)"},
    {O_VPL_COUNT, "vpl-count", "N", "the frame default", G_NODES, 0,
     "vpl: virtual point lights per frame (64..4096)"},
    {O_VPL_SELECTION, "vpl-selection", "flux|view|regular", "flux", G_NODES, 0,
     "vpl: choose the lights by flux, by flux and what the\ntracked head sees, or on a regular pattern"},
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
    {O_EXPOSURE, "exposure", "E|auto", "1", G_OUTPUT, 0,
     "linear scale before tone mapping; auto: the scene's average\nlit surface at middle grey (docs/node.md)"},
    {O_INPUT, "input", "CONFIG|RECORDING", "the scripted head and light path", G_INPUT, 0,
     "trackers and wand (configs/input/), or a recording\nto replay (docs/input.md)"},
    {O_RECORD, "record", "FILE", "the input config's \"record\", in --out", G_INPUT, 0,
     "record the merged input there"},
    {O_PATTERN, "pattern", NULL, NULL, G_CALIBRATION, 0,
     "every screen shows a calibration pattern: a grid in CAVE\ncoordinates, screen names and corners, head and wand"},
    {O_PRINT_POSES, "print-poses", NULL, NULL, G_CALIBRATION, 0,
     "print the head and wand poses (CAVE and tracker space,\npointing direction) and the buttons on stdout, 4 a second"},
};

static const char *set(void *user, int id, const char *v)
{
    master_options *o = user;
    const char *why = NULL;
    float f;
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
    case O_GI: {
        int k = cli_choice(v, frame_gi_names, FRAME_GI_COUNT);
        if (k < 0)
            return cli_choice_reason(frame_gi_names, FRAME_GI_COUNT);
        o->gi = (frame_gi)k;
        o->gi_given = 1;
        break;
    }
    case O_VPL_COUNT: why = cli_int(v, FRAME_VPL_MIN, FRAME_VPL_MAX, &o->vpl_count); break;
    case O_VPL_SELECTION: {
        int k = cli_choice(v, vpl_selection_names, VPL_SELECT_COUNT);
        if (k < 0)
            return cli_choice_reason(vpl_selection_names, VPL_SELECT_COUNT);
        o->vpl_selection = (vpl_selection)k;
        break;
    }
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
    case O_EXPOSURE:
        if (strcmp(v, "auto") == 0) {
            o->exposure_auto = 1;
            break;
        }
        why = cli_float(v, 1e-6f, FRAME_MAX_EXPOSURE, &o->exposure);
        o->exposure_auto = 0;
        break;
    case O_INPUT: o->input = v; break;
    case O_RECORD: o->record = v; break;
    case O_PATTERN: o->pattern = 1; break;
    case O_PRINT_POSES: o->print_poses = 1; break;
    }
    return why;
}

cli_result master_cli_parse(int argc, char **argv, master_options *o)
{
    *o = (master_options){.dt = 1.0 / 30, .out_dir = CLUSTER_DEFAULT_OUT};
    cli_program p = {
        .name = "cavelight-master",
        .usage = "usage: cavelight-master --config FILE [--spawn-local | --spawn-remote] [options]\n"
                 "       cavelight-master --config FILE --keygen\n",
        .groups = groups, .group_count = G_COUNT,
        .options = options, .count = (int)(sizeof options / sizeof *options),
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
