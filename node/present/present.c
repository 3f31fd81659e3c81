/* present: see present.h. */
#include "present.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/folder.h"
#include "base/xalloc.h"
#include "frame/frame_params.h"
#include "gl/gltools.h"
#include "image/image.h"
#include "present_warp.h"
#include "present_window.h"

typedef struct viewport {
    char name[CLUSTER_TEXT_MAX];
    int src_w, src_h, out_w, out_h, eye;
    int pos[2];          /* in its eye's image, pixels from the top-left */
    uint8_t *source;
    float view[16];
} viewport;

/* One GL context and what it shows: a window (one eye, or all), or the headless context. */
typedef struct target {
    present_window win;  /* window output: its handle is set */
    glctx *ctx;
    int eye;             /* the eye it shows; -1: every eye */
    warp_shader shader;
    warp_pass pass[PRESENT_MAX_VIEWPORTS]; /* by viewport; only those it shows are made */
} target;

struct present {
    present_output output;
    char log_name[64], out_dir[1024];
    int keep_frames, quiet;
    int count;
    viewport vp[PRESENT_MAX_VIEWPORTS];
    int eyes, eye_w, eye_h;   /* an eye's image: every viewport at its place */
    cluster_stereo stereo;    /* in effect (quad may have fallen back) */
    int comp_w, comp_h;       /* a window's composition of the eyes */
    target t[2];
    int targets;
    GLuint fbo, color;        /* PNG output: one projector image at a time */
    uint8_t *rgba, *rgb;
};

static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

static int shows(const target *t, const viewport *v)
{
    return t->eye < 0 || t->eye == v->eye;
}

/* Viewports side by side per eye in their order, or where their MPCDI region sits. */
static void layout(present *p, const present_desc *d)
{
    int x[2] = {0, 0};
    for (int i = 0; i < p->count; i++) {
        const present_viewport *in = &d->viewports[i];
        const warp_map *m = in->warp;
        viewport *v = &p->vp[i];
        snprintf(v->name, sizeof v->name, "%s", in->name ? in->name : "");
        v->src_w = in->width;
        v->src_h = in->height;
        v->eye = in->eye ? 1 : 0;
        v->out_w = m && m->out_w > 0 ? m->out_w : in->width;
        v->out_h = m && m->out_h > 0 ? m->out_h : in->height;
        if (m && m->place[0] >= 0) {
            v->pos[0] = m->place[0];
            v->pos[1] = m->place[1];
        } else {
            v->pos[0] = x[v->eye];
            x[v->eye] += v->out_w;
        }
        p->eye_w = v->pos[0] + v->out_w > p->eye_w ? v->pos[0] + v->out_w : p->eye_w;
        p->eye_h = v->pos[1] + v->out_h > p->eye_h ? v->pos[1] + v->out_h : p->eye_h;
        p->eyes = v->eye + 1 > p->eyes ? v->eye + 1 : p->eyes;
        v->source = xcalloc((size_t)v->src_w * v->src_h, 3);
        memcpy(v->view, identity, sizeof v->view);
    }
}

static void composition(present *p)
{
    int two = p->eyes == 2;
    p->comp_w = p->eye_w * (two && p->stereo == CLUSTER_STEREO_SIDE_BY_SIDE ? 2 : 1);
    p->comp_h = p->eye_h * (two && p->stereo == CLUSTER_STEREO_TOP_BOTTOM ? 2 : 1);
}

/* The windows: one, or one per eye; a quad window the driver refuses becomes side-by-side. */
static int open_windows(present *p, const present_desc *d, char *err, size_t errlen)
{
    cluster_window defaults;
    cluster_window_default(&defaults);
    const cluster_window *cw = d->window ? d->window : &defaults;
    const char *env = getenv("DISPLAY");
    if (d->display && *d->display && (!env || !*env) && !getenv("WAYLAND_DISPLAY")) {
        setenv("DISPLAY", d->display, 1);
        fprintf(stderr, "%s: DISPLAY is not set: using %s (the node's \"display\" in the config)\n", p->log_name,
                d->display);
    }
    p->targets = p->eyes == 2 && p->stereo == CLUSTER_STEREO_WINDOW_PER_EYE ? 2 : 1;
    for (int e = 0; e < p->targets; e++) {
        char title[160];
        snprintf(title, sizeof title, "%s%s", d->title ? d->title : "cavelight", p->targets == 2 ? (e ? " right" : " left") : "");
        int width = cw->size[0] ? cw->size[0] : p->comp_w, height = cw->size[1] ? cw->size[1] : p->comp_h;
        int quad = p->eyes == 2 && p->stereo == CLUSTER_STEREO_QUAD;
        present_window_desc wd = {
            .title = title, .width = width, .height = height, .want_quad = quad,
            .width_without_quad = quad && !cw->size[0] ? 2 * p->comp_w : 0, .monitor_name = cw->monitor_name[e],
            .monitor = cw->monitor[e], .fullscreen = cw->fullscreen, .have_position = cw->have_position,
            .position = {cw->position[0] + e * width, cw->position[1]}, /* the right eye's beside the left's */
            .swap_interval = cw->swap_interval, .swap_group = cw->swap_group, .swap_barrier = cw->swap_barrier,
            .log_name = p->log_name, .quiet = p->quiet};
        target *t = &p->t[e];
        t->eye = p->targets == 2 ? e : -1;
        if (present_window_open(&t->win, &wd, err, errlen) != 0)
            return -1;
        t->ctx = t->win.ctx;
        if (wd.want_quad && !t->win.quad) {
            fprintf(stderr, "%s: the driver offers no quad-buffered window: showing side-by-side\n", p->log_name);
            p->stereo = CLUSTER_STEREO_SIDE_BY_SIDE; /* the window was made that wide */
            composition(p);
        }
        present_window_report(&t->win, &wd);
    }
    return 0;
}

static int open_headless(present *p, const present_desc *d, char *err, size_t errlen)
{
    glctx_desc gd = {.backend = d->backend};
    p->t[0].ctx = glctx_create(&gd, err, errlen);
    if (!p->t[0].ctx && d->fallback && d->backend == GLCTX_EGL) {
        gd.backend = GLCTX_OSMESA; /* no EGL: the software fallback */
        p->t[0].ctx = glctx_create(&gd, err, errlen);
    }
    p->t[0].eye = -1;
    p->targets = 1;
    return p->t[0].ctx ? 0 : -1;
}

/* PNG output: a framebuffer for the largest projector image, and its readback. */
static int png_target(present *p, const gl_functions *gl, char *err, size_t errlen)
{
    int w = 1, h = 1;
    for (int i = 0; i < p->count; i++) {
        w = p->vp[i].out_w > w ? p->vp[i].out_w : w;
        h = p->vp[i].out_h > h ? p->vp[i].out_h : h;
    }
    p->color = gltools_texture2d(gl, GL_RGBA8, w, h, GL_NEAREST);
    gl->GenFramebuffers(1, &p->fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, p->fbo);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, p->color, 0);
    int rc = gltools_fbo_complete(gl, "presentation", err, errlen);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    p->rgba = xmalloc((size_t)w * h * 4);
    p->rgb = xmalloc((size_t)w * h * 3);
    return rc;
}

static int make_passes(present *p, const present_desc *d, char *err, size_t errlen)
{
    for (int k = p->targets - 1; k >= 0; k--) { /* the first window's context stays current */
        target *t = &p->t[k];
        if (t->win.handle)
            present_window_make_current(&t->win);
        if (warp_shader_init(&t->shader, glctx_gl(t->ctx), err, errlen) != 0)
            return -1;
        for (int i = 0; i < p->count; i++)
            if (shows(t, &p->vp[i]) &&
                warp_pass_init(&t->pass[i], &t->shader, d->viewports[i].warp, d->viewports[i].to_cave, p->vp[i].src_w,
                               p->vp[i].src_h, err, errlen) != 0)
                return -1;
    }
    return p->output == PRESENT_PNG ? png_target(p, glctx_gl(p->t[0].ctx), err, errlen) : 0;
}

present *present_create(const present_desc *d, char *err, size_t errlen)
{
    present *p = xcalloc(1, sizeof *p);
    p->output = d->output;
    p->count = d->viewport_count < PRESENT_MAX_VIEWPORTS ? d->viewport_count : PRESENT_MAX_VIEWPORTS;
    p->keep_frames = d->keep_frames;
    p->quiet = d->quiet;
    p->stereo = d->stereo;
    snprintf(p->log_name, sizeof p->log_name, "%s", d->log_name ? d->log_name : "cavelight-node");
    snprintf(p->out_dir, sizeof p->out_dir, "%s", d->out_dir ? d->out_dir : CLUSTER_DEFAULT_OUT);
    layout(p, d);
    composition(p);
    char why[300];
    int rc;
    if (d->output == PRESENT_PNG && folder_create(p->out_dir, why, sizeof why) != 0) {
        snprintf(err, errlen, "%s", why);
        rc = -1;
    } else {
        rc = d->output == PRESENT_WINDOW ? open_windows(p, d, err, errlen) : open_headless(p, d, err, errlen);
    }
    if (rc == 0 && d->output != PRESENT_HEADLESS)
        rc = make_passes(p, d, err, errlen);
    if (rc != 0) {
        present_destroy(p);
        return NULL;
    }
    return p;
}

void present_destroy(present *p)
{
    if (!p)
        return;
    for (int k = p->targets - 1; k >= 0; k--) {
        target *t = &p->t[k];
        if (!t->ctx)
            continue;
        if (t->win.handle)
            present_window_make_current(&t->win);
        for (int i = 0; i < p->count; i++)
            warp_pass_fini(&t->pass[i]);
        if (t->shader.gl)
            warp_shader_fini(&t->shader);
        if (k == 0 && p->fbo) {
            glctx_gl(t->ctx)->DeleteFramebuffers(1, &p->fbo);
            glctx_gl(t->ctx)->DeleteTextures(1, &p->color);
        }
        if (t->win.handle)
            present_window_close(&t->win);
        else
            glctx_destroy(t->ctx);
    }
    for (int i = 0; i < p->count; i++)
        free(p->vp[i].source);
    free(p->rgba);
    free(p->rgb);
    free(p);
}

glctx *present_context(present *p) { return p->t[0].ctx; }
uint8_t *present_source(present *p, int vp) { return p->vp[vp].source; }

void present_set_view(present *p, int vp, const float cave_to_clip[16])
{
    memcpy(p->vp[vp].view, cave_to_clip, sizeof p->vp[vp].view);
}

/* ---- one frame ------------------------------------------------------------------------ */

/* Write then rename: a reader never sees half a file. */
static int write_png_atomic(const present *p, const char *path, int w, int h, const uint8_t *rgb, char *err,
                            size_t errlen)
{
    char tmp[1424];
    snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid());
    if (image_write_png(tmp, w, h, rgb, err, errlen) != 0)
        return -1;
    if (rename(tmp, path) != 0) {
        snprintf(err, errlen, "%s: cannot rename %s to %s (%s)", p->log_name, tmp, path, strerror(errno));
        return -1;
    }
    return 0;
}

/* The viewport's rectangle in a framebuffer of fb_w x fb_h showing the composition. */
static void fb_rect(const present *p, const viewport *v, int fb_w, int fb_h, int out[4])
{
    int two = p->eyes == 2, ox = 0, oy = 0;
    if (two && p->stereo == CLUSTER_STEREO_SIDE_BY_SIDE)
        ox = v->eye * p->eye_w;
    if (two && p->stereo == CLUSTER_STEREO_TOP_BOTTOM)
        oy = v->eye * p->eye_h;
    double sx = (double)fb_w / p->comp_w, sy = (double)fb_h / p->comp_h;
    int x0 = (int)lround((ox + v->pos[0]) * sx), x1 = (int)lround((ox + v->pos[0] + v->out_w) * sx);
    int top = (int)lround((oy + v->pos[1]) * sy), bottom = (int)lround((oy + v->pos[1] + v->out_h) * sy);
    out[0] = x0;
    out[1] = fb_h - bottom;
    out[2] = x1 - x0;
    out[3] = bottom - top;
}

static void draw_viewport(target *t, int i, const viewport *v, const int rect[4], const present_frame_desc *f)
{
    warp_pass_upload(&t->pass[i], v->source);
    warp_draw wd = {.rect = {rect[0], rect[1], rect[2], rect[3]}, .cave_to_clip = v->view,
                    .display_gamma = f->display_gamma, .show_blend = f->show_blend};
    warp_pass_draw(&t->pass[i], &wd);
}

/* A window: both back buffers cleared, every viewport it shows at its place, by eye. */
static void draw_window(present *p, target *t, const present_frame_desc *f)
{
    present_window_make_current(&t->win);
    const gl_functions *gl = glctx_gl(t->ctx);
    int fw, fh;
    present_window_framebuffer(&t->win, &fw, &fh);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->Disable(GL_DEPTH_TEST);
    int quad = p->eyes == 2 && p->stereo == CLUSTER_STEREO_QUAD;
    int anaglyph = p->eyes == 2 && p->stereo == CLUSTER_STEREO_ANAGLYPH;
    const GLenum back[2] = {GL_BACK_LEFT, GL_BACK_RIGHT};
    const float black[4] = {0, 0, 0, 1};
    for (int b = 0; b <= quad; b++) {
        gl->DrawBuffers(1, &back[b]);
        gl->ClearBufferfv(GL_COLOR, 0, black);
    }
    for (int i = 0; i < p->count; i++) {
        const viewport *v = &p->vp[i];
        if (!shows(t, v))
            continue;
        if (quad)
            gl->DrawBuffers(1, &back[v->eye]);
        if (anaglyph) /* red from the left eye, green and blue from the right */
            gl->ColorMask(v->eye == 0, v->eye == 1, v->eye == 1, GL_TRUE);
        int rect[4];
        fb_rect(p, v, fw, fh, rect);
        draw_viewport(t, i, v, rect, f);
    }
    gl->ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->DrawBuffers(1, &back[0]);
}

/* PNG output: each projector image drawn alone, read back, written. */
static int write_pngs(present *p, const present_frame_desc *f, char *err, size_t errlen)
{
    target *t = &p->t[0];
    const gl_functions *gl = glctx_gl(t->ctx);
    gl->BindFramebuffer(GL_FRAMEBUFFER, p->fbo);
    gl->Disable(GL_DEPTH_TEST);
    const float black[4] = {0, 0, 0, 1};
    for (int i = 0; i < p->count; i++) {
        const viewport *v = &p->vp[i];
        int w = v->out_w, h = v->out_h, rect[4] = {0, 0, w, h};
        gl->ClearBufferfv(GL_COLOR, 0, black);
        draw_viewport(t, i, v, rect, f);
        gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
        gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl->ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, p->rgba);
        for (int y = 0; y < h; y++) /* GL's bottom row first, the file's top row first */
            for (int x = 0; x < w; x++)
                memcpy(p->rgb + ((size_t)y * w + x) * 3, p->rgba + ((size_t)(h - 1 - y) * w + x) * 4, 3);
        char path[1400];
        snprintf(path, sizeof path, "%s/%s.png", p->out_dir, v->name);
        if (write_png_atomic(p, path, w, h, p->rgb, err, errlen) != 0)
            return -1;
        snprintf(path, sizeof path, "%s/%s-%06llu.png", p->out_dir, v->name, (unsigned long long)f->version);
        if (p->keep_frames && write_png_atomic(p, path, w, h, p->rgb, err, errlen) != 0)
            return -1;
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    return 0;
}

int present_frame(present *p, const present_frame_desc *desc, char *err, size_t errlen)
{
    if (p->output == PRESENT_HEADLESS)
        return 0;
    present_frame_desc fd = *desc;
    if (!(fd.display_gamma > 0)) { /* 0: the frame's default */
        frame_params def;
        frame_params_default(&def);
        fd.display_gamma = def.display_gamma;
    }
    const present_frame_desc *f = &fd;
    if (p->output == PRESENT_PNG && write_pngs(p, f, err, errlen) != 0)
        return -1;
    int open = 1;
    for (int k = 0; k < p->targets && p->output == PRESENT_WINDOW; k++)
        draw_window(p, &p->t[k], f);
    for (int k = 0; k < p->targets; k++) {
        const gl_functions *gl = glctx_gl(p->t[k].ctx);
        GLenum e = gl->GetError();
        gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        if (e != GL_NO_ERROR) {
            snprintf(err, errlen, "%s: showing the frame failed (GL error 0x%x)", p->log_name, (unsigned)e);
            return -1;
        }
        if (p->output == PRESENT_WINDOW)
            open &= present_window_swap(&p->t[k].win);
    }
    if (p->t[0].win.handle)
        present_window_make_current(&p->t[0].win); /* the renderer's context */
    return open ? 0 : 1;
}
