/* renderer_ao: see renderer_ao.h. */
#include "renderer_ao.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/xalloc.h"
#include "gi/ldm/ldm_settings.h"
#include "gi/ldm/ldm_gl.h"
#include "gl/gltools.h"

struct renderer_ao {
    const gl_functions *gl;
    const scene *scene;
    GLuint prog_ldm, prog_ssao;
    ldm_gl *maps;              /* `ao ldm`'s, built for `built` */
    ldm_layout built;
    int refused;               /* `built` could not be made: not again until it changes */
    frame_params frame;        /* the last frame's settings */
    int active;                /* the last eye ran a pass: its texture holds AO */
    int w, h;
    GLuint tex, fbo;
    float *rgb;
    renderer_ao_stats stats;
};

renderer_ao *renderer_ao_create(const gl_functions *gl, const scene *s, char *err,
                                size_t errlen)
{
    renderer_ao *ao = xcalloc(1, sizeof *ao);
    ao->gl = gl;
    ao->scene = s;
    const char *ldm[3] = {"ldm_trace.glsl", "ao_common.glsl", "ao_ldm.frag"};
    const char *ssao[2] = {"ao_common.glsl", "ao_hbao.frag"};
    if (!(ao->prog_ldm = gltools_program_parts(gl, "fullscreen.vert", ldm, 3, NULL, err, errlen)) ||
        !(ao->prog_ssao = gltools_program_parts(gl, "fullscreen.vert", ssao, 2, NULL, err, errlen))) {
        renderer_ao_destroy(ao);
        return NULL;
    }
    frame_params_default(&ao->frame);
    return ao;
}

static void free_target(renderer_ao *ao)
{
    if (ao->tex)
        ao->gl->DeleteTextures(1, &ao->tex);
    if (ao->fbo)
        ao->gl->DeleteFramebuffers(1, &ao->fbo);
    free(ao->rgb);
    ao->tex = ao->fbo = 0;
    ao->rgb = NULL;
    ao->w = ao->h = 0;
}

void renderer_ao_destroy(renderer_ao *ao)
{
    if (!ao)
        return;
    free_target(ao);
    ldm_gl_destroy(ao->maps);
    if (ao->prog_ldm)
        ao->gl->DeleteProgram(ao->prog_ldm);
    if (ao->prog_ssao)
        ao->gl->DeleteProgram(ao->prog_ssao);
    free(ao);
}

static void build(renderer_ao *ao, const scene_gl *mesh)
{
    ao->stats.build_ms = ldm_gl_build(ao->maps, mesh);
    ao->stats.overflow = ldm_gl_overflow(ao->maps);
}

int renderer_ao_frame(renderer_ao *ao, const frame_params *p, const scene_gl *mesh, int moved,
                      char *err, size_t errlen)
{
    ao->frame = *p;
    if (p->ao != FRAME_AO_LDM)
        return 0;
    ldm_layout want;
    ldm_layout_init(&want, ao->scene, p->ao_directions, p->ao_resolution, p->ldm_layers);
    if ((ao->maps || ao->refused) && memcmp(&want, &ao->built, sizeof want) == 0) {
        if (ao->maps && moved)
            build(ao, mesh);
        return 0;
    }
    ldm_gl_destroy(ao->maps);
    ao->maps = NULL;
    ao->built = want;
    ao->stats.memory_mb = 0;
    const char *why = ldm_ao_check(p);
    ao->refused = 1;
    if (why) {
        snprintf(err, errlen, "%s", why);
        return -1;
    }
    if (!(ao->maps = ldm_gl_create(ao->gl, &want, err, errlen)))
        return -1;
    ao->refused = 0;
    build(ao, mesh);
    ao->stats.memory_mb = ldm_memory_bytes(&want) / (1024.0 * 1024.0);
    return 0;
}

/* The eye-sized target; -1 when it cannot be made (then no AO). */
static int target(renderer_ao *ao, int w, int h)
{
    if (w == ao->w && h == ao->h)
        return 0;
    free_target(ao);
    const gl_functions *gl = ao->gl;
    ao->tex = gltools_texture2d(gl, GL_R32F, w, h, GL_NEAREST);
    gl->GenFramebuffers(1, &ao->fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, ao->fbo);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, ao->tex, 0);
    const GLenum buffer = GL_COLOR_ATTACHMENT0;
    gl->DrawBuffers(1, &buffer);
    char err[160];
    int bad = gltools_fbo_complete(gl, "ambient occlusion", err, sizeof err);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    /* not xalloc: the image size (a setting): no ambient occlusion, said once */
    ao->rgb = malloc((size_t)w * h * 4 * sizeof(float)); /* grey RGB, then the read red */
    if (bad || !ao->rgb) {
        fprintf(stderr, "cavelight-node: %s: no ambient occlusion\n", bad ? err : "out of memory");
        free_target(ao);
        return -1;
    }
    ao->w = w;
    ao->h = h;
    return 0;
}

static void bind_gbuffer(const gl_functions *gl, GLuint prog, const renderer_ao_eye_desc *d)
{
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, d->position);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_position"), 0);
    gl->ActiveTexture(GL_TEXTURE1);
    gl->BindTexture(GL_TEXTURE_2D, d->normal);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_normal"), 1);
}

void renderer_ao_eye(renderer_ao *ao, const renderer_ao_eye_desc *d)
{
    const frame_params *p = &ao->frame;
    const gl_functions *gl = ao->gl;
    int use_ldm = p->ao == FRAME_AO_LDM && ao->maps;
    ao->active = (use_ldm || p->ao == FRAME_AO_SSAO) &&
                 target(ao, d->view->width, d->view->height) == 0;
    ao->stats.eye_ms = 0;
    if (!ao->active)
        return;
    double t0 = clock_now_ms();
    GLuint prog = use_ldm ? ao->prog_ldm : ao->prog_ssao;
    gl->BindFramebuffer(GL_FRAMEBUFFER, ao->fbo);
    gl->Viewport(0, 0, ao->w, ao->h);
    gl->UseProgram(prog);
    bind_gbuffer(gl, prog, d);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_ao_distance"), p->ao_distance);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_ao_falloff"), (int)p->ao_falloff);
    if (use_ldm) {
        ldm_gl_bind(ao->maps, prog);
    } else {
        const float *v = d->view->view; /* rows of the world-to-eye matrix: the axes */
        gl->Uniform4fv(gl->GetUniformLocation(prog, "u_eye"), 1, d->eye);
        gl->Uniform3f(gl->GetUniformLocation(prog, "u_right"), v[0], v[4], v[8]);
        gl->Uniform3f(gl->GetUniformLocation(prog, "u_up"), v[1], v[5], v[9]);
        gl->Uniform1f(gl->GetUniformLocation(prog, "u_pixel_angle"), d->pixel_angle);
        gl->Uniform2f(gl->GetUniformLocation(prog, "u_size"), (float)ao->w, (float)ao->h);
    }
    gl->BindVertexArray(d->vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    gl->BindVertexArray(0);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->UseProgram(0);
    if (d->measure)
        gl->Finish();
    ao->stats.eye_ms = clock_now_ms() - t0;
}

void renderer_ao_bind(const renderer_ao *ao, GLuint prog, int unit)
{
    const gl_functions *gl = ao->gl;
    gl->ActiveTexture((GLenum)(GL_TEXTURE0 + unit));
    gl->BindTexture(GL_TEXTURE_2D, ao->active ? ao->tex : 0);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_ao"), unit);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_ao_on"), ao->active);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_ambient"), ao->frame.ambient);
}

const float *renderer_ao_read(renderer_ao *ao)
{
    if (!ao->active)
        return NULL;
    const gl_functions *gl = ao->gl;
    int w = ao->w, h = ao->h;
    float *red = ao->rgb + (size_t)w * h * 3;
    gl->BindFramebuffer(GL_FRAMEBUFFER, ao->fbo);
    gl->ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->ReadPixels(0, 0, w, h, GL_RED, GL_FLOAT, red);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    for (int y = 0; y < h; y++) /* GL's bottom row first: top row first here */
        for (int x = 0; x < w; x++) {
            float a = red[(size_t)(h - 1 - y) * w + x];
            float *o = ao->rgb + ((size_t)y * w + x) * 3;
            o[0] = o[1] = o[2] = a;
        }
    return ao->rgb;
}

void renderer_ao_stats_get(const renderer_ao *ao, renderer_ao_stats *out)
{
    *out = ao->stats;
}
