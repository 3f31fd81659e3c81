#include "base/mat4.h"

#include <math.h>
#include <string.h>

void mat4_mul(const float a[16], const float b[16], float out[16])
{
    float t[16];
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            float s = 0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + r] * b[c * 4 + k];
            t[c * 4 + r] = s;
        }
    memcpy(out, t, sizeof t);
}

void mat4_transform_point(const float m[16], const float p[3], float out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

void mat4_from_trs_deg(const float t[3], const float deg[3], float scale, float out[16])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = deg[i] * 3.14159265358979323846 / 180.0;
    double cx = cos(r[0]), sx = sin(r[0]), cy = cos(r[1]), sy = sin(r[1]), cz = cos(r[2]), sz = sin(r[2]);
    double R[3][3] = { /* R[row][col] = Rz*Ry*Rx */
        {cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx},
        {sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx},
        {-sy, cy * sx, cy * cx},
    };
    memset(out, 0, 16 * sizeof *out);
    for (int col = 0; col < 3; col++)
        for (int row = 0; row < 3; row++)
            out[col * 4 + row] = (float)(R[row][col] * scale);
    out[12] = t[0];
    out[13] = t[1];
    out[14] = t[2];
    out[15] = 1;
}
