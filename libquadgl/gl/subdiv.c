/* subdiv.c: the mean value grid path: a quad drawn as the core's grid, exact weights at its
 * vertices, the driver's own fixed function between them.
 *
 * Which quads: a state whose per-vertex work is affine in the captured attributes (unlit,
 * no texgen, no COMBINE, no per-vertex materials, the shader path's model), so that running
 * it on interpolated inputs at a grid vertex gives the interpolated per-corner results (the
 * picture the shader path draws there); quads in front of the eye whose pixel-space screen
 * quad is in the class of the grid's bound (qgl_mvcgrid_fits: concave and bow-tie covers,
 * sharp or thin quads keep the shader path). The error: the driver interpolates the screen
 * weights linearly between the vertices (its perspective correction divides by each corner's
 * constant w), so the weights it reaches differ from the exact ones by eps(p), a multiple of
 * the corners' screen affine dependency m with |eps| <= the grid's bound. An attribute f
 * then errs by W(p) sum_i (eps_i / w_i) (f_i - f(p)), W the interpolated w: at most bound
 * times the residual of f along n_i = m_i w_max / w_i (unit m), which is the planner's gain
 * machinery (qgl__gain_limit) with this n. The coarsest grid within budget is taken, in AUTO
 * only where the calibrated cost model (calibrate.c) finds it cheaper than the shader path.
 * Under the view-invariant methods only planar quads take it, laid out and weighed in their
 * own plane (inplane_corners), so the grid's picture is as view-invariant as the shader path's.
 * Drawing: per quad, the vertices' perspective weights (the core, vectorised over the
 * vertices), then position and attributes as those weights' combinations of the corners'
 * (the homogeneous object point maps exactly to the grid point, its depth is eq. 4's, on the
 * plane for a planar quad), corners copied bit for bit so that edges meet the neighbours'
 * exactly; flat shading gives every vertex the provoking corner's colours. All vertices of a
 * run go interleaved into our own buffer behind a vertex array object of our own (the
 * batch's stays as it is for the other runs), with indices from the grids' templates, in one
 * draw with the application's state, as the split is drawn. Buffers only grow. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl_internal.h"

/* The attributes the grid streams (position always), floats per vertex in our layout. */
static const struct {
    unsigned bit;
    int size;
} streams[] = {{QGL__A_COLOR, 4}, {QGL__A_COLOR2, 3}, {QGL__A_FOG, 1}, {QGL__A_TEX0, 4},
               {QGL__A_TEX0 << 1, 4}, {QGL__A_TEX0 << 2, 4}, {QGL__A_TEX0 << 3, 4}};
enum { NSTREAMS = sizeof streams / sizeof streams[0], MAX_GRID_VERTS = 1024 };

struct qgl__grid {
    GLuint vao;            /* ours: its arrays point into the stream buffer */
    unsigned char *k;      /* per quad of the batch: the grid chosen */
    size_t k_cap;
    unsigned char *moved;  /* the same after qgl__grid_regroup, swapped in */
    size_t moved_cap;
    float *verts;
    size_t verts_cap;      /* floats */
    uint32_t *idx;
    size_t idx_cap;
    unsigned enabled;      /* attribute arrays enabled in our VAO (QGL__A_* bits) */
    double pts[MAX_GRID_VERTS][2], persp[MAX_GRID_VERTS][4];
};

static int grow(void **p, size_t *cap, size_t n, size_t elem)
{
    if (n <= *cap)
        return 1;
    size_t c = n > 2 * *cap ? n : 2 * *cap;
    void *q = realloc(*p, c * elem);
    if (!q)
        return 0;
    *p = q;
    *cap = c;
    return 1;
}

static struct qgl__grid *grid_of(qgl_context *ctx)
{
    if (ctx->grid || !ctx->has_vao)
        return ctx->grid;
    struct qgl__grid *g = calloc(1, sizeof *g);
    if (!g)
        return NULL;
    ctx->gl.GenVertexArrays(1, &g->vao);
    ctx->grid = g;
    return g;
}

void qgl__grid_free(qgl_context *ctx)
{
    struct qgl__grid *g = ctx->grid;
    if (!g)
        return;
    if (!ctx->gl_gone)
        ctx->gl.DeleteVertexArrays(1, &g->vao);
    free(g->k);
    free(g->moved);
    free(g->verts);
    free(g->idx);
    free(g);
    ctx->grid = NULL;
}

int qgl__grid_regroup(qgl_context *ctx, const unsigned char *path, const size_t *to, size_t nq)
{
    struct qgl__grid *gr = ctx->grid;
    if (!gr)
        return 1; /* no quad took the grid */
    if (!grow((void **)&gr->moved, &gr->moved_cap, nq, 1))
        return 0;
    for (size_t q = 0; q < nq; q++)
        if ((path[q] & QGL__P_KIND) == QGL__P_GRID)
            gr->moved[to[q]] = gr->k[q];
    unsigned char *k = gr->k;
    size_t cap = gr->k_cap;
    gr->k = gr->moved, gr->k_cap = gr->moved_cap;
    gr->moved = k, gr->moved_cap = cap;
    return 1;
}

/* ---- planning ------------------------------------------------------------------------------ */

/* The state's per-vertex work is affine in the captured attributes and the budgets can judge
 * every attribute (see the file comment). */
static int state_allows(const qgl_context *ctx, const qgl__state *st, int planar)
{
    const qgl__key *k = &st->ffp;
    if (!ctx->has_vao || !st->modelled || st->nonaffine || st->pv_material || ctx->split_error < 0 ||
        (k->flags & QGL__KF_LIGHTING) || (!planar && k->fog && (k->flags & QGL__KF_FOG_DEPTH)))
        return 0;
    for (int u = 0; u < k->nunits; u++) {
        const qgl__unit_key *uk = &k->unit[u];
        if (uk->env == QGL__E_COMBINE || uk->gen[0] || uk->gen[1] || uk->gen[2] || uk->gen[3])
            return 0;
    }
    return 1;
}

/* Unit affine dependency of four screen points (sum m = 0, sum m v = 0): the cofactors. */
static int screen_dependency(const double v[4][2], double m[4])
{
    for (int i = 0; i < 4; i++) {
        const double *a = v[(i + 1) & 3], *b = v[(i + 2) & 3], *c = v[(i + 3) & 3];
        double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        m[i] = i & 1 ? -area : area;
    }
    double len = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2] + m[3] * m[3]);
    if (!(len > 0 && len < INFINITY))
        return 0;
    for (int i = 0; i < 4; i++)
        m[i] /= len;
    return 1;
}

/* Area of the screen quad (pixels), at most the viewport's. */
static double screen_area(const double v[4][2], const GLint vp[4])
{
    double a = 0;
    for (int i = 0; i < 4; i++)
        a += v[i][0] * v[(i + 1) & 3][1] - v[i][1] * v[(i + 1) & 3][0];
    a = fabs(a) * 0.5;
    double whole = (double)vp[2] * vp[3];
    return a < whole ? a : whole;
}

/* The view-invariant methods weigh a planar quad in its own plane: its grid is laid out there
 * (the in-plane corners with w = 1, whose screen weights are the in-plane mean value weights),
 * and the rasterizer's perspective-correct interpolation between the vertices is linear on the
 * surface, so the bound holds in the plane along the in-plane corners' dependency, whatever
 * the view. The corners' object w must be 1 (the vertices are the weights' combinations of the
 * object positions). 0 when the quad spans no plane. */
static int inplane_corners(const qgl__verts *v, const size_t idx[4], double out[4][2])
{
    double p[4][3];
    qgl_plane pl;
    for (int c = 0; c < 4; c++) {
        const float *q = v->pos + 4 * idx[c];
        if (q[3] != 1)
            return 0;
        for (int k = 0; k < 3; k++)
            p[c][k] = q[k];
    }
    if (qgl_plane_frame(p, &pl) != 0)
        return 0;
    memcpy(out, pl.corner, sizeof pl.corner);
    return 1;
}

static int inplane(const qgl_context *ctx)
{
    return ctx->method != QGL_METHOD_MVC;
}

int qgl__grid_plan(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4],
                   const double *clip[4], int planar, size_t q)
{
    int forced = ctx->method == QGL_METHOD_SUBDIV;
    if ((!forced && !(ctx->costs && ctx->costs->valid)) || !state_allows(ctx, st, planar) ||
        (inplane(ctx) && !planar)) /* a non-planar quad's view-invariant form is its patch's */
        return 0;
    double sv[4][2], pv[4][2], m[4], n[4], wmax = 0, hw = 0.5 * st->xf.viewport[2], hh = 0.5 * st->xf.viewport[3];
    for (int i = 0; i < 4; i++) {
        if (!(clip[i][3] > 0))
            return 0;
        sv[i][0] = clip[i][0] / clip[i][3] * hw, sv[i][1] = clip[i][1] / clip[i][3] * hh;
        wmax = clip[i][3] > wmax ? clip[i][3] : wmax;
    }
    const double (*shape)[2] = inplane(ctx) ? (const double(*)[2])pv : (const double(*)[2])sv;
    if ((inplane(ctx) && !inplane_corners(v, idx, pv)) || !qgl_mvcgrid_fits(shape))
        return 0;
    double area = screen_area(sv, st->xf.viewport);
    if (!forced && !qgl__grid_cheaper(ctx, area, 0))
        return 0; /* not even the coarsest grid pays: no need to judge the error */
    if (!screen_dependency(shape, m))
        return 0;
    for (int i = 0; i < 4; i++)
        n[i] = inplane(ctx) ? m[i] : m[i] * wmax / clip[i][3];
    int g = qgl_mvcgrid_choose(qgl__gain_limit(ctx, st, v, idx, n));
    if (g < 0 && forced)
        g = qgl_mvcgrid_count() - 1;
    if (g < 0 || (!forced && !qgl__grid_cheaper(ctx, area, g)))
        return 0;
    struct qgl__grid *gr = grid_of(ctx);
    if (!gr || !grow((void **)&gr->k, &gr->k_cap, q + 1, 1))
        return 0;
    gr->k[q] = (unsigned char)g;
    return 1;
}

/* ---- drawing -------------------------------------------------------------------------------- */

static int layout(unsigned mask, int offset[NSTREAMS])
{
    int stride = 4;
    for (int s = 0; s < NSTREAMS; s++) {
        offset[s] = mask & streams[s].bit ? stride : -1;
        stride += offset[s] >= 0 ? streams[s].size : 0;
    }
    return stride;
}

static const float *stream_data(const qgl__verts *v, int s)
{
    switch (streams[s].bit) {
    case QGL__A_COLOR: return v->col;
    case QGL__A_COLOR2: return v->col2;
    case QGL__A_FOG: return v->fog;
    default: return v->tex[s - 3];
    }
}

/* dst[j * stride + k] = sum_i persp[j][i] src[idx[i] * size + k] for the n vertices. */
static void combine(float *dst, int stride, const float *src, int size, const size_t idx[4],
                    const double (*persp)[4], int n)
{
    for (int j = 0; j < n; j++)
        for (int k = 0; k < size; k++) {
            double s = 0;
            for (int i = 0; i < 4; i++)
                s += persp[j][i] * src[idx[i] * (size_t)size + (size_t)k];
            dst[(size_t)j * (size_t)stride + (size_t)k] = (float)s;
        }
}

/* Weights of grid g's vertices for the quad at idx: the corners' own, then the interior's; a
 * quad the core refuses after all (it was planned on the same numbers) becomes the split. */
static const qgl_mvcgrid *quad_weights(qgl_context *ctx, const qgl__state *st, const qgl__verts *v,
                                       const size_t idx[4], int g)
{
    struct qgl__grid *gr = ctx->grid;
    const qgl_mvcgrid *grid = qgl_mvcgrid_at(g);
    double c[4][4], pv[4][2];
    int plane = inplane(ctx) && inplane_corners(v, idx, pv);
    for (int i = 0; i < 4; i++) {
        const double *x = ctx->clip + 4 * idx[i];
        if (plane) {
            c[i][0] = pv[i][0], c[i][1] = pv[i][1], c[i][2] = 0, c[i][3] = 1;
            continue;
        }
        c[i][0] = x[0] * 0.5 * st->xf.viewport[2], c[i][1] = x[1] * 0.5 * st->xf.viewport[3];
        c[i][2] = x[2], c[i][3] = x[3];
    }
    if (grid && qgl_mvcgrid_weights(grid, (const double(*)[4])c, gr->pts, gr->persp))
        return grid;
    return NULL;
}

/* Append quad (corners idx) as grid g: vertices at out (stride floats each), indices at ix
 * from vertex number base. Returns the number of vertices; *nidx receives the indices'. */
static int emit_quad(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4], int g,
                     int flat, const int offset[NSTREAMS], int stride, float *out, uint32_t *ix, uint32_t base,
                     int *nidx)
{
    struct qgl__grid *gr = ctx->grid;
    const qgl_mvcgrid *grid = quad_weights(ctx, st, v, idx, g);
    static const uint16_t split[2][3] = {{0, 1, 2}, {0, 2, 3}};
    int nv = grid ? grid->nverts : 4, nt = grid ? grid->ntris : 2;
    const uint16_t (*tri)[3] = grid ? (const uint16_t(*)[3])grid->tri : split;
    if (!grid)
        for (int i = 0; i < 4; i++)
            for (int k = 0; k < 4; k++)
                gr->persp[i][k] = i == k;
    combine(out, stride, v->pos, 4, idx, (const double(*)[4])gr->persp, nv);
    for (int s = 0; s < NSTREAMS; s++) {
        if (offset[s] < 0)
            continue;
        const float *src = stream_data(v, s);
        int colour = streams[s].bit == QGL__A_COLOR || streams[s].bit == QGL__A_COLOR2;
        if (flat >= 0 && colour) {
            for (int j = 0; j < nv; j++)
                memcpy(out + (size_t)j * (size_t)stride + offset[s], src + idx[flat] * (size_t)streams[s].size,
                       (size_t)streams[s].size * sizeof(float));
        } else {
            combine(out + offset[s], stride, src, streams[s].size, idx, (const double(*)[4])gr->persp, nv);
        }
    }
    for (int t = 0; t < nt; t++)
        for (int c = 0; c < 3; c++)
            ix[3 * t + c] = base + tri[t][c];
    *nidx = 3 * nt;
    return nv;
}

static void set_array(struct qgl__gl *gl, unsigned bit, int u, int on, GLsizei stride, const void *at)
{
    GLenum array;
    switch (bit) {
    case 0: array = GL_VERTEX_ARRAY; if (on) gl->VertexPointer(4, GL_FLOAT, stride, at); break;
    case QGL__A_COLOR: array = GL_COLOR_ARRAY; if (on) gl->ColorPointer(4, GL_FLOAT, stride, at); break;
    case QGL__A_COLOR2:
        array = GL_SECONDARY_COLOR_ARRAY;
        if (on)
            gl->SecondaryColorPointer(3, GL_FLOAT, stride, at);
        break;
    case QGL__A_FOG: array = GL_FOG_COORD_ARRAY; if (on) gl->FogCoordPointer(GL_FLOAT, stride, at); break;
    default:
        array = GL_TEXTURE_COORD_ARRAY;
        gl->ClientActiveTexture(GL_TEXTURE0 + (GLenum)u);
        if (on)
            gl->TexCoordPointer(4, GL_FLOAT, stride, at);
    }
    if (on)
        gl->EnableClientState(array);
    else
        gl->DisableClientState(array);
}

/* Upload nverts vertices and nidx indices, point our VAO's arrays at them, draw, and give the
 * batch's VAO back. */
static void upload_and_draw(qgl_context *ctx, unsigned mask, const int offset[NSTREAMS], int stride,
                            size_t nverts, size_t nidx)
{
    struct qgl__gl *gl = &ctx->gl;
    struct qgl__grid *gr = ctx->grid;
    size_t vbytes = nverts * (size_t)stride * sizeof(float), ibytes = nidx * sizeof(uint32_t), base = 0;
    gl->BindVertexArray(gr->vao);
    unsigned char *map = qgl__stream_begin(ctx, vbytes + ibytes, &base);
    if (!map) {
        gl->BindVertexArray(ctx->vao);
        return;
    }
    memcpy(map, gr->verts, vbytes);
    memcpy(map + vbytes, gr->idx, ibytes);
    qgl__stream_end(ctx);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ctx->stream.buf);
    GLsizei bstride = stride * (GLsizei)sizeof(float);
    set_array(gl, 0, 0, 1, bstride, (const void *)(uintptr_t)base);
    for (int s = 0; s < NSTREAMS; s++) {
        int on = offset[s] >= 0;
        if (on || (gr->enabled & streams[s].bit))
            set_array(gl, streams[s].bit, s - 3, on, bstride,
                      (const void *)(uintptr_t)(base + (size_t)(on ? offset[s] : 0) * sizeof(float)));
    }
    gr->enabled = mask;
    gl->DrawElements(GL_TRIANGLES, (GLsizei)nidx, GL_UNSIGNED_INT, (const void *)(uintptr_t)(base + vbytes));
    gl->BindVertexArray(ctx->vao);
    ctx->stats.draws++;
    ctx->stats.subdiv_triangles += nidx / 3;
}

/* The quads first .. first + nq - 1 (grid numbers in gr->k, or g for all when g >= 0). */
static int draw_quads(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t q0,
                      size_t nq, int g)
{
    struct qgl__grid *gr = grid_of(ctx);
    if (!gr)
        return 0;
    unsigned mask = 0;
    for (int s = 0; s < NSTREAMS; s++)
        mask |= v->mask & streams[s].bit;
    int offset[NSTREAMS], stride = layout(mask, offset);
    size_t nverts = 0, nidx = 0;
    for (size_t q = q0; q < q0 + nq; q++) {
        const qgl_mvcgrid *grid = qgl_mvcgrid_at(g >= 0 ? g : gr->k[q]);
        nverts += grid ? (size_t)grid->nverts : 4;
        nidx += grid ? 3 * (size_t)grid->ntris : 6;
    }
    if (!grow((void **)&gr->verts, &gr->verts_cap, nverts * (size_t)stride, sizeof(float)) ||
        !grow((void **)&gr->idx, &gr->idx_cap, nidx, sizeof(uint32_t)))
        return 0;
    int flat = st->shade_model == GL_FLAT ? qgl__flat_corner(ctx, st, topo) : -1;
    size_t at = 0, ai = 0;
    for (size_t q = q0; q < q0 + nq; q++) {
        size_t idx[4];
        for (int c = 0; c < 4; c++)
            idx[c] = qgl__corner(topo, q, c);
        int ni;
        at += (size_t)emit_quad(ctx, st, v, idx, g >= 0 ? g : gr->k[q], flat, offset, stride,
                                gr->verts + at * (size_t)stride, gr->idx + ai, (uint32_t)at, &ni);
        ai += (size_t)ni;
    }
    upload_and_draw(ctx, mask, offset, stride, at, ai);
    return 1;
}

int qgl__grid_draw(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t q0,
                   size_t nq, GLint *bound)
{
    if (*bound != st->program)
        ctx->gl.UseProgram((GLuint)(*bound = st->program));
    return draw_quads(ctx, st, v, topo, q0, nq, -1);
}

int qgl__grid_draw_all(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, int g)
{
    return draw_quads(ctx, st, v, QGL_QUADS, 0, qgl__nquads(QGL_QUADS, v->n), g);
}

int qgl__grid_draw_arrays(qgl_context *ctx, const qgl__verts *v, GLenum mode)
{
    struct qgl__grid *gr = grid_of(ctx);
    struct qgl__gl *gl = &ctx->gl;
    unsigned mask = v->mask & QGL__A_COLOR;
    int offset[NSTREAMS], stride = layout(mask, offset);
    if (!gr || !grow((void **)&gr->verts, &gr->verts_cap, v->n * (size_t)stride, sizeof(float)))
        return 0;
    for (size_t i = 0; i < v->n; i++) {
        memcpy(gr->verts + i * (size_t)stride, v->pos + 4 * i, 4 * sizeof(float));
        if (mask)
            memcpy(gr->verts + i * (size_t)stride + offset[0], v->col + 4 * i, 4 * sizeof(float));
    }
    size_t bytes = v->n * (size_t)stride * sizeof(float), base = 0;
    gl->BindVertexArray(gr->vao);
    unsigned char *map = qgl__stream_begin(ctx, bytes, &base);
    if (!map) {
        gl->BindVertexArray(ctx->vao);
        return 0;
    }
    memcpy(map, gr->verts, bytes);
    qgl__stream_end(ctx);
    GLsizei bstride = stride * (GLsizei)sizeof(float);
    set_array(gl, 0, 0, 1, bstride, (const void *)(uintptr_t)base);
    for (int s = 0; s < NSTREAMS; s++)
        if (offset[s] >= 0 || (gr->enabled & streams[s].bit))
            set_array(gl, streams[s].bit, s - 3, offset[s] >= 0, bstride,
                      (const void *)(uintptr_t)(base + (size_t)(offset[s] >= 0 ? offset[s] : 0) * sizeof(float)));
    gr->enabled = mask;
    gl->DrawArrays(mode, 0, (GLsizei)v->n);
    gl->BindVertexArray(ctx->vao);
    return 1;
}
