/* gl_functions: the GL 4.3 core entry points the node uses (and glBufferStorage, 4.4), as
 * one table.
 *
 * Every GL call goes through a gl_functions table filled from the active context
 * backend's GetProcAddress: libOpenGL and libOSMesa in one program would otherwise route
 * direct glXxx() calls to whichever library the linker saw first.
 * Call as gl->Clear(...). GL_FUNCTIONS is an X-macro list: X(type, name). */
#ifndef CAVELIGHT_GL_FUNCTIONS_H
#define CAVELIGHT_GL_FUNCTIONS_H

#include <GL/glcorearb.h>

/* glcorearb.h declares no pointer types for these GL 1.1 entry points. */
typedef void (APIENTRYP cavelight_PFNGLGENTEXTURESPROC)(GLsizei n, GLuint *textures);
typedef void (APIENTRYP cavelight_PFNGLDELETETEXTURESPROC)(GLsizei n, const GLuint *textures);
typedef void (APIENTRYP cavelight_PFNGLBINDTEXTUREPROC)(GLenum target, GLuint texture);
typedef void (APIENTRYP cavelight_PFNGLTEXSUBIMAGE2DPROC)(GLenum target, GLint level, GLint x,
    GLint y, GLsizei w, GLsizei h, GLenum format, GLenum type, const void *pixels);
typedef void (APIENTRYP cavelight_PFNGLDRAWARRAYSPROC)(GLenum mode, GLint first, GLsizei count);
typedef void (APIENTRYP cavelight_PFNGLDRAWELEMENTSPROC)(GLenum mode, GLsizei count, GLenum type,
    const void *indices);

#define GL_FUNCTIONS(X) \
    X(PFNGLGETSTRINGPROC, GetString) \
    X(PFNGLGETINTEGERVPROC, GetIntegerv) \
    X(PFNGLGETERRORPROC, GetError) \
    X(PFNGLENABLEPROC, Enable) \
    X(PFNGLDISABLEPROC, Disable) \
    X(PFNGLVIEWPORTPROC, Viewport) \
    X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv) \
    X(PFNGLDEPTHFUNCPROC, DepthFunc) \
    X(PFNGLPIXELSTOREIPROC, PixelStorei) \
    X(PFNGLREADPIXELSPROC, ReadPixels) \
    X(PFNGLREADBUFFERPROC, ReadBuffer) \
    X(PFNGLDRAWBUFFERSPROC, DrawBuffers) \
    X(PFNGLCOLORMASKPROC, ColorMask) \
    X(PFNGLFINISHPROC, Finish) \
    X(PFNGLMEMORYBARRIERPROC, MemoryBarrier) \
    X(cavelight_PFNGLGENTEXTURESPROC, GenTextures) \
    X(cavelight_PFNGLDELETETEXTURESPROC, DeleteTextures) \
    X(cavelight_PFNGLBINDTEXTUREPROC, BindTexture) \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture) \
    X(PFNGLTEXSTORAGE2DPROC, TexStorage2D) \
    X(PFNGLTEXSTORAGE3DPROC, TexStorage3D) \
    X(cavelight_PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D) \
    X(PFNGLTEXSUBIMAGE3DPROC, TexSubImage3D) \
    X(PFNGLGETTEXIMAGEPROC, GetTexImage) \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri) \
    X(PFNGLTEXPARAMETERFVPROC, TexParameterfv) \
    X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap) \
    X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture) \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers) \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers) \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer) \
    X(PFNGLFRAMEBUFFERTEXTUREPROC, FramebufferTexture) \
    X(PFNGLFRAMEBUFFERTEXTURELAYERPROC, FramebufferTextureLayer) \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus) \
    X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer) \
    X(PFNGLGENBUFFERSPROC, GenBuffers) \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers) \
    X(PFNGLBINDBUFFERPROC, BindBuffer) \
    X(PFNGLBUFFERDATAPROC, BufferData) \
    X(PFNGLBUFFERSUBDATAPROC, BufferSubData) \
    X(PFNGLGETBUFFERSUBDATAPROC, GetBufferSubData) \
    X(PFNGLCLEARBUFFERDATAPROC, ClearBufferData) \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase) \
    X(PFNGLFRAMEBUFFERPARAMETERIPROC, FramebufferParameteri) \
    X(PFNGLBLENDFUNCPROC, BlendFunc) \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays) \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays) \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray) \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray) \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer) \
    X(cavelight_PFNGLDRAWARRAYSPROC, DrawArrays) \
    X(cavelight_PFNGLDRAWELEMENTSPROC, DrawElements) \
    X(PFNGLCREATESHADERPROC, CreateShader) \
    X(PFNGLSHADERSOURCEPROC, ShaderSource) \
    X(PFNGLCOMPILESHADERPROC, CompileShader) \
    X(PFNGLGETSHADERIVPROC, GetShaderiv) \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog) \
    X(PFNGLDELETESHADERPROC, DeleteShader) \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram) \
    X(PFNGLATTACHSHADERPROC, AttachShader) \
    X(PFNGLLINKPROGRAMPROC, LinkProgram) \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv) \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog) \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram) \
    X(PFNGLUSEPROGRAMPROC, UseProgram) \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation) \
    X(PFNGLUNIFORM1IPROC, Uniform1i) \
    X(PFNGLUNIFORM1FPROC, Uniform1f) \
    X(PFNGLUNIFORM2FPROC, Uniform2f) \
    X(PFNGLUNIFORM2FVPROC, Uniform2fv) \
    X(PFNGLUNIFORM3FPROC, Uniform3f) \
    X(PFNGLUNIFORM3IPROC, Uniform3i) \
    X(PFNGLUNIFORM3FVPROC, Uniform3fv) \
    X(PFNGLUNIFORM4FVPROC, Uniform4fv) \
    X(PFNGLUNIFORM1FVPROC, Uniform1fv) \
    X(PFNGLUNIFORM1IVPROC, Uniform1iv) \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv) \
    X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv) \
    X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute) \
    X(PFNGLGENQUERIESPROC, GenQueries) \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries) \
    X(PFNGLBEGINQUERYPROC, BeginQuery) \
    X(PFNGLENDQUERYPROC, EndQuery) \
    X(PFNGLGETQUERYOBJECTIVPROC, GetQueryObjectiv) \
    X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v) \
    X(PFNGLQUERYCOUNTERPROC, QueryCounter) \
    X(PFNGLDEBUGMESSAGEINSERTPROC, DebugMessageInsert) \
    X(PFNGLPUSHDEBUGGROUPPROC, PushDebugGroup) \
    X(PFNGLPOPDEBUGGROUPPROC, PopDebugGroup) \
    X(PFNGLBUFFERSTORAGEPROC, BufferStorage) \
    X(PFNGLMAPBUFFERRANGEPROC, MapBufferRange) \
    X(PFNGLUNMAPBUFFERPROC, UnmapBuffer) \
    X(PFNGLFENCESYNCPROC, FenceSync) \
    X(PFNGLCLIENTWAITSYNCPROC, ClientWaitSync) \
    X(PFNGLDELETESYNCPROC, DeleteSync)

typedef struct gl_functions {
#define GL_FUNCTIONS_MEMBER(type, name) type name;
    GL_FUNCTIONS(GL_FUNCTIONS_MEMBER)
#undef GL_FUNCTIONS_MEMBER
} gl_functions;

typedef void (*gl_functions_proc)(void);
typedef gl_functions_proc (*gl_functions_loader)(const char *name);

/* Fills every entry through load("glXxx"). Returns 0, or -1 naming the first missing
 * entry point in err. */
int gl_functions_load(gl_functions *gl, gl_functions_loader load, char *err, size_t errlen);

#endif
