/* gi_ldm: the ldm method (gi_ldm.h). */
#include "gi/ldm/gi_ldm.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/fnv1a.h"
#include "base/mat4.h"
#include "base/xalloc.h"
#include "gi/ldm/ldm_photons.h"
#include "gi/ldm/ldm_settings.h"
#include "gi/gi_reuse.h"
#include "gl/gltools.h"
#include "ldm_gl.h"

/* Storage buffer bindings of its shaders (0 and 1 are the maps', ldm_gl.h). */
enum { BIND_PHOTONS = 3, BIND_SPLITS = 4, SPLIT_VEC4 = 4, GROUP = 64 };

typedef struct gi_ldm {
    const gl_functions *gl;
    const scene *scene;
    ldm_settings settings;       /* the last frame's */
    gi_reuse_state reuse;        /* the last frame's parameters */
    gi_rsm_reader reader;        /* one RSM layer read back */
    ldm_gl *maps;
    int maps_stale;              /* not built yet, or objects moved since: build in frame() */
    ldm_photon *photons;         /* this frame's primary photons */
    size_t photon_count, photon_capacity;
    vpl_emitter *emitters;
    size_t emitter_count;
    GLuint prog_split, prog_splat, photon_buf, split_buf, vao, fbo, irradiance;
    size_t split_slots;          /* the split buffer's room */
    int width, height;           /* the irradiance texture's */
    uint64_t checksum;
    double construct_ms, photons_ms, trace_ms, splat_ms;
    gpu_timer *timer;            /* the renderer's: the stages' GPU time */
    double splits;               /* non-empty split photons (NaN: not counted, checksum()) */
    gpu_checksum *sum;           /* the renderer's: the checksum of what stays on the GPU */
} gi_ldm;

static void release(gi_ldm *g)
{
    const gl_functions *gl = g->gl;
    ldm_gl_destroy(g->maps);
    GLuint progs[2] = {g->prog_split, g->prog_splat}, bufs[2] = {g->photon_buf, g->split_buf};
    for (int i = 0; i < 2; i++) {
        if (progs[i])
            gl->DeleteProgram(progs[i]);
        if (bufs[i])
            gl->DeleteBuffers(1, &bufs[i]);
    }
    if (g->vao)
        gl->DeleteVertexArrays(1, &g->vao);
    if (g->fbo)
        gl->DeleteFramebuffers(1, &g->fbo);
    if (g->irradiance)
        gl->DeleteTextures(1, &g->irradiance);
    free(g->photons);
    gi_rsm_reader_free(&g->reader);
    free(g->emitters);
}

/* The maps' buffers for the settings and the frame's layers, built in the next frame().
 * 0, or -1 with one line. */
static int new_maps(gi_ldm *g, const frame_params *p, char *err, size_t errlen)
{
    const ldm_settings *s = &g->settings;
    const char *why = ldm_memory_check(s->directions, s->resolution, p->ldm_layers,
                                       p->ldm_memory_mb, "ldm", err, errlen);
    if (why)
        return -1;
    ldm_layout l;
    ldm_layout_init(&l, g->scene, s->directions, s->resolution, p->ldm_layers);
    ldm_gl *maps = ldm_gl_create(g->gl, &l, err, errlen);
    if (!maps)
        return -1;
    ldm_gl_destroy(g->maps);
    g->maps = maps;
    g->maps_stale = 1;
    return 0;
}

static void *create(const gi_desc *d, char *err, size_t errlen)
{
    gi_ldm *g = xcalloc(1, sizeof *g);
    g->gl = d->gl;
    g->scene = d->scene;
    g->reuse.never = d->no_reuse;
    g->timer = d->timer;
    g->sum = d->sum;
    ldm_settings_get(d->frame, &g->settings);
    const char *split[2] = {"ldm_trace.glsl", "ldm/ldm_split.comp"};
    const char *splat[2] = {"ldm_trace.glsl", "ldm/ldm_splat.frag"};
    g->emitter_count = vpl_emitters(d->scene, NULL);
    g->emitters = xmalloc((g->emitter_count ? g->emitter_count : 1) * sizeof *g->emitters);
    vpl_emitters(d->scene, g->emitters);
    if (new_maps(g, d->frame, err, errlen) != 0 ||
        !(g->prog_split = gltools_compute_parts(d->gl, split, 2, NULL, err, errlen)) ||
        !(g->prog_splat = gltools_program_parts(d->gl, "ldm/ldm_splat.vert", splat, 2, NULL,
                                                err, errlen))) {
        release(g);
        free(g);
        return NULL;
    }
    const gl_functions *gl = d->gl;
    gl->GenBuffers(1, &g->photon_buf);
    gl->GenBuffers(1, &g->split_buf);
    gl->GenVertexArrays(1, &g->vao);
    gl->GenFramebuffers(1, &g->fbo);
    return g;
}

static void destroy(void *state)
{
    release(state);
    free(state);
}

/* The split photons depend on the lights, the medium and the ldm settings (and the
 * frame's map layers) only. */
static int reuse(void *state, const frame_params *p)
{
    gi_ldm *g = state;
    ldm_settings now;
    ldm_settings_get(p, &now);
    int same = gi_reuse_unchanged(&g->reuse, p, &now, &g->settings, sizeof now,
                                  p->ldm_layers == g->reuse.last.ldm_layers &&
                                  p->rsm_size == g->reuse.last.rsm_size);
    if (same)
        g->construct_ms = g->photons_ms = g->trace_ms = 0;
    return same;
}

/* Room for n primary photons. */
static void reserve_photons(gi_ldm *g, size_t n)
{
    if (n <= g->photon_capacity)
        return;
    g->photons = xrealloc(g->photons, n * sizeof *g->photons);
    g->photon_capacity = n;
}

/* Every RSM layer's blocks (view order), then the emitters. */
static void collect(gi_ldm *g, const frame_params *p, const gi_rsm *rsm)
{
    int side = g->settings.photons;
    reserve_photons(g, (size_t)rsm->layers * side * side + g->emitter_count);
    size_t n = 0;
    for (int layer = 0; layer < rsm->layers; layer++) {
        const float *pos, *nrm, *flux;
        if (gi_rsm_read_layer(&g->reader, g->gl, rsm, layer, &pos, &nrm, &flux) != 0)
            break;
        const frame_light *l = &p->lights[rsm->views[layer].light];
        const float *from = l->type == SCENE_LIGHT_DIRECTIONAL ? NULL : l->position;
        n += ldm_photons_from_rsm(pos, nrm, flux, rsm->size, side, from, g->photons + n);
    }
    for (size_t e = 0; e < g->emitter_count; e++)
        g->photons[n++] = ldm_photon_from_emitter(&g->emitters[e]);
    const ldm_layout *lay = ldm_gl_layout(g->maps);
    ldm_photons_finish(g->photons, n, ldm_gl_maps(g->maps), lay->directions, g->settings.spread);
    g->photon_count = n;
}

/* The split: one invocation per photon and map. Then the checksum of its slots. */
static void split(gi_ldm *g, const frame_params *p)
{
    const gl_functions *gl = g->gl;
    int maps = ldm_gl_layout(g->maps)->directions;
    size_t slots = g->photon_count * (size_t)maps;
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, g->photon_buf);
    gl->BufferData(GL_SHADER_STORAGE_BUFFER,
                   (GLsizeiptr)((g->photon_count ? g->photon_count : 1) * sizeof(ldm_photon)),
                   g->photons, GL_DYNAMIC_DRAW);
    if (slots > g->split_slots || g->split_slots == 0) {
        g->split_slots = slots ? slots : 1;
        gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, g->split_buf);
        gl->BufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(g->split_slots * SPLIT_VEC4 * 16),
                       NULL, GL_DYNAMIC_COPY);
    }
    gl->UseProgram(g->prog_split);
    ldm_gl_bind(g->maps, g->prog_split);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_PHOTONS, g->photon_buf);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_SPLITS, g->split_buf);
    gl->Uniform1i(gl->GetUniformLocation(g->prog_split, "u_photon_count"), (int)g->photon_count);
    gl->Uniform1f(gl->GetUniformLocation(g->prog_split, "u_max_distance"), g->settings.distance);
    gl->Uniform1f(gl->GetUniformLocation(g->prog_split, "u_absorption"), p->absorption);
    if (slots)
        gl->DispatchCompute((GLuint)((slots + GROUP - 1) / GROUP), 1, 1);
    gl->MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    gl->UseProgram(0);
    if (g->reuse.never) /* host ms of a measured frame; a node's frame never waits */
        gl->Finish();
}

/* The checksum READY carries: the maps' (host) and the split slots' (on the GPU,
 * gpu_checksum.h). The splits figure reads the slots back: only in measured frames
 * (benchmarks), NaN otherwise. */
static void checksum(gi_ldm *g, size_t slots)
{
    uint64_t maps = ldm_gl_checksum(g->maps);
    g->checksum = fnv1a64(FNV1A64_CLUSTER_SEED, &maps, sizeof maps);
    gpu_checksum_add(g->sum, g->split_buf, 0, slots, SPLIT_VEC4 * 4, SPLIT_VEC4 * 4);
    g->splits = NAN;
    if (!g->reuse.never)
        return;
    float *all = xmalloc((slots ? slots : 1) * SPLIT_VEC4 * 4 * sizeof(float));
    const gl_functions *gl = g->gl;
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, g->split_buf);
    gl->GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(slots * SPLIT_VEC4 * 16), all);
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    g->splits = 0;
    for (size_t i = 0; i < slots; i++) {
        const float *f = all + i * SPLIT_VEC4 * 4 + 8;
        g->splits += f[0] + f[1] + f[2] > 0;
    }
    free(all);
}

static uint64_t frame(void *state, const frame_params *p, const gi_rsm *rsm)
{
    gi_ldm *g = state;
    char err[256];
    const ldm_layout *lay = ldm_gl_layout(g->maps);
    g->construct_ms = 0;
    if (lay->layers != p->ldm_layers && new_maps(g, p, err, sizeof err) != 0)
        fprintf(stderr, "cavelight-node: %s; the last maps stay\n", err);
    int h = gpu_timer_begin(g->timer, "construct");
    if (g->maps_stale || g->reuse.never) /* never_reuse: a moving scene's cost is measured */
        g->construct_ms = ldm_gl_build(g->maps, rsm->mesh);
    gpu_timer_end(g->timer, h);
    g->maps_stale = 0;
    double t0 = clock_now_ms();
    h = gpu_timer_begin(g->timer, "photons");
    collect(g, p, rsm);
    gpu_timer_end(g->timer, h);
    double t1 = clock_now_ms();
    h = gpu_timer_begin(g->timer, "trace");
    split(g, p);
    gpu_timer_end(g->timer, h);
    double t2 = clock_now_ms();
    checksum(g, g->photon_count * (size_t)ldm_gl_layout(g->maps)->directions);
    g->photons_ms = t1 - t0;
    g->trace_ms = t2 - t1;
    return g->checksum;
}

/* The eye-sized irradiance target. */
static void target(gi_ldm *g, int w, int h)
{
    if (w == g->width && h == g->height)
        return;
    const gl_functions *gl = g->gl;
    if (g->irradiance)
        gl->DeleteTextures(1, &g->irradiance);
    g->irradiance = gltools_texture2d(gl, GL_RGBA32F, w, h, GL_NEAREST);
    gl->BindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, g->irradiance, 0);
    const GLenum color = GL_COLOR_ATTACHMENT0;
    gl->DrawBuffers(1, &color);
    g->width = w;
    g->height = h;
}

/* The split photons over the eye's G-buffer (on units 0 and 1 of the shading program),
 * additively into the irradiance texture; the shading program, framebuffer, viewport and
 * vertex array put back. */
static void splat(gi_ldm *g, const gi_eye *e)
{
    const gl_functions *gl = g->gl;
    double t0 = clock_now_ms();
    int h = gpu_timer_begin(g->timer, "splat");
    gltools_draw_state outer;
    gltools_draw_state_save(gl, &outer);
    target(g, e->width, e->height);
    gl->BindFramebuffer(GL_FRAMEBUFFER, g->fbo);
    gl->Viewport(0, 0, e->width, e->height);
    const float zero[4] = {0, 0, 0, 0};
    gl->ClearBufferfv(GL_COLOR, 0, zero);
    GLuint prog = g->prog_splat;
    gl->UseProgram(prog);
    ldm_gl_bind(g->maps, prog);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_SPLITS, g->split_buf);
    float vp[16];
    mat4_mul(e->view->projection, e->view->view, vp);
    gl->UniformMatrix4fv(gl->GetUniformLocation(prog, "u_view_projection"), 1, GL_FALSE, vp);
    gl->Uniform2f(gl->GetUniformLocation(prog, "u_scale"), e->view->projection[0],
                  e->view->projection[5]);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_perspective"), e->view->projection[11] != 0);
    gl->Uniform2f(gl->GetUniformLocation(prog, "u_pixel"), 2.0f / (float)e->width,
                  2.0f / (float)e->height);
    gl->Uniform4fv(gl->GetUniformLocation(prog, "u_eye"), 1, e->eye);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_pixel_angle"), e->pixel_angle);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_position"), 0);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_normal"), 1);
    gl->Enable(GL_BLEND);
    gl->BlendFunc(GL_ONE, GL_ONE);
    gl->BindVertexArray(g->vao);
    size_t slots = g->photon_count * (size_t)ldm_gl_layout(g->maps)->directions;
    if (slots)
        gl->DrawArrays(GL_TRIANGLES, 0, (GLsizei)(6 * slots));
    gl->Disable(GL_BLEND);
    gltools_draw_state_restore(gl, &outer, e->program);
    gpu_timer_end(g->timer, h);
    if (g->reuse.never)
        gl->Finish();
    g->splat_ms = clock_now_ms() - t0;
}

static void eye_bind(void *state, const gi_eye *e)
{
    gi_ldm *g = state;
    const gl_functions *gl = g->gl;
    int on = e->view != NULL && g->photon_count > 0;
    if (on)
        splat(g, e);
    gl->ActiveTexture((GLenum)(GL_TEXTURE0 + e->first_unit));
    gl->BindTexture(GL_TEXTURE_2D, on ? g->irradiance : 0);
    gl->Uniform1i(gl->GetUniformLocation(e->program, "u_ldm_irradiance"), e->first_unit);
    gl->Uniform1i(gl->GetUniformLocation(e->program, "u_ldm_on"), on);
}

static void stats(const void *state, gi_stats *out)
{
    const gi_ldm *g = state;
    const ldm_layout *l = ldm_gl_layout(g->maps);
    out->stage_count = 3;
    out->stage[0] = (gi_stat){"construct", g->construct_ms};
    out->stage[1] = (gi_stat){"photons", g->photons_ms};
    out->stage[2] = (gi_stat){"trace", g->trace_ms};
    out->figure_count = 5;
    out->figure[0] = (gi_stat){"splat_ms", g->splat_ms};
    out->figure[1] = (gi_stat){"memory_mb", ldm_memory_bytes(l) / (1024.0 * 1024.0)};
    out->figure[2] = (gi_stat){"overflow", (double)ldm_gl_overflow(g->maps)};
    out->figure[3] = (gi_stat){"photons", (double)g->photon_count};
    out->figure[4] = (gi_stat){"splits", g->splits};
}

/* Moved or hidden objects: the maps are drawn again, where the objects are now. */
static void objects(void *state, const gi_objects *o)
{
    (void)o;
    ((gi_ldm *)state)->maps_stale = 1;
}

const gi_method gi_ldm_method = {
    .name = "ldm",
    .shade = {"ldm/ldm_shade.glsl"},
    .create = create,
    .destroy = destroy,
    .reuse = reuse,
    .frame = frame,
    .eye_bind = eye_bind,
    .stats = stats,
    .objects = objects,
};
