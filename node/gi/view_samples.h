/* view_samples: the points the viewer sees, cast on the host with Embree (scene_rt.h), for
 * the GI methods that weigh their lights by what the viewer sees (the vpl method's
 * bidirectional selection, vpl_select.h; the caches method's VAL importance,
 * val_select.h).
 *
 * The viewer is the tracked head's eye centre in the world (navigation x
 * frame_view_head_centre(), the same point the eyes are placed around): every node of a
 * cluster holds the same frame_params, so every node casts the same rays and its method
 * makes the same choice, which one screen's G-buffer could not give, and walls agree at
 * their seams. The rays go out in Halton directions over the whole sphere, since a CAVE's
 * walls surround the viewer (the high-res RSM paper samples its view buffer at 512 or 256
 * Halton points). Does not weigh the samples by what a screen shows, nor cast shadow
 * rays. */
#ifndef CAVELIGHT_VIEW_SAMPLES_H
#define CAVELIGHT_VIEW_SAMPLES_H

#include <stddef.h>

#include "frame/frame_params.h"
#include "scene/scene.h"

enum { VIEW_SAMPLES_MAX = 1024 };

typedef struct view_samples view_samples;

/* Builds the scene's BVH (one thread) for at most count rays (1..VIEW_SAMPLES_MAX). NULL
 * with one line in err. */
view_samples *view_samples_create(const scene *s, int count, char *err, size_t errlen);
void view_samples_destroy(view_samples *v);
/* Its BVH, for other rays of the same scene (read-only, any thread). */
const struct scene_rt *view_samples_rt(const view_samples *v);
/* The viewer of frame p: navigation x frame_view_head_centre() for the eyes' head_to_eye. */
void view_samples_viewer(const frame_params *p, const float head_to_eye[3], float out[3]);
/* Casts the first count rays (at most the created count) from viewer; *samples gets the
 * hits (6 floats each: point, unit normal turned to the viewer), valid until the next
 * call. Returns how many rays hit. */
int view_samples_cast(view_samples *v, const float viewer[3], int count, const float **samples);

#endif
