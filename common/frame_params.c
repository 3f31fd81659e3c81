#include <math.h>
#include <string.h>

#include "frame_params.h"
#include "scene.h"

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
    p->lpv_steps = 8;
    p->lambda_incr = 0.8f;
    p->absorption = 0.0f;
    p->scattering = 0.0f;
    p->environment = FRAME_ENV_DIM;
    p->display_gamma = 2.2f;
    p->exposure = 1.0f;
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
        memcpy(f->position, l->position, sizeof f->position);
        memcpy(f->direction, l->direction, sizeof f->direction);
        memcpy(f->color, l->color, sizeof f->color);
        f->intensity = l->intensity;
        f->outer_angle = l->outer_angle;
        f->inner_angle = l->inner_angle;
    }
    if (p->light_count > 0)
        return;
    /* No lights in the file: one spot above the middle, wide enough for the whole scene. */
    frame_light *f = &p->lights[p->light_count++];
    float size = 0;
    for (int a = 0; a < 3; a++) {
        float e = s->bounds_max[a] - s->bounds_min[a];
        size = e > size ? e : size;
        f->position[a] = 0.5f * (s->bounds_min[a] + s->bounds_max[a]);
    }
    float h = s->bounds_max[1] - s->bounds_min[1];
    f->position[1] = s->bounds_max[1] + 1.5f * (h > 0 ? h : size);
    f->enabled = 1;
    f->direction[1] = -1.0f;
    f->color[0] = f->color[1] = f->color[2] = 1.0f;
    float dist = f->position[1] - s->bounds_min[1];
    f->intensity = 2.0f * dist * dist; /* about 2 W/m^2 at the bottom of the bounds */
    f->outer_angle = 0.6f;
    f->inner_angle = 0.45f;
}
