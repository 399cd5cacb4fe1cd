/* plane_impl.h: a quad's plane frame, written once and instantiated for double and float.
 *
 * plane.c includes this file twice with R (the real type), PLANE (the frame's struct type),
 * FN(name) (the suffixed function name), EPS (the type's unit roundoff), BIG (the type's
 * largest value over 64), RMIN (its smallest normal number), SQRT, FABS, FREXP, LDEXP and
 * ISFINITE. See plane.c for the algorithm. */

#include "pow2_impl.h"

static R FN(dot)(const R a[3], const R b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void FN(cross)(const R a[3], const R b[3], R out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static void FN(diff)(const R a[3], const R b[3], R out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = a[k] - b[k];
}

/* The plane's normal, unnormalized: the longest of the diagonals' cross product (Newell's
 * normal) and the four corner normals. */
static R FN(normal)(const R d[4][3], R n[3])
{
    R e[3], f[3], c[3];
    FN(diff)(d[2], d[0], e);
    FN(diff)(d[3], d[1], f);
    FN(cross)(e, f, n);
    R best = FN(dot)(n, n);
    for (int i = 0; i < 4; i++) {
        FN(diff)(d[(i + 1) & 3], d[i], e);
        FN(diff)(d[(i + 3) & 3], d[i], f);
        FN(cross)(e, f, c);
        R len = FN(dot)(c, c);
        if (len > best) {
            best = len;
            for (int k = 0; k < 3; k++)
                n[k] = c[k];
        }
    }
    return best;
}

/* A unit vector orthogonal to the unit vector n (for a quad with no plane: any will do). */
static void FN(orthogonal)(const R n[3], R u[3])
{
    int k = FABS(n[0]) <= FABS(n[1]) && FABS(n[0]) <= FABS(n[2]) ? 0 : FABS(n[1]) <= FABS(n[2]) ? 1 : 2;
    R a[3] = {0, 0, 0};
    a[k] = 1;
    FN(cross)(n, a, u);
    R len = SQRT(FN(dot)(u, u));
    for (int j = 0; j < 3; j++)
        u[j] /= len;
}

/* 1 when diagonal 1-3 is the preferred one: the shorter in object space; on a tie the one
 * holding the corner that comes first in coordinate order, which depends on the positions
 * only, so rotating or reversing the corner order keeps the choice. */
static int FN(diagonal)(const R d[4][3])
{
    R e[3], f[3];
    FN(diff)(d[2], d[0], e);
    FN(diff)(d[3], d[1], f);
    R le = FN(dot)(e, e), lf = FN(dot)(f, f);
    if (le != lf)
        return lf < le;
    int first = 0;
    for (int i = 1; i < 4; i++)
        for (int k = 0; k < 3; k++) {
            if (d[i][k] != d[first][k]) {
                if (d[i][k] < d[first][k])
                    first = i;
                break;
            }
        }
    return first & 1;
}

/* x within the type's finite range. */
static R FN(clamp)(R x)
{
    R top = 64 * BIG;
    return x > top ? top : x < -top ? -top : x;
}

static int FN(frame)(const R pos[4][3], PLANE *out)
{
    R d[4][3], n[3] = {0, 0, 1}, u[3], v[3], m = 0;
    int finite = 1;
    for (int i = 0; i < 12; i++)
        finite = finite && ISFINITE(pos[i / 3][i % 3]);
    for (int k = 0; k < 3; k++) {
        out->origin[k] = 0;
        out->normal[k] = n[k];
        out->axis[0][k] = k == 0;
        out->axis[1][k] = k == 1;
    }
    for (int i = 0; i < 4; i++)
        out->corner[i][0] = out->corner[i][1] = out->height[i] = 0;
    out->diagonal = 0;
    if (!finite)
        return QGL_NONFINITE;
    /* Corners near the type's range are scaled down by a power of two first (exact), so the
     * differences below cannot overflow; the results are scaled back and clamped. */
    R big = 0, c[3];
    for (int i = 0; i < 12; i++)
        big = FABS(pos[i / 3][i % 3]) > big ? FABS(pos[i / 3][i % 3]) : big;
    int e0 = 0;
    if (big > BIG)
        FREXP(big, &e0);
    /* Centroid, then the corners relative to it scaled by one power of two into [0.5, 1):
     * the frame does not change, and no square overflows or underflows. */
    for (int k = 0; k < 3; k++) {
        c[k] = 0;
        for (int i = 0; i < 4; i++)
            c[k] += FN(ldexp)(pos[i][k], -e0) / 4;
        out->origin[k] = FN(ldexp)(c[k], e0);
    }
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++) {
            d[i][k] = FN(ldexp)(pos[i][k], -e0) - c[k];
            m = FABS(d[i][k]) > m ? FABS(d[i][k]) : m;
        }
    if (m == 0)
        return QGL_DEGENERATE;
    int e;
    FREXP(m, &e);
    FN(scale_pow2)(&d[0][0], 12, e);
    R len = SQRT(FN(normal)((const R(*)[3])d, n));
    int degenerate = !(len > 64 * EPS);
    if (degenerate) {
        n[0] = 0, n[1] = 0, n[2] = 1;
    } else {
        for (int k = 0; k < 3; k++)
            n[k] /= len;
    }
    /* The first axis along the longer diagonal, made orthogonal to the normal. */
    R a[3], b[3];
    FN(diff)(d[2], d[0], a);
    FN(diff)(d[3], d[1], b);
    const R *g = FN(dot)(a, a) >= FN(dot)(b, b) ? a : b;
    R gn = FN(dot)(g, n);
    for (int k = 0; k < 3; k++)
        u[k] = g[k] - gn * n[k];
    R ul = SQRT(FN(dot)(u, u));
    if (ul > 0) {
        for (int k = 0; k < 3; k++)
            u[k] /= ul;
    } else {
        FN(orthogonal)(n, u);
    }
    FN(cross)(n, u, v);
    for (int k = 0; k < 3; k++) {
        out->normal[k] = n[k];
        out->axis[0][k] = u[k];
        out->axis[1][k] = v[k];
    }
    for (int i = 0; i < 4; i++) {
        out->corner[i][0] = FN(clamp)(FN(ldexp)(FN(dot)(d[i], u), e + e0));
        out->corner[i][1] = FN(clamp)(FN(ldexp)(FN(dot)(d[i], v), e + e0));
        out->height[i] = FN(clamp)(FN(ldexp)(FN(dot)(d[i], n), e + e0));
    }
    out->diagonal = FN(diagonal)((const R(*)[3])d);
    return degenerate ? QGL_DEGENERATE : 0;
}

static void FN(coords)(const PLANE *pl, const R p[3], R xy[2])
{
    R d[3];
    FN(diff)(p, pl->origin, d);
    xy[0] = FN(dot)(d, pl->axis[0]);
    xy[1] = FN(dot)(d, pl->axis[1]);
}

/* The corners and the point scaled together by a power of two into [0.5, 1) (the weights do
 * not change): the one-call weights then never overflow on the way. */
static void FN(scale_all)(const R pos[4][3], const R p[3], R spos[4][3], R sp[3])
{
    R m = 0;
    for (int k = 0; k < 3; k++)
        m = FABS(p[k]) > m && ISFINITE(p[k]) ? FABS(p[k]) : m;
    for (int i = 0; i < 12; i++)
        m = FABS(pos[i / 3][i % 3]) > m && ISFINITE(pos[i / 3][i % 3]) ? FABS(pos[i / 3][i % 3]) : m;
    int e = 0;
    if (m > 0)
        FREXP(m, &e);
    memcpy(sp, p, 3 * sizeof(R));
    memcpy(spos, pos, 12 * sizeof(R));
    FN(scale_pow2)(sp, 3, e);
    FN(scale_pow2)(&spos[0][0], 12, e);
}
