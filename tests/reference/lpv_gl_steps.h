/* lpv_gl_steps: the LPV's GL compute shaders run directly, without the renderer, for the
 * GL tests and cavelight-bench lpv --backend gl: volumes to and from three RGBA32F 3D
 * textures (one per colour, 4 SH coefficients each), the blockers as one R32UI word per
 * cell, one propagation step of either transport (node/gi/ilpv/propagate.comp,
 * node/gi/ilpv/paper_propagate.comp), and node/gi/ilpv/accumulate.comp's
 * dst = a dst + b src (the paper merge). The GL side of what lpv_propagate_step() and
 * lpv_paper_merge_run() do on the CPU; header only, a GL context must be current. */
#ifndef CAVELIGHT_LPV_GL_STEPS_H
#define CAVELIGHT_LPV_GL_STEPS_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gltools.h"
#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_paper.h"
#include "gi/ilpv/lpv_propagate.h"
#include "gi/ilpv/sh.h"

typedef struct lpv_gl_steps {
    const gl_functions *gl;
    int n[3];
    float *staging;            /* 4 floats per cell */
    GLuint prog[LPV_TRANSPORT_COUNT];
    GLuint prog_accumulate;
    GLuint blockers;           /* R32UI, one word per cell */
} lpv_gl_steps;

static inline GLuint lpv_gl_volume_textures(const lpv_gl_steps *s, GLuint tex[3])
{
    for (int c = 0; c < 3; c++)
        tex[c] = gltools_texture3d(s->gl, s->n);
    return tex[0];
}

static inline void lpv_gl_upload(lpv_gl_steps *s, const lpv_volume *v, const GLuint tex[3])
{
    const gl_functions *gl = s->gl;
    for (int c = 0; c < 3; c++) {
        for (size_t i = 0; i < v->cells; i++)
            for (int k = 0; k < 4; k++)
                s->staging[4 * i + k] = v->ch[4 * c + k][i];
        gl->BindTexture(GL_TEXTURE_3D, tex[c]);
        gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
        gl->TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, s->n[0], s->n[1], s->n[2], GL_RGBA,
                          GL_FLOAT, s->staging);
    }
}

static inline void lpv_gl_download(lpv_gl_steps *s, const GLuint tex[3], lpv_volume *v)
{
    const gl_functions *gl = s->gl;
    for (int c = 0; c < 3; c++) {
        gl->BindTexture(GL_TEXTURE_3D, tex[c]);
        gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
        gl->GetTexImage(GL_TEXTURE_3D, 0, GL_RGBA, GL_FLOAT, s->staging);
        for (size_t i = 0; i < v->cells; i++)
            for (int k = 0; k < 4; k++)
                v->ch[4 * c + k][i] = s->staging[4 * i + k];
    }
}

/* The programs and the blockers (NULL: none). Returns 0, or -1 with one line in err. */
static inline int lpv_gl_steps_init(lpv_gl_steps *s, const gl_functions *gl, const int n[3],
                                    const lpv_blockers *blockers, const lpv_paper_transfer *t,
                                    char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    s->gl = gl;
    memcpy(s->n, n, sizeof s->n);
    s->staging = malloc((size_t)n[0] * n[1] * n[2] * 4 * sizeof(float));
    char body[8192];
    size_t used = 0;
    for (int k = 0; k <= LPV_NEIGHBOURS; k++) { /* propagate.comp's 27 targets */
        const int zero[3] = {0, 0, 0}, *o = k < LPV_NEIGHBOURS ? lpv_transfer_offsets[k] : zero;
        used += (size_t)snprintf(body + used, sizeof body - used,
                                 "    gather(here, cell, ivec3(%d, %d, %d), %d, ar, ag, ab);\n",
                                 o[0], o[1], o[2], k);
    }
    s->prog[LPV_TRANSPORT_BEAMS] = gltools_program(gl, NULL, NULL, "ilpv/propagate.comp", NULL, body,
                                                   err, errlen);

    if (!lpv_paper_shader_body(t ? t : lpv_paper_transfer_default(), body, sizeof body))
        return -1;
    s->prog[LPV_TRANSPORT_PAPER] = gltools_program(gl, NULL, NULL, "ilpv/paper_propagate.comp", NULL,
                                                   body, err, errlen);
    s->prog_accumulate = gltools_program(gl, NULL, NULL, "ilpv/accumulate.comp", NULL, NULL, err,
                                         errlen);
    if (!s->staging || !s->prog[0] || !s->prog[1] || !s->prog_accumulate)
        return -1;
    gl->GenTextures(1, &s->blockers);
    gl->BindTexture(GL_TEXTURE_3D, s->blockers);
    gl->TexStorage3D(GL_TEXTURE_3D, 1, GL_R32UI, n[0], n[1], n[2]);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    uint32_t *words = calloc((size_t)n[0] * n[1] * n[2], sizeof *words);
    if (!words)
        return -1;
    if (blockers)
        memcpy(words, blockers->mask, blockers->cells * sizeof *words);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, n[0], n[1], n[2], GL_RED_INTEGER,
                      GL_UNSIGNED_INT, words);
    free(words);
    return 0;
}

static inline void lpv_gl_steps_free(lpv_gl_steps *s)
{
    for (int t = 0; t < LPV_TRANSPORT_COUNT; t++)
        if (s->prog[t])
            s->gl->DeleteProgram(s->prog[t]);
    if (s->prog_accumulate)
        s->gl->DeleteProgram(s->prog_accumulate);
    if (s->blockers)
        s->gl->DeleteTextures(1, &s->blockers);
    free(s->staging);
    memset(s, 0, sizeof *s);
}

static inline void lpv_gl_bind_colours(const lpv_gl_steps *s, GLuint prog, const char *name,
                                       const GLuint tex[3], int unit)
{
    const gl_functions *gl = s->gl;
    static const char suffix[3] = {'r', 'g', 'b'};
    for (int c = 0; c < 3; c++) {
        char uname[32];
        snprintf(uname, sizeof uname, "%s_%c", name, suffix[c]);
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)(unit + c));
        gl->BindTexture(GL_TEXTURE_3D, tex[c]);
        gl->Uniform1i(gl->GetUniformLocation(prog, uname), unit + c);
    }
}

static inline void lpv_gl_dispatch(const lpv_gl_steps *s)
{
    const gl_functions *gl = s->gl;
    gl->DispatchCompute((GLuint)(s->n[0] + 3) / 4, (GLuint)(s->n[1] + 3) / 4,
                        (GLuint)(s->n[2] + 3) / 4);
    gl->MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                      GL_TEXTURE_UPDATE_BARRIER_BIT);
}

/* One step src -> dst of desc's transport (its blockers only say whether to block: the
 * texture holds the words given at init; absorption, scattering and step as on the CPU). */
static inline void lpv_gl_step(lpv_gl_steps *s, const lpv_propagate_desc *desc,
                               const GLuint src[3], const GLuint dst[3])
{
    const gl_functions *gl = s->gl;
    GLuint prog = s->prog[desc->transport];
    float la = desc->absorption, ls = desc->scattering;
    gl->UseProgram(prog);
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_size"), s->n[0], s->n[1], s->n[2]);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_use_blockers"), desc->blockers != NULL);
    if (desc->transport == LPV_TRANSPORT_PAPER) {
        gl->Uniform1f(gl->GetUniformLocation(prog, "u_keep"), la + ls < 1.0f ? 1.0f - la - ls : 0.0f);
        gl->Uniform1f(gl->GetUniformLocation(prog, "u_scatter"), ls * (float)SH_ENERGY);
    } else {
        gl->Uniform1i(gl->GetUniformLocation(prog, "u_use_accum"), 0);
        gl->Uniform1f(gl->GetUniformLocation(prog, "u_keep"), 1.0f - la);
        gl->Uniform1f(gl->GetUniformLocation(prog, "u_keep_flux"), (1.0f - la) * (1.0f - ls));
        gl->Uniform1i(gl->GetUniformLocation(prog, "u_step_odd"), (int)(desc->step & 1u));
        gl->Uniform1i(gl->GetUniformLocation(prog, "u_step_axis"), (int)(desc->step % 3u));
    }
    lpv_gl_bind_colours(s, prog, "u_src", src, 0);
    gl->ActiveTexture(GL_TEXTURE6);
    gl->BindTexture(GL_TEXTURE_3D, s->blockers);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_blockers"), 6);
    for (int c = 0; c < 3; c++)
        gl->BindImageTexture((GLuint)c, dst[c], 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    for (int c = 0; c < 3; c++) /* propagate.comp's accumulation images: bound, unused */
        gl->BindImageTexture((GLuint)(3 + c), dst[c], 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
    lpv_gl_dispatch(s);
}

/* dst = a dst + b src (ilpv/accumulate.comp): the paper merge with dst the history. */
static inline void lpv_gl_combine(lpv_gl_steps *s, const GLuint dst[3], float a,
                                  const GLuint src[3], float b)
{
    const gl_functions *gl = s->gl;
    GLuint prog = s->prog_accumulate;
    gl->UseProgram(prog);
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_size"), s->n[0], s->n[1], s->n[2]);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_a"), a);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_b"), b);
    lpv_gl_bind_colours(s, prog, "u_src", src, 0);
    for (int c = 0; c < 3; c++)
        gl->BindImageTexture((GLuint)c, dst[c], 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
    lpv_gl_dispatch(s);
}

#endif
