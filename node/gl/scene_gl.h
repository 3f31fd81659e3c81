/* scene_gl: a loaded scene on the current GL context, for the passes that draw it (the
 * G-buffer, the reflective shadow maps, the vpl method's shadow maps): one vertex buffer
 * with the triangles as loaded, grouped by object (static first) and material, the
 * material textures, and one draw per group with its uniforms set (u_model and
 * u_normal_model from the object's pose, u_base_color, u_has_texture, u_base_texture on
 * unit 0, u_emissive and u_roughness where the program has them); a hidden object's
 * groups are not drawn. Owns no program and loads nothing; the scene must outlive it. */
#ifndef CAVELIGHT_SCENE_GL_H
#define CAVELIGHT_SCENE_GL_H

#include <stddef.h>
#include <stdint.h>

#include "gl_functions.h"
#include "scene/scene.h"

typedef struct scene_gl scene_gl;

/* Returns NULL with one line in err (a scene too large for memory). */
scene_gl *scene_gl_create(const gl_functions *gl, const scene *s, char *err, size_t errlen);
void scene_gl_destroy(scene_gl *m);
/* Where the objects are (scene_pose_models()): object_count matrices and flags. Until
 * set: as loaded, all shown. */
void scene_gl_set_pose(scene_gl *m, const float (*model)[16], const uint8_t *shown);
/* Every triangle, with prog bound (its vertex inputs: position, normal, uv at 0, 1, 2). */
void scene_gl_draw(const scene_gl *m, GLuint prog);
/* The same triangles without their materials (a shadow map's depth): one draw per object. */
void scene_gl_draw_geometry(const scene_gl *m, GLuint prog);

#endif
