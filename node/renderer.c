/* renderer: GL passes of the render node (RSM, G-buffer, shading, final) and the frame /
 * eye pass orchestration. The indirect light is the active GI method's (gi.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/xalloc.h"
#include "base/mat4.h"
#include "base/ratelog.h"
#include "frame/light_view.h"
#include "gi/gi.h"
#include "gi/gi_settings.h"
#include "gl/gltools.h"
#include "gl/gpu_checksum.h"
#include "gl/gpu_timer.h"
#include "renderer.h"
#include "renderer_aa.h"
#include "renderer_ao.h"
#include "renderer_hud.h"
#include "renderer_rsm.h"
#include "gl/scene_gl.h"

enum { RENDERER_DARK_VIEWS = 16 };

struct renderer {
    const gl_functions *gl;
    const scene *scene;
    scene_gl *mesh;          /* the scene's triangles and textures */
    GLuint empty_vao;        /* the full-screen passes' */
    int emits;               /* some surface of the scene emits light */

    GLuint prog_gbuffer, prog_final;

    renderer_rsm *rsm;       /* the lights' shadow maps and the VPL source */
    int rsm_size;            /* its size */

    int eye_w, eye_h;
    GLuint gbuffer_fbo, g_position, g_normal, g_albedo, g_emissive, g_depth;
    GLuint shade_fbo, s_final, s_direct, s_indirect;
    GLuint final_fbo, f_color;
    uint8_t *rgba, *rgb;
    float *linear[3];

    gi *gi;                  /* the indirect-light method (gi.h), with its shading program */
    renderer_ao *ao;         /* the ambient term's occlusion (renderer_ao.h) */
    renderer_aa *aa;         /* the final image's anti-aliasing (renderer_aa.h) */
    uint64_t checksum;       /* its last frame's: READY's */
    uint64_t host_checksum;  /* the method's host part of the last frame it computed */
    renderer_desc desc;
    int software;            /* a software GL (llvmpipe) */
    frame_params refused;    /* the last frame whose method or RSM could not be built */
    int have_refused;
    gi_limits limits;        /* desc.limits' copy, when limited */
    int limited;
    frame_params within;     /* the last frame within the limits */
    renderer_hud *hud;
    frame_params frame;      /* the last frame pass's parameters, sanitized: what the eye
                                passes render */
    /* Views that show no light: a query over the final pass, whose shader leaves black
     * pixels out; one warning when the k-th view of a frame turns black. */
    GLuint lit_query;
    GLuint seen_query;       /* over the G-buffer pass: any surface in view */
    int eye_index;           /* eye passes since the frame pass */
    int view_dark[RENDERER_DARK_VIEWS];
    ratelog dark_log;
    gpu_timer *timer;        /* GPU time per stage, read back late (gpu_timer.h) */
    gpu_checksum *sum;       /* the method's GPU results hashed, one frame late */
    scene_pose pose;         /* where the passes draw the scene's objects */
    scene_pose gi_pose;      /* where the GI method last saw them (rest: as built) */
    float (*models)[16];     /* the pose's model matrices and shown flags */
    uint8_t *shown;
    renderer_timings timings;
    char error[320];         /* why the last eye pass failed, or the last refusal */
};


static GLint loc(renderer *r, GLuint prog, const char *name)
{
    return r->gl->GetUniformLocation(prog, name);
}

static const GLenum draw_buffers[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                                       GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};

static void free_eye_targets(renderer *r)
{
    const gl_functions *gl = r->gl;
    GLuint tex[] = {r->g_position, r->g_normal, r->g_albedo, r->g_emissive, r->g_depth,
                    r->s_final, r->s_direct, r->s_indirect, r->f_color};
    for (size_t i = 0; i < sizeof tex / sizeof tex[0]; i++)
        if (tex[i])
            gl->DeleteTextures(1, &tex[i]);
    GLuint fbo[] = {r->gbuffer_fbo, r->shade_fbo, r->final_fbo};
    for (size_t i = 0; i < 3; i++)
        if (fbo[i])
            gl->DeleteFramebuffers(1, &fbo[i]);
    free(r->rgba);
    free(r->rgb);
    for (int i = 0; i < 3; i++)
        free(r->linear[i]);
    r->rgba = r->rgb = NULL;
    memset(r->linear, 0, sizeof r->linear);
    r->eye_w = r->eye_h = 0;
}

static int eye_targets(renderer *r, int w, int h)
{
    if (w == r->eye_w && h == r->eye_h)
        return 0;
    const gl_functions *gl = r->gl;
    free_eye_targets(r);
    char err[160] = "out of memory for the eye targets";
    r->g_position = gltools_texture2d(r->gl, GL_RGBA32F, w, h, GL_NEAREST);
    r->g_normal = gltools_texture2d(r->gl, GL_RGBA16F, w, h, GL_NEAREST);
    r->g_albedo = gltools_texture2d(r->gl, GL_RGBA8, w, h, GL_NEAREST);
    r->g_emissive = gltools_texture2d(r->gl, GL_RGBA16F, w, h, GL_NEAREST);
    r->g_depth = gltools_texture2d(r->gl, GL_DEPTH_COMPONENT32F, w, h, GL_NEAREST);
    gl->GenFramebuffers(1, &r->gbuffer_fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->gbuffer_fbo);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, r->g_position, 0);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, r->g_normal, 0);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, r->g_albedo, 0);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT3, r->g_emissive, 0);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, r->g_depth, 0);
    gl->DrawBuffers(4, draw_buffers);
    int bad = gltools_fbo_complete(r->gl, "G-buffer", err, sizeof err);

    r->s_final = gltools_texture2d(r->gl, GL_RGBA32F, w, h, GL_NEAREST);
    r->s_direct = gltools_texture2d(r->gl, GL_RGBA32F, w, h, GL_NEAREST);
    r->s_indirect = gltools_texture2d(r->gl, GL_RGBA32F, w, h, GL_NEAREST);
    gl->GenFramebuffers(1, &r->shade_fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->shade_fbo);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, r->s_final, 0);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, r->s_direct, 0);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, r->s_indirect, 0);
    gl->DrawBuffers(3, draw_buffers);
    bad |= gltools_fbo_complete(r->gl, "shading", err, sizeof err);

    r->f_color = gltools_texture2d(r->gl, GL_RGBA8, w, h, GL_NEAREST);
    gl->GenFramebuffers(1, &r->final_fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->final_fbo);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, r->f_color, 0);
    /* The scene's depth, so the HUD drawn into the final image is occluded by it. */
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, r->g_depth, 0);
    gl->DrawBuffers(1, draw_buffers);
    bad |= gltools_fbo_complete(r->gl, "final", err, sizeof err);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);

    /* not xalloc: the image size (a setting): refused in r->error */
    r->rgba = malloc((size_t)w * h * 4);
    r->rgb = malloc((size_t)w * h * 3);
    for (int i = 0; i < 3; i++)
        r->linear[i] = malloc((size_t)w * h * 3 * sizeof(float));
    if (bad || !r->rgba || !r->rgb || !r->linear[0] || !r->linear[1] || !r->linear[2]) {
        snprintf(r->error, sizeof r->error, "renderer: %s (%dx%d)", err, w, h);
        free_eye_targets(r);
        return -1;
    }
    r->eye_w = w;
    r->eye_h = h;
    return 0;
}

/* ---- create / destroy ------------------------------------------------------------- */

/* The shadow maps and the GI method for frame p (sanitized); -1 with one line in err and
 * nothing changed. */
static int build_frame_state(renderer *r, const frame_params *p, char *err, size_t errlen)
{
    renderer_rsm *maps = NULL;
    if (p->rsm_size != r->rsm_size &&
        !(maps = renderer_rsm_create(r->gl, r->scene, p->rsm_size, err, errlen)))
        return -1;
    gi_desc gd = {.gl = r->gl, .scene = r->scene, .frame = p, .rsm_size = p->rsm_size,
                  .threads = r->desc.threads, .software = r->software,
                  .no_reuse = r->desc.no_reuse, .timer = r->timer, .sum = r->sum};
    memcpy(gd.head_to_eye, r->desc.head_to_eye, sizeof gd.head_to_eye);
    gi *g = gi_create(&gd, err, errlen);
    if (!g) {
        renderer_rsm_destroy(maps);
        return -1;
    }
    if (maps) {
        renderer_rsm_destroy(r->rsm);
        r->rsm = maps;
        r->rsm_size = p->rsm_size;
    }
    gi_destroy(r->gi);
    r->gi = g;
    scene_pose_rest(r->scene, &r->gi_pose); /* a fresh method has the scene as loaded */
    return 0;
}

renderer *renderer_create(const renderer_desc *desc, char *err, size_t errlen)
{
    if (!desc->gl || !desc->scene || desc->scene->triangle_count == 0) {
        snprintf(err, errlen, "renderer: needs a GL function table and a loaded scene");
        return NULL;
    }
    renderer *r = xcalloc(1, sizeof *r);
    r->gl = desc->gl;
    r->scene = desc->scene;
    scene_pose_rest(r->scene, &r->pose);
    size_t objects = (size_t)(r->scene->object_count ? r->scene->object_count : 1);
    r->models = xcalloc(objects, sizeof *r->models);
    r->shown = xcalloc(objects, 1);
    r->desc = *desc;
    r->desc.first = NULL;
    r->desc.limits = NULL;
    if (desc->first)
        r->frame = *desc->first;
    else
        frame_params_default(&r->frame);
    gi_frame_sanitize(&r->frame);
    if (desc->limits) {
        r->limits = *desc->limits;
        r->limited = 1;
        r->within = r->frame;
    }
    const char *gl_renderer = (const char *)r->gl->GetString(GL_RENDERER);
    r->software = gl_renderer && (strstr(gl_renderer, "llvmpipe") ||
                                  strstr(gl_renderer, "softpipe") || strstr(gl_renderer, "swrast"));
    r->timer = gpu_timer_create(r->gl);
    if (!(r->sum = gpu_checksum_create(r->gl, err, errlen)) ||
        !(r->prog_gbuffer = gltools_program(r->gl, "scene.vert", "gbuffer.frag", NULL, NULL, NULL, err, errlen)) ||
        !(r->prog_final = gltools_program(r->gl, "fullscreen.vert", "final.frag", NULL, NULL, NULL, err, errlen)) ||
        !(r->mesh = scene_gl_create(r->gl, r->scene, err, errlen)) ||
        build_frame_state(r, &r->frame, err, errlen) != 0 ||
        !(r->ao = renderer_ao_create(r->gl, r->scene, err, errlen)) ||
        !(r->aa = renderer_aa_create(r->gl, err, errlen)) ||
        !(r->hud = renderer_hud_create(r->gl, err, errlen))) {
        renderer_destroy(r);
        return NULL;
    }
    r->gl->GenVertexArrays(1, &r->empty_vao);
    r->gl->GenQueries(1, &r->lit_query);
    r->gl->GenQueries(1, &r->seen_query);
    r->emits = scene_has_emitter(r->scene);
    GLenum e = r->gl->GetError();
    if (e != GL_NO_ERROR) {
        snprintf(err, errlen, "renderer: GL error 0x%x while creating resources", (unsigned)e);
        renderer_destroy(r);
        return NULL;
    }
    return r;
}

void renderer_destroy(renderer *r)
{
    if (!r)
        return;
    const gl_functions *gl = r->gl;
    gi_destroy(r->gi);
    renderer_ao_destroy(r->ao);
    renderer_aa_destroy(r->aa);
    renderer_hud_destroy(r->hud);
    free_eye_targets(r);
    GLuint progs[] = {r->prog_gbuffer, r->prog_final};
    for (int i = 0; i < 2; i++)
        if (progs[i])
            gl->DeleteProgram(progs[i]);
    renderer_rsm_destroy(r->rsm);
    scene_gl_destroy(r->mesh);
    if (r->empty_vao)
        gl->DeleteVertexArrays(1, &r->empty_vao);
    if (r->lit_query)
        gl->DeleteQueries(1, &r->lit_query);
    if (r->seen_query)
        gl->DeleteQueries(1, &r->seen_query);
    free(r->models);
    free(r->shown);
    gpu_timer_destroy(r->timer);
    gpu_checksum_destroy(r->sum);
    free(r);
}

/* ---- frame pass ------------------------------------------------------------------- */

/* A frame that asks for another GI method, another RSM size or another setting that
 * rebuilds its method gets them fresh: every node does so in the same frame and starts the
 * method alike, without history. What cannot be built (memory) leaves the current state in
 * place and says why in renderer_last_error(); the checksums then show the master whether
 * the nodes disagree. */
static int same_state(const frame_params *a, const frame_params *b)
{
    return a->rsm_size == b->rsm_size && a->gi == b->gi && !gi_rebuild_needed(a->gi, a, b);
}

static void follow_frame(renderer *r, const frame_params *p)
{
    if (p->rsm_size == r->rsm_size && !gi_needs_rebuild(r->gi, p))
        return;
    if (r->have_refused && same_state(p, &r->refused))
        return; /* tried and failed: not again every frame */
    char err[200];
    r->have_refused = build_frame_state(r, p, err, sizeof err) != 0;
    r->refused = *p;
    if (r->have_refused)
        snprintf(r->error, sizeof r->error, "renderer: GI method %s with its settings not built "
                 "(%s); keeping %s", gi_method_at(p->gi)->name, err,
                 gi_method_at(gi_active(r->gi))->name);
}

void renderer_set_gbuffer_draw(renderer *r,
                               void (*draw)(void *user, const frame_view *view, const float view_projection[16],
                                            GLuint fbo, GLuint depth_texture),
                               void *user)
{
    r->desc.gbuffer_draw = draw;
    r->desc.gbuffer_user = user;
}

void renderer_set_pose(renderer *r, const scene_pose *pose)
{
    if (memcmp(&r->pose, pose, sizeof *pose) == 0)
        return;
    r->pose = *pose;
    scene_pose_models(r->scene, &r->pose, r->models, r->shown);
    scene_gl_set_pose(r->mesh, (const float (*)[16])r->models, r->shown);
}

/* Tells the GI method which objects moved since it last looked; 1 when any did (then
 * nothing of the last frame is reused: its maps and light saw the old places). */
static int objects_moved(renderer *r)
{
    uint8_t moved[SCENE_MAX_OBJECTS];
    int any = 0;
    for (int o = 0; o < r->scene->object_count; o++)
        any |= moved[o] = (uint8_t)scene_pose_object_changed(r->scene, &r->pose, &r->gi_pose, o);
    if (!any)
        return 0;
    gi_objects_moved(r->gi, &(gi_objects){.count = r->scene->object_count,
                                          .model = (const float (*)[16])r->models, .shown = r->shown,
                                          .moved = moved});
    r->gi_pose = r->pose;
    return 1;
}

/* A frame over a cluster node's limits (gi_cost.h) is rendered with the last settings
 * within them, said once per refusal (renderer_last_error()). */
static void keep_within_limits(renderer *r)
{
    char why[200];
    if (!r->limited)
        return;
    if (gi_cost_within(&r->limits, &r->frame, why, sizeof why)) {
        r->within = r->frame;
        return;
    }
    gi_cost_keep_settings(&r->within, &r->frame);
    snprintf(r->error, sizeof r->error, "renderer: frame settings refused: %s; keeping the last ones within "
             "the limits", why);
}

/* The ambient occlusion's maps for frame p; a refusal (memory) is said in
 * renderer_last_error() and leaves AO off. */
static void follow_ao(renderer *r, const frame_params *p, int moved)
{
    char err[256];
    if (renderer_ao_frame(r->ao, p, r->mesh, moved, err, sizeof err) != 0)
        snprintf(r->error, sizeof r->error, "renderer: no ambient occlusion: %s", err);
}

uint64_t renderer_frame_pass(renderer *r, const frame_params *params)
{
    double t0 = clock_now_ms();
    /* Where a frame begins in a GL trace (the stall test counts calls between these). */
    r->gl->DebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_MARKER, 0,
                              GL_DEBUG_SEVERITY_NOTIFICATION, -1, "cavelight frame");
    gpu_timer_frame(r->timer, params->version);
    /* Whatever arrived (NaN, inf, absurd counts): lights off or defaults, never NaN. Once
     * per frame; the eye passes render this copy. */
    r->frame = *params;
    r->timings.fixed = gi_frame_sanitize(&r->frame);
    keep_within_limits(r);
    r->eye_index = 0;
    const frame_params *p = &r->frame;
    follow_frame(r, p);
    int moved = objects_moved(r);
    follow_ao(r, p, moved);
    if (!moved && gi_reuse(r->gi, p)) { /* RSMs, textures and the method still hold this result */
        r->timings.rsm_ms = 0;
        r->timings.gpu = *gpu_timer_last(r->timer);
        gi_stats_get(r->gi, &r->timings.gi);
        r->checksum = r->host_checksum ^ gpu_checksum_frame(r->sum); /* its GPU part now in */
        r->timings.frame_host_ms = clock_now_ms() - t0;
        return r->checksum;
    }
    int h = gpu_timer_begin(r->timer, "rsm");
    renderer_rsm_render(r->rsm, r->mesh, p);
    gpu_timer_end(r->timer, h);
    gi_rsm rsm;
    renderer_gi_rsm(r, &rsm);
    /* READY's checksum: the method's host part of this frame and the GPU part of the last
     * computed one (docs/cluster.md: a desync there shows one frame late). */
    uint64_t late = gpu_checksum_frame(r->sum);
    h = gpu_timer_begin(r->timer, "gi");
    r->host_checksum = gi_frame(r->gi, p, &rsm);
    gpu_timer_end(r->timer, h);
    gpu_checksum_submit(r->sum);
    r->checksum = r->host_checksum ^ late;
    gi_stats_get(r->gi, &r->timings.gi);
    r->timings.gpu = *gpu_timer_last(r->timer);
    r->timings.rsm_ms = gpu_timer_mean_ms(&r->timings.gpu, "rsm");
    r->timings.frame_host_ms = clock_now_ms() - t0;
    return r->checksum;
}

/* ---- eye pass --------------------------------------------------------------------- */

static void read_rgb_float(renderer *r, GLenum attachment, float *out)
{
    const gl_functions *gl = r->gl;
    int w = r->eye_w, h = r->eye_h;
    gl->ReadBuffer(attachment);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->ReadPixels(0, 0, w, h, GL_RGB, GL_FLOAT, out);
    /* GL reads bottom row first; flip to top row first in place. */
    size_t row = (size_t)w * 3;
    for (int y = 0; y < h / 2; y++)
        for (size_t i = 0; i < row; i++) {
            float t = out[y * row + i];
            out[y * row + i] = out[(size_t)(h - 1 - y) * row + i];
            out[(size_t)(h - 1 - y) * row + i] = t;
        }
}

/* Where the eye is, for the sides and the specular: its position (w 1), or for an
 * orthographic projection (no perspective divide: the last row is 0 0 0 1) the direction
 * towards it, the view's +z axis in the world (w 0). */
static void eye_towards(const renderer_view *v, float eye[4])
{
    if (v->projection[3] == 0 && v->projection[7] == 0 && v->projection[11] == 0) {
        for (int a = 0; a < 3; a++)
            eye[a] = v->view[4 * a + 2];
        eye[3] = 0;
    } else {
        memcpy(eye, v->eye_position, 3 * sizeof(float));
        eye[3] = 1;
    }
}

/* One line when the k-th view of a frame turns black (it showed light before, or it is the
 * first), whatever the cause; not again while it stays black, and rate limited (a view
 * that flickers between black and lit). */
static void warn_if_dark(renderer *r, int lit)
{
    int k = r->eye_index < RENDERER_DARK_VIEWS ? r->eye_index : RENDERER_DARK_VIEWS - 1;
    r->eye_index++;
    if (lit) {
        r->view_dark[k] = 0;
        return;
    }
    if (r->view_dark[k])
        return;
    r->view_dark[k] = 1;
    uint64_t skipped;
    if (!ratelog_event(&r->dark_log, clock_now_ms(), &skipped))
        return;
    const frame_params *p = &r->frame;
    int lights = 0;
    for (int i = 0; i < p->light_count && i < FRAME_MAX_LIGHTS; i++)
        lights += light_is_lit(&p->lights[i]) &&
                  (p->lights[i].color[0] > 0 || p->lights[i].color[1] > 0 || p->lights[i].color[2] > 0);
    GLint seen = 0;
    r->gl->GetQueryObjectiv(r->seen_query, GL_QUERY_RESULT, &seen); /* ready: as lit_query */
    fprintf(stderr, "cavelight-node: warning: frame %llu, view %d receives no light: %s%s\n",
            (unsigned long long)p->version, k,
            seen ? light_dark_reason(lights || r->emits)
                 : "nothing in view (the scene lies outside this view: check its placement and "
                   "scale, e.g. --scene-transform '{\"fit\": true}')",
            skipped ? " (more such lines left out)" : "");
}

void renderer_screen(renderer *r, const renderer_view *views, int n)
{
    gi_screen(r->gi, views, n);
}

/* Texture units of the shading program: the G-buffer, the lights' shadow maps, then the
 * GI method's own. */
enum { UNIT_GBUFFER = 0, UNIT_RSM_DEPTH = 4, UNIT_RSM_NORMAL = 5, UNIT_AO = 6, UNIT_GI = 7 };

/* A pixel's width over its distance from the eye (an orthographic view: its width). */
static float pixel_angle(const renderer_view *view)
{
    return 2.0f / (view->projection[5] * view->height);
}

/* The caller's own geometry into the G-buffer (renderer_desc.gbuffer_draw), then the
 * state the next passes expect. */
static void gbuffer_extra(renderer *r, const renderer_view *view, const float vp[16])
{
    if (!r->desc.gbuffer_draw)
        return;
    const gl_functions *gl = r->gl;
    r->desc.gbuffer_draw(r->desc.gbuffer_user, view, vp, r->gbuffer_fbo, r->g_depth);
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->gbuffer_fbo);
    gl->Viewport(0, 0, view->width, view->height);
    gl->UseProgram(0);
    gl->BindVertexArray(0);
}

static void gbuffer_pass(renderer *r, const renderer_view *view, const float vp[16],
                         const float eye[4])
{
    const gl_functions *gl = r->gl;
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->gbuffer_fbo);
    gl->Viewport(0, 0, view->width, view->height);
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
    for (int b = 0; b < 4; b++)
        gl->ClearBufferfv(GL_COLOR, b, zero);
    gl->ClearBufferfv(GL_DEPTH, 0, &one);
    gl->UseProgram(r->prog_gbuffer);
    gl->UniformMatrix4fv(loc(r, r->prog_gbuffer, "u_view_projection"), 1, GL_FALSE, vp);
    gl->Uniform4fv(loc(r, r->prog_gbuffer, "u_eye"), 1, eye);
    gl->BeginQuery(GL_ANY_SAMPLES_PASSED, r->seen_query);
    scene_gl_draw(r->mesh, r->prog_gbuffer);
    gbuffer_extra(r, view, vp);
    gl->EndQuery(GL_ANY_SAMPLES_PASSED);
    gl->Disable(GL_DEPTH_TEST);
}

/* Direct light and the GI method's indirect light (its program, gi.h). */
static void shade_pass(renderer *r, const renderer_view *view, const float eye[4])
{
    const gl_functions *gl = r->gl;
    const frame_params *p = &r->frame;
    GLuint prog = gi_shade_program(r->gi);
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->shade_fbo);
    gl->UseProgram(prog);
    const GLuint gtex[4] = {r->g_position, r->g_normal, r->g_albedo, r->g_emissive};
    const char *gname[4] = {"u_position", "u_normal", "u_albedo", "u_emissive"};
    for (int i = 0; i < 4; i++) {
        gl->ActiveTexture((GLenum)(GL_TEXTURE0 + UNIT_GBUFFER + i));
        gl->BindTexture(GL_TEXTURE_2D, gtex[i]);
        gl->Uniform1i(loc(r, prog, gname[i]), UNIT_GBUFFER + i);
    }
    renderer_rsm_bind_shading(r->rsm, prog, p, UNIT_RSM_DEPTH, UNIT_RSM_NORMAL);
    renderer_ao_bind(r->ao, prog, UNIT_AO);
    gi_eye_bind(r->gi, &(gi_eye){.program = prog, .first_unit = UNIT_GI, .view = view,
                                 .width = view->width, .height = view->height, .eye = eye,
                                 .pixel_angle = pixel_angle(view)});
    gl->Uniform1f(loc(r, prog, "u_absorption"), p->absorption);
    gl->Uniform4fv(loc(r, prog, "u_eye"), 1, eye);
    gl->Uniform1f(loc(r, prog, "u_exposure"), p->exposure);
    gl->BindVertexArray(r->empty_vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
}

/* Tone map and gamma; black pixels are left out, so the lit query tells whether the view
 * shows any light. Then the HUD, in world space with this eye's view and projection. */
static void final_pass(renderer *r, const renderer_view *view, const float vp[16])
{
    const gl_functions *gl = r->gl;
    const frame_params *p = &r->frame;
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->final_fbo);
    gl->UseProgram(r->prog_final);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, r->s_final);
    gl->Uniform1i(loc(r, r->prog_final, "u_hdr"), 0);
    float encoding = frame_params_e2e_gamma(p->environment) / p->display_gamma;
    gl->Uniform1f(loc(r, r->prog_final, "u_encoding_gamma"), encoding);
    const float zero[4] = {0, 0, 0, 0};
    gl->ClearBufferfv(GL_COLOR, 0, zero);
    gl->BeginQuery(GL_ANY_SAMPLES_PASSED, r->lit_query);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    gl->EndQuery(GL_ANY_SAMPLES_PASSED);
    gl->BindVertexArray(0);
    renderer_hud_draw(r->hud, p, r->timings.gi.hud_cells, vp, view->eye_position, encoding);
}

/* The bound framebuffer's image (the final one, or its anti-aliased copy) as 8-bit RGB,
 * top row first, and the linear images on request. */
static void read_back(renderer *r, int want_linear, renderer_image *out)
{
    const gl_functions *gl = r->gl;
    int w = r->eye_w, h = r->eye_h;
    /* The image handed out: the one read back a trace may allow (the stall test). */
    gl->PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "cavelight image");
    gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl->ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, r->rgba);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            memcpy(r->rgb + ((size_t)y * w + x) * 3, r->rgba + ((size_t)(h - 1 - y) * w + x) * 4, 3);
    GLint any = 0;
    gl->GetQueryObjectiv(r->lit_query, GL_QUERY_RESULT, &any); /* ready: ReadPixels waited */
    out->lit = any != 0;
    warn_if_dark(r, out->lit);
    out->width = w;
    out->height = h;
    out->rgb = r->rgb;
    out->final = out->direct = out->indirect = out->ao = NULL;
    if (want_linear) {
        out->ao = renderer_ao_read(r->ao);
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->shade_fbo);
        for (int i = 0; i < 3; i++)
            read_rgb_float(r, GL_COLOR_ATTACHMENT0 + i, r->linear[i]);
        out->final = r->linear[0];
        out->direct = r->linear[1];
        out->indirect = r->linear[2];
    }
    gl->PopDebugGroup();
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
}

int renderer_eye_pass(renderer *r, const renderer_view *view, int want_linear,
                      renderer_image *out)
{
    if (view->width <= 0 || view->height <= 0) {
        snprintf(r->error, sizeof r->error, "renderer: eye pass needs a positive size, got %dx%d",
                 view->width, view->height);
        return -1;
    }
    if (eye_targets(r, view->width, view->height))
        return -1;
    double t0 = clock_now_ms();
    float vp[16], eye[4];
    mat4_mul(view->projection, view->view, vp);
    eye_towards(view, eye);
    int h = gpu_timer_begin(r->timer, "gbuffer");
    gbuffer_pass(r, view, vp, eye);
    gpu_timer_end(r->timer, h);
    h = gpu_timer_begin(r->timer, "ao");
    renderer_ao_eye(r->ao, &(renderer_ao_eye_desc){.view = view, .position = r->g_position,
                                                   .normal = r->g_normal, .eye = eye,
                                                   .pixel_angle = pixel_angle(view),
                                                   .vao = r->empty_vao,
                                                   .measure = r->desc.no_reuse});
    gpu_timer_end(r->timer, h);
    h = gpu_timer_begin(r->timer, "shade");
    shade_pass(r, view, eye);
    gpu_timer_end(r->timer, h);
    h = gpu_timer_begin(r->timer, "final");
    final_pass(r, view, vp);
    gpu_timer_end(r->timer, h);
    h = gpu_timer_begin(r->timer, "aa");
    renderer_aa_apply(r->aa, r->frame.aa, r->f_color, view->width, view->height, r->empty_vao);
    gpu_timer_end(r->timer, h);
    read_back(r, want_linear, out);
    gi_stats_get(r->gi, &r->timings.gi); /* the eye-side figures (vpl: its assignment) */
    r->timings.gpu = *gpu_timer_last(r->timer);
    r->timings.gbuffer_ms = gpu_timer_mean_ms(&r->timings.gpu, "gbuffer");
    r->timings.shade_ms = gpu_timer_mean_ms(&r->timings.gpu, "shade");
    r->timings.final_ms = gpu_timer_mean_ms(&r->timings.gpu, "final");
    r->timings.aa_ms = gpu_timer_mean_ms(&r->timings.gpu, "aa");
    renderer_ao_stats_get(r->ao, &r->timings.ao);
    r->timings.eye_host_ms = clock_now_ms() - t0;
    GLenum e = r->gl->GetError();
    if (e != GL_NO_ERROR) {
        snprintf(r->error, sizeof r->error, "renderer: GL error 0x%x in the eye pass", (unsigned)e);
        return -1;
    }
    return 0;
}

const char *renderer_last_error(const renderer *r)
{
    return r->error;
}

void renderer_get_timings(const renderer *r, renderer_timings *out)
{
    *out = r->timings;
}

renderer_rsm *renderer_get_rsm(renderer *r) { return r->rsm; }

void renderer_gi_rsm(const renderer *r, gi_rsm *out)
{
    *out = (gi_rsm){.size = renderer_rsm_size(r->rsm), .mesh = r->mesh};
    out->layers = renderer_rsm_views(r->rsm, &out->views, &out->fbo);
    renderer_rsm_textures(r->rsm, out->textures);
}

gpu_timer *renderer_gpu_timer(renderer *r) { return r->timer; }

uint64_t renderer_checksum_complete(renderer *r)
{
    return r->host_checksum ^ gpu_checksum_frame(r->sum);
}
gi *renderer_gi(renderer *r) { return r->gi; }
