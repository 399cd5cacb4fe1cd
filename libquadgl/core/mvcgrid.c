/* mvcgrid.c: the mean value grid, a subdivision of a convex screen quad whose vertices carry
 * the exact mean value weights, and the measured bound on how far its linear interpolation
 * strays from them.
 *
 * The grid has the four corners and the (k-1)^2 interior points of a k x k grid in the
 * bilinear parameters (u, v), graded towards the edges by u -> (1-b) u + b (1 - cos pi u) / 2.
 * No vertex lies on the quad's boundary: interior cells are split along one diagonal, and
 * the ring between the boundary and the outermost interior points is cut, per side, into one
 * triangle on the whole edge (its two corners and the side's middle ring point) and fans from
 * each corner to the ring points on its half of the side. Every boundary edge is then one
 * triangle edge between two corners, as in the split and the shader path's cover, so a
 * neighbour drawn by any path meets it without a T-junction; that costs nothing in accuracy
 * since the mean value weights are linear along each edge.
 *
 * Why graded: mean value weights are not differentiable at a corner (near corner i they are
 * a cone, 1 - r G(theta) with G not linear in the direction), so a uniform grid converges as
 * 1/k only; smaller cells near the boundary restore 1/k^2 in the measured range.
 *
 * The bound: the driver interpolates the weights linearly in screen space between the
 * vertices (perspective only divides by the corners' w, which is constant per corner). The
 * difference eps(p) from the exact screen weights reproduces affine functions, so it is a
 * multiple of the corners' screen affine dependency m (sum m_i = 0, sum m_i v_i = 0), and
 * |eps| depends on the quad's screen shape only. Its maximum over a quad, sampled densely, was
 * measured over random strictly convex quads whose four angles lie in [45, 135] degrees and
 * whose shortest edge is at least a third of the longest (the class qgl_mvcgrid_fits accepts); each tabulated bound is that maximum times 1.5, and the core
 * test re-derives the maxima on other random quads and fails when the margin drops below 1.25.
 * How eps turns into an attribute's error is the caller's part (see gl/subdiv.c). */
#include <quadgl/quadgl.h>

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

/* One row per tabulated k: the grading b and the bound on max |eps| (Euclidean norm of the
 * four weights' differences) for the class of qgl_mvcgrid_fits. */
static const struct {
    int k;
    double grade, bound;
} rows[] = {
    {2, 0.0, 0.27}, {4, 0.75, 0.175}, {6, 0.75, 0.09}, {8, 0.75, 0.058},
    {12, 0.75, 0.03}, {16, 0.75, 0.018}, {24, 0.75, 0.0085}, {32, 0.75, 0.005},
};
enum { NROWS = sizeof rows / sizeof rows[0] };

static qgl_mvcgrid grids[NROWS];
static pthread_once_t once = PTHREAD_ONCE_INIT;

static double graded(double t, double b)
{
    return (1 - b) * t + b * (1 - cos(M_PI * t)) * 0.5;
}

/* Vertex number of interior point (i, j), 1 <= i, j <= k - 1. */
static int interior(int k, int i, int j)
{
    return 4 + (i - 1) * (k - 1) + (j - 1);
}

/* Append triangle (a, b, c), counter-clockwise in (u, v) like the corners 0, 1, 2, 3. */
static void add_tri(qgl_mvcgrid *g, int a, int b, int c)
{
    const float *pa = g->uv[a], *pb = g->uv[b], *pc = g->uv[c];
    double o = (double)(pb[0] - pa[0]) * (pc[1] - pa[1]) - (double)(pb[1] - pa[1]) * (pc[0] - pa[0]);
    uint16_t *t = g->tri[g->ntris++];
    t[0] = (uint16_t)a;
    t[1] = (uint16_t)(o >= 0 ? b : c);
    t[2] = (uint16_t)(o >= 0 ? c : b);
}

/* The ring points along side s (0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0), from corner s to
 * corner s + 1. */
static int side_ring(int k, int s, int t)
{
    int q = t + 1;
    switch (s) {
    case 0: return interior(k, q, 1);
    case 1: return interior(k, k - 1, q);
    case 2: return interior(k, k - q, k - 1);
    default: return interior(k, 1, k - q);
    }
}

static void build_ring(qgl_mvcgrid *g, int k)
{
    int m = k - 1, mid = (m - 1) / 2;
    for (int s = 0; s < 4; s++) {
        int a = s, b = (s + 1) & 3;
        for (int t = 0; t < mid; t++)
            add_tri(g, a, side_ring(k, s, t), side_ring(k, s, t + 1));
        add_tri(g, a, b, side_ring(k, s, mid));
        for (int t = mid; t < m - 1; t++)
            add_tri(g, b, side_ring(k, s, t), side_ring(k, s, t + 1));
    }
}

static int build(qgl_mvcgrid *g, int k, double grade, double bound)
{
    g->k = k;
    g->bound = bound;
    g->nverts = 4 + (k - 1) * (k - 1);
    g->ntris = 0;
    g->uv = malloc((size_t)g->nverts * sizeof *g->uv);
    g->tri = malloc((size_t)(2 * (k - 2) * (k - 2) + 4 * (k - 1)) * sizeof *g->tri);
    if (!g->uv || !g->tri) {
        free(g->uv);
        free(g->tri);
        g->uv = NULL;
        g->tri = NULL;
        return 0;
    }
    static const float corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    memcpy(g->uv, corner, sizeof corner);
    for (int i = 1; i < k; i++)
        for (int j = 1; j < k; j++) {
            g->uv[interior(k, i, j)][0] = (float)graded((double)i / k, grade);
            g->uv[interior(k, i, j)][1] = (float)graded((double)j / k, grade);
        }
    for (int i = 1; i < k - 1; i++)
        for (int j = 1; j < k - 1; j++) {
            add_tri(g, interior(k, i, j), interior(k, i + 1, j), interior(k, i + 1, j + 1));
            add_tri(g, interior(k, i, j), interior(k, i + 1, j + 1), interior(k, i, j + 1));
        }
    build_ring(g, k);
    return 1;
}

static void build_all(void)
{
    for (int r = 0; r < NROWS; r++)
        if (!build(&grids[r], rows[r].k, rows[r].grade, rows[r].bound))
            grids[r].k = 0;
}

QGL_API int qgl_mvcgrid_count(void)
{
    return NROWS;
}

QGL_API const qgl_mvcgrid *qgl_mvcgrid_at(int i)
{
    if (i < 0 || i >= NROWS)
        return NULL;
    pthread_once(&once, build_all);
    return grids[i].k ? &grids[i] : NULL;
}

QGL_API const qgl_mvcgrid *qgl_mvcgrid_get(int k)
{
    for (int r = 0; r < NROWS; r++)
        if (rows[r].k == k)
            return qgl_mvcgrid_at(r);
    return NULL;
}

QGL_API int qgl_mvcgrid_choose(double limit)
{
    for (int r = 0; r < NROWS; r++)
        if (rows[r].bound <= limit)
            return r;
    return -1;
}

/* |cos| of the largest allowed departure from a right angle (45 degrees), and the shortest
 * edge allowed relative to the longest (a short edge makes the weights steep beside it). */
#define QGL__GRID_COS 0.70710678118654752
#define QGL__GRID_EDGE (1.0 / 3)

QGL_API int qgl_mvcgrid_fits(const double v[4][2])
{
    double sign = 0, lo = INFINITY, hi = 0;
    for (int i = 0; i < 4; i++) {
        const double *p = v[(i + 3) & 3], *q = v[i], *r = v[(i + 1) & 3];
        double ax = p[0] - q[0], ay = p[1] - q[1], bx = r[0] - q[0], by = r[1] - q[1];
        double cr = bx * ay - by * ax, dot = ax * bx + ay * by, la = ax * ax + ay * ay;
        double len = sqrt(la * (bx * bx + by * by));
        if (!(len > 0) || !(fabs(dot) <= QGL__GRID_COS * len) || !(cr != 0) || cr * sign < 0)
            return 0;
        sign = cr;
        lo = la < lo ? la : lo;
        hi = la > hi ? la : hi;
    }
    return lo >= QGL__GRID_EDGE * QGL__GRID_EDGE * hi;
}

static int strictly_convex(const double v[4][2])
{
    double turn[4];
    for (int i = 0; i < 4; i++) {
        const double *p = v[(i + 3) & 3], *q = v[i], *r = v[(i + 1) & 3];
        turn[i] = (q[0] - p[0]) * (r[1] - q[1]) - (q[1] - p[1]) * (r[0] - q[0]);
    }
    int pos = 0, neg = 0;
    for (int i = 0; i < 4; i++)
        pos += turn[i] > 0, neg += turn[i] < 0;
    return pos == 4 || neg == 4;
}

QGL_API void qgl_mvcgrid_points(const qgl_mvcgrid *g, const double v[4][2], double (*out)[2])
{
    for (int j = 0; j < g->nverts; j++) {
        double u = g->uv[j][0], w = g->uv[j][1];
        double a = (1 - u) * (1 - w), b = u * (1 - w), c = u * w, d = (1 - u) * w;
        for (int k = 0; k < 2; k++)
            out[j][k] = a * v[0][k] + b * v[1][k] + c * v[2][k] + d * v[3][k];
    }
}

/* Mean value weights mu (unnormalised) of n points strictly inside a strictly convex quad,
 * corners relative to the first point's frame: structure of arrays, one loop the compiler can
 * vectorise. tan(alpha/2) takes the form whose denominator does not cancel; inside, every
 * r_i and A_i (oriented) is positive, so no limit case arises. */
#if defined(__x86_64__) && defined(__GNUC__) && defined(__has_attribute)
#if __has_attribute(target_clones)
__attribute__((target_clones("avx2", "default")))
#endif
#endif
static void interior_mu(const double cx[4], const double cy[4], double orient, const double *px, const double *py,
                        int n, double *mu)
{
    for (int j = 0; j < n; j++) {
        double sx[4], sy[4], r[4], t[4];
        for (int i = 0; i < 4; i++) {
            sx[i] = cx[i] - px[j];
            sy[i] = cy[i] - py[j];
            r[i] = sqrt(sx[i] * sx[i] + sy[i] * sy[i]);
        }
        for (int i = 0; i < 4; i++) {
            int e = (i + 1) & 3;
            double a = orient * (sx[i] * sy[e] - sy[i] * sx[e]), d = sx[i] * sx[e] + sy[i] * sy[e];
            double rr = r[i] * r[e];
            double num = d > 0 ? a : rr - d, den = d > 0 ? rr + d : a;
            t[i] = num / den;
        }
        for (int i = 0; i < 4; i++)
            mu[4 * j + i] = (t[(i + 3) & 3] + t[i]) / r[i];
    }
}

QGL_API int qgl_mvcgrid_weights(const qgl_mvcgrid *g, const double clip[4][4], double (*v)[2], double (*persp)[4])
{
    double c[4][2], cx[4], cy[4];
    enum { CHUNK = 64 };
    for (int i = 0; i < 4; i++) {
        if (!(clip[i][3] > 0))
            return 0;
        c[i][0] = clip[i][0] / clip[i][3];
        c[i][1] = clip[i][1] / clip[i][3];
    }
    if (!strictly_convex(c))
        return 0;
    qgl_mvcgrid_points(g, c, v);
    for (int i = 0; i < 4; i++) /* relative to corner 0: small quads far out keep their digits */
        cx[i] = c[i][0] - c[0][0], cy[i] = c[i][1] - c[0][1];
    double orient = cx[1] * cy[2] - cy[1] * cx[2] > 0 ? 1 : -1;
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++)
            persp[i][k] = i == k;
    for (int j0 = 4; j0 < g->nverts; j0 += CHUNK) {
        int n = g->nverts - j0 < CHUNK ? g->nverts - j0 : CHUNK;
        double px[CHUNK], py[CHUNK], mu[4 * CHUNK];
        for (int j = 0; j < n; j++)
            px[j] = v[j0 + j][0] - c[0][0], py[j] = v[j0 + j][1] - c[0][1];
        interior_mu(cx, cy, orient, px, py, n, mu);
        for (int j = 0; j < n; j++) {
            double s = 0, *p = persp[j0 + j];
            for (int i = 0; i < 4; i++)
                s += p[i] = mu[4 * j + i] / clip[i][3];
            for (int i = 0; i < 4; i++)
                p[i] /= s;
        }
    }
    return 1;
}
