/* scene_rt: the scene in an Embree BVH (scene_rt.h). libembree3 is loaded on the first
 * build (dynlib.h), so programs that never cast a host ray do not map it. */
#include "scene_rt.h"

#include <stdio.h>
#include <string.h>

#include "base/dynlib.h"

static RTCDevice (*new_device)(const char *config);
static enum RTCError (*device_error)(RTCDevice device);
static void (*release_device)(RTCDevice device);
static RTCScene (*new_scene)(RTCDevice device);
static void (*set_scene_flags)(RTCScene scene, enum RTCSceneFlags flags);
static void (*set_build_quality)(RTCScene scene, enum RTCBuildQuality quality);
static void (*commit_scene)(RTCScene scene);
static void (*release_scene)(RTCScene scene);
static RTCGeometry (*new_geometry)(RTCDevice device, enum RTCGeometryType type);
static void *(*new_geometry_buffer)(RTCGeometry geometry, enum RTCBufferType type, unsigned slot,
                                    enum RTCFormat format, size_t stride, size_t count);
static void (*commit_geometry)(RTCGeometry geometry);
static unsigned (*attach_geometry)(RTCScene scene, RTCGeometry geometry);
static void (*release_geometry)(RTCGeometry geometry);
static void (*intersect1)(RTCScene scene, struct RTCIntersectContext *context, struct RTCRayHit *rayhit);
static void (*occluded1)(RTCScene scene, struct RTCIntersectContext *context, struct RTCRay *ray);

static const dynlib_symbol embree_symbols[] = {
    {"rtcNewDevice", &new_device}, {"rtcGetDeviceError", &device_error},
    {"rtcReleaseDevice", &release_device}, {"rtcNewScene", &new_scene},
    {"rtcSetSceneFlags", &set_scene_flags}, {"rtcSetSceneBuildQuality", &set_build_quality},
    {"rtcCommitScene", &commit_scene}, {"rtcReleaseScene", &release_scene},
    {"rtcNewGeometry", &new_geometry}, {"rtcSetNewGeometryBuffer", &new_geometry_buffer},
    {"rtcCommitGeometry", &commit_geometry}, {"rtcAttachGeometry", &attach_geometry},
    {"rtcReleaseGeometry", &release_geometry}, {"rtcIntersect1", &intersect1},
    {"rtcOccluded1", &occluded1},
};
static const char *const embree_files[] = {"libembree3.so.3", "libembree3.so", NULL};
static const dynlib embree_lib = {.what = "Embree", .files = embree_files, .package = "libembree3-3",
                                  .symbols = embree_symbols,
                                  .symbol_count = sizeof embree_symbols / sizeof *embree_symbols};

int scene_rt_build(scene_rt *rt, const scene *s, int threads, char *err, size_t errlen)
{
    memset(rt, 0, sizeof *rt);
    if (dynlib_load(&embree_lib, err, errlen) != 0)
        return -1;
    char config[64] = "";
    if (threads > 0)
        snprintf(config, sizeof config, "threads=%d", threads);
    rt->device = new_device(config);
    if (!rt->device) {
        snprintf(err, errlen, "Embree device creation failed (error %d): check that "
                 "libembree3 is installed", (int)device_error(NULL));
        return -1;
    }
    rt->scene = new_scene(rt->device);
    set_scene_flags(rt->scene, RTC_SCENE_FLAG_ROBUST); /* no leaks along shared edges */
    set_build_quality(rt->scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry g = new_geometry(rt->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    size_t nv = 3 * s->triangle_count;
    float *v = g ? new_geometry_buffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       3 * sizeof(float), nv) : NULL;
    unsigned *ix = g ? new_geometry_buffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), s->triangle_count) : NULL;
    if (!v || !ix) {
        if (g)
            release_geometry(g);
        snprintf(err, errlen, "Embree could not allocate %zu triangles (error %d)",
                 s->triangle_count, (int)device_error(rt->device));
        scene_rt_release(rt);
        return -1;
    }
    memcpy(v, s->positions, nv * 3 * sizeof(float));
    for (size_t i = 0; i < nv; i++)
        ix[i] = (unsigned)i;
    commit_geometry(g);
    attach_geometry(rt->scene, g); /* geometry id 0; primID = scene triangle index */
    release_geometry(g);
    commit_scene(rt->scene);
    enum RTCError e = device_error(rt->device);
    if (e != RTC_ERROR_NONE) {
        snprintf(err, errlen, "Embree scene build failed (error %d)", (int)e);
        scene_rt_release(rt);
        return -1;
    }
    return 0;
}

void scene_rt_intersect(const scene_rt *rt, struct RTCIntersectContext *context, struct RTCRayHit *rayhit)
{
    intersect1(rt->scene, context, rayhit);
}

void scene_rt_occluded(const scene_rt *rt, struct RTCIntersectContext *context, struct RTCRay *ray)
{
    occluded1(rt->scene, context, ray);
}

void scene_rt_release(scene_rt *rt)
{
    if (rt->scene)
        release_scene(rt->scene);
    if (rt->device)
        release_device(rt->device);
    memset(rt, 0, sizeof *rt);
}
