#include "gi/vpl/vpl_settings.h"

#include <math.h>
#include <stddef.h>

#include "gi/gi_cost.h"

#include "gi/vpl/vpl_cluster.h"

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
     VPL_SELECT_COUNT, SETTING_REBUILD, FIELD(selection), /* view: the ray caster is built */
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

int vpl_shadow_face(int n)
{
    int f = (int)sqrt((double)VPL_TEXEL_BUDGET / ((double)VPL_FACES * (n > 0 ? n : 1)));
    return f < VPL_FACE ? f : VPL_FACE;
}

/* Work: the visibility maps' texels (and an imperfect map's points), and the gather's
 * VPL-pixel pairs at 1920 x 1080. Memory: the maps (exact: 16-bit depth; imperfect: RGBA
 * float for the pull-push). */
static void cost(const frame_params *p, const float bounds_min[3], const float bounds_max[3], gi_cost *out)
{
    (void)bounds_min, (void)bounds_max;
    vpl_settings s;
    vpl_settings_get(p, &s);
    double n = s.count, texels, bytes_per_texel = 2, points = 0;
    if (s.visibility == VPL_VISIBILITY_EXACT) {
        double face = vpl_shadow_face(s.count);
        texels = VPL_FACES * n * face * face;
    } else {
        texels = n * s.ism_size * s.ism_size;
        bytes_per_texel = 16;
        points = n * s.ism_points;
    }
    double k = s.interleave > 1 ? s.interleave : 1;
    out->work = texels + points + 1920.0 * 1080.0 * n / (k * k);
    out->memory_bytes = texels * bytes_per_texel;
}

const gi_method_settings vpl_settings_table = {
    .name = "vpl",
    .summary = "virtual point lights with a shadow map each",
    .rows = rows,
    .count = (int)(sizeof rows / sizeof rows[0]),
    .struct_size = sizeof(vpl_settings),
    .cost = cost,
};

void vpl_settings_get(const frame_params *p, vpl_settings *out)
{
    gi_settings_read(GI_METHOD_ID(vpl), p, out);
}
