/* gi_method: the helper every method may share (gi_method.h). */
#include "gi_method.h"

void gi_shade_without_lpv(const gl_functions *gl, const gi_eye *eye)
{
    const char *samplers[3] = {"u_lpv_r", "u_lpv_g", "u_lpv_b"};
    for (int c = 0; c < 3; c++)
        gl->Uniform1i(gl->GetUniformLocation(eye->program, samplers[c]), eye->first_unit + c);
    gl->Uniform1i(gl->GetUniformLocation(eye->program, "u_lpv_enabled"), 0);
}
