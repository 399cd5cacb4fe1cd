/* weights_impl.h: the weight computation, written once and instantiated for double and float.
 *
 * weights.c includes this file twice with R (the real type), FN(name) (the suffixed function
 * name), EPS (the type's unit roundoff), SQRT, FABS, FREXP, LDEXP, RMIN (the type's smallest
 * normal number), ISFINITE and SPLITTER (Veltkamp's constant 2^ceil(p/2) + 1). See weights.c
 * for the algorithm and its limits. */

#include "pow2_impl.h"

/* x - p * w rounded once: the product is made exact with Dekker's two-product, so a point
 * close to a corner keeps all its relative precision in s~ = x - p w (plain arithmetic
 * would lose everything when the coordinates are large and the quad is small). */
static R FN(sub_prod)(R x, R p, R w)
{
    R prod = p * w;
    R a = SPLITTER * p, b = SPLITTER * w;
    R ph = a - (a - p), pl = p - ph;
    R wh = b - (b - w), wl = w - wh;
    R err = ((ph * wh - prod) + ph * wl + pl * wh) + pl * wl;
    if (!ISFINITE(err))
        return x - prod;
    return (x - prod) - err;
}

static void FN(fill)(R out[4], R value)
{
    if (out)
        for (int i = 0; i < 4; i++)
            out[i] = value;
}

/* Rescale the clip corners' x, y, w by one power of two (exact) so that the largest is in
 * [0.5, 1): the weights do not change, and no intermediate overflows or underflows. */
static int FN(normalize)(const R clip[4][4], R h[4][3])
{
    R m = 0;
    for (int i = 0; i < 4; i++) {
        h[i][0] = clip[i][0];
        h[i][1] = clip[i][1];
        h[i][2] = clip[i][3];
        for (int k = 0; k < 3; k++)
            m = FABS(h[i][k]) > m ? FABS(h[i][k]) : m;
    }
    if (m == 0)
        return 0;
    int e;
    FREXP(m, &e);
    FN(scale_pow2)(&h[0][0], 12, e);
    return 1;
}

/* Twice the signed area of the projected triangle (a, b, c), from homogeneous corners with
 * w > 0, translated to a so that it does not cancel for small quads far from the origin. */
static R FN(area_h)(const R a[3], const R b[3], const R c[3], R *scale)
{
    R ax = a[0] / a[2], ay = a[1] / a[2];
    R bx = b[0] / b[2] - ax, by = b[1] / b[2] - ay;
    R cx = c[0] / c[2] - ax, cy = c[1] / c[2] - ay;
    R lb = bx * bx + by * by, lc = cx * cx + cy * cy;
    *scale = lb > lc ? lb : lc;
    return bx * cy - by * cx;
}

/* The quad has no interior on screen: every corner on one line (or every w zero). With w of
 * one sign the test is on the projected corners, relative to their spread; with mixed signs
 * on the homogeneous determinants, relative to Hadamard's bound. */
static int FN(degenerate)(R h[4][3])
{
    int pos = 0, neg = 0;
    for (int i = 0; i < 4; i++) {
        pos += h[i][2] > 0;
        neg += h[i][2] < 0;
    }
    R worst = 0;
    if (pos == 4 || neg == 4) {
        for (int i = 0; i < 4; i++) {
            R scale;
            R a = FN(area_h)(h[i], h[(i + 1) & 3], h[(i + 2) & 3], &scale);
            if (scale > 0 && FABS(a) > 64 * EPS * scale)
                return 0;
        }
        return 1;
    }
    for (int i = 0; i < 4; i++) {
        const R *a = h[i], *b = h[(i + 1) & 3], *c = h[(i + 2) & 3];
        R det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                a[2] * (b[0] * c[1] - b[1] * c[0]);
        R bound = SQRT((a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]) *
                       (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]));
        R rel = bound > 0 ? FABS(det) / bound : 0;
        worst = rel > worst ? rel : worst;
    }
    return worst <= 64 * EPS;
}

/* Weights for a point on one or more corners: equal shares of the coincident corners
 * (one corner: the Lagrange property). */
static void FN(on_vertices)(const int hit[4], R persp[4], R screen[4])
{
    int n = hit[0] + hit[1] + hit[2] + hit[3];
    for (int i = 0; i < 4; i++) {
        persp[i] = hit[i] ? (R)1 / n : 0;
        if (screen)
            screen[i] = persp[i];
    }
}

/* Weights for a point on one or more edge segments (two: the crossing point of a bow-tie):
 * the linear interpolation along each edge, averaged. In homogeneous form the perspective
 * weights along edge i are rho_{i+1} : rho_i and the screen weights w_i rho_{i+1} : w_{i+1} rho_i. */
static void FN(on_edges)(const int hit[4], const R rho[4], const R w[4], R persp[4], R screen[4])
{
    int n = hit[0] + hit[1] + hit[2] + hit[3];
    FN(fill)(persp, 0);
    FN(fill)(screen, 0);
    for (int i = 0; i < 4; i++) {
        if (!hit[i])
            continue;
        int j = (i + 1) & 3;
        R sum = rho[i] + rho[j];
        persp[i] += rho[j] / sum / n;
        persp[j] += rho[i] / sum / n;
        if (screen) {
            R a = w[i] * rho[j], b = w[j] * rho[i];
            R den = a + b;
            if (den != 0 && ISFINITE(a / den)) {
                screen[i] += a / den / n;
                screen[j] += b / den / n;
            } else {
                screen[i] += rho[j] / sum / n;
                screen[j] += rho[i] / sum / n;
            }
        }
    }
}

/* Normalize nu into persp and w * nu into screen. The sums cannot vanish inside the quad; an
 * outside point may have sum(nu) ~ 0, and then the magnitudes normalize instead (finite). */
static void FN(normalize_weights)(const R nu[4], const R w[4], R persp[4], R screen[4])
{
    R sum = 0, mag = 0, wsum = 0;
    for (int i = 0; i < 4; i++) {
        sum += nu[i];
        mag += FABS(nu[i]);
        wsum += w[i] * nu[i];
    }
    if (mag == 0) { /* every angle zero: p on the line of a degenerate quad, off its outline */
        FN(fill)(persp, (R)0.25);
        FN(fill)(screen, (R)0.25);
        return;
    }
    R den = FABS(sum) > 4 * EPS * mag ? sum : mag;
    for (int i = 0; i < 4; i++)
        persp[i] = nu[i] / den;
    if (!screen)
        return;
    int ok = FABS(wsum) > 0;
    for (int i = 0; ok && i < 4; i++) {
        screen[i] = w[i] * nu[i] / wsum;
        ok = ISFINITE(screen[i]);
    }
    if (!ok)
        for (int i = 0; i < 4; i++)
            screen[i] = persp[i];
}

static int FN(weights)(const R clip[4][4], R px, R py, R persp[4], R screen[4])
{
    R h[4][3], s[4][2], rho[4], w[4], t[4], nu[4];
    int finite = ISFINITE(px) && ISFINITE(py);
    for (int i = 0; i < 16; i++)
        finite = finite && ISFINITE(clip[i / 4][i % 4]);
    FN(fill)(persp, (R)0.25);
    FN(fill)(screen, (R)0.25);
    if (!finite)
        return QGL_NONFINITE;
    if (!FN(normalize)(clip, h))
        return QGL_DEGENERATE;
    int degenerate = FN(degenerate)(h);

    R rsum = 0;
    for (int i = 0; i < 4; i++) {
        w[i] = h[i][2];
        s[i][0] = FN(sub_prod)(h[i][0], px, w[i]);
        s[i][1] = FN(sub_prod)(h[i][1], py, w[i]);
    }
    /* One more power-of-two scale of the s~ (weights are invariant to it) keeps the squares
     * in range whatever the point's distance. */
    R smax = 0;
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 2; k++)
            smax = FABS(s[i][k]) > smax ? FABS(s[i][k]) : smax;
    if (smax == 0)
        return QGL_DEGENERATE;
    int e;
    FREXP(smax, &e);
    FN(scale_pow2)(&s[0][0], 8, e);
    for (int i = 0; i < 4; i++) {
        rho[i] = SQRT(s[i][0] * s[i][0] + s[i][1] * s[i][1]);
        rsum += rho[i];
    }

    /* rho is accurate to roundoff (s~ comes from an exact product), so only a corner that
     * p really sits on needs the limit: the threshold just keeps t / rho finite. A larger
     * one would snap points near a collapsed edge (a pole), where the weights of the two
     * coincident corners depend on the direction of approach. */
    int hit[4], nhit = 0;
    for (int i = 0; i < 4; i++)
        nhit += hit[i] = rho[i] <= EPS * EPS * rsum;
    if (nhit) {
        FN(on_vertices)(hit, persp, screen);
        return degenerate ? QGL_DEGENERATE : QGL_INSIDE;
    }

    for (int i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        R a = s[i][0] * s[j][1] - s[i][1] * s[j][0];
        R d = s[i][0] * s[j][0] + s[i][1] * s[j][1];
        R p = rho[i] * rho[j];
        /* tan(alpha/2) in the form whose denominator does not cancel. */
        hit[i] = d < 0 && FABS(a) <= 4 * EPS * (p - d);
        nhit += hit[i];
        t[i] = d > 0 ? a / (p + d) : hit[i] ? 0 : (p - d) / a;
    }
    if (nhit) {
        FN(on_edges)(hit, rho, w, persp, screen);
        return degenerate ? QGL_DEGENERATE : QGL_INSIDE;
    }

    int pos = 0, neg = 0;
    for (int i = 0; i < 4; i++) {
        nu[i] = (t[(i + 3) & 3] + t[i]) / rho[i];
        pos |= nu[i] > 0;
        neg |= nu[i] < 0;
    }
    FN(normalize_weights)(nu, w, persp, screen);
    if (degenerate)
        return QGL_DEGENERATE;
    return pos && neg ? QGL_OUTSIDE : (pos || neg) ? QGL_INSIDE : QGL_OUTSIDE;
}
