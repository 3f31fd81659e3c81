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

static char *read_text(const char *name, char *err, size_t errlen)
{
    char dir[1024], path[1100];
    shader_dir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    char why[128];
    char *s = textfile_read(path, NULL, why, sizeof why);
    if (!s)
        snprintf(err, errlen, "shader %s: %s; set CAVELIGHT_SHADERS to the shaders/ folder (looked in "
                 "CAVELIGHT_SHADERS, then %s beside the program, then %s)", path, why,
                 CAVELIGHT_SHADERS_FROM_BIN, CAVELIGHT_SHADER_DIR);
    return s;
}

/* Source = version + defines + common.glsl + file, with "// @BODY@" in the file replaced
 * by body. defines and body may be NULL. */
static GLuint compile(const gl_functions *gl, GLenum type, const char *name, const char *defines,
                      const char *body, char *err, size_t errlen)
{
    char *common = read_text("common.glsl", err, errlen);
    char *text = common ? read_text(name, err, errlen) : NULL;
    if (!text) {
        free(common);
        return 0;
    }
    const char *marker = body ? strstr(text, "// @BODY@") : NULL;
    const char *parts[7];
    GLint lengths[7];
    int count = 0;
    parts[count] = "#version 430 core\n";
    lengths[count++] = -1;
    parts[count] = defines ? defines : "";
    lengths[count++] = -1;
    parts[count] = common;
    lengths[count++] = -1;
    if (marker) {
        parts[count] = text;
        lengths[count++] = (GLint)(marker - text);
        parts[count] = body;
        lengths[count++] = -1;
        parts[count] = marker + 9;
        lengths[count++] = -1;
    } else {
        parts[count] = text;
        lengths[count++] = -1;
    }
    GLuint s = gl->CreateShader(type);
    gl->ShaderSource(s, count, parts, lengths);
    gl->CompileShader(s);
    free(common);
    free(text);
    GLint ok = 0;
    gl->GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        gl->GetShaderInfoLog(s, sizeof log, NULL, log);
        char *nl = strchr(log, '\n');
        if (nl)
            *nl = '\0';
        snprintf(err, errlen, "shader %s does not compile: %s", name, log);
        gl->DeleteShader(s);
        return 0;
    }
    return s;
}

GLuint gltools_program(const gl_functions *gl, const char *vert, const char *frag,
                       const char *comp, const char *defines, const char *comp_body, char *err,
                       size_t errlen)
{
    GLuint shaders[2] = {0, 0};
    int n = 0;
    if (comp) {
        if (!(shaders[n++] = compile(gl, GL_COMPUTE_SHADER, comp, defines, comp_body, err, errlen)))
            return 0;
    } else {
        if (!(shaders[n++] = compile(gl, GL_VERTEX_SHADER, vert, defines, NULL, err, errlen)))
            return 0;
        if (!(shaders[n++] = compile(gl, GL_FRAGMENT_SHADER, frag, defines, NULL, err, errlen))) {
            gl->DeleteShader(shaders[0]);
            return 0;
        }
    }
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
        char *nl = strchr(log, '\n');
        if (nl)
            *nl = '\0';
        snprintf(err, errlen, "shader program %s does not link: %s", comp ? comp : frag, log);
        gl->DeleteProgram(p);
        return 0;
    }
    return p;
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
