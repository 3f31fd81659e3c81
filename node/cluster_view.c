#include "cluster_view.h"
#include "base/xalloc.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/folder.h"
#include "base/ratelog.h"
#include "frame/pattern.h"
#include "cluster_window.h"
#include "glctx.h"
#include "image/image.h"
#include "base/mat4.h"
#include "base/vec3.h"
#include "scene/scene.h"

typedef struct eye_image {
    int width, height;
    uint8_t *rgb;
} eye_image;

struct cluster_view {
    const cluster_config *cfg;
    int node;
    cluster_output output;
    char out_dir[1024];
    int lpv_threads, rsm_size, lattice_desc, lattice_now, lattice_refused, lpv_mode, gi;
    double converge_threshold;
    scene sc;
    int scene_loaded;
    glctx *ctx;          /* headless context, or the first window's */
    renderer *r;
    cluster_window *win[2];
    cluster_stereo stereo; /* effective window stereo mode */
    int strip_w, strip_h;  /* all of the node's screens side by side, one eye */
    int comp_w, comp_h;
    uint8_t *compose[2];
    float far_plane;
    eye_image img[CLUSTER_NODE_MAX_SCREENS][CLUSTER_VIEW_MAX_EYES];
    int rendered;
    int keep_frames;
    uint64_t version;    /* of the last rendered frame */
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
    mat4_transform_point(f->head, o->head_to_eye, mid);
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

/* Window output: one window (or one per eye) sized for the node's screens in its stereo mode. */
static int open_windows(cluster_view *v, char *err, size_t errlen)
{
    const cluster_node *n = &v->cfg->nodes[v->node];
    for (int s = 0; s < n->screen_count; s++) {
        v->strip_w += n->screens[s].width;
        if (n->screens[s].height > v->strip_h)
            v->strip_h = n->screens[s].height;
    }
    int stereo = cluster_view_eye_count(v->cfg, v->node) == 2;
    v->stereo = n->stereo;
    v->comp_w = v->strip_w * (stereo && v->stereo == CLUSTER_STEREO_SIDE_BY_SIDE ? 2 : 1);
    v->comp_h = v->strip_h * (stereo && v->stereo == CLUSTER_STEREO_TOP_BOTTOM ? 2 : 1);
    char title[96];
    snprintf(title, sizeof title, "cavelight %s%s", n->name, stereo && v->stereo == CLUSTER_STEREO_WINDOW_PER_EYE ? " left" : "");
    cluster_window_desc wd = {.width = v->comp_w, .height = v->comp_h, .title = title, .monitor = n->monitor,
                              .fullscreen = n->fullscreen, .want_quad = stereo && v->stereo == CLUSTER_STEREO_QUAD};
    if (!(v->win[0] = cluster_window_create(&wd, err, errlen)))
        return -1;
    if (wd.want_quad && !cluster_window_quad(v->win[0])) {
        fprintf(stderr, "cavelight-node %s: the driver offers no quad-buffered window: showing side-by-side\n",
                n->name);
        v->stereo = CLUSTER_STEREO_SIDE_BY_SIDE;
        v->comp_w = 2 * v->strip_w;
    }
    if (stereo && v->stereo == CLUSTER_STEREO_WINDOW_PER_EYE) {
        snprintf(title, sizeof title, "cavelight %s right", n->name);
        wd.monitor = n->monitor + 1; /* the right eye's projector, when fullscreen */
        if (!(v->win[1] = cluster_window_create(&wd, err, errlen)))
            return -1;
        cluster_window_make_current(v->win[0]);
    }
    v->ctx = cluster_window_context(v->win[0]);
    for (int e = 0; e < 2; e++)
        if (!(v->compose[e] = calloc((size_t)v->comp_w * v->comp_h, 3))) {
            snprintf(err, errlen, "cluster node %s: out of memory for the window image", n->name);
            return -1;
        }
    return 0;
}

/* Copies one eye's images of all the node's screens, side by side, into dst at (x0, y0). */
static void compose_strip(const cluster_view *v, int eye, uint8_t *dst, int dst_w, int x0, int y0)
{
    const cluster_node *n = &v->cfg->nodes[v->node];
    for (int s = 0, x = x0; s < n->screen_count; x += v->img[s][eye].width, s++) {
        const eye_image *im = &v->img[s][eye];
        for (int y = 0; y < im->height; y++)
            memcpy(dst + ((size_t)(y0 + y) * dst_w + x) * 3, im->rgb + (size_t)y * im->width * 3, (size_t)im->width * 3);
    }
}

static int present_window(cluster_view *v, char *err, size_t errlen)
{
    int stereo = cluster_view_eye_count(v->cfg, v->node) == 2;
    uint8_t *a = v->compose[0], *b = v->compose[1];
    const uint8_t *right = NULL;
    cluster_window *second = NULL;
    compose_strip(v, 0, a, v->comp_w, 0, 0);
    if (stereo) {
        switch (v->stereo) {
        case CLUSTER_STEREO_SIDE_BY_SIDE: compose_strip(v, 1, a, v->comp_w, v->strip_w, 0); break;
        case CLUSTER_STEREO_TOP_BOTTOM: compose_strip(v, 1, a, v->comp_w, 0, v->strip_h); break;
        case CLUSTER_STEREO_ANAGLYPH:
            /* Red-cyan: red from the left eye, green and blue from the right. */
            compose_strip(v, 1, b, v->comp_w, 0, 0);
            for (size_t i = 0; i < (size_t)v->comp_w * v->comp_h; i++) {
                a[3 * i + 1] = b[3 * i + 1];
                a[3 * i + 2] = b[3 * i + 2];
            }
            break;
        case CLUSTER_STEREO_QUAD:
            compose_strip(v, 1, b, v->comp_w, 0, 0);
            right = b;
            break;
        case CLUSTER_STEREO_WINDOW_PER_EYE:
            compose_strip(v, 1, b, v->comp_w, 0, 0);
            second = v->win[1];
            break;
        }
    }
    int open = cluster_window_show(v->win[0], a, right, v->comp_w, v->comp_h);
    if (open > 0 && second) {
        open = cluster_window_show(second, b, NULL, v->comp_w, v->comp_h);
        cluster_window_make_current(v->win[0]);
    }
    if (open < 0) {
        snprintf(err, errlen, "cluster node %s: showing the frame failed (GL error)", v->cfg->nodes[v->node].name);
        return -1;
    }
    return open ? 0 : 1;
}

static int make_renderer(cluster_view *v, int lattice, char *err, size_t errlen)
{
    renderer_desc rd = {.gl = glctx_gl(v->ctx), .scene = &v->sc, .lpv_backend = RENDERER_LPV_AUTO,
                        .rsm_size = v->rsm_size, .lattice_cells = lattice, .threads = v->lpv_threads,
                        .lpv_mode = (renderer_lpv_mode)v->lpv_mode, .gi = (frame_gi)v->gi,
                        .converge_threshold = v->converge_threshold};
    renderer *r = renderer_create(&rd, err, errlen);
    if (!r)
        return -1;
    if (v->r)
        renderer_destroy(v->r);
    v->r = r;
    v->lattice_now = lattice;
    return 0;
}

/* One untracked frame before the node says HELLO: llvmpipe compiles shaders at first use
 * (0.1 to 0.4 s for a 32x64 stereo node under load here), which would hold every screen
 * at the barrier in the node's first frame after a (re)join, or get it dropped. The
 * renderer is then built afresh, so the node starts from the same state as any other;
 * Mesa keeps the compiled code (that first frame: about 50 ms instead of 100 to 240,
 * tests/integration/cluster_lib.sh's 2-node config, ready_after_frame_ms max). */
static int warm_up(cluster_view *v, char *err, size_t errlen)
{
    frame_params f;
    frame_params_default(&f);
    frame_params_lights_from_scene(&f, &v->sc);
    memcpy(&f.head[12], v->cfg->observer.home, sizeof v->cfg->observer.home);
    uint64_t checksum;
    float timings[WIRE_TIMING_COUNT];
    if (cluster_view_render(v, &f, 0, &checksum, timings, err, errlen) != 0)
        return -1;
    return make_renderer(v, v->lattice_desc, err, errlen);
}

cluster_view *cluster_view_create(const cluster_view_desc *desc, char *err, size_t errlen)
{
    cluster_view *v = xcalloc(1, sizeof *v);
    v->cfg = desc->config;
    v->node = desc->node;
    v->output = desc->output;
    v->lpv_threads = desc->lpv_threads;
    v->rsm_size = desc->rsm_size;
    v->lpv_mode = desc->lpv_mode;
    v->gi = desc->gi;
    v->converge_threshold = desc->converge_threshold;
    v->lattice_desc = desc->lattice_cells;
    v->keep_frames = desc->keep_frames;
    snprintf(v->out_dir, sizeof v->out_dir, "%s", desc->out_dir ? desc->out_dir : CLUSTER_DEFAULT_OUT);
    const cluster_node *n = &v->cfg->nodes[v->node];
    char why[300];
    if (v->output == CLUSTER_OUTPUT_PNG && folder_create(v->out_dir, why, sizeof why) != 0) {
        snprintf(err, errlen, "cluster node %s: %s", n->name, why);
        goto fail;
    }
    const char *scene_path = desc->scene ? desc->scene : v->cfg->scene[0] ? v->cfg->scene : "default";
    scene_load_desc sd;
    cluster_config_scene_desc(v->cfg, &sd); /* as the master and every node place it */
    if (scene_load_with(scene_path, &sd, &v->sc, err, errlen) != 0)
        goto fail;
    v->scene_loaded = 1;
    v->far_plane = scene_far_plane(&v->sc);
    if (v->output == CLUSTER_OUTPUT_WINDOW) {
        /* Started over ssh or as a service, a node has no DISPLAY: the config names the
         * display its projectors hang on. */
        const char *display = getenv("DISPLAY");
        if ((!display || !*display) && !getenv("WAYLAND_DISPLAY")) {
            setenv("DISPLAY", n->display, 1);
            fprintf(stderr, "cavelight-node %s: DISPLAY is not set: using %s (the node's \"display\" in "
                    "the config)\n", n->name, n->display);
        }
        if (open_windows(v, err, errlen) != 0) {
            size_t used = strlen(err);
            snprintf(err + used, errlen - used, "; or render without a window: --output headless or "
                     "png (or the node's \"output\" in the config)");
            goto fail;
        }
    } else {
        glctx_desc gd = {.backend = GLCTX_EGL};
        v->ctx = glctx_create(&gd, err, errlen);
        if (!v->ctx) {
            gd.backend = GLCTX_OSMESA; /* no EGL: software fallback */
            v->ctx = glctx_create(&gd, err, errlen);
        }
    }
    if (!v->ctx || make_renderer(v, v->lattice_desc, err, errlen) != 0)
        goto fail;
    for (int s = 0; s < n->screen_count; s++)
        for (int e = 0; e < cluster_view_eye_count(v->cfg, v->node); e++) {
            eye_image *im = &v->img[s][e];
            im->width = n->screens[s].width;
            im->height = n->screens[s].height;
            im->rgb = calloc((size_t)im->width * im->height, 3);
            if (!im->rgb) {
                snprintf(err, errlen, "cluster node %s: out of memory for images", n->name);
                goto fail;
            }
        }
    if (warm_up(v, err, errlen) != 0)
        goto fail;
    return v;
fail:
    cluster_view_destroy(v);
    return NULL;
}

void cluster_view_destroy(cluster_view *v)
{
    if (!v)
        return;
    if (v->win[0])
        cluster_window_make_current(v->win[0]);
    if (v->r)
        renderer_destroy(v->r);
    if (v->win[0]) {
        /* The windows own the GL contexts; the second goes first (GLFW shuts down with it). */
        cluster_window_destroy(v->win[1]);
        cluster_window_destroy(v->win[0]);
    } else if (v->ctx) {
        glctx_destroy(v->ctx);
    }
    free(v->compose[0]);
    free(v->compose[1]);
    if (v->scene_loaded)
        scene_free(&v->sc);
    for (int s = 0; s < CLUSTER_NODE_MAX_SCREENS; s++)
        for (int e = 0; e < CLUSTER_VIEW_MAX_EYES; e++)
            free(v->img[s][e].rgb);
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

int cluster_view_render(cluster_view *v, const frame_params *f, int lattice_cells, uint64_t *checksum,
                        float timings[WIRE_TIMING_COUNT], char *err, size_t errlen)
{
    int want = lattice_cells > 0 ? lattice_cells : v->lattice_desc;
    if (want != v->lattice_now && want != v->lattice_refused) {
        /* A lattice the node cannot build (memory) keeps the current one: the checksums
         * then tell the master if the nodes disagree. */
        char why[256];
        if (make_renderer(v, want, why, sizeof why) != 0) {
            fprintf(stderr, "cavelight-node %s: lattice %d refused (%s): keeping %d\n",
                    v->cfg->nodes[v->node].name, want, why, v->lattice_now);
            v->lattice_refused = want;
        }
    }
    *checksum = renderer_frame_pass(v->r, f);
    renderer_timings t;
    renderer_get_timings(v->r, &t);
    timings[WIRE_TIMING_FRAME] = (float)t.frame_host_ms;
    double eyes = 0;
    const cluster_node *n = &v->cfg->nodes[v->node];
    for (int s = 0; s < n->screen_count; s++)
        for (int e = 0; e < cluster_view_eye_count(v->cfg, v->node); e++) {
            eye_image *im = &v->img[s][e];
            if (f->pattern) { /* on the screen's surface: the same for both eyes */
                const cluster_screen *sc = &v->cfg->screens[n->screens[s].screen];
                pattern_desc pd = {.bottom_left = sc->bottom_left, .bottom_right = sc->bottom_right,
                                   .top_left = sc->top_left, .name = sc->name, .head = f->head,
                                   .wand = f->wand};
                pattern_draw(&pd, im->width, im->height, im->rgb);
                continue;
            }
            renderer_view view;
            float distance = 0;
            int placed = cluster_view_compute(v->cfg, n->screens[s].screen, eye_side(v->cfg, v->node, e), f,
                                              im->width, im->height, v->far_plane, &view, &distance);
            if (placed != 0)
                report_eye(v, f->version, n->screens[s].screen, e, placed, distance);
            if (placed < 0)
                continue; /* no projection at all: the screen keeps its last image */
            renderer_image out;
            if (renderer_eye_pass(v->r, &view, 0, &out) != 0) {
                snprintf(err, errlen, "cluster node %s: eye pass failed", n->name);
                return -1;
            }
            memcpy(im->rgb, out.rgb, (size_t)im->width * im->height * 3);
            renderer_timings te;
            renderer_get_timings(v->r, &te);
            eyes += te.eye_host_ms;
        }
    timings[WIRE_TIMING_EYES] = (float)eyes;
    v->rendered = 1;
    v->version = f->version;
    return 0;
}

/* Write then rename: a reader never sees half a file. */
static int write_png_atomic(const char *node, const char *path, const eye_image *im, char *err,
                            size_t errlen)
{
    char tmp[1300];
    snprintf(tmp, sizeof tmp, "%s.%s.tmp", path, node);
    if (image_write_png(tmp, im->width, im->height, im->rgb, err, errlen) != 0)
        return -1;
    if (rename(tmp, path) != 0) {
        snprintf(err, errlen, "cluster node %s: cannot rename %s to %s (%s)", node, tmp, path,
                 strerror(errno));
        return -1;
    }
    return 0;
}

int cluster_view_present(cluster_view *v, char *err, size_t errlen)
{
    if (!v->rendered || v->output == CLUSTER_OUTPUT_HEADLESS)
        return 0;
    if (v->output == CLUSTER_OUTPUT_WINDOW)
        return present_window(v, err, errlen);
    const cluster_node *n = &v->cfg->nodes[v->node];
    for (int s = 0; s < n->screen_count; s++)
        for (int e = 0; e < cluster_view_eye_count(v->cfg, v->node); e++) {
            char base[1100], path[1200];
            const char *screen = v->cfg->screens[n->screens[s].screen].name;
            snprintf(base, sizeof base, "%s/%s-%s", v->out_dir, screen, cluster_view_eye_name(v->cfg, v->node, e));
            snprintf(path, sizeof path, "%s.png", base);
            const eye_image *im = &v->img[s][e];
            if (write_png_atomic(n->name, path, im, err, errlen) != 0)
                return -1;
            snprintf(path, sizeof path, "%s-%06llu.png", base, (unsigned long long)v->version);
            if (v->keep_frames && write_png_atomic(n->name, path, im, err, errlen) != 0)
                return -1;
        }
    return 0;
}

const uint8_t *cluster_view_image(const cluster_view *v, int screen, int eye, int *width, int *height)
{
    const eye_image *im = &v->img[screen][eye];
    *width = im->width;
    *height = im->height;
    return im->rgb;
}
