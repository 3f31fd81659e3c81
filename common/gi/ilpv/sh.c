#include "gi/ilpv/sh.h"

#include <math.h>

void sh_eval(const float w[3], float out[4])
{
    double len = sqrt((double)w[0] * w[0] + (double)w[1] * w[1] + (double)w[2] * w[2]);
    double s = len > 0.0 ? SH_Y1 / len : 0.0;
    out[0] = (float)SH_Y0;
    out[1] = (float)(-s * w[1]);
    out[2] = (float)(s * w[2]);
    out[3] = (float)(-s * w[0]);
}

void sh_cosine_lobe(const float n[3], float out[4])
{
    double len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
    double s = len > 0.0 ? SH_COS1 / len : 0.0;
    out[0] = (float)SH_COS0;
    out[1] = (float)(-s * n[1]);
    out[2] = (float)(s * n[2]);
    out[3] = (float)(-s * n[0]);
}

float sh_dot(const float a[4], const float b[4])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
}

float sh_value(const float coeff[4], const float w[3])
{
    float y[4];
    sh_eval(w, y);
    return sh_dot(coeff, y);
}

void sh_project(sh_function f, void *ctx, int n_theta, double out[4])
{
    const double pi = 3.14159265358979323846;
    if (n_theta < 1)
        n_theta = 1;
    int n_phi = 2 * n_theta;
    double dw = 4.0 * pi / ((double)n_theta * n_phi); /* solid angle of one cell */
    double acc[4] = {0, 0, 0, 0};
    for (int i = 0; i < n_theta; i++) {
        double z = 1.0 - 2.0 * (i + 0.5) / n_theta;
        double r = sqrt(fmax(0.0, 1.0 - z * z));
        for (int k = 0; k < n_phi; k++) {
            double phi = 2.0 * pi * (k + 0.5) / n_phi;
            double w[3] = {r * cos(phi), r * sin(phi), z};
            double v = f(ctx, w) * dw;
            acc[0] += v * SH_Y0;
            acc[1] += v * -SH_Y1 * w[1];
            acc[2] += v * SH_Y1 * w[2];
            acc[3] += v * -SH_Y1 * w[0];
        }
    }
    for (int s = 0; s < 4; s++)
        out[s] = acc[s];
}
