/* renderer_rsm: the reflective shadow maps, the lights' shading uniforms and the shared
 * VPL source (renderer_rsm.h). */
#include "renderer_rsm.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/xalloc.h"
#include "gltools.h"

struct renderer_rsm {
    const gl_functions *gl;
    const scene *scene;
    GLuint prog;
    int size;                /* texels per side */
    int layers;              /* layers allocated */
    GLuint fbo[LIGHT_VIEW_MAX];
    GLuint position, normal, flux, depth;
    int view_count;          /* views rendered by the last render */
    light_view views[LIGHT_VIEW_MAX];
    float *read[3];          /* position, normal, flux of one layer, read back */
    lpv_vpl *vpls;           /* renderer_rsm_vpls()'s array */
    size_t vpl_capacity;
};

static const GLenum rsm_buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                                      GL_COLOR_ATTACHMENT2};

static void release(renderer_rsm *r)
{
    const gl_functions *gl = r->gl;
    GLuint tex[] = {r->position, r->normal, r->flux, r->depth};
    for (int i = 0; i < 4; i++)
        if (tex[i])
            gl->DeleteTextures(1, &tex[i]);
    if (r->layers > 0)
        gl->DeleteFramebuffers(r->layers, r->fbo);
    r->position = r->normal = r->flux = r->depth = 0;
    r->layers = 0;
}

/* At least `layers` layers (never fewer than before). */
static int reserve(renderer_rsm *r, int layers, char *err, size_t errlen)
{
    if (layers <= r->layers)
        return 0;
    const gl_functions *gl = r->gl;
    release(r);
    int size = r->size;
    r->position = gltools_texture_array(gl, GL_RGBA32F, size, layers);
    r->normal = gltools_texture_array(gl, GL_RGBA32F, size, layers);
    r->flux = gltools_texture_array(gl, GL_RGBA32F, size, layers);
    r->depth = gltools_texture_array(gl, GL_DEPTH_COMPONENT32F, size, layers);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl->GenFramebuffers(layers, r->fbo);
    r->layers = layers;
    for (int i = 0; i < layers; i++) {
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo[i]);
        gl->FramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, r->position, 0, i);
        gl->FramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, r->normal, 0, i);
        gl->FramebufferTextureLayer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, r->flux, 0, i);
        gl->FramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, r->depth, 0, i);
        gl->DrawBuffers(3, rsm_buffers);
        if (gltools_fbo_complete(gl, "RSM", err, errlen)) {
            gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
            return -1;
        }
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    return 0;
}

renderer_rsm *renderer_rsm_create(const gl_functions *gl, const scene *s, int size, char *err,
                                  size_t errlen)
{
    renderer_rsm *r = xcalloc(1, sizeof *r);
    r->gl = gl;
    r->scene = s;
    r->size = size;
    /* As many layers as the scene's own lights need; a frame that needs more grows them. */
    frame_params p;
    frame_params_default(&p);
    frame_params_lights_from_scene(&p, s);
    light_view views[LIGHT_VIEW_MAX];
    int n = light_views(&p, s, size, views);
    size_t texels = (size_t)size * size;
    /* not xalloc: the RSM size (a setting): refused in err */
    for (int i = 0; i < 3; i++)
        if (!(r->read[i] = malloc(texels * 4 * sizeof(float)))) {
            snprintf(err, errlen, "renderer: out of memory for the RSM readback");
            renderer_rsm_destroy(r);
            return NULL;
        }
    if (!(r->prog = gltools_program(gl, "scene.vert", "rsm.frag", NULL, NULL, NULL, err, errlen)) ||
        reserve(r, n > 0 ? n : 1, err, errlen) != 0) {
        renderer_rsm_destroy(r);
        return NULL;
    }
    return r;
}

void renderer_rsm_destroy(renderer_rsm *r)
{
    if (!r)
        return;
    release(r);
    if (r->prog)
        r->gl->DeleteProgram(r->prog);
    for (int i = 0; i < 3; i++)
        free(r->read[i]);
    free(r->vpls);
    free(r);
}

int renderer_rsm_views(const renderer_rsm *r, const light_view **views, const GLuint **fbo)
{
    if (views)
        *views = r->views;
    if (fbo)
        *fbo = r->fbo;
    return r->view_count;
}

int renderer_rsm_size(const renderer_rsm *r) { return r->size; }

void renderer_rsm_textures(const renderer_rsm *r, GLuint out[3])
{
    out[0] = r->position;
    out[1] = r->normal;
    out[2] = r->flux;
}

static void uniform1i(const renderer_rsm *r, GLuint prog, const char *name, int v)
{
    r->gl->Uniform1i(r->gl->GetUniformLocation(prog, name), v);
}

static void uniform1f(const renderer_rsm *r, GLuint prog, const char *name, float v)
{
    r->gl->Uniform1f(r->gl->GetUniformLocation(prog, name), v);
}

/* Texel size at the depth z along a view's axis is a z + b: perspective views (spots and
 * cube faces) 2 tan(half fov) / size per unit depth, orthographic ones a constant. */
static void texel_coefficients(const renderer_rsm *r, const light_view *v, float ab[2])
{
    if (v->orthographic) {
        ab[0] = 0.0f;
        ab[1] = 2.0f * fmaxf(v->extent[0], v->extent[1]) / (float)r->size;
    } else {
        ab[0] = 2.0f * v->tan_half_fov / (float)r->size;
        ab[1] = 0.0f;
    }
}

void renderer_rsm_render(renderer_rsm *r, const scene_gl *mesh, const frame_params *p)
{
    const gl_functions *gl = r->gl;
    GLuint prog = r->prog;
    int n = light_views(p, r->scene, r->size, r->views);
    char err[160];
    if (reserve(r, n, err, sizeof err) != 0) { /* keep the layers there are */
        fprintf(stderr, "cavelight-node: %s: shadows of %d views left out\n", err,
                n - r->layers);
        n = r->layers;
    }
    r->view_count = n;
    gl->UseProgram(prog);
    gl->Viewport(0, 0, r->size, r->size);
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    for (int k = 0; k < n; k++) {
        const light_view *v = &r->views[k];
        const frame_light *l = &p->lights[v->light];
        float outer, inner;
        light_cone(l, &outer, &inner);
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo[k]);
        const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
        for (int b = 0; b < 3; b++)
            gl->ClearBufferfv(GL_COLOR, b, zero);
        gl->ClearBufferfv(GL_DEPTH, 0, &one);
        gl->UniformMatrix4fv(gl->GetUniformLocation(prog, "u_view_projection"), 1, GL_FALSE,
                             v->view_projection);
        gl->Uniform3fv(gl->GetUniformLocation(prog, "u_light_position"), 1, l->position);
        gl->Uniform3fv(gl->GetUniformLocation(prog, "u_light_direction"), 1, l->direction);
        float radiance[3] = {l->color[0] * l->intensity, l->color[1] * l->intensity,
                             l->color[2] * l->intensity};
        gl->Uniform3fv(gl->GetUniformLocation(prog, "u_light_radiance"), 1, radiance);
        uniform1i(r, prog, "u_light_type", (int)l->type);
        uniform1f(r, prog, "u_cos_outer", cosf(outer));
        uniform1f(r, prog, "u_cos_inner", cosf(inner));
        uniform1f(r, prog, "u_tan_half_fov", v->tan_half_fov);
        uniform1f(r, prog, "u_vpl_tan", v->vpl_tan);
        float texel_area = 4.0f * v->extent[0] * v->extent[1] / ((float)r->size * r->size);
        uniform1f(r, prog, "u_texel_area", texel_area);
        const float origin[3] = {0, 0, 0};
        uniform1f(r, prog, "u_travel0", light_directional_travel(r->scene, l->direction, origin));
        uniform1f(r, prog, "u_size", (float)r->size);
        uniform1f(r, prog, "u_absorption", p->absorption);
        scene_gl_draw(mesh, prog);
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void renderer_rsm_bind_shading(const renderer_rsm *r, GLuint prog, const frame_params *p,
                               GLenum depth_unit, GLenum normal_unit)
{
    const gl_functions *gl = r->gl;
    gl->ActiveTexture(GL_TEXTURE0 + depth_unit);
    gl->BindTexture(GL_TEXTURE_2D_ARRAY, r->depth);
    uniform1i(r, prog, "u_shadow", (int)depth_unit);
    gl->ActiveTexture(GL_TEXTURE0 + normal_unit);
    gl->BindTexture(GL_TEXTURE_2D_ARRAY, r->normal);
    uniform1i(r, prog, "u_rsm_normal", (int)normal_unit);
    float pos[FRAME_MAX_LIGHTS][3], dir[FRAME_MAX_LIGHTS][3], rad[FRAME_MAX_LIGHTS][3];
    float cos_outer[FRAME_MAX_LIGHTS], cos_inner[FRAME_MAX_LIGHTS], travel0[FRAME_MAX_LIGHTS];
    float texel[FRAME_MAX_LIGHTS][2];
    int type[FRAME_MAX_LIGHTS], first[FRAME_MAX_LIGHTS], nl = 0;
    float vp[LIGHT_VIEW_MAX][16];
    for (int k = 0; k < r->view_count; k++) {
        const light_view *v = &r->views[k];
        memcpy(vp[k], v->view_projection, sizeof vp[k]);
        if (v->face != 0)
            continue; /* a point light's other faces: the shader picks them from the first */
        const frame_light *l = &p->lights[v->light];
        float outer, inner;
        light_cone(l, &outer, &inner);
        memcpy(pos[nl], l->position, sizeof pos[nl]);
        memcpy(dir[nl], l->direction, sizeof dir[nl]);
        for (int c = 0; c < 3; c++)
            rad[nl][c] = l->color[c] * l->intensity;
        cos_outer[nl] = cosf(outer);
        cos_inner[nl] = cosf(inner);
        const float origin[3] = {0, 0, 0};
        travel0[nl] = light_directional_travel(r->scene, l->direction, origin);
        texel_coefficients(r, v, texel[nl]);
        type[nl] = (int)l->type;
        first[nl] = k;
        nl++;
    }
    uniform1i(r, prog, "u_light_count", nl);
    if (nl > 0) {
        gl->Uniform1iv(gl->GetUniformLocation(prog, "u_light_type"), nl, type);
        gl->Uniform1iv(gl->GetUniformLocation(prog, "u_light_first_view"), nl, first);
        gl->Uniform3fv(gl->GetUniformLocation(prog, "u_light_position"), nl, pos[0]);
        gl->Uniform3fv(gl->GetUniformLocation(prog, "u_light_direction"), nl, dir[0]);
        gl->Uniform3fv(gl->GetUniformLocation(prog, "u_light_radiance"), nl, rad[0]);
        gl->Uniform1fv(gl->GetUniformLocation(prog, "u_cos_outer"), nl, cos_outer);
        gl->Uniform1fv(gl->GetUniformLocation(prog, "u_cos_inner"), nl, cos_inner);
        gl->Uniform1fv(gl->GetUniformLocation(prog, "u_light_travel0"), nl, travel0);
        gl->Uniform2fv(gl->GetUniformLocation(prog, "u_light_texel"), nl, texel[0]);
        gl->UniformMatrix4fv(gl->GetUniformLocation(prog, "u_light_view_projection"), r->view_count,
                             GL_FALSE, vp[0]);
    }
    uniform1f(r, prog, "u_shadow_texel", 1.0f / (float)r->size);
    uniform1f(r, prog, "u_min_light_distance", scene_min_light_distance(r->scene));
}

void renderer_rsm_read_layer(renderer_rsm *r, int layer, const float **position,
                             const float **normal, const float **flux)
{
    const gl_functions *gl = r->gl;
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo[layer]);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    for (int b = 0; b < 3; b++) {
        gl->ReadBuffer(GL_COLOR_ATTACHMENT0 + b);
        gl->ReadPixels(0, 0, r->size, r->size, GL_RGBA, GL_FLOAT, r->read[b]);
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    *position = r->read[0];
    *normal = r->read[1];
    *flux = r->read[2];
}

size_t renderer_rsm_vpls(renderer_rsm *r, lpv_vpl **out)
{
    size_t texels = (size_t)r->size * r->size, n = 0;
    size_t need = (size_t)r->view_count * texels;
    if (need > r->vpl_capacity) {
        /* not xalloc: the RSM size (a setting): no VPLs this frame */
        lpv_vpl *v = realloc(r->vpls, need * sizeof *v);
        if (!v) { /* out of memory: no VPLs this frame rather than a crash */
            *out = r->vpls;
            return 0;
        }
        r->vpls = v;
        r->vpl_capacity = need;
    }
    for (int layer = 0; layer < r->view_count; layer++) {
        const float *pos, *nrm, *flux;
        renderer_rsm_read_layer(r, layer, &pos, &nrm, &flux);
        for (size_t i = 0; i < texels; i++) {
            const float *f = flux + 4 * i;
            if (pos[4 * i + 3] == 0.0f || !(f[0] > 0 || f[1] > 0 || f[2] > 0))
                continue;
            lpv_vpl *v = &r->vpls[n++];
            memcpy(v->position, pos + 4 * i, sizeof v->position);
            memcpy(v->normal, nrm + 4 * i, sizeof v->normal);
            memcpy(v->flux, f, sizeof v->flux);
        }
    }
    *out = r->vpls;
    return n;
}
