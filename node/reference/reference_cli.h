/* reference_cli: the standalone node's `--renderer reference` run (no GL context).
 *
 * Renders two independent images (seeds S and S + 1, `samples` paths per pixel each) and
 * writes their average to out: reference_{direct,indirect1,indirect,final1,final}.pfm
 * (final1 = direct + indirect1, final = direct + indirect), reference.png (final tone
 * mapped as shaders/final.frag does) and reference.json (settings, timings, and the noise
 * of the average estimated from the two halves: mean |A - B| / 2, absolute and relative
 * to the mean). Errors go to stderr as one line; returns the process exit code. */
#ifndef CAVELIGHT_REFERENCE_CLI_H
#define CAVELIGHT_REFERENCE_CLI_H

#include <stdint.h>

#include "frame/frame_params.h"
#include "frame/frame_view.h"
#include "scene/scene.h"

typedef struct reference_cli_desc {
    const scene *scene;
    const char *scene_name;
    const frame_params *params;
    const frame_view *view;
    int threads;           /* 0 = all cores */
    int samples, bounces;  /* per half image; 0 = the reference's defaults (64, 8) */
    uint64_t seed;
    const char *out;       /* existing folder, or NULL to write nothing */
} reference_cli_desc;

int reference_cli_run(const reference_cli_desc *d);

#endif
