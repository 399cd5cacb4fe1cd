/* test_plane: the view-invariant weights (core plane.c) against independent references.
 *
 * Random 2D quads of every shape (convex, concave, bow-tie) are placed in 3D by random rigid
 * motions and scales. The frame must be an isometry of the quad's own plane (pairwise corner
 * distances kept within 1e-12 relative, heights below 1e-12); the weights of a point of the
 * plane must equal the textbook mean value formula evaluated in the original 2D coordinates
 * (angles by atan2 in long double) within 1e-9, whatever the placement; they must reproduce
 * the point (linear precision), be the linear interpolation on edge segments, turn with the
 * corner order (these three within 1e-12 to 1e-13 times the rounding of the coordinates
 * relative to the quad's size), and agree with the float functions within 1e-5 (times the
 * same). The preferred diagonal is the shorter one and does not depend on the corner order; the
 * cover covers the quad's area once. A saddle gets Newell's normal and heights of +-h, a
 * tiny quad far from the origin keeps its weights, collinear corners are degenerate and
 * non-finite input is reported with finite outputs. Last, the planner's samples of the split's
 * difference from the in-plane weights (its invisible-split rule) against a fine grid. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <quadgl/quadgl.h>

#include "check.h"

static double rnd(void)
{
    return rand() / (double)RAND_MAX * 2 - 1;
}

/* Textbook mean value weights of p in the 2D quad v (Floater; signed angles). */
static void reference_weights(const double v[4][2], const double p[2], double w[4])
{
    long double s[4][2], r[4], t[4], sum = 0;
    for (int i = 0; i < 4; i++) {
        s[i][0] = (long double)v[i][0] - p[0];
        s[i][1] = (long double)v[i][1] - p[1];
        r[i] = sqrtl(s[i][0] * s[i][0] + s[i][1] * s[i][1]);
    }
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        long double a = atan2l(s[i][0] * s[j][1] - s[i][1] * s[j][0], s[i][0] * s[j][0] + s[i][1] * s[j][1]);
        t[i] = tanl(a / 2);
    }
    long double mu[4];
    for (int i = 0; i < 4; i++)
        sum += mu[i] = (t[(i + 3) & 3] + t[i]) / r[i];
    for (int i = 0; i < 4; i++)
        w[i] = (double)(mu[i] / sum);
}

/* A random rotation (from a random unit quaternion), translation and scale. */
typedef struct placement {
    double m[3][3], t[3], scale;
} placement;

static void random_placement(placement *pl, double spread)
{
    double q[4], n = 0;
    for (int k = 0; k < 4; k++) {
        q[k] = rnd();
        n += q[k] * q[k];
    }
    n = sqrt(n);
    for (int k = 0; k < 4; k++)
        q[k] /= n;
    double a = q[0], b = q[1], c = q[2], d = q[3];
    double m[3][3] = {{a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)},
                      {2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)},
                      {2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d}};
    memcpy(pl->m, m, sizeof m);
    for (int k = 0; k < 3; k++)
        pl->t[k] = spread * rnd();
    pl->scale = exp(2 * rnd());
}

static void place(const placement *pl, const double xy[2], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = pl->scale * (pl->m[r][0] * xy[0] + pl->m[r][1] * xy[1]) + pl->t[r];
}

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static double dist2(const double a[2], const double b[2])
{
    return hypot(a[0] - b[0], a[1] - b[1]);
}

/* How far the quad is from the origin relative to its size: the rounding of its coordinates
 * is this many units of roundoff of the quad's size. */
static double offset_ratio(const double pos[4][3])
{
    double m = 0, size = 0;
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++) {
            m = fmax(m, fabs(pos[i][k]));
            size = fmax(size, dist3(pos[i], pos[(i + 1) & 3]));
        }
    return 1 + m / size;
}

/* A random quad of the given kind (by rejection). */
static void random_quad(int kind, double v[4][2])
{
    for (;;) {
        for (int i = 0; i < 4; i++)
            v[i][0] = rnd(), v[i][1] = rnd();
        qgl_cover c;
        if (qgl_classify(v, &c) == kind && c.ntri == 2)
            return;
    }
}

/* Distance from p to the quad's outline, relative to its size: reference points nearer
 * than this are skipped (the textbook formula loses accuracy there, the core does not). */
static double outline_distance(const double v[4][2], const double p[2])
{
    double best = INFINITY;
    for (int i = 0; i < 4; i++) {
        const double *a = v[i], *b = v[(i + 1) & 3];
        double dx = b[0] - a[0], dy = b[1] - a[1];
        double t = ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy);
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        best = fmin(best, hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy));
    }
    return best;
}

static void check_frame(const double v[4][2], const double pos[4][3], const qgl_plane *pl, double scale)
{
    for (int i = 0; i < 4; i++) {
        CHECK(fabs(pl->height[i]) < 1e-12 * scale, "height %g", pl->height[i]);
        for (int j = i + 1; j < 4; j++) {
            double d3 = dist3(pos[i], pos[j]), d2 = dist2(pl->corner[i], pl->corner[j]);
            CHECK(fabs(d3 - d2) <= 1e-12 * scale, "corner distance %g in the plane, %g in space", d2, d3);
            (void)v;
        }
    }
    double e02 = dist3(pos[0], pos[2]), e13 = dist3(pos[1], pos[3]);
    CHECK(pl->diagonal == (e13 < e02) || e02 == e13, "diagonal %d for lengths %g, %g", pl->diagonal, e02, e13);
}

/* Random points of the plane: weights against the reference and the checks that need none. */
static void check_points(const double v[4][2], const double pos[4][3], const placement *P, double *worst)
{
    qgl_plane pl;
    float posf[4][3];
    CHECK(qgl_plane_frame(pos, &pl) == 0, "frame of a planar quad");
    check_frame(v, pos, &pl, P->scale);
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            posf[i][k] = (float)pos[i][k];
    for (int s = 0; s < 40; s++) {
        double xy[2] = {1.2 * rnd(), 1.2 * rnd()}, p[3], w[4], ref[4];
        place(P, xy, p);
        int r = qgl_weights_plane(pos, p, w);
        int in = qgl_inside(v, xy[0], xy[1]) != 0;
        CHECK(r == (in ? QGL_INSIDE : QGL_OUTSIDE) || outline_distance(v, xy) < 1e-9, "code %d, inside %d", r, in);
        double back[3] = {0, 0, 0}, sum = 0, mag = 0, off = offset_ratio(pos);
        for (int i = 0; i < 4; i++) {
            sum += w[i];
            mag += fabs(w[i]);
            for (int k = 0; k < 3; k++)
                back[k] += w[i] * pos[i][k];
        }
        CHECK(fabs(sum - 1) < 1e-13 * mag * off && dist3(back, p) < 1e-12 * P->scale * mag * off,
              "linear precision: sum %.17g, point off by %g", sum, dist3(back, p));
        if (in && outline_distance(v, xy) > 1e-3) {
            reference_weights(v, xy, ref);
            for (int i = 0; i < 4; i++) {
                double e = fabs(w[i] - ref[i]);
                *worst = fmax(*worst, e);
                CHECK(e < 1e-9, "weight %d: %.17g, reference %.17g", i, w[i], ref[i]);
            }
            float pf[3] = {(float)p[0], (float)p[1], (float)p[2]}, wf[4];
            qgl_weights_planef((const float(*)[3])posf, pf, wf);
            for (int i = 0; i < 4; i++)
                CHECK(fabs(wf[i] - w[i]) < 1e-5 * off, "float weight %d: %g, double %g",
                      i, wf[i], w[i]);
        }
    }
}

/* Edge segments: the linear interpolation of the edge's two corners, within the rounding of
 * the corners' coordinates relative to the quad's size. */
static void check_edges(const double pos[4][3])
{
    double tol = 1e-12 * offset_ratio(pos);
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        for (int s = 1; s < 8; s++) {
            double t = s / 8.0, p[3], w[4];
            for (int k = 0; k < 3; k++)
                p[k] = (1 - t) * pos[i][k] + t * pos[j][k];
            qgl_weights_plane(pos, p, w);
            CHECK(fabs(w[i] - (1 - t)) < tol && fabs(w[j] - t) < tol, "edge %d at %g: %.3g %.3g", i, t, w[i] - (1 - t), w[j] - t);
        }
    }
}

/* Rotating the corner order rotates the weights and keeps the preferred diagonal. */
static void check_rotation(const double pos[4][3])
{
    double rot[4][3], p[3] = {0, 0, 0}, w0[4], w1[4];
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++) {
            rot[i][k] = pos[(i + 1) & 3][k];
            p[k] += (0.1 + 0.1 * i) * pos[i][k];
        }
    qgl_plane a, b;
    qgl_plane_frame(pos, &a);
    qgl_plane_frame(rot, &b);
    CHECK(a.diagonal != b.diagonal, "the preferred diagonal follows the corners: %d then %d", a.diagonal,
          b.diagonal);
    qgl_weights_plane(pos, p, w0);
    qgl_weights_plane(rot, p, w1);
    /* far outside a bow-tie the weights are large and as ill-conditioned as they are large */
    double mag = fabs(w0[0]) + fabs(w0[1]) + fabs(w0[2]) + fabs(w0[3]);
    for (int i = 0; i < 4; i++)
        CHECK(fabs(w1[i] - w0[(i + 1) & 3]) < 1e-13 * mag * mag * offset_ratio(pos), "rotated weight %d: %g vs %g", i, w1[i], w0[(i + 1) & 3]);
}

/* The cover's triangles cover the quad's area once. */
static void check_cover(const double pos[4][3])
{
    qgl_plane pl;
    qgl_cover c;
    qgl_plane_frame(pos, &pl);
    int kind = qgl_plane_cover(&pl, &c);
    double pts[5][2], area = 0, quad = 0;
    memcpy(pts, pl.corner, sizeof pl.corner);
    pts[4][0] = c.cross[0], pts[4][1] = c.cross[1];
    for (int t = 0; t < c.ntri; t++) {
        const double *a = pts[c.tri[t][0]], *b = pts[c.tri[t][1]], *d = pts[c.tri[t][2]];
        area += fabs((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0])) / 2;
    }
    for (int i = 0; i < 4; i++)
        quad += (pl.corner[i][0] * pl.corner[(i + 1) & 3][1] - pl.corner[(i + 1) & 3][0] * pl.corner[i][1]) / 2;
    if (kind != QGL_QUAD_BOWTIE)
        CHECK(fabs(area - fabs(quad)) < 1e-9 * area, "cover area %g, quad %g", area, quad);
    if (kind == QGL_QUAD_CONVEX)
        CHECK(c.tri[0][0] == pl.diagonal && c.tri[1][0] == pl.diagonal, "convex cover along diagonal %d",
              pl.diagonal);
}

static void random_quads(void)
{
    static const char *names[] = {"convex", "concave", "bow-tie"};
    for (int kind = 0; kind < 3; kind++) {
        double worst = 0;
        for (int n = 0; n < 300; n++) {
            double v[4][2], pos[4][3];
            placement P;
            random_quad(kind, v);
            random_placement(&P, n % 3 == 0 ? 1e3 : 2);
            for (int i = 0; i < 4; i++)
                place(&P, v[i], pos[i]);
            check_points(v, pos, &P, &worst);
            check_edges(pos);
            check_rotation(pos);
            check_cover(pos);
        }
        printf("%-8s 300 quads x 40 points: largest weight error against the textbook formula %.3g\n", names[kind],
               worst);
    }
}

/* A saddle: Newell's normal (the diagonals' cross product), heights +-h, a square in the plane. */
static void saddle(void)
{
    const double h = 0.3, pos[4][3] = {{-1, -1, -h}, {1, -1, h}, {1, 1, -h}, {-1, 1, h}};
    qgl_plane pl;
    CHECK(qgl_plane_frame(pos, &pl) == 0, "saddle frame");
    CHECK(fabs(fabs(pl.normal[2]) - 1) < 1e-15, "saddle normal (%g %g %g)", pl.normal[0], pl.normal[1], pl.normal[2]);
    for (int i = 0; i < 4; i++)
        CHECK(fabs(fabs(pl.height[i]) - h) < 1e-15 && pl.height[i] * pl.height[(i + 1) & 3] < 0, "saddle height %d: %g",
              i, pl.height[i]);
    double p[3] = {0.3, -0.2, 5}, w[4], ref[4];
    const double sq[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}, xy[2] = {0.3, -0.2};
    qgl_weights_plane(pos, p, w);
    reference_weights(sq, xy, ref);
    for (int i = 0; i < 4; i++)
        CHECK(fabs(w[i] - ref[i]) < 1e-12, "saddle weight %d: %g, projection's %g", i, w[i], ref[i]);
}

/* A quad of size 1e-4 a million units from the origin keeps its weights. */
static void tiny_far(void)
{
    const double v[4][2] = {{0, 0}, {1, 0.1}, {0.9, 1}, {-0.1, 0.8}};
    double pos[4][3], far[4][3], p[3], q[3], w[4], wf[4];
    for (int i = 0; i < 4; i++) {
        pos[i][0] = v[i][0], pos[i][1] = v[i][1], pos[i][2] = 0.5 * v[i][0];
        for (int k = 0; k < 3; k++)
            far[i][k] = 1e6 + 1e-4 * pos[i][k];
    }
    for (int k = 0; k < 3; k++) {
        p[k] = 0.3 * pos[0][k] + 0.2 * pos[1][k] + 0.4 * pos[2][k] + 0.1 * pos[3][k];
        q[k] = 1e6 + 1e-4 * p[k];
    }
    qgl_weights_plane(pos, p, w);
    qgl_weights_plane(far, q, wf);
    for (int i = 0; i < 4; i++)
        CHECK(fabs(w[i] - wf[i]) < 1e-5, "far weight %d: %g, at the origin %g", i, wf[i], w[i]);
}

static void bad_input(void)
{
    const double line[4][3] = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
    double nan_pos[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, NAN}}, p[3] = {0.5, 0.5, 0}, w[4];
    qgl_plane pl;
    CHECK(qgl_plane_frame(line, &pl) == QGL_DEGENERATE, "collinear corners are degenerate");
    CHECK(qgl_plane_frame(nan_pos, &pl) == QGL_NONFINITE, "NaN corner");
    CHECK(qgl_weights_plane(nan_pos, p, w) == QGL_NONFINITE, "NaN corner, weights");
    for (int i = 0; i < 4; i++)
        CHECK(isfinite(w[i]) && isfinite(pl.corner[i][0]) && isfinite(pl.corner[i][1]), "finite outputs");
    const double sq[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, bad[3] = {INFINITY, 0, 0};
    CHECK(qgl_weights_plane(sq, bad, w) == QGL_NONFINITE, "infinite point");
}

/* ---- the planner's invisible-split samples against the in-plane weights -------------------- */

/* Perspective-correct barycentrics of (x, y) in triangle t of screen points v with clip w. */
static void triangle_weights(const double v[4][2], const double w[4], const int t[3], double x, double y, double out[4])
{
    double b[3], sum = 0;
    for (int k = 0; k < 3; k++) {
        const double *p = v[t[(k + 1) % 3]], *q = v[t[(k + 2) % 3]];
        b[k] = ((p[0] - x) * (q[1] - y) - (p[1] - y) * (q[0] - x)) / w[t[k]];
        sum += b[k];
    }
    memset(out, 0, 4 * sizeof(double));
    for (int k = 0; k < 3; k++)
        out[t[k]] = b[k] / sum;
}

/* The split along diagonal a -> a + 2 at (x, y). */
static void split_weights(const double v[4][2], const double w[4], int a, double x, double y, double out[4])
{
    int b = (a + 1) & 3, c = (a + 2) & 3, d = (a + 3) & 3;
    double ex = v[c][0] - v[a][0], ey = v[c][1] - v[a][1];
    double side_b = ex * (v[b][1] - v[a][1]) - ey * (v[b][0] - v[a][0]);
    double side_p = ex * (y - v[a][1]) - ey * (x - v[a][0]);
    const int tb[3] = {a, b, c}, td[3] = {a, c, d};
    triangle_weights(v, w, side_p * side_b >= 0 ? tb : td, x, y, out);
}

/* |delta| = |(split - in-plane weights) . n| at screen point (x, y) for diagonal a. */
static double split_delta(const qgl_plane *pl, const double v[4][2], const double w[4], const double n[4], double x,
                          double y, int a)
{
    double s0[4], sa[4], lam[4], xy[2] = {0, 0}, d = 0;
    split_weights(v, w, 0, x, y, s0);
    for (int i = 0; i < 4; i++)
        xy[0] += s0[i] * pl->corner[i][0], xy[1] += s0[i] * pl->corner[i][1];
    qgl_weights_inplane(pl, xy[0], xy[1], lam);
    split_weights(v, w, a, x, y, sa);
    for (int i = 0; i < 4; i++)
        d += (sa[i] - lam[i]) * n[i];
    return fabs(d);
}

static double det3(const double a[3], const double b[3], const double c[3])
{
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

/* The planner (draw.c, split_invisible) bounds the split's difference from AUTO's smooth
 * weights by its largest value at nine screen points (the diagonals' crossing, half-way from
 * there to each corner, the centroids of the four triangles the diagonals cut) times
 * SPLIT_SAFETY = 2. Random planar convex quads in random perspective (corner angles jittered
 * by +-36 degrees, radii 0.8 to 1.3): a 61 x 61 grid's maximum must stay within that. */
static void split_samples(void)
{
    double worst = 0;
    int n_quads = 0;
    for (int t = 0; t < 1000; t++) {
        double q2[4][2], P[4][3], v[4][2], w[4], hw[4][3], nv[4];
        for (int i = 0; i < 4; i++) {
            double ang = (i * 90 + 36 * rnd()) * 3.14159265358979323846 / 180, r = 0.8 + 0.5 * rnd();
            q2[i][0] = r * cos(ang), q2[i][1] = r * sin(ang);
        }
        qgl_cover c;
        if (qgl_classify(q2, &c) != QGL_QUAD_CONVEX || c.ntri != 2)
            continue;
        double ax = 1.3 * rnd(), ay = 1.3 * rnd(), dist = 3.5 + 1.5 * rnd();
        int ok = 1;
        for (int i = 0; i < 4; i++) {
            P[i][0] = q2[i][0] * cos(ay), P[i][1] = q2[i][1] * cos(ax);
            P[i][2] = q2[i][0] * sin(ay) + q2[i][1] * sin(ax) - dist;
            w[i] = -P[i][2];
            ok &= w[i] > 0.1;
            hw[i][0] = 256 * P[i][0], hw[i][1] = 256 * P[i][1], hw[i][2] = w[i];
            v[i][0] = hw[i][0] / w[i], v[i][1] = hw[i][1] / w[i];
        }
        qgl_plane pl;
        if (!ok || qgl_classify(v, &c) != QGL_QUAD_CONVEX || qgl_plane_frame(P, &pl) != 0)
            continue;
        nv[0] = det3(hw[1], hw[2], hw[3]), nv[1] = -det3(hw[0], hw[2], hw[3]);
        nv[2] = det3(hw[0], hw[1], hw[3]), nv[3] = -det3(hw[0], hw[1], hw[2]);
        double len = sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2] + nv[3] * nv[3]);
        for (int i = 0; i < 4; i++)
            nv[i] /= len;
        double d1x = v[2][0] - v[0][0], d1y = v[2][1] - v[0][1], d2x = v[3][0] - v[1][0], d2y = v[3][1] - v[1][1];
        double den = d1x * d2y - d1y * d2x, rx = v[1][0] - v[0][0], ry = v[1][1] - v[0][1];
        double tc = (rx * d2y - ry * d2x) / den, cx = v[0][0] + tc * d1x, cy = v[0][1] + tc * d1y, pts[9][2];
        pts[0][0] = cx, pts[0][1] = cy;
        for (int i = 0; i < 4; i++) {
            int j = (i + 1) & 3;
            pts[1 + i][0] = 0.5 * (cx + v[i][0]), pts[1 + i][1] = 0.5 * (cy + v[i][1]);
            pts[5 + i][0] = (cx + v[i][0] + v[j][0]) / 3, pts[5 + i][1] = (cy + v[i][1] + v[j][1]) / 3;
        }
        double sampled = 0, grid = 0;
        for (int k = 0; k < 9; k++)
            for (int a = 0; a < 2; a++)
                sampled = fmax(sampled, split_delta(&pl, v, w, nv, pts[k][0], pts[k][1], a));
        for (int i = 0; i <= 60; i++)
            for (int j = 0; j <= 60; j++) {
                double s = i / 60.0, u = j / 60.0, b[4] = {(1 - s) * (1 - u), s * (1 - u), s * u, (1 - s) * u};
                double x = b[0] * v[0][0] + b[1] * v[1][0] + b[2] * v[2][0] + b[3] * v[3][0];
                double y = b[0] * v[0][1] + b[1] * v[1][1] + b[2] * v[2][1] + b[3] * v[3][1];
                for (int a = 0; a < 2; a++)
                    grid = fmax(grid, split_delta(&pl, v, w, nv, x, y, a));
            }
        if (sampled > 1e-9) {
            worst = fmax(worst, grid / sampled);
            n_quads++;
        }
    }
    printf("invisible-split samples: over %d planar convex quads the grid's largest difference from the in-plane "
           "weights is at most %.3f times the sampled one (the planner allows 2)\n",
           n_quads, worst);
    CHECK(n_quads > 500 && worst < 2, "sampled split difference underestimates by %g", worst);
}

int main(void)
{
    srand(15);
    random_quads();
    split_samples();
    saddle();
    tiny_far();
    bad_input();
    printf("%d failures\n", failures);
    return failures ? 1 : 0;
}
