/* scene_gl: the scene's triangles and textures on the GL context (scene_gl.h). */
#include "scene_gl.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/xalloc.h"

typedef struct scene_gl_range {
    uint32_t material;
    int object;              /* -1: static */
    GLint first;
    GLsizei count;
} scene_gl_range;

/* Where an object is: its model, its normals' matrix, shown or not. */
typedef struct scene_gl_place {
    float model[16];
    float normal[9];
    int shown;
} scene_gl_place;

struct scene_gl {
    const gl_functions *gl;
    const scene *scene;
    GLuint vao, vbo;
    scene_gl_range *ranges;
    int range_count;
    GLuint *textures;        /* one per scene texture */
    scene_gl_place *places;  /* per object, and the static triangles' last */
};

static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

/* A triangle's group: static triangles first, then by object, each by material. */
static size_t group_of(const scene *s, size_t t)
{
    int o = s->triangle_object ? s->triangle_object[t] : -1;
    return (size_t)(o + 1) * s->material_count + s->triangle_material[t];
}

/* Triangles grouped by object and material (stable), one draw per group: position,
 * normal, uv. */
static int upload_triangles(scene_gl *m, char *err, size_t errlen)
{
    const gl_functions *gl = m->gl;
    const scene *s = m->scene;
    size_t nt = s->triangle_count, groups = (size_t)(s->object_count + 1) * s->material_count;
    /* not xalloc: the scene's triangles: refused in err */
    float *v = malloc(nt * 3 * 8 * sizeof(float));
    size_t *order = malloc(nt * sizeof *order);
    size_t *start = calloc(groups + 1, sizeof *start);
    m->ranges = calloc(groups, sizeof *m->ranges);
    if (!v || !order || !start || !m->ranges) {
        free(v); free(order); free(start);
        snprintf(err, errlen, "renderer: out of memory for %zu triangles", nt);
        return -1;
    }
    for (size_t t = 0; t < nt; t++)
        start[group_of(s, t) + 1]++;
    for (size_t i = 0; i < groups; i++)
        start[i + 1] += start[i];
    for (size_t i = 0; i < groups; i++)
        if (start[i + 1] > start[i])
            m->ranges[m->range_count++] = (scene_gl_range){
                (uint32_t)(i % s->material_count), (int)(i / s->material_count) - 1, (GLint)(3 * start[i]),
                (GLsizei)(3 * (start[i + 1] - start[i]))};
    for (size_t t = 0; t < nt; t++)
        order[start[group_of(s, t)]++] = t;
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
    /* not xalloc: the scene's texture count: refused in err */
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

/* The cofactor matrix of m's 3x3: normals through it stay perpendicular to the surface
 * under any invertible model (proportional to the inverse transpose). */
static void normal_matrix(const float *m, float out[9])
{
    out[0] = m[5] * m[10] - m[6] * m[9];
    out[1] = m[6] * m[8] - m[4] * m[10];
    out[2] = m[4] * m[9] - m[5] * m[8];
    out[3] = m[9] * m[2] - m[10] * m[1];
    out[4] = m[10] * m[0] - m[8] * m[2];
    out[5] = m[8] * m[1] - m[9] * m[0];
    out[6] = m[1] * m[6] - m[2] * m[5];
    out[7] = m[2] * m[4] - m[0] * m[6];
    out[8] = m[0] * m[5] - m[1] * m[4];
}

void scene_gl_set_pose(scene_gl *m, const float (*model)[16], const uint8_t *shown)
{
    for (int o = 0; o < m->scene->object_count; o++) {
        memcpy(m->places[o].model, model[o], sizeof m->places[o].model);
        normal_matrix(model[o], m->places[o].normal);
        m->places[o].shown = shown[o];
    }
}

scene_gl *scene_gl_create(const gl_functions *gl, const scene *s, char *err, size_t errlen)
{
    scene_gl *m = xcalloc(1, sizeof *m);
    m->gl = gl;
    m->scene = s;
    m->places = xcalloc((size_t)s->object_count + 1, sizeof *m->places);
    for (int o = 0; o <= s->object_count; o++) { /* as loaded; the last: static */
        memcpy(m->places[o].model, identity, sizeof identity);
        normal_matrix(identity, m->places[o].normal);
        m->places[o].shown = 1;
    }
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
    free(m->places);
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

/* The ranges from i on that belong to range i's object: [first, *end). */
static GLsizei object_run(const scene_gl *m, int i, int *end)
{
    int k = i;
    while (k + 1 < m->range_count && m->ranges[k + 1].object == m->ranges[i].object)
        k++;
    *end = k + 1;
    return m->ranges[k].first + m->ranges[k].count - m->ranges[i].first;
}

/* Sets the object's matrices for ranges[i]; 0 when the object is hidden. */
static int place(const scene_gl *m, int i, GLint model, GLint normal)
{
    int o = m->ranges[i].object;
    const scene_gl_place *pl = &m->places[o < 0 ? m->scene->object_count : o];
    if (!pl->shown)
        return 0;
    m->gl->UniformMatrix4fv(model, 1, GL_FALSE, pl->model);
    m->gl->UniformMatrix3fv(normal, 1, GL_FALSE, pl->normal);
    return 1;
}

void scene_gl_draw(const scene_gl *m, GLuint prog)
{
    const gl_functions *gl = m->gl;
    GLint model = gl->GetUniformLocation(prog, "u_model"), normal = gl->GetUniformLocation(prog, "u_normal_model");
    gl->BindVertexArray(m->vao);
    for (int i = 0; i < m->range_count; i++) {
        if (!place(m, i, model, normal))
            continue;
        bind_material(m, prog, m->ranges[i].material);
        gl->DrawArrays(GL_TRIANGLES, m->ranges[i].first, m->ranges[i].count);
    }
    gl->BindVertexArray(0);
}

void scene_gl_draw_geometry(const scene_gl *m, GLuint prog)
{
    const gl_functions *gl = m->gl;
    GLint model = gl->GetUniformLocation(prog, "u_model"), normal = gl->GetUniformLocation(prog, "u_normal_model");
    gl->BindVertexArray(m->vao);
    for (int i = 0, end; i < m->range_count; i = end) {
        GLsizei count = object_run(m, i, &end);
        if (place(m, i, model, normal))
            gl->DrawArrays(GL_TRIANGLES, m->ranges[i].first, count);
    }
    gl->BindVertexArray(0);
}
