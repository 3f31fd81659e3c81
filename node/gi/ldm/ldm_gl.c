/* ldm_gl: see ldm_gl.h. */
#include "ldm_gl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/fnv1a.h"
#include "base/xalloc.h"
#include "gl/gltools.h"
#include "gi/ldm/ldm_directions.h"

struct ldm_gl {
    const gl_functions *gl;
    ldm_layout layout;
    ldm_map maps[LDM_DIRECTIONS_MAX];
    GLuint prog, fbo;
    GLuint depth, bases, overflow;  /* shader storage buffers */
    uint64_t checksum;
    size_t overflowed;
};

static GLuint storage(const gl_functions *gl, size_t bytes, const void *data)
{
    GLuint b;
    gl->GenBuffers(1, &b);
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    gl->BufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)bytes, data, GL_DYNAMIC_COPY);
    return b;
}

ldm_gl *ldm_gl_create(const gl_functions *gl, const ldm_layout *l, char *err, size_t errlen)
{
    ldm_gl *m = xcalloc(1, sizeof *m);
    m->gl = gl;
    m->layout = *l;
    ldm_layout_maps(l, m->maps);
    if (!(m->prog = gltools_program(gl, "scene.vert", "ldm_build.frag", NULL, NULL, NULL, err,
                                    errlen))) {
        ldm_gl_destroy(m);
        return NULL;
    }
    float bases[LDM_DIRECTIONS_MAX * 12] = {0};
    for (int i = 0; i < l->directions; i++)
        for (int a = 0; a < 3; a++) {
            bases[12 * i + a] = m->maps[i].u[a];
            bases[12 * i + 4 + a] = m->maps[i].v[a];
            bases[12 * i + 8 + a] = m->maps[i].d[a];
        }
    m->bases = storage(gl, (size_t)l->directions * 12 * sizeof(float), bases);
    m->overflow = storage(gl, sizeof(GLuint), NULL);
    while (gl->GetError() != GL_NO_ERROR) {
    }
    m->depth = storage(gl, (size_t)ldm_memory_bytes(l), NULL);
    GLenum e = gl->GetError();
    gl->GenFramebuffers(1, &m->fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->fbo);
    gl->FramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_WIDTH, l->resolution);
    gl->FramebufferParameteri(GL_FRAMEBUFFER, GL_FRAMEBUFFER_DEFAULT_HEIGHT, l->resolution);
    int bad = gltools_fbo_complete(gl, "layered depth map", err, errlen);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (e != GL_NO_ERROR || bad) {
        if (e != GL_NO_ERROR)
            snprintf(err, errlen, "ldm: the GL has no room for %.0f MB of layered depth maps "
                     "(GL error 0x%x)", ldm_memory_bytes(l) / (1024.0 * 1024.0), (unsigned)e);
        ldm_gl_destroy(m);
        return NULL;
    }
    return m;
}

void ldm_gl_destroy(ldm_gl *m)
{
    if (!m)
        return;
    const gl_functions *gl = m->gl;
    GLuint buffers[] = {m->depth, m->bases, m->overflow};
    for (int i = 0; i < 3; i++)
        if (buffers[i])
            gl->DeleteBuffers(1, &buffers[i]);
    if (m->fbo)
        gl->DeleteFramebuffers(1, &m->fbo);
    if (m->prog)
        gl->DeleteProgram(m->prog);
    free(m);
}

/* Column-major map projection: clip x, y = (p - c).u / R, (p - c).v / R; z = (t - R) / R,
 * inside [-1, 1] for the whole bounding sphere (nothing is clipped). */
static void map_projection(const ldm_layout *l, const ldm_map *mp, float out[16])
{
    const float *rows[3] = {mp->u, mp->v, mp->d};
    memset(out, 0, 16 * sizeof(float));
    for (int r = 0; r < 3; r++) {
        float off = 0;
        for (int a = 0; a < 3; a++) {
            out[4 * a + r] = rows[r][a] / l->radius;
            off += rows[r][a] * l->centre[a];
        }
        out[12 + r] = -off / l->radius;
    }
    out[15] = 1.0f;
}

static void set_uniforms(const ldm_gl *m, GLuint prog)
{
    const gl_functions *gl = m->gl;
    const ldm_layout *l = &m->layout;
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_ldm_count"), l->directions);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_ldm_resolution"), l->resolution);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_ldm_layers"), l->layers);
    gl->Uniform3fv(gl->GetUniformLocation(prog, "u_ldm_centre"), 1, l->centre);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_ldm_radius"), l->radius);
}

double ldm_gl_build(ldm_gl *m, const scene_gl *mesh)
{
    const gl_functions *gl = m->gl;
    const ldm_layout *l = &m->layout;
    double t0 = clock_now_ms();
    const GLuint empty = LDM_EMPTY, zero = 0;
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, m->depth);
    gl->ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, m->overflow);
    gl->ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m->depth);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, m->bases);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, m->overflow);
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->fbo);
    gl->Viewport(0, 0, l->resolution, l->resolution);
    gl->Disable(GL_DEPTH_TEST);
    gl->Disable(GL_CULL_FACE);
    gl->UseProgram(m->prog);
    set_uniforms(m, m->prog);
    GLint map_loc = gl->GetUniformLocation(m->prog, "u_ldm_map");
    GLint vp_loc = gl->GetUniformLocation(m->prog, "u_view_projection");
    for (int i = 0; i < l->directions; i++) {
        float vp[16];
        map_projection(l, &m->maps[i], vp);
        gl->UniformMatrix4fv(vp_loc, 1, GL_FALSE, vp);
        gl->Uniform1i(map_loc, i);
        scene_gl_draw_geometry(mesh, m->prog); /* every object where it is now */
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    gl->Finish();
    double built = clock_now_ms() - t0;
    GLuint lost = 0;
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, m->overflow);
    gl->GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof lost, &lost);
    m->overflowed = lost;
    size_t words = (size_t)(ldm_memory_bytes(l) / 4.0);
    /* not xalloc: the ldm memory setting's size: without it the checksum is 0 */
    uint32_t *all = malloc(words * sizeof *all);
    m->checksum = 0;
    if (all) {
        ldm_gl_read(m, all);
        m->checksum = fnv1a64(FNV1A64_CLUSTER_SEED, all, words * sizeof *all);
    }
    free(all);
    return built;
}

const ldm_layout *ldm_gl_layout(const ldm_gl *m) { return &m->layout; }
const ldm_map *ldm_gl_maps(const ldm_gl *m) { return m->maps; }
uint64_t ldm_gl_checksum(const ldm_gl *m) { return m->checksum; }
size_t ldm_gl_overflow(const ldm_gl *m) { return m->overflowed; }

void ldm_gl_bind(const ldm_gl *m, GLuint prog)
{
    m->gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m->depth);
    m->gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, m->bases);
    set_uniforms(m, prog);
}

void ldm_gl_read(const ldm_gl *m, uint32_t *out)
{
    const gl_functions *gl = m->gl;
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, m->depth);
    gl->GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, (GLsizeiptr)ldm_memory_bytes(&m->layout), out);
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
}
