/* renderer_aa: anti-aliasing of an eye's final image (the frame's `aa` setting, frame_aa in
 * frame_params.h), after tone mapping and the HUD, before the image is read back for the
 * warp and blend.
 *
 *   fxaa  Lottes' FXAA 3.11 quality algorithm (shaders/aa_fxaa.frag): one full-screen pass
 *         over the 8-bit image; pixels without a luma edge come out unchanged
 *   off   no pass
 *
 * Owns its program and its target (an RGBA8 texture of the eye's size); renders nothing
 * else. */
#ifndef CAVELIGHT_RENDERER_AA_H
#define CAVELIGHT_RENDERER_AA_H

#include <stddef.h>

#include "frame/frame_params.h"
#include "gl/gl_functions.h"

typedef struct renderer_aa renderer_aa;

/* NULL with one line in err (the shader). */
renderer_aa *renderer_aa_create(const gl_functions *gl, char *err, size_t errlen);
void renderer_aa_destroy(renderer_aa *aa);
/* Anti-aliases the w x h RGBA8 texture ldr (whose filtering it sets to linear) as mode asks,
 * drawing with the empty vertex array vao. Returns the framebuffer that holds the result
 * in its colour attachment 0, bound; 0 when mode is off (or the target could not be made:
 * the image stays as it was). */
GLuint renderer_aa_apply(renderer_aa *aa, frame_aa mode, GLuint ldr, int w, int h, GLuint vao);

#endif
