/* gi_ilpv: the ILPV method (gi_ilpv.h). The VPLs of the source every light type feeds
 * (renderer_rsm_vpls(), in texel order, so the injection is deterministic) are injected
 * with the CPU core, then merged and propagated either by the CPU ILPV core or by GL
 * compute shaders.
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
    int clamp_negative;
    int gl_tiles;            /* GL propagation through shared-memory tiles */
    float indirect_scale;
    double mean_free_path;   /* metres, 4V/A of the scene */
    float energy_gain;       /* level of the indirect light this frame */
    lattice_desc lattice;
    lpv_transfer transfer;
    lpv_volume geometry;
    ilpv cpu;                /* incremental mode; its injection volume serves both modes */
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
    GLuint prog_merge, prog_propagate, prog_accumulate;
    GLuint gl_injected[3], gl_volume[2][3], gl_geometry;
    GLuint gl_accum[3];      /* classic mode: the sum of the steps */
    int gl_current;
    ilpv_history gl_history; /* the GL path's own merge state (ilpv_merge_factors()) */
    lpv_volume gl_result;
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

static void gather_body(const lpv_transfer *t, char *out, size_t n)
{
    size_t used = 0;
    for (int j = 0; j < LPV_NEIGHBOURS && used < n; j++)
        used += (size_t)snprintf(out + used, n - used,
                                 "    gather(here, ivec3(%d, %d, %d), vec4(%.9g, %.9g, %.9g, %.9g), "
                                 "%.9g, ar, ag, ab);\n",
                                 lpv_transfer_offsets[j][0], lpv_transfer_offsets[j][1],
                                 lpv_transfer_offsets[j][2], t->gamma[j][0], t->gamma[j][1],
                                 t->gamma[j][2], t->gamma[j][3], t->outscatter[j]);
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

static int init_gl_backend(gi_ilpv *r, int software, const renderer_desc *desc, char *err,
                           size_t errlen)
{
    char body[8192];
    gather_body(&r->transfer, body, sizeof body);
    r->gl_tiles = desc->lpv_gl_tiles == RENDERER_TILES_AUTO ? !software
                                                            : desc->lpv_gl_tiles == RENDERER_TILES_ON;
    r->prog_propagate = gltools_program(r->gl, NULL, NULL, "propagate.comp",
                                         r->gl_tiles ? "#define LPV_TILES 1\n" : NULL, body,
                                         err, errlen);
    r->prog_merge = r->prog_propagate
                        ? gltools_program(r->gl, NULL, NULL, "merge.comp", NULL, NULL, err, errlen)
                        : 0;
    if (r->prog_merge && r->mode == RENDERER_LPV_CLASSIC)
        r->prog_accumulate = gltools_program(r->gl, NULL, NULL, "accumulate.comp", NULL, NULL, err,
                                              errlen);
    if (!r->prog_merge || (r->mode == RENDERER_LPV_CLASSIC && !r->prog_accumulate))
        return -1;
    if (lpv_volume_init(&r->gl_result, r->lattice.n, LPV_LIGHT_CHANNELS) != 0) {
        snprintf(err, errlen, "renderer: out of memory for the LPV readback");
        return -1;
    }
    for (int c = 0; c < 3; c++) {
        r->gl_injected[c] = gltools_texture3d(r->gl, r->lattice.n);
        r->gl_volume[0][c] = gltools_texture3d(r->gl, r->lattice.n);
        r->gl_volume[1][c] = gltools_texture3d(r->gl, r->lattice.n);
        if (r->mode == RENDERER_LPV_CLASSIC)
            r->gl_accum[c] = gltools_texture3d(r->gl, r->lattice.n);
    }
    /* Defined contents everywhere: the zeroed readback volume. */
    upload_volume(r, &r->gl_result, r->gl_volume[0]);
    upload_volume(r, &r->gl_result, r->gl_volume[1]);
    if (r->mode == RENDERER_LPV_CLASSIC)
        upload_volume(r, &r->gl_result, r->gl_accum);
    r->gl_geometry = gltools_texture3d(r->gl, r->lattice.n);
    for (size_t i = 0; i < r->geometry.cells; i++)
        for (int s = 0; s < 4; s++)
            r->upload[4 * i + s] = r->geometry.ch[s][i];
    r->gl->BindTexture(GL_TEXTURE_3D, r->gl_geometry);
    r->gl->TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, r->lattice.n[0], r->lattice.n[1],
                         r->lattice.n[2], GL_RGBA, GL_FLOAT, r->upload);
    return 0;
}

/* Mean free path of light in the scene, 4V/A (V volume of the bounds, A surface area). */
static double mean_free_path(const scene *s, double cell)
{
    double volume = 1, area = 0;
    for (int a = 0; a < 3; a++)
        volume *= fmax(s->bounds_max[a] - s->bounds_min[a], cell);
    for (size_t t = 0; t < s->triangle_count; t++) {
        const float *p = s->positions + 9 * t;
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = p[3 + k] - p[k];
            e2[k] = p[6 + k] - p[k];
        }
        double c[3];
        vec3d_cross(e1, e2, c);
        area += 0.5 * sqrt(vec3d_dot(c, c));
    }
    return area > 0 ? 4.0 * volume / area : 0.0;
}

/* Light injected in a frame lives for the mean free path before it hits a surface, i.e.
 * for mfp / (d_mean * cell) propagation steps; the steady indirect light is that many
 * times one step's worth (docs/lpv.md). */
static float auto_indirect_scale(const gi_ilpv *r)
{
    int longest = r->lattice.n[0];
    for (int a = 1; a < 3; a++)
        longest = r->lattice.n[a] > longest ? r->lattice.n[a] : longest;
    double k = r->mean_free_path > 0
                   ? r->mean_free_path / (LPV_MEAN_NEIGHBOUR_DISTANCE * r->lattice.cell) : 1.0;
    return (float)fmin(fmax(k, 1.0), (double)longest);
}

/* The incremental lattice says how the light is spread, not how much there is: blocking
 * removes light within a frame's own steps and the merge keeps only (1 - lambda_incr) of
 * the fresh injection, so its energy changes with steps and lambda_incr while the light in
 * the room does not. The level is therefore this frame's injected energy (less what the
 * medium absorbs over a mean free path), spread as the lattice says. Classic mode keeps
 * the level of its sum, as published. */
static float energy_gain(const gi_ilpv *r, const frame_params *p, const lpv_volume *result)
{
    if (r->mode == RENDERER_LPV_CLASSIC)
        return 1.0f;
    double in[3], out[3];
    lpv_volume_energy(&r->cpu.injected, in);
    lpv_volume_energy(result, out);
    double injected = in[0] + in[1] + in[2], held = out[0] + out[1] + out[2];
    if (!(injected > 0) || !(held > 0))
        return 1.0f;
    double kept = p->absorption > 0
                      ? pow(1.0 - fmin(p->absorption, 0.999999), r->mean_free_path) : 1.0;
    return (float)fmin(injected / held * kept, 1e4);
}

static int init(gi_ilpv *r, const renderer_desc *desc, int software, char *err, size_t errlen)
{
    const scene *s = r->scene;
    r->backend = desc->lpv_backend != RENDERER_LPV_AUTO
                     ? desc->lpv_backend
                     : (software ? RENDERER_LPV_CPU : RENDERER_LPV_GL);
    r->clamp_negative = desc->lpv_clamp_negative;
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
    lpv_transfer_desc td = {0};
    if (lpv_transfer_compute(&td, &r->transfer) != 0) {
        snprintf(err, errlen, "renderer: LPV transfer vectors could not be computed");
        return -1;
    }
    /* Static scene: the blocking lattice is built once, here. */
    if (lpv_volume_init(&r->geometry, r->lattice.n, LPV_GEOMETRY_CHANNELS) != 0 ||
        ilpv_init(&r->cpu, &r->lattice) != 0 || build_emitters(r) != 0 ||
        lpv_converge_init(&r->converge, r->lattice.n, desc->converge_threshold) != 0 ||
        (r->mode == RENDERER_LPV_CLASSIC && r->backend == RENDERER_LPV_CPU &&
         lpv_classic_init(&r->classic, &r->lattice) != 0)) {
        snprintf(err, errlen, "renderer: out of memory for a %dx%dx%d lattice",
                 r->lattice.n[0], r->lattice.n[1], r->lattice.n[2]);
        return -1;
    }
    lpv_geometry_add_triangles(&r->geometry, &r->lattice, s->positions, 3 * s->triangle_count,
                               NULL, s->triangle_count, NULL);
    r->mean_free_path = mean_free_path(s, r->lattice.cell);
    r->energy_gain = 1.0f;
    /* Classic mode sums the light over its life in steps already (docs/lpv.md). */
    r->indirect_scale = desc->indirect_scale > 0       ? desc->indirect_scale
                        : r->mode == RENDERER_LPV_CLASSIC ? 1.0f
                                                          : auto_indirect_scale(r);
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
        GLuint t[5] = {r->lpv_tex[c], r->gl_injected[c], r->gl_volume[0][c], r->gl_volume[1][c],
                       r->gl_accum[c]};
        for (int i = 0; i < 5; i++)
            if (t[i])
                gl->DeleteTextures(1, &t[i]);
    }
    if (r->gl_geometry)
        gl->DeleteTextures(1, &r->gl_geometry);
    if (r->prog_merge)
        gl->DeleteProgram(r->prog_merge);
    if (r->prog_propagate)
        gl->DeleteProgram(r->prog_propagate);
    if (r->prog_accumulate)
        gl->DeleteProgram(r->prog_accumulate);
    if (r->pool)
        workpool_destroy(r->pool);
    if (r->gl_result.cells)
        lpv_volume_free(&r->gl_result);
    if (r->cpu.injected.cells)
        ilpv_free(&r->cpu);
    if (r->classic.accum.cells)
        lpv_classic_free(&r->classic);
    if (r->converge.previous.cells)
        lpv_converge_free(&r->converge);
    if (r->geometry.cells)
        lpv_volume_free(&r->geometry);
    free(r->emitters);
    free(r->vpls);
    free(r->upload);
}

static void textures(const gi_ilpv *r, GLuint out[3])
{
    for (int c = 0; c < 3; c++)
        out[c] = r->backend != RENDERER_LPV_GL       ? r->lpv_tex[c]
                 : r->mode == RENDERER_LPV_CLASSIC ? r->gl_accum[c]
                                                   : r->gl_volume[r->gl_current][c];
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

/* Binds the propagation program and its per-frame uniforms and the geometry image. */
static void use_propagate(gi_ilpv *r, float absorption, float scattering)
{
    const gl_functions *gl = r->gl;
    const int *n = r->lattice.n;
    float la = lpv_transfer_step_probability(absorption, r->lattice.cell);
    float ls = lpv_transfer_step_probability(scattering, r->lattice.cell);
    float lt = la + ls < 1.0f ? la + ls : 1.0f;
    GLuint prog = r->prog_propagate;
    gl->UseProgram(prog);
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_size"), n[0], n[1], n[2]);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_clamp_negative"), r->clamp_negative);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_keep"), 1.0f - lt);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_scatter"), ls);
    bind_images(r, &r->gl_geometry, 1, 6, GL_READ_ONLY);
}

/* One step src -> dst with the bound propagation program. */
static void gl_step(gi_ilpv *r, const GLuint src[3], const GLuint dst[3], int use_blocking)
{
    r->gl->Uniform1i(r->gl->GetUniformLocation(r->prog_propagate, "u_use_blocking"), use_blocking);
    bind_images(r, src, 3, 0, GL_READ_ONLY);
    bind_images(r, dst, 3, 3, GL_WRITE_ONLY);
    dispatch(r);
}

/* gl_accum = (first ? 0 : gl_accum) + weight * step. */
static void gl_accumulate(gi_ilpv *r, const GLuint step[3], int first, float weight)
{
    const gl_functions *gl = r->gl;
    const int *n = r->lattice.n;
    GLuint prog = r->prog_accumulate;
    gl->UseProgram(prog);
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_size"), n[0], n[1], n[2]);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_first"), first);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_weight"), weight);
    bind_images(r, r->gl_accum, 3, 0, GL_READ_WRITE);
    bind_images(r, step, 3, 3, GL_READ_ONLY);
    dispatch(r);
}

/* lpv_classic_frame() on the GPU: the steps start from the injection, each one is added
 * into gl_accum (the first replaces it; 0 steps clear it). */
static void gl_classic_frame(gi_ilpv *r, const frame_params *p)
{
    upload_volume(r, ilpv_injection(&r->cpu), r->gl_injected);
    if (p->lpv_steps <= 0)
        gl_accumulate(r, r->gl_injected, 1, 0.0f);
    const GLuint *src = r->gl_injected;
    for (int step = 0; step < p->lpv_steps; step++) {
        const GLuint *dst = r->gl_volume[step & 1];
        use_propagate(r, p->absorption, p->scattering);
        gl_step(r, src, dst, step > 0);
        gl_accumulate(r, dst, step == 0, 1.0f);
        src = dst;
    }
    download_volume(r, r->gl_accum, &r->gl_result);
}

/* The same merge and steps as ilpv_frame(), on the GPU. */
static void gl_frame(gi_ilpv *r, const frame_params *p, double energy)
{
    const gl_functions *gl = r->gl;
    upload_volume(r, ilpv_injection(&r->cpu), r->gl_injected);
    ilpv_merge f = ilpv_merge_factors(&r->gl_history, p->lambda_incr, energy);
    const int *n = r->lattice.n;

    int dst = 1 - r->gl_current;
    gl->UseProgram(r->prog_merge);
    bind_images(r, r->gl_volume[r->gl_current], 3, 0, GL_READ_ONLY);
    bind_images(r, r->gl_injected, 3, 3, GL_READ_ONLY);
    bind_images(r, r->gl_volume[dst], 3, 6, GL_WRITE_ONLY);
    gl->Uniform3i(gl->GetUniformLocation(r->prog_merge, "u_size"), n[0], n[1], n[2]);
    gl->Uniform1f(gl->GetUniformLocation(r->prog_merge, "u_a"), f.a);
    gl->Uniform1f(gl->GetUniformLocation(r->prog_merge, "u_b"), f.b);
    dispatch(r);
    r->gl_current = dst;

    use_propagate(r, p->absorption, p->scattering);
    for (int step = 0; step < p->lpv_steps; step++) {
        dst = 1 - r->gl_current;
        gl_step(r, r->gl_volume[r->gl_current], r->gl_volume[dst], step > 0);
        r->gl_current = dst;
    }
    ilpv_history_advance(&r->gl_history, energy);
    download_volume(r, r->gl_volume[r->gl_current], &r->gl_result);
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
    lpv_inject_vpls(ilpv_injection(&r->cpu), &r->lattice, vpls, count, &r->inject_stats);
    double t1 = clock_now_ms();
    double energy = emitted_energy(r, p);
    lpv_propagate_desc pd = {
        .transfer = &r->transfer,
        .geometry = &r->geometry,
        .use_blocking = 1,
        .absorption = lpv_transfer_step_probability(p->absorption, r->lattice.cell),
        .scattering = lpv_transfer_step_probability(p->scattering, r->lattice.cell),
        .clamp_negative = r->clamp_negative,
        .pool = r->pool,
    };
    if (r->backend == RENDERER_LPV_GL && r->mode == RENDERER_LPV_CLASSIC)
        gl_classic_frame(r, p);
    else if (r->backend == RENDERER_LPV_GL)
        gl_frame(r, p, energy);
    else if (r->mode == RENDERER_LPV_CLASSIC)
        lpv_classic_frame(&r->classic, ilpv_injection(&r->cpu), p->lpv_steps, &pd);
    else
        ilpv_frame(&r->cpu, &(ilpv_frame_desc){.steps = p->lpv_steps,
                                               .lambda_incr = p->lambda_incr,
                                               .emitted_energy = energy,
                                               .propagate = pd});
    const lpv_volume *result = gi_ilpv_volume(r);
    r->checksum = lpv_volume_checksum(result);
    r->energy_gain = energy_gain(r, p, result);
    if (r->backend != RENDERER_LPV_GL)
        upload_volume(r, result, r->lpv_tex);
    lpv_converge_end(&r->converge, result, r->pool);
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
        return &r->gl_result;
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
    out->energy_gain = r->energy_gain;
}

double gi_ilpv_measure_step_ms(gi_ilpv *r, int steps)
{
    double t0 = 0;
    if (r->backend == RENDERER_LPV_GL) {
        use_propagate(r, 0.0f, 0.0f);
        for (int s = 0; s <= steps; s++) {
            if (s == 1) {
                r->gl->Finish();
                t0 = clock_now_ms();
            }
            gl_step(r, r->gl_volume[s & 1], r->gl_volume[1 - (s & 1)], 1);
            if (r->mode == RENDERER_LPV_CLASSIC) { /* a classic step includes its addition */
                gl_accumulate(r, r->gl_volume[1 - (s & 1)], 0, 1.0f);
                use_propagate(r, 0.0f, 0.0f);
            }
        }
        r->gl->Finish();
    } else {
        lpv_propagate_desc pd = {.transfer = &r->transfer, .geometry = &r->geometry,
                                 .use_blocking = 1, .pool = r->pool};
        if (r->mode == RENDERER_LPV_CLASSIC) {
            lpv_classic_frame(&r->classic, ilpv_injection(&r->cpu), 1, &pd);
            t0 = clock_now_ms();
            lpv_classic_frame(&r->classic, ilpv_injection(&r->cpu), steps, &pd);
        } else {
            for (int s = 0; s <= steps; s++) {
                if (s == 1)
                    t0 = clock_now_ms();
                lpv_propagate_step(&pd, &r->cpu.volume[s & 1], &r->cpu.volume[1 - (s & 1)]);
            }
        }
    }
    double ms = steps > 0 ? (clock_now_ms() - t0) / steps : 0.0;
    ilpv_reset(&r->cpu);
    r->gl_history = (ilpv_history){0};
    lpv_converge_forget(&r->converge);
    return ms;
}

float gi_ilpv_indirect_scale(const gi_ilpv *r)
{
    return r->indirect_scale;
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
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_indirect_scale"), r->indirect_scale * r->energy_gain);
    gl->Uniform3f(gl->GetUniformLocation(prog, "u_lpv_size"), (float)r->lattice.n[0],
                  (float)r->lattice.n[1], (float)r->lattice.n[2]);
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
