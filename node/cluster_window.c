#include "cluster_window.h"
#include "base/xalloc.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

struct cluster_window {
    glctx *ctx;
    GLFWwindow *win;
    int quad;
    GLuint prog, vao, tex;
    int tex_w, tex_h;
};

/* A full-screen triangle sampling the image, flipped so the first row is at the top. */
static const char *const vs =
    "#version 430 core\n"
    "out vec2 uv;\n"
    "void main() {\n"
    "    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
    "    uv = vec2(p.x, 1.0 - p.y);\n"
    "    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
    "}\n";
static const char *const fs =
    "#version 430 core\n"
    "in vec2 uv;\n"
    "uniform sampler2D image;\n"
    "out vec4 color;\n"
    "void main() { color = vec4(texture(image, uv).rgb, 1.0); }\n";

static GLuint shader(const gl_functions *gl, GLenum type, const char *src, char *err, size_t errlen)
{
    GLuint s = gl->CreateShader(type);
    gl->ShaderSource(s, 1, &src, NULL);
    gl->CompileShader(s);
    GLint ok = 0;
    gl->GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = "";
        gl->GetShaderInfoLog(s, sizeof log, NULL, log);
        snprintf(err, errlen, "cluster window: display shader does not compile: %s", log);
        gl->DeleteShader(s);
        return 0;
    }
    return s;
}

cluster_window *cluster_window_create(const cluster_window_desc *d, char *err, size_t errlen)
{
    cluster_window *w = xcalloc(1, sizeof *w);
    glctx_desc gd = {.backend = GLCTX_GLFW, .width = d->width, .height = d->height, .title = d->title, .visible = 1};
    /* glctx sets its own hints after glfwInit; a stereo hint set before survives them. */
    if (d->want_quad && glfwInit()) {
        glfwWindowHint(GLFW_STEREO, GLFW_TRUE);
        w->ctx = glctx_create(&gd, err, errlen);
        glfwWindowHint(GLFW_STEREO, GLFW_FALSE);
        w->quad = w->ctx != NULL;
    }
    if (!w->ctx)
        w->ctx = glctx_create(&gd, err, errlen);
    if (!w->ctx) {
        free(w);
        return NULL;
    }
    w->win = glfwGetCurrentContext();
    if (d->fullscreen) {
        int count = 0;
        GLFWmonitor **mons = glfwGetMonitors(&count);
        if (d->monitor < count) {
            const GLFWvidmode *mode = glfwGetVideoMode(mons[d->monitor]);
            glfwSetWindowMonitor(w->win, mons[d->monitor], 0, 0, mode->width, mode->height, mode->refreshRate);
        } else {
            fprintf(stderr, "cavelight-node: monitor %d not found (%d connected): staying windowed\n", d->monitor, count);
        }
    }
    const gl_functions *gl = glctx_gl(w->ctx);
    GLuint v = shader(gl, GL_VERTEX_SHADER, vs, err, errlen), f = v ? shader(gl, GL_FRAGMENT_SHADER, fs, err, errlen) : 0;
    if (!f) {
        cluster_window_destroy(w);
        return NULL;
    }
    w->prog = gl->CreateProgram();
    gl->AttachShader(w->prog, v);
    gl->AttachShader(w->prog, f);
    gl->LinkProgram(w->prog);
    gl->DeleteShader(v);
    gl->DeleteShader(f);
    gl->GenVertexArrays(1, &w->vao);
    return w;
}

void cluster_window_destroy(cluster_window *w)
{
    if (!w)
        return;
    if (w->ctx) {
        cluster_window_make_current(w);
        const gl_functions *gl = glctx_gl(w->ctx);
        if (w->tex)
            gl->DeleteTextures(1, &w->tex);
        if (w->vao)
            gl->DeleteVertexArrays(1, &w->vao);
        if (w->prog)
            gl->DeleteProgram(w->prog);
        glctx_destroy(w->ctx);
    }
    free(w);
}

glctx *cluster_window_context(cluster_window *w) { return w->ctx; }
int cluster_window_quad(const cluster_window *w) { return w->quad; }

void cluster_window_make_current(cluster_window *w)
{
    if (glfwGetCurrentContext() != w->win)
        glfwMakeContextCurrent(w->win);
}

static void draw(cluster_window *w, const uint8_t *rgb, int width, int height, int fb_w, int fb_h)
{
    const gl_functions *gl = glctx_gl(w->ctx);
    if (w->tex_w != width || w->tex_h != height) {
        if (w->tex)
            gl->DeleteTextures(1, &w->tex);
        gl->GenTextures(1, &w->tex);
        gl->BindTexture(GL_TEXTURE_2D, w->tex);
        gl->TexStorage2D(GL_TEXTURE_2D, 1, GL_RGB8, width, height);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        w->tex_w = width;
        w->tex_h = height;
    }
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, w->tex);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl->TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb);
    gl->Viewport(0, 0, fb_w, fb_h);
    gl->UseProgram(w->prog);
    gl->Uniform1i(gl->GetUniformLocation(w->prog, "image"), 0);
    gl->BindVertexArray(w->vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
}

int cluster_window_show(cluster_window *w, const uint8_t *left, const uint8_t *right, int width, int height)
{
    cluster_window_make_current(w);
    const gl_functions *gl = glctx_gl(w->ctx);
    int fb_w, fb_h;
    glfwGetFramebufferSize(w->win, &fb_w, &fb_h);
    /* The renderer draws into its own framebuffers; the window's is 0. */
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->Disable(GL_DEPTH_TEST);
    if (w->quad && right) {
        GLenum back_left = GL_BACK_LEFT, back_right = GL_BACK_RIGHT;
        gl->DrawBuffers(1, &back_left);
        draw(w, left, width, height, fb_w, fb_h);
        gl->DrawBuffers(1, &back_right);
        draw(w, right, width, height, fb_w, fb_h);
    } else {
        GLenum back = GL_BACK_LEFT;
        gl->DrawBuffers(1, &back);
        draw(w, left, width, height, fb_w, fb_h);
    }
    if (gl->GetError() != GL_NO_ERROR)
        return -1;
    return glctx_swap(w->ctx) ? 1 : 0;
}
