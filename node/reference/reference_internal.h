/* reference_internal: state shared by reference.c (Embree scene, threads, images),
 * reference_ray.c (ray primitives), reference_sample.c (one pixel's paths) and
 * reference_light.c (light arriving at a path vertex). Not for other modules. */
#ifndef CAVELIGHT_REFERENCE_INTERNAL_H
#define CAVELIGHT_REFERENCE_INTERNAL_H

#include <embree3/rtcore.h>
#include <math.h>

#include "reference.h"
#include "scene_rt.h"
#include "base/vec3.h"
#include "base/workpool.h"

struct reference {
    const scene *scene;
    scene_rt rt;              /* Embree device and BVH of the scene's triangles */
    workpool *pool;
    float *face_normal;       /* unit geometric normal per triangle */
    float **texture_linear;   /* per scene texture: width*height*3 linear RGB (sRGB decoded) */
    /* Emissive triangles, picked for next-event estimation in proportion to their power. */
    size_t emitter_count;
    uint32_t *emitter_triangle;
    float *emitter_front;     /* 3 per emitter: the side the emitter lights (vertex normals') */
    double *emitter_cdf;      /* running sums of power, last = emitter_power */
    double emitter_power;
    int32_t *emitter_of;      /* per triangle: its emitter index, or -1 */
    float *emitter_area_pdf;  /* per emitter: probability of picking it / its area */
};

/* A light as the paths see it (light_view.h has the rules shared with the rasterizer). */
typedef struct reference_light {
    scene_light_type type;
    float position[3], direction[3], radiance[3];
    float axis[3];            /* direction normalized */
    float cos_outer, cos_inner; /* spot */
    float sample_cos;         /* the light strategy samples directions with cos to the axis
                                 above this: a spot's outer cone, a point light's sphere (-1) */
    float travel0;            /* directional: light_directional_travel() at the origin */
    float window[3][3];       /* directional: where its light enters the scene, corner and edges */
    float window_area;
} reference_light;

/* Per-render constants and outputs, read by every row. */
typedef struct reference_job {
    const reference *ref;
    int light_count;
    reference_light lights[FRAME_MAX_LIGHTS];
    float absorption, exposure;
    float min_light_distance2;      /* falloff bound, squared: scene_min_light_distance() */
    double inv_view_projection[16]; /* column-major, clip -> world */
    int width, height, samples, max_bounces;
    uint64_t seed;
    float *direct, *indirect1, *indirect;
    float *ao;                      /* NULL: no AO asked for (params->ao off) */
    float ao_distance, ambient;     /* the frame's (frame/ao.h) */
    frame_ao_falloff ao_falloff;
    uint8_t *coverage;
    uint64_t *row_rays;             /* per row, summed after the run (no atomics) */
} reference_job;

/* Small helpers shared by the reference's modules. */
static const float PI_F = 3.14159265358979f;

/* PCG32 (O'Neill), seeded per pixel through splitmix64. */
typedef struct rng {
    uint64_t state;
} rng;

static inline float rng_next(rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ull + 1442695040888963407ull;
    uint32_t xs = (uint32_t)(((old >> 18) ^ old) >> 27);
    uint32_t rot = (uint32_t)(old >> 59);
    uint32_t v = (xs >> rot) | (xs << ((32 - rot) & 31));
    return (float)(v >> 8) * (1.0f / 16777216.0f); /* [0, 1) */
}

typedef struct hit {
    float p[3], n[3], ng[3]; /* point, shading and geometric normals on the seen side */
    float albedo[3];
    uint32_t tri;
} hit;

static inline float transmittance(float sigma, float r)
{
    return sigma > 0 ? powf(1.0f - fminf(sigma, 0.999999f), r) : 1.0f;
}

/* reference_ray.c: the ray primitives */
/* Fills h from Embree's hit; normals turned to face `toward` (a direction, not a point). */
void reference_ray_hit(const reference *ref, const struct RTCHit *eh, const float toward[3],
                       hit *h);
/* Ray origin off the surface along the geometric normal, scaled with the coordinates. */
void reference_ray_offset(const hit *h, float o[3]);
/* Closest hit along o + t d, t < tfar; 1 when something was hit. Counts the ray. */
int reference_ray_trace(const reference_job *job, const float o[3], const float d[3],
                        float tfar, struct RTCRayHit *rh, uint64_t *rays);
/* 1 when nothing lies between o and o + d * dist (d unit). Counts the ray. */
int reference_ray_visible(const reference_job *job, const float o[3], const float d[3],
                          float dist, uint64_t *rays);

/* reference_sample.c */
/* workpool_fn: renders row `row` of job (a reference_job *). */
void reference_sample_row(void *job, int row);
/* reference_light.c: light arriving at a vertex (docs/reference.md, "Sampling"). */
/* Light i at h: irradiance on the shading normal and the unit direction to the light; 0
 * when it does not reach h. As shade.frag, with an exact shadow ray (shadow = 1) instead
 * of PCF; shadow = 0 when h is known to see the light. */
int reference_light_one(const reference_job *job, int i, const hit *h, int shadow, float e[3],
                        float l[3], uint64_t *rays);
/* All lights at h; cosine_pdf > 0 weights against the light strategy (see the .c). */
void reference_light_all(const reference_job *job, const hit *h, float cosine_pdf, float e[3],
                         uint64_t *rays);
/* One-sample irradiance at h from the emitters' front sides; mis: a cosine ray leaves h. */
void reference_light_emitters(const reference_job *job, const hit *h, int mis, rng *g,
                              float e[3], uint64_t *rays);
/* MIS weight of a cosine ray from `from` (direction d, length t) that hit triangle tri. */
float reference_light_emitter_hit_weight(const reference *ref, const hit *from, const float d[3],
                                         float t, uint32_t tri);
/* Light strategy for light i -> y -> x0; adds x0's albedo / pi times the radiance to out. */
void reference_light_connect(const reference_job *job, int i, const hit *x0, rng *g,
                             float out[3], uint64_t *rays);

#endif
