/* Affinity tests: planarity, Oliveira's parallelogram test, Bloomenthal's corner barycentrics,
 * and the predicate "the diagonal split renders this quad exactly".
 *
 * A quad rendered as two triangles is exact when the map from the quad's plane to its
 * attributes is affine, so the predicates ask, each in its own way, whether four corners are
 * the affine image of one another. Planarity uses the distance between the two diagonals'
 * lines (zero iff the four corners are coplanar; twice the corners' distance from the mid
 * plane). Barycentric coordinates of a corner with respect to the other three are found by
 * least squares in any dimension (Gram matrix), so a 3D corner off the others' plane is
 * projected onto it; combine with planarity. Every tolerance is relative to the quad's own
 * extent, except Oliveira's, which the paper defines on unnormalized dot products. */
#include <quadgl/quadgl.h>

#include <stdlib.h>

#include "core_util.h"

static double dot_n(const double *a, const double *b, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

static void cross3(const double a[3], const double b[3], double r[3])
{
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

/* Largest |component| of the corner differences from corner 0 (0 for a point). */
static double extent(const double *p, int dim)
{
    double m = 0;
    for (int i = 1; i < 4; i++)
        for (int k = 0; k < dim; k++)
            m = qgl__max(m, fabs(p[i * dim + k] - p[k]));
    return m;
}

/* Corners as doubles in a small local buffer, relative to corner 0 and scaled to unit
 * extent so that the Gram determinant neither overflows nor underflows. */
static int normalized_corners(const double *src, int dim, double *dst)
{
    if (!qgl__all_finite(src, 4 * dim))
        return 0;
    double m = 0;
    for (int i = 0; i < 4 * dim; i++)
        m = qgl__max(m, fabs(src[i]));
    for (int i = 0; i < 4 * dim; i++)
        dst[i] = src[i];
    qgl__scale_pow2(dst, 4 * dim, qgl__exponent_of(m));
    for (int i = 3; i >= 0; i--) /* corner 0 last: the others subtract its scaled value */
        for (int k = 0; k < dim; k++)
            dst[i * dim + k] -= dst[k];
    qgl__scale_pow2(dst, 4 * dim, qgl__exponent_of(extent(dst, dim)));
    return 1;
}

/* Planarity of normalized corners (corner 0 at the origin, unit extent). */
static int planar_normalized(const double q[4][3], double rel_tol)
{
    double d02[3], d13[3], n[3];
    for (int k = 0; k < 3; k++) {
        d02[k] = q[2][k] - q[0][k];
        d13[k] = q[3][k] - q[1][k];
    }
    cross3(d02, d13, n);
    /* distance between the diagonals' lines = |n . (q1 - q0)| / |n| in units of the extent
     * (q0 = 0); parallel diagonals (n = 0) always span a plane. The additive term absorbs
     * the rounding of n and of the dot product. */
    double h = fabs(dot_n(n, q[1], 3));
    return h <= rel_tol * sqrt(dot_n(n, n, 3)) + 32 * DBL_EPSILON;
}

QGL_API int qgl_is_planar(const double p[4][3], double rel_tol)
{
    double q[4][3];
    return rel_tol >= 0 && normalized_corners(&p[0][0], 3, &q[0][0]) && planar_normalized((const double(*)[3])q, rel_tol);
}

QGL_API int qgl_is_parallelogram(const double *q, int dim, double tol)
{
    if (!q || dim < 1 || !qgl__all_finite(q, 4 * dim) || !(tol >= 0))
        return 0;
    const double *a = q, *b = q + dim, *c = q + 2 * dim, *d = q + 3 * dim;
    double v12 = 0, v34 = 0, v14 = 0, v23 = 0;
    for (int k = 0; k < dim; k++) {
        double v1 = a[k] - b[k], v2 = c[k] - b[k], v3 = c[k] - d[k], v4 = a[k] - d[k];
        v12 += v1 * v2;
        v34 += v3 * v4;
        v14 += v1 * v4;
        v23 += v2 * v3;
    }
    return fabs(v12 - v34) < tol && fabs(v14 - v23) < tol;
}

/* Barycentric coordinates of p with respect to (a, b, c) in dim dimensions, by projection
 * onto their plane. Returns 0 when the triangle is degenerate relative to its size. */
static int bary(const double *p, const double *a, const double *b, const double *c, int dim, double out[3])
{
    double e1[16], e2[16], h[16];
    for (int k = 0; k < dim; k++) {
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
        h[k] = p[k] - a[k];
    }
    double g11 = dot_n(e1, e1, dim), g12 = dot_n(e1, e2, dim), g22 = dot_n(e2, e2, dim);
    double r1 = dot_n(h, e1, dim), r2 = dot_n(h, e2, dim);
    double det = g11 * g22 - g12 * g12;
    if (!(det > 1e3 * DBL_EPSILON * g11 * g22) || !isfinite(det))
        return 0;
    double s = (r1 * g22 - r2 * g12) / det, t = (r2 * g11 - r1 * g12) / det;
    out[0] = 1 - s - t;
    out[1] = s;
    out[2] = t;
    return isfinite(s) && isfinite(t);
}

QGL_API int qgl_bloomenthal_affine(const double *geom, int dim_g, const double *attr, int dim_a, double tol)
{
    double g[64], a[64];
    if (!geom || !attr || dim_g < 1 || dim_g > 16 || dim_a < 1 || dim_a > 16 || !(tol >= 0))
        return 0;
    if (!normalized_corners(geom, dim_g, g) || !normalized_corners(attr, dim_a, a))
        return 0;
    for (int i = 0; i < 4; i++) {
        int i1 = (i + 1) & 3, i2 = (i + 2) & 3, i3 = (i + 3) & 3;
        double bg[3], ba[3];
        if (!bary(g + i * dim_g, g + i1 * dim_g, g + i2 * dim_g, g + i3 * dim_g, dim_g, bg) ||
            !bary(a + i * dim_a, a + i1 * dim_a, a + i2 * dim_a, a + i3 * dim_a, dim_a, ba))
            return 0;
        double dx = bg[0] - ba[0], dy = bg[1] - ba[1], dz = bg[2] - ba[2];
        if (!(sqrt(dx * dx + dy * dy + dz * dz) <= tol))
            return 0;
    }
    return 1;
}

/* The corner whose opposite triangle is best conditioned (largest area). */
static int best_corner(const double p[4][3])
{
    int best = 0;
    double best_area = -1;
    for (int i = 0; i < 4; i++) {
        const double *a = p[(i + 1) & 3], *b = p[(i + 2) & 3], *c = p[(i + 3) & 3];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]}, n[3];
        cross3(u, w, n);
        double area = dot_n(n, n, 3);
        if (area > best_area) {
            best_area = area;
            best = i;
        }
    }
    return best;
}

/* Attribute component k of corner i predicted from the other three by barycentrics b:
 * within rel_tol of the component's range over the quad (plus rounding). */
static int attr_affine(const double *attr, int nattr, int i, const double b[3], double rel_tol)
{
    int i1 = (i + 1) & 3, i2 = (i + 2) & 3, i3 = (i + 3) & 3;
    double bsum = fabs(b[0]) + fabs(b[1]) + fabs(b[2]);
    for (int k = 0; k < nattr; k++) {
        double a0 = attr[i * nattr + k], a1 = attr[i1 * nattr + k], a2 = attr[i2 * nattr + k],
               a3 = attr[i3 * nattr + k];
        if (!qgl__value_affine(a0, a1, a2, a3, b[0] * a1 + b[1] * a2 + b[2] * a3, bsum, rel_tol))
            return 0;
    }
    return 1;
}

int qgl__affine_dependency(const double p[4][3], double n[4])
{
    double d1[3], d2[3], r[3], c[3], a[3], b[3];
    for (int k = 0; k < 3; k++)
        d1[k] = p[2][k] - p[0][k], d2[k] = p[3][k] - p[1][k], r[k] = p[1][k] - p[0][k];
    double e2 = dot_n(d1, d1, 3) + dot_n(d2, d2, 3);
    if (!(e2 > 1e-140 && e2 < 1e140)) { /* c . c below is of the fourth power: scale to 1 */
        double e = fabs(d1[0]);
        for (int k = 0; k < 3; k++)
            e = qgl__max(e, qgl__max(qgl__max(fabs(d1[k]), fabs(d2[k])), fabs(r[k])));
        if (!(e > 0 && e < INFINITY))
            return 0;
        for (int k = 0; k < 3; k++)
            d1[k] /= e, d2[k] /= e, r[k] /= e;
    }
    cross3(d1, d2, c);
    double cc = dot_n(c, c, 3);
    if (qgl__parallelogram(d1, d2, r) && cc > 0 && cc < INFINITY) { /* the diagonals halve each other */
        n[0] = n[2] = 0.5, n[1] = n[3] = -0.5;
        return 1;
    }
    cross3(r, d2, a);
    cross3(r, d1, b);
    /* t d1 - u d2 = r: crossed with d2 and d1, t c = r x d2 and u c = r x d1 */
    double tc = dot_n(a, c, 3), uc = dot_n(b, c, 3);
    if (!(cc > 0 && cc < INFINITY && tc > 0.01 * cc && tc < 0.99 * cc && uc > 0.01 * cc && uc < 0.99 * cc))
        return 0; /* also NaN: every comparison fails */
    double t = tc / cc, u = uc / cc;
    n[0] = 1 - t, n[1] = u - 1, n[2] = t, n[3] = -u;
    return 1;
}

/* The planner's per-quad call: hidden, so the library calls it directly. */
QGL_API int qgl_affine_dependency(const double p[4][3], double n[4])
{
    return qgl__affine_dependency(p, n);
}

QGL_API int qgl_split_is_exact(const double p[4][3], const double *attr, int nattr, double rel_tol)
{
    if (nattr < 0 || (nattr > 0 && !attr) || !(rel_tol >= 0) || !qgl__all_finite(&p[0][0], 12))
        return 0;
    if (nattr > 0 && !qgl__all_finite(attr, 4 * nattr))
        return 0;
    double g[12];
    normalized_corners(&p[0][0], 3, g);
    const double (*q)[3] = (const double (*)[3])g;
    if (!planar_normalized(q, rel_tol))
        return 0;
    int i = best_corner(q);
    double b[3];
    if (!bary(q[i], q[(i + 1) & 3], q[(i + 2) & 3], q[(i + 3) & 3], 3, b))
        return 0; /* no triangle with area: the quad has no interior */
    return attr_affine(attr, nattr, i, b, rel_tol);
}
