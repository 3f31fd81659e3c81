#include "gi/ilpv/lpv_receive.h"

#include <math.h>

#include "gi/ilpv/sh.h"

float lpv_receive_closure(const float L[4], const float n[3], float cell)
{
    const float pi = 3.14159265358979f, inv_y1 = (float)(1.0 / SH_Y1);
    float e = (float)SH_ENERGY * L[0];
    if (!(e > 0.0f))
        return 0.0f;
    float f[3] = {-L[3] * inv_y1, -L[1] * inv_y1, L[2] * inv_y1};
    float len = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    float q = len / e, t = 0.0f;
    q = q < 1.0f ? q : 1.0f;
    if (len > 0.0f)
        t = -(f[0] * n[0] + f[1] * n[1] + f[2] * n[2]) / len;
    t = t > 1.0f ? 1.0f : t < -1.0f ? -1.0f : t;
    float theta = acosf(t);
    float beam = t > 0.0f ? t : 0.0f;
    float lobe = ((pi - theta) * t + sinf(theta)) * (2.0f / (3.0f * pi));
    float hemi = 0.25f * (1.0f + t), iso = 0.25f;
    float g;
    if (q >= 2.0f / 3.0f) {
        float w = 3.0f * q - 2.0f;
        g = w * beam + (1.0f - w) * lobe;
    } else if (q >= 0.5f) {
        float w = 6.0f * q - 3.0f;
        g = w * lobe + (1.0f - w) * hemi;
    } else {
        float w = 2.0f * q;
        g = w * hemi + (1.0f - w) * iso;
    }
    return e * g / (cell * cell);
}

void lpv_receive_irradiance(const lpv_volume *field, const lattice_desc *lat, const float p[3],
                            const float n[3], int on_surface, float out_rgb[3])
{
    out_rgb[0] = out_rgb[1] = out_rgb[2] = 0.0f;
    float q[3];
    int i0[3];
    for (int a = 0; a < 3; a++) {
        q[a] = (p[a] - lat->origin[a]) / lat->cell - 0.5f;
        i0[a] = (int)floorf(q[a]);
        q[a] -= (float)i0[a];
    }
    float L[3][4] = {{0}}, wsum = 0.0f, layer = lpv_own_layer(n) * lat->cell;
    for (int k = 0; k < 8; k++) {
        int c[3] = {i0[0] + (k & 1), i0[1] + ((k >> 1) & 1), i0[2] + ((k >> 2) & 1)};
        float w = 1.0f, behind = 0.0f;
        for (int a = 0; a < 3; a++) {
            w *= (k >> a) & 1 ? q[a] : 1.0f - q[a];
            float centre = lat->origin[a] + ((float)c[a] + 0.5f) * lat->cell;
            behind += (centre - p[a]) * n[a];
        }
        if ((on_surface && (behind < -LPV_RECEIVE_BEHIND * lat->cell || behind >= layer)) ||
            !(w > 0.0f))
            continue;
        /* GL textures clamp to the edge */
        for (int a = 0; a < 3; a++)
            c[a] = c[a] < 0 ? 0 : c[a] >= lat->n[a] ? lat->n[a] - 1 : c[a];
        size_t i = (size_t)c[0] + (size_t)lat->n[0] * ((size_t)c[1] + (size_t)lat->n[1] * c[2]);
        for (int col = 0; col < 3; col++)
            for (int s = 0; s < 4; s++)
                L[col][s] += w * field->ch[4 * col + s][i];
        wsum += w;
    }
    if (!(wsum > 0.0f))
        return;
    for (int col = 0; col < 3; col++) {
        for (int s = 0; s < 4; s++)
            L[col][s] /= wsum;
        out_rgb[col] = lpv_receive_closure(L[col], n, lat->cell);
    }
}
