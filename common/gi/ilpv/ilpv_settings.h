/* ilpv_settings: the ILPV method's settings (gi_settings.h), without GL: what every program
 * needs to name, check and send them. The frame's steps, lambda_incr and medium are the
 * frame's own (frame_transport_settings[]). */
#ifndef CAVELIGHT_ILPV_SETTINGS_H
#define CAVELIGHT_ILPV_SETTINGS_H

#include <stddef.h>

#include "gi/gi_settings.h"
#include "gi/ilpv/lattice.h"
#include "gi/ilpv/lpv_propagate.h"

/* Where the propagation runs. */
typedef enum ilpv_backend_choice {
    ILPV_BACKEND_AUTO = 0, /* CPU on llvmpipe/softpipe, GL compute on a real GPU */
    ILPV_BACKEND_CPU,
    ILPV_BACKEND_GL,
} ilpv_backend_choice;

/* The GL propagation's variant (propagate.comp). */
typedef enum ilpv_tiles {
    ILPV_TILES_AUTO = 0, /* shared-memory tiles on a GPU, plain image loads on llvmpipe */
    ILPV_TILES_ON,
    ILPV_TILES_OFF,
} ilpv_tiles;

typedef enum ilpv_mode {
    ILPV_MODE_INCREMENTAL = 0, /* the history merge: light accumulates over frames (ilpv.h) */
    ILPV_MODE_CLASSIC,         /* classic LPV: the sum of this frame's steps alone */
} ilpv_mode;

/* The largest lattice a node builds: 128^3 cells of its volumes are about 0.5 GB. A
 * lattice fitted to a cell budget may stretch further along a long scene's axis. */
enum {
    ILPV_LATTICE_MAX = 128,
    ILPV_LATTICE_CELLS_MAX = ILPV_LATTICE_MAX * ILPV_LATTICE_MAX * ILPV_LATTICE_MAX,
    ILPV_FITTED_AXIS_MAX = 1024,
};

typedef struct ilpv_settings {
    int lattice;          /* cells along the scene's longest axis */
    int lattice_cells;    /* > 0: instead, as many cells in all, spent on the scene's shape */
    ilpv_backend_choice backend;
    ilpv_tiles gl_tiles;
    lpv_transport transport; /* beams: the ILPV driver (ilpv.h); paper: the thesis's
                                 (lpv_paper_frame.h) */
    ilpv_mode mode;
    float converge_threshold; /* skip a frame below this residual with unchanged inputs;
                                 negative: never */
} ilpv_settings;

extern const gi_method_settings ilpv_settings_table;

/* The frame's ILPV settings. */
void ilpv_settings_get(const frame_params *p, ilpv_settings *out);
/* The lattice these settings give a scene with these bounds. Returns 0, or -1 with one line
 * in err. */
int ilpv_settings_lattice(const ilpv_settings *s, const float bounds_min[3], const float bounds_max[3],
                          lattice_desc *out, char *err, size_t errlen);

#endif
