/* app_draw: points and lines of an application into the G-buffer (app_draw.h). */
#include "app_draw.h"

#include <stdint.h>
#include <stdlib.h>

#include "base/xalloc.h"
#include "gl/gltools.h"

struct app_draw {
    const gl_functions *gl;
    GLuint prog, vao, vbo;
};

app_draw *app_draw_create(const gl_functions *gl, char *err, size_t errlen)
{
    app_draw *a = xcalloc(1, sizeof *a);
    a->gl = gl;
    if (!(a->prog = gltools_program(gl, "app_geometry.vert", "app_geometry.frag", NULL, NULL, NULL, err, errlen))) {
        free(a);
        return NULL;
    }
    gl->GenVertexArrays(1, &a->vao);
    gl->BindVertexArray(a->vao);
    gl->GenBuffers(1, &a->vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, a->vbo);
    for (GLuint k = 0; k < 3; k++) {
        gl->EnableVertexAttribArray(k);
        gl->VertexAttribPointer(k, 3, GL_FLOAT, GL_FALSE, sizeof(cavelight_vertex),
                                (const void *)(uintptr_t)(k * 3 * sizeof(float)));
    }
    gl->BindVertexArray(0);
    return a;
}

void app_draw_destroy(app_draw *a)
{
    if (!a)
        return;
    a->gl->DeleteProgram(a->prog);
    a->gl->DeleteBuffers(1, &a->vbo);
    a->gl->DeleteVertexArrays(1, &a->vao);
    free(a);
}

void app_draw_geometry(app_draw *a, const cavelight_draw *d, int mode, const cavelight_vertex *v, int count,
                       float size)
{
    const gl_functions *gl = a->gl;
    const float eye[4] = {d->eye_position[0], d->eye_position[1], d->eye_position[2], 1.0f};
    gl->UseProgram(a->prog);
    gl->UniformMatrix4fv(gl->GetUniformLocation(a->prog, "u_view_projection"), 1, GL_FALSE, d->view_projection);
    gl->Uniform4fv(gl->GetUniformLocation(a->prog, "u_eye"), 1, eye);
    gl->Uniform1f(gl->GetUniformLocation(a->prog, "u_point_size"), size > 1.0f ? size : 1.0f);
    gl->Uniform1f(gl->GetUniformLocation(a->prog, "u_roughness"), 0.8f);
    gl->BindVertexArray(a->vao);
    gl->BindBuffer(GL_ARRAY_BUFFER, a->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((size_t)count * sizeof *v), v, GL_STREAM_DRAW);
    if (mode == 0)
        gl->Enable(GL_PROGRAM_POINT_SIZE);
    gl->DrawArrays(mode == 0 ? GL_POINTS : GL_LINES, 0, mode == 0 ? count : count / 2 * 2);
    if (mode == 0)
        gl->Disable(GL_PROGRAM_POINT_SIZE);
    gl->BindVertexArray(0);
}
