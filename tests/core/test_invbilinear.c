/* Tests of qgl_inv_bilinear: round trips through the forward bilinear map, at every scale.
 *
 * (u, v) drawn in [0,1]^2 are mapped forward by the bilinear formula, then inverted; the
 * result must return 1 and match (u, v). Quilez's published method (absolute 0.001 switch to
 * the linear root) is written out here as the comparison and measured on the same points;
 * on small trapezoids it must be visibly wrong while ours is not. */
#include <quadgl/quadgl.h>

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"

static double urand(void)
{
    return rand() / (RAND_MAX + 1.0);
}

static void forward(const double q[4][2], double u, double v, double p[2])
{
    for (int k = 0; k < 2; k++)
        p[k] = (1 - u) * (1 - v) * q[0][k] + u * (1 - v) * q[1][k] + u * v * q[2][k] + (1 - u) * v * q[3][k];
}

static double cross(const double a[2], const double b[2])
{
    return a[0] * b[1] - a[1] * b[0];
}

/* Quilez 2010, as published: linear root when |k2| < 0.001, textbook quadratic otherwise. */
static void quilez(const double q[4][2], const double p[2], double uv[2])
{
    double e[2], f[2], g[2], h[2];
    for (int k = 0; k < 2; k++) {
        e[k] = q[1][k] - q[0][k];
        f[k] = q[3][k] - q[0][k];
        g[k] = q[0][k] - q[1][k] + q[2][k] - q[3][k];
        h[k] = p[k] - q[0][k];
    }
    double k2 = cross(g, f), k1 = cross(e, f) + cross(h, g), k0 = cross(h, e);
    if (fabs(k2) < 0.001) {
        uv[1] = -k0 / k1;
        uv[0] = (h[0] - f[0] * uv[1]) / (e[0] + g[0] * uv[1]);
        return;
    }
    double w = k1 * k1 - 4 * k0 * k2;
    if (w < 0) {
        uv[0] = uv[1] = -1;
        return;
    }
    w = sqrt(w);
    double ik2 = 0.5 / k2, v = (-k1 - w) * ik2, u = (h[0] - f[0] * v) / (e[0] + g[0] * v);
    if (u < 0 || u > 1 || v < 0 || v > 1) {
        v = (-k1 + w) * ik2;
        u = (h[0] - f[0] * v) / (e[0] + g[0] * v);
    }
    uv[0] = u;
    uv[1] = v;
}

/* A random convex quad: the unit square with corners moved by up to `jitter`, scaled, moved. */
static void random_quad(double jitter, double scale, double off, double q[4][2])
{
    const double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 2; k++)
            q[i][k] = off + scale * (sq[i][k] + jitter * (urand() - 0.5));
}

/* Max |uv error| of ours and of Quilez's over n random round trips. */
static void round_trips(const double q[4][2], int n, double *ours, double *theirs)
{
    *ours = *theirs = 0;
    for (int it = 0; it < n; it++) {
        double u = urand(), v = urand(), p[2], uv[2], uq[2];
        forward(q, u, v, p);
        int r = qgl_inv_bilinear(q, p[0], p[1], uv);
        double err = fmax(fabs(uv[0] - u), fabs(uv[1] - v));
        *ours = fmax(*ours, r == 1 ? err : INFINITY);
        quilez(q, p, uq);
        double eq = fmax(fabs(uq[0] - u), fabs(uq[1] - v));
        *theirs = fmax(*theirs, isnan(eq) ? INFINITY : eq);
    }
}

static void check_scales(void)
{
    const double scales[][2] = {{1e-6, 0}, {1e-6, 1e3}, {1e-2, 0}, {1, 0}, {1, -1e4}, {1e4, 0}, {1e6, 1e7}};
    printf("%-10s %-8s %-14s %-14s\n", "size", "offset", "ours max err", "Quilez max err");
    for (size_t s = 0; s < sizeof scales / sizeof scales[0]; s++) {
        double worst = 0, worst_q = 0;
        for (int it = 0; it < 200; it++) {
            double q[4][2], ours, theirs;
            random_quad(0.6, scales[s][0], scales[s][1], q);
            round_trips(q, 50, &ours, &theirs);
            worst = fmax(worst, ours);
            worst_q = fmax(worst_q, theirs);
        }
        /* parameters lose the offset's relative precision: ulp(offset)/size */
        double tol = 1e-9 + 1e2 * DBL_EPSILON * fabs(scales[s][1]) / scales[s][0];
        printf("%-10g %-8g %-14.3g %-14.3g\n", scales[s][0], scales[s][1], worst, worst_q);
        CHECK(worst < tol, "size %g offset %g: round-trip error %g", scales[s][0], scales[s][1], worst);
    }
}

/* A trapezoid 1e-2 wide: k2 ~ 1e-5 < 0.001, so Quilez takes the linear root and is wrong. */
static void check_quilez_threshold_case(void)
{
    const double q[4][2] = {{0, 0}, {0.01, 0}, {0.0075, 0.005}, {0.0025, 0.005}};
    double ours, theirs;
    round_trips(q, 1000, &ours, &theirs);
    printf("small trapezoid: ours %.3g, Quilez %.3g\n", ours, theirs);
    CHECK(ours < 1e-12, "small trapezoid: our error %g", ours);
    CHECK(theirs > 1e-3, "small trapezoid: Quilez's threshold did not fail (%g): test premise wrong", theirs);
}

static void check_special(void)
{
    const double sq[4][2] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
    const double para[4][2] = {{0, 0}, {2, 1}, {3, 3}, {1, 2}}; /* k2 = 0 exactly */
    double uv[2];
    CHECK(qgl_inv_bilinear(sq, 1, 1, uv) == 1 && uv[0] == 0.5 && uv[1] == 0.5, "square centre");
    CHECK(qgl_inv_bilinear(para, 1.5, 1.5, uv) == 1 && fabs(uv[0] - 0.5) < 1e-15 && fabs(uv[1] - 0.5) < 1e-15,
          "parallelogram centre (%g, %g)", uv[0], uv[1]);
    const double corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const double trap[4][2] = {{0, 0}, {4, 0}, {3, 1}, {1, 1}};
    for (int i = 0; i < 4; i++) {
        CHECK(qgl_inv_bilinear(trap, trap[i][0], trap[i][1], uv) == 1 && fabs(uv[0] - corners[i][0]) < 1e-14 &&
                  fabs(uv[1] - corners[i][1]) < 1e-14,
              "trapezoid corner %d -> (%g, %g)", i, uv[0], uv[1]);
    }
    CHECK(qgl_inv_bilinear(trap, 2, 0, uv) == 1 && fabs(uv[0] - 0.5) < 1e-14 && fabs(uv[1]) < 1e-14, "edge point");
    CHECK(qgl_inv_bilinear(trap, 2, -0.5, uv) == 0 && isfinite(uv[0]) && isfinite(uv[1]), "point below");
    CHECK(qgl_inv_bilinear(trap, 0.2, 0.9, uv) == 0 && isfinite(uv[0]) && isfinite(uv[1]), "point left of edge 3-0");
    CHECK(qgl_inv_bilinear(trap, NAN, 0, uv) == QGL_NONFINITE && uv[0] == 0 && uv[1] == 0, "NaN point");
    const double bad[4][2] = {{0, 0}, {INFINITY, 0}, {1, 1}, {0, 1}};
    CHECK(qgl_inv_bilinear(bad, 0.5, 0.5, uv) == QGL_NONFINITE, "infinite corner");
    const double dot[4][2] = {{3, 3}, {3, 3}, {3, 3}, {3, 3}};
    int r = qgl_inv_bilinear(dot, 3, 3, uv);
    CHECK(r >= 0 && isfinite(uv[0]) && isfinite(uv[1]), "point quad: %d", r);
    CHECK(qgl_inv_bilinear(sq, 1, 1, NULL) == 1, "NULL uv accepted");
}

int main(void)
{
    srand(4242);
    check_scales();
    check_quilez_threshold_case();
    check_special();
    printf("%d failures\n", failures);
    return failures ? 1 : 0;
}
