/* gpu_timer: GPU time per named stage of a frame, from GL timestamp queries read back
 * late (a later frame collects whatever has arrived, never waiting), so timing adds no
 * stall. Stages may nest (timestamps, not GL_TIME_ELAPSED) and repeat within a frame (the
 * eye passes of a stereo screen): a repeated name's times add up.
 *
 *   gpu_timer_frame(t, n)      at the start of frame n: collects every earlier frame whose
 *                              queries all arrived, then records into a fresh slot
 *   h = gpu_timer_begin(t, "inject") ... gpu_timer_end(t, h)
 *   gpu_timer_last(t)          the newest frame whose results are all in
 *
 * Names must outlive the timer (string literals). A NULL timer is accepted everywhere and
 * records nothing, so code that may run without one needs no test. */
#ifndef CAVELIGHT_GPU_TIMER_H
#define CAVELIGHT_GPU_TIMER_H

#include <stdint.h>

#include "gl_functions.h"

enum { GPU_TIMER_STAGES = 24 };

typedef struct gpu_timer_stage {
    const char *name;
    double ms;                /* summed over the stage's times in the frame */
    int times;                /* how often it ran in the frame (eye passes: the views) */
} gpu_timer_stage;

typedef struct gpu_timer_result {
    uint64_t frame;           /* the frame number given to gpu_timer_frame() */
    int count;                /* stages, in the order they first began (0: none yet) */
    gpu_timer_stage stage[GPU_TIMER_STAGES];
} gpu_timer_result;

typedef struct gpu_timer gpu_timer;

gpu_timer *gpu_timer_create(const gl_functions *gl);
void gpu_timer_destroy(gpu_timer *t);
void gpu_timer_frame(gpu_timer *t, uint64_t frame);
/* A handle for gpu_timer_end(), or -1 (no frame begun, or its stages are all used). */
int gpu_timer_begin(gpu_timer *t, const char *name);
void gpu_timer_end(gpu_timer *t, int handle);
const gpu_timer_result *gpu_timer_last(const gpu_timer *t);
/* Stage name's ms in r divided by its times (per eye pass, say); 0 when absent. */
double gpu_timer_mean_ms(const gpu_timer_result *r, const char *name);
/* Frames whose readings were lost: the ring came round before they arrived, or llvmpipe
 * gave an implausible timestamp. */
long gpu_timer_dropped(const gpu_timer *t);

#endif
