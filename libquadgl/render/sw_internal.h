/* sw_internal.h: what the software renderer's files share (quad setup, coverage, fragments).
 *
 * Every primitive is set up in window-homogeneous coordinates h = (X w, Y w, w), X and Y in
 * pixels, so a pixel centre P = (X, Y, 1) is covered by reading signs of the homogeneous
 * edge functions E_ij(P) = det(h_i, h_j, P) (Olano & Greer 1997): no division by w, corners
 * behind the eye need no clipper, and E_ji is computed as the exact negation of E_ij (the
 * cross product's two products swap places), which with one fixed evaluation order makes
 * neighbouring primitives agree bit for bit on which of them owns a pixel on their shared
 * edge. Floating-point contraction is switched off in every file of the renderer for that
 * reason: a fused multiply-add would break the exact antisymmetry. */
#ifndef QGL_SW_INTERNAL_H
#define QGL_SW_INTERNAL_H

#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include <quadgl/quadgl.h>

/* The 5 edge functions of H&T eq. (12), in this order; index 4 is the diagonal E20. */
enum { QGL__E01, QGL__E12, QGL__E23, QGL__E30, QGL__E20, QGL__NEDGE };

typedef struct qgl__edge {
    double a, b, c;   /* E(X, Y) = (a X + b Y) + c */
    int degenerate;   /* identically zero (a collapsed edge): no constraint */
    int tie[2];       /* tie[f > 0]: a centre exactly on the edge counts as inside for facing f */
} qgl__edge;

/* A quad ready to rasterize. */
typedef struct qgl__quad {
    double h[4][3];   /* window-homogeneous corners */
    double z[4];      /* clip z */
    double clip[4][4]; /* the clip corners as given (double) */
    double px[4][4];   /* the clip corners with x, y times the half size: with a pixel centre
                          less the centre of the framebuffer, the space the weights are computed
                          in (isotropic pixels, as h; NDC would squeeze a non-square image) */
    const float *attr;
    int nattr;
    qgl__edge e[QGL__NEDGE];
    int f012, f023;   /* orientation of the triangles 012 and 023 in homogeneous form */
    int convex;       /* +1 / -1: strictly convex on screen, every w > 0 (eq. 12 is then the
                         four edges' half-planes); 0 otherwise */
    int x0, y0, x1, y1; /* pixel box to scan, inclusive; empty when x0 > x1 */
} qgl__quad;

/* What every fragment write needs. */
typedef struct qgl__ctx {
    qgl_sw_fb *fb;
    const qgl_sw_draw_desc *d;
    long long fragments, triangles;
    float scratch[64];
} qgl__ctx;

void qgl__edge_setup(qgl__edge *e, const double hi[3], const double hj[3]);
double qgl__det3(const double a[3], const double b[3], const double c[3]);
/* Pixel box covering the homogeneous points (whole viewport when a w is <= 0); returns 0 when
 * every w is <= 0 (nothing visible). */
int qgl__bbox(const qgl_sw_fb *fb, const double (*h)[3], int n, int box[4]);
void qgl__quad_setup(qgl__quad *q, const qgl_sw_fb *fb, const float *clip, const float *attr, int nattr);

static inline double qgl__edge_eval(const qgl__edge *e, double X, double Y)
{
    return (e->a * X + e->b * Y) + e->c;
}

static inline int qgl__edge_in(const qgl__edge *e, double value, int f)
{
    if (e->degenerate)
        return 1;
    double v = f > 0 ? value : -value;
    return v > 0 || (v == 0 && e->tie[f > 0]);
}

/* H&T eq. (12) on the homogeneous edge values ev[5]: +1 inside and front-facing, -1 inside
 * and back-facing, 0 outside. The region of the first expression lies in triangle 012 and
 * can only face as that triangle does (f012), the second likewise with f023; requiring it
 * rejects the mirror region behind the eye that an external quad would otherwise claim. */
static inline int qgl__eq12(const qgl__quad *q, const double ev[5])
{
    const qgl__edge *e = q->e;
    int f = q->f012;
    if (f && qgl__edge_in(&e[QGL__E20], ev[QGL__E20], f) && qgl__edge_in(&e[QGL__E01], ev[QGL__E01], f) &&
        qgl__edge_in(&e[QGL__E12], ev[QGL__E12], f) &&
        (qgl__edge_in(&e[QGL__E23], ev[QGL__E23], f) || qgl__edge_in(&e[QGL__E30], ev[QGL__E30], f)))
        return f;
    f = q->f023;
    if (f && qgl__edge_in(&e[QGL__E20], ev[QGL__E20], -f) && qgl__edge_in(&e[QGL__E23], ev[QGL__E23], f) &&
        qgl__edge_in(&e[QGL__E30], ev[QGL__E30], f) &&
        (qgl__edge_in(&e[QGL__E01], ev[QGL__E01], f) || qgl__edge_in(&e[QGL__E12], ev[QGL__E12], f)))
        return f;
    return 0;
}

static inline int qgl__cover(const qgl__quad *q, double X, double Y)
{
    double ev[5];
    for (int k = 0; k < QGL__NEDGE; k++)
        ev[k] = qgl__edge_eval(&q->e[k], X, Y);
    return qgl__eq12(q, ev);
}

#if defined(__GNUC__)
#define QGL__HOT_INLINE static inline __attribute__((always_inline))
#else
#define QGL__HOT_INLINE static inline
#endif

/* NDC depth of the point with perspective weights persp: sum persp z / sum persp w. */
static inline double qgl__zndc(const qgl__quad *q, const double persp[4])
{
    double zs = 0, ws = 0;
    for (int i = 0; i < 4; i++) {
        zs += persp[i] * q->clip[i][2];
        ws += persp[i] * q->clip[i][3];
    }
    return zs / ws;
}

/* Facing f is culled by the draw's cull mode. */
static inline int qgl__culled(const qgl__ctx *c, int f)
{
    return (c->d->cull == QGL_SW_CULL_BACK && f < 0) || (c->d->cull == QGL_SW_CULL_FRONT && f > 0);
}

/* Copy n floats; the first four explicitly, since a plain loop of unknown small length
 * becomes a memcpy call, which costs more than the copy. */
QGL__HOT_INLINE void qgl__copy_small(float *dst, const float *src, int n)
{
    if (n > 0)
        dst[0] = src[0];
    if (n > 1)
        dst[1] = src[1];
    if (n > 2)
        dst[2] = src[2];
    if (n > 3)
        dst[3] = src[3];
    for (int k = 4; k < n; k++)
        dst[k] = src[k];
}

/* One fragment at pixel (x, y): cull, near/far clip on the NDC depth, depth test, shade,
 * blend, and the facing / count bookkeeping. Inline: it runs once per pixel. */
QGL__HOT_INLINE void qgl__fragment(qgl__ctx *c, int x, int y, double zndc, int facing, const float *attr)
{
    const qgl_sw_draw_desc *d = c->d;
    qgl_sw_fb *fb = c->fb;
    if ((d->cull == QGL_SW_CULL_BACK && facing < 0) || (d->cull == QGL_SW_CULL_FRONT && facing > 0))
        return;
    if (!(zndc >= -1.0 && zndc <= 1.0))
        return;
    float zw = (float)(0.5 * zndc + 0.5);
    size_t i = (size_t)y * (size_t)fb->width + (size_t)x;
    if (fb->depth && d->depth != QGL_SW_DEPTH_ALWAYS) {
        float old = fb->depth[i];
        if (d->depth == QGL_SW_DEPTH_LESS ? !(zw < old) : !(zw <= old))
            return;
    }
    int ch = fb->channels;
    float *dst = fb->color + i * (size_t)ch;
    const float *out = attr;
    if (d->shade) {
        if (!d->shade(d->user, attr, d->nattr, facing, c->scratch))
            return;
        out = c->scratch;
    } else if (d->nattr < ch) {
        qgl__copy_small(c->scratch, attr, d->nattr);
        for (int k = d->nattr; k < ch; k++)
            c->scratch[k] = 0;
        out = c->scratch;
    }
    if (d->blend == QGL_SW_BLEND_ADD)
        for (int k = 0; k < ch; k++)
            dst[k] += out[k];
    else
        qgl__copy_small(dst, out, ch);
    if (fb->depth)
        fb->depth[i] = zw;
    if (fb->facing)
        fb->facing[i] = (signed char)facing;
    if (fb->count)
        fb->count[i]++;
    c->fragments++;
}

/* Pixel columns [*x0, *x1] of row Y (a pixel-centre coordinate) that may hold covered pixels:
 * the union of the row's intervals in triangles 012 and 023 (every eq. 12 region lies in
 * one of them), one pixel wider on each side, clamped to the quad's box. 0 when empty. */
int qgl__row_range(const qgl__quad *q, double Y, int *x0, int *x1);
/* For a convex quad: columns [*xa, *xb] within [x0, x1] whose centres are inside all four
 * edges by a pixel's margin (checked exactly at both ends; the edge functions are linear
 * along the row), so eq. (12) needs no evaluation there. 0 when there are none. */
int qgl__row_inner(const qgl__quad *q, double Y, int x0, int x1, int *xa, int *xb);

/* A triangle of 3 vertices, each clip (4 doubles) then nattr attribute doubles. */
void qgl__triangle(qgl__ctx *c, const double *v0, const double *v1, const double *v2, int nattr);
/* Turns a fragment's nvary interpolated values into the draw's attributes; 0 drops it. */
typedef int (*qgl__vary_fn)(void *user, const double *vary, float *attr);
/* The same triangle with nvary values per vertex after clip, interpolated perspective-
 * correctly in double and mapped to attributes by map. */
void qgl__triangle_map(qgl__ctx *c, const double *v0, const double *v1, const double *v2, int nvary,
                       qgl__vary_fn map, void *user);

/* Per-pixel weights for the generic quad scan: fill persp[4] (attribute weights) and *zndc;
 * return 0 to drop the pixel. X, Y are pixel-centre window coordinates. */
typedef int (*qgl__weight_fn)(void *user, const qgl__quad *q, double X, double Y, double persp[4],
                              double *zndc);
void qgl__quad_scan(qgl__ctx *c, const qgl__quad *q, qgl__weight_fn fn, void *user);

/* The methods. */
void qgl__draw_mvc(qgl__ctx *c, const qgl__quad *q);
/* mvc's kernel for a planar quad every corner of which is in front of the eye, with the
 * corners' in-plane coordinates: the in-plane weights (sw_mvc.c). */
void qgl__draw_mvc_plane(qgl__ctx *c, const qgl__quad *q, const double corner[4][2]);
void qgl__draw_mvc64(qgl__ctx *c, const qgl__quad *q);
void qgl__draw_invbilinear(qgl__ctx *c, const qgl__quad *q);
void qgl__draw_projective(qgl__ctx *c, const qgl__quad *q);
void qgl__draw_exact(qgl__ctx *c, const qgl__quad *q);
/* The in-plane methods (sw_plane.c): mvcplane and invbilinearplane rasterize the quad's
 * in-plane cover; mvcpatch weighs the exact reference's hit in the plane. */
void qgl__draw_plane(qgl__ctx *c, int quad);
void qgl__draw_mvcpatch(qgl__ctx *c, const qgl__quad *q, int quad);
/* The bilinear patch's hit at pixel centre (X, Y) (sw_exact.c): parameters, NDC depth and
 * facing of the nearest visible hit; 0 when the ray misses. */
int qgl__patch_hit(const qgl__quad *q, double X, double Y, double uv[2], double *zndc, int *facing);

/* A pixel-centre window coordinate along an axis of n pixels, from the axis' centre (px). */
static inline double qgl__centred(double X, int n)
{
    return X - 0.5 * n;
}

#endif
