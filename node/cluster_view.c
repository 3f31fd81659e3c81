#include "cluster_view.h"
#include "base/xalloc.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app_host.h"
#include "app_draw.h"
#include "base/clock.h"
#include "base/folder.h"
#include "base/ratelog.h"
#include "frame/pattern.h"
#include "gi/gi_settings.h"
#include "gl/glctx.h"
#include "base/mat4.h"
#include "base/vec3.h"
#include "present/present.h"
#include "scene/scene.h"

struct cluster_view {
    const cluster_config *cfg;
    int node;
    cluster_output output;
    int threads;
    frame_params first;  /* the config's settings on the defaults: the warm-up frame */
    gi_limits limits;    /* what the frames' GI settings may cost (gi_cost.h) */
    scene sc;
    int scene_loaded;
    glctx *ctx;          /* the presentation's: headless, or the first window's */
    renderer *r;
    present *out;        /* viewport s * eyes + e: screen s of the node, eye e */
    float far_plane;
    int rendered;
    int show_blend;
    uint64_t version;    /* of the last rendered frame */
    float display_gamma; /* of the last rendered frame */
    int pattern;
    char refusal[256];   /* the renderer's last refusal, said once */
    app_host *app;       /* an application drawing into every eye pass, or NULL */
    app_draw *app_draw;  /* its points and lines, made at their first call */
    int screen, side;    /* the eye pass under way: config screen, eye side */
    ratelog eye_log;     /* eyes moved in front of a screen, screens without a projection */
};

int cluster_view_eye_count(const cluster_config *cfg, int node)
{
    return cfg->nodes[node].eyes == CLUSTER_EYES_STEREO ? 2 : 1;
}

static int eye_side(const cluster_config *cfg, int node, int eye)
{
    switch (cfg->nodes[node].eyes) {
    case CLUSTER_EYES_STEREO: return eye == 0 ? -1 : 1;
    case CLUSTER_EYES_LEFT: return -1;
    case CLUSTER_EYES_RIGHT: return 1;
    default: return 0;
    }
}

const char *cluster_view_eye_name(const cluster_config *cfg, int node, int eye)
{
    int side = eye_side(cfg, node, eye);
    return side < 0 ? "left" : side > 0 ? "right" : "mono";
}

int cluster_view_compute(const cluster_config *cfg, int screen, int side, const frame_params *f,
                         int width, int height, float far_plane, renderer_view *out,
                         float *distance)
{
    const cluster_screen *s = &cfg->screens[screen];
    const cluster_observer *o = &cfg->observer;
    /* Eye in CAVE space: head pose times the head-to-eye offset, then along the head's
     * right axis (the pose's first column). */
    float mid[3], right[3], eye_cave[3];
    frame_view_head_centre(f->head, o->head_to_eye, mid);
    memcpy(right, f->head, sizeof right);
    if (!(vec3_normalize(right) > 0))
        memcpy(right, (const float[3]){1, 0, 0}, sizeof right);
    frame_view_eye(mid, right, o->eye_separation, side, eye_cave);
    float corner[3][3], eye[3];
    mat4_transform_point(f->navigation, s->bottom_left, corner[0]);
    mat4_transform_point(f->navigation, s->bottom_right, corner[1]);
    mat4_transform_point(f->navigation, s->top_left, corner[2]);
    mat4_transform_point(f->navigation, eye_cave, eye);
    return frame_view_screen(corner[0], corner[1], corner[2], eye, far_plane, width, height, out,
                             distance);
}

/* The node's output (present.h): one viewport per screen and eye, each with its screen's
 * projector warp, read here once. The maps are uploaded by present_create() and freed. */
static int open_output(cluster_view *v, const cluster_view_desc *desc, char *err, size_t errlen)
{
    const cluster_node *n = &v->cfg->nodes[v->node];
    int eyes = cluster_view_eye_count(v->cfg, v->node), count = 0, rc = 0;
    warp_map maps[CLUSTER_NODE_MAX_SCREENS] = {0};
    present_viewport vps[PRESENT_MAX_VIEWPORTS];
    char names[PRESENT_MAX_VIEWPORTS][2 * CLUSTER_NAME_MAX + 8], log_name[64];
    for (int s = 0; rc == 0 && s < n->screen_count; s++) {
        const cluster_warp *w = &n->screens[s].warp;
        rc = cluster_warp_load(w, &maps[s], err, errlen);
        for (int e = 0; rc == 0 && e < eyes; e++, count++) {
            snprintf(names[count], sizeof names[count], "%s-%s", v->cfg->screens[n->screens[s].screen].name,
                     cluster_view_eye_name(v->cfg, v->node, e));
            vps[count] = (present_viewport){.name = names[count], .width = n->screens[s].width,
                                            .height = n->screens[s].height, .eye = eyes == 2 ? e : 0,
                                            .warp = w->kind ? &maps[s] : NULL, .to_cave = w->to_cave};
        }
    }
    snprintf(log_name, sizeof log_name, "cavelight-node %s", n->name);
    static const present_output outputs[] = {[CLUSTER_OUTPUT_WINDOW] = PRESENT_WINDOW,
                                             [CLUSTER_OUTPUT_HEADLESS] = PRESENT_HEADLESS,
                                             [CLUSTER_OUTPUT_PNG] = PRESENT_PNG};
    char title[96];
    snprintf(title, sizeof title, "cavelight %s", n->name);
    present_desc pd = {.output = outputs[v->output], .backend = GLCTX_EGL, .fallback = 1, .log_name = log_name,
                       .quiet = desc->quiet, .viewport_count = count, .viewports = vps,
                       .out_dir = desc->out_dir, .keep_frames = desc->keep_frames, .title = title,
                       .display = n->display, .stereo = n->stereo, .window = &n->window};
    if (rc == 0)
        v->out = present_create(&pd, err, errlen);
    for (int s = 0; s < n->screen_count; s++)
        warp_map_free(&maps[s]);
    if (rc == 0 && !v->out && v->output == CLUSTER_OUTPUT_WINDOW) {
        size_t used = strlen(err);
        snprintf(err + used, errlen - used, "; or render without a window: --output headless or png (or the "
                 "node's \"output\" in the config)");
    }
    if (v->out)
        v->ctx = present_context(v->out);
    return v->out ? 0 : -1;
}

/* The application's draw for the eye pass under way (renderer_desc.gbuffer_draw). */
static void gbuffer_draw(void *user, const frame_view *view, const float vp[16], GLuint fbo, GLuint depth)
{
    cluster_view *v = user;
    cavelight_draw d = {.screen = v->cfg->screens[v->screen].name, .eye = v->side, .width = view->width,
                        .height = view->height, .framebuffer = fbo, .depth_texture = depth};
    memcpy(d.view, view->view, sizeof d.view);
    memcpy(d.projection, view->projection, sizeof d.projection);
    memcpy(d.view_projection, vp, sizeof d.view_projection);
    memcpy(d.eye_position, view->eye_position, sizeof d.eye_position);
    app_host_draw(v->app, &d);
}

/* A renderer built for the config's settings (the master's frames may change them). */
static int make_renderer(cluster_view *v, char *err, size_t errlen)
{
    renderer_desc rd = {.gl = glctx_gl(v->ctx), .scene = &v->sc, .first = &v->first,
                        .threads = v->threads, .limits = &v->limits,
                        .gbuffer_draw = app_host_draws(v->app) ? gbuffer_draw : NULL, .gbuffer_user = v};
    memcpy(rd.head_to_eye, v->cfg->observer.head_to_eye, sizeof rd.head_to_eye);
    renderer *r = renderer_create(&rd, err, errlen);
    if (!r)
        return -1;
    if (v->r)
        renderer_destroy(v->r);
    v->r = r;
    return 0;
}

/* One untracked frame of every GI method (the config's settings) before the node says
 * HELLO: llvmpipe compiles shaders at first use (0.1 to 0.4 s for a 32x64 stereo node
 * under load here), which would hold every screen at the barrier in the node's first frame
 * after a (re)join or a live switch of the method, or get it dropped. The renderer is then
 * built afresh, so the node starts from the same state as any other; Mesa keeps the
 * compiled code (the first frame: about 50 ms instead of 100 to 240,
 * tests/integration/cluster_lib.sh's 2-node config, ready_after_frame_ms max). */
static int warm_up(cluster_view *v, char *err, size_t errlen)
{
    frame_params f = v->first;
    frame_params_lights_from_scene(&f, &v->sc);
    memcpy(&f.head[12], v->cfg->observer.home, sizeof v->cfg->observer.home);
    int lights = f.light_count;
    for (int m = 0; m < gi_method_count(); m++) {
        uint64_t checksum;
        float timings[WIRE_TIMING_COUNT];
        int fixed;
        f.gi = m;
        /* The session's method with the scene's lights; the others, which a frame may
         * switch to later, under an ambient light instead (their programs are made and
         * run all the same, and no view is dark): a method's light can take seconds a
         * frame on a software GL (ldm's splat), and ten nodes on two cores must still
         * join in time. */
        f.light_count = m == v->first.gi ? lights : 0;
        f.ambient = m == v->first.gi ? v->first.ambient : 1.0f;
        if (cluster_view_render(v, &f, &checksum, timings, &fixed, err, errlen) != 0)
            return -1;
    }
    return make_renderer(v, err, errlen);
}

cluster_view *cluster_view_create(const cluster_view_desc *desc, char *err, size_t errlen)
{
    cluster_view *v = xcalloc(1, sizeof *v);
    v->cfg = desc->config;
    v->node = desc->node;
    v->output = desc->output;
    v->threads = desc->threads;
    v->show_blend = desc->show_blend;
    frame_params_default(&v->first);
    if (gi_set_config(v->cfg, &v->first, err, errlen) != 0)
        goto fail;
    const char *scene_path = desc->scene ? desc->scene : v->cfg->scene[0] ? v->cfg->scene : "default";
    scene_load_desc sd;
    cluster_config_scene_desc(v->cfg, &sd); /* as the master and every node place it */
    if (scene_load_with(scene_path, &sd, &v->sc, err, errlen) != 0)
        goto fail;
    v->scene_loaded = 1;
    v->far_plane = scene_far_plane(&v->sc);
    v->limits = (gi_limits){.base = v->first, .memory_mb = v->cfg->gi_memory_mb};
    memcpy(v->limits.bounds_min, v->sc.bounds_min, sizeof v->limits.bounds_min);
    memcpy(v->limits.bounds_max, v->sc.bounds_max, sizeof v->limits.bounds_max);
    if (open_output(v, desc, err, errlen) != 0 || make_renderer(v, err, errlen) != 0)
        goto fail;
    if (warm_up(v, err, errlen) != 0)
        goto fail;
    return v;
fail:
    cluster_view_destroy(v);
    return NULL;
}

const scene *cluster_view_scene(const cluster_view *v) { return &v->sc; }

void cluster_view_set_pose(cluster_view *v, const scene_pose *pose) { renderer_set_pose(v->r, pose); }

void cluster_view_set_app(cluster_view *v, app_host *app)
{
    v->app = app;
    renderer_set_gbuffer_draw(v->r, app_host_draws(app) ? gbuffer_draw : NULL, v);
    char err[300];
    /* Its points' and lines' shaders compiled now, before the node joins (warm_up()). */
    if (app_host_draws(app) && !v->app_draw && !(v->app_draw = app_draw_create(glctx_gl(v->ctx), err, sizeof err)))
        fprintf(stderr, "cavelight-node %s: %s\n", v->cfg->nodes[v->node].name, err);
}

int cluster_view_app_draw(void *view, const cavelight_draw *d, int mode, const cavelight_vertex *vx, int count,
                          float size)
{
    cluster_view *v = view;
    char err[300];
    if (!v->app_draw && !(v->app_draw = app_draw_create(glctx_gl(v->ctx), err, sizeof err))) {
        fprintf(stderr, "cavelight-node %s: %s\n", v->cfg->nodes[v->node].name, err);
        return -1;
    }
    app_draw_geometry(v->app_draw, d, mode, vx, count, size);
    return 0;
}

void *cluster_view_gl_proc(void *view, const char *name)
{
    return (void *)glctx_proc(((cluster_view *)view)->ctx, name);
}

void cluster_view_destroy(cluster_view *v)
{
    if (!v)
        return;
    app_draw_destroy(v->app_draw);
    if (v->r)
        renderer_destroy(v->r);
    present_destroy(v->out);
    if (v->scene_loaded)
        scene_free(&v->sc);
    free(v);
}

/* A pose the view had to correct, rate-limited (ratelog.h): it never ends the session. */
static void report_eye(cluster_view *v, uint64_t version, int screen, int eye, int placed, float distance)
{
    uint64_t skipped;
    if (!ratelog_event(&v->eye_log, clock_now_ms(), &skipped))
        return;
    const char *node = v->cfg->nodes[v->node].name, *name = v->cfg->screens[screen].name;
    if (placed > 0)
        fprintf(stderr, "cavelight-node %s: frame %llu: the %s eye is %.3f m %s the plane of screen %s: "
                "rendered from %g m in front (%llu corrected views so far, %llu not logged)\n", node,
                (unsigned long long)version, cluster_view_eye_name(v->cfg, v->node, eye), fabsf(distance),
                distance < 0 ? "behind" : "in front of", name, FRAME_VIEW_NEAR_PLANE,
                (unsigned long long)v->eye_log.count, (unsigned long long)skipped);
    else
        fprintf(stderr, "cavelight-node %s: frame %llu: no projection for screen %s (degenerate "
                "navigation or pose): keeping its last image (%llu so far, %llu not logged)\n", node,
                (unsigned long long)version, name, (unsigned long long)v->eye_log.count,
                (unsigned long long)skipped);
}

/* A method or setting the renderer could not build (memory) keeps the current one: the
 * checksums then tell the master if the nodes disagree. Said once per refusal. */
static void report_refusal(cluster_view *v)
{
    const char *why = renderer_last_error(v->r);
    if (why[0] && strcmp(why, v->refusal) != 0)
        fprintf(stderr, "cavelight-node %s: %s\n", v->cfg->nodes[v->node].name, why);
    snprintf(v->refusal, sizeof v->refusal, "%s", why);
}

int cluster_view_render(cluster_view *v, const frame_params *f, uint64_t *checksum,
                        float timings[WIRE_TIMING_COUNT], int *fixed, char *err, size_t errlen)
{
    *checksum = renderer_frame_pass(v->r, f);
    report_refusal(v);
    renderer_timings t;
    renderer_get_timings(v->r, &t);
    *fixed = t.fixed;
    timings[WIRE_TIMING_FRAME] = (float)t.frame_host_ms;
    double eyes = 0;
    const cluster_node *n = &v->cfg->nodes[v->node];
    int eye_count = cluster_view_eye_count(v->cfg, v->node);
    for (int s = 0; s < n->screen_count; s++)
        for (int e = 0; e < eye_count; e++) {
            int vp = s * eye_count + e, w = n->screens[s].width, h = n->screens[s].height;
            uint8_t *rgb = present_source(v->out, vp);
            renderer_view view;
            float distance = 0;
            int placed = cluster_view_compute(v->cfg, n->screens[s].screen, eye_side(v->cfg, v->node, e), f,
                                              w, h, v->far_plane, &view, &distance);
            if (placed >= 0) { /* a 3d projector warp projects its surface points through this eye */
                float cave_to_clip[16];
                mat4_mul(view.projection, view.view, cave_to_clip);
                mat4_mul(cave_to_clip, f->navigation, cave_to_clip);
                present_set_view(v->out, vp, cave_to_clip);
            }
            if (f->pattern) { /* on the screen's surface: the same for both eyes */
                const cluster_screen *sc = &v->cfg->screens[n->screens[s].screen];
                pattern_desc pd = {.bottom_left = sc->bottom_left, .bottom_right = sc->bottom_right,
                                   .top_left = sc->top_left, .name = sc->name, .head = f->head,
                                   .wand = f->wand};
                pattern_draw(&pd, w, h, rgb);
                continue;
            }
            if (placed != 0)
                report_eye(v, f->version, n->screens[s].screen, e, placed, distance);
            if (placed < 0)
                continue; /* no projection at all: the screen keeps its last image */
            v->screen = n->screens[s].screen;
            v->side = eye_side(v->cfg, v->node, e);
            renderer_image out;
            if (renderer_eye_pass(v->r, &view, 0, &out) != 0) {
                snprintf(err, errlen, "cluster node %s: eye pass failed", n->name);
                return -1;
            }
            memcpy(rgb, out.rgb, (size_t)w * h * 3);
            renderer_timings te;
            renderer_get_timings(v->r, &te);
            eyes += te.eye_host_ms;
        }
    timings[WIRE_TIMING_EYES] = (float)eyes;
    v->rendered = 1;
    v->version = f->version;
    v->display_gamma = f->display_gamma;
    v->pattern = f->pattern;
    return 0;
}

int cluster_view_present(cluster_view *v, char *err, size_t errlen)
{
    if (!v->rendered)
        return 0;
    present_frame_desc fd = {.version = v->version, .display_gamma = v->display_gamma,
                             .show_blend = v->show_blend && v->pattern};
    return present_frame(v->out, &fd, err, errlen);
}

const uint8_t *cluster_view_image(const cluster_view *v, int screen, int eye, int *width, int *height)
{
    const cluster_node_screen *ns = &v->cfg->nodes[v->node].screens[screen];
    *width = ns->width;
    *height = ns->height;
    return present_source(v->out, screen * cluster_view_eye_count(v->cfg, v->node) + eye);
}
