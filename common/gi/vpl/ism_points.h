/* ism_points: the point set of the vpl method's imperfect shadow maps (node/vpl_ism.h): points
 * spread over a scene's triangles uniformly by area, the same on every node.
 *
 * Point k lies on triangle j with probability area_j / total area and uniformly within it,
 * from three fixed random numbers of (ISM_POINTS_SEED, k) (vpl_slot_random()), so the
 * first n points are the same whatever n: VPL i's subset, points [i m, (i + 1) m), stays
 * the same when more VPLs are asked for. Each point of an m-point subset stands for
 * total area / m of surface, a disk of radius ism_point_radius().
 * Plain maths on host arrays; no GL. */
#ifndef CAVELIGHT_ISM_POINTS_H
#define CAVELIGHT_ISM_POINTS_H

#include <stddef.h>

#include "scene/scene.h"

enum { ISM_POINTS_SEED = 0x15a1 };

/* Total area of s's triangles, m^2. */
double ism_scene_area(const scene *s);
/* Points first .. first + n - 1 of s's sequence into position (3 floats each). Returns -1
 * when memory is short or s has no area, else 0. */
int ism_points(const scene *s, size_t first, size_t n, float *position);
/* Radius of the disk each point of an m-point subset stands for: area / m = pi r^2. */
float ism_point_radius(double area, int m);

#endif
