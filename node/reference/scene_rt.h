/* scene_rt: the scene's triangles in an Embree 3 BVH, for rays cast on the host: the
 * reference's paths (reference.h) and the vpl method's view samples (gi_vpl.h).
 *
 * Positions only: a hit's primID is the scene's triangle index, and materials, normals
 * and textures stay with the caller. Built once and read-only afterwards, so any thread
 * may cast rays into it. The Embree library is loaded on the first build (not linked):
 * cast rays through scene_rt_intersect() and scene_rt_occluded(), never rtc* directly
 * (Embree's inline helpers such as rtcInitIntersectContext() are fine). */
#ifndef CAVELIGHT_SCENE_RT_H
#define CAVELIGHT_SCENE_RT_H

#include <embree3/rtcore.h>
#include <stddef.h>

#include "scene/scene.h"

typedef struct scene_rt {
    RTCDevice device;
    RTCScene scene; /* geometry 0: every triangle of the scene, in order */
} scene_rt;

/* threads: Embree's build threads, 0 = all cores. 0, or -1 with one line in err (rt then
 * holds nothing to release). */
int scene_rt_build(scene_rt *rt, const scene *s, int threads, char *err, size_t errlen);
/* rtcIntersect1() and rtcOccluded1() on a built rt. */
void scene_rt_intersect(const scene_rt *rt, struct RTCIntersectContext *context, struct RTCRayHit *rayhit);
void scene_rt_occluded(const scene_rt *rt, struct RTCIntersectContext *context, struct RTCRay *ray);
void scene_rt_release(scene_rt *rt);

#endif
