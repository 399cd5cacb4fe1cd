/* Quad subdivision into triangles: Bailey's bilinear n x n SuperQuad and Oliveira's adaptive scheme.
 *
 * Both produce a triangle soup of caller-laid-out vertices (every component interpolated the
 * same way) and split each cell along its 0-2 diagonal as (0,1,2), (0,2,3), which keeps the
 * quad's winding. The bilinear grid evaluates each grid point once, with an edge lerp that
 * gives bitwise the same point from either end (so quads sharing an edge share its points).
 * The adaptive scheme follows Oliveira's figure 11: a cell is emitted when its object-space
 * and texture-space parallelogram differences are below thresholds or its projected area is
 * below 200 pixels; otherwise its edge midpoints and centre split it into four. Unlike the
 * paper, which quarters the parent's area, each cell's area is measured from its own clip
 * corners (clip coordinates are affine in object space, so the midpoints project exactly). */
#include <quadgl/quadgl.h>

#include <stdlib.h>
#include <string.h>

#include "core_util.h"

QGL_API void qgl_mesh_free(qgl_mesh *m)
{
    if (!m)
        return;
    free(m->v);
    m->v = NULL;
    m->ntri = 0;
    m->cap = 0;
}

/* Room for `more` triangles (cap counts triangles). */
static int mesh_reserve(qgl_mesh *m, int stride, long more)
{
    if (m->ntri > 0 && m->stride != stride)
        return -1;
    if (m->ntri < 0 || m->cap < 0 || (m->cap > 0 && !m->v))
        return -1;
    long need = (long)m->ntri + more;
    if (need > (1L << 28) / stride)
        return -1;
    if (need > m->cap) {
        long cap = m->cap > 0 ? m->cap : 64;
        while (cap < need)
            cap *= 2;
        double *v = realloc(m->v, (size_t)cap * 3 * (size_t)stride * sizeof *v);
        if (!v)
            return -1;
        m->v = v;
        m->cap = (int)cap;
    }
    m->stride = stride;
    return 0;
}

static void mesh_push(qgl_mesh *m, const double *a, const double *b, const double *c)
{
    size_t sz = (size_t)m->stride * sizeof(double);
    double *dst = m->v + (size_t)m->ntri * 3 * (size_t)m->stride;
    memcpy(dst, a, sz);
    memcpy(dst + m->stride, b, sz);
    memcpy(dst + 2 * m->stride, c, sz);
    m->ntri++;
}

/* A cell with corners in GL order as two triangles sharing the 0-2 diagonal. */
static void push_cell(qgl_mesh *m, const double *c0, const double *c1, const double *c2, const double *c3)
{
    mesh_push(m, c0, c1, c2);
    mesh_push(m, c0, c2, c3);
}

/* A cell as four triangles around its centre: no diagonal is preferred, so the result does
 * not depend on which corner the quad starts at. The centre is the mean of the corners (the
 * bilinear value there), summed in opposite pairs so that every rotation of the corner order
 * gives the same bits. */
static void push_cell_centred(qgl_mesh *m, const double *c0, const double *c1, const double *c2, const double *c3)
{
    double mid[4096];
    for (int k = 0; k < m->stride; k++)
        mid[k] = 0.25 * ((c0[k] + c2[k]) + (c1[k] + c3[k]));
    mesh_push(m, c0, c1, mid);
    mesh_push(m, c1, c2, mid);
    mesh_push(m, c2, c3, mid);
    mesh_push(m, c3, c0, mid);
}

/* a + (b - a) i/n, evaluated from the nearer end so that lerp(a,b,i) == lerp(b,a,n-i) bitwise. */
static double lerp_sym(double a, double b, int i, int n)
{
    if (2 * i == n)
        return 0.5 * (a + b);
    if (2 * i < n)
        return a + (b - a) * ((double)i / n);
    return b + (a - b) * ((double)(n - i) / n);
}

QGL_API int qgl_subdiv_bilinear(const double *quad, int stride, int n, qgl_mesh *out)
{
    if (!quad || !out || stride < 1 || stride > 4096 || n < 1 || n > 4096)
        return -1;
    if (mesh_reserve(out, stride, 4L * n * n) < 0)
        return -1;
    double *grid = malloc((size_t)(n + 1) * (size_t)(n + 1) * (size_t)stride * sizeof *grid);
    if (!grid)
        return -1;
    const double *q0 = quad, *q1 = quad + stride, *q2 = quad + 2 * stride, *q3 = quad + 3 * stride;
    /* grid point (i, j) at s = i/n along 0->1 (and 3->2), t = j/n along 0->3 */
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            for (int k = 0; k < stride; k++) {
                double bottom = lerp_sym(q0[k], q1[k], i, n), top = lerp_sym(q3[k], q2[k], i, n);
                grid[((size_t)j * (n + 1) + i) * stride + k] = lerp_sym(bottom, top, j, n);
            }
#define G(i, j) (grid + ((size_t)(j) * (n + 1) + (i)) * stride)
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++)
            push_cell_centred(out, G(i, j), G(i + 1, j), G(i + 1, j + 1), G(i, j + 1));
#undef G
    free(grid);
    return 0;
}

/* ---- adaptive ----------------------------------------------------------------------------- */

typedef struct adaptive_ctx {
    int stride, pos_off, tex_off, clip_off;
    qgl_adaptive_params p;
    qgl_mesh *out;
    int failed;
} adaptive_ctx;

/* Oliveira's differences |V1.V2 - V3.V4| and |V1.V4 - V2.V3| below tol, on dim components. */
static int parallelogram_at(const double *c[4], int off, int dim, double tol)
{
    double q[4 * 3];
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < dim; k++)
            q[i * dim + k] = c[i][off + k];
    return qgl_is_parallelogram(q, dim, tol);
}

/* Projected area in pixels (shoelace on window coordinates); infinite when a corner is
 * not strictly in front of the eye, so the area criterion never stops such a cell. */
static double projected_area(const adaptive_ctx *cx, const double *c[4])
{
    double px[4][2], a = 0;
    for (int i = 0; i < 4; i++) {
        const double *h = c[i] + cx->clip_off;
        if (!(h[3] > 0))
            return INFINITY;
        px[i][0] = 0.5 * (h[0] / h[3] + 1) * cx->p.viewport[0];
        px[i][1] = 0.5 * (h[1] / h[3] + 1) * cx->p.viewport[1];
    }
    for (int i = 0; i < 4; i++)
        a += px[i][0] * px[(i + 1) & 3][1] - px[i][1] * px[(i + 1) & 3][0];
    return 0.5 * fabs(a);
}

static int cell_is_leaf(const adaptive_ctx *cx, const double *c[4], int depth)
{
    if (depth >= cx->p.max_depth)
        return 1;
    if (cx->clip_off >= 0 && cx->p.viewport[0] > 0 && cx->p.viewport[1] > 0 &&
        projected_area(cx, c) < cx->p.min_area_px)
        return 1;
    if (!parallelogram_at(c, cx->pos_off, 3, cx->p.threshold_q))
        return 0;
    return cx->tex_off < 0 || parallelogram_at(c, cx->tex_off, 2, cx->p.threshold_t);
}

static void midpoint(const double *a, const double *b, int n, double *m)
{
    for (int k = 0; k < n; k++)
        m[k] = (a[k] + b[k]) * 0.5;
}

static void adaptive_cell(adaptive_ctx *cx, const double *c[4], int depth)
{
    if (cx->failed)
        return;
    if (cell_is_leaf(cx, c, depth)) {
        if (mesh_reserve(cx->out, cx->stride, 2) < 0)
            cx->failed = 1;
        else
            push_cell(cx->out, c[0], c[1], c[2], c[3]);
        return;
    }
    int s = cx->stride;
    double *buf = malloc(5 * (size_t)s * sizeof *buf);
    if (!buf) {
        cx->failed = 1;
        return;
    }
    double *ab = buf, *bc = buf + s, *cd = buf + 2 * s, *da = buf + 3 * s, *mid = buf + 4 * s;
    midpoint(c[0], c[1], s, ab);
    midpoint(c[1], c[2], s, bc);
    midpoint(c[2], c[3], s, cd);
    midpoint(c[3], c[0], s, da);
    midpoint(ab, cd, s, mid);
    const double *k0[4] = {c[0], ab, mid, da}, *k1[4] = {ab, c[1], bc, mid};
    const double *k2[4] = {mid, bc, c[2], cd}, *k3[4] = {da, mid, cd, c[3]};
    adaptive_cell(cx, k0, depth + 1);
    adaptive_cell(cx, k1, depth + 1);
    adaptive_cell(cx, k2, depth + 1);
    adaptive_cell(cx, k3, depth + 1);
    free(buf);
}

static qgl_adaptive_params params_or_defaults(const qgl_adaptive_params *in)
{
    qgl_adaptive_params p = {0};
    if (in)
        p = *in;
    if (!(p.threshold_q > 0))
        p.threshold_q = 1e-3;
    if (!(p.threshold_t > 0))
        p.threshold_t = 1e-4;
    if (!(p.min_area_px > 0))
        p.min_area_px = 200;
    if (p.max_depth <= 0)
        p.max_depth = 8;
    if (p.max_depth > 10) /* 4^10 cells already */
        p.max_depth = 10;
    return p;
}

QGL_API int qgl_subdiv_adaptive(const double *quad, int stride, int pos_off, int tex_off, int clip_off,
                                const qgl_adaptive_params *params, qgl_mesh *out)
{
    if (!quad || !out || stride < 1 || stride > 4096 || pos_off < 0 || pos_off + 3 > stride ||
        tex_off + 2 > stride || tex_off < -1 || clip_off + 4 > stride || clip_off < -1)
        return -1;
    if (!qgl__all_finite(quad, 4 * stride) || mesh_reserve(out, stride, 2) < 0)
        return -1;
    adaptive_ctx cx = {stride, pos_off, tex_off, clip_off, params_or_defaults(params), out, 0};
    int ntri0 = out->ntri;
    const double *c[4] = {quad, quad + stride, quad + 2 * stride, quad + 3 * stride};
    adaptive_cell(&cx, c, 0);
    if (cx.failed) {
        out->ntri = ntri0;
        return -1;
    }
    return 0;
}
