#include "view_samples.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/mat4.h"
#include "frame/frame_view.h"
#include "base/xalloc.h"
#include "reference/scene_rt.h"

struct view_samples {
    scene_rt rt;
    int count;
    float direction[3 * VIEW_SAMPLES_MAX];
    float sample[6 * VIEW_SAMPLES_MAX];
};

static double radical_inverse(unsigned i, unsigned base)
{
    double inv = 1.0 / base, f = inv, r = 0;
    for (; i > 0; i /= base, f *= inv)
        r += f * (i % base);
    return r;
}

view_samples *view_samples_create(const scene *s, int count, char *err, size_t errlen)
{
    view_samples *v = xcalloc(1, sizeof *v);
    v->count = count < 1 ? 1 : (count > VIEW_SAMPLES_MAX ? VIEW_SAMPLES_MAX : count);
    char why[256];
    if (scene_rt_build(&v->rt, s, 1, why, sizeof why) != 0) {
        snprintf(err, errlen, "renderer: view samples: %s", why);
        free(v);
        return NULL;
    }
    /* Halton points (bases 2, 3) mapped to the sphere uniformly in solid angle. */
    for (int i = 0; i < v->count; i++) {
        double z = 1.0 - 2.0 * radical_inverse((unsigned)i + 1, 2);
        double phi = 6.283185307179586 * radical_inverse((unsigned)i + 1, 3);
        double r = sqrt(fmax(0.0, 1.0 - z * z));
        float *d = v->direction + 3 * i;
        d[0] = (float)(r * cos(phi));
        d[1] = (float)(r * sin(phi));
        d[2] = (float)z;
    }
    return v;
}

void view_samples_destroy(view_samples *v)
{
    if (!v)
        return;
    scene_rt_release(&v->rt);
    free(v);
}

const scene_rt *view_samples_rt(const view_samples *v) { return &v->rt; }

int view_samples_cast(view_samples *v, const float viewer[3], int count, const float **samples)
{
    int n = 0;
    for (int i = 0; i < count && i < v->count; i++) {
        const float *d = v->direction + 3 * i;
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        struct RTCRayHit rh = {
            .ray = {.org_x = viewer[0], .org_y = viewer[1], .org_z = viewer[2], .tnear = 0,
                    .dir_x = d[0], .dir_y = d[1], .dir_z = d[2], .tfar = INFINITY,
                    .mask = 0xffffffffu},
            .hit = {.geomID = RTC_INVALID_GEOMETRY_ID, .primID = RTC_INVALID_GEOMETRY_ID},
        };
        scene_rt_intersect(&v->rt, &ctx, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
            continue;
        float ng[3] = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
        float len = sqrtf(ng[0] * ng[0] + ng[1] * ng[1] + ng[2] * ng[2]);
        if (!(len > 0))
            continue;
        float side = ng[0] * d[0] + ng[1] * d[1] + ng[2] * d[2] > 0 ? -1.0f : 1.0f;
        float *s = v->sample + 6 * n++;
        for (int k = 0; k < 3; k++) {
            s[k] = viewer[k] + rh.ray.tfar * d[k];
            s[3 + k] = side * ng[k] / len;
        }
    }
    *samples = v->sample;
    return n;
}

void view_samples_viewer(const frame_params *p, const float head_to_eye[3], float out[3])
{
    float centre[3];
    frame_view_head_centre(p->head, head_to_eye, centre);
    mat4_transform_point(p->navigation, centre, out);
}
