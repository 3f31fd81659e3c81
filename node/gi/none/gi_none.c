/* gi_none: the skeleton of a GI method (docs/architecture.md, "GI methods"). A new method
 * NAME starts as a copy of this folder and of common/gi/none/ with "none" renamed:
 *   common/gi/NAME/NAME_settings.{h,c}   its settings' rows, no GL (the master links them)
 *   node/gi/NAME/gi_NAME.{h,c}           this interface (gi_method.h)
 *   node/gi/NAME/NAME_shade.glsl         its shading snippet, gi_irradiance()
 * and one line GI_METHOD(NAME) in common/gi/gi_methods.def: five files and one line. */
#include "gi/none/gi_none.h"

#include <stdlib.h>
#include <string.h>

#include "base/fnv1a.h"
#include "base/xalloc.h"
#include "gi/none/none_settings.h"

typedef struct gi_none {
    const gl_functions *gl;
    none_settings settings;  /* this frame's */
} gi_none;

static void *none_create(const gi_desc *desc, char *err, size_t errlen)
{
    gi_none *n = xcalloc(1, sizeof *n);
    n->gl = desc->gl;
    none_settings_get(desc->frame, &n->settings);
    return n;
}

static void none_destroy(void *state) { free(state); }
static int none_reuse(void *state, const frame_params *p) { return 0; }

/* READY's checksum: FNV-1a of "none", then of the irradiance's bits when it is set, so two
 * nodes that shade differently never agree. */
static uint64_t none_frame(void *state, const frame_params *p, const gi_rsm *rsm)
{
    gi_none *n = state;
    none_settings_get(p, &n->settings);
    uint64_t h = fnv1a64(FNV1A64_CLUSTER_SEED, "none", 4);
    return n->settings.irradiance == 0.0f
               ? h
               : fnv1a64(h, &n->settings.irradiance, sizeof n->settings.irradiance);
}

static void none_eye_bind(void *state, const gi_eye *eye)
{
    const gi_none *n = state;
    float e = n->settings.irradiance;
    n->gl->Uniform3f(n->gl->GetUniformLocation(eye->program, "u_none_irradiance"), e, e, e);
}

static void none_stats(const void *state, gi_stats *out) {}

const gi_method gi_none_method = {
    .name = "none",
    .shade = {"none/none_shade.glsl"},
    .create = none_create,
    .destroy = none_destroy,
    .reuse = none_reuse,
    .frame = none_frame,
    .eye_bind = none_eye_bind,
    .stats = none_stats,
};
