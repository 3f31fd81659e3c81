/* gltools: see gltools.h. */
#include "gltools.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/textfile.h"

/* Where the shaders are, in this order: CAVELIGHT_SHADERS; the installed folder beside the
 * program (PREFIX/bin/cavelight-node -> PREFIX/CAVELIGHT_SHADERS_FROM_BIN, the layout of
 * `cmake --install`, scripts/install_nodes.py and scripts/bundle.sh) when it holds them; the
 * source tree the program was built from (a build folder's programs). An installed program
 * thus never reads a source tree that may have moved on. */
static void shader_dir(char *dir, size_t cap)
{
    const char *env = getenv("CAVELIGHT_SHADERS");
    if (env && *env) {
        snprintf(dir, cap, "%s", env);
        return;
    }
    char exe[900], probe[1100]; /* exe, the suffix and the file name fit */
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    char *slash = n > 0 ? (exe[n] = 0, strrchr(exe, '/')) : NULL;
    if (slash) {
        *slash = 0;
        snprintf(dir, cap, "%s/%s", exe, CAVELIGHT_SHADERS_FROM_BIN);
        snprintf(probe, sizeof probe, "%s/common.glsl", dir);
        if (access(probe, R_OK) == 0)
            return;
    }
    snprintf(dir, cap, "%s", CAVELIGHT_SHADER_DIR);
}

/* name under the shader folder, or under its gi/ folder (a GI method's own shaders: the
 * source tree's node/gi/METHOD/, installed as shaders/gi/METHOD/). */
static char *read_text(const char *name, char *err, size_t errlen)
{
    char dir[1024], path[1100], gi_path[1100];
    shader_dir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    snprintf(gi_path, sizeof gi_path, "%s/gi/%s", dir, name);
    if (access(path, R_OK) != 0 && access(gi_path, R_OK) == 0)
        snprintf(path, sizeof path, "%s", gi_path);
    else if (access(path, R_OK) != 0)
        snprintf(path, sizeof path, "%s/%s", CAVELIGHT_GI_SHADER_DIR, name);
    char why[128];
    char *s = textfile_read(path, NULL, why, sizeof why);
    if (!s)
        snprintf(err, errlen, "shader %s: %s; set CAVELIGHT_SHADERS to the shaders/ folder (looked in "
                 "CAVELIGHT_SHADERS, then %s beside the program, then %s)", path, why,
                 CAVELIGHT_SHADERS_FROM_BIN, CAVELIGHT_SHADER_DIR);
    return s;
}

enum { MAX_FILES = 4 };

/* A driver's log cut to its first line: error messages are one line. */
static const char *first_line(char *log)
{
    char *nl = strchr(log, '\n');
    if (nl)
        *nl = '\0';
    return log;
}

/* Source = version + defines + common.glsl + the files in order, with "// @BODY@" in a
 * file replaced by body. defines and body may be NULL. */
static GLuint compile(const gl_functions *gl, GLenum type, const char *const *names, int files,
                      const char *defines, const char *body, char *err, size_t errlen)
{
    char *text[MAX_FILES + 1] = {0};
    const char *parts[2 + 3 * (MAX_FILES + 1)];
    GLint lengths[2 + 3 * (MAX_FILES + 1)];
    int count = 0, ok = files <= MAX_FILES;
    parts[count] = "#version 430 core\n";
    lengths[count++] = -1;
    parts[count] = defines ? defines : "";
    lengths[count++] = -1;
    for (int f = 0; f <= files && ok; f++) {
        ok = (text[f] = read_text(f == 0 ? "common.glsl" : names[f - 1], err, errlen)) != NULL;
        const char *marker = ok && body ? strstr(text[f], "// @BODY@") : NULL;
        parts[count] = text[f];
        lengths[count++] = marker ? (GLint)(marker - text[f]) : -1;
        if (marker) {
            parts[count] = body;
            lengths[count++] = -1;
            parts[count] = marker + 9;
            lengths[count++] = -1;
        }
    }
    GLuint s = 0;
    if (ok) {
        s = gl->CreateShader(type);
        gl->ShaderSource(s, count, parts, lengths);
        gl->CompileShader(s);
        GLint compiled = 0;
        gl->GetShaderiv(s, GL_COMPILE_STATUS, &compiled);
        if (!compiled) {
            char log[512] = "";
            gl->GetShaderInfoLog(s, sizeof log, NULL, log);
            snprintf(err, errlen, "shader %s does not compile: %s", names[files - 1],
                     first_line(log));
            gl->DeleteShader(s);
            s = 0;
        }
    }
    for (int f = 0; f <= files; f++)
        free(text[f]);
    return s;
}

static GLuint link_program(const gl_functions *gl, const GLuint *shaders, int n,
                           const char *name, char *err, size_t errlen)
{
    GLuint p = gl->CreateProgram();
    for (int i = 0; i < n; i++)
        gl->AttachShader(p, shaders[i]);
    gl->LinkProgram(p);
    for (int i = 0; i < n; i++)
        gl->DeleteShader(shaders[i]);
    GLint ok = 0;
    gl->GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        gl->GetProgramInfoLog(p, sizeof log, NULL, log);
        snprintf(err, errlen, "shader program %s does not link: %s", name, first_line(log));
        gl->DeleteProgram(p);
        return 0;
    }
    return p;
}

GLuint gltools_program_parts(const gl_functions *gl, const char *vert, const char *const *frags,
                             int frag_count, const char *defines, char *err, size_t errlen)
{
    GLuint shaders[2];
    if (!(shaders[0] = compile(gl, GL_VERTEX_SHADER, &vert, 1, defines, NULL, err, errlen)))
        return 0;
    if (!(shaders[1] = compile(gl, GL_FRAGMENT_SHADER, frags, frag_count, defines, NULL, err,
                               errlen))) {
        gl->DeleteShader(shaders[0]);
        return 0;
    }
    return link_program(gl, shaders, 2, frags[frag_count - 1], err, errlen);
}

GLuint gltools_program(const gl_functions *gl, const char *vert, const char *frag,
                       const char *comp, const char *defines, const char *comp_body, char *err,
                       size_t errlen)
{
    if (!comp)
        return gltools_program_parts(gl, vert, &frag, 1, defines, err, errlen);
    GLuint shader = compile(gl, GL_COMPUTE_SHADER, &comp, 1, defines, comp_body, err, errlen);
    return shader ? link_program(gl, &shader, 1, comp, err, errlen) : 0;
}

GLuint gltools_compute_parts(const gl_functions *gl, const char *const *comps, int count,
                             const char *defines, char *err, size_t errlen)
{
    GLuint shader = compile(gl, GL_COMPUTE_SHADER, comps, count, defines, NULL, err, errlen);
    return shader ? link_program(gl, &shader, 1, comps[count - 1], err, errlen) : 0;
}

GLuint gltools_texture2d(const gl_functions *gl, GLenum format, int w, int h, GLenum filter)
{
    GLuint t;
    gl->GenTextures(1, &t);
    gl->BindTexture(GL_TEXTURE_2D, t);
    gl->TexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, (GLint)filter);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, (GLint)filter);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

GLuint gltools_texture_array(const gl_functions *gl, GLenum format, int size, int layers)
{
    GLuint t;
    gl->GenTextures(1, &t);
    gl->BindTexture(GL_TEXTURE_2D_ARRAY, t);
    gl->TexStorage3D(GL_TEXTURE_2D_ARRAY, 1, format, size, size, layers);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

GLuint gltools_texture3d(const gl_functions *gl, const int n[3])
{
    GLuint t;
    gl->GenTextures(1, &t);
    gl->BindTexture(GL_TEXTURE_3D, t);
    gl->TexStorage3D(GL_TEXTURE_3D, 1, GL_RGBA32F, n[0], n[1], n[2]);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    return t;
}

int gltools_fbo_complete(const gl_functions *gl, const char *what, char *err, size_t errlen)
{
    GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(err, errlen, "%s framebuffer incomplete (status 0x%x): the driver lacks "
                 "float render targets", what, (unsigned)st);
        return -1;
    }
    return 0;
}

void gltools_draw_state_save(const gl_functions *gl, gltools_draw_state *s)
{
    gl->GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->framebuffer);
    gl->GetIntegerv(GL_VIEWPORT, s->viewport);
    gl->GetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vertex_array);
}

void gltools_draw_state_restore(const gl_functions *gl, const gltools_draw_state *s,
                                GLuint program)
{
    gl->BindVertexArray((GLuint)s->vertex_array);
    gl->BindFramebuffer(GL_FRAMEBUFFER, (GLuint)s->framebuffer);
    gl->Viewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    gl->UseProgram(program);
}
