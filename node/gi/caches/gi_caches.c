/* gi_caches: the caches method (gi_caches.h). Host: the caches, the grid, the view samples,
 * the exact variant's rays, the checksum. GL: shader storage buffers (bindings below) and
 * one compute program per stage; the interpolation draws into an RGBA32F texture. */
#include "gi/caches/gi_caches.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/fnv1a.h"
#include "base/xalloc.h"
#include "gi/caches/caches_exact.h"
#include "gl/gltools.h"
#include "gi/gi_reuse.h"
#include "gi/view_samples.h"
#include "gi/vpl_source.h"

/* Shader storage bindings (the shaders' binding = N). */
enum { B_CACHES = 0, B_PROXIES, B_VALS, B_PICKS, B_SUMS, B_ROW, B_SAMPLES, B_GRID, BUFFERS };
enum { STAGE_IMPORTANCE = 0, STAGE_SELECT, STAGE_PROXY, STAGE_OCCLUSION, STAGE_INTERPOLATE,
       STAGES };
static const char *const STAGE_NAMES[STAGES] = {"importance", "sat_select", "proxy", "occlusion",
                                                "interpolate"};
enum { P_IMPORTANCE = 0, P_COLUMNS, P_ROW, P_SELECT, P_PROXY, P_PROXY_ALL, P_OCCLUDE,
       P_PROXY_GLOSSY, P_PROXY_ALL_GLOSSY, P_OCCLUDE_GLOSSY, P_INTERP, P_INTERP_GLOSSY,
       PROGRAMS };
enum { TILE = 64 }; /* the compute shaders' local size */
/* VALs or caches one dispatch loops over (caches_proxy.comp: llvmpipe stops a shader loop
 * after 65535 iterations, and a GPU's watchdog a long dispatch). */
enum { CHUNK = 8192 };
/* Floats per cache in each part of B_PROXIES: the proxy (8), the running sums of the proxy
 * pass (12) and of the occlusion (1), rounded up to vec4s. The glossy part follows the
 * diffuse one, the same, its last vec4 the cache's lobe exponent (uploaded once). */
#define PROXY_VEC4S 6
#define TEXT_OF(x) #x
#define TEXT(x) TEXT_OF(x)
enum { PROXY_FLOATS = 4 * PROXY_VEC4S, PARTS = 2 };
/* the shaders' switch to the glossy proxies, and where their part starts (vec4s per cache) */
#define GLOSSY_DEFINES "#define GLOSSY 1\n#define GLOSSY_PART " TEXT(PROXY_VEC4S) "\n"

struct gi_caches {
    const gl_functions *gl;
    const scene *scene;
    caches_settings settings;  /* the last frame's */
    int threads;
    float head_to_eye[3];
    gi_reuse_state reuse;      /* the last frame's parameters */

    cache_set set;
    cache_grid grid;
    cache_store_report store;
    view_samples *viewer;
    caches_exact *exact;       /* made on the first exact frame */
    vpl *vals;                 /* the emitters, then the picks' VALs (read back) */
    size_t emitters, val_count;
    val_pick picks[CACHES_VALS_MAX];
    float pick_read[CACHES_VALS_MAX * 4]; /* the picks as the GPU wrote them */
    int pick_count;
    cache_proxy *proxies;      /* read back each frame (or computed here: exact) */
    cache_proxy *glossy;       /* the glossy proxies, as proxies (caches-glossy on) */
    float eye[3];              /* the viewer the glossy proxies were made for */
    uint8_t *hidden;           /* per cache: under another surface (caches_hidden()) */
    size_t hidden_count;
    uint64_t checksum;
    double ms[STAGES];
    gpu_timer *timer;          /* the renderer's: the stages' GPU time */
    int gpu_stage;             /* its running stage */
    gpu_checksum *sum;         /* the renderer's: the checksum of what stays on the GPU */

    GLuint program[PROGRAMS];
    GLuint buffer[BUFFERS];
    size_t sums_texels;        /* room in B_SUMS */
    int row_columns;           /* room in B_ROW */
    GLuint vao, fbo, irradiance, glossy_texture;
    int eye_w, eye_h;
};

static void release(gi_caches *c)
{
    const gl_functions *gl = c->gl;
    for (int i = 0; i < PROGRAMS; i++)
        if (c->program[i])
            gl->DeleteProgram(c->program[i]);
    for (int i = 0; i < BUFFERS; i++)
        if (c->buffer[i])
            gl->DeleteBuffers(1, &c->buffer[i]);
    if (c->irradiance)
        gl->DeleteTextures(1, &c->irradiance);
    if (c->glossy_texture)
        gl->DeleteTextures(1, &c->glossy_texture);
    if (c->fbo)
        gl->DeleteFramebuffers(1, &c->fbo);
    if (c->vao)
        gl->DeleteVertexArrays(1, &c->vao);
    cache_set_free(&c->set);
    cache_grid_free(&c->grid);
    view_samples_destroy(c->viewer);
    caches_exact_destroy(c->exact);
    free(c->vals);
    free(c->proxies);
    free(c->glossy);
    free(c->hidden);
}

/* A storage buffer of size bytes (data or zeros). */
static void buffer_data(const gl_functions *gl, GLuint b, size_t size, const void *data)
{
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    gl->BufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(size ? size : 16), data,
                   GL_DYNAMIC_DRAW);
}

static int programs(gi_caches *c, char *err, size_t errlen)
{
    const gl_functions *gl = c->gl;
    static const char *const comp[P_INTERP] = {
        "caches/caches_importance.comp", "caches/caches_sat_columns.comp",
        "caches/caches_sat_row.comp", "caches/caches_select.comp", "caches/caches_proxy.comp",
        "caches/caches_proxy.comp", "caches/caches_occlude.comp", "caches/caches_proxy.comp",
        "caches/caches_proxy.comp", "caches/caches_occlude.comp"};
    static const char *const defines[P_INTERP] = {
        [P_PROXY_ALL] = "#define ALL_TEXELS 1\n", [P_PROXY_GLOSSY] = GLOSSY_DEFINES,
        [P_PROXY_ALL_GLOSSY] = "#define ALL_TEXELS 1\n" GLOSSY_DEFINES,
        [P_OCCLUDE_GLOSSY] = GLOSSY_DEFINES};
    for (int i = 0; i < P_INTERP; i++) {
        const char *parts[2] = {"caches/caches_val.glsl", comp[i]};
        if (!(c->program[i] = gltools_compute_parts(gl, parts, 2, defines[i], err, errlen)))
            return -1;
    }
    for (int i = P_INTERP; i <= P_INTERP_GLOSSY; i++)
        if (!(c->program[i] = gltools_program(gl, "fullscreen.vert",
                                              "caches/caches_interpolate.frag", NULL,
                                              i == P_INTERP_GLOSSY ? GLOSSY_DEFINES : NULL,
                                              NULL, err, errlen)))
            return -1;
    return 0;
}

/* The caches, the grid and the emitters into their buffers (they never change). */
static void upload_static(gi_caches *c)
{
    const gl_functions *gl = c->gl;
    gl->GenBuffers(BUFFERS, c->buffer);
    size_t n = c->set.count;
    float *caches = xmalloc((n ? n : 1) * 8 * sizeof *caches);
    for (size_t i = 0; i < n; i++) {
        const light_cache *l = &c->set.caches[i];
        float *o = caches + 8 * i;
        memcpy(o, l->position, 3 * sizeof *o);
        o[3] = l->area;
        memcpy(o + 4, l->normal, 3 * sizeof *o);
        o[7] = c->hidden[i];
    }
    buffer_data(gl, c->buffer[B_CACHES], n * 8 * sizeof *caches, caches);
    free(caches);
    buffer_data(gl, c->buffer[B_PROXIES], n * PARTS * PROXY_FLOATS * sizeof(float), NULL);
    float *lobe = xcalloc(n ? n : 1, 4 * sizeof *lobe);
    for (size_t i = 0; i < n; i++)
        lobe[4 * i] = cache_specular_exponent(c->set.caches[i].roughness);
    /* the glossy part's last vec4 per cache */
    gl->BufferSubData(GL_SHADER_STORAGE_BUFFER,
                      (GLintptr)(n * (PARTS * PROXY_FLOATS - 4) * sizeof *lobe),
                      (GLsizeiptr)(n * 4 * sizeof *lobe), lobe);
    free(lobe);
    size_t cells = (size_t)c->grid.dims[0] * c->grid.dims[1] * c->grid.dims[2];
    uint32_t *grid = xmalloc((cells + 1 + c->grid.listed) * sizeof *grid);
    memcpy(grid, c->grid.first, (cells + 1) * sizeof *grid);
    memcpy(grid + cells + 1, c->grid.index, c->grid.listed * sizeof *grid);
    buffer_data(gl, c->buffer[B_GRID], (cells + 1 + c->grid.listed) * sizeof *grid, grid);
    free(grid);
    size_t vals = c->emitters + CACHES_VALS_MAX;
    float *v = xcalloc(vals * 12, sizeof *v);
    for (size_t i = 0; i < c->emitters; i++) {
        const vpl *e = &c->vals[i];
        float *o = v + 12 * i;
        memcpy(o, e->position, 3 * sizeof *o);
        o[3] = e->area;
        memcpy(o + 4, e->normal, 3 * sizeof *o);
        memcpy(o + 8, e->flux, 3 * sizeof *o);
    }
    buffer_data(gl, c->buffer[B_VALS], vals * 12 * sizeof *v, v);
    free(v);
    buffer_data(gl, c->buffer[B_PICKS], CACHES_VALS_MAX * 4 * sizeof(float), NULL);
    buffer_data(gl, c->buffer[B_SAMPLES], VIEW_SAMPLES_MAX * 8 * sizeof(float), NULL);
    for (int i = 0; i < BUFFERS; i++)
        gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)i, c->buffer[i]);
}

/* The caches of the scene (disk cache or placement), its grid and emitters. */
static int place(gi_caches *c, char *err, size_t errlen)
{
    const scene *s = c->scene;
    cache_place_desc pd = {.edge = cache_place_edge(s, c->settings.density),
                           .angle = c->settings.angle * 3.14159265f / 180.0f};
    char dir[512];
    int have_dir = cache_file_dir(dir, sizeof dir) == 0;
    if (cache_store_get(s, &pd, have_dir ? dir : NULL, &c->set, &c->store, err, errlen) != 0)
        return -1;
    if (c->store.note[0])
        fprintf(stderr, "cavelight-node: %s\n", c->store.note);
    if (cache_grid_build(&c->set, s->bounds_min, s->bounds_max, &c->grid, err, errlen) != 0)
        return -1;
    c->emitters = vpl_emitters(s, NULL);
    vpl_emitter *raw = xmalloc((c->emitters ? c->emitters : 1) * sizeof *raw);
    vpl_emitters(s, raw);
    c->vals = xmalloc((c->emitters + CACHES_VALS_MAX) * sizeof *c->vals);
    for (size_t i = 0; i < c->emitters; i++)
        c->vals[i] = vpl_from_emitter(&raw[i]);
    free(raw);
    c->proxies = xcalloc(c->set.count ? c->set.count : 1, sizeof *c->proxies);
    c->glossy = xcalloc(c->set.count ? c->set.count : 1, sizeof *c->glossy);
    c->hidden = xcalloc(c->set.count ? c->set.count : 1, 1);
    /* a quarter edge: what the placement keeps apart as two parallel surfaces */
    caches_hidden(view_samples_rt(c->viewer), c->set.caches, c->set.count, 0.25f * c->set.edge,
                  1e-4f * scene_diagonal(s), c->hidden);
    for (size_t i = 0; i < c->set.count; i++)
        c->hidden_count += c->hidden[i];
    return 0;
}

static void *create(const gi_desc *d, char *err, size_t errlen)
{
    gi_caches *c = xcalloc(1, sizeof *c);
    c->gl = d->gl;
    c->scene = d->scene;
    c->threads = d->threads;
    c->reuse.never = d->no_reuse;
    c->timer = d->timer;
    c->sum = d->sum;
    memcpy(c->head_to_eye, d->head_to_eye, sizeof c->head_to_eye);
    caches_settings_get(d->frame, &c->settings);
    if (!(c->viewer = view_samples_create(d->scene, VIEW_SAMPLES_MAX, err, errlen)) ||
        place(c, err, errlen) != 0 || programs(c, err, errlen) != 0) {
        release(c);
        free(c);
        return NULL;
    }
    upload_static(c);
    d->gl->GenVertexArrays(1, &c->vao);
    d->gl->GenFramebuffers(1, &c->fbo);
    return c;
}

static void destroy(void *state)
{
    release(state);
    free(state);
}

static int reuse(void *state, const frame_params *p)
{
    gi_caches *c = state;
    caches_settings now;
    caches_settings_get(p, &now);
    float eye[3], before[3];
    view_samples_viewer(p, c->head_to_eye, eye);
    view_samples_viewer(&c->reuse.last, c->head_to_eye, before);
    int same = gi_reuse_unchanged(&c->reuse, p, &now, &c->settings, sizeof now,
                                  (now.selection == CACHES_SELECT_ALL &&
                                   now.glossy == CACHES_GLOSSY_OFF) ||
                                  memcmp(eye, before, sizeof eye) == 0);
    if (same)
        memset(c->ms, 0, sizeof c->ms);
    return same;
}

static void use_program(gi_caches *c, int i)
{
    c->gl->UseProgram(c->program[i]);
}

static void uniform1i(gi_caches *c, int i, const char *name, int v)
{
    c->gl->Uniform1i(c->gl->GetUniformLocation(c->program[i], name), v);
}

/* The RSM maps on units 0..2 for program i. */
static void bind_rsm(gi_caches *c, int i, const gi_rsm *rsm)
{
    static const char *const names[3] = {"u_rsm_position", "u_rsm_normal", "u_rsm_flux"};
    const gl_functions *gl = c->gl;
    use_program(c, i);
    for (int k = 0; k < 3; k++) {
        gl->ActiveTexture((GLenum)(GL_TEXTURE0 + k));
        gl->BindTexture(GL_TEXTURE_2D_ARRAY, rsm->textures[k]);
        uniform1i(c, i, names[k], k);
    }
    uniform1i(c, i, "u_rsm_size", rsm->size);
}

/* Room for the tables of this frame's maps; every buffer bound to its binding (another
 * method or pass may have bound others there). */
static void reserve_tables(gi_caches *c, size_t texels, int columns)
{
    if (texels > c->sums_texels) {
        buffer_data(c->gl, c->buffer[B_SUMS], texels * 2 * sizeof(float), NULL);
        c->sums_texels = texels;
    }
    if (columns > c->row_columns) {
        buffer_data(c->gl, c->buffer[B_ROW], (size_t)columns * 2 * sizeof(float), NULL);
        c->row_columns = columns;
    }
    for (int i = 0; i < BUFFERS; i++)
        c->gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)i, c->buffer[i]);
}

/* The view samples from the head, uploaded; how many hit. */
static int upload_samples(gi_caches *c, const frame_params *p)
{
    float eye[3], v[VIEW_SAMPLES_MAX * 8];
    const float *s;
    view_samples_viewer(p, c->head_to_eye, eye);
    int n = view_samples_cast(c->viewer, eye, c->settings.view_samples, &s);
    for (int i = 0; i < n; i++) {
        memcpy(v + 8 * i, s + 6 * i, 3 * sizeof *v);
        v[8 * i + 3] = 0;
        memcpy(v + 8 * i + 4, s + 6 * i + 3, 3 * sizeof *v);
        v[8 * i + 7] = 0;
    }
    c->gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, c->buffer[B_SAMPLES]);
    c->gl->BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)(n * 8 * sizeof *v), v);
    return n;
}

/* A stage begins: its GPU time (gpu_timer.h) and the host's clock. */
static double start(gi_caches *c, int stage)
{
    c->gpu_stage = gpu_timer_begin(c->timer, STAGE_NAMES[stage]);
    return clock_now_ms();
}

/* A stage ends. GL is finished for its host ms only when the renderer measures every
 * frame (benchmarks): a node's frame never waits, its GPU time is the timer's. */
static double finish(gi_caches *c, double since)
{
    gpu_timer_end(c->timer, c->gpu_stage);
    c->gl->MemoryBarrier(GL_ALL_BARRIER_BITS);
    if (c->reuse.never)
        c->gl->Finish();
    return clock_now_ms() - since;
}

/* Stages importance and sat_select: caches-vals picks and their VALs on the GPU. */
static void select_vals(gi_caches *c, const frame_params *p, const gi_rsm *rsm)
{
    const gl_functions *gl = c->gl;
    int columns = rsm->layers * rsm->size, n = c->settings.vals;
    double t0 = start(c, STAGE_IMPORTANCE);
    reserve_tables(c, (size_t)columns * rsm->size, columns);
    int samples = upload_samples(c, p);
    bind_rsm(c, P_IMPORTANCE, rsm);
    uniform1i(c, P_IMPORTANCE, "u_samples", samples);
    gl->DispatchCompute((GLuint)(rsm->size + 7) / 8, (GLuint)(rsm->size + 7) / 8,
                        (GLuint)rsm->layers);
    c->ms[STAGE_IMPORTANCE] = finish(c, t0);
    double t1 = start(c, STAGE_SELECT);
    for (int i = P_COLUMNS; i <= P_ROW; i++) {
        use_program(c, i);
        uniform1i(c, i, "u_columns", columns);
        uniform1i(c, i, "u_rows", rsm->size);
        gl->MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        gl->DispatchCompute(i == P_COLUMNS ? (GLuint)(columns + TILE - 1) / TILE : 1, 1, 1);
    }
    bind_rsm(c, P_SELECT, rsm);
    uniform1i(c, P_SELECT, "u_slots", n);
    uniform1i(c, P_SELECT, "u_columns", columns);
    uniform1i(c, P_SELECT, "u_rows", rsm->size);
    uniform1i(c, P_SELECT, "u_first", (int)c->emitters);
    uniform1i(c, P_SELECT, "u_seed", c->settings.seed);
    gl->MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    gl->DispatchCompute((GLuint)(n + TILE - 1) / TILE, 1, 1);
    c->pick_count = n;
    c->val_count = c->emitters + (size_t)n;
    c->ms[STAGE_SELECT] = finish(c, t1);
}

/* The picks from the GPU into c->picks (tests, gi_caches_picks()): a frame does not read
 * them, the checksum is the GPU's. */
static void read_picks(gi_caches *c)
{
    float *picks = c->pick_read;
    c->gl->MemoryBarrier(GL_ALL_BARRIER_BITS);
    c->gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, c->buffer[B_PICKS]);
    c->gl->GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                            (GLsizeiptr)(c->pick_count * 4 * sizeof *picks), picks);
    for (int i = 0; i < c->pick_count; i++) {
        int32_t col, row;
        memcpy(&col, &picks[4 * i], 4);
        memcpy(&row, &picks[4 * i + 1], 4);
        c->picks[i] = (val_pick){col, row, picks[4 * i + 2]};
    }
}

/* The selected VALs from the GPU into c->vals after the emitters. */
static void read_vals(gi_caches *c)
{
    size_t n = c->val_count - c->emitters;
    float *v = xmalloc((n ? n : 1) * 12 * sizeof *v);
    c->gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, c->buffer[B_VALS]);
    c->gl->GetBufferSubData(GL_SHADER_STORAGE_BUFFER,
                            (GLintptr)(c->emitters * 12 * sizeof *v),
                            (GLsizeiptr)(n * 12 * sizeof *v), v);
    for (size_t i = 0; i < n; i++) {
        vpl *o = &c->vals[c->emitters + i];
        const float *f = v + 12 * i;
        memcpy(o->position, f, sizeof o->position);
        o->area = f[3];
        memcpy(o->normal, f + 4, sizeof o->normal);
        memcpy(o->flux, f + 8, sizeof o->flux);
    }
    free(v);
}

/* The proxies of part (0 diffuse, 1 glossy) of B_PROXIES: cache_proxy's 8 floats each. */
static GLintptr part_offset(const gi_caches *c, int part)
{
    return (GLintptr)((size_t)part * c->set.count * PROXY_FLOATS * sizeof(float));
}

static void upload_proxies(gi_caches *c, int part, const cache_proxy *proxies)
{
    size_t n = c->set.count;
    float *v = xmalloc((n ? n : 1) * 8 * sizeof *v);
    for (size_t i = 0; i < n; i++) {
        const cache_proxy *p = &proxies[i];
        memcpy(v + 8 * i, p->position, 3 * sizeof *v);
        v[8 * i + 3] = p->radius;
        memcpy(v + 8 * i + 4, p->irradiance, 3 * sizeof *v);
        v[8 * i + 7] = p->visibility;
    }
    c->gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, c->buffer[B_PROXIES]);
    c->gl->BufferSubData(GL_SHADER_STORAGE_BUFFER, part_offset(c, part),
                         (GLsizeiptr)(n * 8 * sizeof *v), v);
    free(v);
}

static void read_proxies(gi_caches *c, int part, cache_proxy *proxies)
{
    size_t n = c->set.count;
    float *v = xmalloc((n ? n : 1) * 8 * sizeof *v);
    c->gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, c->buffer[B_PROXIES]);
    c->gl->GetBufferSubData(GL_SHADER_STORAGE_BUFFER, part_offset(c, part),
                            (GLsizeiptr)(n * 8 * sizeof *v), v);
    for (size_t i = 0; i < n; i++) {
        cache_proxy *p = &proxies[i];
        memcpy(p->position, v + 8 * i, sizeof p->position);
        p->radius = v[8 * i + 3];
        memcpy(p->irradiance, v + 8 * i + 4, sizeof p->irradiance);
        p->visibility = v[8 * i + 7];
    }
    free(v);
}

/* Program prog over items [0, count) in chunks of CHUNK, one dispatch each (u_begin,
 * u_end, u_last), a thread per cache. */
static void dispatch_chunks(gi_caches *c, int prog, int count)
{
    GLuint groups = (GLuint)(c->set.count + TILE - 1) / TILE;
    for (int begin = 0; groups && (begin < count || begin == 0); begin += CHUNK) {
        int end = count - begin > CHUNK ? begin + CHUNK : count;
        uniform1i(c, prog, "u_begin", begin);
        uniform1i(c, prog, "u_end", end);
        uniform1i(c, prog, "u_last", end == count);
        c->gl->MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        c->gl->DispatchCompute(groups, 1, 1);
    }
}

/* Stages proxy and occlusion on the GPU (exact occlusion with every texel, which the
 * settings' check refuses, is approximated). */
static void gpu_proxies(gi_caches *c, const gi_rsm *rsm)
{
    int all = c->settings.selection == CACHES_SELECT_ALL;
    int glossy = c->settings.glossy == CACHES_GLOSSY_ON;
    int prog = glossy ? (all ? P_PROXY_ALL_GLOSSY : P_PROXY_GLOSSY) : all ? P_PROXY_ALL : P_PROXY;
    int occlude = glossy ? P_OCCLUDE_GLOSSY : P_OCCLUDE;
    int texels = rsm->layers * rsm->size * rsm->size;
    double t0 = start(c, STAGE_PROXY);
    bind_rsm(c, prog, rsm);
    if (glossy)
        c->gl->Uniform3fv(c->gl->GetUniformLocation(c->program[prog], "u_eye"), 1, c->eye);
    uniform1i(c, prog, "u_caches", (int)c->set.count);
    uniform1i(c, prog, "u_vals", (int)(all ? c->emitters : c->val_count));
    uniform1i(c, prog, "u_texels", texels);
    dispatch_chunks(c, prog, (int)(all ? c->emitters + (size_t)texels : c->val_count));
    c->ms[STAGE_PROXY] = finish(c, t0);
    double t1 = start(c, STAGE_OCCLUSION);
    if (c->settings.occlusion != CACHES_OCCLUSION_OFF) {
        use_program(c, occlude);
        uniform1i(c, occlude, "u_caches", (int)c->set.count);
        dispatch_chunks(c, occlude, (int)c->set.count);
    }
    c->ms[STAGE_OCCLUSION] = finish(c, t1);
}

/* Stages proxy and occlusion on the host, a ray from every cache to every VAL. */
static void exact_proxies(gi_caches *c)
{
    if (!c->exact)
        c->exact = caches_exact_create(view_samples_rt(c->viewer), c->threads,
                                       1e-4f * scene_diagonal(c->scene));
    read_vals(c);
    int glossy = c->settings.glossy == CACHES_GLOSSY_ON;
    caches_exact_glossy g = {c->eye, c->glossy};
    if (!c->exact || caches_exact_proxies(c->exact, c->set.caches, c->set.count, c->vals,
                                          c->val_count, glossy ? &g : NULL, c->proxies,
                                          &c->ms[STAGE_OCCLUSION], &c->ms[STAGE_PROXY]) != 0) {
        fprintf(stderr, "cavelight-node: light caches: out of memory for the exact "
                "occlusion's rays: no indirect light this frame\n");
        memset(c->proxies, 0, c->set.count * sizeof *c->proxies);
        memset(c->glossy, 0, c->set.count * sizeof *c->glossy);
    }
    upload_proxies(c, 0, c->proxies);
    if (glossy)
        upload_proxies(c, 1, c->glossy);
}

static uint64_t frame(void *state, const frame_params *p, const gi_rsm *rsm)
{
    gi_caches *c = state;
    memset(c->ms, 0, sizeof c->ms);
    c->pick_count = 0;
    c->val_count = c->emitters;
    int glossy = c->settings.glossy == CACHES_GLOSSY_ON;
    view_samples_viewer(p, c->head_to_eye, c->eye);
    int importance = c->settings.selection == CACHES_SELECT_IMPORTANCE && rsm->layers > 0;
    if (importance)
        select_vals(c, p, rsm);
    if (c->settings.occlusion == CACHES_OCCLUSION_EXACT && importance)
        exact_proxies(c);
    else
        gpu_proxies(c, rsm);
    /* The checksum READY carries: the picks and the proxies (cache_proxy's 8 floats of
     * each, the glossy ones too when on), hashed on the GPU (gpu_checksum.h). */
    gpu_checksum_add(c->sum, c->buffer[B_PICKS], 0, (size_t)c->pick_count, 4, 4);
    for (int part = 0; part < 1 + glossy; part++)
        gpu_checksum_add(c->sum, c->buffer[B_PROXIES], (size_t)part_offset(c, part) / sizeof(float),
                         c->set.count, 8, PROXY_FLOATS);
    return c->checksum = FNV1A64_OFFSET; /* no host part */
}

/* The irradiance texture at the eye's size, and the glossy one when glossy. */
static void reserve_eye(gi_caches *c, int w, int h, int glossy)
{
    if (w != c->eye_w || h != c->eye_h) {
        GLuint old[2] = {c->irradiance, c->glossy_texture};
        c->gl->DeleteTextures(2, old);
        c->irradiance = gltools_texture2d(c->gl, GL_RGBA32F, w, h, GL_NEAREST);
        c->glossy_texture = 0;
        c->eye_w = w;
        c->eye_h = h;
    }
    if (glossy && !c->glossy_texture)
        c->glossy_texture = gltools_texture2d(c->gl, GL_RGBA32F, w, h, GL_NEAREST);
}

/* The interpolation program's uniforms (the grid's, the eye's). */
static void interpolate_uniforms(gi_caches *c, GLuint prog, const gi_eye *e)
{
    const gl_functions *gl = c->gl;
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_position"), 0);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_normal"), 1);
    const cache_grid *g = &c->grid;
    gl->Uniform3fv(gl->GetUniformLocation(prog, "u_grid_origin"), 1, g->origin);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_grid_cell"), g->cell);
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_grid_dims"), g->dims[0], g->dims[1], g->dims[2]);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_grid_cells"), g->dims[0] * g->dims[1] * g->dims[2]);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_caches"), (int)c->set.count);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_reach"), g->reach);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_plane_weight"), CACHE_PLANE_WEIGHT);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_min_cos"), CACHE_PROXY_MIN_COS);
    gl->Uniform4fv(gl->GetUniformLocation(prog, "u_eye"), 1, e->eye);
}

static void eye_bind(void *state, const gi_eye *e)
{
    gi_caches *c = state;
    const gl_functions *gl = c->gl;
    double t0 = start(c, STAGE_INTERPOLATE);
    gltools_draw_state outer;
    gltools_draw_state_save(gl, &outer);
    int glossy = c->settings.glossy == CACHES_GLOSSY_ON;
    reserve_eye(c, e->width, e->height, glossy);
    GLuint prog = c->program[glossy ? P_INTERP_GLOSSY : P_INTERP];
    gl->UseProgram(prog);
    for (int i = 0; i < BUFFERS; i++)
        gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)i, c->buffer[i]);
    interpolate_uniforms(c, prog, e);
    gl->BindFramebuffer(GL_FRAMEBUFFER, c->fbo);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, c->irradiance, 0);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, glossy ? c->glossy_texture : 0, 0);
    const GLenum color[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    gl->DrawBuffers(glossy ? 2 : 1, color);
    gl->Viewport(0, 0, e->width, e->height);
    gl->BindVertexArray(c->vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    gltools_draw_state_restore(gl, &outer, e->program);
    gl->ActiveTexture((GLenum)(GL_TEXTURE0 + e->first_unit));
    gl->BindTexture(GL_TEXTURE_2D, c->irradiance);
    gl->Uniform1i(gl->GetUniformLocation(e->program, "u_caches_irradiance"), e->first_unit);
    gl->Uniform1i(gl->GetUniformLocation(e->program, "u_caches_glossy_on"), glossy);
    /* a unit of the method's even when off: no other sampler type may share it */
    gl->Uniform1i(gl->GetUniformLocation(e->program, "u_caches_glossy"), e->first_unit + 1);
    if (glossy) {
        gl->ActiveTexture((GLenum)(GL_TEXTURE0 + e->first_unit + 1));
        gl->BindTexture(GL_TEXTURE_2D, c->glossy_texture);
    }
    c->ms[STAGE_INTERPOLATE] = finish(c, t0);
}

static void stats(const void *state, gi_stats *out)
{
    const gi_caches *c = state;
    out->stage_count = STAGES;
    for (int i = 0; i < STAGES; i++)
        out->stage[i] = (gi_stat){STAGE_NAMES[i], c->ms[i]};
    /* a cache, its diffuse and glossy proxies (the glossy ones are kept even when off) */
    size_t cache_bytes = c->set.count * (sizeof(light_cache) + 2 * sizeof(cache_proxy));
    size_t bytes = 2 * (cache_bytes + cache_grid_bytes(&c->grid)); /* host and GPU copies */
    const gi_stat figures[] = {
        {"caches", (double)c->set.count},
        {"hidden_caches", (double)c->hidden_count},
        {"vals", (double)(c->settings.selection == CACHES_SELECT_ALL ? 0 : c->val_count)},
        {"cache_kb", (double)bytes / 1024.0},
        {"placement_ms", c->store.ms},
        {"cache_file", (double)c->store.from_file},
        {"reach_m", c->grid.reach},
        {"longest_list", (double)c->grid.longest},
    };
    out->figure_count = (int)(sizeof figures / sizeof figures[0]);
    memcpy(out->figure, figures, sizeof figures);
}

gi_caches *gi_caches_of(gi *g)
{
    return g && gi_active(g) == GI_METHOD_ID(caches) ? gi_state(g) : NULL;
}

const cache_set *gi_caches_set(const gi_caches *c) { return &c->set; }
const cache_grid *gi_caches_grid(const gi_caches *c) { return &c->grid; }
const cache_store_report *gi_caches_store(const gi_caches *c) { return &c->store; }
const cache_proxy *gi_caches_proxies(gi_caches *c)
{
    read_proxies(c, 0, c->proxies);
    return c->proxies;
}

const cache_proxy *gi_caches_glossy(gi_caches *c)
{
    read_proxies(c, 1, c->glossy);
    return c->glossy;
}
const float *gi_caches_viewer(const gi_caches *c) { return c->eye; }
const uint8_t *gi_caches_hidden(const gi_caches *c) { return c->hidden; }

int gi_caches_picks(gi_caches *c, const val_pick **picks)
{
    read_picks(c);
    *picks = c->picks;
    return c->pick_count;
}

size_t gi_caches_vals(gi_caches *c, const vpl **vals)
{
    read_vals(c);
    *vals = c->vals;
    return c->val_count;
}

const gi_method gi_caches_method = {
    .name = "caches",
    .shade = {"caches/caches_shade.glsl"},
    .glossy = 1,
    .create = create,
    .destroy = destroy,
    .reuse = reuse,
    .frame = frame,
    .eye_bind = eye_bind,
    .stats = stats,
};
