/* node_cli: cavelight-node's option table (see node_cli.h). */
#include "node_cli.h"

#include <stdlib.h>
#include <string.h>

#include "frame/frame_view.h"
#include "frame/hud.h"
#include "lpv/lattice.h"
#include "lpv/lpv_converge.h"
#include "reference.h"
#include "vpl_ism.h"

enum { MODE_STANDALONE = 1u << NODE_MODE_STANDALONE, MODE_CLUSTER = 1u << NODE_MODE_CLUSTER };

enum group { G_MODE, G_CLUSTER, G_SCENE, G_OUTPUT, G_GI, G_DISPLAY, G_REFERENCE, G_TEST, G_COUNT };

static const char *const groups[G_COUNT] = {
    "Mode (one of them)",
    "Cluster (--cluster)",
    "Scene and view (standalone)",
    "Output",
    "GI: indirect light (--gi; --vpl-* are vpl's, the rest ILPV's)",
    "Display and HUD (standalone; the master sends them in a cluster)",
    "Path-traced reference (standalone, --renderer reference)",
    "Test hooks",
};

static const char *const modes[] = {"standalone mode (--standalone)", "cluster mode (--cluster)"};

enum id {
    O_STANDALONE, O_CLUSTER, O_NAME, O_MASTER, O_EXIT_WITH_MASTER, O_RENDER, O_QUIET,
    O_GL, O_SCENE, O_CAMERA, O_FRAMES, O_WIDTH, O_HEIGHT, O_POSITION, O_TARGET, O_FOV, O_SCREEN, O_EYE,
    O_EYES, O_EYE_SEPARATION,
    O_OUT, O_OUTPUT, O_KEEP_FRAMES, O_PFM,
    O_GI, O_VPL_COUNT, O_VPL_SEED, O_VPL_BOUND, O_VPL_VISIBILITY, O_VPL_SELECTION, O_ISM_SIZE, O_ISM_POINTS, O_VPL_INTERLEAVE, O_LPV, O_RSM, O_LATTICE, O_LATTICE_CELLS, O_THREADS, O_STEPS, O_LAMBDA, O_ABSORPTION,
    O_SCATTERING, O_GL_TILES, O_LPV_MODE, O_CONVERGE, O_BUDGET,
    O_ENV, O_DISPLAY_GAMMA, O_EXPOSURE, O_HUD, O_WAND,
    O_RENDERER, O_SAMPLES, O_BOUNCES, O_SEED,
    O_FAULT_CHECKSUM,
    O_SCENE_TRANSFORM, O_ALLOW_OUTSIDE,
};

#define S MODE_STANDALONE
#define C MODE_CLUSTER
static const cli_option options[] = {
    {O_STANDALONE, "standalone", NULL, NULL, G_MODE, S, "render without a master: images and report.json"},
    {O_CLUSTER, "cluster", "FILE", NULL, G_MODE, C, "join the master of this cluster config as --name"},
    {O_NAME, "name", "NODE", NULL, G_CLUSTER, C, "this node's name in the config"},
    {O_MASTER, "master", "ENDPOINT", "the config's master.connect", G_CLUSTER, C,
     "the master's endpoint, e.g. tcp://host:5570"},
    {O_EXIT_WITH_MASTER, "exit-with-master", NULL, "wait for the next master", G_CLUSTER, C,
     "leave when the master ends the session"},
    {O_RENDER, "render", "gl|none", "gl", G_CLUSTER, C, "none: no GL, the checksum of the parameters (tests)"},
    {O_QUIET, "quiet", NULL, NULL, G_CLUSTER, C, "log only errors"},
    {O_GL, "gl", "egl|osmesa|glfw", "egl", G_SCENE, S, "GL context: headless EGL, OSMesa, or a GLFW window"},
    {O_SCENE, "scene", "FILE|NAME", "default (cluster: the config's scene)", G_SCENE, 0,
     "glTF 2.0 (.gltf/.glb) or a built-in scene: default,\n"
     "corridor, doorway, courtyard, leak-lid, leak-panel,\nleak-wall (docs/node.md)"},
    {O_SCENE_TRANSFORM, "scene-transform", "JSON", "the config's scene_transform", G_CLUSTER, C,
     "where the scene stands in the CAVE (docs/cluster.md)"},
    {O_ALLOW_OUTSIDE, "allow-outside-paths", NULL, NULL, G_SCENE, 0,
     "glTF buffers and images from outside the scene file's\nfolder too"},
    {O_CAMERA, "camera", "NAME|INDEX", "the file's first; without one, a view inside the scene",
     G_SCENE, S, "the scene file's camera to look through"},
    {O_FRAMES, "frames", "N", "1", G_SCENE, S, "frames to render"},
    {O_WIDTH, "width", "W", "320", G_SCENE, S, "image width"},
    {O_HEIGHT, "height", "H", "240; a file camera's aspect ratio", G_SCENE, S, "image height"},
    {O_POSITION, "position", "x,y,z", "the scene's camera", G_SCENE, S, "symmetric camera position instead"},
    {O_TARGET, "target", "x,y,z", "the scene's camera", G_SCENE, S, "point the camera looks at"},
    {O_FOV, "fov", "DEG", "the scene's", G_SCENE, S, "vertical field of view"},
    {O_SCREEN, "screen", "blx,bly,blz,brx,bry,brz,tlx,tly,tlz", NULL, G_SCENE, S,
     "off-axis screen: bottom-left, bottom-right, top-left\ncorners (with --eye)"},
    {O_EYE, "eye", "x,y,z", NULL, G_SCENE, S, "eye (head) position for --screen"},
    {O_EYES, "eyes", "mono|stereo", "mono", G_SCENE, S, "one eye or two"},
    {O_EYE_SEPARATION, "eye-separation", "M", NULL, G_SCENE, S, "distance between the eyes, metres"},
    {O_OUT, "out", "DIR", NULL, G_OUTPUT, 0, "output folder, created with its parents\n"
     "(standalone: frameNNNN_EYE.png and report.json, none\n"
     "without --out; cluster: SCREEN-EYE.png for png output,\ndefault out)"},
    {O_OUTPUT, "output", "window|headless|png", "the node's \"output\" in the config", G_OUTPUT, C,
     "what the node does with its images"},
    {O_KEEP_FRAMES, "keep-frames", NULL, NULL, G_OUTPUT, C,
     "png output: also keep every frame as SCREEN-EYE-NNNNNN.png"},
    {O_PFM, "pfm", NULL, NULL, G_OUTPUT, S, "also write linear final/direct/indirect PFMs"},
    {O_GI, "gi", "ilpv|none|vpl", "ilpv", G_GI, 0,
     "indirect-light method: incremental LPV, none (direct\nlight only), or virtual point lights with a shadow map\neach; cluster: the first, the master's frames choose"},
    {O_VPL_COUNT, "vpl-count", "N", NULL, G_GI, S, "vpl: lights chosen per frame (64..4096)"},
    {O_VPL_SEED, "vpl-seed", "S", NULL, G_GI, S, "vpl: seed of their random choice"},
    {O_VPL_BOUND, "vpl-bound", "disk|point", "disk", G_GI, S,
     "vpl: each light a disk of its area near it, or a point\n(unbounded: to measure the disk's bias)"},
    {O_VPL_VISIBILITY, "vpl-visibility", "exact|ism|ism-splat", "exact", G_GI, S,
     "vpl: a cube shadow map per light from the triangles, or\nimperfect maps from points (pull-push or splats)"},
    {O_VPL_SELECTION, "vpl-selection", "flux|view|regular", "flux", G_GI, S,
     "vpl: choose lights by flux, by flux and what the head\nsees (bidirectional), or on a regular pattern"},
    {O_ISM_SIZE, "ism-size", "N", NULL, G_GI, S, "vpl: texels per side of each imperfect map\n(a power of two, 8..256)"},
    {O_ISM_POINTS, "ism-points", "N", NULL, G_GI, S, "vpl: points per imperfect map (64..16384)"},
    {O_VPL_INTERLEAVE, "vpl-interleave", "K", "0 (every pixel every light)", G_GI, S,
     "vpl: interleaved sampling in K x K blocks (1..8):\neach pixel gathers 1/K^2 of the lights, then a blur\nthat keeps edges"},
    {O_LPV, "lpv", "auto|cpu|gl", "auto", G_GI, S, "where the LPV runs (auto: CPU on llvmpipe, GL on a GPU)"},
    {O_RSM, "rsm", "N", NULL, G_GI, 0, "reflective shadow map size"},
    {O_LATTICE, "lattice", "N", NULL, G_GI, 0, "LPV cells along the scene's longest axis"},
    {O_LATTICE_CELLS, "lattice-cells", "N", NULL, G_GI, S,
     "instead of --lattice: N cells in all, fitted to the\nscene's shape (finer cells in a long, thin scene)"},
    {O_THREADS, "threads", "T", "all cores", G_GI, 0, "CPU LPV (and path tracer) threads"},
    {O_STEPS, "steps", "S", NULL, G_GI, S, "propagation steps per frame"},
    {O_LAMBDA, "lambda", "L", NULL, G_GI, S, "lambda_incr: share of the last frame's light kept, [0, 1)"},
    {O_ABSORPTION, "absorption", "S", NULL, G_GI, S, "participating medium: absorption per metre"},
    {O_SCATTERING, "scattering", "S", NULL, G_GI, S, "participating medium: scattering per metre"},
    {O_GL_TILES, "gl-tiles", "auto|on|off", "auto", G_GI, S, "GL propagation through shared-memory tiles"},
    {O_LPV_MODE, "lpv-mode", "incremental|classic", "incremental", G_GI, 0,
     "ILPV, or classic LPV accumulation (every node the same)"},
    {O_CONVERGE, "converge-threshold", "R", NULL, G_GI, 0,
     "skip the frame pass once the LPV residual is below R\nand nothing changed (negative = never)"},
    {O_BUDGET, "budget-ms", "X", NULL, G_GI, S,
     "choose --lattice and --steps so that the LPV work takes\nabout X ms per frame on this machine"},
    {O_ENV, "env", "dark|dim|office", NULL, G_DISPLAY, S, "viewing environment (end-to-end gamma)"},
    {O_DISPLAY_GAMMA, "display-gamma", "G", NULL, G_DISPLAY, S, "display gamma"},
    {O_EXPOSURE, "exposure", "E", NULL, G_DISPLAY, S, "linear scale before tone mapping"},
    {O_HUD, "hud", "0|1|2", "no HUD", G_DISPLAY, S, "show the HUD of that layout (navigation, lighting, settings)"},
    {O_WAND, "wand", "x,y,z", "in front of the first eye", G_DISPLAY, S, "HUD wand position (pointing along -Z)"},
    {O_RENDERER, "renderer", "raster|reference", "raster", G_REFERENCE, S,
     "GL rasterizer + LPV, or the Embree path tracer\n(mono; writes reference_*.pfm/png/json)"},
    {O_SAMPLES, "samples", "N", NULL, G_REFERENCE, S, "paths per pixel per half image"},
    {O_BOUNCES, "bounces", "B", NULL, G_REFERENCE, S, "reflections per path"},
    {O_SEED, "seed", "S", "1", G_REFERENCE, S, "random seed (the halves use S and S+1)"},
    {O_FAULT_CHECKSUM, "fault-checksum-from", "V", NULL, G_TEST, C,
     "report a wrong checksum from frame version V on"},
};
#undef S
#undef C

static const char *const env_names[] = {"dark", "dim", "office"};
static const char *const lpv_names[] = {"auto", "cpu", "gl"};
static const char *const tiles_names[] = {"auto", "on", "off"};
static const char *const mode_names[] = {"incremental", "classic"};
static const char *const render_names[] = {"gl", "none"};
static const char *const renderer_names[] = {"raster", "reference"};
static const char *const eyes_names[] = {"mono", "stereo"};
static const char *const vpl_bound_names[] = {"disk", "point"};

#define CHOICE(field, names)                                                                  \
    do {                                                                                      \
        int k_ = cli_choice(v, names, (int)(sizeof names / sizeof *names));                   \
        if (k_ < 0)                                                                           \
            return cli_choice_reason(names, (int)(sizeof names / sizeof *names));             \
        field = k_;                                                                           \
    } while (0)

static const char *set(void *user, int id, const char *v)
{
    node_cli *c = user;
    node_options *o = &c->standalone;
    cluster_node_desc *d = &c->cluster;
    frame_params *fp = &o->frame;
    const char *why = NULL;
    int k;
    switch ((enum id)id) {
    case O_STANDALONE: o->standalone = 1; break;
    case O_CLUSTER: c->config_path = v; break;
    case O_NAME: d->name = v; break;
    case O_MASTER: d->endpoint = v; break;
    case O_EXIT_WITH_MASTER: d->exit_with_master = 1; break;
    case O_RENDER: CHOICE(d->render, render_names); break;
    case O_QUIET: d->quiet = 1; break;
    case O_GL:
        if (glctx_parse_backend(v, &o->gl) != 0)
            return "one of egl, osmesa or glfw";
        break;
    case O_SCENE: o->scene = d->scene = v; break;
    case O_SCENE_TRANSFORM: d->has_scene_transform = !(why = cluster_scene_transform_option(v, &d->scene_transform)); break;
    case O_ALLOW_OUTSIDE: o->allow_outside_paths = d->allow_outside_paths = 1; break;
    case O_FRAMES: why = cli_int(v, 1, 1000000, &o->frames); break;
    case O_WIDTH: why = cli_int(v, 1, 16384, &o->width); break;
    case O_HEIGHT: why = cli_int(v, 1, 16384, &o->height); o->have_height = 1; break;
    case O_CAMERA: o->camera = v; break;
    case O_POSITION: why = cli_floats(v, 3, o->position); o->have_position = 1; break;
    case O_TARGET: why = cli_floats(v, 3, o->target); o->have_target = 1; break;
    case O_FOV: {
        float deg;
        if ((why = cli_float(v, 0.01f, 179.0f, &deg)) == NULL)
            o->yfov = deg * 3.14159265f / 180.0f;
        break;
    }
    case O_SCREEN: why = cli_floats(v, 9, o->screen); o->have_screen = 1; break;
    case O_EYE: why = cli_floats(v, 3, o->eye); o->have_eye = 1; break;
    case O_EYES: CHOICE(o->stereo, eyes_names); break;
    case O_EYE_SEPARATION: why = cli_float(v, 0.0f, 1.0f, &o->eye_separation); break;
    case O_OUT: o->out = d->out_dir = v; break;
    case O_OUTPUT:
        if ((d->output = cluster_output_parse(v)) < 0)
            return "one of window, headless or png";
        break;
    case O_KEEP_FRAMES: d->keep_frames = 1; break;
    case O_PFM: o->pfm = 1; break;
    case O_GI: CHOICE(k, frame_gi_names); fp->gi = (frame_gi)k; d->gi = k; break;
    case O_VPL_COUNT: why = cli_int(v, FRAME_VPL_MIN, FRAME_VPL_MAX, &fp->vpl_count); break;
    case O_VPL_SEED: {
        int seed = 0;
        why = cli_int(v, 0, 2147483647, &seed);
        fp->vpl_seed = (uint32_t)seed;
        break;
    }
    case O_VPL_BOUND: CHOICE(o->vpl_point, vpl_bound_names); break;
    case O_VPL_VISIBILITY: CHOICE(o->vpl_visibility, vpl_visibility_names); break;
    case O_VPL_SELECTION:
        CHOICE(k, vpl_selection_names);
        fp->vpl_selection = (vpl_selection)k;
        break;
    case O_ISM_SIZE:
        why = cli_int(v, RENDERER_ISM_SIZE_MIN, RENDERER_ISM_SIZE_MAX, &o->ism_size);
        if (!why && (o->ism_size & (o->ism_size - 1)))
            why = "a power of two";
        break;
    case O_VPL_INTERLEAVE:
        why = cli_int(v, 1, RENDERER_VPL_INTERLEAVE_MAX, &o->vpl_interleave);
        break;
    case O_ISM_POINTS:
        why = cli_int(v, RENDERER_ISM_POINTS_MIN, RENDERER_ISM_POINTS_MAX, &o->ism_points);
        break;
    case O_LPV: CHOICE(o->lpv, lpv_names); break;
    case O_RSM: why = cli_int(v, 8, 4096, &o->rsm); d->rsm_size = o->rsm; break;
    case O_LATTICE: why = cli_int(v, 2, 512, &o->lattice); d->lattice_cells = o->lattice; break;
    case O_LATTICE_CELLS: why = cli_int(v, 8, 1 << 24, &o->lattice_total); break;
    case O_THREADS: why = cli_int(v, 0, 256, &o->threads); d->lpv_threads = o->threads; break;
    case O_STEPS: why = cli_int(v, 0, 1000, &fp->lpv_steps); o->have_steps = 1; break;
    case O_LAMBDA: why = cli_floats(v, 1, &fp->lambda_incr); break;
    case O_ABSORPTION: why = cli_floats(v, 1, &fp->absorption); break;
    case O_SCATTERING: why = cli_floats(v, 1, &fp->scattering); break;
    case O_GL_TILES: CHOICE(o->tiles, tiles_names); break;
    case O_LPV_MODE: CHOICE(o->mode, mode_names); d->lpv_mode = (int)o->mode; break;
    case O_CONVERGE:
        why = cli_floats(v, 1, &o->converge_threshold);
        d->converge_threshold = o->converge_threshold;
        break;
    case O_BUDGET: why = cli_float(v, 1e-3f, 1e6f, &o->budget_ms); break;
    case O_ENV: CHOICE(fp->environment, env_names); break;
    case O_DISPLAY_GAMMA: why = cli_floats(v, 1, &fp->display_gamma); break;
    case O_EXPOSURE: why = cli_floats(v, 1, &fp->exposure); break;
    case O_HUD: why = cli_int(v, 0, HUD_INDICATOR_COUNT - 1, &fp->hud_layout); break;
    case O_WAND: why = cli_floats(v, 3, o->wand); o->have_wand = 1; break;
    case O_RENDERER: CHOICE(k, renderer_names); o->reference = k == 1; break;
    case O_SAMPLES: why = cli_int(v, 1, 1 << 20, &o->samples); break;
    case O_BOUNCES: why = cli_int(v, 1, 1000, &o->bounces); break;
    case O_SEED: {
        char *end;
        o->seed = strtoull(v, &end, 10);
        if (end == v || *end || v[0] == '-')
            return "a whole number >= 0";
        break;
    }
    case O_FAULT_CHECKSUM: {
        char *end;
        d->fault_checksum_from = strtoull(v, &end, 10);
        if (end == v || *end || v[0] == '-')
            return "a frame version >= 0";
        break;
    }
    }
    return why;
}

/* Defaults that live in the code they configure, shown from there. */
static const char *show_default(void *user, int id, char *buf, size_t cap)
{
    frame_params f;
    frame_params_default(&f);
    switch ((enum id)id) {
    case O_CONVERGE: snprintf(buf, cap, "%g", LPV_CONVERGE_DEFAULT_THRESHOLD); break;
    case O_EYE_SEPARATION: snprintf(buf, cap, "%g", FRAME_VIEW_EYE_SEPARATION); break;
    case O_RSM: snprintf(buf, cap, "%d", RENDERER_DEFAULT_RSM_SIZE); break;
    case O_LATTICE: snprintf(buf, cap, "%d", LATTICE_DEFAULT_AXIS_CELLS); break;
    case O_STEPS: snprintf(buf, cap, "%d", f.lpv_steps); break;
    case O_LAMBDA: snprintf(buf, cap, "%g", f.lambda_incr); break;
    case O_VPL_COUNT: snprintf(buf, cap, "%d", f.vpl_count); break;
    case O_VPL_SEED: snprintf(buf, cap, "%u", f.vpl_seed); break;
    case O_ISM_SIZE: snprintf(buf, cap, "%d", RENDERER_DEFAULT_ISM_SIZE); break;
    case O_ISM_POINTS: snprintf(buf, cap, "%d", RENDERER_DEFAULT_ISM_POINTS); break;
    case O_ABSORPTION: snprintf(buf, cap, "%g", f.absorption); break;
    case O_SCATTERING: snprintf(buf, cap, "%g", f.scattering); break;
    case O_ENV: snprintf(buf, cap, "%s", env_names[f.environment]); break;
    case O_DISPLAY_GAMMA: snprintf(buf, cap, "%g", f.display_gamma); break;
    case O_EXPOSURE: snprintf(buf, cap, "%g", f.exposure); break;
    case O_SAMPLES: snprintf(buf, cap, "%d", REFERENCE_DEFAULT_SAMPLES); break;
    case O_BOUNCES: snprintf(buf, cap, "%d", REFERENCE_DEFAULT_BOUNCES); break;
    default: return NULL;
    }
    return buf;
}

/* The frame's ranges are frame_params_sanitize()'s alone: a value it would change is
 * refused here with the option's name rather than changed behind the user's back. */
static int check_frame_options(const node_options *o)
{
    frame_params sane = o->frame;
    if (frame_params_sanitize(&sane) == 0)
        return 0;
    const frame_params *f = &o->frame;
    struct { const char *option; double given; int changed; } field[] = {
        {"--steps", f->lpv_steps, f->lpv_steps != sane.lpv_steps},
        {"--lambda", f->lambda_incr, f->lambda_incr != sane.lambda_incr},
        {"--absorption", f->absorption, f->absorption != sane.absorption},
        {"--scattering", f->scattering, f->scattering != sane.scattering},
        {"--display-gamma", f->display_gamma, f->display_gamma != sane.display_gamma},
        {"--exposure", f->exposure, f->exposure != sane.exposure},
    };
    for (size_t i = 0; i < sizeof field / sizeof field[0]; i++)
        if (field[i].changed) {
            fprintf(stderr, "cavelight-node: %s %g is outside what a frame accepts (see "
                    "frame_params_sanitize() in common/frame/frame_params.h)\n", field[i].option,
                    field[i].given);
            return -1;
        }
    return 0;
}

static int check_standalone(const node_options *o)
{
    if (check_frame_options(o) != 0)
        return -1;
    const char *why = NULL;
    if (o->budget_ms > 0 && (o->lattice > 0 || o->lattice_total > 0 || o->have_steps))
        why = "--budget-ms chooses --lattice and --steps: give either the budget or those two";
    else if (o->budget_ms > 0 && o->frame.gi != FRAME_GI_ILPV)
        why = "--budget-ms chooses the ILPV lattice: it needs --gi ilpv";
    else if (o->lattice > 0 && o->lattice_total > 0)
        why = "give --lattice (cells along the longest axis) or --lattice-cells (cells in all), not both";
    else if (o->have_screen != o->have_eye)
        why = "--screen and --eye go together";
    else if (o->reference && o->stereo)
        why = "--renderer reference renders one eye: use --eyes mono";
    if (why)
        fprintf(stderr, "cavelight-node: %s\n", why);
    return why ? -1 : 0;
}

cli_result node_cli_parse(int argc, char **argv, node_cli *c)
{
    *c = (node_cli){0};
    c->standalone = (node_options){
        .gl = GLCTX_EGL, .scene = "default", .frames = 1, .width = 320, .height = 240,
        .yfov = -1, .eye_separation = FRAME_VIEW_EYE_SEPARATION, .seed = 1,
    };
    frame_params_default(&c->standalone.frame);
    c->cluster = (cluster_node_desc){.output = -1, .render = CLUSTER_RENDER_GL};
    cli_program p = {
        .name = "cavelight-node",
        .usage = "usage: cavelight-node --standalone [options]\n"
                 "       cavelight-node --cluster FILE --name NODE [options]\n",
        .groups = groups, .group_count = G_COUNT, .modes = modes, .mode_count = 2,
        .options = options, .count = (int)(sizeof options / sizeof *options),
        .epilogue = "Options marked for one mode are refused in the other. docs/node.md describes\n"
                    "the standalone node, docs/cluster.md the cluster.\n",
        .set = set, .show_default = show_default, .user = c,
    };
    int npositional;
    cli_given given;
    cli_result r = cli_parse(&p, argc, argv, NULL, 0, &npositional, &given);
    if (r != CLI_OK)
        return r;
    int standalone = c->standalone.standalone, cluster = c->config_path != NULL;
    if (standalone == cluster) {
        fprintf(stderr, "cavelight-node: %s: use --standalone, or --cluster FILE --name NODE (see --help)\n",
                standalone ? "--standalone and --cluster exclude each other" : "no mode given");
        return CLI_ERROR;
    }
    c->mode = cluster ? NODE_MODE_CLUSTER : NODE_MODE_STANDALONE;
    if (cli_check_modes(&p, &given, (int)c->mode) != CLI_OK)
        return CLI_ERROR;
    if (cluster && !c->cluster.name) {
        fprintf(stderr, "cavelight-node: --cluster needs --name NODE (one of the config's nodes)\n");
        return CLI_ERROR;
    }
    if (!cluster && check_standalone(&c->standalone) != 0)
        return CLI_ERROR;
    return CLI_OK;
}
