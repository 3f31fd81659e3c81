#include "gi/ldm/ldm_settings.h"

#include <stddef.h>

#include "gi/gi_cost.h"
#include "gi/ldm/ldm_directions.h"
#include "gi/ldm/ldm_map.h"

static const char *const spread_names[] = {"light", "cell"};

#define FIELD(f) offsetof(ldm_settings, f)
/* 32 maps of 128^2 (16 MB at 8 layers) and 32^2 photons per light view: seconds a frame on
 * llvmpipe at 320x240 (docs/node.md); the paper's 512 maps of 200^2 are for a GPU. At
 * 64^2 a texel of the chart's rooms is 10 cm, and a photon that close to a wall's foot
 * may pass it (docs/stability.md). */
static const setting rows[] = {
    {"ldm-directions", "N", SETTING_INT, LDM_DIRECTIONS_MIN, LDM_DIRECTIONS_MAX, 32, NULL, 0,
     SETTING_REBUILD, FIELD(directions),
     "ldm: layered depth maps, one per direction of the\nequal-area set (each traced both ways)"},
    {"ldm-resolution", "N", SETTING_INT, LDM_RESOLUTION_MIN, LDM_RESOLUTION_MAX, 128, NULL, 0,
     SETTING_REBUILD, FIELD(resolution), "ldm: texels per side of each map"},
    {"ldm-photons", "N", SETTING_INT, LDM_PHOTONS_MIN, LDM_PHOTONS_MAX, 32, NULL, 0, 0,
     FIELD(photons), "ldm: primary photons per side of each light view (the\nRSM in N x N "
     "blocks), each split into one per map"},
    {"ldm-distance", "M", SETTING_FLOAT, 0, 1e6, 0, NULL, 0, 0, FIELD(distance),
     "ldm: farthest a split photon travels, metres (0: any)"},
    {"ldm-spread", NULL, SETTING_CHOICE, 0, 0, LDM_SPREAD_LIGHT, spread_names, 2, 0,
     FIELD(spread), "ldm: a split photon's footprint widens as the light's own\ndivergence "
     "(the paper's), or as the cone of its direction's\ncell (smoother, leaks past thin walls)"},
};
#undef FIELD

const char *ldm_ao_check(const frame_params *p)
{
    static _Thread_local char why[256];
    if (p->ao != FRAME_AO_LDM)
        return NULL;
    return ldm_memory_check(p->ao_directions, p->ao_resolution, p->ldm_layers,
                            p->ldm_memory_mb, "ao", why, sizeof why);
}

/* The frame's AO maps (whatever the method), then the method's maps when ldm is the
 * method, must fit ldm-memory (the frame's). */
static const char *check(const frame_params *p)
{
    static _Thread_local char why[256];
    const char *ao = ldm_ao_check(p);
    if (ao || p->gi != GI_METHOD_ID(ldm))
        return ao;
    ldm_settings s;
    ldm_settings_get(p, &s);
    return ldm_memory_check(s.directions, s.resolution, p->ldm_layers, p->ldm_memory_mb, "ldm",
                            why, sizeof why);
}

/* Work: the split photons (photons^2 per light view, one slot per map), each traced and
 * splatted; the maps are built once per scene and settings. Memory: the maps' k-buffers and
 * the slots (4 vec4 each, on the GPU and read back). */
static void cost(const frame_params *p, const float bounds_min[3], const float bounds_max[3], gi_cost *out)
{
    (void)bounds_min, (void)bounds_max;
    ldm_settings s;
    ldm_settings_get(p, &s);
    gi_cost rsm;
    gi_cost_rsm(p, &rsm);
    double views = p->rsm_size > 0 ? rsm.work / ((double)p->rsm_size * p->rsm_size) : 0;
    double slots = (double)s.photons * s.photons * views * s.directions;
    ldm_layout l = {.directions = s.directions, .resolution = s.resolution, .layers = p->ldm_layers};
    out->work = slots;
    out->memory_bytes = ldm_memory_bytes(&l) + slots * 2 * 4 * 4 * sizeof(float);
}

const gi_method_settings ldm_settings_table = {
    .name = "ldm",
    .summary = "layered depth maps: photons split into every map's direction",
    .rows = rows,
    .count = (int)(sizeof rows / sizeof rows[0]),
    .struct_size = sizeof(ldm_settings),
    .check = check,
    .cost = cost,
};

void ldm_settings_get(const frame_params *p, ldm_settings *out)
{
    gi_settings_read(GI_METHOD_ID(ldm), p, out);
}
