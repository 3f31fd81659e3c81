/* reference_internal: state shared by reference.c (Embree scene, threads, images) and
 * reference_sample.c (one pixel's paths). Not for other modules. */
#ifndef CAVELIGHT_REFERENCE_INTERNAL_H
#define CAVELIGHT_REFERENCE_INTERNAL_H

#include <embree3/rtcore.h>

#include "reference.h"
#include "workpool.h"

struct reference {
    const scene *scene;
    RTCDevice device;
    RTCScene rt;
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

typedef struct reference_spot {
    float position[3], direction[3], radiance[3];
    float cos_outer, cos_inner;
} reference_spot;

/* Per-render constants and outputs, read by every row. */
typedef struct reference_job {
    const reference *ref;
    int spot_count;
    reference_spot spots[FRAME_MAX_LIGHTS];
    float absorption, exposure;
    double inv_view_projection[16]; /* column-major, clip -> world */
    float eye[3];
    int width, height, samples, max_bounces;
    uint64_t seed;
    float *direct, *indirect1, *indirect;
    uint64_t *row_rays;             /* per row, summed after the run (no atomics) */
} reference_job;

/* workpool_fn: renders row `row` of job (a reference_job *). */
void reference_sample_row(void *job, int row);

#endif
