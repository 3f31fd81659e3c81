/* present_warp: see present_warp.h. */
#include "present_warp.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mat4.h"
#include "base/xalloc.h"
#include "gl/gltools.h"

enum { UNIT_SOURCE, UNIT_GRID, UNIT_ALPHA, UNIT_BETA };

static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

int warp_shader_init(warp_shader *s, const gl_functions *gl, char *err, size_t errlen)
{
    *s = (warp_shader){.gl = gl};
    s->program = gltools_program(gl, "present.vert", "present.frag", NULL, NULL, NULL, err, errlen);
    if (!s->program)
        return -1;
    gl->GenVertexArrays(1, &s->empty_vao);
    gl->UseProgram(s->program);
    static const char *const units[] = {"u_source", "u_grid", "u_alpha", "u_beta"};
    for (int i = 0; i < 4; i++)
        gl->Uniform1i(gl->GetUniformLocation(s->program, units[i]), i);
    return 0;
}

void warp_shader_fini(warp_shader *s)
{
    if (s->program)
        s->gl->DeleteProgram(s->program);
    if (s->empty_vao)
        s->gl->DeleteVertexArrays(1, &s->empty_vao);
    memset(s, 0, sizeof *s);
}

/* A float texture of 1 or 3 channels (a grey map reads as grey in all three). */
static GLuint float_texture(const gl_functions *gl, int w, int h, int channels, const float *v, GLenum filter)
{
    GLuint t = gltools_texture2d(gl, channels == 1 ? GL_R32F : GL_RGB32F, w, h, filter);
    if (channels == 1) {
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_G, GL_RED);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_B, GL_RED);
    }
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, channels == 1 ? GL_RED : GL_RGB, GL_FLOAT, v);
    return t;
}

/* The mesh's vertices (x y u v w) and two triangles per cell. */
static void mesh_buffers(warp_pass *p, const warp_map *m)
{
    const gl_functions *gl = p->shader->gl;
    size_t cells = (size_t)(m->mesh_cols - 1) * (m->mesh_rows - 1);
    GLuint *idx = xmalloc(cells * 6 * sizeof *idx);
    size_t k = 0;
    for (int r = 0; r + 1 < m->mesh_rows; r++)
        for (int c = 0; c + 1 < m->mesh_cols; c++) {
            GLuint a = (GLuint)(r * m->mesh_cols + c), b = a + 1, d = a + (GLuint)m->mesh_cols, e = d + 1;
            const GLuint tri[6] = {a, b, e, a, e, d};
            memcpy(idx + k, tri, sizeof tri);
            k += 6;
        }
    gl->GenVertexArrays(1, &p->mesh_vao);
    gl->BindVertexArray(p->mesh_vao);
    gl->GenBuffers(1, &p->mesh_vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, p->mesh_vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((size_t)m->mesh_cols * m->mesh_rows * 5 * sizeof(float)), m->mesh,
                   GL_STATIC_DRAW);
    gl->GenBuffers(1, &p->mesh_ibo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, p->mesh_ibo);
    gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(k * sizeof *idx), idx, GL_STATIC_DRAW);
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 5 * sizeof(float), (const void *)0);
    gl->EnableVertexAttribArray(1);
    gl->VertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, 5 * sizeof(float), (const void *)(4 * sizeof(float)));
    gl->BindVertexArray(0);
    p->mesh_indices = (int)k;
    free(idx);
}

int warp_pass_init(warp_pass *p, const warp_shader *s, const warp_map *map, const float *to_cave,
                   int src_w, int src_h, char *err, size_t errlen)
{
    const gl_functions *gl = s->gl;
    *p = (warp_pass){.shader = s, .kind = map ? map->kind : WARP_NONE, .src_w = src_w, .src_h = src_h,
                     .out_w = map && map->out_w > 0 ? map->out_w : src_w,
                     .out_h = map && map->out_h > 0 ? map->out_h : src_h,
                     .alpha_gamma = map ? map->alpha_gamma : 1};
    memcpy(p->to_cave, to_cave ? to_cave : identity, sizeof p->to_cave);
    p->source = gltools_texture2d(gl, GL_RGB8, src_w, src_h, GL_LINEAR);
    if (map && (map->kind == WARP_UV_GRID || map->kind == WARP_POINT_GRID))
        p->grid = float_texture(gl, map->grid_w, map->grid_h, 3, map->grid, GL_NEAREST);
    if (map && map->kind == WARP_MESH)
        mesh_buffers(p, map);
    if (map && map->alpha.values)
        p->alpha = float_texture(gl, map->alpha.width, map->alpha.height, map->alpha.channels, map->alpha.values,
                                 GL_LINEAR);
    if (map && map->beta.values)
        p->beta = float_texture(gl, map->beta.width, map->beta.height, map->beta.channels, map->beta.values,
                                GL_LINEAR);
    GLenum e = gl->GetError();
    if (e != GL_NO_ERROR) {
        snprintf(err, errlen, "presentation: GL error 0x%x making a %d x %d projector image's textures "
                 "(out of GPU memory?)", (unsigned)e, p->out_w, p->out_h);
        warp_pass_fini(p);
        return -1;
    }
    return 0;
}

void warp_pass_fini(warp_pass *p)
{
    if (!p->shader)
        return;
    const gl_functions *gl = p->shader->gl;
    GLuint tex[4] = {p->source, p->grid, p->alpha, p->beta}, buf[2] = {p->mesh_vbo, p->mesh_ibo};
    gl->DeleteTextures(4, tex);
    gl->DeleteBuffers(2, buf);
    if (p->mesh_vao)
        gl->DeleteVertexArrays(1, &p->mesh_vao);
    memset(p, 0, sizeof *p);
}

void warp_pass_upload(warp_pass *p, const uint8_t *rgb)
{
    const gl_functions *gl = p->shader->gl;
    gl->BindTexture(GL_TEXTURE_2D, p->source);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, p->src_w, p->src_h, GL_RGB, GL_UNSIGNED_BYTE, rgb);
}

void warp_pass_draw(const warp_pass *p, const warp_draw *d)
{
    const gl_functions *gl = p->shader->gl;
    GLuint prog = p->shader->program;
    gl->Viewport(d->rect[0], d->rect[1], d->rect[2], d->rect[3]);
    gl->UseProgram(prog);
    float m[16];
    mat4_mul(d->cave_to_clip ? d->cave_to_clip : identity, p->to_cave, m);
    const float rect[4] = {(float)d->rect[0], (float)d->rect[1], (float)d->rect[2], (float)d->rect[3]};
    gl->Uniform4fv(gl->GetUniformLocation(prog, "u_rect"), 1, rect);
    gl->UniformMatrix4fv(gl->GetUniformLocation(prog, "u_cave_to_clip"), 1, GL_FALSE, m);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_mode"), (GLint)p->kind);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_mesh"), p->kind == WARP_MESH);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_alpha_map"), p->alpha != 0);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_beta_map"), p->beta != 0);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_alpha_gamma"), p->alpha_gamma);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_display_gamma"), d->display_gamma);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_show_blend"), d->show_blend);
    const GLuint tex[4] = {p->source, p->grid, p->alpha, p->beta};
    for (int u = UNIT_SOURCE; u <= UNIT_BETA; u++) {
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)u);
        gl->BindTexture(GL_TEXTURE_2D, tex[u]);
    }
    if (p->kind == WARP_MESH) {
        gl->BindVertexArray(p->mesh_vao);
        gl->DrawElements(GL_TRIANGLES, p->mesh_indices, GL_UNSIGNED_INT, NULL);
    } else {
        gl->BindVertexArray(p->shader->empty_vao);
        gl->DrawArrays(GL_TRIANGLES, 0, 3);
    }
    gl->BindVertexArray(0);
    gl->ActiveTexture(GL_TEXTURE0);
}
