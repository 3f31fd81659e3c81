/* gi_cost: what a frame's GI settings cost a node, without GL, and the limits a cluster
 * node holds every frame to.
 *
 * A node takes its settings from whoever acts as its master: in insecure mode that may be
 * a stranger, and a legitimate master may be given a runaway value. Each setting's own
 * range is checked where it is parsed (gi_set(), gi_frame_sanitize()); combinations are
 * bounded here. A method's settings table may give a cost model (gi_method_settings.cost):
 * its work per frame, in units of its own (compared only with itself), and the memory its
 * state takes. The RSMs cost rsm^2 texels per light view. The limits:
 *   - work: at most GI_COST_WORK_LIMIT times the work of the same method and RSMs with the
 *     settings the wall was set up for (the cluster config's "settings" on the defaults),
 *     or with the defaults, whichever is more: heavier settings belong in the config,
 *     where every node reads them;
 *   - memory: the method's state, the RSMs and the AO maps together at most memory_mb
 *     (the config's limits.gi_memory_mb, CLUSTER_GI_MEMORY_MB by default).
 * The ambient occlusion's maps (ao ldm) count like a method of their own: their work
 * against the set-up's or the defaults' AO maps, their memory in the total (ldm-memory is
 * a frame setting too, so it cannot be what bounds them).
 * A frame over a limit keeps the node's last frame settings within them (the renderer,
 * renderer_desc.limits), with one line; the master refuses such settings before any node
 * starts. Models are estimates within a small factor: a limit stops a frame that would
 * take minutes or gigabytes, it does not meter milliseconds. The standalone node has no
 * limits (its settings are its user's own). */
#ifndef CAVELIGHT_GI_COST_H
#define CAVELIGHT_GI_COST_H

#include <stddef.h>

#include "frame/frame_params.h"

enum { GI_COST_WORK_LIMIT = 10 };

typedef struct gi_cost {
    double work;          /* per frame, in the method's own units */
    double memory_bytes;  /* its state */
} gi_cost;

typedef struct gi_limits {
    frame_params base;                  /* the settings the wall was set up for */
    float bounds_min[3], bounds_max[3]; /* the scene's */
    double memory_mb;                   /* > 0 */
} gi_limits;

/* The frame's method and its RSMs. */
void gi_cost_method(const frame_params *p, const float bounds_min[3], const float bounds_max[3], gi_cost *out);
void gi_cost_rsm(const frame_params *p, gi_cost *out);
/* The ambient occlusion's layered depth maps (ao ldm): texels drawn, bytes held; ssao and
 * off cost nothing here. Counted in both limits like a method. */
void gi_cost_ao(const frame_params *p, gi_cost *out);
/* 1 when p is within the limits; else 0 and one line in why. */
int gi_cost_within(const gi_limits *l, const frame_params *p, char *why, size_t cap);
/* Copies the settings the costs depend on (the method, its settings, steps, RSM size, the
 * AO and its maps). */
void gi_cost_keep_settings(const frame_params *from, frame_params *to);

#endif
