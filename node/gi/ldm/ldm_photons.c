/* ldm_photons: see ldm_photons.h. */
#include "gi/ldm/ldm_photons.h"

#include <math.h>
#include <string.h>

#include "base/vec3.h"

static const float PI_F = 3.14159265358979f;

/* One block's lit texels x0..x1, y0..y1 as a photon; 0 when it has no light. */
static int block(const float *position, const float *normal, const float *flux, int size,
                 int x0, int x1, int y0, int y1, const float *light, ldm_photon *out)
{
    double w = 0, area = 0, p[3] = {0, 0, 0}, n[3] = {0, 0, 0}, f[3] = {0, 0, 0};
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            size_t i = 4 * ((size_t)y * size + x);
            const float *fl = flux + i;
            double lum = (double)fl[0] + fl[1] + fl[2];
            if (position[i + 3] == 0.0f || !(lum > 0))
                continue;
            w += lum;
            area += vpl_texel_area(position, normal, size, x, y);
            for (int a = 0; a < 3; a++) {
                p[a] += lum * position[i + a];
                n[a] += lum * normal[i + a];
                f[a] += fl[a];
            }
        }
    if (!(w > 0))
        return 0;
    memset(out, 0, sizeof *out);
    for (int a = 0; a < 3; a++) {
        out->position[a] = (float)(p[a] / w);
        out->normal[a] = (float)n[a];
        out->flux[a] = (float)f[a];
    }
    vec3_normalize(out->normal);
    out->radius = sqrtf((float)area / PI_F);
    if (light) { /* the block's angular half-width seen from the light */
        float to[3];
        vec3_sub(out->position, light, to);
        float d = vec3_length(to);
        out->spread = d > 0 ? out->radius / d : 0.0f;
    }
    return 1;
}

size_t ldm_photons_from_rsm(const float *position, const float *normal, const float *flux,
                            int size, int side, const float *light, ldm_photon *out)
{
    if (side > size)
        side = size;
    int step = size / side;
    size_t n = 0;
    for (int by = 0; by < side; by++)
        for (int bx = 0; bx < side; bx++) {
            int x1 = bx + 1 == side ? size : (bx + 1) * step;
            int y1 = by + 1 == side ? size : (by + 1) * step;
            n += (size_t)block(position, normal, flux, size, bx * step, x1, by * step, y1, light,
                               &out[n]);
        }
    return n;
}

ldm_photon ldm_photon_from_emitter(const vpl_emitter *e)
{
    vpl v = vpl_from_emitter(e);
    ldm_photon p;
    memset(&p, 0, sizeof p);
    memcpy(p.position, v.position, sizeof p.position);
    memcpy(p.normal, v.normal, sizeof p.normal);
    memcpy(p.flux, v.flux, sizeof p.flux);
    p.radius = sqrtf(e->area / PI_F);
    p.spread = -1.0f; /* its light leaves in every direction: the cell's, always */
    return p;
}

void ldm_photons_finish(ldm_photon *p, size_t n, const ldm_map *maps, int count,
                        ldm_spread spread)
{
    float cos_cell = 1.0f - 1.0f / (float)count;
    float cell = sqrtf(fmaxf(1.0f - cos_cell * cos_cell, 0.0f)) / cos_cell;
    for (size_t i = 0; i < n; i++) {
        double sum = 0;
        for (int m = 0; m < count; m++)
            sum += fabsf(vec3_dot(p[i].normal, maps[m].d));
        p[i].weight = sum > 0 ? (float)(1.0 / sum) : 0.0f;
        if (spread == LDM_SPREAD_CELL || p[i].spread < 0.0f)
            p[i].spread = cell;
    }
}
