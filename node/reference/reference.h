/* reference: a CPU path tracer (Embree 3) that renders the rasterizer's scene, lights,
 * materials and cameras as ground truth for the LPV (docs/reference.md).
 *
 * It uses the rasterizer's light model exactly: primary rays through pixel centres,
 * two-sided surfaces shaded on the side the ray sees, normalized Blinn-Phong for the spots
 * at the camera vertex (exact shadow rays instead of PCF), Lambertian everywhere else,
 * emitters one-sided when they light other surfaces (as the LPV's emitter VPLs), the same
 * spot cone, 1/max(r^2, 0.01) falloff and absorption transmittance on every segment.
 * Scattering in the medium is not modelled.
 *
 *   direct     emitted radiance of the visible surface + every spot, exact (no noise)
 *   indirect1  spot -> one Lambertian surface -> visible point, plus emitter -> visible
 *              point (the LPV injects emitters as VPLs): what the LPV models
 *   indirect   every path with at least one reflection before the visible point, up to
 *              max_bounces reflections (Russian roulette after the second); a superset of
 *              indirect1. Both indirect images shade the visible point with albedo/pi.
 *   ao         when params->ao is not off: the visible point's ambient occlusion under the
 *              frame's distance limit and falloff (ao_visibility() of frame/ao.h), from
 *              `samples` cosine-weighted rays (its own random numbers: the other images
 *              are the same with or without it); params->ambient times albedo times it
 *              is part of direct, as in the rasterizer
 * All but ao are multiplied by params->exposure, as the rasterizer's are.
 *
 * Deterministic: every pixel draws from its own generator seeded by (seed, pixel), so the
 * images depend on the seed only, never on the thread count or scheduling. */
#ifndef CAVELIGHT_REFERENCE_H
#define CAVELIGHT_REFERENCE_H

#include <stddef.h>
#include <stdint.h>

#include "frame/frame_params.h"
#include "frame/frame_view.h"
#include "scene/scene.h"

enum { REFERENCE_DEFAULT_SAMPLES = 64, REFERENCE_DEFAULT_BOUNCES = 8 };

typedef struct reference reference; /* Embree device + committed scene, built once */

/* The scene must outlive the reference. threads: 0 = all cores. NULL + one line in err. */
reference *reference_create(const scene *s, int threads, char *err, size_t errlen);
void reference_destroy(reference *ref);

typedef struct reference_render_desc {
    const frame_params *params; /* lights, absorption, exposure: as the rasterizer gets them */
    const frame_view *view;  /* view, projection, eye_position, width, height */
    int samples;                /* paths per pixel, 0 = REFERENCE_DEFAULT_SAMPLES */
    int max_bounces;            /* reflections before the visible point, 0 = REFERENCE_DEFAULT_BOUNCES */
    uint64_t seed;
} reference_render_desc;

typedef struct reference_images {
    int width, height;
    float *direct;    /* linear RGB, top row first, same layout as renderer_image.direct */
    float *indirect1; /* one diffuse bounce: what the LPV models */
    float *indirect;  /* many bounces */
    float *ao;        /* ambient occlusion (frame/ao.h: the frame's ao-distance and
                         ao-falloff) as grey RGB, 1 where no geometry; NULL when the frame's
                         ao is off */
    uint8_t *coverage; /* 1 where the pixel's primary ray meets geometry, else 0 (the mask
                          of "masked to geometry"; a black surface is still covered) */
    double render_ms; /* wall time of reference_render() */
    uint64_t rays;    /* rays traced (intersection + shadow) */
} reference_images;

/* Allocates out's images (free with reference_images_free). 0, or -1 with one line in err
 * (empty view, singular view-projection, non-finite light or absorption, out of memory). */
int reference_render(reference *ref, const reference_render_desc *d, reference_images *out,
                     char *err, size_t errlen);
void reference_images_free(reference_images *img);

/* Expected error of an averaged image: mean |a - b| / 2 over all channels of two
 * independent estimates a and b; indirect1_rms: its RMS, sqrt(mean (a - b)^2) / 2 over
 * the covered pixels (the averaged image's standard deviation, what adds to a relRMSE). */
typedef struct reference_noise {
    double direct, indirect1, indirect, ao;
    double indirect1_rms;
} reference_noise;

/* Two independent renders (seeds d->seed and d->seed + 1) averaged into out (times and
 * rays summed), and the noise of that average estimated from their difference. */
int reference_render_averaged(reference *ref, const reference_render_desc *d,
                              reference_images *out, reference_noise *noise, char *err,
                              size_t errlen);

#endif
