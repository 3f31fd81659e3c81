/* ilpv_gl: see ilpv_gl.h. */
#include "gi/ilpv/ilpv_gl.h"

#include <stdio.h>
#include <stdlib.h>

#include "base/xalloc.h"
#include "gl/gltools.h"
#include "gi/ilpv/lpv_paper.h"
#include "gi/ilpv/lpv_transfer.h"
#include "gi/ilpv/sh.h"

struct ilpv_gl {
    const gl_functions *gl;
    lattice_desc lattice;
    GLuint prog_propagate, prog_accumulate; /* paper: prog_propagate is paper_propagate.comp */
    GLuint near[3], shell[3], front[2][3], sum[3], blockers;
    int current;              /* index of the front textures */
    lpv_volume host_sum;      /* the sum, read back */
    float *scratch;           /* 4 floats per cell */
};

void ilpv_gl_upload(const gl_functions *gl, const lpv_volume *v, const GLuint tex[3], float *scratch)
{
    for (int c = 0; c < 3; c++) {
        for (size_t i = 0; i < v->cells; i++)
            for (int s = 0; s < 4; s++)
                scratch[4 * i + s] = v->ch[4 * c + s][i];
        gl->BindTexture(GL_TEXTURE_3D, tex[c]);
        gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl->TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, v->n[0], v->n[1], v->n[2], GL_RGBA,
                          GL_FLOAT, scratch);
    }
}

void ilpv_gl_download(const gl_functions *gl, const GLuint tex[3], lpv_volume *v, float *scratch)
{
    for (int c = 0; c < 3; c++) {
        gl->BindTexture(GL_TEXTURE_3D, tex[c]);
        gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
        gl->GetTexImage(GL_TEXTURE_3D, 0, GL_RGBA, GL_FLOAT, scratch);
        for (size_t i = 0; i < v->cells; i++)
            for (int s = 0; s < 4; s++)
                v->ch[4 * c + s][i] = scratch[4 * i + s];
    }
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

/* The blockers as one 32-bit unsigned word per cell. */
static GLuint blockers_texture(const gl_functions *gl, const int n[3], const lpv_blockers *b)
{
    GLuint t;
    gl->GenTextures(1, &t);
    gl->BindTexture(GL_TEXTURE_3D, t);
    gl->TexStorage3D(GL_TEXTURE_3D, 1, GL_R32UI, n[0], n[1], n[2]);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, n[0], n[1], n[2], GL_RED_INTEGER,
                      GL_UNSIGNED_INT, b->mask);
    return t;
}

void ilpv_gl_update_blockers(ilpv_gl *g, const lpv_blockers *b)
{
    const gl_functions *gl = g->gl;
    const int *n = g->lattice.n;
    gl->BindTexture(GL_TEXTURE_3D, g->blockers);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, n[0], n[1], n[2], GL_RED_INTEGER, GL_UNSIGNED_INT, b->mask);
}

static void dispatch(ilpv_gl *g)
{
    const gl_functions *gl = g->gl;
    const int *n = g->lattice.n;
    gl->DispatchCompute((GLuint)(n[0] + 3) / 4, (GLuint)(n[1] + 3) / 4, (GLuint)(n[2] + 3) / 4);
    gl->MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                      GL_TEXTURE_UPDATE_BARRIER_BIT);
}

static void bind_images(ilpv_gl *g, const GLuint *tex, int first, GLenum access)
{
    for (int i = 0; i < 3; i++)
        g->gl->BindImageTexture((GLuint)(first + i), tex[i], 0, GL_TRUE, 0, access, GL_RGBA32F);
}

/* Three 3D textures (R, G, B) on texture units unit .. unit + 2 as prog's name_r/g/b. */
static void bind_samplers(ilpv_gl *g, GLuint prog, const char *name, const GLuint tex[3], int unit)
{
    const gl_functions *gl = g->gl;
    static const char suffix[3] = {'r', 'g', 'b'};
    for (int c = 0; c < 3; c++) {
        char uname[32];
        snprintf(uname, sizeof uname, "%s_%c", name, suffix[c]);
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)(unit + c));
        gl->BindTexture(GL_TEXTURE_3D, tex[c]);
        gl->Uniform1i(gl->GetUniformLocation(prog, uname), unit + c);
    }
}

/* One step src -> dst (lpv_propagate_step()), also added into the sum. */
static void step(ilpv_gl *g, const GLuint src[3], const GLuint dst[3], float absorption,
                 float scattering, unsigned index)
{
    const gl_functions *gl = g->gl;
    const int *n = g->lattice.n;
    GLuint prog = g->prog_propagate;
    gl->UseProgram(prog);
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_size"), n[0], n[1], n[2]);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_use_accum"), 1);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_use_blockers"), 1);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_keep"), 1.0f - absorption);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_keep_flux"),
                  (1.0f - absorption) * (1.0f - scattering));
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_step_odd"), (int)(index & 1u));
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_step_axis"), (int)(index % 3u));
    bind_samplers(g, prog, "u_src", src, 0);
    gl->ActiveTexture(GL_TEXTURE6);
    gl->BindTexture(GL_TEXTURE_3D, g->blockers);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_blockers"), 6);
    bind_images(g, dst, 0, GL_WRITE_ONLY);
    bind_images(g, g->sum, 3, GL_READ_WRITE);
    dispatch(g);
}

/* dst = a dst + b src (accumulate.comp); a = 0 leaves dst unread. */
static void combine(ilpv_gl *g, const GLuint dst[3], float a, const GLuint src[3], float b)
{
    const gl_functions *gl = g->gl;
    const int *n = g->lattice.n;
    GLuint prog = g->prog_accumulate;
    gl->UseProgram(prog);
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_size"), n[0], n[1], n[2]);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_a"), a);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_b"), b);
    bind_samplers(g, prog, "u_src", src, 0);
    bind_images(g, dst, 0, GL_READ_WRITE);
    dispatch(g);
}

/* One paper step src -> dst (lpv_paper.h; the uniforms as lpv_propagate_step() reads its
 * desc). */
static void paper_step(ilpv_gl *g, const GLuint src[3], const GLuint dst[3], float absorption,
                       float scattering, int use_blockers)
{
    const gl_functions *gl = g->gl;
    const int *n = g->lattice.n;
    GLuint prog = g->prog_propagate;
    float keep = absorption + scattering < 1.0f ? 1.0f - absorption - scattering : 0.0f;
    gl->UseProgram(prog);
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_size"), n[0], n[1], n[2]);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_use_blockers"), use_blockers);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_keep"), keep);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_scatter"), scattering * (float)SH_ENERGY);
    bind_samplers(g, prog, "u_src", src, 0);
    gl->ActiveTexture(GL_TEXTURE6);
    gl->BindTexture(GL_TEXTURE_3D, g->blockers);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_blockers"), 6);
    bind_images(g, dst, 0, GL_WRITE_ONLY);
    dispatch(g);
}

void ilpv_gl_paper_steps(ilpv_gl *g, int steps, int block_first, float absorption, float scattering)
{
    for (int s = 0; s < steps; s++) {
        int dst = 1 - g->current;
        paper_step(g, g->front[g->current], g->front[dst], absorption, scattering,
                   s > 0 || block_first);
        g->current = dst;
    }
}

void ilpv_gl_paper_frame(ilpv_gl *g, const lpv_volume *injected, lpv_paper_merge m, int steps,
                         float absorption, float scattering, lpv_volume *result)
{
    ilpv_gl_upload(g->gl, injected, g->near, g->scratch);
    combine(g, g->front[g->current], m.a, g->near, m.b);
    ilpv_gl_paper_steps(g, steps, 0, absorption, scattering);
    ilpv_gl_download(g->gl, g->front[g->current], result, g->scratch);
}

static void gl_start(void *state, const lpv_volume *near, const lpv_volume *shell)
{
    ilpv_gl *g = state;
    ilpv_gl_upload(g->gl, near, g->near, g->scratch);
    ilpv_gl_upload(g->gl, shell, g->shell, g->scratch);
    combine(g, g->front[0], 0.0f, g->shell, 1.0f);
    combine(g, g->sum, 0.0f, g->near, 1.0f);
    combine(g, g->sum, 1.0f, g->shell, 1.0f);
    g->current = 0;
}

static void gl_steps(void *state, int steps, unsigned first, float absorption, float scattering)
{
    ilpv_gl *g = state;
    for (int s = 0; s < steps; s++) {
        int dst = 1 - g->current;
        step(g, g->front[g->current], g->front[dst], absorption, scattering, first + (unsigned)s);
        g->current = dst;
    }
}

static const lpv_volume *gl_sum(void *state)
{
    ilpv_gl *g = state;
    ilpv_gl_download(g->gl, g->sum, &g->host_sum, g->scratch);
    return &g->host_sum;
}

void ilpv_gl_destroy(ilpv_gl *g)
{
    const gl_functions *gl = g->gl;
    GLuint *all[] = {g->near, g->shell, g->front[0], g->front[1], g->sum};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        for (int c = 0; c < 3; c++)
            if (all[i][c])
                gl->DeleteTextures(1, &all[i][c]);
    if (g->blockers)
        gl->DeleteTextures(1, &g->blockers);
    if (g->prog_propagate)
        gl->DeleteProgram(g->prog_propagate);
    if (g->prog_accumulate)
        gl->DeleteProgram(g->prog_accumulate);
    lpv_volume_free(&g->host_sum);
    free(g->scratch);
    free(g);
}

static void gl_destroy(void *state)
{
    ilpv_gl_destroy(state);
}

ilpv_gl *ilpv_gl_create(const gl_functions *gl, const lattice_desc *lat,
                        const lpv_blockers *blockers, const ilpv_gl_variant *v, char *err,
                        size_t errlen)
{
    ilpv_gl *g = xcalloc(1, sizeof *g);
    g->gl = gl;
    g->lattice = *lat;
    char body[8192];
    if (v->transport == LPV_TRANSPORT_PAPER) {
        lpv_paper_shader_body(lpv_paper_transfer_default(), body, sizeof body);
        g->prog_propagate = gltools_program(gl, NULL, NULL, "ilpv/paper_propagate.comp", NULL,
                                            body, err, errlen);
    } else {
        gather_body(body, sizeof body);
        g->prog_propagate = gltools_program(gl, NULL, NULL, "ilpv/propagate.comp",
                                            v->tiles ? "#define LPV_TILES 1\n" : NULL, body, err,
                                            errlen);
    }
    g->prog_accumulate = g->prog_propagate ? gltools_program(gl, NULL, NULL, "ilpv/accumulate.comp",
                                                             NULL, NULL, err, errlen)
                                           : 0;
    if (!g->prog_accumulate) {
        ilpv_gl_destroy(g);
        return NULL;
    }
    /* not xalloc: scratch is the lattice's size (a setting): refused in err */
    if (lpv_volume_init(&g->host_sum, lat->n, LPV_LIGHT_CHANNELS) != 0 ||
        !(g->scratch = malloc(lattice_cell_count(lat) * 4 * sizeof(float)))) {
        snprintf(err, errlen, "renderer: out of memory for a %dx%dx%d GL lattice", lat->n[0],
                 lat->n[1], lat->n[2]);
        ilpv_gl_destroy(g);
        return NULL;
    }
    GLuint *all[] = {g->near, g->shell, g->front[0], g->front[1], g->sum};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) {
        if (v->transport == LPV_TRANSPORT_PAPER && (all[i] == g->shell || all[i] == g->sum))
            continue; /* paper: the injection (near) and the ping-pong only */
        for (int c = 0; c < 3; c++)
            all[i][c] = gltools_texture3d(gl, lat->n);
        ilpv_gl_upload(gl, &g->host_sum, all[i], g->scratch); /* defined contents: zeros */
    }
    g->blockers = blockers_texture(gl, lat->n, blockers);
    return g;
}

ilpv_backend ilpv_gl_backend(ilpv_gl *g)
{
    return (ilpv_backend){.state = g, .start = gl_start, .steps = gl_steps, .sum = gl_sum,
                          .destroy = gl_destroy};
}
