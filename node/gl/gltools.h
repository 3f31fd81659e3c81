/* gltools: the small GL toolkit every GL module of the node uses, on a gl_functions table.
 *
 * Programs from the shaders/ folder (CAVELIGHT_SHADERS, else the source tree's, else
 * ../share/cavelight/shaders beside the installed program), a GI method's own files from
 * its folder (node/gi/METHOD/ in the source tree, gi/METHOD/ under the shader folder when
 * installed), named "METHOD/FILE": each stage
 * is "#version 430 core", the caller's defines, common.glsl, then the files, with a
 * "// @BODY@" line in a compute shader replaced by generated code; a compile or link
 * failure is one line naming the file and the driver's first message. Immutable textures
 * (2D, 2D array, 3D RGBA32F with linear filtering) clamped to their edges, and the check
 * that a framebuffer is complete, and the draw state a nested pass borrows. Holds no
 * state. */
#ifndef CAVELIGHT_GLTOOLS_H
#define CAVELIGHT_GLTOOLS_H

#include <stddef.h>

#include "gl_functions.h"

/* A vertex + fragment program, or a compute program when comp is given (comp_body replaces
 * its @BODY@ line). defines and comp_body may be NULL. Returns 0 with one line in err. */
GLuint gltools_program(const gl_functions *gl, const char *vert, const char *frag,
                       const char *comp, const char *defines, const char *comp_body, char *err,
                       size_t errlen);
/* Vertex + fragment program whose fragment stage is the files frags[0..n) in that order
 * (a GI method's snippet before shaders/shade.frag), at most 4. */
GLuint gltools_program_parts(const gl_functions *gl, const char *vert, const char *const *frags,
                             int frag_count, const char *defines, char *err, size_t errlen);
/* A compute program from the files comps[0..count) in that order (shared functions first),
 * at most 4. */
GLuint gltools_compute_parts(const gl_functions *gl, const char *const *comps, int count,
                             const char *defines, char *err, size_t errlen);
GLuint gltools_texture2d(const gl_functions *gl, GLenum format, int w, int h, GLenum filter);
/* size x size x layers, nearest filtering. */
GLuint gltools_texture_array(const gl_functions *gl, GLenum format, int size, int layers);
/* n[0] x n[1] x n[2] RGBA32F, linear filtering: an LPV colour channel's 4 SH coefficients. */
GLuint gltools_texture3d(const gl_functions *gl, const int n[3]);
/* Of the bound GL_FRAMEBUFFER: 0, or -1 with "WHAT framebuffer incomplete ..." in err. */
int gltools_fbo_complete(const gl_functions *gl, const char *what, char *err, size_t errlen);

/* The draw state a pass inside another's (a GI method's inside the eye pass) borrows:
 * saved before, given back after with the caller's program current again. */
typedef struct gltools_draw_state {
    GLint framebuffer, viewport[4], vertex_array;
} gltools_draw_state;
void gltools_draw_state_save(const gl_functions *gl, gltools_draw_state *s);
void gltools_draw_state_restore(const gl_functions *gl, const gltools_draw_state *s,
                                GLuint program);

#endif
