/* interaction: navigation, lighting and renderer-settings layouts driven by the wand. */
#include "interaction.h"
#include "gi/gi_settings.h"
#include "base/vec3.h"

#include <math.h>
#include <string.h>

#include "base/mat4.h"

static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

void interaction_init(interaction *ia, const interaction_desc *desc)
{
    memset(ia, 0, sizeof *ia);
    interaction_desc d = *desc;
    if (d.speed <= 0) d.speed = 1.4f;
    if (d.reference_distance <= 0) d.reference_distance = 0.4f;
    if (d.exponent <= 0) d.exponent = 2.5f;
    if (d.max_distance <= 0) d.max_distance = 1.0f;
    if (d.intensity_step <= 1) d.intensity_step = sqrtf(2.0f);
    if (d.hue_rate <= 0) d.hue_rate = 0.25f;
    if (d.saturation_rate <= 0) d.saturation_rate = 0.5f;
    if (d.medium_rate <= 0) d.medium_rate = 0.25f;
    if (d.dead_zone <= 0) d.dead_zone = 0.15f;
    if (d.steps_min <= 0) d.steps_min = 1;
    if (d.steps_max <= 0) d.steps_max = 64;
    if (d.light < 0 || d.light >= FRAME_MAX_LIGHTS) d.light = 0;
    int any = 0;
    for (int i = 0; i < INTERACTION_LAMBDA_PRESETS; i++)
        any |= d.lambda_presets[i] != 0.0f;
    if (!any) {
        const float presets[INTERACTION_LAMBDA_PRESETS] = {0.0f, 0.5f, 0.8f, 0.9f};
        memcpy(d.lambda_presets, presets, sizeof presets);
    }
    if ((unsigned)d.first_layout >= (d.grab ? INTERACTION_LAYOUT_COUNT : INTERACTION_GRAB))
        d.first_layout = INTERACTION_NAVIGATION;
    ia->desc = d;
    ia->layout = d.first_layout;
}

float interaction_speed(const interaction_desc *desc, float distance)
{
    float ref = desc->reference_distance > 0 ? desc->reference_distance : 0.4f;
    float ex = desc->exponent > 0 ? desc->exponent : 2.5f;
    float v0 = desc->speed > 0 ? desc->speed : 1.4f;
    float dmax = desc->max_distance > 0 ? desc->max_distance : 1.0f;
    float d = distance < 0 ? 0 : distance > dmax ? dmax : distance;
    return v0 * powf(d / ref, ex);
}

void interaction_hsv_to_rgb(float h, float s, float v, float rgb[3])
{
    h = h - floorf(h);
    float x = h * 6.0f;
    int sector = (int)x;
    float f = x - (float)sector;
    float p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    float r, g, b;
    switch (sector % 6) {
    case 0: r = v; g = t; b = p; break;
    case 1: r = q; g = v; b = p; break;
    case 2: r = p; g = v; b = t; break;
    case 3: r = p; g = q; b = v; break;
    case 4: r = t; g = p; b = v; break;
    default: r = v; g = p; b = q; break;
    }
    rgb[0] = r;
    rgb[1] = g;
    rgb[2] = b;
}

void interaction_rgb_to_hsv(const float rgb[3], float *h, float *s, float *v)
{
    float r = rgb[0], g = rgb[1], b = rgb[2];
    float mx = fmaxf(r, fmaxf(g, b)), mn = fminf(r, fminf(g, b)), c = mx - mn;
    float hh = 0.0f;
    if (c > 0) {
        if (mx == r)
            hh = (g - b) / c;
        else if (mx == g)
            hh = (b - r) / c + 2.0f;
        else
            hh = (r - g) / c + 4.0f;
        hh /= 6.0f;
        hh -= floorf(hh);
    }
    *h = hh;
    *s = mx > 0 ? c / mx : 0.0f;
    *v = mx;
}

/* ---- small column-major helpers ---- */

static void transform_dir(const float m[16], const float d[3], float out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = m[r] * d[0] + m[4 + r] * d[1] + m[8 + r] * d[2];
}

/* The wand points along its -Z axis. */
static void wand_forward(const input_pose *w, float f[3])
{
    for (int i = 0; i < 3; i++)
        f[i] = -w->rotation[6 + i];
}

/* Heading of the wand about Y: 0 when pointing at -Z, positive turning left (CCW from
 * above). Returns 0 if the wand points nearly straight up or down. */
static int wand_yaw(const input_pose *w, float *yaw)
{
    float f[3];
    wand_forward(w, f);
    if (f[0] * f[0] + f[2] * f[2] < 1e-4f)
        return 0;
    *yaw = atan2f(-f[0], -f[2]);
    return 1;
}

static float dead(const interaction_desc *d, float x)
{
    float a = fabsf(x);
    if (!(a > d->dead_zone))
        return 0.0f;
    a = (fminf(a, 1.0f) - d->dead_zone) / (1.0f - d->dead_zone);
    return x < 0 ? -a : a;
}

static float clamp01(float x) { return x < 0 ? 0 : x > 1 ? 1 : x; }

static int set16(float dst[16], const float src[16])
{
    if (memcmp(dst, src, 16 * sizeof(float)) == 0)
        return 0;
    memcpy(dst, src, 16 * sizeof(float));
    return 1;
}

/* ---- layouts ---- */

static void navigation_update(interaction *ia, const input_state *in, double dt, frame_params *p)
{
    const interaction_desc *d = &ia->desc;
    if (in->pressed & (1u << INPUT_BUTTON_M)) {
        memcpy(p->navigation, identity, sizeof identity);
        ia->dragging = 0;
    }
    if ((in->buttons & (1u << INPUT_BUTTON_C)) && in->wand.valid && in->head.valid && dt > 0) {
        float dx = in->wand.position[0] - in->head.position[0];
        float dz = in->wand.position[2] - in->head.position[2];
        float v = interaction_speed(d, sqrtf(dx * dx + dz * dz));
        float f[3], fw[3];
        wand_forward(&in->wand, f);
        transform_dir(p->navigation, f, fw);
        vec3_normalize(fw);
        for (int i = 0; i < 3; i++)
            p->navigation[12 + i] += fw[i] * v * (float)dt;
    }
    float yaw;
    if ((in->buttons & (1u << INPUT_BUTTON_L)) && in->wand.valid && wand_yaw(&in->wand, &yaw)) {
        if (!ia->dragging) {
            ia->dragging = 1;
            ia->drag_yaw = yaw;
            memcpy(ia->drag_navigation, p->navigation, sizeof ia->drag_navigation);
            ia->drag_pivot[0] = in->head.valid ? in->head.position[0] : 0.0f;
            ia->drag_pivot[1] = 0.0f;
            ia->drag_pivot[2] = in->head.valid ? in->head.position[2] : 0.0f;
            return;
        }
        float a = yaw - ia->drag_yaw, c = cosf(a), s = sinf(a);
        const float *pv = ia->drag_pivot;
        /* T(pivot) * Ry(a) * T(-pivot) */
        float r[16] = {c, 0, -s, 0, 0, 1, 0, 0, s, 0, c, 0,
                       pv[0] - (c * pv[0] + s * pv[2]), 0, pv[2] - (-s * pv[0] + c * pv[2]), 1};
        mat4_mul(ia->drag_navigation, r, p->navigation);
    } else {
        ia->dragging = 0;
    }
}

static void lighting_update(interaction *ia, const input_state *in, double dt, frame_params *p)
{
    const interaction_desc *d = &ia->desc;
    int li = d->light;
    if (p->light_count <= li) {
        /* No spot to hold: make one, so the flashlight works in an unlit scene. */
        for (int i = p->light_count; i <= li; i++)
            p->lights[i] = (frame_light){.enabled = 1, .position = {0, 2, 0},
                                         .direction = {0, 0, -1}, .color = {1, 1, 1},
                                         .intensity = 10.0f, .outer_angle = 0.5f,
                                         .inner_angle = 0.4f};
        p->light_count = li + 1;
    }
    frame_light *l = &p->lights[li];
    if (!ia->hsv_known) {
        interaction_rgb_to_hsv(l->color, &ia->hue, &ia->saturation, &ia->value);
        if (ia->value <= 0)
            ia->value = 1.0f;
        ia->hsv_known = 1;
    }
    if ((in->buttons & (1u << INPUT_BUTTON_C)) && in->wand.valid) {
        float f[3];
        wand_forward(&in->wand, f);
        mat4_transform_point(p->navigation, in->wand.position, l->position);
        transform_dir(p->navigation, f, l->direction);
        vec3_normalize(l->direction);
    }
    if (in->pressed & (1u << INPUT_BUTTON_M))
        l->intensity *= d->intensity_step;
    if (in->pressed & (1u << INPUT_BUTTON_L))
        l->intensity /= d->intensity_step;
    float y = dead(d, in->axes[INPUT_AXIS_Y]), x = dead(d, in->axes[INPUT_AXIS_X]);
    if ((x != 0 || y != 0) && dt > 0) {
        ia->hue += y * d->hue_rate * (float)dt;
        ia->hue -= floorf(ia->hue);
        ia->saturation = clamp01(ia->saturation + x * d->saturation_rate * (float)dt);
        interaction_hsv_to_rgb(ia->hue, ia->saturation, ia->value, l->color);
    }
}

static void settings_update(interaction *ia, const input_state *in, double dt, frame_params *p)
{
    const interaction_desc *d = &ia->desc;
    if (in->pressed & (1u << INPUT_BUTTON_M))
        p->lpv_steps++;
    if (in->pressed & (1u << INPUT_BUTTON_L))
        p->lpv_steps--;
    p->lpv_steps = p->lpv_steps < d->steps_min ? d->steps_min
                 : p->lpv_steps > d->steps_max ? d->steps_max : p->lpv_steps;
    if (dt > 0) {
        p->absorption = clamp01(p->absorption + dead(d, in->axes[INPUT_AXIS_X]) * d->medium_rate * (float)dt);
        p->scattering = clamp01(p->scattering + dead(d, in->axes[INPUT_AXIS_Y]) * d->medium_rate * (float)dt);
    }
    if (in->pressed & (1u << INPUT_BUTTON_AUX)) {
        float next = d->lambda_presets[0];
        for (int i = 0; i < INTERACTION_LAMBDA_PRESETS; i++)
            if (d->lambda_presets[i] > p->lambda_incr + 1e-6f) {
                next = d->lambda_presets[i];
                break;
            }
        p->lambda_incr = next;
    }
    if (in->pressed & (1u << INPUT_BUTTON_C))
        p->gi = (p->gi + 1) % gi_method_count();
}

uint32_t interaction_update(interaction *ia, const input_state *in, double dt, frame_params *p)
{
    uint32_t changed = 0;
    float m[16];
    if (in->head.valid) {
        input_pose_to_mat4(&in->head, m);
        if (set16(p->head, m))
            changed |= INTERACTION_CHANGED_HEAD;
    }
    if (in->wand.valid) {
        input_pose_to_mat4(&in->wand, m);
        if (set16(p->wand, m))
            changed |= INTERACTION_CHANGED_WAND;
    }
    if (in->pressed & (1u << INPUT_BUTTON_R)) {
        int layouts = ia->desc.grab ? INTERACTION_LAYOUT_COUNT : INTERACTION_GRAB;
        ia->layout = (interaction_layout)((ia->layout + 1) % layouts);
        ia->dragging = 0;
    }
    if (p->hud_layout != (int)ia->layout) {
        p->hud_layout = (int)ia->layout;
        changed |= INTERACTION_CHANGED_LAYOUT;
    }

    float nav[16];
    memcpy(nav, p->navigation, sizeof nav);
    int light_count = p->light_count;
    frame_light light = p->lights[ia->desc.light];
    int steps = p->lpv_steps;
    int gi = p->gi;
    float absorption = p->absorption, scattering = p->scattering, lambda = p->lambda_incr;
    switch (ia->layout) {
    case INTERACTION_NAVIGATION: navigation_update(ia, in, dt, p); break;
    case INTERACTION_LIGHTING: lighting_update(ia, in, dt, p); break;
    case INTERACTION_SETTINGS: settings_update(ia, in, dt, p); break;
    default: break; /* grab: the scene's objects, not the frame (grab.h) */
    }
    if (memcmp(nav, p->navigation, sizeof nav))
        changed |= INTERACTION_CHANGED_NAVIGATION;
    if (light_count != p->light_count || memcmp(&light, &p->lights[ia->desc.light], sizeof light))
        changed |= INTERACTION_CHANGED_LIGHT;
    if (steps != p->lpv_steps)
        changed |= INTERACTION_CHANGED_STEPS;
    if (absorption != p->absorption)
        changed |= INTERACTION_CHANGED_ABSORPTION;
    if (scattering != p->scattering)
        changed |= INTERACTION_CHANGED_SCATTERING;
    if (lambda != p->lambda_incr)
        changed |= INTERACTION_CHANGED_LAMBDA;
    if (gi != p->gi)
        changed |= INTERACTION_CHANGED_GI;
    return changed;
}
