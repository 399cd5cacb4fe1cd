/* fallback.c: the CPU path: subdivide a quad so the driver's fixed function draws the MVC
 * interpolant within a screen-space tolerance.
 *
 * The quad's exact screen cover (core classification) is cut into a uniform grid of n x n
 * sub-triangles per cover triangle. Each grid point p gets the core's perspective weights
 * lambda'(p), and is sent as the homogeneous object point sum lambda'_i X_i with the
 * attributes sum lambda'_i a_i: the driver's transform maps it exactly back to p (the weights
 * reproduce the point, eq. 2 and 9) with the eq. 4 depth, and its per-vertex work (lighting,
 * texgen, fog, an application's program) runs on interpolated inputs. n doubles until the
 * driver's perspective-correct interpolation of the grid weights, checked at every
 * sub-triangle's centroid, differs from the true weights by at most tolerance_px relative to
 * the quad's size in pixels (weights error times diameter: how far, in pixels, the attribute
 * pattern is displaced). Quads with a corner at or behind the eye, and degenerate ones, are
 * sent as the plain split. Known limit: grids of neighbouring quads differ along shared
 * edges (T-junctions), which can open sub-pixel cracks there. */
#include <math.h>
#include <stdlib.h>

#include "gl_internal.h"

#define MAX_N 64

typedef struct grid {
    int n;
    double (*lam)[4]; /* perspective weights per grid point */
    double *w;        /* clip w of the grid point's vertex */
} grid;

/* Grid point (i, j) of a triangle subdivided n times, row-major over i + j <= n. */
static int gidx(int n, int i, int j)
{
    return i * (n + 1) - i * (i - 1) / 2 + j;
}

static void fill_grid(const double clip[4][4], const double P[3][2], grid *g)
{
    int n = g->n;
    for (int i = 0; i <= n; i++)
        for (int j = 0; j + i <= n; j++) {
            double a = (double)i / n, b = (double)j / n;
            double x = P[0][0] + a * (P[1][0] - P[0][0]) + b * (P[2][0] - P[0][0]);
            double y = P[0][1] + a * (P[1][1] - P[0][1]) + b * (P[2][1] - P[0][1]);
            int k = gidx(n, i, j);
            qgl_weights(clip, x, y, g->lam[k], NULL);
            g->w[k] = 0;
            for (int c = 0; c < 4; c++)
                g->w[k] += g->lam[k][c] * clip[c][3];
        }
}

/* Largest weight error at the centroids of the sub-triangles of g. */
static double grid_error(const double clip[4][4], const double P[3][2], const grid *g)
{
    int n = g->n;
    double err = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j + i < n; j++)
            for (int up = 0; up < 2; up++) {
                if (up && i + j + 2 > n)
                    continue;
                int k[3] = {gidx(n, i, j), gidx(n, i + 1, j), gidx(n, i, j + 1)};
                double a = (i + 1.0 / 3) / n, b = (j + 1.0 / 3) / n;
                if (up) {
                    k[0] = gidx(n, i + 1, j + 1);
                    a = (i + 2.0 / 3) / n, b = (j + 2.0 / 3) / n;
                }
                double x = P[0][0] + a * (P[1][0] - P[0][0]) + b * (P[2][0] - P[0][0]);
                double y = P[0][1] + a * (P[1][1] - P[0][1]) + b * (P[2][1] - P[0][1]);
                double exact[4], num[4] = {0}, den = 0;
                qgl_weights(clip, x, y, exact, NULL);
                for (int v = 0; v < 3; v++) {
                    double f = 1.0 / g->w[k[v]];
                    den += f;
                    for (int c = 0; c < 4; c++)
                        num[c] += f * g->lam[k[v]][c];
                }
                for (int c = 0; c < 4; c++)
                    err = fmax(err, fabs(num[c] / den - exact[c]));
            }
    return err;
}

static void lerp_attr(float *dst, const float *src, int dim, const size_t idx[4], const double lam[4])
{
    for (int k = 0; k < dim; k++) {
        double s = 0;
        for (int c = 0; c < 4; c++)
            s += lam[c] * src[dim * idx[c] + k];
        dst[k] = (float)s;
    }
}

/* Append the vertex with weights lam (flat: the colour of corner flat, else -1). */
static void emit(qgl__verts *out, const qgl__verts *v, const size_t idx[4], const double lam[4], int flat)
{
    size_t i = out->n++;
    unsigned m = out->mask;
    lerp_attr(out->pos + 4 * i, v->pos, 4, idx, lam);
    if (m & QGL__A_COLOR) {
        if (flat >= 0)
            for (int k = 0; k < 4; k++)
                out->col[4 * i + k] = v->col[4 * idx[flat] + k];
        else
            lerp_attr(out->col + 4 * i, v->col, 4, idx, lam);
    }
    if (m & QGL__A_NORMAL)
        lerp_attr(out->nrm + 3 * i, v->nrm, 3, idx, lam);
    if (m & QGL__A_COLOR2)
        lerp_attr(out->col2 + 3 * i, v->col2, 3, idx, lam);
    if (m & QGL__A_FOG)
        lerp_attr(out->fog + i, v->fog, 1, idx, lam);
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
        if (m & (QGL__A_TEX0 << u))
            lerp_attr(out->tex[u] + 4 * i, v->tex[u], 4, idx, lam);
}

static void emit_grid(qgl__verts *out, const qgl__verts *v, const size_t idx[4], const grid *g, int flat)
{
    int n = g->n;
    for (int i = 0; i < n; i++)
        for (int j = 0; j + i < n; j++) {
            emit(out, v, idx, g->lam[gidx(n, i, j)], flat);
            emit(out, v, idx, g->lam[gidx(n, i + 1, j)], flat);
            emit(out, v, idx, g->lam[gidx(n, i, j + 1)], flat);
            if (i + j + 2 > n)
                continue;
            emit(out, v, idx, g->lam[gidx(n, i + 1, j)], flat);
            emit(out, v, idx, g->lam[gidx(n, i + 1, j + 1)], flat);
            emit(out, v, idx, g->lam[gidx(n, i, j + 1)], flat);
        }
}

static double diameter(const double P[5][2])
{
    double d = 0;
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++)
            d = fmax(d, hypot(P[a][0] - P[b][0], P[a][1] - P[b][1]));
    return d;
}

/* Subdivide cover triangle tri until the grid is within tolerance, then emit it. */
static int subdivide_tri(qgl_context *ctx, const double clip[4][4], const double P5[5][2], const unsigned char tri[3],
                         double diam, const qgl__verts *v, const size_t idx[4], int flat, qgl__verts *out)
{
    double P[3][2];
    for (int k = 0; k < 3; k++)
        P[k][0] = P5[tri[k]][0], P[k][1] = P5[tri[k]][1];
    size_t npts = (MAX_N + 1) * (MAX_N + 2) / 2;
    grid g = {1, malloc(npts * sizeof *g.lam), malloc(npts * sizeof *g.w)};
    if (!g.lam || !g.w) {
        free(g.lam);
        free(g.w);
        return 0;
    }
    for (;;) {
        fill_grid(clip, P, &g);
        if (g.n >= MAX_N || diam / g.n < 1 || grid_error(clip, P, &g) * diam <= ctx->tolerance_px)
            break;
        g.n *= 2;
    }
    int ok = qgl__verts_reserve(out, out->n + 3 * (size_t)g.n * g.n, out->mask);
    if (ok)
        emit_grid(out, v, idx, &g, flat);
    free(g.lam);
    free(g.w);
    return ok;
}

/* The plain split, for quads the cover cannot describe (corners behind the eye). */
static int emit_split(const qgl__verts *v, const size_t idx[4], int flat, qgl__verts *out)
{
    static const int tris[6] = {0, 1, 2, 0, 2, 3};
    if (!qgl__verts_reserve(out, out->n + 6, out->mask))
        return 0;
    for (int k = 0; k < 6; k++) {
        double lam[4] = {0};
        lam[tris[k]] = 1;
        emit(out, v, idx, lam, flat);
    }
    return 1;
}

int qgl__subdivide(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t q,
                   qgl__verts *out)
{
    size_t idx[4];
    double clip[4][4], P[5][2];
    /* clip x and y scaled by the viewport's half size: screen points in pixels from its
     * centre, so the weights are those of the quad as it appears (as on the shader path) */
    const double scale[4] = {0.5 * st->viewport[2], 0.5 * st->viewport[3], 1, 1};
    for (int c = 0; c < 4; c++) {
        idx[c] = qgl__corner(topo, q, c);
        for (int k = 0; k < 4; k++)
            clip[c][k] = ctx->clip[4 * idx[c] + k] * scale[k];
    }
    int flat = st->shade_model == GL_FLAT ? qgl__flat_corner(ctx, st, topo) : -1;
    qgl_cover cov;
    int kind = qgl_classify_clip(clip, &cov);
    if (kind < 0 || kind == QGL_QUAD_EXTERNAL || kind == QGL_QUAD_DEGENERATE || cov.ntri == 0)
        return emit_split(v, idx, flat, out);
    for (int c = 0; c < 4; c++)
        P[c][0] = clip[c][0] / clip[c][3], P[c][1] = clip[c][1] / clip[c][3];
    P[4][0] = cov.cross[0], P[4][1] = cov.cross[1];
    double diam = diameter(P);
    for (int t = 0; t < cov.ntri; t++)
        if (!subdivide_tri(ctx, clip, P, cov.tri[t], diam, v, idx, flat, out))
            return 0;
    return 1;
}
