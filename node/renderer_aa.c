/* renderer_aa: FXAA on the eye's final image (renderer_aa.h). */
#include "renderer_aa.h"

#include <stdlib.h>

#include "base/xalloc.h"
#include "gl/gltools.h"

struct renderer_aa {
    const gl_functions *gl;
    GLuint prog;
    GLuint fbo, color;       /* the result */
    int w, h;
};

renderer_aa *renderer_aa_create(const gl_functions *gl, char *err, size_t errlen)
{
    renderer_aa *aa = xcalloc(1, sizeof *aa);
    aa->gl = gl;
    if (!(aa->prog = gltools_program(gl, "fullscreen.vert", "aa_fxaa.frag", NULL, NULL, NULL,
                                     err, errlen))) {
        renderer_aa_destroy(aa);
        return NULL;
    }
    return aa;
}

static void free_target(renderer_aa *aa)
{
    if (aa->color)
        aa->gl->DeleteTextures(1, &aa->color);
    if (aa->fbo)
        aa->gl->DeleteFramebuffers(1, &aa->fbo);
    aa->color = aa->fbo = 0;
    aa->w = aa->h = 0;
}

void renderer_aa_destroy(renderer_aa *aa)
{
    if (!aa)
        return;
    free_target(aa);
    if (aa->prog)
        aa->gl->DeleteProgram(aa->prog);
    free(aa);
}

static int target(renderer_aa *aa, int w, int h)
{
    if (w == aa->w && h == aa->h)
        return 0;
    const gl_functions *gl = aa->gl;
    free_target(aa);
    aa->color = gltools_texture2d(gl, GL_RGBA8, w, h, GL_NEAREST);
    gl->GenFramebuffers(1, &aa->fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, aa->fbo);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, aa->color, 0);
    const GLenum buffer = GL_COLOR_ATTACHMENT0;
    gl->DrawBuffers(1, &buffer);
    char err[160];
    if (!aa->color || gltools_fbo_complete(gl, "anti-aliasing", err, sizeof err)) {
        free_target(aa);
        return -1;
    }
    aa->w = w;
    aa->h = h;
    return 0;
}

GLuint renderer_aa_apply(renderer_aa *aa, frame_aa mode, GLuint ldr, int w, int h, GLuint vao)
{
    if (mode == FRAME_AA_OFF || target(aa, w, h) != 0)
        return 0;
    const gl_functions *gl = aa->gl;
    gl->BindFramebuffer(GL_FRAMEBUFFER, aa->fbo);
    gl->Viewport(0, 0, w, h);
    gl->Disable(GL_DEPTH_TEST);
    gl->Disable(GL_BLEND);
    gl->UseProgram(aa->prog);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, ldr);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl->Uniform1i(gl->GetUniformLocation(aa->prog, "u_ldr"), 0);
    gl->Uniform2f(gl->GetUniformLocation(aa->prog, "u_texel"), 1.0f / (float)w, 1.0f / (float)h);
    gl->BindVertexArray(vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    gl->BindVertexArray(0);
    gl->UseProgram(0);
    return aa->fbo;
}
