#include "gi/ilpv/ilpv_settings.h"

#include "gi/ilpv/ilpv_budget.h"

#include <stdio.h>

#include "gi/gi_cost.h"
#include "gi/ilpv/ilpv.h"

#include "gi/ilpv/lpv_converge.h"
#include "gi/ilpv/lpv_paper_frame.h"

static const char *const backend_names[] = {"auto", "cpu", "gl"};
static const char *const tiles_names[] = {"auto", "on", "off"};
static const char *const mode_names[] = {"incremental", "classic"};

#define FIELD(f) offsetof(ilpv_settings, f)
static const setting rows[] = {
    {"lattice", "N", SETTING_INT, 2, ILPV_LATTICE_MAX, LATTICE_DEFAULT_AXIS_CELLS, NULL, 0,
     SETTING_REBUILD, FIELD(lattice), "ilpv: LPV cells along the scene's longest axis"},
    {"lattice-cells", "N", SETTING_INT, 0, ILPV_LATTICE_CELLS_MAX, 0, NULL, 0, SETTING_REBUILD,
     FIELD(lattice_cells),
     "ilpv: instead of --lattice: N cells in all, fitted to the\n"
     "scene's shape (finer cells in a long, thin scene); 0: off"},
    {"lpv", NULL, SETTING_CHOICE, 0, 0, ILPV_BACKEND_AUTO, backend_names, 3, SETTING_REBUILD,
     FIELD(backend), "ilpv: where the LPV runs (auto: CPU on llvmpipe, GL on a\nGPU; "
     "every node must resolve it alike)"},
    {"gl-tiles", NULL, SETTING_CHOICE, 0, 0, ILPV_TILES_AUTO, tiles_names, 3, SETTING_REBUILD,
     FIELD(gl_tiles), "ilpv: GL propagation through shared-memory tiles"},
    {"lpv-transport", NULL, SETTING_CHOICE, 0, 0, LPV_TRANSPORT_BEAMS, lpv_transport_names,
     LPV_TRANSPORT_COUNT, SETTING_REBUILD, FIELD(transport),
     "ilpv: the propagation: beams (two beams per cell) or paper\n(the thesis's transfer "
     "vectors, merge and receiver)"},
    {"lpv-mode", NULL, SETTING_CHOICE, 0, 0, ILPV_MODE_INCREMENTAL, mode_names, 2,
     SETTING_REBUILD, FIELD(mode), "ilpv: ILPV, or classic LPV accumulation"},
    {"converge-threshold", "R", SETTING_FLOAT, -1, 1, LPV_CONVERGE_DEFAULT_THRESHOLD, NULL, 0,
     SETTING_REBUILD, FIELD(converge_threshold),
     "ilpv: skip the frame pass once the LPV residual is below R\nand nothing changed "
     "(negative = never)"},
};
#undef FIELD

/* --lattice and --lattice-cells say the same thing two ways. */
static const char *check(const frame_params *p)
{
    const gi_option *a = gi_option_find("lattice"), *b = gi_option_find("lattice-cells");
    if (gi_option_is_set(a, p) && gi_option_is_set(b, p) && gi_option_get(b, p).i > 0)
        return "give --lattice (cells along the longest axis) or --lattice-cells (cells in "
               "all), not both";
    return NULL;
}

/* Work: every step touches every cell, and the frame's injection, merge and composition
 * about one step's worth; memory: the transport's own volumes. */
static void cost(const frame_params *p, const float bounds_min[3], const float bounds_max[3], gi_cost *out)
{
    ilpv_settings s;
    ilpv_settings_get(p, &s);
    lattice_desc lat;
    char err[256];
    if (ilpv_settings_lattice(&s, bounds_min, bounds_max, &lat, err, sizeof err) != 0)
        return; /* no lattice: the method is not built */
    out->work = (double)lattice_cell_count(&lat) * (p->lpv_steps + 1);
    out->memory_bytes = s.transport == LPV_TRANSPORT_PAPER ? lpv_paper_state_bytes(&lat)
                                                           : ilpv_state_bytes(&lat);
}

const gi_method_settings ilpv_settings_table = {
    .name = "ilpv",
    .summary = "incremental light propagation volumes",
    .rows = rows,
    .count = (int)(sizeof rows / sizeof rows[0]),
    .struct_size = sizeof(ilpv_settings),
    .check = check,
    .cost = cost,
    .budget = &ilpv_budget_rule,
};

void ilpv_settings_get(const frame_params *p, ilpv_settings *out)
{
    gi_settings_read(GI_METHOD_ID(ilpv), p, out);
}

int ilpv_settings_lattice(const ilpv_settings *s, const float bounds_min[3], const float bounds_max[3],
                          lattice_desc *out, char *err, size_t errlen)
{
    lattice_fit_desc fit = {
        .bounds_min = {bounds_min[0], bounds_min[1], bounds_min[2]},
        .bounds_max = {bounds_max[0], bounds_max[1], bounds_max[2]},
        .max_axis_cells = s->lattice_cells > 0 ? ILPV_FITTED_AXIS_MAX : s->lattice,
        .max_cells = s->lattice_cells > 0 ? s->lattice_cells : 0,
        .margin_cells = -1.0f,
    };
    char why[160];
    if (lattice_fit(&fit, out, why, sizeof why) != 0) {
        snprintf(err, errlen, "renderer: no light lattice for this scene: %s", why);
        return -1;
    }
    return 0;
}
