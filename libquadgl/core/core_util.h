/* Private helpers of the numeric core: finiteness checks and scale-free normalization.
 *
 * Geometric predicates must not depend on where a quad sits or how big it is. Before any
 * orientation is computed, points are translated to a local origin and scaled by powers of
 * two (ldexp, exact) so that the largest coordinate is of order one: then a fixed threshold
 * such as 64 eps is a tolerance relative to the quad's size, products cannot overflow or
 * underflow, and signs are exactly those of the original configuration up to the rounding of
 * the one translation. */
#ifndef QGL_CORE_UTIL_H
#define QGL_CORE_UTIL_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

/* Orientations of normalized points at or below this are treated as zero (collinear). */
#define QGL__COLLINEAR_EPS (64.0 * DBL_EPSILON)

/* qgl_affine_dependency, hidden: the GL layer's planner (gl/draw.c) calls it per quad. */
int qgl__affine_dependency(const double p[4][3], double n[4]);

/* Whether corners given by their diagonals d02 = p2 - p0, d13 = p3 - p1 and the edge
 * d01 = p1 - p0 form a parallelogram (p0 + p2 = p1 + p3, that is d13 = d02 - 2 d01) as these
 * differences round, so relative to the quad's size: the quads of grids, glyphs and boxes.
 * False for NaN; callers check what they derive for finiteness and an area. */
static inline int qgl__parallelogram(const double d02[3], const double d13[3], const double d01[3])
{
    return d13[0] == d02[0] - 2 * d01[0] && d13[1] == d02[1] - 2 * d01[1] && d13[2] == d02[2] - 2 * d01[2];
}

/* max and min of finite values (fmax and fmin are library calls here: they must order NaNs) */
static inline double qgl__max(double a, double b)
{
    return a > b ? a : b;
}

static inline double qgl__min(double a, double b)
{
    return a < b ? a : b;
}

/* Whether one corner's value a0 agrees with its prediction pred from the other three (a1,
 * a2, a3, by barycentrics whose magnitudes sum to bsum): within rel_tol of the four values'
 * range, plus the rounding of the prediction. The affinity tests' one rule: the core's
 * qgl_split_is_exact and the GL planner's parallelogram shortcut. */
static inline int qgl__value_affine(double a0, double a1, double a2, double a3, double pred, double bsum,
                                    double rel_tol)
{
    double lo = qgl__min(qgl__min(a0, a1), qgl__min(a2, a3)), hi = qgl__max(qgl__max(a0, a1), qgl__max(a2, a3));
    double mag = qgl__max(fabs(lo), fabs(hi));
    return fabs(pred - a0) <= rel_tol * (hi - lo) + 16 * DBL_EPSILON * (1 + bsum) * mag;
}

static inline int qgl__all_finite(const double *a, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(a[i]))
            return 0;
    return 1;
}

/* Exponent e such that ldexp(x, -e) lies in [0.5, 1) for the largest |x|; 0 for all zero. */
static inline int qgl__exponent_of(double maxabs)
{
    int e = 0;
    if (maxabs > 0)
        frexp(maxabs, &e);
    return e;
}

/* 2^k, from its bits where it is a normal double (ldexp is a library call, which the planner
 * would make several times a quad). */
static inline double qgl__pow2(int k)
{
    if (k < -1022 || k > 1023)
        return ldexp(1.0, k);
    uint64_t bits = (uint64_t)(k + 1023) << 52;
    double d;
    memcpy(&d, &bits, sizeof d);
    return d;
}

/* a[i] *= 2^-e for n values, exactly as ldexp(a[i], -e) but by one multiplication (a library
 * call per value costs more than the predicates it serves) wherever 2^-e is a normal double. */
static inline void qgl__scale_pow2(double *a, int n, int e)
{
    if (e > -1000 && e < 1000) {
        double s = qgl__pow2(-e);
        for (int i = 0; i < n; i++)
            a[i] *= s;
    } else {
        for (int i = 0; i < n; i++)
            a[i] = ldexp(a[i], -e);
    }
}

/* d[i] = (v[i] - origin), scaled exactly by a power of two so max |d| is in [0.5, 1).
 * The first scaling makes the subtraction overflow-free; the second restores precision
 * when the points are tiny next to their distance from zero. Inputs must be finite. */
static inline void qgl__normalize2(const double (*v)[2], int n, const double origin[2], double (*d)[2])
{
    double m = qgl__max(fabs(origin[0]), fabs(origin[1]));
    for (int i = 0; i < n; i++)
        m = qgl__max(m, qgl__max(fabs(v[i][0]), fabs(v[i][1])));
    int e1 = qgl__exponent_of(m);
    double o[2] = {origin[0], origin[1]};
    qgl__scale_pow2(o, 2, e1);
    double m2 = 0;
    for (int i = 0; i < n; i++) {
        d[i][0] = v[i][0], d[i][1] = v[i][1];
        qgl__scale_pow2(d[i], 2, e1);
        d[i][0] -= o[0], d[i][1] -= o[1];
        m2 = qgl__max(m2, qgl__max(fabs(d[i][0]), fabs(d[i][1])));
    }
    int e2 = qgl__exponent_of(m2);
    for (int i = 0; i < n; i++)
        qgl__scale_pow2(d[i], 2, e2);
}

static inline double qgl__cross2(const double a[2], const double b[2])
{
    return a[0] * b[1] - a[1] * b[0];
}

/* Twice the signed area of (a, b, c): positive when counter-clockwise. */
static inline double qgl__orient2(const double a[2], const double b[2], const double c[2])
{
    double u[2] = {b[0] - a[0], b[1] - a[1]}, w[2] = {c[0] - a[0], c[1] - a[1]};
    return qgl__cross2(u, w);
}

static inline int qgl__sign_tol(double x, double tol)
{
    return x > tol ? 1 : (x < -tol ? -1 : 0);
}

#endif
