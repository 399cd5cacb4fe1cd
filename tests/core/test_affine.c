/* Tests of the affinity predicates on constructed affine and non-affine quads.
 *
 * Planar quads are built as a random 2D quad placed on a random plane; attributes that must
 * pass are a random affine map of position; attributes that must fail are the same with one
 * corner moved by a stated fraction of the attribute range (well above the tolerance used).
 * Every case is also repeated far from the origin and at extreme scales. */
#include <quadgl/quadgl.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"

static double urand(void)
{
    return rand() / (RAND_MAX + 1.0) - 0.5;
}

/* A random convex 2D quad (perturbed square) in [-1,1]^2. */
static void random_quad2(double q[4][2])
{
    const double sq[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 2; k++)
            q[i][k] = 0.5 * sq[i][k] + 0.4 * urand();
}

/* Place 2D points on a random plane: origin o, basis (a, b), times scale. A "flat" plane
 * is z = const, which stays exactly planar after the coordinates are rounded (far from the
 * origin, rounding alone moves corners by 1e-6 of a 1e-4 quad at 1e6). */
static void embed(const double q[4][2], double scale, double off, int flat, double p[4][3], double frame[3][3])
{
    for (int k = 0; k < 3; k++) {
        frame[0][k] = k == 2 && flat ? 0 : urand();
        frame[1][k] = k == 2 && flat ? 0 : urand();
        frame[2][k] = off + scale * urand();
    }
    frame[0][0] += 1; /* keep the basis away from degenerate */
    frame[1][1] += 1;
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            p[i][k] = frame[2][k] + scale * (q[i][0] * frame[0][k] + q[i][1] * frame[1][k]);
}

static void check_planarity(void)
{
    const double scales[4][2] = {{1, 0}, {1e-4, 1e6}, {1e-200, 0}, {1e200, 1e201}};
    for (int sc = 0; sc < 4; sc++)
        for (int it = 0; it < 500; it++) {
            double q[4][2], p[4][3], f[3][3];
            random_quad2(q);
            embed(q, scales[sc][0], scales[sc][1], sc == 1, p, f);
            CHECK(qgl_is_planar(p, 1e-9), "planar quad rejected (scale %g)", scales[sc][0]);
            /* lift corner 3 off the plane by 1e-6 of the size along the normal */
            double n[3] = {f[0][1] * f[1][2] - f[0][2] * f[1][1], f[0][2] * f[1][0] - f[0][0] * f[1][2],
                           f[0][0] * f[1][1] - f[0][1] * f[1][0]};
            double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int k = 0; k < 3; k++)
                p[3][k] += 1e-6 * scales[sc][0] * n[k] / len;
            if (sc != 1) /* at 1e6 the 1e-10 lift is below the coordinates' resolution */
                CHECK(!qgl_is_planar(p, 1e-9), "lifted quad accepted at 1e-9 (scale %g)", scales[sc][0]);
            CHECK(qgl_is_planar(p, 1e-5), "slightly lifted quad rejected at 1e-5 (scale %g)", scales[sc][0]);
        }
    const double twisted[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.1}, {0, 1, 0}};
    CHECK(!qgl_is_planar(twisted, 1e-3), "twisted quad accepted");
    CHECK(qgl_is_planar(twisted, 0.2), "twist 0.1 rejected at 0.2");
    const double tri[4][3] = {{0, 0, 0}, {0, 0, 0}, {1, 2, 3}, {-1, 5, 2}};
    CHECK(qgl_is_planar(tri, 0), "collapsed edge (three points) not planar");
    const double nan[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, NAN, 0}, {0, 1, 0}};
    CHECK(!qgl_is_planar(nan, 1), "NaN accepted as planar");
}

static void check_parallelogram(void)
{
    for (int it = 0; it < 200; it++) {
        /* integer corners: the dot products are exact */
        double a[2] = {rand() % 100, rand() % 100}, u[2] = {rand() % 50 - 25, rand() % 50 - 25},
               w[2] = {rand() % 50 - 25, rand() % 50 - 25};
        double par[8] = {a[0], a[1], a[0] + u[0], a[1] + u[1], a[0] + u[0] + w[0], a[1] + u[1] + w[1],
                         a[0] + w[0], a[1] + w[1]};
        CHECK(qgl_is_parallelogram(par, 2, 1e-9), "sheared parallelogram rejected");
        par[4] += 1; /* corner C moved by one unit: a trapezoid-like quad */
        CHECK(!qgl_is_parallelogram(par, 2, 1e-3) || (u[0] == 0 && u[1] == 0) || (w[0] == 0 && w[1] == 0),
              "moved corner accepted");
    }
    const double trap[8] = {0, 0, 4, 0, 3, 1, 1, 1};
    CHECK(!qgl_is_parallelogram(trap, 2, 1e-3), "trapezoid accepted");
    const double par3[12] = {0, 0, 0, 1, 0, 1, 1.5, 1, 1, 0.5, 1, 0};
    CHECK(qgl_is_parallelogram(par3, 3, 1e-12), "3D parallelogram rejected");
    const double kite[8] = {0, 0, 1, -1, 3, 0, 1, 1};
    CHECK(!qgl_is_parallelogram(kite, 2, 1e-3), "kite accepted");
}

/* attr = M pos + c for a random affine M (dim_a x dim_g). */
static void affine_attr(const double *pos, int dim_g, double *attr, int dim_a, double arange)
{
    double m[16][16], c[16];
    for (int r = 0; r < dim_a; r++) {
        c[r] = arange * urand();
        for (int k = 0; k < dim_g; k++)
            m[r][k] = arange * urand();
    }
    for (int i = 0; i < 4; i++)
        for (int r = 0; r < dim_a; r++) {
            double s = c[r];
            for (int k = 0; k < dim_g; k++)
                s += m[r][k] * pos[i * dim_g + k];
            attr[i * dim_a + r] = s;
        }
}

/* uv = M q + c with M well conditioned (det >= 0.16): Bloomenthal's comparison is made in uv
 * space, where a nearly singular map would make the barycentrics themselves ill-posed. */
static void uv_map(const double q[4][2], double uv[8])
{
    double m[2][2] = {{1 + urand(), 0.6 * urand()}, {0.6 * urand(), 1 + urand()}}, c[2] = {urand(), urand()};
    for (int i = 0; i < 4; i++)
        for (int r = 0; r < 2; r++)
            uv[i * 2 + r] = c[r] + m[r][0] * q[i][0] + m[r][1] * q[i][1];
}

static void check_bloomenthal(void)
{
    for (int it = 0; it < 500; it++) {
        double q[4][2], p[4][3], f[3][3], uv[8], uv2[8];
        random_quad2(q);
        embed(q, 1, 0, 0, p, f);
        uv_map(q, uv);
        CHECK(qgl_bloomenthal_affine(&p[0][0], 3, uv, 2, 1e-9), "3D affine uv rejected");
        CHECK(qgl_bloomenthal_affine(&q[0][0], 2, uv, 2, 1e-9), "2D affine uv rejected");
        double big[4][2], rel[4][2];
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 2; k++) {
                big[i][k] = 1e6 + 1e-3 * q[i][k];
                rel[i][k] = (big[i][k] - 1e6) * 1e3; /* affine in the rounded corners */
            }
        uv_map((const double (*)[2])rel, uv2);
        CHECK(qgl_bloomenthal_affine(&big[0][0], 2, uv2, 2, 1e-6), "affine uv rejected at 1e6");
        uv[5] += 0.05; /* corner 2's v by about 5% of the range */
        CHECK(!qgl_bloomenthal_affine(&p[0][0], 3, uv, 2, 1e-3), "perturbed uv accepted");
    }
    const double trap[8] = {0, 0, 4, 0, 3, 1, 1, 1}, sq[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    CHECK(!qgl_bloomenthal_affine(trap, 2, sq, 2, 0.01), "trapezoid onto square accepted");
    const double nan[8] = {0, 0, 1, 0, NAN, 1, 0, 1};
    CHECK(!qgl_bloomenthal_affine(nan, 2, sq, 2, 1), "NaN accepted");
}

static void check_split_exact(void)
{
    const double scales[3][2] = {{1, 0}, {1e-4, 1e6}, {1e100, 0}};
    for (int sc = 0; sc < 3; sc++)
        for (int it = 0; it < 500; it++) {
            double q[4][2], p[4][3], f[3][3], a[20];
            random_quad2(q);
            embed(q, scales[sc][0], scales[sc][1], sc == 1, p, f);
            /* attributes: affine in position (5 of them, ranges of 1 and 1e3) */
            double rel[4][3];
            for (int i = 0; i < 4; i++)
                for (int k = 0; k < 3; k++)
                    rel[i][k] = (p[i][k] - p[0][k]) / scales[sc][0];
            affine_attr(&rel[0][0], 3, a, 5, it % 2 ? 1 : 1e3);
            CHECK(qgl_split_is_exact(p, a, 5, 1e-9), "affine attributes rejected (scale %g)", scales[sc][0]);
            int corner = it & 3, comp = it % 5;
            double lo = a[comp], hi = a[comp];
            for (int i = 1; i < 4; i++) {
                lo = fmin(lo, a[i * 5 + comp]);
                hi = fmax(hi, a[i * 5 + comp]);
            }
            a[corner * 5 + comp] += 1e-6 * (hi - lo);
            CHECK(!qgl_split_is_exact(p, a, 5, 1e-9), "perturbed attribute accepted (scale %g)", scales[sc][0]);
            CHECK(qgl_split_is_exact(p, a, 5, 1e-4), "1e-6 perturbation rejected at 1e-4");
        }
    const double twisted[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.1}, {0, 1, 0}};
    const double affine_on_twisted[4] = {0, 1, 2, 1}; /* u + v: would be affine if planar */
    CHECK(!qgl_split_is_exact(twisted, affine_on_twisted, 1, 1e-6), "non-planar quad split called exact");
    const double pole[4][3] = {{0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
    const double same[4] = {0.5, 0.5, 0, 1}, diff[4] = {0.25, 0.75, 0, 1};
    CHECK(qgl_split_is_exact(pole, same, 1, 1e-9), "collapsed edge with equal attributes rejected");
    CHECK(!qgl_split_is_exact(pole, diff, 1, 1e-9), "pole with different attributes accepted");
    const double trap[4][3] = {{0, 0, 0}, {4, 0, 0}, {3, 1, 0}, {1, 1, 0}};
    const double u[4] = {0, 1, 1, 0}, x[4] = {0, 4, 3, 1};
    CHECK(!qgl_split_is_exact(trap, u, 1, 1e-6), "square texture on trapezoid accepted");
    CHECK(qgl_split_is_exact(trap, x, 1, 1e-12), "x on trapezoid rejected");
    CHECK(qgl_split_is_exact(trap, NULL, 0, 1e-12), "no attributes: planar quad rejected");
}

/* Cofactors of the corners' (x, y, w): the dependency of a projected quad. */
static void clip_dependency(const double c[4][4], double n[4])
{
    for (int i = 0; i < 4; i++) {
        const double *a = c[(i + 1) & 3], *b = c[(i + 2) & 3], *d = c[(i + 3) & 3];
        double det = a[0] * (b[1] * d[3] - b[3] * d[1]) - a[1] * (b[0] * d[3] - b[3] * d[0]) +
                     a[3] * (b[0] * d[1] - b[1] * d[0]);
        n[i] = (i & 1) ? -det : det; /* cyclic order: the sign alternates for the odd corners */
    }
}

static void check_dependency(void)
{
    const double scales[3][2] = {{1, 0}, {1e-4, 1e6}, {1e100, 0}};
    for (int sc = 0; sc < 3; sc++)
        for (int it = 0; it < 500; it++) {
            double q[4][2], p[4][3], f[3][3], n[4];
            random_quad2(q);
            embed(q, scales[sc][0], scales[sc][1], sc == 1, p, f);
            CHECK(qgl_affine_dependency(p, n), "convex quad has no dependency (scale %g)", scales[sc][0]);
            double sum = n[0] + n[1] + n[2] + n[3], worst = 0;
            for (int k = 0; k < 3; k++) {
                double s = 0;
                for (int i = 0; i < 4; i++)
                    s += n[i] * (p[i][k] - p[0][k]);
                worst = fmax(worst, fabs(s) / scales[sc][0]);
            }
            CHECK(fabs(sum) < 1e-12 && worst < 1e-8, "dependency off: sum %g, residual %g (scale %g)", sum, worst,
                  scales[sc][0]);
            if (sc)
                continue;
            /* a random projective image (a camera): the cofactors there are parallel to n */
            double m[4][4], c[4][4], nc[4];
            for (int r = 0; r < 4; r++)
                for (int k = 0; k < 4; k++)
                    m[r][k] = (r == k) + 0.4 * urand();
            m[3][3] += 3; /* w > 0 over the quad */
            for (int i = 0; i < 4; i++)
                for (int r = 0; r < 4; r++)
                    c[i][r] = m[r][0] * p[i][0] + m[r][1] * p[i][1] + m[r][2] * p[i][2] + m[r][3];
            clip_dependency(c, nc);
            double nn = 0, cc = 0, dot = 0;
            for (int i = 0; i < 4; i++)
                nn += n[i] * n[i], cc += nc[i] * nc[i], dot += n[i] * nc[i];
            CHECK(dot * dot >= (1 - 1e-9) * nn * cc, "clip-space dependency not parallel: cos^2 %.12f",
                  dot * dot / (nn * cc));
        }
    /* parallelograms (p0 + p2 = p1 + p3 in floats, as the planner's corners are): their
     * diagonals halve each other; one a millionth off is not one */
    int tested = 0;
    for (int it = 0; it < 400; it++) {
        float fp[4][3];
        double p[4][3], n[4];
        for (int k = 0; k < 3; k++) {
            fp[0][k] = (float)(1e4 * urand()), fp[1][k] = fp[0][k] + (float)urand();
            fp[2][k] = fp[1][k] + (float)urand(), fp[3][k] = (float)((double)fp[0][k] + fp[2][k] - fp[1][k]);
        }
        int exact = 1;
        for (int c = 0; c < 4; c++)
            for (int k = 0; k < 3; k++)
                p[c][k] = fp[c][k];
        for (int k = 0; k < 3; k++)
            exact &= p[0][k] + p[2][k] == p[1][k] + p[3][k];
        if (!exact)
            continue; /* p3 rounded off the parallelogram */
        tested++;
        CHECK(qgl_affine_dependency(p, n) && n[0] == 0.5 && n[1] == -0.5 && n[2] == 0.5 && n[3] == -0.5,
              "parallelogram: n = %g %g %g %g", n[0], n[1], n[2], n[3]);
        for (int k = 0; k < 3; k++) /* along an edge: in the plane, off the parallelogram */
            p[3][k] += 1e-6 * (p[1][k] - p[0][k]);
        CHECK(qgl_affine_dependency(p, n), "near-parallelogram has no dependency");
        double worst = 0;
        for (int k = 0; k < 3; k++) {
            double s = 0;
            for (int i = 0; i < 4; i++)
                s += n[i] * (p[i][k] - p[0][k]);
            worst = fmax(worst, fabs(s));
        }
        CHECK(worst < 1e-9, "near-parallelogram taken for one: residual %g", worst);
    }
    CHECK(tested > 100, "only %d exact parallelograms drawn", tested);
    const double flat[4][3] = {{0, 0, 0}, {1, 0, 0}, {3, 0, 0}, {2, 0, 0}}; /* p0 + p2 = p1 + p3 */
    double n[4];
    CHECK(!qgl_affine_dependency(flat, n), "collinear parallelogram given a dependency");
    /* t = 2/7, u = 4/7 */
    const double quad[4][3] = {{0, 0, 0}, {2, 0, 0}, {3, 2, 0}, {0, 1, 0}}, want[4] = {5 / 7., -3 / 7., 2 / 7., -4 / 7.};
    CHECK(qgl_affine_dependency(quad, n), "irregular quad has no dependency");
    for (int i = 0; i < 4; i++)
        CHECK(fabs(n[i] - want[i]) < 1e-15, "irregular quad: n[%d] = %.17g, want %.17g", i, n[i], want[i]);
    const double dart[4][3] = {{0, 0, 0}, {2, 0, 0}, {0.5, 0.5, 0}, {0, 2, 0}};
    const double bowtie[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    const double line[4][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
    const double nan[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, NAN, 0}, {0, 1, 0}};
    CHECK(!qgl_affine_dependency(dart, n), "concave quad given a dependency");
    CHECK(!qgl_affine_dependency(bowtie, n), "bow-tie given a dependency");
    CHECK(!qgl_affine_dependency(line, n), "collinear quad given a dependency");
    CHECK(!qgl_affine_dependency(nan, n), "NaN given a dependency");
}

int main(void)
{
    srand(777);
    check_planarity();
    check_parallelogram();
    check_bloomenthal();
    check_split_exact();
    check_dependency();
    printf("%d failures\n", failures);
    return failures ? 1 : 0;
}
