#include "lpv/lpv_inject.h"

#include "base/fpmode.h"

#include <math.h>

#include "lpv/sh.h"

static int finite3(const float v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

void lpv_inject_vpls(lpv_volume *light, const lattice_desc *lat, const lpv_vpl *vpls,
                     size_t count, lpv_inject_stats *stats)
{
    lpv_inject_stats st = {0};
    fpmode mode = fpmode_enter();
    int usable = light && light->channels == LPV_LIGHT_CHANNELS && lat &&
                 lat->n[0] == light->n[0] && lat->n[1] == light->n[1] && lat->n[2] == light->n[2];
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
        for (int a = 0; a < 3; a++) {
            n[a] = v->normal[a] * inv;
            p[a] = v->position[a] + 0.5f * lat->cell * n[a];
        }
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
        st.injected++;
    }
    fpmode_leave(mode);
    if (stats) {
        stats->injected += st.injected;
        stats->outside += st.outside;
        stats->invalid += st.invalid;
    }
}
