/* Inverse bilinear interpolation (Quilez's formulation) with a numerically stable quadratic.
 *
 * The patch is p(u,v) = q0 + u e + v f + u v g with e = q1 - q0, f = q3 - q0,
 * g = q0 - q1 + q2 - q3. Eliminating u (cross both sides of h - v f = u (e + v g) with
 * e + v g, h = p - q0) leaves k2 v^2 + k1 v + k0 = 0 with k2 = g x f, k1 = e x f + h x g,
 * k0 = h x e. Quilez switches to the linear root when |k2| < 0.001, an absolute threshold
 * that is wrong for small quads (k2 scales with the area) and for large ones. Here both roots
 * come from the cancellation-free pair q = -(k1 + sign(k1) sqrt(disc)) / 2, v = k0 / q and
 * v = q / k2: the first tends to the linear root -k0/k1 as k2 -> 0, the second then runs
 * off to infinity and is rejected by the range test, so no threshold is needed. u is the
 * least-squares solution of h - v f = u (e + v g), which needs no choice of axis. Points are
 * normalized first (core_util.h) so that the coefficients are of order one. */
#include <quadgl/quadgl.h>

#include "core_util.h"

/* Accept roots this far outside [0, 1] (parameters are dimensionless: scale-free). */
#define QGL__UV_TOL 1e-12

/* u for a given v; returns 0 when e + v g vanishes (the patch has no extent in u there). */
static int solve_u(const double d[5][2], double v, double *u)
{
    double e[2], f[2], g[2], h[2], a[2], b[2];
    for (int k = 0; k < 2; k++) {
        e[k] = d[1][k] - d[0][k];
        f[k] = d[3][k] - d[0][k];
        g[k] = d[0][k] - d[1][k] + d[2][k] - d[3][k];
        h[k] = d[4][k] - d[0][k];
        a[k] = h[k] - v * f[k];
        b[k] = e[k] + v * g[k];
    }
    double bb = b[0] * b[0] + b[1] * b[1];
    if (!(bb > 0))
        return 0;
    *u = (a[0] * b[0] + a[1] * b[1]) / bb;
    return isfinite(*u);
}

/* Distance of (u, v) from the unit square, in parameter units. */
static double outside_by(double u, double v)
{
    double du = u < 0 ? -u : (u > 1 ? u - 1 : 0), dv = v < 0 ? -v : (v > 1 ? v - 1 : 0);
    return fmax(du, dv);
}

/* The up to two roots in v of k2 v^2 + k1 v + k0 = 0 without cancellation. */
static int quadratic_roots(double k2, double k1, double k0, double r[2])
{
    double disc = k1 * k1 - 4 * k0 * k2;
    /* a double root computed a few ulps negative is still a root */
    if (disc < 0 && disc >= -8 * DBL_EPSILON * (k1 * k1 + 4 * fabs(k0 * k2)))
        disc = 0;
    if (disc < 0)
        return 0;
    double q = -0.5 * (k1 + copysign(sqrt(disc), k1));
    int n = 0;
    if (q != 0)
        r[n++] = k0 / q;
    if (k2 != 0)
        r[n++] = q / k2;
    if (n == 0 && k0 == 0 && k2 != 0)
        r[n++] = 0; /* k1 = k0 = 0: double root at 0 */
    return n;
}

QGL_API int qgl_inv_bilinear(const double q[4][2], double x, double y, double uv[2])
{
    double tmp[2];
    if (!uv)
        uv = tmp;
    uv[0] = uv[1] = 0;
    if (!qgl__all_finite(&q[0][0], 8) || !isfinite(x) || !isfinite(y))
        return QGL_NONFINITE;
    double pts[5][2] = {{q[0][0], q[0][1]}, {q[1][0], q[1][1]}, {q[2][0], q[2][1]}, {q[3][0], q[3][1]}, {x, y}};
    double d[5][2];
    qgl__normalize2((const double (*)[2])pts, 5, q[0], d);
    double e[2] = {d[1][0], d[1][1]}, f[2] = {d[3][0], d[3][1]}, h[2] = {d[4][0], d[4][1]};
    double g[2] = {-d[1][0] + d[2][0] - d[3][0], -d[1][1] + d[2][1] - d[3][1]};
    double k2 = qgl__cross2(g, f), k1 = qgl__cross2(e, f) + qgl__cross2(h, g), k0 = qgl__cross2(h, e);
    double roots[2], best = INFINITY;
    int n = quadratic_roots(k2, k1, k0, roots);
    for (int i = 0; i < n; i++) {
        double u;
        if (!isfinite(roots[i]) || !solve_u(d, roots[i], &u))
            continue;
        double out = outside_by(u, roots[i]);
        if (out < best) {
            best = out;
            uv[0] = u;
            uv[1] = roots[i];
        }
    }
    return best <= QGL__UV_TOL;
}
