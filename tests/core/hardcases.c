/* hardcases.c: the hard-case suite and the __float128 reference (see hardcases.h).
 *
 * Cases are generated around a few base quads (in clip space) so that every category of
 * the foundation issue appears for convex, concave, bow-tie and perspective quads alike.
 * Points "near" a feature are placed at a relative distance d (times the quad's size) from
 * it; in exactly representable configurations (axis-aligned edges, w = 1) d = 0 is exactly
 * on it. */
#include <math.h>
#include <quadmath.h>
#include <stdlib.h>
#include <string.h>
#include <quadgl/quadgl.h>
#include "hardcases.h"

typedef __float128 Q;

/* ---- the reference --------------------------------------------------------------------- */

static Q qabs(Q a)
{
    return a < 0 ? -a : a;
}

/* Projected-area degeneracy, as the library defines it, with a far tighter tolerance. */
static int ref_degenerate(const double clip[4][4])
{
    int pos = 0, neg = 0;
    for (int i = 0; i < 4; i++) {
        pos += clip[i][3] > 0;
        neg += clip[i][3] < 0;
    }
    if (pos == 4 || neg == 4) {
        for (int i = 0; i < 4; i++) {
            const double *a = clip[i], *b = clip[(i + 1) & 3], *c = clip[(i + 2) & 3];
            Q ax = (Q)a[0] / a[3], ay = (Q)a[1] / a[3];
            Q bx = (Q)b[0] / b[3] - ax, by = (Q)b[1] / b[3] - ay;
            Q cx = (Q)c[0] / c[3] - ax, cy = (Q)c[1] / c[3] - ay;
            Q lb = bx * bx + by * by, lc = cx * cx + cy * cy;
            Q scale = lb > lc ? lb : lc;
            if (scale > 0 && qabs(bx * cy - by * cx) > 1e-25Q * scale)
                return 0;
        }
        return 1;
    }
    for (int i = 0; i < 4; i++) {
        const double *a = clip[i], *b = clip[(i + 1) & 3], *c = clip[(i + 2) & 3];
        Q det = (Q)a[0] * ((Q)b[1] * c[3] - (Q)b[3] * c[1]) - (Q)a[1] * ((Q)b[0] * c[3] - (Q)b[3] * c[0]) +
                (Q)a[3] * ((Q)b[0] * c[1] - (Q)b[1] * c[0]);
        Q na = (Q)a[0] * a[0] + (Q)a[1] * a[1] + (Q)a[3] * a[3];
        Q nb = (Q)b[0] * b[0] + (Q)b[1] * b[1] + (Q)b[3] * b[3];
        Q nc = (Q)c[0] * c[0] + (Q)c[1] * c[1] + (Q)c[3] * c[3];
        if (qabs(det) > 1e-25Q * sqrtq(na * nb * nc))
            return 0;
    }
    return 1;
}

int hc_reference(const double clip[4][4], double x, double y, double persp[4], double screen[4])
{
    Q s[4][2], rho[4], t[4], nu[4], w[4], out_p[4], out_s[4];
    int finite = isfinite(x) && isfinite(y);
    for (int i = 0; i < 16; i++)
        finite = finite && isfinite(clip[i / 4][i % 4]);
    for (int i = 0; i < 4; i++)
        persp[i] = screen[i] = 0.25;
    if (!finite)
        return QGL_NONFINITE;
    int degenerate = ref_degenerate(clip);
    for (int i = 0; i < 4; i++) {
        w[i] = clip[i][3];
        s[i][0] = (Q)clip[i][0] - (Q)x * w[i];
        s[i][1] = (Q)clip[i][1] - (Q)y * w[i];
        rho[i] = sqrtq(s[i][0] * s[i][0] + s[i][1] * s[i][1]);
    }
    int code = QGL_INSIDE, vert = -1, edge = -1, nedge = 0;
    for (int i = 0; i < 4; i++)
        if (rho[i] == 0 && vert < 0)
            vert = i;
    if (vert < 0 && rho[0] + rho[1] + rho[2] + rho[3] == 0)
        return QGL_DEGENERATE;
    if (vert >= 0) {
        int n = 0;
        for (int i = 0; i < 4; i++)
            n += rho[i] == 0;
        for (int i = 0; i < 4; i++)
            out_p[i] = out_s[i] = rho[i] == 0 ? 1.0Q / n : 0;
    } else {
        for (int i = 0; i < 4; i++) {
            int j = (i + 1) & 3;
            Q a = s[i][0] * s[j][1] - s[i][1] * s[j][0];
            Q d = s[i][0] * s[j][0] + s[i][1] * s[j][1];
            Q p = rho[i] * rho[j];
            t[i] = d > 0 ? a / (p + d) : a == 0 ? 0 : (p - d) / a;
            if (a == 0 && d < 0) {
                edge = i;
                nedge++;
            }
        }
        if (nedge) {
            for (int i = 0; i < 4; i++)
                out_p[i] = out_s[i] = 0;
            for (int i = 0; i < 4; i++) {
                int j = (i + 1) & 3;
                Q a = s[i][0] * s[j][1] - s[i][1] * s[j][0];
                Q d = s[i][0] * s[j][0] + s[i][1] * s[j][1];
                if (!(a == 0 && d < 0))
                    continue;
                Q sum = rho[i] + rho[j], ws = w[i] * rho[j] + w[j] * rho[i];
                out_p[i] += rho[j] / sum / nedge;
                out_p[j] += rho[i] / sum / nedge;
                out_s[i] += (ws != 0 ? w[i] * rho[j] / ws : rho[j] / sum) / nedge;
                out_s[j] += (ws != 0 ? w[j] * rho[i] / ws : rho[i] / sum) / nedge;
            }
        } else {
            Q sum = 0, wsum = 0;
            int pos = 0, neg = 0;
            for (int i = 0; i < 4; i++) {
                nu[i] = (t[(i + 3) & 3] + t[i]) / rho[i];
                sum += nu[i];
                wsum += w[i] * nu[i];
                pos |= nu[i] > 0;
                neg |= nu[i] < 0;
            }
            code = pos && neg ? QGL_OUTSIDE : (pos || neg) ? QGL_INSIDE : QGL_OUTSIDE;
            for (int i = 0; i < 4; i++) {
                out_p[i] = sum != 0 ? nu[i] / sum : 0;
                out_s[i] = wsum != 0 ? w[i] * nu[i] / wsum : out_p[i];
            }
        }
    }
    (void)edge;
    for (int i = 0; i < 4; i++) {
        persp[i] = (double)out_p[i];
        screen[i] = (double)out_s[i];
    }
    return degenerate ? QGL_DEGENERATE : code;
}

/* ---- the suite ------------------------------------------------------------------------- */

typedef struct builder {
    hc_case *c;
    int n, cap;
    unsigned long long rng;
} builder;

static double rnd(builder *b)
{
    b->rng ^= b->rng << 13;
    b->rng ^= b->rng >> 7;
    b->rng ^= b->rng << 17;
    return (double)(b->rng >> 11) / 9007199254740992.0;
}

static void add(builder *b, const double clip[4][4], double x, double y, const char *group, double dist)
{
    if (b->n == b->cap) {
        b->cap = b->cap ? 2 * b->cap : 1024;
        b->c = realloc(b->c, (size_t)b->cap * sizeof *b->c);
    }
    hc_case *c = &b->c[b->n++];
    memcpy(c->clip, clip, sizeof c->clip);
    c->p[0] = x;
    c->p[1] = y;
    c->group = group;
    c->dist = dist;
}

/* A 2D quad (w = 1) as clip corners, scaled by w (same screen quad, other clip values). */
static void quad2d(double clip[4][4], const double v[4][2], double w)
{
    for (int i = 0; i < 4; i++) {
        clip[i][0] = v[i][0] * w;
        clip[i][1] = v[i][1] * w;
        clip[i][2] = 0.5 * w;
        clip[i][3] = w;
    }
}

/* Interior points: projections of random positive combinations of the clip corners. */
static void interior(builder *b, const double clip[4][4], const char *group, int count)
{
    for (int k = 0; k < count; k++) {
        double c[4], X = 0, Y = 0, W = 0;
        for (int i = 0; i < 4; i++)
            c[i] = 0.05 + rnd(b);
        for (int i = 0; i < 4; i++) {
            X += c[i] * clip[i][0];
            Y += c[i] * clip[i][1];
            W += c[i] * clip[i][3];
        }
        if (W != 0)
            add(b, clip, X / W, Y / W, group, -1);
    }
}

static const double dists[] = {1e-3, 1e-5, 1e-7, 0};

/* Points near and on the edges (both sides) and corners, and on edge extensions, of a quad
 * whose corners all have w > 0. */
static void boundary(builder *b, const double clip[4][4], const char *group)
{
    double v[4][2], size = 0;
    for (int i = 0; i < 4; i++) {
        v[i][0] = clip[i][0] / clip[i][3];
        v[i][1] = clip[i][1] / clip[i][3];
    }
    for (int i = 0; i < 4; i++)
        size = fmax(size, hypot(v[(i + 2) & 3][0] - v[i][0], v[(i + 2) & 3][1] - v[i][1]));
    for (int i = 0; i < 4; i++) {
        const double *a = v[i], *c = v[(i + 1) & 3];
        double ex = c[0] - a[0], ey = c[1] - a[1], len = hypot(ex, ey);
        if (len == 0)
            continue;
        double nx = -ey / len, ny = ex / len;
        for (int k = 0; k < 4; k++) {
            double d = dists[k] * size;
            for (int side = -1; side <= 1; side += 2) {
                double u = 0.1 + 0.8 * rnd(b);
                add(b, clip, a[0] + u * ex + side * d * nx, a[1] + u * ey + side * d * ny, group, dists[k]);
                add(b, clip, a[0] + 0.5 * ex + side * d * nx, a[1] + 0.5 * ey + side * d * ny, group, dists[k]);
                double ang = 6.283185307179586 * rnd(b);
                add(b, clip, a[0] + d * cos(ang), a[1] + d * sin(ang), group, dists[k]);
            }
            /* Beyond the corner on the edge's outer extension. */
            add(b, clip, c[0] + (dists[k] + 1e-9) * 1e3 * ex, c[1] + (dists[k] + 1e-9) * 1e3 * ey, group, -1);
        }
    }
}

/* A square with axis-aligned edges at (ox, oy) of side h: exactly representable points on
 * edges, corners and edge extensions. */
static void exact_square(builder *b, double ox, double oy, double h, double w, const char *group)
{
    const double v[4][2] = {{ox, oy}, {ox + h, oy}, {ox + h, oy + h}, {ox, oy + h}};
    double clip[4][4];
    quad2d(clip, v, w);
    for (int i = 0; i < 4; i++)
        add(b, clip, v[i][0], v[i][1], group, 0);
    const double us[] = {0.25, 0.5, 0.75, 0.125};
    for (int k = 0; k < 4; k++) {
        double u = us[k] * h;
        add(b, clip, ox + u, oy, group, 0);
        add(b, clip, ox + h, oy + u, group, 0);
        add(b, clip, ox + u, oy + h, group, 0);
        add(b, clip, ox, oy + u, group, 0);
        add(b, clip, ox + h + u, oy, group, -1); /* edge extensions */
        add(b, clip, ox, oy - u, group, -1);
    }
    interior(b, clip, group, 16);
    boundary(b, clip, group);
}

/* Clip corners of the 3D quad P seen by a camera at the origin looking down -z (w = -z). */
static void project(double clip[4][4], const double P[4][3])
{
    for (int i = 0; i < 4; i++) {
        clip[i][0] = 1.5 * P[i][0];
        clip[i][1] = 1.5 * P[i][1];
        clip[i][2] = -1.2 * P[i][2] - 2.2;
        clip[i][3] = -P[i][2];
    }
}

static void shapes(builder *b)
{
    static const double convex[4][2] = {{-0.6, -0.5}, {0.7, -0.4}, {0.8, 0.6}, {-0.5, 0.7}};
    static const double concave[4][2] = {{-0.6, -0.6}, {0.7, -0.5}, {0.0, -0.1}, {-0.5, 0.7}};
    static const double bowtie[4][2] = {{-0.5, -0.5}, {0.5, 0.5}, {0.5, -0.5}, {-0.5, 0.5}};
    static const double collapsed[4][2] = {{-0.5, -0.5}, {0.5, 0.5}, {0.5, 0.5}, {-0.5, 0.5}};
    static const double collinear3[4][2] = {{-0.5, -0.5}, {0.0, -0.5}, {0.5, -0.5}, {-0.5, 0.5}};
    static const double thin[4][2] = {{-0.5, -1e-4}, {0.5, -1e-4}, {0.5, 1e-4}, {-0.5, 1e-4}};
    double clip[4][4];
    for (int rot = 0; rot < 4; rot++) {
        double v[4][2];
        for (int i = 0; i < 4; i++)
            memcpy(v[i], convex[(i + rot) & 3], sizeof v[i]);
        quad2d(clip, v, 1);
        interior(b, clip, "convex", 24);
        boundary(b, clip, "convex");
        quad2d(clip, v, -2); /* all w < 0: the same screen quad */
        interior(b, clip, "w<0", 24);
        boundary(b, clip, "w<0");
        for (int i = 0; i < 4; i++)
            memcpy(v[i], concave[(i + rot) & 3], sizeof v[i]);
        quad2d(clip, v, 1);
        interior(b, clip, "concave", 24);
        boundary(b, clip, "concave");
    }
    quad2d(clip, bowtie, 1);
    interior(b, clip, "bow-tie", 24);
    boundary(b, clip, "bow-tie");
    const double cross[] = {1e-3, 1e-5, 1e-7, 0};
    for (int k = 0; k < 4; k++) /* around the crossing point, in the four lobes' directions */
        for (int q = 0; q < 4; q++)
            add(b, clip, cross[k] * (q & 1 ? 1 : -1), cross[k] * (q & 2 ? 1 : -1), "bow-tie-crossing", cross[k]);
    add(b, clip, 0.0, 1e-7, "bow-tie-crossing", 1e-7);
    quad2d(clip, collapsed, 1);
    interior(b, clip, "collapsed", 24);
    boundary(b, clip, "collapsed");
    quad2d(clip, collinear3, 1);
    interior(b, clip, "collinear", 24);
    boundary(b, clip, "collinear");
    quad2d(clip, thin, 1);
    interior(b, clip, "thin", 24);
}

static void degenerate_quads(builder *b)
{
    static const double line[4][2] = {{-0.5, -0.5}, {0.0, 0.0}, {0.25, 0.25}, {0.5, 0.5}};
    static const double point[4][2] = {{0.3, 0.3}, {0.3, 0.3}, {0.3, 0.3}, {0.3, 0.3}};
    double clip[4][4];
    quad2d(clip, line, 1);
    add(b, clip, 0.1, 0.1, "zero-area", 0);
    add(b, clip, 0.1, -0.1, "zero-area", -1);
    quad2d(clip, point, 1);
    add(b, clip, 0.3, 0.3, "zero-area", 0);
    add(b, clip, 0.0, 0.0, "zero-area", -1);
    memset(clip, 0, sizeof clip);
    add(b, clip, 0.0, 0.0, "zero-area", -1);
}

static void perspective(builder *b)
{
    static const double tilted[4][3] = {{-1, -1, -1.2}, {1, -1, -1.2}, {1, 1, -6}, {-1, 1, -6}};
    static const double twisted[4][3] = {{-1, -1, -2}, {1, -1, -3}, {1, 1, -2}, {-1, 1, -4}};
    double clip[4][4];
    project(clip, tilted);
    interior(b, clip, "perspective", 40);
    boundary(b, clip, "perspective");
    project(clip, twisted);
    interior(b, clip, "perspective", 40);
    boundary(b, clip, "perspective");
    /* One corner approaching the eye plane from in front and from behind, then crossing. */
    static const double ws[] = {1e-3, 1e-8, 1e-15, 1e-300, 0, -1e-300, -1e-15, -1e-8, -1e-3, -0.5};
    for (int k = 0; k < 10; k++) {
        double P[4][3] = {{-1, -1, -2}, {1, -1, -2}, {1, 1, -2}, {-0.5, 0.5, 0}};
        project(clip, P);
        clip[3][3] = ws[k];
        interior(b, clip, ws[k] > 0 ? "w->0+" : "w->0-", 40);
    }
    static const double crossing[4][3] = {{-1, -1, -3}, {1, -1, -3}, {1, 1, 2}, {-1, 1, 2}};
    project(clip, crossing);
    interior(b, clip, "eye-plane", 60);
}

static void scales(builder *b)
{
    exact_square(b, -0.5, -0.5, 1.0, 1, "axis");
    exact_square(b, 1e6, 1e6, 1.0 / 16384, 1, "far-tiny");
    exact_square(b, 1e6, -1e6, 1.0 / 16384, 4, "far-tiny");
    exact_square(b, 0.0, 0.0, 1e-7, 1, "tiny");
    exact_square(b, 0.0, 0.0, 1e-7, 3, "tiny");
    exact_square(b, -3e5, 2e5, 1e5, 1, "huge");
    double clip[4][4];
    static const double v[4][2] = {{1e6, 1e6}, {1e6 + 1e-4, 1e6}, {1e6 + 1.2e-4, 1e6 + 0.9e-4}, {1e6 - 1e-5, 1e6 + 1e-4}};
    quad2d(clip, v, 3);
    interior(b, clip, "far-tiny", 24);
    boundary(b, clip, "far-tiny");
}

static void nonfinite(builder *b)
{
    static const double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    double clip[4][4];
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 3; k++) {
        quad2d(clip, sq, 1);
        add(b, clip, bad[k], 0.5, "non-finite", -1);
        for (int c = 0; c < 4; c++) {
            quad2d(clip, sq, 1);
            clip[1][c] = bad[k];
            add(b, clip, 0.5, 0.5, "non-finite", -1);
        }
    }
}

int hc_build(hc_case **out)
{
    builder b = {0};
    b.rng = 0x9e3779b97f4a7c15ull;
    shapes(&b);
    degenerate_quads(&b);
    perspective(&b);
    scales(&b);
    nonfinite(&b);
    *out = b.c;
    return b.n;
}

void hc_to_float(const hc_case *c, float clip[4][4], float p[2])
{
    for (int i = 0; i < 16; i++)
        clip[i / 4][i % 4] = (float)c->clip[i / 4][i % 4];
    p[0] = (float)c->p[0];
    p[1] = (float)c->p[1];
}
