/* cache_light: the light of the caches method's caches (cache_place.h) from a set of VALs
 * (val_select.h), as LightSkin's proxy lights (Lensing and Broll 2013; the high-res RSM
 * paper, equations 3, 5, 7, 13, 14), their occlusion by the caches' disks, and the
 * interpolation to a surface point. The host's copy of node/gi/caches/'s shaders (the
 * exact occlusion variant runs here; the tests compare the shaders with it).
 *
 * Proxy of cache c (position p, normal n) from VALs j (position x, normal n_j, flux Phi
 * and area A, both already times the weight 1 / (N P) of their selection):
 *   E_j    = Phi_j cos_c cos_j / (A_j + pi r^2)            irradiance at p (equation 14
 *                                                          times pi / rho: irradiance, not
 *                                                          radiance, is what we shade with)
 *   E      = sum_j E_j                                    times V_j, the VAL's visibility,
 *                                                          in the exact variant
 *   x_p    = p + sum_j w_j (x_j - p) / sum_j w_j,  w_j = E_j's three channels summed
 *   radius = 2 max_axis sigma,  sigma^2 = the w-weighted variance of x_j along each axis
 * The paper weights positions by the form factor alone (equation 6); weighting by the
 * light each VAL brings puts the proxy where the light comes from, not where dark
 * surfaces are. The proxy is a point light at x_p that gives E at p: at a surface point x
 * with normal n_x it gives (equation 7 read back, with the proxy's extent as a bound)
 *   E(x) = E cos_x / max(cos_p, 0.1) (|x_p - p|^2 + radius^2) / (|x_p - x|^2 + radius^2),
 * cos_p and cos_x the cosines at p and x towards x_p: equal to E at x = p, falling off as
 * a point light's would around it. A point x sums E(x) of each cache within reach with
 * cache_weight() (cache_grid.h) and divides by the weights (equation 9, applied to each
 * cache's light rather than to averaged proxy parameters: two caches' proxies on opposite
 * sides do not average to a light between them).
 *
 * Glossy proxy (caches-glossy on; the paper's equations 4, 6, 7 with our lobe): the same
 * sums with each VAL's weight times the cache's specular BRDF f_s(w, w_j) towards the
 * viewer w (the head-derived eye every node shares) from VAL direction w_j, so that
 *   L_g = sum_j f_s(w, w_j) E_j        the cache's glossy radiance (before occlusion)
 *   x_g = p + sum_j w'_j (x_j - p) / sum_j w'_j,  w'_j = f_s(w, w_j) w_j
 * and its irradiance E_g = L_g / f_s(w, w_g), w_g towards x_g: the point light at x_g that
 * gives the cache the glossy radiance it has (equation 7). A proxy far down the lobe (a
 * tiny f_s(w, w_g)) would blow E_g up: the denominator is at least sum_j w'_j / sum_j w_j,
 * the lobe's mean, which bounds E_g by about the VALs' whole irradiance. f_s is
 * shaders/common.glsl's specular_brdf(), the lobe shade.frag lights direct light with, at
 * the cache's roughness. At a point x it is interpolated with equation 8's glossy weight
 *   w_g(x, c) = (1 - d / R) sqrt(max(r_x . r_c, 0))
 * (r the direction to the glossy proxy mirrored at the normal, at x and at c), E_g times
 * cache_proxy_at()'s ratio and x_g averaged (equation 9), and lit by x's own lobe towards
 * the averaged x_g: radiance, not irradiance.
 *
 * Occlusion, the paper's approximation after Bunnell: seen from p, the proxy's sphere and
 * the disk of every other cache k nearer than the sphere (area A_k, normal n_k) are
 * projected onto the unit sphere (solid angles 2 pi (1 - cos asin(radius / d)) and
 * A_k |n_k . w_k| / r_k^2, at most 2 pi) and down onto the unit disk around n (times the
 * cosine to n), each made a square of the same area around its projected centre; the
 * squares' overlaps summed over the proxy's square is the share of its light blocked:
 *   visibility = max(0, 1 - sum_k overlap_k / square_p).
 * No GL, no allocation. */
#ifndef CAVELIGHT_CACHE_LIGHT_H
#define CAVELIGHT_CACHE_LIGHT_H

#include <stddef.h>
#include <stdint.h>

#include "gi/caches/cache_grid.h"
#include "gi/caches/cache_place.h"
#include "gi/vpl_source.h"

/* A cosine at the cache below this counts as this: a proxy near the cache's horizon. */
#define CACHE_PROXY_MIN_COS 0.1f

typedef struct cache_proxy {
    float position[3];
    float radius;
    float irradiance[3];   /* E at the cache, W/m^2, visibility applied */
    float visibility;      /* the share of the proxy's light that reaches the cache */
} cache_proxy;

/* The proxy of c from n VALs; visible (n flags, or NULL: all) leaves some out. */
void cache_proxy_gather(const light_cache *c, const vpl *vals, size_t n,
                        const uint8_t *visible, cache_proxy *out);
/* The glossy proxy of c (above) seen from eye, from n VALs; visible as above. */
void cache_glossy_gather(const light_cache *c, const float eye[3], const vpl *vals, size_t n,
                         const uint8_t *visible, cache_proxy *out);
/* shaders/common.glsl's specular_exponent() of a roughness and specular_brdf() of
 * exponent m at normal n between unit directions wo and wi. */
float cache_specular_exponent(float roughness);
float cache_specular(float m, const float n[3], const float wo[3], const float wi[3]);
/* The approximated visibility of proxy p of cache self among all count caches. */
float cache_occlusion(const light_cache *caches, size_t count, size_t self,
                      const cache_proxy *p);
/* E(x) of one cache's proxy at x (normal n_x) as above, before the interpolation. */
void cache_proxy_at(const light_cache *c, const cache_proxy *p, const float x[3],
                    const float n[3], float out[3]);
/* The interpolated irradiance at x (normal n) from the caches g lists for its cell but the
 * hidden ones (hidden: a flag per cache, or NULL): 0 when no cache reaches it. */
void cache_interpolate(const cache_grid *g, const light_cache *caches, const uint8_t *hidden,
                       const cache_proxy *proxies, const float x[3], const float n[3],
                       float out[3]);
/* The glossy radiance at x (normal n, roughness, unit direction v to the eye) from the
 * glossy proxies as above; 0 when no cache reaches it. */
void cache_interpolate_glossy(const cache_grid *g, const light_cache *caches,
                              const uint8_t *hidden, const cache_proxy *glossy,
                              const float x[3], const float n[3], float roughness,
                              const float v[3], float out[3]);

#endif
