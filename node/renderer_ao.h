/* renderer_ao: the ambient term's occlusion, beside any GI method (frame/ao.h says what it
 * is, the frame's `ao` settings which one).
 *
 *   ldm   against layered depth maps of the whole scene (ldm_gl.h: ao-directions maps of
 *         ao-resolution^2 texels, ldm-layers deep), one ray per map from each pixel
 *         (shaders/ao_ldm.frag): sees what is off screen and behind the first surface;
 *         the maps are built when the settings ask for them and again when objects
 *         move, and refused, with one line, when they exceed ldm-memory
 *   ssao  horizons in the G-buffer (shaders/ao_hbao.frag), the screen-space baseline
 *   off   no pass; the shading takes AO as 1
 *
 * Per eye after the G-buffer, into a texture of the eye's size that the shading reads
 * (u_ao: the ambient radiance times albedo times AO is part of the direct light). Owns
 * its maps, programs and texture; renders nothing else. */
#ifndef CAVELIGHT_RENDERER_AO_H
#define CAVELIGHT_RENDERER_AO_H

#include <stddef.h>

#include "frame/frame_params.h"
#include "frame/frame_view.h"
#include "gl/gl_functions.h"
#include "scene/scene.h"
#include "gl/scene_gl.h"

typedef struct renderer_ao renderer_ao;

/* NULL with one line in err (a shader). */
renderer_ao *renderer_ao_create(const gl_functions *gl, const scene *s, char *err,
                                size_t errlen);
void renderer_ao_destroy(renderer_ao *ao);
/* Follows frame p (sanitized): builds the maps `ao ldm` asks for from mesh when their
 * settings changed, or when objects moved (moved 1) since they were built. 0, or -1 with
 * one line in err (over ldm-memory, no GL memory): AO is then off until the settings
 * change. */
int renderer_ao_frame(renderer_ao *ao, const frame_params *p, const scene_gl *mesh, int moved,
                      char *err, size_t errlen);

/* One eye's G-buffer, as renderer_ao_eye() reads it. */
typedef struct renderer_ao_eye_desc {
    const frame_view *view;
    GLuint position, normal;   /* the G-buffer's world positions (w 0: none), normals */
    const float *eye;          /* the eye (w 1) or the direction to it (w 0) */
    float pixel_angle;         /* a pixel's width over its distance (w 0: its width) */
    GLuint vao;                /* an empty vertex array for the full-screen pass */
    int measure;               /* 1: GL finished for eye_ms (benchmarks); a node's eye pass
                                  never waits (its GPU time: the renderer's timer) */
} renderer_ao_eye_desc;

/* The eye's AO into the module's texture (nothing when off). Leaves the program and the
 * framebuffer unbound. */
void renderer_ao_eye(renderer_ao *ao, const renderer_ao_eye_desc *d);
/* prog's u_ao (on texture unit `unit`), u_ao_on and u_ambient; prog bound. */
void renderer_ao_bind(const renderer_ao *ao, GLuint prog, int unit);
/* The last eye's AO as grey linear RGB, top row first (width x height x 3 floats, the
 * module's), or NULL when off. */
const float *renderer_ao_read(renderer_ao *ao);
/* Host ms of the last eye's pass (GL finished when measured) and of the last build of
 * the maps; the maps' MB (0 when none). */
typedef struct renderer_ao_stats {
    double eye_ms, build_ms, memory_mb;
    size_t overflow;           /* depths that did not fit the maps */
} renderer_ao_stats;
void renderer_ao_stats_get(const renderer_ao *ao, renderer_ao_stats *out);

#endif
