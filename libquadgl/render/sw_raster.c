/* sw_raster.c: quad and triangle setup, row ranges, the triangle rasterizer, the generic scan.
 *
 * Setup maps clip corners to window-homogeneous form h = ((x + w) W / 2, (y + w) H / 2, w)
 * and builds the homogeneous edge functions (see sw_internal.h). A triangle is covered where
 * its three edge functions carry the sign of det(h0, h1, h2) (Olano & Greer: the opposite
 * sign is the mirror image behind the eye), and is interpolated perspective-correctly by the
 * same edge values: a = sum E_k a_k / sum E_k, z_ndc = sum E_k z_k / sum E_k w_k. Scans walk
 * only the columns a row can cover: each edge function is linear along a row, so the row's
 * interval inside a triangle is an intersection of half-lines. */
#include "sw_internal.h"

#include <math.h>
#include <string.h>

double qgl__det3(const double a[3], const double b[3], const double c[3])
{
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
           a[2] * (b[0] * c[1] - b[1] * c[0]);
}

static int sign_of(double x)
{
    return (x > 0) - (x < 0);
}

void qgl__edge_setup(qgl__edge *e, const double hi[3], const double hj[3])
{
    e->a = hi[1] * hj[2] - hi[2] * hj[1];
    e->b = hi[2] * hj[0] - hi[0] * hj[2];
    e->c = hi[0] * hj[1] - hi[1] * hj[0];
    e->degenerate = e->a == 0 && e->b == 0;
    /* Inside lies where f E > 0, so the gradient f (a, b) points inwards: a centre on the edge
     * belongs to the primitive whose inside is towards +x (towards +y when a == 0). */
    e->tie[1] = e->a > 0 || (e->a == 0 && e->b > 0);
    e->tie[0] = e->a < 0 || (e->a == 0 && e->b < 0);
}

static void to_window(const qgl_sw_fb *fb, const double clip[4], double h[3])
{
    h[0] = (clip[0] + clip[3]) * (0.5 * fb->width);
    h[1] = (clip[1] + clip[3]) * (0.5 * fb->height);
    h[2] = clip[3];
}

int qgl__bbox(const qgl_sw_fb *fb, const double (*h)[3], int n, int box[4])
{
    int pos = 0;
    for (int i = 0; i < n; i++)
        pos += h[i][2] > 0;
    if (pos == 0)
        return 0;
    box[0] = 0;
    box[1] = 0;
    box[2] = fb->width - 1;
    box[3] = fb->height - 1;
    if (pos < n)
        return 1;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 2; k++) {
            double v = h[i][k] / h[i][2];
            lo[k] = v < lo[k] ? v : lo[k];
            hi[k] = v > hi[k] ? v : hi[k];
        }
    for (int k = 0; k < 2; k++) {
        if (!(lo[k] <= hi[k]))
            return 0;
        double a = floor(lo[k] - 0.5), b = ceil(hi[k] - 0.5);
        if (a > box[2 + k] || b < 0)
            return 0;
        if (a > box[k])
            box[k] = (int)a;
        if (b < box[2 + k])
            box[2 + k] = (int)b;
    }
    return 1;
}

void qgl__quad_setup(qgl__quad *q, const qgl_sw_fb *fb, const float *clip, const float *attr, int nattr)
{
    for (int i = 0; i < 4; i++) {
        for (int k = 0; k < 4; k++)
            q->clip[i][k] = clip[4 * i + k];
        to_window(fb, q->clip[i], q->h[i]);
        q->px[i][0] = q->clip[i][0] * (0.5 * fb->width);
        q->px[i][1] = q->clip[i][1] * (0.5 * fb->height);
        q->px[i][2] = q->clip[i][2];
        q->px[i][3] = q->clip[i][3];
        q->z[i] = q->clip[i][2];
    }
    q->attr = attr;
    q->nattr = nattr;
    for (int i = 0; i < 4; i++)
        qgl__edge_setup(&q->e[i], q->h[i], q->h[(i + 1) & 3]);
    qgl__edge_setup(&q->e[QGL__E20], q->h[2], q->h[0]);
    q->f012 = sign_of(qgl__det3(q->h[0], q->h[1], q->h[2]));
    q->f023 = sign_of(qgl__det3(q->h[0], q->h[2], q->h[3]));
    q->convex = 0;
    int turn = sign_of(qgl__det3(q->h[3], q->h[0], q->h[1])), same = turn != 0;
    for (int i = 0; i < 4; i++)
        same = same && q->h[i][2] > 0 && sign_of(qgl__det3(q->h[i], q->h[(i + 1) & 3], q->h[(i + 2) & 3])) == turn;
    if (same)
        q->convex = turn;
    int box[4];
    if (!qgl__bbox(fb, (const double(*)[3])q->h, 4, box)) {
        q->x0 = q->y0 = 0;
        q->x1 = q->y1 = -1;
        return;
    }
    q->x0 = box[0];
    q->y0 = box[1];
    q->x1 = box[2];
    q->y1 = box[3];
}

/* Narrow [lo, hi] to where s E(X, Y) >= 0 along the row. */
static void clip_interval(const qgl__edge *e, int s, double Y, double *lo, double *hi)
{
    if (e->degenerate)
        return;
    double a = s * e->a, rest = s * (e->b * Y + e->c);
    if (a > 0) {
        double x = -rest / a;
        *lo = x > *lo ? x : *lo;
    } else if (a < 0) {
        double x = -rest / a;
        *hi = x < *hi ? x : *hi;
    } else if (rest < 0) {
        *hi = -INFINITY;
    }
}

static void tri_interval(const qgl__edge *e0, int s0, const qgl__edge *e1, int s1, const qgl__edge *e2, int s2,
                         double Y, double *lo, double *hi)
{
    *lo = -INFINITY;
    *hi = INFINITY;
    clip_interval(e0, s0, Y, lo, hi);
    clip_interval(e1, s1, Y, lo, hi);
    clip_interval(e2, s2, Y, lo, hi);
}

/* Columns of the interval [lo, hi] (window X), one pixel of slack, clamped to [bx0, bx1]. */
static int columns(double lo, double hi, int bx0, int bx1, int *x0, int *x1)
{
    if (!(lo <= hi))
        return 0;
    double a = floor(lo - 0.5) - 1, b = ceil(hi - 0.5) + 1;
    if (a > bx1 || b < bx0)
        return 0;
    *x0 = a > bx0 ? (int)a : bx0;
    *x1 = b < bx1 ? (int)b : bx1;
    return 1;
}

int qgl__row_range(const qgl__quad *q, double Y, int *x0, int *x1)
{
    double lo = INFINITY, hi = -INFINITY, l, h;
    const qgl__edge *e = q->e;
    if (q->f012) {
        int f = q->f012;
        tri_interval(&e[QGL__E01], f, &e[QGL__E12], f, &e[QGL__E20], f, Y, &l, &h);
        if (l <= h) {
            lo = l < lo ? l : lo;
            hi = h > hi ? h : hi;
        }
    }
    if (q->f023) {
        int f = q->f023;
        tri_interval(&e[QGL__E20], -f, &e[QGL__E23], f, &e[QGL__E30], f, Y, &l, &h);
        if (l <= h) {
            lo = l < lo ? l : lo;
            hi = h > hi ? h : hi;
        }
    }
    return columns(lo, hi, q->x0, q->x1, x0, x1);
}

int qgl__row_inner(const qgl__quad *q, double Y, int x0, int x1, int *xa, int *xb)
{
    int f = q->convex;
    if (!f)
        return 0;
    double lo = -INFINITY, hi = INFINITY;
    for (int k = 0; k < 4; k++) {
        const qgl__edge *e = &q->e[k];
        double a = f * e->a, rest = f * (e->b * Y + e->c);
        if (a > 0)
            lo = fmax(lo, -rest / a + 1);
        else if (a < 0)
            hi = fmin(hi, -rest / a - 1);
        else if (!(rest > 0))
            return 0;
    }
    double ca = ceil(lo - 0.5), cb = floor(hi - 0.5);
    if (!(ca <= cb) || ca > x1 || cb < x0)
        return 0;
    *xa = ca > x0 ? (int)ca : x0;
    *xb = cb < x1 ? (int)cb : x1;
    for (int k = 0; k < 4; k++) {
        const qgl__edge *e = &q->e[k];
        if (!(f * qgl__edge_eval(e, *xa + 0.5, Y) > 0) || !(f * qgl__edge_eval(e, *xb + 0.5, Y) > 0))
            return 0;
    }
    return 1;
}

/* The triangle scan: per covered pixel the nvary values interpolated perspective-correctly
 * (in double), then either written as the fragment's attributes (map NULL: the splits and
 * subdivisions) or handed to map, which turns them into attributes (the in-plane methods
 * interpolate a position and weigh it). Inline so the splits' loop keeps no indirect call. */
QGL__HOT_INLINE void triangle_scan(qgl__ctx *c, const double *v0, const double *v1, const double *v2, int nvary,
                                   qgl__vary_fn map, void *user)
{
    const double *v[3] = {v0, v1, v2};
    double h[3][3];
    for (int i = 0; i < 3; i++)
        to_window(c->fb, v[i], h[i]);
    int f = sign_of(qgl__det3(h[0], h[1], h[2]));
    int box[4];
    if (!f || qgl__culled(c, f) || !qgl__bbox(c->fb, (const double(*)[3])h, 3, box))
        return;
    c->triangles++;
    qgl__edge e[3]; /* e[k] is opposite corner k: its value is corner k's weight */
    qgl__edge_setup(&e[0], h[1], h[2]);
    qgl__edge_setup(&e[1], h[2], h[0]);
    qgl__edge_setup(&e[2], h[0], h[1]);
    float attr[QGL_SW_MAX_ATTR];
    double vary[QGL_SW_MAX_ATTR];
    for (int y = box[1]; y <= box[3]; y++) {
        double Y = y + 0.5, lo, hi;
        int x0, x1;
        tri_interval(&e[0], f, &e[1], f, &e[2], f, Y, &lo, &hi);
        if (!columns(lo, hi, box[0], box[2], &x0, &x1))
            continue;
        for (int x = x0; x <= x1; x++) {
            double X = x + 0.5, E[3];
            int in = 1;
            for (int k = 0; k < 3; k++) {
                E[k] = qgl__edge_eval(&e[k], X, Y);
                in = in && qgl__edge_in(&e[k], E[k], f);
            }
            if (!in)
                continue;
            double sum = E[0] + E[1] + E[2];
            double zs = E[0] * v0[2] + E[1] * v1[2] + E[2] * v2[2];
            double ws = E[0] * v0[3] + E[1] * v1[3] + E[2] * v2[3];
            if (map) {
                for (int k = 0; k < nvary; k++)
                    vary[k] = (E[0] * v0[4 + k] + E[1] * v1[4 + k] + E[2] * v2[4 + k]) / sum;
                if (!map(user, vary, attr))
                    continue;
            } else {
                for (int k = 0; k < nvary; k++)
                    attr[k] = (float)((E[0] * v0[4 + k] + E[1] * v1[4 + k] + E[2] * v2[4 + k]) / sum);
            }
            qgl__fragment(c, x, y, zs / ws, f, attr);
        }
    }
}

void qgl__triangle(qgl__ctx *c, const double *v0, const double *v1, const double *v2, int nattr)
{
    triangle_scan(c, v0, v1, v2, nattr, NULL, NULL);
}

void qgl__triangle_map(qgl__ctx *c, const double *v0, const double *v1, const double *v2, int nvary,
                       qgl__vary_fn map, void *user)
{
    triangle_scan(c, v0, v1, v2, nvary, map, user);
}

void qgl__quad_scan(qgl__ctx *c, const qgl__quad *q, qgl__weight_fn fn, void *user)
{
    float attr[QGL_SW_MAX_ATTR];
    for (int y = q->y0; y <= q->y1; y++) {
        double Y = y + 0.5;
        int x0, x1;
        if (!qgl__row_range(q, Y, &x0, &x1))
            continue;
        for (int x = x0; x <= x1; x++) {
            double X = x + 0.5, persp[4], zndc;
            int f = qgl__cover(q, X, Y);
            if (!f || qgl__culled(c, f) || !fn(user, q, X, Y, persp, &zndc))
                continue;
            for (int k = 0; k < q->nattr; k++) {
                double a = 0;
                for (int i = 0; i < 4; i++)
                    a += persp[i] * q->attr[i * q->nattr + k];
                attr[k] = (float)a;
            }
            qgl__fragment(c, x, y, zndc, f, attr);
        }
    }
}
