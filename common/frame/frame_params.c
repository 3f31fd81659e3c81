#include <math.h>
#include <string.h>

#include "frame/frame_params.h"
#include "scene/scene.h"

static void identity(float m[16])
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = m[10] = m[15] = 1.0f;
}

void frame_params_default(frame_params *p)
{
    memset(p, 0, sizeof *p);
    identity(p->head);
    identity(p->wand);
    identity(p->navigation);
    /* 8 steps with lambda_incr 0.8 look like non-incremental rendering (paper, figure 2)
     * and stay below 0.9, beyond which the temporal lag becomes noticeable (section 3.4). */
    p->lpv_steps = 8;
    p->lambda_incr = 0.8f;
    p->absorption = 0.0f;
    p->scattering = 0.0f;
    /* A CAVE's projected light lights its own room: a dim surround (paper table 3.1). */
    p->environment = FRAME_ENV_DIM;
    p->display_gamma = 2.2f;
    p->exposure = 1.0f;
    p->hud_layout = -1;
    p->gi = FRAME_GI_ILPV;
    p->vpl_count = FRAME_VPL_DEFAULT;
    p->vpl_seed = 0;
    p->vpl_selection = VPL_SELECT_FLUX;
}

const char *const frame_gi_names[FRAME_GI_COUNT] = {"ilpv", "none", "vpl"};

const char *frame_gi_name(frame_gi gi)
{
    return (unsigned)gi < FRAME_GI_COUNT ? frame_gi_names[gi] : NULL;
}

int frame_gi_parse(const char *name, frame_gi *out)
{
    for (int i = 0; i < FRAME_GI_COUNT; i++)
        if (strcmp(name, frame_gi_names[i]) == 0) {
            *out = (frame_gi)i;
            return 0;
        }
    return -1;
}

float frame_params_e2e_gamma(frame_environment env)
{
    switch (env) {
    case FRAME_ENV_DARK: return 1.5f;
    case FRAME_ENV_OFFICE: return 1.125f;
    case FRAME_ENV_DIM:
    default: return 1.25f;
    }
}

void frame_params_lights_from_scene(frame_params *p, const scene *s)
{
    p->light_count = 0;
    for (int i = 0; i < s->light_count && i < FRAME_MAX_LIGHTS; i++) {
        const scene_light *l = &s->lights[i];
        frame_light *f = &p->lights[p->light_count++];
        f->enabled = 1;
        f->type = l->type;
        memcpy(f->position, l->position, sizeof f->position);
        memcpy(f->direction, l->direction, sizeof f->direction);
        memcpy(f->color, l->color, sizeof f->color);
        f->intensity = l->intensity;
        f->outer_angle = l->outer_angle;
        f->inner_angle = l->inner_angle;
    }
}

static int all_finite(const float *x, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}

/* Sets *x to fallback unless it is in [lo, hi] (NaN is never in range); 1 if changed. */
static int clamp_or(float *x, float lo, float hi, float below, float above, float nan)
{
    float v = *x;
    if (v != v)
        *x = nan;
    else if (v < lo)
        *x = below;
    else if (v > hi)
        *x = above;
    else
        return 0;
    return 1;
}

static int sanitize_light(frame_light *l)
{
    int changed = 0;
    if ((unsigned)l->type >= SCENE_LIGHT_TYPES) {
        changed = l->enabled != 0;
        l->enabled = 0;
        return changed;
    }
    if (l->type == SCENE_LIGHT_POINT && !(all_finite(l->direction, 3) &&
                                          (l->direction[0] != 0 || l->direction[1] != 0 ||
                                           l->direction[2] != 0))) {
        l->direction[0] = l->direction[2] = 0.0f;
        l->direction[1] = -1.0f;
        changed++;
    }
    float len2 = l->direction[0] * l->direction[0] + l->direction[1] * l->direction[1] +
                 l->direction[2] * l->direction[2];
    if (!all_finite(l->position, 3) || !all_finite(l->direction, 3) || !all_finite(l->color, 3) ||
        !isfinite(l->intensity) || !isfinite(l->outer_angle) || !isfinite(l->inner_angle) ||
        !(len2 > 0.0f) || !isfinite(len2)) {
        changed = l->enabled != 0;
        l->enabled = 0;
        return changed;
    }
    if (fabsf(len2 - 1.0f) > 1e-4f) {
        float len = sqrtf(len2);
        for (int a = 0; a < 3; a++)
            l->direction[a] /= len;
        changed++;
    }
    for (int c = 0; c < 3; c++)
        changed += clamp_or(&l->color[c], 0.0f, INFINITY, 0.0f, 0.0f, 0.0f);
    changed += clamp_or(&l->intensity, 0.0f, FRAME_MAX_INTENSITY, 0.0f, FRAME_MAX_INTENSITY, 0.0f);
    return changed;
}

int frame_params_sanitize(frame_params *p)
{
    int changed = 0;
    float *poses[3] = {p->head, p->wand, p->navigation};
    for (int i = 0; i < 3; i++)
        if (!all_finite(poses[i], 16)) {
            identity(poses[i]);
            changed++;
        }
    if (!isfinite(p->time)) {
        p->time = 0.0;
        changed++;
    }
    if (p->light_count < 0 || p->light_count > FRAME_MAX_LIGHTS) {
        p->light_count = p->light_count < 0 ? 0 : FRAME_MAX_LIGHTS;
        changed++;
    }
    for (int i = 0; i < p->light_count; i++)
        changed += sanitize_light(&p->lights[i]);
    if (p->lpv_steps < 0 || p->lpv_steps > FRAME_MAX_LPV_STEPS) {
        p->lpv_steps = p->lpv_steps < 0 ? 0 : FRAME_MAX_LPV_STEPS;
        changed++;
    }
    changed += clamp_or(&p->lambda_incr, 0.0f, 0.999f, 0.0f, 0.999f, 0.0f);
    changed += clamp_or(&p->absorption, 0.0f, 1.0f, 0.0f, 1.0f, 0.0f);
    changed += clamp_or(&p->scattering, 0.0f, 1.0f, 0.0f, 1.0f, 0.0f);
    if (p->pattern != 0 && p->pattern != 1) {
        p->pattern = 0;
        changed++;
    }
    if (p->environment != FRAME_ENV_DARK && p->environment != FRAME_ENV_DIM &&
        p->environment != FRAME_ENV_OFFICE) {
        p->environment = FRAME_ENV_DIM;
        changed++;
    }
    if ((unsigned)p->gi >= FRAME_GI_COUNT) {
        p->gi = FRAME_GI_ILPV;
        changed++;
    }
    if ((unsigned)p->vpl_selection >= VPL_SELECT_COUNT) {
        p->vpl_selection = VPL_SELECT_FLUX;
        changed++;
    }
    if (p->vpl_count < FRAME_VPL_MIN || p->vpl_count > FRAME_VPL_MAX) {
        p->vpl_count = p->vpl_count <= 0               ? FRAME_VPL_DEFAULT
                       : p->vpl_count < FRAME_VPL_MIN ? FRAME_VPL_MIN
                                                      : FRAME_VPL_MAX;
        changed++;
    }
    if (!(p->display_gamma > 0.0f) || !isfinite(p->display_gamma)) {
        p->display_gamma = 2.2f;
        changed++;
    }
    if (!(p->exposure > 0.0f) || !isfinite(p->exposure)) {
        p->exposure = 1.0f;
        changed++;
    } else if (p->exposure > FRAME_MAX_EXPOSURE) {
        p->exposure = FRAME_MAX_EXPOSURE;
        changed++;
    }
    return changed;
}
