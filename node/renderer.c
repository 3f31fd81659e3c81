/* renderer: GL passes of the render node (RSM, G-buffer, shading, final) and the frame /
 * eye pass orchestration. The indirect light is the active GI method's (gi.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/xalloc.h"
#include "base/mat4.h"
#include "frame/offaxis.h"
#include "gi.h"
#include "gi_ilpv.h"
#include "gltools.h"
#include "renderer.h"
#include "renderer_hud.h"

enum { Q_RSM = 0, Q_GBUFFER = 0, Q_SHADE = 1, Q_FINAL = 2 };

enum { RENDERER_QUERY_RING = 4 };

/* GL timer queries read a few frames later, never waited for (paper 4.6). */
typedef struct renderer_queries {
    GLuint id[RENDERER_QUERY_RING][4];
    int pending[RENDERER_QUERY_RING];
    int next;
    long dropped;            /* implausible readings thrown away */
    double ms[4];            /* latest results that arrived */
} renderer_queries;

typedef struct renderer_draw_range {
    uint32_t material;
    GLint first;
    GLsizei count;
} renderer_draw_range;

struct renderer {
    const gl_functions *gl;
    const scene *scene;
    GLuint vao, vbo, empty_vao;
    renderer_draw_range *ranges;
    int range_count;
    GLuint *textures;

    GLuint prog_gbuffer, prog_rsm, prog_shade, prog_final;

    int rsm_size;
    GLuint rsm_fbo[FRAME_MAX_LIGHTS];
    GLuint rsm_position, rsm_normal, rsm_flux, rsm_depth;
    float light_view_projection[FRAME_MAX_LIGHTS][16];
    float rsm_tan_half_fov[FRAME_MAX_LIGHTS];
    int rsm_lights;          /* lights rendered in the last frame pass */
    int rsm_layer_of[FRAME_MAX_LIGHTS];

    int eye_w, eye_h;
    GLuint gbuffer_fbo, g_position, g_normal, g_albedo, g_emissive, g_depth;
    GLuint shade_fbo, s_final, s_direct, s_indirect;
    GLuint final_fbo, f_color;
    uint8_t *rgba, *rgb;
    float *linear[3];

    gi *gi;                  /* the indirect-light method (gi.h) */
    uint64_t checksum;       /* its last frame's */
    gi_desc gi_desc;         /* what it is made with, for a live switch */
    renderer_desc desc;
    renderer_hud *hud;
    frame_params frame;      /* the last frame pass's parameters, sanitized: what the eye
                                passes render */
    renderer_queries frame_queries, eye_queries;
    renderer_timings timings;
    char error[256];         /* why the last eye pass failed */
};


static GLint loc(renderer *r, GLuint prog, const char *name)
{
    return r->gl->GetUniformLocation(prog, name);
}

static const GLenum draw_buffers[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                                       GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};

static int create_rsm(renderer *r, char *err, size_t errlen)
{
    const gl_functions *gl = r->gl;
    int s = r->rsm_size;
    r->rsm_position = gltools_texture_array(r->gl, GL_RGBA32F, s, FRAME_MAX_LIGHTS);
    r->rsm_normal = gltools_texture_array(r->gl, GL_RGBA32F, s, FRAME_MAX_LIGHTS);
    r->rsm_flux = gltools_texture_array(r->gl, GL_RGBA32F, s, FRAME_MAX_LIGHTS);
    r->rsm_depth = gltools_texture_array(r->gl, GL_DEPTH_COMPONENT32F, s, FRAME_MAX_LIGHTS);
    gl->BindTexture(GL_TEXTURE_2D_ARRAY, r->rsm_depth);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl->GenFramebuffers(FRAME_MAX_LIGHTS, r->rsm_fbo);
    for (int i = 0; i < FRAME_MAX_LIGHTS; i++) {
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->rsm_fbo[i]);
        gl->FramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, r->rsm_position, 0, i);
        gl->FramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, r->rsm_normal, 0, i);
        gl->FramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, r->rsm_flux, 0, i);
        gl->FramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, r->rsm_depth, 0, i);
        gl->DrawBuffers(3, draw_buffers);
        if (gltools_fbo_complete(r->gl, "RSM", err, errlen))
            return -1;
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    return 0;
}

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

/* Triangles grouped by material (stable), one draw per group. */
static int upload_scene(renderer *r, char *err, size_t errlen)
{
    const gl_functions *gl = r->gl;
    const scene *s = r->scene;
    size_t nt = s->triangle_count;
    float *v = malloc(nt * 3 * 8 * sizeof(float));
    size_t *order = malloc(nt * sizeof *order);
    size_t *start = calloc(s->material_count + 1, sizeof *start);
    r->ranges = calloc(s->material_count, sizeof *r->ranges);
    if (!v || !order || !start || !r->ranges) {
        free(v); free(order); free(start);
        snprintf(err, errlen, "renderer: out of memory for %zu triangles", nt);
        return -1;
    }
    for (size_t t = 0; t < nt; t++)
        start[s->triangle_material[t] + 1]++;
    for (size_t m = 0; m < s->material_count; m++)
        start[m + 1] += start[m];
    for (size_t m = 0; m < s->material_count; m++)
        if (start[m + 1] > start[m])
            r->ranges[r->range_count++] = (renderer_draw_range){
                (uint32_t)m, (GLint)(3 * start[m]), (GLsizei)(3 * (start[m + 1] - start[m]))};
    for (size_t t = 0; t < nt; t++)
        order[start[s->triangle_material[t]]++] = t;
    for (size_t i = 0; i < nt; i++)
        for (int k = 0; k < 3; k++) {
            float *d = v + (i * 3 + k) * 8;
            size_t t = order[i];
            memcpy(d, s->positions + 9 * t + 3 * k, 3 * sizeof(float));
            memcpy(d + 3, s->normals + 9 * t + 3 * k, 3 * sizeof(float));
            memcpy(d + 6, s->uvs + 6 * t + 2 * k, 2 * sizeof(float));
        }
    gl->GenVertexArrays(1, &r->vao);
    gl->GenVertexArrays(1, &r->empty_vao);
    gl->BindVertexArray(r->vao);
    gl->GenBuffers(1, &r->vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, r->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(nt * 3 * 8 * sizeof(float)), v, GL_STATIC_DRAW);
    for (GLuint a = 0; a < 3; a++) {
        gl->EnableVertexAttribArray(a);
        gl->VertexAttribPointer(a, a == 2 ? 2 : 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float),
                                (const void *)(uintptr_t)(a * 3 * sizeof(float)));
    }
    gl->BindVertexArray(0);
    free(v); free(order); free(start);

    r->textures = calloc(s->texture_count ? s->texture_count : 1, sizeof *r->textures);
    if (!r->textures)
        return snprintf(err, errlen, "renderer: out of memory"), -1;
    for (size_t i = 0; i < s->texture_count; i++) {
        const scene_texture *t = &s->textures[i];
        int levels = 1;
        while ((t->width >> levels) > 0 || (t->height >> levels) > 0)
            levels++;
        gl->GenTextures(1, &r->textures[i]);
        gl->BindTexture(GL_TEXTURE_2D, r->textures[i]);
        gl->TexStorage2D(GL_TEXTURE_2D, levels, GL_SRGB8_ALPHA8, t->width, t->height);
        gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, t->width, t->height, GL_RGBA,
                          GL_UNSIGNED_BYTE, t->rgba);
        gl->GenerateMipmap(GL_TEXTURE_2D);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    }
    return 0;
}

/* Material uniforms shared by the G-buffer and RSM programs (same names). */
static void bind_material(renderer *r, GLuint prog, uint32_t mi)
{
    const gl_functions *gl = r->gl;
    const scene_material *m = &r->scene->materials[mi];
    gl->Uniform4fv(loc(r, prog, "u_base_color"), 1, m->base_color);
    int tex = m->base_color_texture >= 0 && (size_t)m->base_color_texture < r->scene->texture_count;
    gl->Uniform1i(loc(r, prog, "u_has_texture"), tex);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, tex ? r->textures[m->base_color_texture] : 0);
    gl->Uniform1i(loc(r, prog, "u_base_texture"), 0);
    GLint e = loc(r, prog, "u_emissive");
    if (e >= 0)
        gl->Uniform3fv(e, 1, m->emissive);
    GLint ro = loc(r, prog, "u_roughness");
    if (ro >= 0)
        gl->Uniform1f(ro, m->roughness);
}

static void draw_scene(renderer *r, GLuint prog)
{
    const gl_functions *gl = r->gl;
    gl->BindVertexArray(r->vao);
    for (int i = 0; i < r->range_count; i++) {
        bind_material(r, prog, r->ranges[i].material);
        gl->DrawArrays(GL_TRIANGLES, r->ranges[i].first, r->ranges[i].count);
    }
    gl->BindVertexArray(0);
}

/* ---- timer queries ---------------------------------------------------------------- */

static void queries_init(renderer *r, renderer_queries *q)
{
    for (int i = 0; i < RENDERER_QUERY_RING; i++)
        r->gl->GenQueries(4, q->id[i]);
}

/* Collects every finished slot without waiting; returns the slot to use now. A slot whose
 * results are still out is simply reused (its numbers are dropped, the pipeline never
 * stalls). */
static int queries_begin_frame(renderer *r, renderer_queries *q, int used)
{
    const gl_functions *gl = r->gl;
    for (int k = 0; k < RENDERER_QUERY_RING; k++) {
        int slot = (q->next + k) % RENDERER_QUERY_RING;
        if (!(q->pending[slot]))
            continue;
        int last = 0;
        for (int i = 0; i < used; i++)
            if (q->pending[slot] & (1 << i))
                last = i;
        GLint ready = 0;
        gl->GetQueryObjectiv(q->id[slot][last], GL_QUERY_RESULT_AVAILABLE, &ready);
        if (!ready)
            continue;
        for (int i = 0; i < used; i++) {
            if (!(q->pending[slot] & (1 << i)))
                continue;
            GLuint64 ns = 0;
            gl->GetQueryObjectui64v(q->id[slot][i], GL_QUERY_RESULT, &ns);
            /* llvmpipe now and then times a query from an undefined start (hundreds of
             * seconds, seen on the first query of a context and after compute work): a
             * pass longer than 10 s is such a reading, dropped and counted. */
            if (ns < 10000000000ull)
                q->ms[i] = (double)ns * 1e-6;
            else
                q->dropped++;
        }
        q->pending[slot] = 0;
    }
    int slot = q->next;
    q->next = (q->next + 1) % RENDERER_QUERY_RING;
    q->pending[slot] = 0;
    return slot;
}

static void query_begin(renderer *r, renderer_queries *q, int slot, int i)
{
    r->gl->BeginQuery(GL_TIME_ELAPSED, q->id[slot][i]);
}

static void query_end(renderer *r, renderer_queries *q, int slot, int i)
{
    r->gl->EndQuery(GL_TIME_ELAPSED);
    q->pending[slot] |= 1 << i;
}

/* ---- create / destroy ------------------------------------------------------------- */

renderer *renderer_create(const renderer_desc *desc, char *err, size_t errlen)
{
    if (!desc->gl || !desc->scene || desc->scene->triangle_count == 0) {
        snprintf(err, errlen, "renderer: needs a GL function table and a loaded scene");
        return NULL;
    }
    renderer *r = xcalloc(1, sizeof *r);
    r->gl = desc->gl;
    r->scene = desc->scene;
    frame_params_default(&r->frame);
    r->rsm_size = desc->rsm_size > 0 ? desc->rsm_size : 256;
    const char *gl_renderer = (const char *)r->gl->GetString(GL_RENDERER);
    r->desc = *desc;
    r->gi_desc = (gi_desc){
        .gl = r->gl, .scene = r->scene, .settings = &r->desc, .rsm_size = r->rsm_size,
        .software = gl_renderer && (strstr(gl_renderer, "llvmpipe") ||
                                    strstr(gl_renderer, "softpipe") || strstr(gl_renderer, "swrast")),
    };
    if (!(r->prog_gbuffer = gltools_program(r->gl, "scene.vert", "gbuffer.frag", NULL, NULL, NULL, err, errlen)) ||
        !(r->prog_rsm = gltools_program(r->gl, "scene.vert", "rsm.frag", NULL, NULL, NULL, err, errlen)) ||
        !(r->prog_shade = gltools_program(r->gl, "fullscreen.vert", "shade.frag", NULL, NULL, NULL, err, errlen)) ||
        !(r->prog_final = gltools_program(r->gl, "fullscreen.vert", "final.frag", NULL, NULL, NULL, err, errlen)) ||
        upload_scene(r, err, errlen) || create_rsm(r, err, errlen) ||
        !(r->gi = gi_create(desc->gi, &r->gi_desc, err, errlen)) ||
        !(r->hud = renderer_hud_create(r->gl, err, errlen))) {
        renderer_destroy(r);
        return NULL;
    }
    queries_init(r, &r->frame_queries);
    queries_init(r, &r->eye_queries);
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
    renderer_hud_destroy(r->hud);
    free_eye_targets(r);
    GLuint progs[] = {r->prog_gbuffer, r->prog_rsm, r->prog_shade, r->prog_final};
    for (int i = 0; i < 4; i++)
        if (progs[i])
            gl->DeleteProgram(progs[i]);
    GLuint tex[] = {r->rsm_position, r->rsm_normal, r->rsm_flux, r->rsm_depth};
    for (int i = 0; i < 4; i++)
        if (tex[i])
            gl->DeleteTextures(1, &tex[i]);
    if (r->rsm_fbo[0])
        gl->DeleteFramebuffers(FRAME_MAX_LIGHTS, r->rsm_fbo);
    if (r->textures && r->scene->texture_count)
        gl->DeleteTextures((GLsizei)r->scene->texture_count, r->textures);
    if (r->vbo)
        gl->DeleteBuffers(1, &r->vbo);
    if (r->vao)
        gl->DeleteVertexArrays(1, &r->vao);
    if (r->empty_vao)
        gl->DeleteVertexArrays(1, &r->empty_vao);
    for (int i = 0; i < RENDERER_QUERY_RING; i++) {
        if (r->frame_queries.id[i][0])
            gl->DeleteQueries(4, r->frame_queries.id[i]);
        if (r->eye_queries.id[i][0])
            gl->DeleteQueries(4, r->eye_queries.id[i]);
    }
    free(r->textures);
    free(r->ranges);
    free(r);
}

/* ---- frame pass ------------------------------------------------------------------- */

/* The shadow map's near plane follows the scene's size (as the falloff bound does,
 * scene_min_light_distance()), so that a 4 cm model and a 4 km site render alike
 * (docs/stability.md): a fixed 5 cm left a 4 cm model's RSM empty. D / 128 gives the 6.4 m
 * default room the former value. The shadow test's offset is in texels (shade.frag). */
static void render_rsms(renderer *r, const frame_params *p)
{
    const gl_functions *gl = r->gl;
    GLuint prog = r->prog_rsm;
    float diagonal = scene_diagonal(r->scene);
    r->rsm_lights = 0;
    gl->UseProgram(prog);
    gl->Viewport(0, 0, r->rsm_size, r->rsm_size);
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    for (int i = 0; i < p->light_count && i < FRAME_MAX_LIGHTS; i++) {
        const frame_light *l = &p->lights[i];
        if (!l->enabled || !(l->intensity > 0))
            continue;
        int layer = r->rsm_lights++;
        r->rsm_layer_of[layer] = i;
        float outer = fminf(fmaxf(l->outer_angle, 0.01f), 1.45f);
        float inner = fminf(fmaxf(l->inner_angle, 0.0f), outer);
        float target[3], view[16], proj[16];
        for (int a = 0; a < 3; a++)
            target[a] = l->position[a] + l->direction[a];
        float dist = 0;
        for (int a = 0; a < 3; a++) {
            float c = 0.5f * (r->scene->bounds_min[a] + r->scene->bounds_max[a]) - l->position[a];
            dist += c * c;
        }
        float fp = diagonal + sqrtf(dist) + diagonal / 6.4f;
        offaxis_look_at(l->position, target, 2.0f * outer, 1.0f, diagonal / 128.0f, fp, view,
                        proj);
        mat4_mul(proj, view, r->light_view_projection[layer]);
        r->rsm_tan_half_fov[layer] = tanf(outer);
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->rsm_fbo[layer]);
        const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
        for (int b = 0; b < 3; b++)
            gl->ClearBufferfv(GL_COLOR, b, zero);
        gl->ClearBufferfv(GL_DEPTH, 0, &one);
        gl->UniformMatrix4fv(loc(r, prog, "u_view_projection"), 1, GL_FALSE,
                             r->light_view_projection[layer]);
        gl->Uniform3fv(loc(r, prog, "u_light_position"), 1, l->position);
        gl->Uniform3fv(loc(r, prog, "u_light_direction"), 1, l->direction);
        float radiance[3] = {l->color[0] * l->intensity, l->color[1] * l->intensity,
                             l->color[2] * l->intensity};
        gl->Uniform3fv(loc(r, prog, "u_light_radiance"), 1, radiance);
        gl->Uniform1f(loc(r, prog, "u_cos_outer"), cosf(outer));
        gl->Uniform1f(loc(r, prog, "u_cos_inner"), cosf(inner));
        gl->Uniform1f(loc(r, prog, "u_tan_half_fov"), r->rsm_tan_half_fov[layer]);
        gl->Uniform1f(loc(r, prog, "u_size"), (float)r->rsm_size);
        gl->Uniform1f(loc(r, prog, "u_absorption"), p->absorption);
        draw_scene(r, prog);
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
}

/* A frame that asks for another GI method gets a fresh one: every node switches in the
 * same frame and starts it alike, without history. One that cannot be built (memory)
 * leaves the current method in place and says why in renderer_last_error(); the checksums
 * then show the master whether the nodes disagree. */
static void switch_gi(renderer *r, frame_gi want)
{
    if (want == gi_active(r->gi))
        return;
    char err[200];
    gi *g = gi_create(want, &r->gi_desc, err, sizeof err);
    if (!g) {
        snprintf(r->error, sizeof r->error, "renderer: GI method %s not built (%s); keeping %s",
                 frame_gi_name(want), err, frame_gi_name(gi_active(r->gi)));
        return;
    }
    gi_destroy(r->gi);
    r->gi = g;
}

uint64_t renderer_frame_pass(renderer *r, const frame_params *params)
{
    double t0 = clock_now_ms();
    /* Whatever arrived (NaN, inf, absurd counts): lights off or defaults, never NaN. Once
     * per frame; the eye passes render this copy. */
    r->frame = *params;
    frame_params_sanitize(&r->frame);
    const frame_params *p = &r->frame;
    switch_gi(r, p->gi);
    if (gi_reuse(r->gi, p)) { /* RSMs, textures and the method still hold this result */
        r->timings.rsm_ms = r->timings.inject_ms = r->timings.propagate_ms = 0;
        r->timings.frame_host_ms = clock_now_ms() - t0;
        return r->checksum;
    }
    int slot = queries_begin_frame(r, &r->frame_queries, 1);
    query_begin(r, &r->frame_queries, slot, Q_RSM);
    render_rsms(r, p);
    query_end(r, &r->frame_queries, slot, Q_RSM);
    gi_rsm rsm = {.size = r->rsm_size, .layers = r->rsm_lights, .fbo = r->rsm_fbo};
    r->checksum = gi_frame(r->gi, p, &rsm);
    gi_stats gs;
    gi_stats_get(r->gi, &gs);
    r->timings.inject_ms = gs.inject_ms;
    r->timings.propagate_ms = gs.propagate_ms;
    r->timings.rsm_ms = r->frame_queries.ms[Q_RSM];
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

int renderer_eye_pass(renderer *r, const renderer_view *view, int want_linear,
                      renderer_image *out)
{
    const gl_functions *gl = r->gl;
    const frame_params *p = &r->frame;
    if (view->width <= 0 || view->height <= 0) {
        snprintf(r->error, sizeof r->error, "renderer: eye pass needs a positive size, got %dx%d",
                 view->width, view->height);
        return -1;
    }
    if (eye_targets(r, view->width, view->height))
        return -1;
    double t0 = clock_now_ms();
    int w = view->width, h = view->height;
    int slot = queries_begin_frame(r, &r->eye_queries, 3);
    float vp[16];
    mat4_mul(view->projection, view->view, vp);

    /* G-buffer */
    query_begin(r, &r->eye_queries, slot, Q_GBUFFER);
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->gbuffer_fbo);
    gl->Viewport(0, 0, w, h);
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
    for (int b = 0; b < 4; b++)
        gl->ClearBufferfv(GL_COLOR, b, zero);
    gl->ClearBufferfv(GL_DEPTH, 0, &one);
    gl->UseProgram(r->prog_gbuffer);
    gl->UniformMatrix4fv(loc(r, r->prog_gbuffer, "u_view_projection"), 1, GL_FALSE, vp);
    gl->Uniform3fv(loc(r, r->prog_gbuffer, "u_eye"), 1, view->eye_position);
    draw_scene(r, r->prog_gbuffer);
    gl->Disable(GL_DEPTH_TEST);
    query_end(r, &r->eye_queries, slot, Q_GBUFFER);

    /* Shading */
    query_begin(r, &r->eye_queries, slot, Q_SHADE);
    GLuint prog = r->prog_shade;
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->shade_fbo);
    gl->UseProgram(prog);
    const GLuint gtex[4] = {r->g_position, r->g_normal, r->g_albedo, r->g_emissive};
    const char *gname[4] = {"u_position", "u_normal", "u_albedo", "u_emissive"};
    for (int i = 0; i < 4; i++) {
        gl->ActiveTexture(GL_TEXTURE0 + i);
        gl->BindTexture(GL_TEXTURE_2D, gtex[i]);
        gl->Uniform1i(loc(r, prog, gname[i]), i);
    }
    gl->ActiveTexture(GL_TEXTURE4);
    gl->BindTexture(GL_TEXTURE_2D_ARRAY, r->rsm_depth);
    gl->Uniform1i(loc(r, prog, "u_shadow"), 4);
    gl->ActiveTexture(GL_TEXTURE8);
    gl->BindTexture(GL_TEXTURE_2D_ARRAY, r->rsm_normal);
    gl->Uniform1i(loc(r, prog, "u_rsm_normal"), 8);
    gi_eye_bind(r->gi, &(gi_eye){.program = prog, .first_unit = 5});
    float lpos[FRAME_MAX_LIGHTS][3], ldir[FRAME_MAX_LIGHTS][3], lrad[FRAME_MAX_LIGHTS][3];
    float cos_outer[FRAME_MAX_LIGHTS], cos_inner[FRAME_MAX_LIGHTS];
    for (int k = 0; k < r->rsm_lights; k++) {
        const frame_light *l = &p->lights[r->rsm_layer_of[k]];
        float outer = fminf(fmaxf(l->outer_angle, 0.01f), 1.45f);
        float inner = fminf(fmaxf(l->inner_angle, 0.0f), outer);
        memcpy(lpos[k], l->position, sizeof lpos[k]);
        memcpy(ldir[k], l->direction, sizeof ldir[k]);
        for (int c = 0; c < 3; c++)
            lrad[k][c] = l->color[c] * l->intensity;
        cos_outer[k] = cosf(outer);
        cos_inner[k] = cosf(inner);
    }
    int nl = r->rsm_lights;
    gl->Uniform1i(loc(r, prog, "u_light_count"), nl);
    if (nl > 0) {
        gl->Uniform3fv(loc(r, prog, "u_light_position"), nl, lpos[0]);
        gl->Uniform3fv(loc(r, prog, "u_light_direction"), nl, ldir[0]);
        gl->Uniform3fv(loc(r, prog, "u_light_radiance"), nl, lrad[0]);
        gl->Uniform1fv(loc(r, prog, "u_cos_outer"), nl, cos_outer);
        gl->Uniform1fv(loc(r, prog, "u_cos_inner"), nl, cos_inner);
        gl->UniformMatrix4fv(loc(r, prog, "u_light_view_projection"), nl, GL_FALSE,
                             r->light_view_projection[0]);
        gl->Uniform1fv(loc(r, prog, "u_light_tan_half_fov"), nl, r->rsm_tan_half_fov);
    }
    gl->Uniform1f(loc(r, prog, "u_shadow_texel"), 1.0f / (float)r->rsm_size);
    gl->Uniform1f(loc(r, prog, "u_min_light_distance"), scene_min_light_distance(r->scene));
    gl->Uniform1f(loc(r, prog, "u_absorption"), p->absorption);
    gl->Uniform3fv(loc(r, prog, "u_eye"), 1, view->eye_position);
    gl->Uniform1f(loc(r, prog, "u_exposure"), p->exposure > 0 ? p->exposure : 1.0f);
    gl->BindVertexArray(r->empty_vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    query_end(r, &r->eye_queries, slot, Q_SHADE);

    /* Final: tone map and gamma */
    query_begin(r, &r->eye_queries, slot, Q_FINAL);
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->final_fbo);
    gl->UseProgram(r->prog_final);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, r->s_final);
    gl->Uniform1i(loc(r, r->prog_final, "u_hdr"), 0);
    float display = p->display_gamma > 0 ? p->display_gamma : 2.2f;
    float encoding = frame_params_e2e_gamma(p->environment) / display;
    gl->Uniform1f(loc(r, r->prog_final, "u_encoding_gamma"), encoding);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    gl->BindVertexArray(0);
    /* The HUD after tone mapping, in world space with this eye's view and projection. */
    gi_stats gs;
    gi_stats_get(r->gi, &gs);
    renderer_hud_draw(r->hud, p, gs.lattice_cells, vp, view->eye_position, encoding);
    query_end(r, &r->eye_queries, slot, Q_FINAL);

    gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl->ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, r->rgba);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            memcpy(r->rgb + ((size_t)y * w + x) * 3, r->rgba + ((size_t)(h - 1 - y) * w + x) * 4, 3);
    out->width = w;
    out->height = h;
    out->rgb = r->rgb;
    out->final = out->direct = out->indirect = NULL;
    if (want_linear) {
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->shade_fbo);
        for (int i = 0; i < 3; i++)
            read_rgb_float(r, GL_COLOR_ATTACHMENT0 + i, r->linear[i]);
        out->final = r->linear[0];
        out->direct = r->linear[1];
        out->indirect = r->linear[2];
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    r->timings.gbuffer_ms = r->eye_queries.ms[Q_GBUFFER];
    r->timings.shade_ms = r->eye_queries.ms[Q_SHADE];
    r->timings.final_ms = r->eye_queries.ms[Q_FINAL];
    r->timings.eye_host_ms = clock_now_ms() - t0;
    GLenum e = gl->GetError();
    if (e != GL_NO_ERROR) {
        snprintf(r->error, sizeof r->error, "renderer: GL error 0x%x in the eye pass", (unsigned)e);
        return -1;
    }
    return 0;
}

void renderer_present(renderer *r, int width, int height)
{
    const gl_functions *gl = r->gl;
    if (!r->final_fbo)
        return;
    gl->BindFramebuffer(GL_READ_FRAMEBUFFER, r->final_fbo);
    gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    gl->BlitFramebuffer(0, 0, r->eye_w, r->eye_h, 0, 0, width, height, GL_COLOR_BUFFER_BIT,
                        GL_LINEAR);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
}

const char *renderer_last_error(const renderer *r)
{
    return r->error;
}

void renderer_get_timings(const renderer *r, renderer_timings *out)
{
    *out = r->timings;
}

/* ---- the ILPV method's figures, while it is the active one ----------------------------- */

static gi_ilpv *active_ilpv(const renderer *r)
{
    return gi_active(r->gi) == FRAME_GI_ILPV ? gi_state(r->gi) : NULL;
}

frame_gi renderer_get_gi(const renderer *r) { return gi_active(r->gi); }

renderer_lpv_backend renderer_get_lpv_backend(const renderer *r)
{
    return active_ilpv(r) ? gi_ilpv_backend(active_ilpv(r)) : RENDERER_LPV_AUTO;
}

const lattice_desc *renderer_get_lattice(const renderer *r)
{
    return active_ilpv(r) ? gi_ilpv_lattice(active_ilpv(r)) : NULL;
}

const lpv_volume *renderer_get_lpv(const renderer *r)
{
    return active_ilpv(r) ? gi_ilpv_volume(active_ilpv(r)) : NULL;
}

float renderer_get_indirect_scale(const renderer *r)
{
    return active_ilpv(r) ? gi_ilpv_indirect_scale(active_ilpv(r)) : 0.0f;
}

renderer_lpv_mode renderer_get_lpv_mode(const renderer *r)
{
    return active_ilpv(r) ? gi_ilpv_mode(active_ilpv(r)) : r->desc.lpv_mode;
}

void renderer_get_lpv_stats(const renderer *r, renderer_lpv_stats *out)
{
    *out = (renderer_lpv_stats){.last_residual = INFINITY};
    if (active_ilpv(r))
        gi_ilpv_lpv_stats(active_ilpv(r), out);
}

double renderer_measure_step_ms(renderer *r, int steps)
{
    return active_ilpv(r) ? gi_ilpv_measure_step_ms(active_ilpv(r), steps) : 0.0;
}
