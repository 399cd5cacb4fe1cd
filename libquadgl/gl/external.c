/* external.c: the visible part of a quad with a corner behind the eye, as convex pieces.
 *
 * With corners on both sides of the eye plane the screen quad is H&T's external quad (sec.
 * 3.2): in the projective plane of the homogeneous corners h_i = (x_i, y_i, w_i) it is an
 * ordinary quad, and a pixel p lies in it where eq. 12 holds, either facing, on the edge
 * functions E_ij(P) = det(h_i, h_j, P) of its ray P = (p, 1). Those are linear in clip space,
 * and so is every plane of the view volume (-w <= x, y, z <= w). Either split of a quad
 * covers it, each of its points once (the split's triangles, taken in clip space, are the
 * projective triangles), so the visible part of the quad's surface is each triangle of the
 * split cut by the quad's region and by the view volume: eq. 12 falls into four convex
 * parts per facing (by the signs of the diagonal E_20 and of the edges that the "or" joins),
 * and each cut is a convex polygon clipped plane by plane (Sutherland-Hodgman). Where the
 * projective quad is convex (all four corner turns det(h_{i-1}, h_i, h_{i+1}) of one sign)
 * the split is its exact cover and only the view volume cuts. A vertex is kept as the four
 * corner weights of its clip position sum cw_c C_c; the transform is linear on homogeneous
 * positions, so the same weights give its homogeneous object position, a point of the
 * split's own triangle. Every piece lies in the view volume: its vertices have w >= 0. */
#include <math.h>
#include <string.h>

#include "gl_internal.h"

/* A half-space l . C >= 0 of clip space, as its value l . C_c at each corner. */
typedef struct half {
    double at[4];
} half;

static double value(const half *h, const double cw[4])
{
    return cw[0] * h->at[0] + cw[1] * h->at[1] + cw[2] * h->at[2] + cw[3] * h->at[3];
}

/* Clip the polygon p by h (Sutherland-Hodgman); the result replaces it. */
static void clip_by(qgl__piece *p, const half *h)
{
    qgl__piece out;
    out.n = 0;
    for (int i = 0; i < p->n; i++) {
        const double *a = p->cw[i], *b = p->cw[(i + 1) % p->n];
        double fa = value(h, a), fb = value(h, b);
        if (fa >= 0 && out.n < QGL__PIECE_VERTS)
            memcpy(out.cw[out.n++], a, sizeof out.cw[0]);
        if ((fa < 0) != (fb < 0) && out.n < QGL__PIECE_VERTS) {
            double t = fa / (fa - fb);
            for (int c = 0; c < 4; c++)
                out.cw[out.n][c] = a[c] + t * (b[c] - a[c]);
            out.n++;
        }
    }
    *p = out;
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The edge functions E_01, E_12, E_23, E_30, E_20 at the corners (each corner's h scaled to
 * at most 1 first: a positive scale keeps every sign), and whether the projective quad is
 * strictly convex. */
static int edges(const double clip[4][4], half e[5])
{
    double h[4][3], n[3];
    for (int i = 0; i < 4; i++) {
        double m = fmax(fmax(fabs(clip[i][0]), fabs(clip[i][1])), fabs(clip[i][3]));
        double s = m > 0 ? 1 / m : 1;
        h[i][0] = clip[i][0] * s, h[i][1] = clip[i][1] * s, h[i][2] = clip[i][3] * s;
    }
    static const int ends[5][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {2, 0}};
    for (int k = 0; k < 5; k++) {
        cross3(h[ends[k][0]], h[ends[k][1]], n);
        for (int c = 0; c < 4; c++) {
            const double P[3] = {clip[c][0], clip[c][1], clip[c][3]};
            e[k].at[c] = dot3(n, P);
        }
    }
    int pos = 0, neg = 0;
    for (int i = 0; i < 4; i++) {
        cross3(h[i], h[(i + 1) & 3], n);
        double t = dot3(h[(i + 3) & 3], n);
        pos += t > 0, neg += t < 0;
    }
    return pos == 4 || neg == 4;
}

/* The convex parts of eq. 12 (front facing): edge indices into edges()'s list with the sign
 * each must have (0 ends a part). Back facing is the same with every sign turned. */
static const signed char parts[4][6] = {
    {5, 1, 2, 3, 0, 0},     /* E20 >= 0, E01, E12, E23 >= 0 */
    {5, 1, 2, -3, 4, 0},    /* E20 >= 0, E01, E12 >= 0, E23 <= 0, E30 >= 0 */
    {-5, 3, 4, 1, 0, 0},    /* E20 <= 0, E23, E30, E01 >= 0 */
    {-5, 3, 4, -1, 2, 0},   /* E20 <= 0, E23, E30 >= 0, E01 <= 0, E12 >= 0 */
};

/* The view volume's six planes. */
static void volume(const double clip[4][4], half v[6])
{
    for (int k = 0; k < 6; k++)
        for (int c = 0; c < 4; c++)
            v[k].at[c] = clip[c][3] + (k & 1 ? -clip[c][k >> 1] : clip[c][k >> 1]);
}

/* Add triangle t cut by the listed part of eq. 12 (NULL: none) and the volume. */
static int add_piece(const int t[3], const half e[5], const signed char *part, int facing, const half vol[6],
                     qgl__piece *out, int n, int max)
{
    qgl__piece p;
    p.n = 3;
    for (int k = 0; k < 3; k++) {
        memset(p.cw[k], 0, sizeof p.cw[k]);
        p.cw[k][t[k]] = 1;
    }
    for (int k = 0; part && k < 6 && part[k] && p.n >= 3; k++) {
        half h = e[(part[k] < 0 ? -part[k] : part[k]) - 1];
        double s = part[k] < 0 ? -facing : facing;
        for (int c = 0; c < 4; c++)
            h.at[c] *= s;
        clip_by(&p, &h);
    }
    for (int k = 0; k < 6 && p.n >= 3; k++)
        clip_by(&p, &vol[k]);
    if (p.n < 3 || n >= max)
        return n;
    out[n] = p;
    return n + 1;
}

int qgl__external_pieces(const double clip[4][4], int diag, qgl__piece *out, int max)
{
    static const int split[2][2][3] = {{{0, 1, 2}, {0, 2, 3}}, {{0, 1, 3}, {1, 2, 3}}};
    half e[5], vol[6];
    int convex = edges(clip, e), n = 0;
    volume(clip, vol);
    for (int t = 0; t < 2; t++) {
        const int *tri = split[diag & 1][t];
        if (convex) {
            n = add_piece(tri, e, NULL, 1, vol, out, n, max);
            continue;
        }
        for (int facing = 1; facing >= -1; facing -= 2)
            for (int k = 0; k < 4; k++)
                n = add_piece(tri, e, parts[k], facing, vol, out, n, max);
    }
    return n;
}
