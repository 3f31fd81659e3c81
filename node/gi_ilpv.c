/* gi_ilpv: the ILPV method (gi_ilpv.h). The VPLs of the source every light type feeds
 * (renderer_rsm_vpls(), in texel order, so the injection is deterministic) are injected
 * with the CPU core, then propagated as a chain of ages (ilpv.h) either by the CPU core
 * or by GL compute shaders.
 *
 * Units: an RSM texel holds the flux Phi it reflects (W). A Lambertian VPL of flux Phi
 * has radiant intensity Phi/pi cos(theta); lpv_inject adds flux * SH_cos(n), so we pass
 * Phi/pi and the lattice holds radiant intensity (W/sr) per cell, whose energy <L|1> is
 * Phi. The shading divides by the cell area to get radiance (docs/node.md).
 *
 * Classic mode (lpv_classic.h) uses the same injection and propagation; the GL backend adds
 * each step into three accumulation textures (shaders/accumulate.comp). In both modes a
 * frame whose inputs are unchanged and whose result has converged is skipped
 * (lpv_converge.h); the residual is computed on the host from the result the checksum is
 * taken of, so every node decides alike. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/fpmode.h"
#include "base/vec3.h"
#include "lpv/lpv_geometry.h"
#include "base/workpool.h"
#include "base/xalloc.h"
#include "frame/light_view.h"
#include "gi/vpl_source.h"
#include "gi_ilpv.h"
#include "gltools.h"
#include "lpv/ilpv.h"
#include "lpv/lpv_classic.h"
#include "lpv/lpv_converge.h"
#include "lpv/lpv_inject.h"
#include "lpv/lpv_transfer.h"

struct gi_ilpv {
    const gl_functions *gl;
    const scene *scene;
    renderer_lpv_backend backend;
    int gl_tiles;            /* GL propagation through shared-memory tiles */
    lattice_desc lattice;
    lpv_blockers blockers;   /* built once from the scene (lpv_geometry.h) */
    ilpv cpu;                /* incremental mode; its injection, splat and near/shell volumes
                                serve every mode and backend */
    renderer_lpv_mode mode;
    lpv_classic classic;     /* classic mode, CPU backend */
    lpv_converge converge;
    uint64_t checksum;       /* of the last computed result */
    workpool *pool;
    lpv_vpl *vpls;           /* what the LPV injects: RSM VPLs (flux / pi) and emitters */
    size_t vpl_capacity;
    lpv_vpl *emitters;       /* one VPL per emissive triangle, built at load */
    size_t emitter_count;
    double emitter_energy;
    float *upload;           /* 4 floats per cell, one colour at a time */
    GLuint lpv_tex[3];       /* what the shading samples (CPU backend) */
    uint32_t reset_epoch;
    int frames;
    lpv_inject_stats inject_stats;
    gi_stats timings;        /* inject_ms, propagate_ms of the last frame */

    /* GL compute backend */
    GLuint prog_propagate, prog_accumulate;
    GLuint gl_near[3], gl_shell[3], gl_front[2][3], gl_blockers;
    GLuint gl_sum[3];        /* near + the chain's ages so far (classic: this frame's) */
    GLuint gl_result[3];     /* sum + w faded, composed on the host: what the shading samples */
    int gl_current;
    ilpv_history gl_history; /* the GL path's own history (ilpv_history_rule()) */
    lpv_volume gl_readback;  /* the GL path's result on the host (read back or composed) */
};

static const double PI = 3.14159265358979323846;

/* One VPL per emissive triangle (paper 3.3.5, gi/vpl_source.h), flux pi * L_e * area
 * passed as L_e * area (see the units above). */
static int build_emitters(gi_ilpv *r)
{
    size_t n = vpl_emitters(r->scene, NULL);
    vpl_emitter *e = n ? malloc(n * sizeof *e) : NULL;
    r->emitters = n ? malloc(n * sizeof *r->emitters) : NULL;
    if (n && (!e || !r->emitters)) {
        free(e);
        return -1;
    }
    vpl_emitters(r->scene, e);
    r->emitter_count = n;
    r->emitter_energy = 0;
    for (size_t i = 0; i < n; i++) {
        lpv_vpl *v = &r->emitters[i];
        for (int k = 0; k < 3; k++) {
            v->position[k] = e[i].position[k];
            v->normal[k] = e[i].normal[k];
            v->flux[k] = e[i].radiance[k] * e[i].area;
        }
        r->emitter_energy +=
            PI * e[i].area * (e[i].radiance[0] + e[i].radiance[1] + e[i].radiance[2]) / 3.0;
    }
    free(e);
    return 0;
}

/* The propagation shader's body: the 27 targets with constant offsets (uniform arrays
 * indexed in a loop are very slow on llvmpipe), the cell itself as neighbour 26. */
static void gather_body(char *out, size_t n)
{
    size_t used = 0;
    for (int k = 0; k <= LPV_NEIGHBOURS && used < n; k++) {
        const int zero[3] = {0, 0, 0}, *o = k < LPV_NEIGHBOURS ? lpv_transfer_offsets[k] : zero;
        used += (size_t)snprintf(out + used, n - used,
                                 "    gather(here, cell, ivec3(%d, %d, %d), %d, ar, ag, ab);\n",
                                 o[0], o[1], o[2], k);
    }
}

/* Host SoA volume <-> three RGBA textures (one per colour, 4 SH coefficients each). */
static void upload_volume(gi_ilpv *r, const lpv_volume *v, const GLuint tex[3])
{
    const gl_functions *gl = r->gl;
    for (int c = 0; c < 3; c++) {
        for (size_t i = 0; i < v->cells; i++)
            for (int s = 0; s < 4; s++)
                r->upload[4 * i + s] = v->ch[4 * c + s][i];
        gl->BindTexture(GL_TEXTURE_3D, tex[c]);
        gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl->TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, v->n[0], v->n[1], v->n[2], GL_RGBA,
                          GL_FLOAT, r->upload);
    }
}

static void download_volume(gi_ilpv *r, const GLuint tex[3], lpv_volume *v)
{
    const gl_functions *gl = r->gl;
    for (int c = 0; c < 3; c++) {
        gl->BindTexture(GL_TEXTURE_3D, tex[c]);
        gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
        gl->GetTexImage(GL_TEXTURE_3D, 0, GL_RGBA, GL_FLOAT, r->upload);
        for (size_t i = 0; i < v->cells; i++)
            for (int s = 0; s < 4; s++)
                v->ch[4 * c + s][i] = r->upload[4 * i + s];
    }
}

/* The blockers as one 32-bit unsigned word per cell. */
static GLuint blockers_texture(gi_ilpv *r)
{
    const gl_functions *gl = r->gl;
    const int *n = r->lattice.n;
    GLuint t;
    gl->GenTextures(1, &t);
    gl->BindTexture(GL_TEXTURE_3D, t);
    gl->TexStorage3D(GL_TEXTURE_3D, 1, GL_R32UI, n[0], n[1], n[2]);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, n[0], n[1], n[2], GL_RED_INTEGER,
                      GL_UNSIGNED_INT, r->blockers.mask);
    return t;
}

static int init_gl_backend(gi_ilpv *r, int software, const renderer_desc *desc, char *err,
                           size_t errlen)
{
    char body[4096];
    gather_body(body, sizeof body);
    r->gl_tiles = desc->lpv_gl_tiles == RENDERER_TILES_AUTO ? !software
                                                            : desc->lpv_gl_tiles == RENDERER_TILES_ON;
    r->prog_propagate = gltools_program(r->gl, NULL, NULL, "propagate.comp",
                                         r->gl_tiles ? "#define LPV_TILES 1\n" : NULL, body,
                                         err, errlen);
    r->prog_accumulate = r->prog_propagate ? gltools_program(r->gl, NULL, NULL, "accumulate.comp",
                                                              NULL, NULL, err, errlen)
                                           : 0;
    if (!r->prog_accumulate)
        return -1;
    if (lpv_volume_init(&r->gl_readback, r->lattice.n, LPV_LIGHT_CHANNELS) != 0) {
        snprintf(err, errlen, "renderer: out of memory for the LPV readback");
        return -1;
    }
    GLuint *all[] = {r->gl_near, r->gl_shell, r->gl_front[0], r->gl_front[1], r->gl_sum,
                     r->gl_result};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) {
        for (int c = 0; c < 3; c++)
            all[i][c] = gltools_texture3d(r->gl, r->lattice.n);
        upload_volume(r, &r->gl_readback, all[i]); /* defined contents: zeros */
    }
    r->gl_blockers = blockers_texture(r);
    return 0;
}

static int init(gi_ilpv *r, const renderer_desc *desc, int software, char *err, size_t errlen)
{
    const scene *s = r->scene;
    r->backend = desc->lpv_backend != RENDERER_LPV_AUTO
                     ? desc->lpv_backend
                     : (software ? RENDERER_LPV_CPU : RENDERER_LPV_GL);
    r->mode = desc->lpv_mode == RENDERER_LPV_CLASSIC ? RENDERER_LPV_CLASSIC
                                                      : RENDERER_LPV_INCREMENTAL;
    lattice_fit_desc fit = {
        .bounds_min = {s->bounds_min[0], s->bounds_min[1], s->bounds_min[2]},
        .bounds_max = {s->bounds_max[0], s->bounds_max[1], s->bounds_max[2]},
        .max_axis_cells = desc->lattice_cell_budget > 0 ? 1024 : desc->lattice_cells,
        .max_cells = desc->lattice_cell_budget > 0 ? desc->lattice_cell_budget : 0,
        .margin_cells = -1.0f,
    };
    char why[160];
    if (lattice_fit(&fit, &r->lattice, why, sizeof why) != 0) {
        snprintf(err, errlen, "renderer: no light lattice for this scene: %s", why);
        return -1;
    }
    /* Static scene: the blockers are built once, here. */
    if (lpv_blockers_init(&r->blockers, r->lattice.n) != 0 || ilpv_init(&r->cpu, &r->lattice) != 0 ||
        build_emitters(r) != 0 ||
        lpv_converge_init(&r->converge, r->lattice.n, desc->converge_threshold) != 0 ||
        (r->mode == RENDERER_LPV_CLASSIC && r->backend == RENDERER_LPV_CPU &&
         lpv_classic_init(&r->classic, &r->lattice) != 0)) {
        snprintf(err, errlen, "renderer: out of memory for a %dx%dx%d lattice",
                 r->lattice.n[0], r->lattice.n[1], r->lattice.n[2]);
        return -1;
    }
    lpv_geometry_add_triangles(&r->blockers, &r->lattice, s->positions, 3 * s->triangle_count,
                               NULL, s->triangle_count, NULL);
    size_t cells = lattice_cell_count(&r->lattice);
    r->upload = malloc(cells * 4 * sizeof(float));
    r->pool = workpool_create(desc->threads);
    if (!r->upload || !r->pool) {
        snprintf(err, errlen, "renderer: out of memory for the LPV upload");
        return -1;
    }
    if (r->backend == RENDERER_LPV_GL)
        return init_gl_backend(r, software, desc, err, errlen);
    for (int c = 0; c < 3; c++)
        r->lpv_tex[c] = gltools_texture3d(r->gl, r->lattice.n);
    return 0;
}

static void release(gi_ilpv *r)
{
    const gl_functions *gl = r->gl;
    for (int c = 0; c < 3; c++) {
        GLuint t[7] = {r->lpv_tex[c],     r->gl_near[c], r->gl_shell[c], r->gl_front[0][c],
                       r->gl_front[1][c], r->gl_sum[c],  r->gl_result[c]};
        for (int i = 0; i < 7; i++)
            if (t[i])
                gl->DeleteTextures(1, &t[i]);
    }
    if (r->gl_blockers)
        gl->DeleteTextures(1, &r->gl_blockers);
    if (r->prog_propagate)
        gl->DeleteProgram(r->prog_propagate);
    if (r->prog_accumulate)
        gl->DeleteProgram(r->prog_accumulate);
    if (r->pool)
        workpool_destroy(r->pool);
    if (r->gl_readback.cells)
        lpv_volume_free(&r->gl_readback);
    if (r->cpu.injected.cells)
        ilpv_free(&r->cpu);
    if (r->classic.accum.cells)
        lpv_classic_free(&r->classic);
    if (r->converge.previous.cells)
        lpv_converge_free(&r->converge);
    lpv_blockers_free(&r->blockers);
    free(r->emitters);
    free(r->vpls);
    free(r->upload);
}

static void textures(const gi_ilpv *r, GLuint out[3])
{
    for (int c = 0; c < 3; c++)
        out[c] = r->backend != RENDERER_LPV_GL       ? r->lpv_tex[c]
                 : r->mode == RENDERER_LPV_CLASSIC ? r->gl_sum[c]
                                                   : r->gl_result[c];
}

/* The shared VPL source (renderer_rsm_vpls()) as the lattice wants it, Phi / pi (the units
 * above), then the emitters. NULL when out of memory (the frame injects nothing). */
static const lpv_vpl *collect_vpls(gi_ilpv *r, const gi_rsm *rsm, size_t *count)
{
    lpv_vpl *source;
    size_t n = renderer_rsm_vpls(rsm->maps, &source), need = n + r->emitter_count;
    if (need > r->vpl_capacity) {
        lpv_vpl *v = realloc(r->vpls, need * sizeof *v);
        if (!v) {
            *count = 0;
            return NULL;
        }
        r->vpls = v;
        r->vpl_capacity = need;
    }
    for (size_t i = 0; i < n; i++) {
        r->vpls[i] = source[i];
        for (int k = 0; k < 3; k++)
            r->vpls[i].flux[k] = source[i].flux[k] * (float)(1.0 / PI);
    }
    if (r->emitter_count) /* a scene without emitters has no emitter array */
        memcpy(r->vpls + n, r->emitters, r->emitter_count * sizeof *r->emitters);
    *count = need;
    return r->vpls;
}

/* Emitted energy for the incremental merge, from the lights' parameters (paper 3.4). */
static double emitted_energy(const gi_ilpv *r, const frame_params *p)
{
    double e = r->emitter_energy;
    for (int i = 0; i < p->light_count && i < FRAME_MAX_LIGHTS; i++)
        e += light_power(&p->lights[i], r->scene);
    return e;
}

static void dispatch(gi_ilpv *r)
{
    const gl_functions *gl = r->gl;
    const int *n = r->lattice.n;
    gl->DispatchCompute((GLuint)(n[0] + 3) / 4, (GLuint)(n[1] + 3) / 4, (GLuint)(n[2] + 3) / 4);
    gl->MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                      GL_TEXTURE_UPDATE_BARRIER_BIT);
}

static void bind_images(gi_ilpv *r, const GLuint *tex, int count, int first, GLenum access)
{
    for (int i = 0; i < count; i++)
        r->gl->BindImageTexture((GLuint)(first + i), tex[i], 0, GL_TRUE, 0, access, GL_RGBA32F);
}

/* Three 3D textures (R, G, B) on texture units unit .. unit + 2 as prog's name_r/g/b. */
static void bind_samplers(gi_ilpv *r, GLuint prog, const char *name, const GLuint tex[3],
                          int unit)
{
    const gl_functions *gl = r->gl;
    static const char suffix[3] = {'r', 'g', 'b'};
    for (int c = 0; c < 3; c++) {
        char uname[32];
        snprintf(uname, sizeof uname, "%s_%c", name, suffix[c]);
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)(unit + c));
        gl->BindTexture(GL_TEXTURE_3D, tex[c]);
        gl->Uniform1i(gl->GetUniformLocation(prog, uname), unit + c);
    }
}

/* One step src -> dst (lpv_propagate_step()), also added into accum when not NULL. */
static void gl_step(gi_ilpv *r, const GLuint src[3], const GLuint dst[3], const GLuint *accum,
                    float absorption, float scattering, unsigned step)
{
    const gl_functions *gl = r->gl;
    const int *n = r->lattice.n;
    GLuint prog = r->prog_propagate;
    gl->UseProgram(prog);
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_size"), n[0], n[1], n[2]);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_use_accum"), accum != NULL);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_use_blockers"), 1);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_keep"), 1.0f - absorption);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_keep_flux"),
                  (1.0f - absorption) * (1.0f - scattering));
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_step_odd"), (int)(step & 1u));
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_step_axis"), (int)(step % 3u));
    bind_samplers(r, prog, "u_src", src, 0);
    gl->ActiveTexture(GL_TEXTURE6);
    gl->BindTexture(GL_TEXTURE_3D, r->gl_blockers);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_blockers"), 6);
    bind_images(r, dst, 3, 0, GL_WRITE_ONLY);
    bind_images(r, accum ? accum : dst, 3, 3, GL_READ_WRITE);
    dispatch(r);
}

/* dst = a dst + b src (shaders/accumulate.comp); a = 0 leaves dst unread, b = 0 src. */
static void gl_combine(gi_ilpv *r, const GLuint dst[3], float a, const GLuint src[3], float b)
{
    const gl_functions *gl = r->gl;
    const int *n = r->lattice.n;
    GLuint prog = r->prog_accumulate;
    gl->UseProgram(prog);
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_size"), n[0], n[1], n[2]);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_a"), a);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_b"), b);
    bind_samplers(r, prog, "u_src", src, 0);
    bind_images(r, dst, 3, 0, GL_READ_WRITE);
    dispatch(r);
}

/* The splat on the host (both backends inject there), uploaded; a chain starts: front =
 * shell, sum = near + shell. */
static void gl_start_chain(gi_ilpv *r, float absorption)
{
    lpv_splat_desc sd = {ilpv_injection(&r->cpu), ilpv_origin(&r->cpu), &r->blockers, absorption,
                         r->pool};
    lpv_splat_run(&r->cpu.splat, &sd, &r->cpu.near, &r->cpu.shell);
    upload_volume(r, &r->cpu.near, r->gl_near);
    upload_volume(r, &r->cpu.shell, r->gl_shell);
    gl_combine(r, r->gl_front[0], 0.0f, r->gl_shell, 1.0f);
    gl_combine(r, r->gl_sum, 0.0f, r->gl_near, 1.0f);
    gl_combine(r, r->gl_sum, 1.0f, r->gl_shell, 1.0f);
    r->gl_current = 0;
}

static void gl_steps(gi_ilpv *r, int steps, unsigned first, float absorption,
                     float scattering)
{
    for (int step = 0; step < steps; step++) {
        int dst = 1 - r->gl_current;
        gl_step(r, r->gl_front[r->gl_current], r->gl_front[dst], r->gl_sum, absorption,
                scattering, first + (unsigned)step);
        r->gl_current = dst;
    }
}

/* lpv_classic_frame() on the GPU: a new chain every frame; the result is its sum. */
static void gl_classic_frame(gi_ilpv *r, const frame_params *p, float absorption,
                             float scattering)
{
    gl_start_chain(r, absorption);
    gl_steps(r, p->lpv_steps, 0u, absorption, scattering);
    download_volume(r, r->gl_sum, &r->gl_readback);
}

/* ilpv_frame() on the GPU; the result is composed on the host from the chain's sum (read
 * back for the checksum anyway) and the faded light, and uploaded for the shading. */
static void gl_frame(gi_ilpv *r, const frame_params *p, uint64_t key, double energy,
                     float absorption, float scattering)
{
    ilpv_rule rule = ilpv_history_rule(&r->gl_history, p->lambda_incr, key, energy);
    double faded_energy = r->gl_history.faded_energy;
    lpv_volume *sum = &r->cpu.sum, *result = &r->gl_readback;
    if (rule.restart) {
        faded_energy = ilpv_fade(rule, result, &r->cpu.early, &r->cpu.faded);
        gl_start_chain(r, absorption);
    }
    gl_steps(r, p->lpv_steps, rule.restart ? 0u : r->gl_history.chain_steps, absorption,
             scattering);
    ilpv_history_advance(&r->gl_history, rule, p->lpv_steps, key, energy, faded_energy);
    download_volume(r, r->gl_sum, sum);
    ilpv_compose(&r->gl_history, rule, p->lambda_incr, sum, &r->cpu.early, &r->cpu.faded,
                 result);
    upload_volume(r, result, r->gl_result);
}

static uint64_t frame(void *state, const frame_params *p, const gi_rsm *rsm)
{
    gi_ilpv *r = state;
    if (r->frames == 0 || p->reset_epoch != r->reset_epoch) {
        ilpv_reset(&r->cpu);
        r->gl_history = (ilpv_history){0};
        r->reset_epoch = p->reset_epoch;
    }
    double t0 = clock_now_ms();
    size_t count;
    const lpv_vpl *vpls = collect_vpls(r, rsm, &count);
    ilpv_begin_frame(&r->cpu);
    memset(&r->inject_stats, 0, sizeof r->inject_stats);
    lpv_inject_vpls(ilpv_injection(&r->cpu), ilpv_origin(&r->cpu), &r->lattice, vpls, count,
                    &r->inject_stats);
    double t1 = clock_now_ms();
    double energy = emitted_energy(r, p);
    float la = lpv_transfer_step_probability(p->absorption, r->lattice.cell);
    float ls = lpv_transfer_step_probability(p->scattering, r->lattice.cell);
    lpv_propagate_desc pd = {.blockers = &r->blockers, .absorption = la, .scattering = ls,
                             .pool = r->pool};
    if (r->backend == RENDERER_LPV_GL && r->mode == RENDERER_LPV_CLASSIC)
        gl_classic_frame(r, p, la, ls);
    else if (r->backend == RENDERER_LPV_GL)
        gl_frame(r, p, ilpv_injection_key(ilpv_injection(&r->cpu), ilpv_origin(&r->cpu), la, ls),
                 energy, la, ls);
    else if (r->mode == RENDERER_LPV_CLASSIC)
        lpv_classic_frame(&r->classic, ilpv_injection(&r->cpu), ilpv_origin(&r->cpu),
                          p->lpv_steps, &pd);
    else
        ilpv_frame(&r->cpu, &(ilpv_frame_desc){.steps = p->lpv_steps,
                                               .lambda_incr = p->lambda_incr,
                                               .emitted_energy = energy,
                                               .propagate = pd});
    const lpv_volume *result = gi_ilpv_volume(r);
    r->checksum = lpv_volume_checksum(result);
    if (r->backend != RENDERER_LPV_GL)
        upload_volume(r, result, r->lpv_tex);
    double pending = r->mode == RENDERER_LPV_CLASSIC ? 0.0
                     : r->backend == RENDERER_LPV_GL ? r->gl_history.pending
                                                     : ilpv_pending(&r->cpu);
    lpv_converge_end(&r->converge, result, pending, r->pool);
    r->timings.inject_ms = t1 - t0;
    r->timings.propagate_ms = clock_now_ms() - t1;
    r->frames++;
    return r->checksum;
}

static int reuse(void *state, const frame_params *p)
{
    gi_ilpv *r = state;
    return lpv_converge_begin(&r->converge, p);
}

const lpv_volume *gi_ilpv_volume(const gi_ilpv *r)
{
    if (r->backend == RENDERER_LPV_GL)
        return &r->gl_readback;
    return r->mode == RENDERER_LPV_CLASSIC ? lpv_classic_result(&r->classic) : ilpv_result(&r->cpu);
}

renderer_lpv_mode gi_ilpv_mode(const gi_ilpv *r)
{
    return r->mode;
}

void gi_ilpv_lpv_stats(const gi_ilpv *r, renderer_lpv_stats *out)
{
    out->frames_skipped = r->converge.frames_skipped;
    out->last_residual = r->converge.residual;
    out->skipped_this_frame = r->converge.skipped;
    lpv_volume_energy(&r->cpu.injected, out->injected_energy);
}

double gi_ilpv_measure_step_ms(gi_ilpv *r, int steps)
{
    double t0 = 0;
    if (r->backend == RENDERER_LPV_GL) {
        for (int s = 0; s <= steps; s++) {
            if (s == 1) {
                r->gl->Finish();
                t0 = clock_now_ms();
            }
            gl_step(r, r->gl_front[s & 1], r->gl_front[1 - (s & 1)], r->gl_sum, 0.0f, 0.0f,
                    (unsigned)s);
        }
        r->gl->Finish();
    } else {
        lpv_propagate_desc pd = {.blockers = &r->blockers, .accum = &r->cpu.sum, .pool = r->pool};
        for (int s = 0; s <= steps; s++) {
            if (s == 1)
                t0 = clock_now_ms();
            pd.step = (unsigned)s;
            lpv_propagate_step(&pd, &r->cpu.front[s & 1], &r->cpu.front[1 - (s & 1)]);
        }
    }
    double ms = steps > 0 ? (clock_now_ms() - t0) / steps : 0.0;
    ilpv_reset(&r->cpu);
    r->gl_history = (ilpv_history){0};
    lpv_converge_forget(&r->converge);
    return ms;
}

renderer_lpv_backend gi_ilpv_backend(const gi_ilpv *r) { return r->backend; }
const lattice_desc *gi_ilpv_lattice(const gi_ilpv *r) { return &r->lattice; }

/* ---- the method --------------------------------------------------------------------- */

static void *create(const gi_desc *d, char *err, size_t errlen)
{
    gi_ilpv *r = xcalloc(1, sizeof *r);
    r->gl = d->gl;
    r->scene = d->scene;
    if (init(r, d->settings, d->software, err, errlen) != 0) {
        release(r);
        free(r);
        return NULL;
    }
    return r;
}

static void destroy(void *state)
{
    release(state);
    free(state);
}

static void eye_bind(void *state, const gi_eye *e)
{
    const gi_ilpv *r = state;
    const gl_functions *gl = r->gl;
    GLuint prog = e->program, lpv[3];
    textures(r, lpv);
    const char *lname[3] = {"u_lpv_r", "u_lpv_g", "u_lpv_b"};
    for (int c = 0; c < 3; c++) {
        gl->ActiveTexture((GLenum)(GL_TEXTURE0 + e->first_unit + c));
        gl->BindTexture(GL_TEXTURE_3D, lpv[c]);
        gl->Uniform1i(gl->GetUniformLocation(prog, lname[c]), e->first_unit + c);
    }
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_lpv_enabled"), lpv[0] != 0 && r->frames > 0);
    gl->Uniform3fv(gl->GetUniformLocation(prog, "u_lpv_origin"), 1, r->lattice.origin);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_lpv_cell"), r->lattice.cell);
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_lpv_size"), r->lattice.n[0], r->lattice.n[1],
                  r->lattice.n[2]);
}

static void stats(const void *state, gi_stats *out)
{
    const gi_ilpv *r = state;
    *out = r->timings;
    out->lattice_cells = r->lattice.n[0];
    for (int a = 1; a < 3; a++)
        out->lattice_cells = r->lattice.n[a] > out->lattice_cells ? r->lattice.n[a] : out->lattice_cells;
}

const gi_method gi_ilpv_method = {
    .name = "ilpv",
    .create = create,
    .destroy = destroy,
    .reuse = reuse,
    .frame = frame,
    .eye_bind = eye_bind,
    .stats = stats,
};
