#include "scene_rt.h"

#include <stdio.h>
#include <string.h>

int scene_rt_build(scene_rt *rt, const scene *s, int threads, char *err, size_t errlen)
{
    memset(rt, 0, sizeof *rt);
    char config[64] = "";
    if (threads > 0)
        snprintf(config, sizeof config, "threads=%d", threads);
    rt->device = rtcNewDevice(config);
    if (!rt->device) {
        snprintf(err, errlen, "Embree device creation failed (error %d): check that "
                 "libembree3 is installed", (int)rtcGetDeviceError(NULL));
        return -1;
    }
    rt->scene = rtcNewScene(rt->device);
    rtcSetSceneFlags(rt->scene, RTC_SCENE_FLAG_ROBUST); /* no leaks along shared edges */
    rtcSetSceneBuildQuality(rt->scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = rtcNewGeometry(rt->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    size_t nv = 3 * s->triangle_count;
    float *v = g ? rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                           3 * sizeof(float), nv) : NULL;
    unsigned *ix = g ? rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                               3 * sizeof(unsigned), s->triangle_count) : NULL;
    if (!v || !ix) {
        if (g)
            rtcReleaseGeometry(g);
        snprintf(err, errlen, "Embree could not allocate %zu triangles (error %d)",
                 s->triangle_count, (int)rtcGetDeviceError(rt->device));
        scene_rt_release(rt);
        return -1;
    }
    memcpy(v, s->positions, nv * 3 * sizeof(float));
    for (size_t i = 0; i < nv; i++)
        ix[i] = (unsigned)i;
    rtcCommitGeometry(g);
    rtcAttachGeometry(rt->scene, g); /* geometry id 0; primID = scene triangle index */
    rtcReleaseGeometry(g);
    rtcCommitScene(rt->scene);
    enum RTCError e = rtcGetDeviceError(rt->device);
    if (e != RTC_ERROR_NONE) {
        snprintf(err, errlen, "Embree scene build failed (error %d)", (int)e);
        scene_rt_release(rt);
        return -1;
    }
    return 0;
}

void scene_rt_release(scene_rt *rt)
{
    if (rt->scene)
        rtcReleaseScene(rt->scene);
    if (rt->device)
        rtcReleaseDevice(rt->device);
    memset(rt, 0, sizeof *rt);
}
