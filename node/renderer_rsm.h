/* renderer_rsm: the reflective shadow maps (RSMs) of a frame's lights, one layer per light
 * view (light_view.h says which views a light type gets), the lights' uniforms for the
 * shading pass. The GI methods get the maps as a gi_rsm (gi/gi_rsm.h), which also reads
 * them back.
 *
 * All views share four 2D array textures (position, normal with the texel's plane, flux,
 * depth), grown when a frame needs more layers than any before. Owns the RSM program;
 * draws the scene through scene_gl. Does not decide what a GI method does with the maps. */
#ifndef CAVELIGHT_RENDERER_RSM_H
#define CAVELIGHT_RENDERER_RSM_H

#include <stddef.h>

#include "frame/frame_params.h"
#include "frame/light_view.h"
#include "gl/gl_functions.h"
#include "scene/scene.h"
#include "gl/scene_gl.h"

typedef struct renderer_rsm renderer_rsm;

/* size: texels per side. As many layers as the scene's own lights need. NULL with one
 * line in err. */
renderer_rsm *renderer_rsm_create(const gl_functions *gl, const scene *s, int size, char *err,
                                  size_t errlen);
void renderer_rsm_destroy(renderer_rsm *m);
/* The RSM of every view of every lit light of p (light_views()). */
void renderer_rsm_render(renderer_rsm *m, const scene_gl *mesh, const frame_params *p);
/* The last render's views: how many, the views, and per layer the framebuffer with
 * position, normal, flux in colour attachments 0..2. */
int renderer_rsm_views(const renderer_rsm *m, const light_view **views, const GLuint **fbo);
int renderer_rsm_size(const renderer_rsm *m);
/* The maps as three 2D array textures (RGBA32F, one layer per view of the last render):
 * position (w 1 where geometry), normal with the texel's plane (n, -n . position), flux. */
void renderer_rsm_textures(const renderer_rsm *m, GLuint out[3]);
/* The lights, their views and shadow maps as shade.frag's uniforms (texture units given);
 * p: the parameters of the last render. */
void renderer_rsm_bind_shading(const renderer_rsm *m, GLuint prog, const frame_params *p,
                               GLenum depth_unit, GLenum normal_unit);
#endif
