/* node_cli: cavelight-node's option table (see node_cli.h). */
#include "node_cli.h"

#include <stdlib.h>
#include <string.h>

#include "frame/frame_view.h"
#include "frame/hud.h"
#include "gi/gi_settings.h"
#include "gi/gi_budget.h"
#include "reference/reference.h"

enum { MODE_STANDALONE = 1u << NODE_MODE_STANDALONE, MODE_CLUSTER = 1u << NODE_MODE_CLUSTER };

enum group { G_MODE, G_CLUSTER, G_SCENE, G_OUTPUT, G_GI, G_DISPLAY, G_REFERENCE, G_TEST, G_COUNT };

static const char *const groups[G_COUNT] = {
    "Mode (one of them)",
    "Cluster (--cluster)",
    "Scene and view (standalone)",
    "Output",
    "GI: indirect light (standalone; the master sets them for a cluster)",
    "Display and HUD (standalone; the master sends them in a cluster)",
    "Path-traced reference (standalone, --renderer reference)",
    "Test hooks",
};

static const char *const modes[] = {
    "standalone mode (--standalone)",
    "cluster mode (--cluster: give GI and display settings to cavelight-master or the config's "
    "\"settings\")"};

enum id {
    O_STANDALONE, O_CLUSTER, O_NAME, O_MASTER, O_EXIT_WITH_MASTER, O_RENDER, O_QUIET,
    O_GL, O_SCENE, O_CAMERA, O_FRAMES, O_WIDTH, O_HEIGHT, O_POSITION, O_TARGET, O_FOV, O_SCREEN, O_EYE,
    O_EYES, O_EYE_SEPARATION,
    O_OUT, O_OUTPUT, O_KEEP_FRAMES, O_SHOW_BLEND, O_PFM,
    O_THREADS, O_CACHE_DIR, O_BUDGET, O_HUD, O_WAND,
    O_RENDERER, O_SAMPLES, O_BOUNCES, O_SEED,
    O_FAULT_CHECKSUM, O_LIGHT_DRIFT,
    O_SCENE_TRANSFORM, O_ALLOW_OUTSIDE, O_APP,
    O_SETTING = 1000, /* + gi_option index: the GI and display settings (gi_settings.h) */
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
    {O_APP, "app", "FILE.so", NULL, G_CLUSTER, 0,
     "an application (cavelight/app.h, docs/app.md): the master's\n--app; standalone: its update, frame and draw here"},
    {O_GL, "gl", "egl|osmesa|glfw", "egl", G_SCENE, S, "GL context: headless EGL, OSMesa, or a GLFW window"},
    {O_SCENE, "scene", "FILE|NAME", "default (cluster: the config's scene)", G_SCENE, 0,
     "glTF 2.0 (.gltf/.glb) or a built-in scene: default,\n"
     "corridor, doorway, courtyard, street, leak-lid,\nleak-panel, leak-wall (docs/node.md)"},
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
    {O_SHOW_BLEND, "show-blend", NULL, NULL, G_OUTPUT, C,
     "while the master shows the pattern: tint where each\nprojector's blend dims it (docs/cluster.md)"},
    {O_PFM, "pfm", NULL, NULL, G_OUTPUT, S, "also write linear final/direct/indirect PFMs"},
    {O_THREADS, "threads", "T", "all cores", G_GI, 0, "CPU threads of the GI methods (and the path tracer)"},
    {O_CACHE_DIR, "cache-dir", "DIR", "CAVELIGHT_CACHE_DIR, else $XDG_CACHE_HOME/cavelight, else ~/.cache/cavelight",
     G_GI, 0, "where a GI method keeps what it computes once per scene\n(caches: the light caches; sets CAVELIGHT_CACHE_DIR)"},
    {O_BUDGET, "budget-ms", "MS", NULL, G_GI, S,
     "choose the settings of the frame's method (one with a\nbudget rule, docs/node.md) so that its work takes about\nMS ms per frame on this machine"},
    {O_HUD, "hud", "0|1|2", "no HUD", G_DISPLAY, S, "show the HUD of that layout (navigation, lighting, settings)"},
    {O_WAND, "wand", "x,y,z", "in front of the first eye", G_DISPLAY, S, "HUD wand position (pointing along -Z)"},
    {O_RENDERER, "renderer", "raster|reference", "raster", G_REFERENCE, S,
     "GL rasterizer + LPV, or the Embree path tracer\n(mono; writes reference_*.pfm/png/json)"},
    {O_SAMPLES, "samples", "N", NULL, G_REFERENCE, S, "paths per pixel per half image"},
    {O_BOUNCES, "bounces", "B", NULL, G_REFERENCE, S, "reflections per path"},
    {O_SEED, "seed", "S", "1", G_REFERENCE, S, "random seed (the halves use S and S+1)"},
    {O_FAULT_CHECKSUM, "fault-checksum-from", "V", NULL, G_TEST, C,
     "report a wrong checksum from frame version V on"},
    {O_LIGHT_DRIFT, "light-drift", "M", NULL, G_TEST, S,
     "move the first light M metres along x each frame (no frame's GI is reused)"},
};
#undef S
#undef C

static const char *const render_names[] = {"gl", "none"};
static const char *const renderer_names[] = {"raster", "reference"};
static const char *const eyes_names[] = {"mono", "stereo"};

#define CHOICE(field, names)                                                                  \
    do {                                                                                      \
        int k_ = cli_choice(v, names, (int)(sizeof names / sizeof *names));                   \
        if (k_ < 0)                                                                           \
            return cli_choice_reason(names, (int)(sizeof names / sizeof *names));             \
        field = k_;                                                                           \
    } while (0)

/* The options of the standalone view and its output. */
static const char *set_view(node_options *o, int id, const char *v)
{
    const char *why = NULL;
    switch ((enum id)id) {
    case O_GL:
        if (glctx_parse_backend(v, &o->gl) != 0)
            return "one of egl, osmesa or glfw";
        break;
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
    case O_PFM: o->pfm = 1; break;
    case O_BUDGET: why = cli_float(v, 1e-3f, 1e6f, &o->budget_ms); break;
    case O_LIGHT_DRIFT: why = cli_float(v, -1.0f, 1.0f, &o->light_drift); break;
    case O_HUD: why = cli_int(v, 0, HUD_INDICATOR_COUNT - 1, &o->frame.hud_layout); break;
    case O_WAND: why = cli_floats(v, 3, o->wand); o->have_wand = 1; break;
    case O_RENDERER: {
        int k;
        CHOICE(k, renderer_names);
        o->reference = k == 1;
        break;
    }
    case O_SAMPLES: why = cli_int(v, 1, 1 << 20, &o->samples); break;
    case O_BOUNCES: why = cli_int(v, 1, 1000, &o->bounces); break;
    case O_SEED: {
        char *end;
        o->seed = strtoull(v, &end, 10);
        if (end == v || *end || v[0] == '-')
            return "a whole number >= 0";
        break;
    }
    default: break;
    }
    return why;
}

static const char *set(void *user, int id, const char *v)
{
    node_cli *c = user;
    node_options *o = &c->standalone;
    cluster_node_desc *d = &c->cluster;
    if (id >= O_SETTING) {
        const gi_option *g = gi_option_at(id - O_SETTING);
        /* --exposure auto (the default): the scene's light decides, once it is loaded
         * (exposure.h); a number fixes it. */
        if (strcmp(g->row->name, "exposure") == 0) {
            o->exposure_auto = strcmp(v, "auto") == 0;
            if (o->exposure_auto)
                return NULL;
        }
        return gi_set(&o->frame, g->row->name, v);
    }
    switch ((enum id)id) {
    case O_STANDALONE: o->standalone = 1; break;
    case O_CLUSTER: c->config_path = v; break;
    case O_NAME: d->name = v; break;
    case O_MASTER: d->endpoint = v; break;
    case O_EXIT_WITH_MASTER: d->exit_with_master = 1; break;
    case O_RENDER: CHOICE(d->render, render_names); break;
    case O_QUIET: d->quiet = 1; break;
    case O_APP: o->app = d->app = v; break;
    case O_SCENE: o->scene = d->scene = v; break;
    case O_SCENE_TRANSFORM: {
        const char *why = cluster_scene_transform_option(v, &d->scene_transform);
        d->has_scene_transform = !why;
        return why;
    }
    case O_ALLOW_OUTSIDE: o->allow_outside_paths = d->allow_outside_paths = 1; break;
    case O_OUT: o->out = d->out_dir = v; break;
    case O_OUTPUT:
        if ((d->output = cluster_output_parse(v)) < 0)
            return "one of window, headless or png";
        break;
    case O_KEEP_FRAMES: d->keep_frames = 1; break;
    case O_SHOW_BLEND: d->show_blend = 1; break;
    case O_THREADS: {
        const char *why = cli_int(v, 0, 256, &o->threads);
        d->threads = o->threads;
        return why;
    }
    case O_CACHE_DIR: /* read where the folder is needed (common/gi/caches/cache_file.h) */
        if (!*v || setenv("CAVELIGHT_CACHE_DIR", v, 1) != 0)
            return "a folder";
        break;
    case O_FAULT_CHECKSUM: {
        char *end;
        d->fault_checksum_from = strtoull(v, &end, 10);
        if (end == v || *end || v[0] == '-')
            return "a frame version >= 0";
        break;
    }
    default: return set_view(o, id, v);
    }
    return NULL;
}

/* Defaults that live in the code they configure, shown from there. */
static const char *show_default(void *user, int id, char *buf, size_t cap)
{
    switch ((enum id)id) {
    case O_EYE_SEPARATION: snprintf(buf, cap, "%g", FRAME_VIEW_EYE_SEPARATION); break;
    case O_SAMPLES: snprintf(buf, cap, "%d", REFERENCE_DEFAULT_SAMPLES); break;
    case O_BOUNCES: snprintf(buf, cap, "%d", REFERENCE_DEFAULT_BOUNCES); break;
    default: return NULL;
    }
    return buf;
}

/* The command line, for setting_given(). */
typedef struct given_query {
    const cli_program *program;
    const cli_given *given;
} given_query;

/* gi_budget_check()'s question: was the setting named name on the command line? */
static int setting_given(void *ctx, const char *name)
{
    const given_query *q = ctx;
    const cli_program *p = q->program;
    const cli_given *given = q->given;
    for (int i = 0; i < gi_option_count(); i++)
        if (strcmp(gi_option_at(i)->row->name, name) == 0)
            return cli_was_given(p, given, O_SETTING + i);
    return 0;
}

/* What no single option can say. */
static int check_standalone(const node_options *o, const cli_program *p, const cli_given *given)
{
    given_query q = {p, given};
    const char *why = gi_check(&o->frame); /* the methods' own rules first */
    if (!why && o->budget_ms > 0)
        why = gi_budget_check(&o->frame, setting_given, &q);
    if (!why && o->have_screen != o->have_eye)
        why = "--screen and --eye go together";
    if (!why && !o->reference)
        why = ao_ambient_check(&o->frame);
    if (!why && o->reference && o->app)
        why = "--app runs with the GL renderer, not --renderer reference";
    if (!why && o->reference && o->stereo)
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
        .exposure_auto = 1,
    };
    frame_params_default(&c->standalone.frame);
    c->cluster = (cluster_node_desc){.output = -1, .render = CLUSTER_RENDER_GL};
    static cli_option all[CLI_MAX_OPTIONS];
    int count = (int)(sizeof options / sizeof *options);
    memcpy(all, options, sizeof options);
    count = gi_cli_options(all, count, O_SETTING, G_GI, G_DISPLAY, MODE_STANDALONE);
    cli_program p = {
        .name = "cavelight-node",
        .usage = "usage: cavelight-node --standalone [options]\n"
                 "       cavelight-node --cluster FILE --name NODE [options]\n",
        .groups = groups, .group_count = G_COUNT, .modes = modes, .mode_count = 2,
        .options = all, .count = count,
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
    if (!cluster && check_standalone(&c->standalone, &p, &given) != 0)
        return CLI_ERROR;
    return CLI_OK;
}
