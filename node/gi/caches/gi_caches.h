/* gi_caches: the GI method "caches", behind gi.h: light caches over the scene's surfaces,
 * lit by virtual area lights (VALs) importance-sampled from high-resolution RSMs (Bischoff,
 * Schwandt and Broll 2017, on LightSkin: Lensing and Broll 2013).
 *
 * create(): the caches of the scene (common/gi/caches/cache_place.h) from the disk cache or
 * placed and stored there (cache_file.h; a note on stderr when a file was not trusted or
 * could not be written), which of them are hidden under another surface (caches_exact.h),
 * the lookup grid of the interpolation (cache_grid.h), the scene's
 * emissive triangles as fixed VALs, the view samples' rays (view_samples.h), the GPU
 * buffers and programs.
 * frame(), each stage timed with GL finished:
 *   importance  view samples from the tracked head, the same on every node
 *               (frame_view_head_centre()); every RSM texel's two importance channels
 *               (caches_importance.comp);
 *   sat_select  the summed-area tables and the binary search of caches-vals slots, each
 *               a VAL with its 1/P weight (caches_sat_*.comp, caches_select.comp); the
 *               picks are read back for the checksum; with caches-selection all there is
 *               no selection, every texel lights every cache (plain LightSkin);
 *   proxy       each cache's proxy light (caches_proxy.comp);
 *   occlusion   the disks' approximation (caches_occlude.comp); or, exact, a ray from every
 *               cache to every VAL on the host (caches_exact.h), the proxies gathered there
 *               and uploaded;
 * common/gi/caches/val_select.h and cache_light.h are the host's copy of each shader's maths.
 * The checksum READY carries: FNV-1a over the picks and the proxies as read back.
 * eye_bind(): the interpolation (caches_interpolate.frag) over the eye's G-buffer into an
 * irradiance texture the snippet (caches_shade.glsl) reads; timed as stage
 * "interpolate" (of the last eye pass; with GL finished when the renderer measures every
 * frame, gi_desc.no_reuse, else the host's time to submit it).
 * reuse(): lights, medium, settings and (with importance) the viewer unchanged, unless the
 * renderer computes every frame.
 * stats(): the stages above; figures: caches, hidden_caches, vals (lighting the caches this frame),
 * cache_kb (host and GPU memory of caches, grid and proxies), placement_ms and
 * cache_file (1: read from disk) of create(), reach_m (the interpolation's radius),
 * longest_list. */
#ifndef CAVELIGHT_GI_CACHES_H
#define CAVELIGHT_GI_CACHES_H

#include "gi/caches/cache_file.h"
#include "gi/caches/cache_grid.h"
#include "gi/caches/cache_light.h"
#include "gi/caches/val_select.h"
#include "gi/caches/caches_settings.h"
#include "gi/gi.h"

extern const gi_method gi_caches_method;

typedef struct gi_caches gi_caches;

/* The method's state when g runs caches, else NULL. */
gi_caches *gi_caches_of(gi *g);
/* What the tests and benchmarks inspect after a frame: the caches and grid, how they were
 * got, the last selection's picks (n), its VALs (the emitters first, then one per pick) and
 * the proxies; picks, VALs and proxies are read back from the GPU on each call (a frame
 * keeps them there). */
const cache_set *gi_caches_set(const gi_caches *c);
const cache_grid *gi_caches_grid(const gi_caches *c);
const cache_store_report *gi_caches_store(const gi_caches *c);
int gi_caches_picks(gi_caches *c, const val_pick **picks);
size_t gi_caches_vals(gi_caches *c, const vpl **vals);
const cache_proxy *gi_caches_proxies(gi_caches *c);
/* The glossy proxies (caches-glossy on; stale when off) and the viewer they were made for
 * (view_samples_viewer() of the last frame). */
const cache_proxy *gi_caches_glossy(gi_caches *c);
const float *gi_caches_viewer(const gi_caches *c);
/* Per cache 1 when it lies under another surface (caches_exact.h): not interpolated. */
const uint8_t *gi_caches_hidden(const gi_caches *c);

#endif
