/* sw_draw.c: qgl_sw_draw, the method dispatch, and the triangle-based methods.
 *
 * Per quad: the per-pixel methods (mvc, mvc64, invbilinear, projective, exact, mvcpatch) get a quad
 * set up once (sw_raster.c) and scan it; the splits hand two of its triangles to the
 * triangle rasterizer; bilinear:N and adaptive build a triangle soup with the core's
 * subdivisions (corners carry clip position and attributes, both subdivided bilinearly,
 * which equals subdividing in object space since the projection is linear on homogeneous
 * coordinates) and rasterize it the same way; mvcplane and invbilinearplane rasterize the
 * quad's in-plane cover (sw_plane.c). mvcgrid evaluates the exact weights at the
 * vertices of the core's mean value grid and sends them as triangles too (clip position and
 * attributes as the weights' combinations of the corners'), for every strictly convex quad
 * in front of the eye (the others per pixel as mvc). */
#include "sw_internal.h"

#include <stdlib.h>
#include <string.h>

const char *qgl_sw_error_string(int code)
{
    switch (code) {
#define QGL__SW_CASE(name, value, msg) \
    case name:                         \
        return msg;
        QGL_SW_ERRORS(QGL__SW_CASE)
#undef QGL__SW_CASE
    }
    return "unknown error";
}

/* A quad's corners as doubles: [object xyz when with_obj] clip xyzw, attributes. */
static void corner_row(const qgl_sw_draw_desc *d, int quad, int corner, int with_obj, double *out)
{
    int n = 0;
    if (with_obj) {
        for (int k = 0; k < 3; k++) {
            if (d->object) {
                out[n++] = d->object[(quad * 4 + corner) * 3 + k];
            } else {
                const float *c = d->clip + (quad * 4 + corner) * 4;
                out[n++] = (double)c[k] / c[3];
            }
        }
    }
    for (int k = 0; k < 4; k++)
        out[n++] = d->clip[(quad * 4 + corner) * 4 + k];
    for (int k = 0; k < d->nattr; k++)
        out[n++] = d->attr[(quad * 4 + corner) * d->nattr + k];
}

static void draw_split(qgl__ctx *c, int quad, int first)
{
    double v[4][4 + QGL_SW_MAX_ATTR];
    for (int i = 0; i < 4; i++)
        corner_row(c->d, quad, i, 0, v[i]);
    int a = first, b = (first + 1) & 3, cc = (first + 2) & 3, dd = (first + 3) & 3;
    qgl__triangle(c, v[a], v[b], v[cc], c->d->nattr);
    qgl__triangle(c, v[a], v[cc], v[dd], c->d->nattr);
}

static int draw_mesh(qgl__ctx *c, const qgl_mesh *m, int offset)
{
    for (int t = 0; t < m->ntri; t++) {
        const double *v = m->v + (size_t)t * 3 * m->stride + offset;
        qgl__triangle(c, v, v + m->stride, v + 2 * m->stride, c->d->nattr);
    }
    return QGL_SW_OK;
}

static int draw_subdivided(qgl__ctx *c, int quad, qgl_mesh *mesh)
{
    const qgl_sw_draw_desc *d = c->d;
    int adaptive = d->method.method == QGL_SW_ADAPTIVE;
    int stride = (adaptive ? 3 : 0) + 4 + d->nattr;
    double corners[4 * (7 + QGL_SW_MAX_ATTR)];
    for (int i = 0; i < 4; i++)
        corner_row(d, quad, i, adaptive, corners + i * stride);
    mesh->ntri = 0;
    int r;
    if (adaptive) {
        qgl_adaptive_params p = d->method.adaptive;
        p.viewport[0] = c->fb->width;
        p.viewport[1] = c->fb->height;
        int tex = d->uv_attr1 > 0 ? 7 + d->uv_attr1 - 1 : -1;
        r = qgl_subdiv_adaptive(corners, stride, 0, tex, 3, &p, mesh);
    } else {
        r = qgl_subdiv_bilinear(corners, stride, d->method.n > 0 ? d->method.n : 8, mesh);
    }
    if (r < 0)
        return QGL_SW_ESUBDIV;
    return draw_mesh(c, mesh, adaptive ? 3 : 0);
}

/* The tabulated grid with at least n cells per side (the finest when none has). */
static const qgl_mvcgrid *grid_for(int n)
{
    const qgl_mvcgrid *g = NULL;
    for (int i = 0; i < qgl_mvcgrid_count(); i++)
        if ((g = qgl_mvcgrid_at(i)) && g->k >= n)
            break;
    return g;
}

/* Room for one grid's vertices: screen points, weights, and rows of clip + attributes. */
typedef struct grid_buf {
    const qgl_mvcgrid *g;
    double (*pts)[2], (*persp)[4], *rows;
} grid_buf;

static void draw_grid(qgl__ctx *c, int quad, const grid_buf *b)
{
    const qgl_sw_draw_desc *d = c->d;
    const float *attr = d->attr ? d->attr + quad * 4 * d->nattr : NULL, *clip = d->clip + quad * 16;
    qgl__quad q;
    qgl__quad_setup(&q, c->fb, clip, attr, d->nattr);
    if (q.x0 > q.x1 || q.y0 > q.y1)
        return;
    if (!qgl_mvcgrid_weights(b->g, (const double(*)[4])q.px, b->pts, b->persp)) {
        qgl__draw_mvc(c, &q);
        return;
    }
    /* Clip positions are rounded to float, as the corners are (and as a GL driver takes
     * them): the edge functions' products then stay exact in double, so a pixel centre on a
     * corner is decided by the tie rule, not by rounding, in every triangle of the fan there. */
    int stride = 4 + d->nattr;
    for (int j = 0; j < b->g->nverts; j++) {
        double *row = b->rows + (size_t)j * (size_t)stride;
        for (int k = 0; k < stride; k++) {
            double s = 0;
            for (int i = 0; i < 4; i++)
                s += b->persp[j][i] * (k < 4 ? clip[4 * i + k] : attr[i * d->nattr + k - 4]);
            row[k] = k < 4 ? (double)(float)s : s;
        }
    }
    for (int t = 0; t < b->g->ntris; t++) {
        const uint16_t *tr = b->g->tri[t];
        qgl__triangle(c, b->rows + tr[0] * stride, b->rows + tr[1] * stride, b->rows + tr[2] * stride, d->nattr);
    }
}

static int grid_buf_init(grid_buf *b, const qgl_sw_draw_desc *d)
{
    memset(b, 0, sizeof *b);
    if (d->method.method != QGL_SW_MVCGRID)
        return QGL_SW_OK;
    if (!(b->g = grid_for(d->method.n)))
        return QGL_SW_ENOMEM;
    size_t n = (size_t)b->g->nverts;
    b->pts = malloc(n * sizeof *b->pts);
    b->persp = malloc(n * sizeof *b->persp);
    b->rows = malloc(n * (size_t)(4 + d->nattr) * sizeof *b->rows);
    return b->pts && b->persp && b->rows ? QGL_SW_OK : QGL_SW_ENOMEM;
}

static void grid_buf_free(grid_buf *b)
{
    free(b->pts);
    free(b->persp);
    free(b->rows);
}

static void draw_quad(qgl__ctx *c, int quad)
{
    const qgl_sw_draw_desc *d = c->d;
    qgl__quad q;
    qgl__quad_setup(&q, c->fb, d->clip + quad * 16, d->attr ? d->attr + quad * 4 * d->nattr : NULL, d->nattr);
    if (q.x0 > q.x1 || q.y0 > q.y1)
        return;
    switch (d->method.method) {
    case QGL_SW_MVC:
        qgl__draw_mvc(c, &q);
        break;
    case QGL_SW_MVC64:
        qgl__draw_mvc64(c, &q);
        break;
    case QGL_SW_INVBILINEAR:
        qgl__draw_invbilinear(c, &q);
        break;
    case QGL_SW_PROJECTIVE:
        qgl__draw_projective(c, &q);
        break;
    case QGL_SW_MVCPATCH:
        qgl__draw_mvcpatch(c, &q, quad);
        break;
    default:
        qgl__draw_exact(c, &q);
        break;
    }
}

static int check(const qgl_sw_fb *fb, const qgl_sw_draw_desc *d)
{
    if (!fb || !d || d->nquads < 0 || (d->nquads > 0 && !d->clip))
        return QGL_SW_EINVAL;
    if (d->nattr < 0 || d->nattr > QGL_SW_MAX_ATTR || (d->nattr > 0 && d->nquads > 0 && !d->attr))
        return QGL_SW_EINVAL;
    if ((unsigned)d->method.method >= QGL_SW_METHOD_COUNT || d->method.n < 0)
        return QGL_SW_EMETHOD;
    if (fb->channels > (int)(sizeof(((qgl__ctx *)0)->scratch) / sizeof(float)))
        return QGL_SW_EFORMAT;
    if (d->uv_attr1 < 0 || (d->uv_attr1 > 0 && d->uv_attr1 + 1 > d->nattr))
        return QGL_SW_EINVAL;
    return QGL_SW_OK;
}

int qgl_sw_draw(qgl_sw_fb *fb, const qgl_sw_draw_desc *d, qgl_sw_stats *stats)
{
    int r = check(fb, d);
    if (r != QGL_SW_OK)
        return r;
    qgl__ctx c = {.fb = fb, .d = d};
    qgl_mesh mesh = {0};
    qgl_sw_method m = d->method.method;
    grid_buf grid;
    r = grid_buf_init(&grid, d);
    for (int i = 0; i < d->nquads && r == QGL_SW_OK; i++) {
        if (m == QGL_SW_SPLIT02 || m == QGL_SW_SPLIT13)
            draw_split(&c, i, m == QGL_SW_SPLIT02 ? 0 : 1);
        else if (m == QGL_SW_MVCGRID)
            draw_grid(&c, i, &grid);
        else if (m == QGL_SW_BILINEAR || m == QGL_SW_ADAPTIVE)
            r = draw_subdivided(&c, i, &mesh);
        else if (m == QGL_SW_MVCPLANE || m == QGL_SW_INVBILINEARPLANE)
            qgl__draw_plane(&c, i);
        else
            draw_quad(&c, i);
    }
    qgl_mesh_free(&mesh);
    grid_buf_free(&grid);
    if (stats) {
        stats->fragments += c.fragments;
        stats->triangles += c.triangles;
    }
    return r;
}
