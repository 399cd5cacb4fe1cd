/* fallback.c: the CPU path: subdivide a quad so the driver's fixed function draws the smooth
 * interpolant within a screen-space tolerance.
 *
 * Four forms, as the shader path weighs. Screen-space weights (method MVC): the quad's exact
 * screen cover (core classification) is cut into a uniform grid of n x n sub-triangles per
 * cover triangle; each grid point p gets the core's perspective weights lambda'(p) and is sent
 * as the homogeneous object point sum lambda'_i X_i with the attributes sum lambda'_i a_i: the
 * driver's transform maps it exactly back to p (the weights reproduce the point, eq. 2 and 9)
 * with the eq. 4 depth. View-invariant weights (every other method), planar quads: the quad's
 * cover in its own plane (qgl_plane_cover) is cut into a grid uniform in object space; each
 * grid point is a point of the cover triangle (sent as it is, so the picture is the quad's own
 * surface), weighed by the in-plane mean value weights of its position in the plane.
 * Non-planar quads in front of the eye: the bilinear patch of the corners sampled on an n x n
 * grid of its parameters, every cell as four triangles around its centre (no diagonal
 * preferred), each point a point of the patch weighed in the best-fit plane, as the shader
 * path's patch form. A corner behind the eye: the visible pieces of the split (external.c:
 * cut by the screen quad and the view volume) in grids uniform on screen, each grid point a
 * point of the split's surface weighed as the shader path weighs that quad (in the plane when
 * planar, else on screen). The driver's per-vertex work (lighting, texgen, fog, an
 * application's program) runs on interpolated inputs. n doubles until the driver's
 * interpolation of the grid weights over each sub-triangle, checked at its centroid and the
 * midpoints of its edges, differs from the true weights by at most tolerance_px relative to
 * the quad's size in pixels (weights error times diameter: how far, in pixels, the attribute
 * pattern is displaced); every triangle of a quad takes the finest n any of them needs, so
 * that they meet without T-junctions. Degenerate quads go as the plain split. Known limit:
 * grids of neighbouring quads differ along shared edges (T-junctions), which can open
 * sub-pixel cracks there. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl_internal.h"

#define MAX_N 64

typedef struct grid {
    int n;
    int persp;        /* uniform on screen: the driver interpolates between the grid's
                         vertices with weights 1/w (else uniform in object space: affinely) */
    double (*lam)[4]; /* weights per grid point (perspective weights in the screen form) */
    double (*pos)[4]; /* the corners' weights in the grid point's object position (plane and
                         patch forms, and quads behind the eye) */
    double *w;        /* clip w of the grid point's vertex */
} grid;

static int grid_alloc(grid *g, size_t npts)
{
    g->n = 1;
    g->lam = malloc(npts * sizeof *g->lam);
    g->pos = malloc(npts * sizeof *g->pos);
    g->w = malloc(npts * sizeof *g->w);
    return g->lam && g->pos && g->w;
}

static void grid_free(grid *g)
{
    free(g->lam);
    free(g->pos);
    free(g->w);
}

/* Grid point (i, j) of a triangle subdivided n times, row-major over i + j <= n. */
static int gidx(int n, int i, int j)
{
    return i * (n + 1) - i * (i - 1) / 2 + j;
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

/* Append the vertex at the object position sum pos_i X_i with the attributes sum lam_i a_i
 * (flat: the colour of corner flat, else -1). */
static void emit(qgl__verts *out, const qgl__verts *v, const size_t idx[4], const double pos[4], const double lam[4],
                 int flat)
{
    size_t i = out->n++;
    unsigned m = out->mask;
    lerp_attr(out->pos + 4 * i, v->pos, 4, idx, pos);
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

/* Grid point k: its position weights, or (the screen form) its weights, which are both. */
static const double *grid_pos(const grid *g, int k)
{
    return g->pos ? g->pos[k] : g->lam[k];
}

static void emit_point(qgl__verts *out, const qgl__verts *v, const size_t idx[4], const grid *g, int k, int flat)
{
    emit(out, v, idx, grid_pos(g, k), g->lam[k], flat);
}

static void emit_grid(qgl__verts *out, const qgl__verts *v, const size_t idx[4], const grid *g, int flat)
{
    int n = g->n;
    for (int i = 0; i < n; i++)
        for (int j = 0; j + i < n; j++) {
            emit_point(out, v, idx, g, gidx(n, i, j), flat);
            emit_point(out, v, idx, g, gidx(n, i + 1, j), flat);
            emit_point(out, v, idx, g, gidx(n, i, j + 1), flat);
            if (i + j + 2 > n)
                continue;
            emit_point(out, v, idx, g, gidx(n, i + 1, j), flat);
            emit_point(out, v, idx, g, gidx(n, i + 1, j + 1), flat);
            emit_point(out, v, idx, g, gidx(n, i, j + 1), flat);
        }
}

/* ---- what the grid interpolates: one weight function per form ------------------------------- */

/* A triangle (or the patch) to subdivide, and the weights at a point of it. */
typedef struct form form;
struct form {
    /* weights (and for the plane and patch forms the position weights) at parameters (a, b):
     * barycentric in the triangle, or (u, v) on the patch */
    void (*at)(const form *f, double a, double b, double lam[4], double pos[4]);
    double clip[4][4];  /* screen form: clip corners in pixels */
    double P[3][2];     /* screen form: the triangle's screen points */
    double cw[3][4];    /* plane form: the triangle's vertices as weights of the corners */
    double pw[3];       /* behind the eye: the clip w of the triangle's vertices */
    int inplane;        /* behind the eye: weighed in the plane (else on screen) */
    double obj[4][4];   /* plane and patch forms: homogeneous object corners */
    qgl_plane pl;
};

static void screen_at(const form *f, double a, double b, double lam[4], double pos[4])
{
    double x = f->P[0][0] + a * (f->P[1][0] - f->P[0][0]) + b * (f->P[2][0] - f->P[0][0]);
    double y = f->P[0][1] + a * (f->P[1][1] - f->P[0][1]) + b * (f->P[2][1] - f->P[0][1]);
    qgl_weights(f->clip, x, y, lam, NULL);
    memcpy(pos, lam, 4 * sizeof(double));
}

/* The in-plane weights of the object point with corner weights pos. */
static void weigh_in_plane(const form *f, const double pos[4], double lam[4])
{
    double h[4] = {0, 0, 0, 0}, p[3], xy[2];
    for (int c = 0; c < 4; c++)
        for (int k = 0; k < 4; k++)
            h[k] += pos[c] * f->obj[c][k];
    for (int k = 0; k < 3; k++)
        p[k] = h[k] / h[3];
    qgl_plane_coords(&f->pl, p, xy);
    qgl_weights_inplane(&f->pl, xy[0], xy[1], lam);
}

static void plane_at(const form *f, double a, double b, double lam[4], double pos[4])
{
    for (int c = 0; c < 4; c++)
        pos[c] = (1 - a - b) * f->cw[0][c] + a * f->cw[1][c] + b * f->cw[2][c];
    weigh_in_plane(f, pos, lam);
}

/* A quad behind the eye: (a, b) are screen parameters of a triangle of the split's surface
 * (its vertices P on screen, cw as corner weights); the surface point under them is the
 * perspective-correct combination, weighed in the plane or on screen. */
static void external_at(const form *f, double a, double b, double lam[4], double pos[4])
{
    double beta[3] = {(1 - a - b) / f->pw[0], a / f->pw[1], b / f->pw[2]};
    double sum = beta[0] + beta[1] + beta[2];
    for (int c = 0; c < 4; c++)
        pos[c] = (beta[0] * f->cw[0][c] + beta[1] * f->cw[1][c] + beta[2] * f->cw[2][c]) / sum;
    if (f->inplane) {
        weigh_in_plane(f, pos, lam);
        return;
    }
    double x = f->P[0][0] + a * (f->P[1][0] - f->P[0][0]) + b * (f->P[2][0] - f->P[0][0]);
    double y = f->P[0][1] + a * (f->P[1][1] - f->P[0][1]) + b * (f->P[2][1] - f->P[0][1]);
    qgl_weights(f->clip, x, y, lam, NULL);
}

static void patch_at(const form *f, double u, double v, double lam[4], double pos[4])
{
    pos[0] = (1 - u) * (1 - v), pos[1] = u * (1 - v), pos[2] = u * v, pos[3] = (1 - u) * v;
    weigh_in_plane(f, pos, lam);
}

/* ---- triangles: the screen and plane forms ----------------------------------------------- */

static void fill_grid(const form *f, grid *g)
{
    int n = g->n;
    for (int i = 0; i <= n; i++)
        for (int j = 0; j + i <= n; j++) {
            int k = gidx(n, i, j);
            double pos[4];
            f->at(f, (double)i / n, (double)j / n, g->lam[k], pos);
            if (g->pos)
                memcpy(g->pos[k], pos, sizeof pos);
            g->w[k] = 0;
            for (int c = 0; c < 4; c++)
                g->w[k] += pos[c] * f->clip[c][3];
        }
}

/* The points where the driver's interpolation over a sub-triangle is checked, as weights of
 * its vertices: the centroid, and the midpoints of the edges, where the error of a long thin
 * triangle (a piece of a quad behind the eye can be one) peaks and the centroid sees none. */
static const double check_at[4][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};

/* Largest weight error at the check points of the sub-triangles of g: the driver interpolates
 * the vertices' weights perspective-correctly on screen (a grid uniform on screen: weights
 * 1/w), affinely in object space (the plane form's grid is uniform there). */
static double grid_error(const form *f, const grid *g)
{
    int n = g->n;
    double err = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j + i < n; j++)
            for (int up = 0; up < 2; up++) {
                if (up && i + j + 2 > n)
                    continue;
                int vi[3] = {i + up, i + 1, i}, vj[3] = {j + up, j, j + 1}, k[3];
                double fw[3];
                for (int v = 0; v < 3; v++) {
                    k[v] = gidx(n, vi[v], vj[v]);
                    fw[v] = g->persp ? 1.0 / g->w[k[v]] : 1;
                }
                for (int m = 0; m < 4; m++) {
                    const double *mix = check_at[m];
                    double a = 0, b = 0, exact[4], pos[4], num[4] = {0}, den = 0;
                    for (int v = 0; v < 3; v++) {
                        a += mix[v] * vi[v] / n, b += mix[v] * vj[v] / n;
                        den += mix[v] * fw[v];
                        for (int c = 0; c < 4; c++)
                            num[c] += mix[v] * fw[v] * g->lam[k[v]][c];
                    }
                    f->at(f, a, b, exact, pos);
                    for (int c = 0; c < 4; c++)
                        err = fmax(err, fabs(num[c] / den - exact[c]));
                }
            }
    return err;
}

/* The grid size triangle f needs: n doubles until the grid is within tolerance (diam: the
 * quad's size in pixels), MAX_N, or cells under a pixel. */
static int grid_size(qgl_context *ctx, const form *f, grid *g, double diam)
{
    for (g->n = 1; g->n < MAX_N && diam / g->n >= 1; g->n *= 2) {
        fill_grid(f, g);
        if (grid_error(f, g) * diam <= ctx->tolerance_px)
            break;
    }
    return g->n;
}

/* Puts triangle t of a set into f. */
typedef void (*tri_loader)(form *f, const void *set, int t);

/* Subdivide the ntri triangles of a set with one grid size, the finest any of them needs:
 * triangles sharing an edge then place the same vertices on it (a T-junction's vertex,
 * snapped to the rasterizer's subpixel grid, opens holes along the edge). keep_pos: the
 * vertices are the points the form gives (else the weights place them); persp: the form's
 * parameters are uniform on screen. */
static int subdivide_tris(qgl_context *ctx, form *f, tri_loader load, const void *set, int ntri, int keep_pos,
                          int persp, double diam, const qgl__verts *v, const size_t idx[4], int flat, qgl__verts *out)
{
    grid g;
    int n = 1, ok = grid_alloc(&g, (MAX_N + 1) * (MAX_N + 2) / 2);
    g.persp = persp;
    if (ok && !keep_pos) {
        free(g.pos);
        g.pos = NULL;
    }
    for (int t = 0; t < ntri && ok; t++) {
        load(f, set, t);
        int m = grid_size(ctx, f, &g, diam);
        n = m > n ? m : n;
    }
    for (int t = 0; t < ntri && ok; t++) {
        load(f, set, t);
        g.n = n;
        fill_grid(f, &g);
        ok = qgl__verts_reserve(out, out->n + 3 * (size_t)n * n, out->mask);
        if (ok)
            emit_grid(out, v, idx, &g, flat);
    }
    grid_free(&g);
    return ok;
}

/* ---- the patch form ---------------------------------------------------------------------- */

/* Screen position in pixels of the object point with corner weights pos. */
static void screen_of(const form *f, const double pos[4], double out[2])
{
    double x = 0, y = 0, w = 0;
    for (int c = 0; c < 4; c++)
        x += pos[c] * f->clip[c][0], y += pos[c] * f->clip[c][1], w += pos[c] * f->clip[c][3];
    out[0] = x / w, out[1] = y / w;
}

/* How far, in pixels, an n x n patch grid displaces the attribute pattern, checked at the
 * centroid of each triangle and the midpoints of its two spokes (its third side is an edge
 * line of the patch, exact): the weights' interpolation error times the quad's size, or the
 * distance on screen between the triangle's point and the patch point of the same parameters
 * (the triangles are chords of the curved patch), whichever is larger. */
static double patch_error(const form *f, int n, double diam)
{
    static const double cu[5] = {0, 1, 1, 0, 0.5}, cv[5] = {0, 0, 1, 1, 0.5};
    /* the check points as weights of the triangle's corner a, corner b and the centre */
    static const double mix[3][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    double err = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double lam[5][4], pos[5][4];
            for (int c = 0; c < 5; c++)
                f->at(f, (i + cu[c]) / n, (j + cv[c]) / n, lam[c], pos[c]);
            for (int t = 0; t < 4; t++) {
                const int v3[3] = {t, (t + 1) & 3, 4};
                for (int m = 0; m < 3; m++) {
                    double u = 0, v = 0, exact[4], p[4], chord[4], sp[2], sc[2];
                    for (int k = 0; k < 3; k++)
                        u += mix[m][k] * cu[v3[k]], v += mix[m][k] * cv[v3[k]];
                    f->at(f, (i + u) / n, (j + v) / n, exact, p);
                    for (int c = 0; c < 4; c++) {
                        double l = 0;
                        chord[c] = 0;
                        for (int k = 0; k < 3; k++) {
                            l += mix[m][k] * lam[v3[k]][c];
                            chord[c] += mix[m][k] * pos[v3[k]][c];
                        }
                        err = fmax(err, fabs(l - exact[c]) * diam);
                    }
                    screen_of(f, p, sp);
                    screen_of(f, chord, sc);
                    err = fmax(err, hypot(sp[0] - sc[0], sp[1] - sc[1]));
                }
            }
        }
    return err;
}

static int subdivide_patch(qgl_context *ctx, const form *f, double diam, const qgl__verts *v, const size_t idx[4],
                           int flat, qgl__verts *out)
{
    int n = 1;
    while (n < MAX_N && diam / n >= 1 && patch_error(f, n, diam) > ctx->tolerance_px)
        n *= 2;
    if (!qgl__verts_reserve(out, out->n + 12 * (size_t)n * n, out->mask))
        return 0;
    static const double cu[5] = {0, 1, 1, 0, 0.5}, cv[5] = {0, 0, 1, 1, 0.5};
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double lam[5][4], pos[5][4];
            for (int c = 0; c < 5; c++)
                f->at(f, (i + cu[c]) / n, (j + cv[c]) / n, lam[c], pos[c]);
            for (int t = 0; t < 4; t++) {
                int a = t, b = (t + 1) & 3;
                emit(out, v, idx, pos[a], lam[a], flat);
                emit(out, v, idx, pos[b], lam[b], flat);
                emit(out, v, idx, pos[4], lam[4], flat);
            }
        }
    return 1;
}

/* ---- per quad ---------------------------------------------------------------------------- */

static double diameter(const double P[4][2])
{
    double d = 0;
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++)
            d = fmax(d, hypot(P[a][0] - P[b][0], P[a][1] - P[b][1]));
    return d;
}

/* The plain split, for quads the screen cover cannot describe (degenerate, non-finite). */
static int emit_split(const qgl__verts *v, const size_t idx[4], int flat, qgl__verts *out)
{
    static const int tris[6] = {0, 1, 2, 0, 2, 3};
    if (!qgl__verts_reserve(out, out->n + 6, out->mask))
        return 0;
    for (int k = 0; k < 6; k++) {
        double lam[4] = {0};
        lam[tris[k]] = 1;
        emit(out, v, idx, lam, lam, flat);
    }
    return 1;
}

/* The screen form's triangles: the screen cover's, on its points (corners and crossing). */
typedef struct screen_set {
    const qgl_cover *cov;
    const double (*P)[2];
} screen_set;

static void load_screen(form *f, const void *set, int t)
{
    const screen_set *s = set;
    for (int k = 0; k < 3; k++)
        memcpy(f->P[k], s->P[s->cov->tri[t][k]], sizeof f->P[k]);
}

static int subdivide_screen(qgl_context *ctx, form *f, const qgl__verts *v, const size_t idx[4], int flat,
                            qgl__verts *out)
{
    double P[5][2];
    qgl_cover cov;
    int kind = qgl_classify_clip(f->clip, &cov);
    if (kind < 0 || kind == QGL_QUAD_DEGENERATE || cov.ntri == 0)
        return emit_split(v, idx, flat, out);
    for (int c = 0; c < 4; c++)
        P[c][0] = f->clip[c][0] / f->clip[c][3], P[c][1] = f->clip[c][1] / f->clip[c][3];
    P[4][0] = cov.cross[0], P[4][1] = cov.cross[1];
    double diam = diameter((const double(*)[2])P);
    screen_set set = {&cov, P};
    f->at = screen_at;
    return subdivide_tris(ctx, f, load_screen, &set, cov.ntri, 0, 1, diam, v, idx, flat, out);
}

/* The in-plane cover's vertex k (a corner, or 4: the crossing point on edge a, a+1 at the
 * in-plane parameter t, made homogeneous with the object w) as corner weights. */
static void cover_weights(const form *f, const qgl_cover *cov, int k, double cw[4])
{
    memset(cw, 0, 4 * sizeof(double));
    if (k < 4) {
        cw[k] = 1;
        return;
    }
    int a = cov->cross_edge, b = a + 1;
    double t = cov->cross_t, wa = f->obj[a][3], wb = f->obj[b][3];
    double s = t * wa / ((1 - t) * wb + t * wa);
    cw[a] = 1 - s;
    cw[b] = s;
}

static void load_plane(form *f, const void *set, int t)
{
    const qgl_cover *cov = set;
    for (int k = 0; k < 3; k++)
        cover_weights(f, cov, cov->tri[t][k], f->cw[k]);
}

static int subdivide_plane(qgl_context *ctx, form *f, double diam, const qgl__verts *v, const size_t idx[4], int flat,
                           qgl__verts *out)
{
    qgl_cover cov;
    int kind = qgl_plane_cover(&f->pl, &cov);
    if (kind < 0 || kind == QGL_QUAD_DEGENERATE)
        return 1;
    f->at = plane_at;
    return subdivide_tris(ctx, f, load_plane, &cov, cov.ntri, 1, 0, diam, v, idx, flat, out);
}

/* Screen position (pixels) and clip w of the point with corner weights cw. */
static double project(const form *f, const double cw[4], double P[2])
{
    double x = 0, y = 0, w = 0;
    for (int c = 0; c < 4; c++)
        x += cw[c] * f->clip[c][0], y += cw[c] * f->clip[c][1], w += cw[c] * f->clip[c][3];
    P[0] = x / w, P[1] = y / w;
    return w;
}

/* A triangle of a piece of a quad behind the eye: corner weights, screen points, clip w. */
typedef struct ext_tri {
    double cw[3][4], P[3][2], w[3];
} ext_tri;

static void load_external(form *f, const void *set, int t)
{
    const ext_tri *e = (const ext_tri *)set + t;
    memcpy(f->cw, e->cw, sizeof f->cw);
    memcpy(f->P, e->P, sizeof e->P);
    memcpy(f->pw, e->w, sizeof f->pw);
}

/* A quad with a corner behind the eye: the visible pieces of its split (external.c), each
 * cut into triangles from its first vertex and subdivided uniformly on screen, so the grid is
 * as fine where the surface comes close to the eye as elsewhere; the vertices are points of
 * the split's surface, which the driver clips where the shader path's cover is clipped, and
 * carry the in-plane weights (inplane) or H&T's screen-space ones. */
static int subdivide_external(qgl_context *ctx, form *f, const double clip[4][4], int inplane, const qgl__verts *v,
                              const size_t idx[4], int flat, qgl__verts *out)
{
    qgl__piece pc[QGL__PIECES_MAX];
    int n = qgl__external_pieces(clip, 0, pc, QGL__PIECES_MAX), ntri = 0;
    ext_tri *tri = malloc(QGL__PIECES_MAX * (QGL__PIECE_VERTS - 2) * sizeof *tri);
    if (!tri)
        return 0;
    double diam = 0, lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int i = 0; i < n; i++)
        for (int k = 1; k + 1 < pc[i].n; k++) {
            ext_tri *e = tri + ntri;
            const int fan[3] = {0, k, k + 1};
            int visible = 1;
            for (int j = 0; j < 3; j++) {
                memcpy(e->cw[j], pc[i].cw[fan[j]], sizeof e->cw[j]);
                e->w[j] = project(f, e->cw[j], e->P[j]);
                visible &= e->w[j] > 0; /* 0 only at the eye itself */
            }
            for (int j = 0; j < 3 && visible; j++)
                for (int c = 0; c < 2; c++)
                    lo[c] = fmin(lo[c], e->P[j][c]), hi[c] = fmax(hi[c], e->P[j][c]);
            ntri += visible;
        }
    if (ntri)
        diam = hypot(hi[0] - lo[0], hi[1] - lo[1]);
    f->at = external_at;
    f->inplane = inplane;
    int ok = subdivide_tris(ctx, f, load_external, tri, ntri, 1, 1, diam, v, idx, flat, out);
    free(tri);
    return ok;
}

int qgl__subdivide(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t q,
                   qgl__verts *out)
{
    size_t idx[4];
    form f;
    double pos[4][3], P[4][2];
    /* clip x and y scaled by the viewport's half size: screen points in pixels from its
     * centre, so the weights are those of the quad as it appears (as on the shader path) */
    const double scale[4] = {0.5 * st->xf.viewport[2], 0.5 * st->xf.viewport[3], 1, 1};
    double clip[4][4];
    int front = 1, finite_obj = 1, seen = 0;
    for (int c = 0; c < 4; c++) {
        idx[c] = qgl__corner(topo, q, c);
        for (int k = 0; k < 4; k++) {
            clip[c][k] = ctx->clip[4 * idx[c] + k];
            f.clip[c][k] = clip[c][k] * scale[k];
            f.obj[c][k] = v->pos[4 * idx[c] + k];
        }
        seen |= f.clip[c][3] > 0;
        front &= f.clip[c][3] > 0;
        finite_obj &= f.obj[c][3] > 0;
        for (int k = 0; k < 3 && finite_obj; k++)
            pos[c][k] = f.obj[c][k] / f.obj[c][3];
        if (front)
            P[c][0] = f.clip[c][0] / f.clip[c][3], P[c][1] = f.clip[c][1] / f.clip[c][3];
    }
    int flat = st->shade_model == GL_FLAT ? qgl__flat_corner(ctx, st, topo) : -1;
    int framed = finite_obj && qgl_plane_frame(pos, &f.pl) == 0;
    if (!seen)
        return 1; /* wholly behind the eye: the driver would clip all of it */
    if (!front) { /* weighed as on the shader path (draw.c's plan_quad) */
        int inplane = ctx->method != QGL_METHOD_MVC && framed && qgl__external_planar(v, idx);
        return subdivide_external(ctx, &f, (const double(*)[4])clip, inplane, v, idx, flat, out);
    }
    if (ctx->method == QGL_METHOD_MVC || !framed)
        return subdivide_screen(ctx, &f, v, idx, flat, out);
    double diam = diameter((const double(*)[2])P);
    if (qgl__planar(pos))
        return subdivide_plane(ctx, &f, diam, v, idx, flat, out);
    f.at = patch_at;
    return subdivide_patch(ctx, &f, diam, v, idx, flat, out);
}
