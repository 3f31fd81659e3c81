#include "gi/vpl/vpl_settings.h"

#include <stddef.h>

#include "vpl/vpl_cluster.h"

static const char *const bound_names[] = {"disk", "point"};
static const char *const visibility_names[] = {"exact", "ism", "ism-splat"};
static const char *const lights_names[] = {"clustered", "tiled", "all"};

#define FIELD(f) offsetof(vpl_settings, f)
static const setting rows[] = {
    {"vpl-count", "N", SETTING_INT, VPL_COUNT_MIN, VPL_COUNT_MAX, VPL_COUNT_DEFAULT, NULL, 0, 0,
     FIELD(count), "vpl: lights chosen per frame"},
    {"vpl-seed", "S", SETTING_INT, 0, 2147483647, 0, NULL, 0, 0, FIELD(seed),
     "vpl: seed of their random choice"},
    {"vpl-selection", NULL, SETTING_CHOICE, 0, 0, VPL_SELECT_FLUX, vpl_selection_names,
     VPL_SELECT_COUNT, 0, FIELD(selection),
     "vpl: choose lights by flux, by flux and what the head\nsees (bidirectional), or on a "
     "regular pattern"},
    {"vpl-bound", NULL, SETTING_CHOICE, 0, 0, VPL_BOUND_DISK, bound_names, 2, 0, FIELD(bound),
     "vpl: each light a disk of its area near it, or a point\n(unbounded: to measure the "
     "disk's bias)"},
    {"vpl-visibility", NULL, SETTING_CHOICE, 0, 0, VPL_VISIBILITY_EXACT, visibility_names, 3,
     SETTING_REBUILD, FIELD(visibility),
     "vpl: a cube shadow map per light from the triangles, or\nimperfect maps from points "
     "(pull-push or splats)"},
    {"vpl-interleave", "K", SETTING_INT, 0, VPL_INTERLEAVE_MAX, 0, NULL, 0, SETTING_REBUILD,
     FIELD(interleave),
     "vpl: interleaved sampling in K x K blocks: each pixel\ngathers 1/K^2 of the lights, "
     "then a blur that keeps\nedges (0: off)"},
    {"ism-size", "N", SETTING_INT, VPL_ISM_SIZE_MIN, VPL_ISM_SIZE_MAX, 32, NULL, 0, SETTING_POW2 | SETTING_REBUILD,
     FIELD(ism_size), "vpl: texels per side of each imperfect map"},
    {"ism-points", "N", SETTING_INT, VPL_ISM_POINTS_MIN, VPL_ISM_POINTS_MAX, 1024, NULL, 0, SETTING_REBUILD,
     FIELD(ism_points), "vpl: points per imperfect map"},
    {"vpl-lights", NULL, SETTING_CHOICE, 0, 0, VPL_LIGHTS_CLUSTERED, lights_names, 3, 0,
     FIELD(lights), "vpl: light assignment of the gather (lists per\ncluster, per tile, or "
     "every light everywhere)"},
    {"vpl-cut", "C", SETTING_FLOAT, -1, 1000, VPL_CUT_DEFAULT, NULL, 0, 0, FIELD(cut),
     "vpl: influence cut, a share of the flux spread evenly\nover the scene (<= 0: none)"},
};
#undef FIELD

const gi_method_settings vpl_settings_table = {
    .name = "vpl",
    .summary = "virtual point lights with a shadow map each",
    .rows = rows,
    .count = (int)(sizeof rows / sizeof rows[0]),
    .struct_size = sizeof(vpl_settings),
};

void vpl_settings_get(const frame_params *p, vpl_settings *out)
{
    gi_settings_read(gi_method_find("vpl"), p, out);
}
