/* gi_vpl: the GI method "vpl", instant radiosity with exact visibility, behind gi.h.
 *
 * frame(): every RSM texel with flux and every emissive triangle is a candidate
 * (common/gi/vpl_source.h); vpl-count of them are chosen with vpl-seed by
 * vpl-selection's rule (vpl_settings.h; common/gi/vpl/vpl_select.h:
 * flux, bidirectional view importance from the head's view samples (view_samples.h), or the
 * regular pattern; unbiased weights, the same choice on every node); the checksum READY
 * carries is vpl_checksum() of that set.
 * Each chosen VPL gets a real shadow map: a cube of six distance maps (faces wholly
 * behind its surface skipped), all VPLs' faces tiles of one depth array texture, rendered
 * once per frame and shared by every screen and eye; or, with vpl-visibility
 * ism or ism-splat, an imperfect shadow map from a subset of a point set (vpl_ism.h).
 * eye_bind(): the VPLs, the maps and the light lists for its shading snippet
 * (vpl_gather.glsl, vpl_shade.glsl), which gathers per pixel the VPLs its cluster lists
 * (common/gi/vpl/vpl_cluster.h; vpl-lights:
 * clustered by default, tiled, or every VPL), testing visibility in whichever maps were
 * rendered. The lists are assigned per eye in eye_bind(), or once for all eyes of a screen
 * in screen() (enclosed clustering: one grid enclosing both frusta). A VPL reaches
 * receivers within its influence radius (vpl-cut), whichever assignment.
 *
 * reuse(): a frame whose lights, medium and VPL settings are those of the last frame (a
 * moving head's, except under the view rule) keeps its VPLs and shadow maps, unless
 * the renderer computes every frame (renderer_desc.no_reuse: the benchmarks measure them).
 *
 * A VPL stands for a patch of surface of area A (its texel's or triangle's, times its
 * weight 1 / (N p)); the gather treats it as a disk of that area seen on its axis, so the
 * irradiance it gives is flux cos cos / (A + pi r^2) instead of flux cos cos / (pi r^2):
 * bounded near the VPL (eq. 14 of the high-res RSM paper), biased only within about
 * sqrt(A / pi) of it, and the bias shrinks as N grows (docs/node.md has its measure).
 *
 * With vpl-interleave, eye_bind() runs the interleaved gather and its blur
 * first (vpl_interleave.h) and shade.frag reads their result.
 * stats(): stages "select" (reading the RSMs and choosing the VPLs) and "shadow" (their
 * maps, GL work finished before the clock stops); figures "assign_ms" and "assignments",
 * the last light assignment. */
#ifndef CAVELIGHT_GI_VPL_H
#define CAVELIGHT_GI_VPL_H

#include "gi/gi_method.h"
#include "gi/vpl/vpl_settings.h"

extern const gi_method gi_vpl_method;

#endif
