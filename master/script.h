/* script: a scripted head and lamp path, the input of the demo and of sessions without
 * --input.
 *
 * At time t (seconds) the head walks a slow loop around the observer's home position
 * (±0.25 m sideways, ±0.15 m forward, ±0.05 m up) while turning ±0.3 rad. Light 0 becomes
 * a lamp (a point light of its own colour and intensity) SCRIPT_LAMP_RISE_M above the
 * home, on a circle of SCRIPT_LAMP_RADIUS_M around the vertical through it: it glides a
 * SCRIPT_LAMP_ARC of the circle in the first half of every SCRIPT_LAMP_PERIOD_S and rests
 * in the second half. A point lamp lights every wall of a CAVE directly in every frame
 * (a spot lit one side, and the incremental LPV restarts while a light moves, so the far
 * side stayed dark); the rests let the LPV converge, so frames are then skipped and the
 * walls gain their full indirect light. Deterministic in t, so a run with a fixed time
 * step gives the same frames every time. The script does not touch the other lights. */
#ifndef CAVELIGHT_SCRIPT_H
#define CAVELIGHT_SCRIPT_H

#include "cluster/cluster_config.h"
#include "frame/frame_params.h"

#define SCRIPT_LAMP_RISE_M 0.6f   /* above the home (head) height */
#define SCRIPT_LAMP_RADIUS_M 0.6f
#define SCRIPT_LAMP_ARC 1.4f      /* radians of the circle per glide */
#define SCRIPT_LAMP_PERIOD_S 4.0  /* a glide and a rest */

typedef struct script {
    float home[3];
} script;

void script_init(script *s, const cluster_config *cfg);
/* Sets f's time, head (in CAVE space, as the master's tracker input delivers it) and, when
 * f has a light, light 0 at time t. */
void script_frame(const script *s, double t, frame_params *f);

#endif
