/* vpl_ism: imperfect shadow maps (vpl_ism.h). GL: the point set in one vertex buffer, drawn
 * once for all VPLs (shaders/ism_point.vert), into level 0 of a pyramid of RGBA32F atlases;
 * pull passes build the coarser levels, push passes write a second pyramid from the top
 * down, whose level 0 is the map shade.frag reads. */
#include "gi/vpl/vpl_ism.h"
#include "gi/vpl/vpl_settings.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/xalloc.h"
#include "gi/vpl/ism_points.h"
#include "gl/gltools.h"

enum { ISM_ATLAS_MAX = 2048, ISM_LEVELS_MAX = 8 }; /* 2^8 = VPL_ISM_SIZE_MAX */

struct vpl_ism {
    const gl_functions *gl;
    const scene *scene;
    int size, points, splat;   /* as asked */
    float far, radius;         /* a point's disk, world units */
    float *host;               /* the first `generated` points of the scene's sequence */
    size_t generated;
    GLuint prog_point, prog_pull, prog_push, vao_points, vbo, vao_empty, fbo;
    int tile, tiles, levels;   /* this frame's tile side (<= size), tiles per side, levels */
    int allocated_side;        /* atlas side the textures were made for */
    GLuint pulled[ISM_LEVELS_MAX + 1], pushed[ISM_LEVELS_MAX], depth;
    GLuint result;             /* the map shade.frag reads */
};

static void release_atlas(vpl_ism *m)
{
    const gl_functions *gl = m->gl;
    for (int k = 0; k <= ISM_LEVELS_MAX; k++) {
        if (m->pulled[k])
            gl->DeleteTextures(1, &m->pulled[k]);
        if (k < ISM_LEVELS_MAX && m->pushed[k])
            gl->DeleteTextures(1, &m->pushed[k]);
        m->pulled[k] = 0;
        if (k < ISM_LEVELS_MAX)
            m->pushed[k] = 0;
    }
    if (m->depth)
        gl->DeleteTextures(1, &m->depth);
    m->depth = m->result = 0;
    m->allocated_side = 0;
}

void vpl_ism_destroy(vpl_ism *m)
{
    if (!m)
        return;
    const gl_functions *gl = m->gl;
    release_atlas(m);
    GLuint programs[3] = {m->prog_point, m->prog_pull, m->prog_push};
    for (int i = 0; i < 3; i++)
        if (programs[i])
            gl->DeleteProgram(programs[i]);
    if (m->vbo)
        gl->DeleteBuffers(1, &m->vbo);
    GLuint vaos[2] = {m->vao_points, m->vao_empty};
    for (int i = 0; i < 2; i++)
        if (vaos[i])
            gl->DeleteVertexArrays(1, &vaos[i]);
    if (m->fbo)
        gl->DeleteFramebuffers(1, &m->fbo);
    free(m->host);
    free(m);
}

vpl_ism *vpl_ism_create(const vpl_ism_desc *d, char *err, size_t errlen)
{
    vpl_ism *m = xcalloc(1, sizeof *m);
    const gl_functions *gl = d->gl;
    *m = (vpl_ism){.gl = gl, .scene = d->scene, .size = d->size, .points = d->points,
                   .splat = d->splat, .far = d->far};
    m->radius = ism_point_radius(ism_scene_area(d->scene), d->points);
    if (!(m->prog_point = gltools_program(gl, "vpl/ism_point.vert", "vpl/ism_point.frag", NULL, NULL,
                                          NULL, err, errlen)) ||
        !(m->prog_pull = gltools_program(gl, "fullscreen.vert", "vpl/ism_pullpush.frag", NULL, NULL,
                                         NULL, err, errlen)) ||
        !(m->prog_push = gltools_program(gl, "fullscreen.vert", "vpl/ism_pullpush.frag", NULL,
                                         "#define ISM_PUSH\n", NULL, err, errlen))) {
        vpl_ism_destroy(m);
        return NULL;
    }
    gl->GenVertexArrays(1, &m->vao_points);
    gl->GenVertexArrays(1, &m->vao_empty);
    gl->GenBuffers(1, &m->vbo);
    gl->GenFramebuffers(1, &m->fbo);
    return m;
}

/* The first n points of the scene's sequence in the vertex buffer; -1 when short of memory. */
static int reserve_points(vpl_ism *m, size_t n)
{
    if (n <= m->generated)
        return 0;
    /* not xalloc: the ISM point count (a setting): -1 to the caller */
    float *h = realloc(m->host, n * 3 * sizeof *h);
    if (!h)
        return -1;
    m->host = h;
    if (ism_points(m->scene, m->generated, n - m->generated, h + 3 * m->generated) != 0)
        return -1;
    m->generated = n;
    const gl_functions *gl = m->gl;
    gl->BindVertexArray(m->vao_points);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(n * 3 * sizeof(float)), h, GL_STATIC_DRAW);
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), NULL);
    gl->BindVertexArray(0);
    return 0;
}

static GLuint level_texture(const gl_functions *gl, int side)
{
    return gltools_texture2d(gl, GL_RGBA32F, side, side, GL_NEAREST);
}

/* The atlas for count VPLs: tiles of the asked size while the atlas side stays within
 * ISM_ATLAS_MAX, smaller beyond. Textures are remade when the side changes. */
static int reserve_atlas(vpl_ism *m, int count)
{
    int tiles = 1;
    while (tiles * tiles < count)
        tiles++;
    int tile = m->size;
    while (tile > VPL_ISM_SIZE_MIN && tile * tiles > ISM_ATLAS_MAX)
        tile /= 2;
    int levels = 0;
    while ((1 << levels) < tile)
        levels++;
    m->tile = tile;
    m->tiles = tiles;
    m->levels = levels;
    int side = tile * tiles;
    if (side == m->allocated_side)
        return 0;
    release_atlas(m);
    const gl_functions *gl = m->gl;
    for (int k = 0; k <= (m->splat ? 0 : levels); k++) {
        m->pulled[k] = level_texture(gl, side >> k);
        if (k < levels && !m->splat)
            m->pushed[k] = level_texture(gl, side >> k);
    }
    m->depth = gltools_texture2d(gl, GL_DEPTH_COMPONENT32F, side, side, GL_NEAREST);
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->fbo);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, m->pulled[0], 0);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, m->depth, 0);
    const GLenum color = GL_COLOR_ATTACHMENT0;
    gl->DrawBuffers(1, &color);
    char err[160];
    int bad = gltools_fbo_complete(gl, "ISM", err, sizeof err);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (bad) {
        fprintf(stderr, "cavelight-node: %s: indirect light left out\n", err);
        release_atlas(m);
        return -1;
    }
    m->allocated_side = side;
    m->result = m->splat ? m->pulled[0] : m->pushed[0];
    return 0;
}

static void pass(const vpl_ism *m, GLuint prog, GLuint target, int level, GLuint fine,
                 GLuint coarse)
{
    const gl_functions *gl = m->gl;
    int side = m->allocated_side >> level;
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target, 0);
    gl->Viewport(0, 0, side, side);
    gl->UseProgram(prog);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, fine);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_fine"), 0);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_interval"), 2.0f * m->radius / m->far);
    if (coarse) {
        gl->ActiveTexture(GL_TEXTURE1);
        gl->BindTexture(GL_TEXTURE_2D, coarse);
        gl->Uniform1i(gl->GetUniformLocation(prog, "u_coarse"), 1);
        gl->Uniform1i(gl->GetUniformLocation(prog, "u_texel"), 1 << level);
        gl->Uniform1i(gl->GetUniformLocation(prog, "u_tile"), m->tile >> (level + 1));
    }
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
}

int vpl_ism_render(vpl_ism *m, GLuint vpl_tex, int count)
{
    const gl_functions *gl = m->gl;
    if (count <= 0 || reserve_points(m, (size_t)count * m->points) != 0) {
        if (count > 0)
            fprintf(stderr, "cavelight-node: out of memory for %d x %d ISM points: indirect "
                            "light left out\n", count, m->points);
        return -1;
    }
    if (reserve_atlas(m, count) != 0)
        return -1;
    GLuint prog = m->prog_point;
    const float zero[4] = {0, 0, 0, 0}, one = 1.0f;
    gl->BindFramebuffer(GL_FRAMEBUFFER, m->fbo);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, m->pulled[0], 0);
    gl->Viewport(0, 0, m->allocated_side, m->allocated_side);
    gl->ClearBufferfv(GL_COLOR, 0, zero);
    gl->ClearBufferfv(GL_DEPTH, 0, &one);
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    if (m->splat)
        gl->Enable(GL_PROGRAM_POINT_SIZE);
    gl->UseProgram(prog);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, vpl_tex);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_vpls"), 0);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_points"), m->points);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_size"), m->tile);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_tiles"), m->tiles);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_far"), m->far);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_radius"), m->radius);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_splat"), m->splat);
    gl->BindVertexArray(m->vao_points);
    gl->DrawArrays(GL_POINTS, 0, (GLsizei)(count * m->points));
    gl->Disable(GL_PROGRAM_POINT_SIZE);
    gl->Disable(GL_DEPTH_TEST);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, 0, 0);
    if (!m->splat) {
        gl->BindVertexArray(m->vao_empty);
        for (int k = 0; k < m->levels; k++)
            pass(m, m->prog_pull, m->pulled[k + 1], k + 1, m->pulled[k], 0);
        for (int k = m->levels - 1; k >= 0; k--)
            pass(m, m->prog_push, m->pushed[k], k, m->pulled[k],
                 k + 1 < m->levels ? m->pushed[k + 1] : m->pulled[m->levels]);
    }
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, m->pulled[0], 0);
    gl->FramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, m->depth, 0);
    gl->BindVertexArray(0);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    return 0;
}

void vpl_ism_bind(const vpl_ism *m, GLuint program, int unit)
{
    const gl_functions *gl = m->gl;
    gl->ActiveTexture((GLenum)(GL_TEXTURE0 + unit));
    gl->BindTexture(GL_TEXTURE_2D, m->result);
    gl->Uniform1i(gl->GetUniformLocation(program, "u_ism"), unit);
    gl->Uniform1i(gl->GetUniformLocation(program, "u_ism_size"), m->tile);
    gl->Uniform1i(gl->GetUniformLocation(program, "u_ism_tiles"), m->tiles);
    gl->Uniform1f(gl->GetUniformLocation(program, "u_ism_radius"), m->radius);
}

int vpl_ism_atlas_side(const vpl_ism *m) { return m->allocated_side; }

void vpl_ism_read(const vpl_ism *m, float *out)
{
    const gl_functions *gl = m->gl;
    gl->BindTexture(GL_TEXTURE_2D, m->result);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->GetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, out);
}
