/* sw_exact.c: the reference renderer: each pixel's ray against the bilinear patch, in double.
 *
 * The patch is C(u, v) = (1-u)(1-v) c0 + u(1-v) c1 + uv c2 + (1-u)v c3 over the clip corners
 * (bilinear in clip space is bilinear in object space: the projection is linear on
 * homogeneous coordinates). The pixel's ray is every clip point with X w = x_win, Y w =
 * y_win, so a hit solves F(u, v) = 0 for the 2D bilinear map of s~_i = (hx_i - X hw_i,
 * hy_i - Y hw_i). Writing F = (s0 + v e3) + u (e1 + v g), the two vectors must be parallel:
 * k2 v^2 + k1 v + k0 = 0 with k2 = e3 x g, k1 = s0 x g + e3 x e1, k0 = s0 x e1, solved in
 * the cancellation-free form q = -(k1 + sign(k1) sqrt(k1^2 - 4 k2 k0)) / 2, v = q / k2 and
 * v = k0 / q (Ramsey et al. 2004; the form also yields the single root when k2 = 0). u comes
 * from least squares along e1 + v g. A hit counts when (u, v) lies in the unit square and the
 * clip point is in front of the eye (w > 0) and between the near and far planes; the nearest
 * such hit wins. Within a rounding margin of the square's border the quad's own edge function
 * with the renderer's tie rule decides, so patches sharing an edge stay watertight. Facing is
 * the sign of det(C, C_u, C_v) over (x, y, w): the orientation of the screen map at the hit.
 * Attributes are bilinear in (u, v); for a planar parallelogram that is affine interpolation. */
#include "sw_internal.h"

#include <math.h>

#define BORDER 1e-9

typedef struct hit {
    double u, v, zndc;
    int facing;
} hit;

static void patch_point(const qgl__quad *q, double u, double v, double out[4])
{
    double w0 = (1 - u) * (1 - v), w1 = u * (1 - v), w2 = u * v, w3 = (1 - u) * v;
    for (int k = 0; k < 4; k++)
        out[k] = w0 * q->clip[0][k] + w1 * q->clip[1][k] + w2 * q->clip[2][k] + w3 * q->clip[3][k];
}

static int patch_facing(const qgl__quad *q, double u, double v)
{
    double p[3], pu[3], pv[3];
    for (int k = 0; k < 3; k++) {
        const double *c0 = &q->h[0][0], *c1 = &q->h[1][0], *c2 = &q->h[2][0], *c3 = &q->h[3][0];
        p[k] = (1 - u) * (1 - v) * c0[k] + u * (1 - v) * c1[k] + u * v * c2[k] + (1 - u) * v * c3[k];
        pu[k] = (1 - v) * (c1[k] - c0[k]) + v * (c2[k] - c3[k]);
        pv[k] = (1 - u) * (c3[k] - c0[k]) + u * (c2[k] - c1[k]);
    }
    double d = qgl__det3(p, pu, pv);
    return (d > 0) - (d < 0);
}

/* Near the square's border the edge function of that border edge decides (tie rule). */
static int border_ok(const qgl__quad *q, double X, double Y, double u, double v, int f)
{
    const double t[4] = {v, 1 - u, 1 - v, u}; /* distance to edges 01, 12, 23, 30 */
    for (int k = 0; k < 4; k++) {
        if (t[k] < -BORDER)
            return 0;
        if (t[k] <= BORDER && !qgl__edge_in(&q->e[k], qgl__edge_eval(&q->e[k], X, Y), f))
            return 0;
    }
    return 1;
}

static void try_root(const qgl__quad *q, double X, double Y, const double s0[2], const double e1[2],
                     const double e3[2], const double g[2], double v, hit *best)
{
    double dx = e1[0] + v * g[0], dy = e1[1] + v * g[1];
    double nx = s0[0] + v * e3[0], ny = s0[1] + v * e3[1];
    double den = dx * dx + dy * dy;
    if (!(den > 0) || !isfinite(v))
        return;
    double u = -(nx * dx + ny * dy) / den;
    if (u < -BORDER || u > 1 + BORDER || v < -BORDER || v > 1 + BORDER)
        return;
    int f = patch_facing(q, u, v);
    if (!f || !border_ok(q, X, Y, u, v, f))
        return;
    u = fmin(fmax(u, 0), 1);
    v = fmin(fmax(v, 0), 1);
    double c[4];
    patch_point(q, u, v, c);
    if (!(c[3] > 0) || c[2] < -c[3] || c[2] > c[3])
        return;
    double z = c[2] / c[3];
    if (z < best->zndc) {
        best->u = u;
        best->v = v;
        best->zndc = z;
        best->facing = f;
    }
}

static double cross2(const double a[2], const double b[2])
{
    return a[0] * b[1] - a[1] * b[0];
}

static int intersect(const qgl__quad *q, double X, double Y, hit *best)
{
    double s[4][2];
    for (int i = 0; i < 4; i++) {
        s[i][0] = q->h[i][0] - X * q->h[i][2];
        s[i][1] = q->h[i][1] - Y * q->h[i][2];
    }
    double e1[2] = {s[1][0] - s[0][0], s[1][1] - s[0][1]};
    double e3[2] = {s[3][0] - s[0][0], s[3][1] - s[0][1]};
    double g[2] = {s[0][0] - s[1][0] + s[2][0] - s[3][0], s[0][1] - s[1][1] + s[2][1] - s[3][1]};
    double k2 = cross2(e3, g), k1 = cross2(s[0], g) + cross2(e3, e1), k0 = cross2(s[0], e1);
    double disc = k1 * k1 - 4 * k2 * k0;
    best->zndc = INFINITY;
    if (disc < 0)
        return 0;
    double qq = -0.5 * (k1 + copysign(sqrt(disc), k1));
    if (k2 != 0)
        try_root(q, X, Y, s[0], e1, e3, g, qq / k2, best);
    if (qq != 0)
        try_root(q, X, Y, s[0], e1, e3, g, k0 / qq, best);
    return best->zndc < INFINITY;
}

int qgl__patch_hit(const qgl__quad *q, double X, double Y, double uv[2], double *zndc, int *facing)
{
    hit h;
    if (!intersect(q, X, Y, &h))
        return 0;
    uv[0] = h.u;
    uv[1] = h.v;
    *zndc = h.zndc;
    *facing = h.facing;
    return 1;
}

void qgl__draw_exact(qgl__ctx *c, const qgl__quad *q)
{
    float attr[QGL_SW_MAX_ATTR];
    for (int y = q->y0; y <= q->y1; y++) {
        double Y = y + 0.5;
        for (int x = q->x0; x <= q->x1; x++) {
            double X = x + 0.5, wts[4];
            hit h;
            if (!intersect(q, X, Y, &h))
                continue;
            wts[0] = (1 - h.u) * (1 - h.v);
            wts[1] = h.u * (1 - h.v);
            wts[2] = h.u * h.v;
            wts[3] = (1 - h.u) * h.v;
            for (int k = 0; k < q->nattr; k++) {
                double a = 0;
                for (int i = 0; i < 4; i++)
                    a += wts[i] * q->attr[i * q->nattr + k];
                attr[k] = (float)a;
            }
            qgl__fragment(c, x, y, h.zndc, h.facing, attr);
        }
    }
}
