#include <stdio.h>

#include "gl_functions.h"

int gl_functions_load(gl_functions *gl, gl_functions_loader load, char *err, size_t errlen)
{
    gl_functions_proc p;
#define GL_FUNCTIONS_LOAD(type, name)                                                    \
    p = load("gl" #name);                                                                \
    if (!p) {                                                                            \
        snprintf(err, errlen, "GL entry point gl%s missing: the driver does not offer "  \
                 "OpenGL 4.3 core", #name);                                              \
        return -1;                                                                       \
    }                                                                                    \
    gl->name = (type)p;
    GL_FUNCTIONS(GL_FUNCTIONS_LOAD)
#undef GL_FUNCTIONS_LOAD
    return 0;
}
