/* pose_guard: the master's check of every tracked pose before it reaches the nodes.
 *
 * A tracker can deliver anything: NaN after a lost body, a position kilometres away from
 * a corrupted datagram, a rotation that is no longer one. None of that may end a session.
 * pose_guard_apply() takes one pose (CAVE space) and
 *   keeps it when it is sane: finite, inside the tracked space, a rotation;
 *   repairs it when its rotation drifted a little from orthonormal (more than trackers'
 *   own rounding, POSE_GUARD_ROTATION_EXACT, up to POSE_GUARD_ROTATION_REPAIR): the
 *   nearest rotation by Gram-Schmidt on its columns;
 *   replaces it by the last good pose (before any, the observer's home, unrotated) when it
 *   is not finite, lies outside the tracked space, or is no rotation at all.
 * The tracked space is the box around every screen corner and the observer's home, grown
 * on every side by its own largest side: someone may step out of an open CAVE or stand
 * back from a powerwall, but not by more than the installation is large.
 * Each repaired or replaced pose is one line on stderr, rate-limited per pose (ratelog.h).
 * An eye that is inside the space but on or behind a screen's plane is the node's to
 * handle (frame_view_screen()), per screen. */
#ifndef CAVELIGHT_POSE_GUARD_H
#define CAVELIGHT_POSE_GUARD_H

#include <stdint.h>

#include "base/ratelog.h"
#include "cluster/cluster_config.h"
#include "input/input_state.h"

/* max |R^T R - I|: a tracker's rotation rounded to 6 decimals (DTrack) or a float
 * quaternion is off by about 1e-6; 1e-3 is a thousand times that and below what a
 * projection shows (0.06 degrees). */
#define POSE_GUARD_ROTATION_EXACT 1e-3f
/* Beyond 0.1 (columns 6 degrees off square, or 5 % off unit length) the matrix is no
 * rotation a tracker meant: replaced, not repaired. */
#define POSE_GUARD_ROTATION_REPAIR 0.1f

typedef enum pose_guard_result {
    POSE_GUARD_KEPT = 0,
    POSE_GUARD_REPAIRED,   /* rotation made orthonormal */
    POSE_GUARD_REPLACED,   /* the last good pose (or home) instead */
} pose_guard_result;

typedef struct pose_guard_track {
    const char *name;          /* "head", "wand" */
    input_pose last_good;
    ratelog log;
    uint64_t repaired, replaced;
} pose_guard_track;

typedef struct pose_guard {
    float lo[3], hi[3];        /* the tracked space, CAVE metres */
    pose_guard_track head, wand;
} pose_guard;

void pose_guard_init(pose_guard *g, const cluster_config *cfg);
/* Checks *p (a valid pose) in place; now_ms for the rate limit (clock_now_ms()). */
pose_guard_result pose_guard_apply(pose_guard *g, pose_guard_track *t, input_pose *p, double now_ms);

#endif
