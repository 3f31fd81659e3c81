#include "gi/caches/caches_settings.h"

#include <stddef.h>

#include "gi/caches/cache_light.h"
#include "gi/caches/cache_place.h"
#include "gi/gi_cost.h"

static const char *const selection_names[] = {"importance", "all"};
static const char *const occlusion_names[] = {"approx", "exact", "off"};
static const char *const glossy_names[] = {"off", "on"};

#define FIELD(f) offsetof(caches_settings, f)
static const setting rows[] = {
    {"caches-vals", "N", SETTING_INT, CACHES_VALS_MIN, CACHES_VALS_MAX, CACHES_VALS_DEFAULT,
     NULL, 0, 0, FIELD(vals), "caches: virtual area lights selected per frame"},
    {"caches-selection", NULL, SETTING_CHOICE, 0, 0, CACHES_SELECT_IMPORTANCE,
     selection_names, 2, 0, FIELD(selection),
     "caches: VALs by importance, or every RSM texel (plain\nLightSkin, the comparison)"},
    {"caches-view-samples", "N", SETTING_INT, CACHES_VIEW_SAMPLES_MIN, CACHES_VIEW_SAMPLES_MAX,
     CACHES_VIEW_SAMPLES_DEFAULT, NULL, 0, 0, FIELD(view_samples),
     "caches: rays from the head that weigh the VALs"},
    {"caches-density", "D", SETTING_FLOAT, 0, 10000, 0, NULL, 0, SETTING_REBUILD,
     FIELD(density), "caches: light caches per m^2 of surface (0: auto, 4096\nover the "
     "scene)"},
    {"caches-angle", "DEG", SETTING_FLOAT, 5, 45, 30, NULL, 0, SETTING_REBUILD, FIELD(angle),
     "caches: normals within this many degrees share a cache"},
    {"caches-occlusion", NULL, SETTING_CHOICE, 0, 0, CACHES_OCCLUSION_APPROX, occlusion_names,
     3, 0, FIELD(occlusion),
     "caches: occlusion of the proxy lights by the caches' disks,\nby a ray to every VAL "
     "(the ceiling), or none"},
    {"caches-seed", "S", SETTING_INT, 0, 2147483647, 0, NULL, 0, 0, FIELD(seed),
     "caches: seed of the selection's jitter"},
    {"caches-glossy", NULL, SETTING_CHOICE, 0, 0, CACHES_GLOSSY_OFF, glossy_names, 2, 0,
     FIELD(glossy), "caches: a glossy proxy light per cache too (the specular\nindirect "
     "term, view dependent)"},
};
#undef FIELD

/* A ray per cache and RSM texel is more than any frame can afford. */
static const char *check(const frame_params *p)
{
    const gi_option *sel = gi_option_find("caches-selection");
    const gi_option *occ = gi_option_find("caches-occlusion");
    if (gi_option_get(sel, p).i == CACHES_SELECT_ALL &&
        gi_option_get(occ, p).i == CACHES_OCCLUSION_EXACT)
        return "caches-occlusion exact casts a ray from every cache to every VAL: it needs "
               "caches-selection importance, not all";
    return NULL;
}

/* The caches: the density over the scene's box surface (its triangles' area is not known
 * here; a limit compares the same scene's settings, so the box's factor cancels), or
 * CACHE_AUTO_COUNT. Work: every cache gathers every VAL (every RSM texel with selection
 * all), plus its occlusion (approx: every other cache's disk; exact: a ray per VAL).
 * Memory: the caches, their proxies, the VALs and a 1080p irradiance texture (with glossy on,
 * a second proxy per cache and a second texture). */
static void cost(const frame_params *p, const float bounds_min[3], const float bounds_max[3], gi_cost *out)
{
    caches_settings s;
    caches_settings_get(p, &s);
    double e[3], caches = CACHE_AUTO_COUNT;
    for (int a = 0; a < 3; a++)
        e[a] = bounds_max[a] - bounds_min[a];
    if (s.density > 0)
        caches = s.density * 2 * (e[0] * e[1] + e[1] * e[2] + e[2] * e[0]) + 1;
    gi_cost rsm;
    gi_cost_rsm(p, &rsm);
    double vals = s.selection == CACHES_SELECT_ALL ? rsm.work : s.vals; /* RSM texels */
    double occlusion = s.occlusion == CACHES_OCCLUSION_APPROX ? caches * caches
                     : s.occlusion == CACHES_OCCLUSION_EXACT  ? caches * vals : 0;
    out->work = caches * vals + occlusion;
    int proxies = s.glossy == CACHES_GLOSSY_ON ? 2 : 1; /* glossy: a second proxy and texture */
    out->memory_bytes = caches * (sizeof(light_cache) + proxies * sizeof(cache_proxy)) +
                        vals * 12 * sizeof(float) + proxies * 1920.0 * 1080.0 * 4 * sizeof(float);
}

const gi_method_settings caches_settings_table = {
    .name = "caches",
    .summary = "light caches lit by importance-sampled virtual area lights",
    .rows = rows,
    .count = (int)(sizeof rows / sizeof rows[0]),
    .struct_size = sizeof(caches_settings),
    .check = check,
    .cost = cost,
};

void caches_settings_get(const frame_params *p, caches_settings *out)
{
    gi_settings_read(GI_METHOD_ID(caches), p, out);
}
