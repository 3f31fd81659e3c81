/* vpl_view: the view samples of the vpl method's bidirectional selection (vpl_select.h's
 * view rule): the points the viewer sees, cast on the host with Embree (scene_rt.h).
 *
 * The viewer is the tracked head's eye centre in the world (navigation x
 * frame_view_head_centre(), the same point the eyes are placed around): every node of a cluster
 * holds the same frame_params, so every node casts the same rays and picks the same VPLs,
 * which one screen's G-buffer could not give. The rays go out in VPL_VIEW_SAMPLES Halton
 * directions over the whole sphere, since a CAVE's walls surround the viewer; the high-res
 * RSM paper takes 512 or 256 samples of its view buffer, and 256 kept its quality. Does
 * not weigh the samples by what a screen shows, nor cast shadow rays. */
#ifndef CAVELIGHT_VPL_VIEW_H
#define CAVELIGHT_VPL_VIEW_H

#include <stddef.h>

#include "scene/scene.h"

enum { VPL_VIEW_SAMPLES = 256 };

typedef struct vpl_view vpl_view;

/* Builds the scene's BVH (one thread). NULL with one line in err. */
vpl_view *vpl_view_create(const scene *s, char *err, size_t errlen);
void vpl_view_destroy(vpl_view *v);
/* Casts the rays from viewer; *samples gets the hits (6 floats each: point, unit normal
 * turned to the viewer), valid until the next call. Returns how many rays hit. */
int vpl_view_samples(vpl_view *v, const float viewer[3], const float **samples);

#endif
