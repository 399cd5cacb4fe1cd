/* Tests of qgl_classify, qgl_classify_clip and qgl_inside against independent references.
 *
 * The reference for "inside" is the winding number of the closed corner path (Sunday's
 * crossing rule, long double): +1 in a counter-clockwise region, -1 in a clockwise one, 0
 * outside. Every shape is checked in its 4 rotations and 2 mirror images, at unit size, at
 * 1e6 with size 1e-4, and at 1e150: the kind, orientation, reflex corner and crossing edge
 * must transform as the shape does; on a dense grid (points within 1e-9 of the size from an
 * edge skipped) every point of winding w != 0 lies in exactly one cover triangle, whose
 * orientation is sign(w), and points of w = 0 lie in none; qgl_inside returns sign(w). */
#include <quadgl/quadgl.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"

static long double is_left(const double a[2], const double b[2], const double p[2])
{
    return ((long double)b[0] - a[0]) * ((long double)p[1] - a[1]) -
           ((long double)p[0] - a[0]) * ((long double)b[1] - a[1]);
}

static int winding(const double (*v)[2], int n, const double p[2])
{
    int w = 0;
    for (int i = 0; i < n; i++) {
        const double *a = v[i], *b = v[(i + 1) % n];
        if (a[1] <= p[1]) {
            if (b[1] > p[1] && is_left(a, b, p) > 0)
                w++;
        } else if (b[1] <= p[1] && is_left(a, b, p) < 0) {
            w--;
        }
    }
    return w;
}

/* Distance from p to segment ab (long double). */
static long double seg_dist(const double a[2], const double b[2], const double p[2])
{
    long double dx = (long double)b[0] - a[0], dy = (long double)b[1] - a[1];
    long double px = (long double)p[0] - a[0], py = (long double)p[1] - a[1];
    long double l2 = dx * dx + dy * dy, t = l2 > 0 ? (px * dx + py * dy) / l2 : 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    long double ex = px - t * dx, ey = py - t * dy;
    return sqrtl(ex * ex + ey * ey);
}

/* Strictly inside triangle (a, b, c) of either orientation: returns its orientation or 0. */
static int in_triangle(const double a[2], const double b[2], const double c[2], const double p[2])
{
    long double o = is_left(a, b, c), e0 = is_left(a, b, p), e1 = is_left(b, c, p), e2 = is_left(c, a, p);
    if (o > 0 && e0 > 0 && e1 > 0 && e2 > 0)
        return 1;
    if (o < 0 && e0 < 0 && e1 < 0 && e2 < 0)
        return -1;
    return 0;
}

typedef struct shape {
    const char *name;
    double v[4][2];
    int kind, orientation, reflex, cross_edge, ntri;
} shape;

static const shape shapes[] = {
    {"square", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, QGL_QUAD_CONVEX, 1, -1, -1, 2},
    {"trapezoid", {{0, 0}, {4, 0}, {3, 1}, {1, 1}}, QGL_QUAD_CONVEX, 1, -1, -1, 2},
    {"kite", {{0, 0}, {1, -1}, {3, 0}, {1, 1}}, QGL_QUAD_CONVEX, 1, -1, -1, 2},
    {"arrow r2", {{0, 0}, {2, 1}, {0.5, 0.5}, {1, 2}}, QGL_QUAD_CONCAVE, 1, 2, -1, 2},
    {"dart r1", {{0, 0}, {0.3, 0.4}, {2, 2}, {-1, 3}}, QGL_QUAD_CONCAVE, 1, 1, -1, 2},
    {"bowtie 01x23", {{0, 0}, {2, 2}, {2, 0}, {0, 2}}, QGL_QUAD_BOWTIE, 0, -1, 0, 2},
    {"bowtie 12x30", {{0, 0}, {2, 0}, {0, 2}, {2, 3}}, QGL_QUAD_BOWTIE, 0, -1, 1, 2},
    {"bowtie lopsided", {{0, 0}, {5, 0.2}, {0.1, 1}, {4, -3}}, QGL_QUAD_BOWTIE, 0, -1, 0, 2},
    {"collapsed 01", {{0, 0}, {0, 0}, {1, 0}, {0, 1}}, QGL_QUAD_CONVEX, 1, -1, -1, 1},
    {"straight corner 1", {{0, 0}, {1, 0}, {2, 0}, {0, 1}}, QGL_QUAD_CONVEX, 1, -1, -1, 1},
    {"spike at 1", {{0, 0}, {3, 0}, {2, 0}, {0, 1}}, QGL_QUAD_CONVEX, 1, -1, -1, 1},
    {"touching bowtie", {{0, 0}, {1, 0}, {1, 1}, {0.5, 0}}, QGL_QUAD_CONVEX, 1, -1, -1, 1},
    {"collinear", {{0, 0}, {1, 1}, {3, 3}, {2, 2}}, QGL_QUAD_DEGENERATE, 0, -1, -1, 0},
    {"point", {{5, 5}, {5, 5}, {5, 5}, {5, 5}}, QGL_QUAD_DEGENERATE, 0, -1, -1, 0},
    {"thin 1e-8", {{0, 0}, {1, 0}, {1, 1e-8}, {0, 2e-8}}, QGL_QUAD_CONVEX, 1, -1, -1, 2},
    {"thin concave", {{0, 0}, {1, 0}, {0.5, 1e-7}, {0, 1e-6}}, QGL_QUAD_CONCAVE, 1, 2, -1, 2},
};

/* Apply rotation r (corner i <- corner i+r), mirror (x -> -x), then scale and offset. */
static void transform(const shape *s, int r, int mirror, double scale, double off, double v[4][2])
{
    for (int i = 0; i < 4; i++) {
        const double *p = s->v[(i + r) & 3];
        v[i][0] = off + scale * (mirror ? -p[0] : p[0]);
        v[i][1] = off + scale * p[1];
    }
}

static void tri_corner(const double v[4][2], const qgl_cover *c, int k, int j, double out[2])
{
    int idx = c->tri[k][j];
    out[0] = idx == 4 ? c->cross[0] : v[idx][0];
    out[1] = idx == 4 ? c->cross[1] : v[idx][1];
}

/* Grid of n x n points over the bounding box (slightly enlarged). */
static void check_cover_grid(const char *name, const double v[4][2], const qgl_cover *c, int n)
{
    double lo[2] = {v[0][0], v[0][1]}, hi[2] = {v[0][0], v[0][1]};
    for (int i = 1; i < 4; i++)
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], v[i][k]);
            hi[k] = fmax(hi[k], v[i][k]);
        }
    double size = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    int bad = 0, inside = 0;
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) {
            double p[2] = {lo[0] - 0.05 * size + 1.1 * size * (a + 0.37) / n,
                           lo[1] - 0.05 * size + 1.1 * size * (b + 0.61) / n};
            long double dmin = INFINITY;
            for (int i = 0; i < 4; i++)
                dmin = fminl(dmin, seg_dist(v[i], v[(i + 1) & 3], p));
            if (dmin < 1e-9 * size)
                continue;
            int w = winding(v, 4, p), hits = 0, sgn = 0;
            for (int k = 0; k < c->ntri; k++) {
                double t[3][2];
                for (int j = 0; j < 3; j++)
                    tri_corner(v, c, k, j, t[j]);
                int s = in_triangle(t[0], t[1], t[2], p);
                if (s) {
                    hits++;
                    sgn = s;
                }
            }
            int expect = w != 0;
            inside += expect;
            if (hits != expect || (expect && sgn != (w > 0 ? 1 : -1)))
                bad++;
            int in = qgl_inside(v, p[0], p[1]);
            CHECK(in == (w > 0) - (w < 0), "%s: qgl_inside(%.17g, %.17g) = %d, winding %d", name, p[0], p[1], in, w);
        }
    CHECK(bad == 0, "%s: %d grid points covered wrongly (%d inside)", name, bad, inside);
}

static void check_shape(const shape *s)
{
    const double scales[3][2] = {{1, 0}, {1e-4, 1e6}, {1e150, -3e150}};
    for (int sc = 0; sc < 3; sc++)
        for (int mirror = 0; mirror < 2; mirror++)
            for (int r = 0; r < 4; r++) {
                double v[4][2];
                if (sc == 1 && s->name[0] == 't' && s->name[1] == 'h')
                    continue; /* "thin": below the 1e-10 resolution of coordinates at 1e6 */
                char name[96];
                transform(s, r, mirror, scales[sc][0], scales[sc][1], v);
                snprintf(name, sizeof name, "%s rot %d mirror %d scale %g", s->name, r, mirror, scales[sc][0]);
                qgl_cover c;
                int kind = qgl_classify(v, &c);
                int orient = mirror ? -s->orientation : s->orientation;
                int reflex = s->reflex < 0 ? -1 : (s->reflex - r) & 3;
                int cross = s->cross_edge < 0 ? -1 : (s->cross_edge + r) & 1;
                CHECK(kind == s->kind && (int)c.kind == s->kind, "%s: kind %d, expected %d", name, kind, s->kind);
                CHECK(c.orientation == orient, "%s: orientation %d, expected %d", name, c.orientation, orient);
                CHECK(c.reflex == reflex, "%s: reflex %d, expected %d", name, c.reflex, reflex);
                CHECK(c.cross_edge == cross, "%s: cross edge %d, expected %d", name, c.cross_edge, cross);
                CHECK(c.ntri == s->ntri, "%s: ntri %d, expected %d", name, c.ntri, s->ntri);
                if (c.kind != QGL_QUAD_DEGENERATE)
                    check_cover_grid(name, v, &c, 61);
            }
}

/* Independent kind: bow-tie iff a pair of opposite edges properly intersects; otherwise
 * convex iff no reflex turn (long double orientations, generic random input). */
static int segments_cross(const double a[2], const double b[2], const double c[2], const double d[2])
{
    long double o1 = is_left(a, b, c), o2 = is_left(a, b, d), o3 = is_left(c, d, a), o4 = is_left(c, d, b);
    return ((o1 > 0) != (o2 > 0)) && ((o3 > 0) != (o4 > 0));
}

static int reference_kind(const double v[4][2])
{
    if (segments_cross(v[0], v[1], v[2], v[3]) || segments_cross(v[1], v[2], v[3], v[0]))
        return QGL_QUAD_BOWTIE;
    int pos = 0;
    for (int i = 0; i < 4; i++)
        pos += is_left(v[(i + 3) & 3], v[i], v[(i + 1) & 3]) > 0;
    return pos == 0 || pos == 4 ? QGL_QUAD_CONVEX : QGL_QUAD_CONCAVE;
}

static double urand(void)
{
    return rand() / (RAND_MAX + 1.0);
}

static void check_random(void)
{
    int counts[5] = {0};
    for (int it = 0; it < 3000; it++) {
        double v[4][2];
        double scale = pow(10, -6 + 12 * urand()), off = (urand() - 0.5) * 1e3 * scale * (it % 3 == 0 ? 1e6 : 1);
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 2; k++)
                v[i][k] = off + scale * (urand() - 0.5);
        qgl_cover c;
        int kind = qgl_classify(v, &c), ref = reference_kind(v);
        counts[kind >= 0 && kind < 5 ? kind : 4]++;
        CHECK(kind == ref, "random %d: kind %d, reference %d", it, kind, ref);
        if (it < 300 && kind != QGL_QUAD_DEGENERATE) {
            char name[32];
            snprintf(name, sizeof name, "random %d", it);
            check_cover_grid(name, v, &c, 41);
        }
    }
    printf("random quads: %d convex, %d concave, %d bow-tie\n", counts[0], counts[1], counts[2]);
    CHECK(counts[0] > 100 && counts[1] > 100 && counts[2] > 100, "random mix too narrow");
}

/* Points exactly on edges and vertices (dyadic, so edge functions are exact) are inside. */
static void check_boundary_points(void)
{
    const double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const double cw[4][2] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    const double on[][2] = {{0.5, 0}, {1, 0.25}, {0.75, 1}, {0, 0.5}, {0, 0}, {1, 1}, {0.5, 0.5}};
    for (size_t i = 0; i < sizeof on / sizeof on[0]; i++) {
        CHECK(qgl_inside(sq, on[i][0], on[i][1]) == 1, "boundary point %zu of ccw square", i);
        CHECK(qgl_inside(cw, on[i][0], on[i][1]) == -1, "boundary point %zu of cw square", i);
    }
    CHECK(qgl_inside(sq, 1.5, 0) == 0, "edge extension beyond corner 1");
    CHECK(qgl_inside(sq, -0.5, 0) == 0, "edge extension beyond corner 0");
    CHECK(qgl_inside(sq, 1.5, 1.5) == 0, "diagonal extension");
    const double line[4][2] = {{0, 0}, {1, 1}, {3, 3}, {2, 2}};
    CHECK(qgl_inside(line, 2.5, 2.5) == 1, "point on a degenerate outline");
    CHECK(qgl_inside(line, 4, 4) == 0, "point on the line of a degenerate quad, outside it");
}

static void check_nonfinite(void)
{
    const double bad[] = {NAN, INFINITY, -INFINITY};
    for (int b = 0; b < 3; b++)
        for (int i = 0; i < 8; i++) {
            double v[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            (&v[0][0])[i] = bad[b];
            qgl_cover c;
            CHECK(qgl_classify(v, &c) == QGL_NONFINITE, "non-finite corner %d", i);
            CHECK(c.ntri == 0 && isfinite(c.cross[0]) && isfinite(c.cross[1]), "cover after non-finite");
            CHECK(qgl_inside(v, 0.5, 0.5) == 0, "qgl_inside with non-finite corner");
            double clip[4][4] = {{0, 0, 0, 1}, {1, 0, 0, 1}, {1, 1, 0, 1}, {0, 1, 0, 1}};
            clip[i / 2][i % 4] = bad[b];
            CHECK(qgl_classify_clip(clip, &c) == QGL_NONFINITE, "clip non-finite %d", i);
        }
    const double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    CHECK(qgl_inside(sq, NAN, 0.5) == 0 && qgl_inside(sq, 0.5, INFINITY) == 0, "non-finite point");
    CHECK(qgl_classify(sq, NULL) == QGL_QUAD_CONVEX, "NULL cover accepted");
}

static void check_clip(void)
{
    for (size_t s = 0; s < sizeof shapes / sizeof shapes[0]; s++) {
        double clip[4][4], neg[4][4];
        for (int i = 0; i < 4; i++) {
            double w = 0.25 + 3 * urand();
            clip[i][0] = shapes[s].v[i][0] * w;
            clip[i][1] = shapes[s].v[i][1] * w;
            clip[i][2] = 0.5;
            clip[i][3] = w;
            for (int k = 0; k < 4; k++)
                neg[i][k] = -clip[i][k];
        }
        qgl_cover a, b, c;
        int k2 = qgl_classify(shapes[s].v, &a), kp = qgl_classify_clip(clip, &b), kn = qgl_classify_clip(neg, &c);
        CHECK(k2 == kp && kp == kn, "%s: clip kinds %d %d %d", shapes[s].name, k2, kp, kn);
        CHECK(a.orientation == b.orientation && b.orientation == c.orientation && a.reflex == b.reflex &&
                  a.cross_edge == b.cross_edge && a.ntri == b.ntri,
              "%s: clip cover differs", shapes[s].name);
        if (a.kind == QGL_QUAD_BOWTIE)
            CHECK(fabs(a.cross[0] - b.cross[0]) < 1e-12 && fabs(a.cross[1] - b.cross[1]) < 1e-12,
                  "%s: clip crossing point", shapes[s].name);
        clip[2][3] = -clip[2][3];
        CHECK(qgl_classify_clip(clip, &b) == QGL_QUAD_EXTERNAL && b.ntri == 0, "%s: mixed w", shapes[s].name);
        clip[2][3] = 0;
        CHECK(qgl_classify_clip(clip, &b) == QGL_QUAD_EXTERNAL, "%s: one w = 0", shapes[s].name);
    }
    double zero[4][4] = {{0, 0, 0, 0}, {1, 0, 0, 0}, {1, 1, 0, 0}, {0, 1, 0, 0}};
    CHECK(qgl_classify_clip(zero, NULL) == QGL_QUAD_DEGENERATE, "every w = 0");
    /* x/w overflows for one corner: still classified (scale invariant), cross point finite */
    double far[4][4] = {{-1, -1, 0, 1}, {1e300, 0, 0, 1e-300}, {1, 1, 0, 1}, {-1, 1, 0, 1}};
    qgl_cover c;
    int k = qgl_classify_clip(far, &c);
    CHECK(k >= 0 && k != QGL_QUAD_EXTERNAL && isfinite(c.cross[0]), "overflowing projection: kind %d", k);
}

/* The crossing point lies on both crossing edges (relative residual). */
static void check_crossing_points(void)
{
    for (int it = 0; it < 2000; it++) {
        double v[4][2], scale = pow(10, -5 + 10 * urand());
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 2; k++)
                v[i][k] = 7 * scale + scale * (urand() - 0.5);
        qgl_cover c;
        if (qgl_classify(v, &c) != QGL_QUAD_BOWTIE)
            continue;
        int e = c.cross_edge;
        long double r1 = is_left(v[e], v[e + 1], c.cross), r2 = is_left(v[e + 2], v[(e + 3) & 3], c.cross);
        long double l1 = hypotl(v[e + 1][0] - v[e][0], v[e + 1][1] - v[e][1]);
        long double l2 = hypotl(v[(e + 3) & 3][0] - v[e + 2][0], v[(e + 3) & 3][1] - v[e + 2][1]);
        CHECK(fabsl(r1) / l1 < 1e-12 * scale && fabsl(r2) / l2 < 1e-12 * scale, "crossing point off its edges");
        CHECK(c.cross_t >= 0 && c.cross_t <= 1, "cross_t %g", c.cross_t);
        double along[2] = {v[e][0] + c.cross_t * (v[e + 1][0] - v[e][0]), v[e][1] + c.cross_t * (v[e + 1][1] - v[e][1])};
        CHECK(hypot(along[0] - c.cross[0], along[1] - c.cross[1]) < 1e-12 * scale, "cross_t inconsistent");
    }
}

int main(void)
{
    srand(12345);
    for (size_t s = 0; s < sizeof shapes / sizeof shapes[0]; s++)
        check_shape(&shapes[s]);
    check_random();
    check_boundary_points();
    check_nonfinite();
    check_clip();
    check_crossing_points();
    printf("%d failures\n", failures);
    return failures ? 1 : 0;
}
