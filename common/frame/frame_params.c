#include <math.h>
#include <stddef.h>
#include <string.h>

#include "frame/frame_params.h"
#include "frame/ldm_limits.h"
#include "scene/scene.h"

static void identity(float m[16])
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = m[10] = m[15] = 1.0f;
}

static const char *const environment_names[] = {"dark", "dim", "office"};
static const char *const ao_names[FRAME_AO_COUNT] = {"off", "ldm", "ssao"};
static const char *const aa_names[FRAME_AA_COUNT] = {"off", "fxaa"};
static const char *const ao_falloff_names[FRAME_AO_FALLOFFS] = {"occlusion", "obscurance"};

#define FIELD(f) offsetof(frame_params, f)
const setting frame_transport_settings[] = {
    /* 8 steps with lambda_incr 0.8 look like non-incremental rendering (paper, figure 2)
     * and stay below 0.9, beyond which the temporal lag becomes noticeable (section 3.4). */
    {"steps", "S", SETTING_INT, 0, 256, 8, NULL, 0, 0, FIELD(lpv_steps),
     "propagation steps per frame"},
    {"lambda", "L", SETTING_FLOAT, 0, 0.999, 0.8, NULL, 0, 0, FIELD(lambda_incr),
     "lambda_incr: share of the last frame's light kept"},
    {"absorption", "S", SETTING_FLOAT, 0, 1, 0, NULL, 0, 0, FIELD(absorption),
     "participating medium: absorption per metre"},
    {"scattering", "S", SETTING_FLOAT, 0, 1, 0, NULL, 0, 0, FIELD(scattering),
     "participating medium: scattering per metre"},
    /* 2048^2 texels of the four RSM targets are 256 MB per light view. */
    {"rsm", "N", SETTING_INT, 8, 2048, 256, NULL, 0, SETTING_REBUILD, FIELD(rsm_size),
     "reflective shadow map size"},
    /* 8 layers hold every surface over a texel of the chart's rooms (ldm_gl.h counts the
     * rest); 512 MB is the paper's 512 maps of 200^2 at 8 layers with room to spare. */
    {"ldm-layers", "K", SETTING_INT, LDM_LAYERS_MIN, LDM_LAYERS_MAX, 8, NULL, 0, SETTING_REBUILD,
     FIELD(ldm_layers), "layered depth maps: depths kept per texel (the nearest\nK along "
     "each map's direction)"},
    {"ldm-memory", "MB", SETTING_INT, 1, 65536, 512, NULL, 0, 0, FIELD(ldm_memory_mb),
     "layered depth maps: most memory one set of them may take"},
};
const int frame_transport_setting_count =
    (int)(sizeof frame_transport_settings / sizeof frame_transport_settings[0]);

const setting frame_display_settings[] = {
    /* A CAVE's projected light lights its own room: a dim surround (paper table 3.1). */
    {"env", NULL, SETTING_CHOICE, 0, 0, FRAME_ENV_DIM, environment_names, 3, 0,
     FIELD(environment), "viewing environment (end-to-end gamma)"},
    {"display-gamma", "G", SETTING_FLOAT, 0.1, 10, 2.2, NULL, 0, 0, FIELD(display_gamma),
     "display gamma"},
    {"exposure", "E|auto", SETTING_FLOAT, 1e-6, 1e6, 1, NULL, 0, 0, FIELD(exposure),
     "linear scale before tone mapping; auto (what the master\nand the standalone node "
     "take unless a number is given): the\nscene's average lit surface at middle grey (docs/node.md)"},
    {"ao", NULL, SETTING_CHOICE, 0, 0, FRAME_AO_OFF, ao_names, FRAME_AO_COUNT, 0,
     FIELD(ao), "ambient occlusion of the ambient term: layered depth\nmaps, screen space "
     "(horizons) or none"},
    {"ao-distance", "M", SETTING_FLOAT, 0, 1e6, 1, NULL, 0, 0, FIELD(ao_distance),
     "ambient occlusion: farthest occluder, metres (0: any)"},
    {"ao-falloff", NULL, SETTING_CHOICE, 0, 0, FRAME_AO_OCCLUSION, ao_falloff_names,
     FRAME_AO_FALLOFFS, 0, FIELD(ao_falloff),
     "ambient occlusion (an occluder hides) or obscurance\n(it hides less the farther it is)"},
    /* 64 maps of 128^2 (32 MB at 8 layers) take a few seconds to build on llvmpipe. */
    {"ao-directions", "N", SETTING_INT, LDM_DIRECTIONS_MIN, LDM_DIRECTIONS_MAX, 64, NULL, 0, SETTING_REBUILD,
     FIELD(ao_directions), "ambient occlusion: layered depth maps (directions)"},
    {"ao-resolution", "N", SETTING_INT, LDM_RESOLUTION_MIN, LDM_RESOLUTION_MAX, 128, NULL, 0,
     SETTING_REBUILD, FIELD(ao_resolution), "ambient occlusion: texels per side of each map"},
    {"ambient", "L", SETTING_FLOAT, 0, 1e6, 0, NULL, 0, 0, FIELD(ambient),
     "ambient light from every direction, W/(m^2 sr), times\nits occlusion (ao); 0: none"},
    /* After the tone map, before warp and blend: what a wall's pixels show. */
    {"aa", NULL, SETTING_CHOICE, 0, 0, FRAME_AA_OFF, aa_names, FRAME_AA_COUNT, 0, FIELD(aa),
     "anti-aliasing of each eye's image: FXAA 3.11 (Lottes)\nor none"},
};
#undef FIELD
const int frame_display_setting_count =
    (int)(sizeof frame_display_settings / sizeof frame_display_settings[0]);

/* Both tables, for what treats every frame setting alike. */
static const struct {
    const setting *rows;
    const int *count;
} tables[2] = {{frame_transport_settings, &frame_transport_setting_count},
               {frame_display_settings, &frame_display_setting_count}};

void frame_params_default(frame_params *p)
{
    memset(p, 0, sizeof *p);
    identity(p->head);
    identity(p->wand);
    identity(p->navigation);
    for (int t = 0; t < 2; t++)
        for (int i = 0; i < *tables[t].count; i++)
            setting_store(&tables[t].rows[i], setting_default(&tables[t].rows[i]), p);
    p->hud_layout = -1;
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
    if (p->pattern != 0 && p->pattern != 1) {
        p->pattern = 0;
        changed++;
    }
    for (int t = 0; t < 2; t++)
        for (int i = 0; i < *tables[t].count; i++) {
            const setting *row = &tables[t].rows[i];
            setting_value v = setting_load(row, p);
            if (setting_clamp(row, &v)) {
                setting_store(row, v, p);
                changed++;
            }
        }
    return changed;
}
