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

void mat4d_mul(const double a[16], const double b[16], double out[16])
{
    double t[16];
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a[k * 4 + r] * b[c * 4 + k];
            t[c * 4 + r] = s;
        }
    memcpy(out, t, sizeof t);
}

void mat4d_identity(double out[16])
{
    for (int i = 0; i < 16; i++)
        out[i] = i % 5 == 0;
}

void mat4d_from_float(const float m[16], double out[16])
{
    for (int i = 0; i < 16; i++)
        out[i] = m[i];
}

/* Swaps row c with the row below it of the largest |a[r][c]|; 0 when that is ~0. */
static int pivot(double a[4][8], int c)
{
    int piv = c;
    for (int r = c + 1; r < 4; r++)
        if (fabs(a[r][c]) > fabs(a[piv][c]))
            piv = r;
    if (!(fabs(a[piv][c]) > 1e-300))
        return 0;
    for (int k = 0; k < 8; k++) {
        double t = a[c][k];
        a[c][k] = a[piv][k];
        a[piv][k] = t;
    }
    return 1;
}

int mat4d_inverse(const double m[16], double out[16])
{
    double a[4][8]; /* [m | I], row-major */
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            a[r][c] = m[c * 4 + r];
            a[r][4 + c] = r == c;
        }
    for (int c = 0; c < 4; c++) {
        if (!pivot(a, c))
            return -1;
        double inv = 1.0 / a[c][c];
        for (int k = 0; k < 8; k++)
            a[c][k] *= inv;
        for (int r = 0; r < 4; r++)
            if (r != c) {
                double f = a[r][c];
                for (int k = 0; k < 8; k++)
                    a[r][k] -= f * a[c][k];
            }
    }
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            out[c * 4 + r] = a[r][4 + c];
    return 0;
}

int mat4_affine_inverse_d(const double m[16], double out[16])
{
    /* The 3x3 part by its cofactors over the determinant, the translation by -R^-1 t. */
    double c[9] = {
        m[5] * m[10] - m[6] * m[9], m[2] * m[9] - m[1] * m[10], m[1] * m[6] - m[2] * m[5],
        m[6] * m[8] - m[4] * m[10], m[0] * m[10] - m[2] * m[8], m[2] * m[4] - m[0] * m[6],
        m[4] * m[9] - m[5] * m[8], m[1] * m[8] - m[0] * m[9], m[0] * m[5] - m[1] * m[4],
    };
    double det = m[0] * c[0] + m[4] * c[1] + m[8] * c[2];
    if (!(fabs(det) > 1e-30) || !isfinite(det))
        return -1;
    double r[16] = {0};
    for (int col = 0; col < 3; col++)
        for (int row = 0; row < 3; row++)
            r[col * 4 + row] = c[col * 3 + row] / det;
    for (int row = 0; row < 3; row++)
        r[12 + row] = -(r[row] * m[12] + r[4 + row] * m[13] + r[8 + row] * m[14]);
    r[15] = 1;
    for (int i = 0; i < 16; i++)
        if (!isfinite(r[i]))
            return -1;
    memcpy(out, r, sizeof r);
    return 0;
}

int mat4_affine_inverse(const float m[16], float out[16])
{
    double d[16], r[16];
    for (int i = 0; i < 16; i++)
        d[i] = m[i];
    if (mat4_affine_inverse_d(d, r) != 0)
        return -1;
    for (int i = 0; i < 16; i++)
        out[i] = (float)r[i];
    return 0;
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
