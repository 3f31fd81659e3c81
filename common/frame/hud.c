/* hud: derive the HUD's indicators and bars from the frame parameters. */
#include "frame/hud.h"

#include <string.h>

#include "base/mat4.h"

static void grey(float c[3], float v) { c[0] = c[1] = c[2] = v; }

static float clamp01(float x) { return x < 0 ? 0 : x > 1 ? 1 : x; }

void hud_describe(const frame_params *p, int lattice_cells, hud *out)
{
    memset(out, 0, sizeof *out);
    out->visible = p->hud_layout >= 0;
    out->active_layout = p->hud_layout;
    /* wand_world = navigation * wand */
    mat4_mul(p->navigation, p->wand, out->wand_world);
    for (int i = 0; i < HUD_INDICATOR_COUNT; i++) {
        hud_indicator *ind = &out->indicators[i];
        ind->shape = (hud_shape)i;
        ind->active = p->hud_layout == i;
        grey(ind->color, ind->active ? HUD_WHITE : HUD_GREY);
    }
    out->has_light = p->light_count > 0 && p->lights[0].enabled;
    if (out->has_light) {
        const frame_light *l = &p->lights[0];
        /* The cone shows the light's hue at full brightness, whatever its intensity. */
        float mx = l->color[0];
        for (int k = 1; k < 3; k++)
            mx = l->color[k] > mx ? l->color[k] : mx;
        for (int k = 0; k < 3; k++)
            out->indicators[HUD_SHAPE_CONE].color[k] = mx > 0 ? l->color[k] / mx : 0.0f;
        out->light_type = l->type;
        memcpy(out->light_position, l->position, sizeof out->light_position);
        memcpy(out->light_direction, l->direction, sizeof out->light_direction);
        out->light_angle = l->outer_angle;
    }
    const char letters[HUD_BAR_COUNT] = {'A', 'S', 'I', 'P'};
    if (lattice_cells <= 0)
        lattice_cells = HUD_DEFAULT_LATTICE_CELLS;
    float cells = (float)(lattice_cells > 1 ? lattice_cells : 1);
    const float values[HUD_BAR_COUNT] = {clamp01(p->absorption), clamp01(p->scattering),
                                         clamp01(p->lambda_incr),
                                         clamp01((float)p->lpv_steps / cells)};
    for (int i = 0; i < HUD_BAR_COUNT; i++) {
        out->bars[i].letter = letters[i];
        out->bars[i].value = values[i];
        grey(out->bars[i].color, 0.75f);
    }
    grey(out->bars[2].color, p->lambda_incr > 0 ? HUD_WHITE : HUD_GREY);
}
