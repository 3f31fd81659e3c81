/* sh: real spherical harmonics with 2 bands (4 coefficients), the paper's sign convention.
 *
 * For a unit direction w = (x, y, z): Y0 = 1/(2 sqrt pi), Y1 = -sqrt(3/(4 pi)) y,
 * Y2 = sqrt(3/(4 pi)) z, Y3 = -sqrt(3/(4 pi)) x. A distribution is 4 coefficients;
 * its value in w is sh_dot(L, sh_eval(w)) and its energy <L|1> = 2 sqrt(pi) L0.
 * Pure functions, no state. */
#ifndef CAVELIGHT_SH_H
#define CAVELIGHT_SH_H

#define SH_Y0 0.28209479177387814   /* 1 / (2 sqrt(pi)) */
#define SH_Y1 0.48860251190291992   /* sqrt(3 / (4 pi)) */
#define SH_COS0 0.88622692545275801 /* sqrt(pi) / 2 */
#define SH_COS1 1.02332670794648849 /* sqrt(pi / 3) */
#define SH_ENERGY 3.54490770181103205 /* 2 sqrt(pi): <L|1> = SH_ENERGY * L0 */

/* Basis functions in direction w (need not be unit length; normalized inside; a zero
 * vector gives the constant term only). */
void sh_eval(const float w[3], float out[4]);
/* Clamped-cosine lobe max(0, dot(n, w)) around n, projected to 2 bands. */
void sh_cosine_lobe(const float n[3], float out[4]);
float sh_dot(const float a[4], const float b[4]);
/* Value of the distribution in direction w. */
float sh_value(const float coeff[4], const float w[3]);

/* Projects f over the sphere by numerical integration on a fixed grid of `n_theta` x
 * `2 n_theta` cells in (cos theta, phi) (equal solid angle per cell, midpoint rule).
 * Deterministic; for tests and precomputation, not per frame. */
typedef double (*sh_function)(void *ctx, const double w[3]);
void sh_project(sh_function f, void *ctx, int n_theta, double out[4]);

#endif
