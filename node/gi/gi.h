/* gi: the node's indirect-light (GI) methods behind one small interface (gi_method.h),
 * from the registry (gi_methods.def).
 *
 * The renderer builds the method a frame asks for (frame_params.gi, with the method's
 * settings from the frame) and rebuilds it when a frame asks for another one or changes one
 * of its settings marked SETTING_REBUILD (gi_needs_rebuild()): every node does so in the
 * same frame. It calls the method at two places of a frame:
 *   frame pass (renderer_frame_pass(), once per frame, view independent): gi_reuse()
 *     before the reflective shadow maps are rendered (1: last frame's result stands), then
 *     gi_frame() with this frame's RSMs; its checksum is the one READY carries;
 *   eye pass (renderer_eye_pass(), per screen and eye): the method's shading program
 *     (gi_shade_program(): shaders/shade.frag with the method's snippet), then
 *     gi_eye_bind() for its uniforms and textures; before a screen's eye passes,
 *     gi_screen() with all its views (renderer_screen()), when the caller knows them.
 * gi_stats_get() reports its stages for the frame report.
 * Nothing here names a method. */
#ifndef CAVELIGHT_GI_H
#define CAVELIGHT_GI_H

#include <stddef.h>
#include <stdint.h>

#include "gi/gi_method.h"

typedef struct gi gi;

/* The method desc->frame->gi (sanitized) with its settings from desc->frame; NULL with one
 * line in err. */
gi *gi_create(const gi_desc *desc, char *err, size_t errlen);
void gi_destroy(gi *g);
/* The method's index in the registry (gi_settings.h names it). */
int gi_active(const gi *g);
/* 1 when p asks for another method, or changes a setting that rebuilds this one. */
int gi_needs_rebuild(const gi *g, const frame_params *p);
int gi_reuse(gi *g, const frame_params *p);
uint64_t gi_frame(gi *g, const frame_params *p, const gi_rsm *rsm);
void gi_screen(gi *g, const frame_view *views, int n);
/* Objects that moved (gi_method.h's objects()); nothing for a method without it. */
void gi_objects_moved(gi *g, const gi_objects *o);
/* The shading program: fullscreen.vert, and shade.frag with the method's snippet. */
GLuint gi_shade_program(const gi *g);
void gi_eye_bind(gi *g, const gi_eye *eye);
void gi_stats_get(const gi *g, gi_stats *out);
/* The method's own state, for its inspection functions (gi_ilpv.h, gi_vpl.h). */
void *gi_state(const gi *g);

#endif
