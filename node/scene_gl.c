/* scene_gl: the scene's triangles and textures on the GL context (scene_gl.h). */
#include "scene_gl.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/xalloc.h"

typedef struct scene_gl_range {
    uint32_t material;
    GLint first;
    GLsizei count;
} scene_gl_range;

struct scene_gl {
    const gl_functions *gl;
    const scene *scene;
    GLuint vao, vbo;
    scene_gl_range *ranges;
    int range_count;
    GLuint *textures;        /* one per scene texture */
};

/* Triangles grouped by material (stable), one draw per group: position, normal, uv. */
static int upload_triangles(scene_gl *m, char *err, size_t errlen)
{
    const gl_functions *gl = m->gl;
    const scene *s = m->scene;
    size_t nt = s->triangle_count;
    float *v = malloc(nt * 3 * 8 * sizeof(float));
    size_t *order = malloc(nt * sizeof *order);
    size_t *start = calloc(s->material_count + 1, sizeof *start);
    m->ranges = calloc(s->material_count, sizeof *m->ranges);
    if (!v || !order || !start || !m->ranges) {
        free(v); free(order); free(start);
        snprintf(err, errlen, "renderer: out of memory for %zu triangles", nt);
        return -1;
    }
    for (size_t t = 0; t < nt; t++)
        start[s->triangle_material[t] + 1]++;
    for (size_t i = 0; i < s->material_count; i++)
        start[i + 1] += start[i];
    for (size_t i = 0; i < s->material_count; i++)
        if (start[i + 1] > start[i])
            m->ranges[m->range_count++] = (scene_gl_range){
                (uint32_t)i, (GLint)(3 * start[i]), (GLsizei)(3 * (start[i + 1] - start[i]))};
    for (size_t t = 0; t < nt; t++)
        order[start[s->triangle_material[t]]++] = t;
    for (size_t i = 0; i < nt; i++)
        for (int k = 0; k < 3; k++) {
            float *d = v + (i * 3 + k) * 8;
            size_t t = order[i];
            memcpy(d, s->positions + 9 * t + 3 * k, 3 * sizeof(float));
            memcpy(d + 3, s->normals + 9 * t + 3 * k, 3 * sizeof(float));
            memcpy(d + 6, s->uvs + 6 * t + 2 * k, 2 * sizeof(float));
        }
    gl->GenVertexArrays(1, &m->vao);
    gl->BindVertexArray(m->vao);
    gl->GenBuffers(1, &m->vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(nt * 3 * 8 * sizeof(float)), v, GL_STATIC_DRAW);
    for (GLuint a = 0; a < 3; a++) {
        gl->EnableVertexAttribArray(a);
        gl->VertexAttribPointer(a, a == 2 ? 2 : 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float),
                                (const void *)(uintptr_t)(a * 3 * sizeof(float)));
    }
    gl->BindVertexArray(0);
    free(v); free(order); free(start);
    return 0;
}

static int upload_textures(scene_gl *m, char *err, size_t errlen)
{
    const gl_functions *gl = m->gl;
    const scene *s = m->scene;
    m->textures = calloc(s->texture_count ? s->texture_count : 1, sizeof *m->textures);
    if (!m->textures)
        return snprintf(err, errlen, "renderer: out of memory for %zu textures", s->texture_count), -1;
    for (size_t i = 0; i < s->texture_count; i++) {
        const scene_texture *t = &s->textures[i];
        int levels = 1;
        while ((t->width >> levels) > 0 || (t->height >> levels) > 0)
            levels++;
        gl->GenTextures(1, &m->textures[i]);
        gl->BindTexture(GL_TEXTURE_2D, m->textures[i]);
        gl->TexStorage2D(GL_TEXTURE_2D, levels, GL_SRGB8_ALPHA8, t->width, t->height);
        gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, t->width, t->height, GL_RGBA,
                          GL_UNSIGNED_BYTE, t->rgba);
        gl->GenerateMipmap(GL_TEXTURE_2D);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    }
    return 0;
}

scene_gl *scene_gl_create(const gl_functions *gl, const scene *s, char *err, size_t errlen)
{
    scene_gl *m = xcalloc(1, sizeof *m);
    m->gl = gl;
    m->scene = s;
    if (upload_triangles(m, err, errlen) != 0 || upload_textures(m, err, errlen) != 0) {
        scene_gl_destroy(m);
        return NULL;
    }
    return m;
}

void scene_gl_destroy(scene_gl *m)
{
    if (!m)
        return;
    const gl_functions *gl = m->gl;
    if (m->textures && m->scene->texture_count)
        gl->DeleteTextures((GLsizei)m->scene->texture_count, m->textures);
    if (m->vbo)
        gl->DeleteBuffers(1, &m->vbo);
    if (m->vao)
        gl->DeleteVertexArrays(1, &m->vao);
    free(m->textures);
    free(m->ranges);
    free(m);
}

/* Material uniforms shared by the G-buffer and RSM programs (same names). */
static void bind_material(const scene_gl *m, GLuint prog, uint32_t mi)
{
    const gl_functions *gl = m->gl;
    const scene_material *mat = &m->scene->materials[mi];
    gl->Uniform4fv(gl->GetUniformLocation(prog, "u_base_color"), 1, mat->base_color);
    int tex = mat->base_color_texture >= 0 &&
              (size_t)mat->base_color_texture < m->scene->texture_count;
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_has_texture"), tex);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, tex ? m->textures[mat->base_color_texture] : 0);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_base_texture"), 0);
    GLint e = gl->GetUniformLocation(prog, "u_emissive");
    if (e >= 0)
        gl->Uniform3fv(e, 1, mat->emissive);
    GLint ro = gl->GetUniformLocation(prog, "u_roughness");
    if (ro >= 0)
        gl->Uniform1f(ro, mat->roughness);
}

void scene_gl_draw(const scene_gl *m, GLuint prog)
{
    const gl_functions *gl = m->gl;
    gl->BindVertexArray(m->vao);
    for (int i = 0; i < m->range_count; i++) {
        bind_material(m, prog, m->ranges[i].material);
        gl->DrawArrays(GL_TRIANGLES, m->ranges[i].first, m->ranges[i].count);
    }
    gl->BindVertexArray(0);
}
