#include "gi/ilpv/lpv_inject.h"

#include "base/fpmode.h"

#include <math.h>

#include "gi/ilpv/sh.h"

static int finite3(const float v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static int same_shape(const lpv_volume *v, const lattice_desc *lat, int channels)
{
    return v && v->channels == channels && lat->n[0] == v->n[0] && lat->n[1] == v->n[1] &&
           lat->n[2] == v->n[2];
}

void lpv_inject_vpls(lpv_volume *light, lpv_volume *origin, const lattice_desc *lat,
                     const lpv_vpl *vpls, size_t count, lpv_inject_stats *stats)
{
    lpv_inject_stats st = {0};
    fpmode mode = fpmode_enter();
    int usable = lat && same_shape(light, lat, LPV_LIGHT_CHANNELS) &&
                 (!origin || same_shape(origin, lat, LPV_GEOMETRY_CHANNELS));
    for (size_t i = 0; i < count; i++) {
        const lpv_vpl *v = &vpls[i];
        float len2 = v->normal[0] * v->normal[0] + v->normal[1] * v->normal[1] +
                     v->normal[2] * v->normal[2];
        if (!finite3(v->position) || !finite3(v->normal) || !finite3(v->flux) ||
            !(len2 > 0.0f) || !isfinite(len2)) {
            st.invalid++;
            continue;
        }
        float inv = 1.0f / sqrtf(len2), n[3], p[3];
        for (int a = 0; a < 3; a++)
            n[a] = v->normal[a] * inv;
        float offset = 0.5f * lat->cell * (fabsf(n[0]) + fabsf(n[1]) + fabsf(n[2]));
        for (int a = 0; a < 3; a++)
            p[a] = v->position[a] + offset * n[a];
        size_t idx;
        if (!usable || lattice_cell_of(lat, p, NULL, &idx) != 0) {
            st.outside++;
            continue;
        }
        float lobe[4];
        sh_cosine_lobe(n, lobe);
        for (int c = 0; c < 3; c++)
            for (int s = 0; s < 4; s++)
                light->ch[4 * c + s][idx] += v->flux[c] * lobe[s];
        if (origin) {
            float w = v->flux[0] + v->flux[1] + v->flux[2];
            for (int a = 0; a < 3; a++)
                origin->ch[a][idx] +=
                    w * ((v->position[a] - lat->origin[a]) / lat->cell - 0.5f);
            origin->ch[3][idx] += w;
        }
        st.injected++;
    }
    fpmode_leave(mode);
    if (stats) {
        stats->injected += st.injected;
        stats->outside += st.outside;
        stats->invalid += st.invalid;
    }
}
