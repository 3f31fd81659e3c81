/* exposure: middle grey from the scene's light (exposure.h). */
#include "frame/exposure.h"

#include <math.h>

#include "base/vec3.h"
#include "frame/light_view.h"

static const double PI = 3.14159265358979323846;

float exposure_from_light(const frame_params *p, const scene *s)
{
    double area = 0, reflected = 0, power = 0;
    for (size_t t = 0; t < s->triangle_count; t++) {
        double a = vec3_triangle_area(s->positions + 9 * t);
        const scene_material *m = &s->materials[s->triangle_material[t]];
        area += a;
        reflected += a * (m->base_color[0] + m->base_color[1] + m->base_color[2]) / 3.0;
        power += PI * a * (m->emissive[0] + m->emissive[1] + m->emissive[2]) / 3.0;
    }
    for (int i = 0; i < p->light_count && i < FRAME_MAX_LIGHTS; i++)
        power += light_power(&p->lights[i], s);
    double radiance = area > 0 ? (reflected / area) * power / (PI * area) : 0;
    if (!(radiance > 0))
        return 1.0f;
    /* Within the exposure setting's range (frame_display_settings[]). */
    const setting *row = &frame_display_settings[setting_find(
        frame_display_settings, frame_display_setting_count, "exposure")];
    setting_value v = {.f = (float)fmin(EXPOSURE_KEY / radiance, 3.0e38)};
    setting_clamp(row, &v);
    return v.f;
}
