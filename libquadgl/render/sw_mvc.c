/* sw_mvc.c: the fast mean value rasterizer (method "mvc"): float, spans of 8 pixels.
 *
 * H&T sec. 4.2 in homogeneous form. With s~_i = (hx_i - X hw_i, hy_i - Y hw_i) (window-
 * homogeneous corners, so no division by w and corners behind the eye need no case), the
 * cross products A_i = s~_i x s~_{i+1} are linear in the pixel position and the dot products
 * D_i = s~_i . s~_{i+1} and squared lengths rho_i^2 = |s~_i|^2 are quadratic. Each row is cut
 * into spans; at a span's first pixel the three families are evaluated exactly (double) and
 * carried to the span's pixel k by their finite differences: A + k dA, D + k (dD + k d2D),
 * rho^2 likewise (the closed form of the forward-difference recurrence, which lets the 8
 * pixels of a span run as SIMD lanes instead of a serial chain, and keeps the rounding of the
 * recurrence bounded by the span length rather than the row's). Per pixel that leaves 4
 * square roots and 10 divisions: t_i = tan(alpha_i / 2) = A / (P + D) when D > 0, else
 * (P - D) / A (P = rho_i rho_{i+1}; the form whose denominator does not cancel), nu_i =
 * (t_{i-1} + t_i) / rho_i (which is H&T's mu_i / w_i), then attributes sum nu a / sum nu and
 * depth sum nu z / sum nu w. Coverage is eq. (12) on the double edge functions shared with
 * every other method. A pixel whose float weights are not finite (its centre on a corner or
 * on an edge line) is handed to qgl_weightsf, which knows the limits. The kernel is compiled
 * for AVX2 and for the baseline and picked at load time (target_clones).
 * The same kernel draws mvcplane's planar quads in front of the eye: there s~_i is
 * q_i W - P, the in-plane corner q_i against the pixel's in-plane position in homogeneous
 * form (P, W) = sum_k E_k (q_k, 1), E_k the edge functions of one of the quad's triangles
 * (its perspective-correct barycentrics, unnormalized), so s~_i = sum_k E_k (q_i - q_k) is
 * linear in the pixel position too; the scale W cancels in the weights, which then are the
 * attributes' weights directly (no perspective division), and sum nu z / sum nu w is still
 * the surface's depth (the in-plane weights reproduce the clip position of a planar quad).
 * Both coordinates of s~ now change along a row, so A gains a quadratic term. */
#include "sw_internal.h"

#include <math.h>
#include <stdint.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("vect-cost-model=dynamic")
#endif

#define SPAN 8

#if defined(__x86_64__) && defined(__GNUC__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#define QGL__CLONES __attribute__((target_clones("avx2", "default")))
#endif
#endif
#ifndef QGL__CLONES
#define QGL__CLONES
#endif

typedef struct span_coef {
    float A0[4], A1[4], A2[4];  /* A_i = A0 + k (A1 + k A2) */
    float D0[4], D1[4], D2[4];  /* D_i = D0 + k (D1 + k D2) */
    float R0[4], R1[4], R2[4];  /* rho_i^2 = R0 + k (R1 + k R2) */
} span_coef;

typedef struct span_out {
    float nu[4][SPAN];
    float inv[SPAN];    /* 1 / sum nu */
    float zndc[SPAN];
    float attr[QGL_SW_MAX_ATTR][SPAN];
} span_out;

/* A planar quad's in-plane form: E_k = a X + b Y + c for the three corners tri[k] of one
 * triangle, and dq[i][k] = scale (q_i - q_tri[k]), the scale a power of two that keeps s~
 * near 1 over the framebuffer (the weights do not depend on it). */
typedef struct plane_form {
    double e[3][3];
    double dq[4][3][2];
    float corner[4][2]; /* for the exact limits of qgl_weights_inplanef */
    int tri[3];
} plane_form;

static const float lane_k[SPAN] = {0, 1, 2, 3, 4, 5, 6, 7};

/* s~_i at the span's first pixel centre (X0, Y), and its change per pixel along the row. */
typedef struct span_src {
    double sx[4], sy[4], dx[4], dy[4];
} span_src;

static void screen_src(const qgl__quad *q, double X0, double Y, span_src *s)
{
    for (int i = 0; i < 4; i++) {
        double w = q->h[i][2];
        s->sx[i] = q->h[i][0] - X0 * w;
        s->sy[i] = q->h[i][1] - Y * w;
        s->dx[i] = -w;
        s->dy[i] = 0;
    }
}

static void plane_src(const plane_form *pf, double X0, double Y, span_src *s)
{
    double E[3];
    for (int k = 0; k < 3; k++)
        E[k] = (pf->e[k][0] * X0 + pf->e[k][1] * Y) + pf->e[k][2];
    for (int i = 0; i < 4; i++) {
        s->sx[i] = s->sy[i] = s->dx[i] = s->dy[i] = 0;
        for (int k = 0; k < 3; k++) {
            s->sx[i] += E[k] * pf->dq[i][k][0];
            s->sy[i] += E[k] * pf->dq[i][k][1];
            s->dx[i] += pf->e[k][0] * pf->dq[i][k][0];
            s->dy[i] += pf->e[k][0] * pf->dq[i][k][1];
        }
    }
}

/* The exact values and differences of A, D and rho^2 along the span. */
static void span_setup(const span_src *s, span_coef *c)
{
    const double *sx = s->sx, *sy = s->sy, *dx = s->dx, *dy = s->dy;
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        c->A0[i] = (float)(sx[i] * sy[j] - sy[i] * sx[j]);
        c->A1[i] = (float)((sx[i] * dy[j] + dx[i] * sy[j]) - (sy[i] * dx[j] + dy[i] * sx[j]));
        c->A2[i] = (float)(dx[i] * dy[j] - dy[i] * dx[j]);
        c->D0[i] = (float)(sx[i] * sx[j] + sy[i] * sy[j]);
        c->D1[i] = (float)((sx[i] * dx[j] + dx[i] * sx[j]) + (sy[i] * dy[j] + dy[i] * sy[j]));
        c->D2[i] = (float)(dx[i] * dx[j] + dy[i] * dy[j]);
        c->R0[i] = (float)(sx[i] * sx[i] + sy[i] * sy[i]);
        c->R1[i] = (float)(2 * (sx[i] * dx[i] + sy[i] * dy[i]));
        c->R2[i] = (float)(dx[i] * dx[i] + dy[i] * dy[i]);
    }
}

/* m ? a : b for a mask m of all ones or all zeros, by bits: a float ?: with a comparison
 * counts as control flow that may trap, which stops the vectorizer under IEEE semantics. */
static inline float select_bits(int32_t m, float a, float b)
{
    uint32_t ua, ub;
    memcpy(&ua, &a, sizeof ua);
    memcpy(&ub, &b, sizeof ub);
    uint32_t r = (ua & (uint32_t)m) | (ub & ~(uint32_t)m);
    float f;
    memcpy(&f, &r, sizeof f);
    return f;
}

/* Square roots of a span's lanes in place. sqrtf sets errno, which keeps the compiler from
 * vectorizing it under the project's flags; the SSE2 instruction does not. */
static inline void lanes_sqrt(float v[SPAN])
{
#if defined(__SSE2__)
    for (int k = 0; k < SPAN; k += 4)
        _mm_storeu_ps(v + k, _mm_sqrt_ps(_mm_loadu_ps(v + k)));
#else
    for (int k = 0; k < SPAN; k++)
        v[k] = sqrtf(v[k]);
#endif
}

/* The weights of the span's pixels: nu, 1 / sum nu, NDC depth and the attributes. */
QGL__CLONES
static void span_weights(const span_coef *s, const float (*corner_attr)[QGL_SW_MAX_ATTR], int nattr,
                         const float z[4], const float w[4], span_out *o)
{
    float r[4][SPAN], t[4][SPAN];
    for (int i = 0; i < 4; i++) {
        for (int k = 0; k < SPAN; k++) {
            float R = s->R0[i] + lane_k[k] * (s->R1[i] + lane_k[k] * s->R2[i]);
            r[i][k] = R > 0 ? R : 0;
        }
        lanes_sqrt(r[i]);
    }
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        for (int k = 0; k < SPAN; k++) {
            float A = s->A0[i] + lane_k[k] * (s->A1[i] + lane_k[k] * s->A2[i]);
            float D = s->D0[i] + lane_k[k] * (s->D1[i] + lane_k[k] * s->D2[i]);
            float P = r[i][k] * r[j][k];
            float diff = P - D, sum = P + D;
            int32_t pos = -(int32_t)(D > 0);
            float num = select_bits(pos, A, diff);
            float den = select_bits(pos, sum, A);
            t[i][k] = num / den;
        }
    }
    for (int i = 0; i < 4; i++) {
        int h = (i + 3) & 3;
        for (int k = 0; k < SPAN; k++)
            o->nu[i][k] = (t[h][k] + t[i][k]) / r[i][k];
    }
    for (int k = 0; k < SPAN; k++) {
        float n0 = o->nu[0][k], n1 = o->nu[1][k], n2 = o->nu[2][k], n3 = o->nu[3][k];
        o->inv[k] = 1.0f / ((n0 + n1) + (n2 + n3));
        o->zndc[k] = ((n0 * z[0] + n1 * z[1]) + (n2 * z[2] + n3 * z[3])) /
                     ((n0 * w[0] + n1 * w[1]) + (n2 * w[2] + n3 * w[3]));
    }
    for (int a = 0; a < nattr; a++) {
        float a0 = corner_attr[0][a], a1 = corner_attr[1][a], a2 = corner_attr[2][a], a3 = corner_attr[3][a];
        for (int k = 0; k < SPAN; k++)
            o->attr[a][k] = ((o->nu[0][k] * a0 + o->nu[1][k] * a1) + (o->nu[2][k] * a2 + o->nu[3][k] * a3)) *
                            o->inv[k];
    }
}

/* Eq. (12) for the span's lanes; facing[k] = +1, -1 or 0. Returns the number covered. */
static int span_cover(const qgl__quad *q, double X0, double Y, int n, signed char facing[SPAN])
{
    unsigned char pos[QGL__NEDGE][SPAN], neg[QGL__NEDGE][SPAN];
    for (int e = 0; e < QGL__NEDGE; e++) {
        const qgl__edge *ed = &q->e[e];
        double a = ed->a, by = ed->b * Y, c = ed->c;
        unsigned char deg = (unsigned char)ed->degenerate, t1 = (unsigned char)ed->tie[1],
                      t0 = (unsigned char)ed->tie[0];
        for (int k = 0; k < SPAN; k++) {
            double v = (a * (X0 + k) + by) + c;
            pos[e][k] = deg | (v > 0) | ((v == 0) & t1);
            neg[e][k] = deg | (v < 0) | ((v == 0) & t0);
        }
    }
    const unsigned char(*p1)[SPAN] = q->f012 > 0 ? pos : neg;
    const unsigned char(*p2)[SPAN] = q->f023 > 0 ? pos : neg, (*m2)[SPAN] = q->f023 > 0 ? neg : pos;
    unsigned char on1 = q->f012 != 0, on2 = q->f023 != 0;
    int count = 0;
    for (int k = 0; k < SPAN; k++) {
        unsigned char c1 = on1 & p1[QGL__E20][k] & p1[QGL__E01][k] & p1[QGL__E12][k] &
                           (p1[QGL__E23][k] | p1[QGL__E30][k]);
        unsigned char c2 = on2 & m2[QGL__E20][k] & p2[QGL__E23][k] & p2[QGL__E30][k] &
                           (p2[QGL__E01][k] | p2[QGL__E12][k]);
        facing[k] = (signed char)(k >= n ? 0 : c1 ? q->f012 : c2 ? q->f023 : 0);
        count += facing[k] != 0;
    }
    return count;
}

/* Clear the culled lanes; returns how many are left. */
static int uncull(const qgl__ctx *c, signed char facing[SPAN])
{
    int left = 0;
    for (int k = 0; k < SPAN; k++) {
        if (facing[k] && qgl__culled(c, facing[k]))
            facing[k] = 0;
        left += facing[k] != 0;
    }
    return left;
}

/* A lane whose float weights came out non-finite: qgl_weightsf's limits instead (for the
 * in-plane form qgl_weights_inplanef's, at the pixel's in-plane position). */
static int lane_fallback(qgl__ctx *c, const qgl__quad *q, const plane_form *pf, const float clipf[4][4], double X,
                         double Y, float *attr, double *zndc)
{
    float persp[4], screen[4];
    int r;
    if (pf) {
        qgl_planef pl;
        double E[3], sum = 0, xy[2] = {0, 0};
        for (int k = 0; k < 3; k++) {
            E[k] = (pf->e[k][0] * X + pf->e[k][1] * Y) + pf->e[k][2];
            sum += E[k];
            xy[0] += E[k] * pf->corner[pf->tri[k]][0];
            xy[1] += E[k] * pf->corner[pf->tri[k]][1];
        }
        for (int i = 0; i < 4; i++)
            pl.corner[i][0] = pf->corner[i][0], pl.corner[i][1] = pf->corner[i][1];
        r = qgl_weights_inplanef(&pl, (float)(xy[0] / sum), (float)(xy[1] / sum), persp);
    } else {
        r = qgl_weightsf(clipf, (float)qgl__centred(X, c->fb->width), (float)qgl__centred(Y, c->fb->height), persp,
                         screen);
    }
    if (r == QGL_NONFINITE)
        return 0;
    const double pd[4] = {persp[0], persp[1], persp[2], persp[3]};
    *zndc = qgl__zndc(q, pd);
    for (int a = 0; a < q->nattr; a++) {
        float v = 0;
        for (int i = 0; i < 4; i++)
            v += persp[i] * q->attr[i * q->nattr + a];
        attr[a] = v;
    }
    return 1;
}

/* A whole span of plain fragments (no shading callback, no blending, no facing or count
 * buffer, depth test LESS, every lane covered with finite weights inside the near/far
 * range): the arithmetic of qgl__fragment, laid out lane by lane so that it vectorizes.
 * Returns 0 when the span does not qualify; the caller then takes the per-lane path. */
static int span_store_plain(qgl__ctx *c, int xs, int y, int n, const signed char facing[SPAN], const span_out *o,
                            int nattr)
{
    const qgl_sw_draw_desc *d = c->d;
    qgl_sw_fb *fb = c->fb;
    if (n != SPAN || d->shade || d->blend == QGL_SW_BLEND_ADD || fb->facing || fb->count || !fb->depth ||
        d->depth != QGL_SW_DEPTH_LESS || nattr != fb->channels)
        return 0;
    int ok = 1;
    for (int k = 0; k < SPAN; k++)
        ok &= facing[k] != 0 && o->inv[k] != 0 && isfinite(o->inv[k]) && o->zndc[k] >= -1.0f && o->zndc[k] <= 1.0f;
    if (!ok)
        return 0;
    size_t i0 = (size_t)y * (size_t)fb->width + (size_t)xs;
    float *dz = fb->depth + i0, *col = fb->color + i0 * (size_t)nattr;
    int written = 0;
    for (int k = 0; k < SPAN; k++) {
        float zw = (float)(0.5 * o->zndc[k] + 0.5);
        if (!(zw < dz[k]))
            continue;
        dz[k] = zw;
        for (int a = 0; a < nattr; a++)
            col[k * nattr + a] = o->attr[a][k];
        written++;
    }
    c->fragments += written;
    return 1;
}

static void draw_spans(qgl__ctx *c, const qgl__quad *q, const plane_form *pf)
{
    float corner_attr[4][QGL_SW_MAX_ATTR], z[4], w[4], clipf[4][4], attr[QGL_SW_MAX_ATTR];
    int nattr = q->nattr;
    for (int i = 0; i < 4; i++) {
        for (int a = 0; a < nattr; a++)
            corner_attr[i][a] = q->attr[i * nattr + a];
        z[i] = (float)q->clip[i][2];
        w[i] = (float)q->clip[i][3];
        for (int k = 0; k < 4; k++)
            clipf[i][k] = (float)q->px[i][k];
    }
    span_src src;
    span_coef s;
    span_out o;
    signed char facing[SPAN];
    if (q->convex && qgl__culled(c, q->convex))
        return;
    for (int y = q->y0; y <= q->y1; y++) {
        double Y = y + 0.5;
        int x0, x1;
        if (!qgl__row_range(q, Y, &x0, &x1))
            continue;
        int xa = 1, xb = 0;
        qgl__row_inner(q, Y, x0, x1, &xa, &xb);
        for (int xs = x0; xs <= x1; xs += SPAN) {
            int n = x1 - xs + 1 < SPAN ? x1 - xs + 1 : SPAN;
            double X0 = xs + 0.5;
            if (xs >= xa && xs + n - 1 <= xb) {
                for (int k = 0; k < SPAN; k++)
                    facing[k] = (signed char)(k < n ? q->convex : 0);
            } else if (!span_cover(q, X0, Y, n, facing) || !uncull(c, facing)) {
                continue;
            }
            if (pf)
                plane_src(pf, X0, Y, &src);
            else
                screen_src(q, X0, Y, &src);
            span_setup(&src, &s);
            span_weights(&s, (const float(*)[QGL_SW_MAX_ATTR])corner_attr, nattr, z, w, &o);
            if (span_store_plain(c, xs, y, n, facing, &o, nattr))
                continue;
            for (int k = 0; k < n; k++) {
                if (!facing[k])
                    continue;
                double zndc = o.zndc[k];
                if (isfinite(o.inv[k]) && isfinite(o.zndc[k]) && o.inv[k] != 0) {
                    for (int a = 0; a < nattr; a++)
                        attr[a] = o.attr[a][k];
                } else if (!lane_fallback(c, q, pf, (const float(*)[4])clipf, X0 + k, Y, attr, &zndc)) {
                    continue;
                }
                qgl__fragment(c, xs + k, y, zndc, facing[k], attr);
            }
        }
    }
}

void qgl__draw_mvc(qgl__ctx *c, const qgl__quad *q)
{
    draw_spans(c, q, NULL);
}

/* The in-plane form of a planar quad in front of the eye: the triangle (0, 1, 2) or (0, 2, 3)
 * whose screen determinant is larger (either interpolates the plane exactly; the larger is
 * the better conditioned), its edge functions, and the scaled corner differences. */
static void plane_form_setup(const qgl__quad *q, const qgl_sw_fb *fb, const double corner[4][2], plane_form *pf)
{
    double d012 = fabs(qgl__det3(q->h[0], q->h[1], q->h[2])), d023 = fabs(qgl__det3(q->h[0], q->h[2], q->h[3]));
    static const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
    const int *t = tris[d023 > d012];
    double emax = 0, qmax = 0;
    for (int k = 0; k < 3; k++) {
        qgl__edge e;
        pf->tri[k] = t[k];
        qgl__edge_setup(&e, q->h[t[(k + 1) % 3]], q->h[t[(k + 2) % 3]]);
        pf->e[k][0] = e.a, pf->e[k][1] = e.b, pf->e[k][2] = e.c;
        emax = fmax(emax, fabs(e.a) * fb->width + fabs(e.b) * fb->height + fabs(e.c));
    }
    for (int i = 0; i < 4; i++) {
        pf->corner[i][0] = (float)corner[i][0];
        pf->corner[i][1] = (float)corner[i][1];
        for (int k = 0; k < 3; k++)
            qmax = fmax(qmax, fmax(fabs(corner[i][0] - corner[t[k]][0]), fabs(corner[i][1] - corner[t[k]][1])));
    }
    int ee = 0, eq = 0;
    frexp(emax, &ee);
    frexp(qmax, &eq);
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 2; j++)
                pf->dq[i][k][j] = ldexp(corner[i][j] - corner[t[k]][j], -ee - eq);
}

void qgl__draw_mvc_plane(qgl__ctx *c, const qgl__quad *q, const double corner[4][2])
{
    plane_form pf;
    plane_form_setup(q, c->fb, corner, &pf);
    draw_spans(c, q, &pf);
}
