/* vpl_interleave: interleaved sampling (vpl_interleave.h). Two full-screen passes into two
 * RGBA32F textures: the de-interleaved gather (k x k sub-images of ceil(w / k) x
 * ceil(h / k)), then the blur at the eye's size. */
#include "gi/vpl/vpl_interleave.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/xalloc.h"
#include "gl/gltools.h"

struct vpl_interleave {
    const gl_functions *gl;
    int block;
    GLuint prog_gather, prog_blur, vao, fbo;
    GLuint deinterleaved, irradiance;
    int width, height;        /* the eye size the textures are for */
};

void vpl_interleave_destroy(vpl_interleave *il)
{
    if (!il)
        return;
    const gl_functions *gl = il->gl;
    GLuint tex[2] = {il->deinterleaved, il->irradiance};
    for (int i = 0; i < 2; i++)
        if (tex[i])
            gl->DeleteTextures(1, &tex[i]);
    if (il->prog_gather)
        gl->DeleteProgram(il->prog_gather);
    if (il->prog_blur)
        gl->DeleteProgram(il->prog_blur);
    if (il->vao)
        gl->DeleteVertexArrays(1, &il->vao);
    if (il->fbo)
        gl->DeleteFramebuffers(1, &il->fbo);
    free(il);
}

vpl_interleave *vpl_interleave_create(const gl_functions *gl, int block, char *err,
                                      size_t errlen)
{
    vpl_interleave *il = xcalloc(1, sizeof *il);
    il->gl = gl;
    il->block = block;
    const char *gather[2] = {"vpl/vpl_gather.glsl", "vpl/vpl_deinterleave.frag"};
    if (!(il->prog_gather = gltools_program_parts(gl, "fullscreen.vert", gather, 2, NULL, err,
                                                  errlen)) ||
        !(il->prog_blur = gltools_program(gl, "fullscreen.vert", "vpl/vpl_blur.frag", NULL, NULL,
                                          NULL, err, errlen))) {
        vpl_interleave_destroy(il);
        return NULL;
    }
    gl->GenVertexArrays(1, &il->vao);
    gl->GenFramebuffers(1, &il->fbo);
    return il;
}

GLuint vpl_interleave_program(const vpl_interleave *il) { return il->prog_gather; }

static int sub_size(int n, int k) { return (n + k - 1) / k; }

static void reserve(vpl_interleave *il, int w, int h)
{
    if (w == il->width && h == il->height)
        return;
    const gl_functions *gl = il->gl;
    if (il->deinterleaved)
        gl->DeleteTextures(1, &il->deinterleaved);
    if (il->irradiance)
        gl->DeleteTextures(1, &il->irradiance);
    int k = il->block;
    il->deinterleaved = gltools_texture2d(gl, GL_RGBA32F, k * sub_size(w, k), k * sub_size(h, k),
                                          GL_NEAREST);
    il->irradiance = gltools_texture2d(gl, GL_RGBA32F, w, h, GL_NEAREST);
    il->width = w;
    il->height = h;
}

static void draw_into(const vpl_interleave *il, GLuint target, int w, int h)
{
    const gl_functions *gl = il->gl;
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target, 0);
    const GLenum color = GL_COLOR_ATTACHMENT0;
    gl->DrawBuffers(1, &color);
    gl->Viewport(0, 0, w, h);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
}

void vpl_interleave_run(vpl_interleave *il, const gi_eye *e, int unit)
{
    const gl_functions *gl = il->gl;
    gltools_draw_state outer;
    gltools_draw_state_save(gl, &outer);
    reserve(il, e->width, e->height);
    int k = il->block;
    gl->BindFramebuffer(GL_FRAMEBUFFER, il->fbo);
    gl->BindVertexArray(il->vao);

    GLuint g = il->prog_gather; /* current, its VPL uniforms bound by the caller */
    gl->Uniform1i(gl->GetUniformLocation(g, "u_position"), 0);
    gl->Uniform1i(gl->GetUniformLocation(g, "u_normal"), 1);
    gl->Uniform1i(gl->GetUniformLocation(g, "u_vpl_block"), k);
    draw_into(il, il->deinterleaved, k * sub_size(e->width, k), k * sub_size(e->height, k));

    GLuint b = il->prog_blur;
    gl->UseProgram(b);
    gl->ActiveTexture((GLenum)(GL_TEXTURE0 + unit));
    gl->BindTexture(GL_TEXTURE_2D, il->deinterleaved);
    gl->Uniform1i(gl->GetUniformLocation(b, "u_position"), 0);
    gl->Uniform1i(gl->GetUniformLocation(b, "u_normal"), 1);
    gl->Uniform1i(gl->GetUniformLocation(b, "u_deinterleaved"), unit);
    gl->Uniform1i(gl->GetUniformLocation(b, "u_block"), k);
    gl->Uniform4fv(gl->GetUniformLocation(b, "u_eye"), 1, e->eye);
    gl->Uniform1f(gl->GetUniformLocation(b, "u_pixel_angle"), e->pixel_angle);
    draw_into(il, il->irradiance, e->width, e->height);

    gl->BindTexture(GL_TEXTURE_2D, il->irradiance);
    gltools_draw_state_restore(gl, &outer, e->program);
}
