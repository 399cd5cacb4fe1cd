/* Screen-quad classification, its exact cover by triangles, and the membership test of eq. 12.
 *
 * Everything is decided by the signs of corner turns c_i = orient(v_{i-1}, v_i, v_{i+1}).
 * The four c_i are the orientations of the four corner triples of the quad, and
 * c_1 + c_3 = c_0 + c_2 (both are twice the signed area). Four equal signs: convex. One odd
 * sign: that corner is reflex, and the diagonal from it lies inside. Two and two, adjacent:
 * a bow-tie whose two crossing edges are the ones joining opposite signs (an alternating
 * pattern is impossible, by the identity). A zero turn means three collinear corners; the
 * collinear path is then homotopic to the straight edge that skips it (for every point off
 * that line), so the region is the triangle of the other three corners, whatever the order
 * of the collinear points (straight corner, spike, touching bow-tie, collapsed edge). More
 * zeros leave no interior. Points are normalized first (core_util.h), so "zero" means below
 * a fixed fraction of the quad's own size. */
#include <quadgl/quadgl.h>

#include "core_util.h"

/* Turns at the four corners, on normalized coordinates. */
static void corner_turns(const double d[4][2], double c[4])
{
    for (int i = 0; i < 4; i++)
        c[i] = qgl__orient2(d[(i + 3) & 3], d[i], d[(i + 1) & 3]);
}

static void set_tri(qgl_cover *out, int k, int a, int b, int c)
{
    out->tri[k][0] = (unsigned char)a;
    out->tri[k][1] = (unsigned char)b;
    out->tri[k][2] = (unsigned char)c;
}

static void cover_reset(qgl_cover *out, qgl_quad_kind kind)
{
    out->kind = kind;
    out->orientation = 0;
    out->reflex = -1;
    out->cross_edge = -1;
    out->cross[0] = out->cross[1] = 0;
    out->cross_t = 0;
    out->ntri = 0;
    for (int k = 0; k < 2; k++)
        set_tri(out, k, 0, 0, 0);
}

/* The triangle left when corner i is skipped, in the quad's cyclic order. */
static void cover_skip(qgl_cover *out, int i, int orientation)
{
    out->kind = QGL_QUAD_CONVEX;
    out->orientation = orientation;
    out->ntri = 1;
    set_tri(out, 0, (i + 1) & 3, (i + 2) & 3, (i + 3) & 3);
}

/* a + t (b - a), or the convex combination when the difference overflows. */
static double lerp_safe(double a, double b, double t)
{
    double r = a + t * (b - a);
    return isfinite(r) ? r : (1 - t) * a + t * b;
}

/* Bow-tie: edges (e, e+1) and (e+2, e+3) cross. The crossing parameter along the first
 * is the ratio of the two turns that change sign across it, both of one sign: no
 * cancellation. Lobes are (X, e+1, e+2) and (X, e+3, e), X = vertex 4. */
static void cover_bowtie(const double v[4][2], const double c[4], int e, qgl_cover *out)
{
    double ca = e == 0 ? c[3] : c[0], cb = e == 0 ? c[2] : c[3];
    double t = ca / (ca - cb);
    int a = e, b = e + 1;
    out->kind = QGL_QUAD_BOWTIE;
    out->cross_edge = e;
    out->cross_t = t;
    for (int k = 0; k < 2; k++) {
        double x = t <= 0.5 ? lerp_safe(v[a][k], v[b][k], t) : lerp_safe(v[b][k], v[a][k], 1 - t);
        out->cross[k] = fmax(-DBL_MAX, fmin(DBL_MAX, x));
    }
    out->ntri = 2;
    set_tri(out, 0, 4, e + 1, e + 2);
    set_tri(out, 1, 4, (e + 3) & 3, e);
}

/* Exactly one zero turn, or two adjacent ones (a collapsed edge): one triangle. */
static int classify_zeros(const int s[4], int nzero, qgl_cover *out)
{
    int z = 0;
    if (nzero == 1) {
        while (s[z] != 0)
            z++;
        cover_skip(out, z, s[(z + 2) & 3]);
        return out->kind;
    }
    while (z < 4 && !(s[z] == 0 && s[(z + 1) & 3] == 0))
        z++;
    /* the two other turns are equal by the identity; the triangles skipping z or z+1 coincide */
    if (z == 4 || s[(z + 2) & 3] != s[(z + 3) & 3]) {
        cover_reset(out, QGL_QUAD_DEGENERATE);
        return out->kind;
    }
    cover_skip(out, z, s[(z + 2) & 3]);
    return out->kind;
}

static int classify_signs(const double v[4][2], const double c[4], const int s[4], qgl_cover *out)
{
    int npos = 0;
    for (int i = 0; i < 4; i++)
        npos += s[i] > 0;
    if (npos == 4 || npos == 0) {
        out->kind = QGL_QUAD_CONVEX;
        out->orientation = npos ? 1 : -1;
        out->ntri = 2;
        set_tri(out, 0, 0, 1, 2);
        set_tri(out, 1, 0, 2, 3);
    } else if (npos == 3 || npos == 1) {
        int odd = npos == 3 ? -1 : 1, r = 0;
        while (s[r] != odd)
            r++;
        out->kind = QGL_QUAD_CONCAVE;
        out->orientation = -odd;
        out->reflex = r;
        out->ntri = 2;
        set_tri(out, 0, r, (r + 1) & 3, (r + 2) & 3);
        set_tri(out, 1, r, (r + 2) & 3, (r + 3) & 3);
    } else if (s[1] == s[2]) {
        cover_bowtie(v, c, 0, out);
    } else if (s[0] == s[1]) {
        cover_bowtie(v, c, 1, out);
    } else {
        cover_reset(out, QGL_QUAD_DEGENERATE); /* alternating: only rounding gets here */
    }
    return out->kind;
}

QGL_API int qgl_classify(const double v[4][2], qgl_cover *out)
{
    qgl_cover dummy;
    if (!out)
        out = &dummy;
    cover_reset(out, QGL_QUAD_DEGENERATE);
    if (!qgl__all_finite(&v[0][0], 8))
        return QGL_NONFINITE;
    double d[4][2], c[4];
    int s[4], nzero = 0;
    qgl__normalize2(v, 4, v[0], d);
    corner_turns(d, c);
    for (int i = 0; i < 4; i++) {
        s[i] = qgl__sign_tol(c[i], QGL__COLLINEAR_EPS);
        nzero += s[i] == 0;
    }
    if (nzero >= 3)
        return out->kind;
    if (nzero > 0)
        return classify_zeros(s, nzero, out);
    return classify_signs(v, c, s, out);
}

/* Projected corners; when some x/w would overflow, every corner is scaled by the same power
 * of two first (the shape, hence the classification, is scale invariant). Returns that
 * exponent. */
static int project_scaled(const double clip[4][4], double v[4][2])
{
    int k = 0;
    for (int i = 0; i < 4; i++) {
        double m = fmax(fabs(clip[i][0]), fabs(clip[i][1]));
        if (m > 0)
            k = k > ilogb(m) - ilogb(clip[i][3]) ? k : ilogb(m) - ilogb(clip[i][3]);
    }
    k = k > 1000 ? k - 1000 : 0;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 2; j++)
            v[i][j] = ldexp(clip[i][j], -k) / clip[i][3];
    return k;
}

QGL_API int qgl_classify_clip(const double clip[4][4], qgl_cover *out)
{
    qgl_cover dummy;
    if (!out)
        out = &dummy;
    cover_reset(out, QGL_QUAD_DEGENERATE);
    if (!qgl__all_finite(&clip[0][0], 16))
        return QGL_NONFINITE;
    int npos = 0, nneg = 0;
    for (int i = 0; i < 4; i++) {
        npos += clip[i][3] > 0;
        nneg += clip[i][3] < 0;
    }
    if (npos + nneg == 0)
        return out->kind;
    if (npos != 4 && nneg != 4) {
        out->kind = QGL_QUAD_EXTERNAL;
        return out->kind;
    }
    double v[4][2];
    int k = project_scaled(clip, v);
    int kind = qgl_classify(v, out);
    for (int j = 0; j < 2 && k; j++)
        out->cross[j] = fmax(-DBL_MAX, fmin(DBL_MAX, ldexp(out->cross[j], k)));
    return kind;
}

/* Eq. 12: inside and front-facing iff
 *   E20 & E01 & E12 & (E23 | E30)   or   !E20 & E23 & E30 & (E01 | E12),
 * back-facing iff the same holds with every edge function negated. An edge function counts
 * as true when >= 0 (so edges belong to the quad); the diagonal's two branches overlap on it. */
static int eq12(const double e[5], double sgn)
{
    double e01 = sgn * e[0], e12 = sgn * e[1], e23 = sgn * e[2], e30 = sgn * e[3], e20 = sgn * e[4];
    return (e20 >= 0 && e01 >= 0 && e12 >= 0 && (e23 >= 0 || e30 >= 0)) ||
           (e20 <= 0 && e23 >= 0 && e30 >= 0 && (e01 >= 0 || e12 >= 0));
}

/* A collinear quad with the point on its line: the edges' union is the span of the corners. */
static int on_degenerate_outline(const double d[4][2])
{
    double lo[2] = {d[0][0], d[0][1]}, hi[2] = {d[0][0], d[0][1]};
    for (int i = 1; i < 4; i++)
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], d[i][k]);
            hi[k] = fmax(hi[k], d[i][k]);
        }
    return lo[0] <= 0 && hi[0] >= 0 && lo[1] <= 0 && hi[1] >= 0;
}

QGL_API int qgl_inside(const double v[4][2], double x, double y)
{
    double p[2] = {x, y}, d[4][2], e[5];
    if (!qgl__all_finite(&v[0][0], 8) || !isfinite(x) || !isfinite(y))
        return 0;
    qgl__normalize2(v, 4, p, d);
    for (int i = 0; i < 4; i++)
        e[i] = qgl__cross2(d[i], d[(i + 1) & 3]);
    e[4] = qgl__cross2(d[2], d[0]);
    if (e[0] == 0 && e[1] == 0 && e[2] == 0 && e[3] == 0 && e[4] == 0)
        return on_degenerate_outline(d);
    if (eq12(e, 1))
        return 1;
    return eq12(e, -1) ? -1 : 0;
}
