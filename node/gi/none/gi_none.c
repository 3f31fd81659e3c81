#include "gi/none/gi_none.h"

#include <stdlib.h>

#include "base/xalloc.h"

typedef struct gi_none {
    const gl_functions *gl;
} gi_none;

/* FNV-1a of "none": what READY carries while no method computes anything. */
static const uint64_t NONE_CHECKSUM = 0x8e37b614dbd95475ull;

static void *none_create(const gi_desc *desc, char *err, size_t errlen)
{
    gi_none *n = xcalloc(1, sizeof *n);
    n->gl = desc->gl;
    return n;
}

static void none_destroy(void *state) { free(state); }
static int none_reuse(void *state, const frame_params *p) { return 0; }

static uint64_t none_frame(void *state, const frame_params *p, const gi_rsm *rsm)
{
    return NONE_CHECKSUM;
}

/* Its snippet (none_shade.glsl) has no uniforms. */
static void none_eye_bind(void *state, const gi_eye *eye) {}

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
