/* ao: the ambient term and its ambient occlusion, what every renderer shares without GL.
 *
 * A uniform ambient light of radiance `ambient` (W/(m^2 sr)) from every direction gives a
 * Lambertian surface the irradiance pi x ambient x AO, where AO is the cosine-weighted
 * share of its hemisphere that sees the ambient light:
 *   AO = 1/pi integral over the hemisphere of V(d(w)) cos(theta) dw,
 * d(w) the distance to the first surface along w (none: infinite), V the visibility
 * function below. The node computes AO with layered depth maps (`ao ldm`, node/renderer_ao.h)
 * or in screen space (`ao ssao`, the horizon-based baseline); the path-traced reference
 * with rays (reference_ao.pfm). The frame's settings (frame_params.h: ao, ao-distance,
 * ao-falloff, ao-directions, ao-resolution, ambient) say which and how.
 *
 * Nothing here renders. */
#ifndef CAVELIGHT_AO_H
#define CAVELIGHT_AO_H

typedef enum frame_ao {
    FRAME_AO_OFF = 0,   /* AO is 1 everywhere: the ambient term unattenuated */
    FRAME_AO_LDM,       /* against layered depth maps: the whole scene, on and off screen */
    FRAME_AO_SSAO,      /* screen-space horizons of the G-buffer: the baseline */
    FRAME_AO_COUNT
} frame_ao;

typedef enum frame_ao_falloff {
    FRAME_AO_OCCLUSION = 0, /* V = 0 for a surface nearer than the distance, else 1 */
    FRAME_AO_OBSCURANCE,    /* V = d / distance, 1 beyond it (Zhukov et al.'s obscurance) */
    FRAME_AO_FALLOFFS
} frame_ao_falloff;

/* The visibility of a surface at distance d (< 0: none) for the maximum distance max_d
 * (<= 0: none, every surface occludes) under falloff f. The GLSL twin is ao_visibility()
 * in shaders/ao_common.glsl. */
float ao_visibility(float d, float max_d, frame_ao_falloff f);

struct frame_params;
/* NULL, or one line when the frame asks for AO (ldm, ssao) and has no ambient term for it
 * to occlude: the rasterized picture would not change. The master and the standalone GL
 * node refuse such settings; the path tracer, which writes the AO image itself, does not. */
const char *ao_ambient_check(const struct frame_params *p);

#endif
