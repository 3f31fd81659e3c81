#include "frame/screen_fit.h"

#include <math.h>

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double norm(double v[3])
{
    double l = sqrt(dot(v, v));
    if (l > 0)
        for (int i = 0; i < 3; i++)
            v[i] /= l;
    return l;
}

/* The rectangle nearest to p[0..3] = bl, br, tl, tr: centre c, axes e1 (right), e2 (up),
 * half sizes a, b. Corners c + a sx e1 + b sy e2 with (sx, sy) = (-,-), (+,-), (-,+), (+,+).
 * For fixed axes the best a is e1.X / 4 with X = sum sx p (likewise b with Y = sum sy p),
 * leaving sum (e1.X)^2 + (e2.Y)^2 to maximise: in the plane of X and Y, with X along u,
 * that is A cos 2t + B sin 2t, largest at 2t = atan2(B, A). */
static int fit4(const double p[4][3], double q[4][3])
{
    static const int sx[4] = {-1, 1, -1, 1}, sy[4] = {-1, -1, 1, 1};
    double c[3], X[3], Y[3], u[3], w[3];
    for (int i = 0; i < 3; i++) {
        c[i] = (p[0][i] + p[1][i] + p[2][i] + p[3][i]) / 4;
        X[i] = Y[i] = 0;
        for (int k = 0; k < 4; k++) {
            X[i] += sx[k] * p[k][i];
            Y[i] += sy[k] * p[k][i];
        }
        u[i] = X[i];
    }
    double xl = norm(u);
    double yu = dot(Y, u);
    for (int i = 0; i < 3; i++)
        w[i] = Y[i] - yu * u[i];
    double yw = norm(w);
    if (!(xl > 1e-9) || !(yw > 1e-9))
        return -1;
    double t = 0.5 * atan2(-yu * yw, 0.5 * (xl * xl - yu * yu + yw * yw));
    double e1[3], e2[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = cos(t) * u[i] + sin(t) * w[i];
        e2[i] = -sin(t) * u[i] + cos(t) * w[i];
    }
    double a = dot(e1, X) / 4, b = dot(e2, Y) / 4;
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < 3; i++)
            q[k][i] = c[i] + a * sx[k] * e1[i] + b * sy[k] * e2[i];
    return 0;
}

int screen_fit_rectangle(const float bottom_left[3], const float bottom_right[3],
                         const float top_left[3], const float *top_right, screen_fit *out)
{
    double p[4][3], q[4][3];
    for (int i = 0; i < 3; i++) {
        p[0][i] = bottom_left[i];
        p[1][i] = bottom_right[i];
        p[2][i] = top_left[i];
        /* Unmeasured: the parallelogram's corner to start from. */
        p[3][i] = top_right ? top_right[i] : p[1][i] + p[2][i] - p[0][i];
    }
    enum { MAX_ITERATIONS = 1000 };
    int n = 0;
    for (;;) {
        if (fit4(p, q) != 0)
            return -1;
        n++;
        if (top_right || n == MAX_ITERATIONS)
            break;
        double moved = 0;
        for (int i = 0; i < 3; i++) {
            moved = fmax(moved, fabs(q[3][i] - p[3][i]));
            p[3][i] = q[3][i];
        }
        if (moved < 1e-12)
            break;
    }
    out->deviation = 0;
    for (int k = 0; k < (top_right ? 4 : 3); k++) {
        double d[3] = {q[k][0] - p[k][0], q[k][1] - p[k][1], q[k][2] - p[k][2]};
        out->deviation = fmax(out->deviation, sqrt(dot(d, d)));
    }
    for (int i = 0; i < 3; i++) {
        out->bottom_left[i] = (float)q[0][i];
        out->bottom_right[i] = (float)q[1][i];
        out->top_left[i] = (float)q[2][i];
    }
    out->iterations = n;
    return 0;
}
