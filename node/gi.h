/* gi: the node's indirect-light (GI) methods behind one small interface (gi_method.h).
 *
 * The renderer calls the active method at two places of a frame:
 *   frame pass (renderer_frame_pass(), once per frame, view independent): gi_reuse()
 *     before the reflective shadow maps are rendered (1: last frame's result stands), then
 *     gi_frame() with this frame's RSMs; its checksum is the one READY carries;
 *   eye pass (renderer_eye_pass(), per screen and eye): gi_eye_bind() with the shading
 *     program bound, to set the method's uniforms and textures; before a screen's eye
 *     passes, gi_screen() with all its views (renderer_screen()), when the caller knows them.
 * gi_stats_get() reports its stage timings for the frame report.
 *
 * Methods, indexed by frame_gi: ilpv (gi_ilpv.c), none (gi_none.c: direct light only) and
 * vpl (gi_vpl.c: virtual point lights with a shadow map each). To add one: a gi_X.c
 * defining a gi_method, its name in frame_gi (common/frame/frame_params.h) and one line in
 * gi.c's table. */
#ifndef CAVELIGHT_GI_H
#define CAVELIGHT_GI_H

#include <stddef.h>
#include <stdint.h>

#include "gi_method.h"

typedef struct gi gi;

gi *gi_create(frame_gi method, const gi_desc *desc, char *err, size_t errlen);
void gi_destroy(gi *g);
frame_gi gi_active(const gi *g);
int gi_reuse(gi *g, const frame_params *p);
uint64_t gi_frame(gi *g, const frame_params *p, const gi_rsm *rsm);
void gi_screen(gi *g, const frame_view *views, int n);
void gi_eye_bind(gi *g, const gi_eye *eye);
void gi_stats_get(const gi *g, gi_stats *out);
/* The method's own state, for its inspection functions (gi_ilpv.h). */
void *gi_state(const gi *g);

#endif
