/* script: a scripted head and light path, the input of the demo and the tests.
 *
 * At time t (seconds) the head walks a slow loop around the observer's home position
 * (±0.25 m sideways, ±0.15 m forward, ±0.05 m up) while turning its head ±0.3 rad,
 * and light 0 circles 0.3 m around its start position with its axis swinging ±0.25 rad.
 * Deterministic in t, so a run with a fixed time step gives the same frames every time. */
#ifndef CAVELIGHT_SCRIPT_H
#define CAVELIGHT_SCRIPT_H

#include "cluster/cluster_config.h"
#include "cluster/params.h"

typedef struct script {
    float home[3];
    frame_light light0;  /* light 0 at t = 0 */
    int have_light;
} script;

/* Captures the start state (home from the config, light 0 from the store). */
void script_init(script *s, const cluster_config *cfg, const params_store *start);
/* Sets time, head (already in CAVE space, as the master's tracker input delivers it) and light 0. */
void script_apply(const script *s, double t, params_store *p);
/* The head pose at time t in CAVE space (column-major). */
void script_head(const script *s, double t, float out[16]);

#endif
