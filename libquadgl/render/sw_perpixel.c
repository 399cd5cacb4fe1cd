/* sw_perpixel.c: the per-pixel comparison methods mvc64, invbilinear and projective.
 *
 * All three share eq. (12) coverage (qgl__quad_scan) and differ only in the weights:
 * mvc64 asks qgl_weights (double, exact limits on corners and edges) at the pixel's position
 * (in pixels, as the fast mvc); invbilinear inverts the bilinear map of the projected screen quad (Quilez) and
 * interpolates bilinearly in screen space, with no perspective correction, as the original
 * shader does; projective maps the screen quad to the unit square by the homography through
 * its four corners (Heckbert's square-to-quad, inverted by its adjugate) and interpolates
 * bilinearly there (H&T fig. 1d). Depth follows each method's own parametrization. */
#include "sw_internal.h"

#include <math.h>

static int weights_mvc64(void *user, const qgl__quad *q, double X, double Y, double persp[4], double *zndc)
{
    const qgl_sw_fb *fb = user;
    double screen[4];
    int r = qgl_weights(q->px, qgl__centred(X, fb->width), qgl__centred(Y, fb->height), persp, screen);
    if (r == QGL_NONFINITE)
        return 0;
    *zndc = qgl__zndc(q, persp);
    return 1;
}

void qgl__draw_mvc64(qgl__ctx *c, const qgl__quad *q)
{
    qgl__quad_scan(c, q, weights_mvc64, c->fb);
}

static void bilinear_weights(double u, double v, double wts[4])
{
    wts[0] = (1 - u) * (1 - v);
    wts[1] = u * (1 - v);
    wts[2] = u * v;
    wts[3] = (1 - u) * v;
}

/* Depth of a screen-space parametrization: the projected corner depths, bilinearly. */
static double screen_depth(const qgl__quad *q, const double wts[4])
{
    double z = 0;
    for (int i = 0; i < 4; i++)
        z += wts[i] * (q->clip[i][2] / q->clip[i][3]);
    return z;
}

static int weights_invbilinear(void *user, const qgl__quad *q, double X, double Y, double persp[4], double *zndc)
{
    double v2[4][2], uv[2];
    for (int i = 0; i < 4; i++) {
        v2[i][0] = q->h[i][0] / q->h[i][2];
        v2[i][1] = q->h[i][1] / q->h[i][2];
    }
    if (qgl_inv_bilinear(v2, X, Y, uv) < 0)
        return 0;
    double u = fmin(fmax(uv[0], 0), 1), v = fmin(fmax(uv[1], 0), 1);
    bilinear_weights(u, v, persp);
    *zndc = screen_depth(q, persp);
    return 1;
}

void qgl__draw_invbilinear(qgl__ctx *c, const qgl__quad *q)
{
    qgl__quad_scan(c, q, weights_invbilinear, NULL);
}

/* The inverse homography (screen -> unit square) of one quad, as a 3x3 row-major matrix. */
typedef struct homography {
    double m[9];
} homography;

static void square_to_quad(const double p[4][2], double m[9])
{
    double sx = p[0][0] - p[1][0] + p[2][0] - p[3][0], sy = p[0][1] - p[1][1] + p[2][1] - p[3][1];
    double g = 0, h = 0;
    if (sx != 0 || sy != 0) {
        double dx1 = p[1][0] - p[2][0], dx2 = p[3][0] - p[2][0];
        double dy1 = p[1][1] - p[2][1], dy2 = p[3][1] - p[2][1];
        double det = dx1 * dy2 - dx2 * dy1;
        g = (sx * dy2 - dx2 * sy) / det;
        h = (dx1 * sy - sx * dy1) / det;
    }
    m[0] = p[1][0] - p[0][0] + g * p[1][0];
    m[1] = p[3][0] - p[0][0] + h * p[3][0];
    m[2] = p[0][0];
    m[3] = p[1][1] - p[0][1] + g * p[1][1];
    m[4] = p[3][1] - p[0][1] + h * p[3][1];
    m[5] = p[0][1];
    m[6] = g;
    m[7] = h;
    m[8] = 1;
}

static void adjugate(const double a[9], double b[9])
{
    b[0] = a[4] * a[8] - a[5] * a[7];
    b[1] = a[2] * a[7] - a[1] * a[8];
    b[2] = a[1] * a[5] - a[2] * a[4];
    b[3] = a[5] * a[6] - a[3] * a[8];
    b[4] = a[0] * a[8] - a[2] * a[6];
    b[5] = a[2] * a[3] - a[0] * a[5];
    b[6] = a[3] * a[7] - a[4] * a[6];
    b[7] = a[1] * a[6] - a[0] * a[7];
    b[8] = a[0] * a[4] - a[1] * a[3];
}

static int weights_projective(void *user, const qgl__quad *q, double X, double Y, double persp[4], double *zndc)
{
    const double *m = ((const homography *)user)->m;
    double uq = m[0] * X + m[1] * Y + m[2];
    double vq = m[3] * X + m[4] * Y + m[5];
    double wq = m[6] * X + m[7] * Y + m[8];
    if (!(wq != 0))
        return 0;
    double u = fmin(fmax(uq / wq, 0), 1), v = fmin(fmax(vq / wq, 0), 1);
    if (!isfinite(uq / wq) || !isfinite(vq / wq))
        return 0;
    bilinear_weights(u, v, persp);
    *zndc = screen_depth(q, persp);
    return 1;
}

void qgl__draw_projective(qgl__ctx *c, const qgl__quad *q)
{
    double p[4][2], fwd[9];
    homography inv;
    for (int i = 0; i < 4; i++) {
        p[i][0] = q->h[i][0] / q->h[i][2];
        p[i][1] = q->h[i][1] / q->h[i][2];
    }
    square_to_quad((const double(*)[2])p, fwd);
    adjugate(fwd, inv.m);
    qgl__quad_scan(c, q, weights_projective, &inv);
}
