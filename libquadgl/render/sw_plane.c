/* sw_plane.c: the view-invariant methods, weights in the quad's own plane (core plane.c).
 *
 * mvcplane and invbilinearplane draw what the GL path draws: the quad's exact cover in its
 * plane (qgl_plane_cover: convex split along the preferred diagonal, concave through the
 * reflex corner, a bow-tie as two lobes meeting at the in-plane crossing point, whose clip
 * position is that of the same point of its edge in object space) rasterized as triangles,
 * each vertex carrying its in-plane position; the rasterizer interpolates the position
 * perspective-correctly, which is exact on a planar quad (it is affine on the surface), and
 * each fragment weighs it: mvcplane with the core's float mean value weights (the GL shader's
 * arithmetic), invbilinearplane with the inverse bilinear map of the in-plane quad (Quilez's
 * stable quadratic, qgl_inv_bilinear; for a planar convex quad that is the bilinear patch,
 * the exact reference). Depth and facing are the triangles': a planar quad's own, a
 * non-planar quad's split surface. A planar mvcplane quad in front of the eye takes mvc's
 * span kernel instead (the same weights, with eq. 12 coverage, at mvc's speed). mvcpatch instead takes, per pixel, the exact reference's
 * hit on the bilinear patch (sw_exact.c), projects it onto the best-fit plane and weighs it
 * with the double mean value weights there, with the patch's depth: for a non-planar quad a
 * surface point keeps its weights from every view. Object positions come from the draw
 * (desc.object); without them the NDC positions stand in, which are not rigid, so the result
 * is then as view-dependent as the screen-space methods. */
#include "sw_internal.h"

#include <math.h>

typedef struct plane_quad {
    qgl_plane pl;
    qgl_planef plf;
    const float *attr;
    int nattr;
} plane_quad;

/* Object corner i of quad: desc.object, or clip x, y, z over w. */
static void object_corner(const qgl_sw_draw_desc *d, int quad, int i, double out[3])
{
    const float *c = d->clip + (quad * 4 + i) * 4;
    for (int k = 0; k < 3; k++)
        out[k] = d->object ? d->object[(quad * 4 + i) * 3 + k] : (double)c[k] / c[3];
}

static void plane_setup(const qgl_sw_draw_desc *d, int quad, plane_quad *p)
{
    double pos[4][3];
    for (int i = 0; i < 4; i++)
        object_corner(d, quad, i, pos[i]);
    qgl_plane_frame(pos, &p->pl);
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 2; k++)
            p->plf.corner[i][k] = (float)p->pl.corner[i][k];
    p->attr = d->attr ? d->attr + quad * 4 * d->nattr : NULL;
    p->nattr = d->nattr;
}

static void weigh(const plane_quad *p, const double w[4], float *out)
{
    for (int k = 0; k < p->nattr; k++) {
        double a = 0;
        for (int i = 0; i < 4; i++)
            a += w[i] * p->attr[i * p->nattr + k];
        out[k] = (float)a;
    }
}

static int map_mvc(void *user, const double *vary, float *out)
{
    const plane_quad *p = user;
    float lam[4];
    if (qgl_weights_inplanef(&p->plf, (float)vary[0], (float)vary[1], lam) == QGL_NONFINITE)
        return 0;
    const double w[4] = {lam[0], lam[1], lam[2], lam[3]};
    weigh(p, w, out);
    return 1;
}

static void bilinear_weights(double u, double v, double w[4])
{
    u = fmin(fmax(u, 0), 1);
    v = fmin(fmax(v, 0), 1);
    w[0] = (1 - u) * (1 - v);
    w[1] = u * (1 - v);
    w[2] = u * v;
    w[3] = (1 - u) * v;
}

static int map_invbilinear(void *user, const double *vary, float *out)
{
    const plane_quad *p = user;
    double uv[2], w[4];
    if (qgl_inv_bilinear(p->pl.corner, vary[0], vary[1], uv) < 0)
        return 0;
    bilinear_weights(uv[0], uv[1], w);
    weigh(p, w, out);
    return 1;
}

/* Cover vertex k (a corner, or 4: the crossing point) as clip position then in-plane
 * position. */
static void cover_vertex(const qgl_sw_draw_desc *d, int quad, const plane_quad *p, const qgl_cover *cov, int k,
                         double out[6])
{
    const float *c = d->clip + quad * 16;
    if (k < 4) {
        for (int j = 0; j < 4; j++)
            out[j] = c[4 * k + j];
        out[4] = p->pl.corner[k][0];
        out[5] = p->pl.corner[k][1];
        return;
    }
    int a = cov->cross_edge, b = a + 1;
    double t = cov->cross_t;
    for (int j = 0; j < 4; j++)
        out[j] = (1 - t) * c[4 * a + j] + t * c[4 * b + j];
    out[4] = cov->cross[0];
    out[5] = cov->cross[1];
}

/* mvcplane's fast case: a planar quad whose corners are all in front of the eye goes to
 * mvc's span kernel in its in-plane form (sw_mvc.c), with eq. 12 coverage. */
static int draw_planar_spans(qgl__ctx *c, int quad, const plane_quad *p)
{
    const qgl_sw_draw_desc *d = c->d;
    const float *clip = d->clip + quad * 16;
    double pos[4][3];
    for (int i = 0; i < 4; i++) {
        if (!(clip[4 * i + 3] > 0))
            return 0;
        object_corner(d, quad, i, pos[i]);
    }
    /* float object positions of small quads (a fine sphere's) are planar to their rounding */
    if (!qgl_is_planar(pos, 1e-5))
        return 0;
    qgl__quad q;
    qgl__quad_setup(&q, c->fb, clip, p->attr, p->nattr);
    if (q.x0 <= q.x1 && q.y0 <= q.y1)
        qgl__draw_mvc_plane(c, &q, p->pl.corner);
    return 1;
}

void qgl__draw_plane(qgl__ctx *c, int quad)
{
    const qgl_sw_draw_desc *d = c->d;
    plane_quad p;
    qgl_cover cov;
    plane_setup(d, quad, &p);
    if (d->method.method == QGL_SW_MVCPLANE && draw_planar_spans(c, quad, &p))
        return;
    qgl_plane_cover(&p.pl, &cov);
    qgl__vary_fn map = d->method.method == QGL_SW_INVBILINEARPLANE ? map_invbilinear : map_mvc;
    for (int t = 0; t < cov.ntri; t++) {
        double v[3][6];
        for (int k = 0; k < 3; k++)
            cover_vertex(d, quad, &p, &cov, cov.tri[t][k], v[k]);
        qgl__triangle_map(c, v[0], v[1], v[2], 2, map, &p);
    }
}

void qgl__draw_mvcpatch(qgl__ctx *c, const qgl__quad *q, int quad)
{
    plane_quad p;
    plane_setup(c->d, quad, &p);
    double pc[4][2];
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 2; k++)
            pc[i][k] = p.pl.corner[i][k];
    float attr[QGL_SW_MAX_ATTR];
    for (int y = q->y0; y <= q->y1; y++) {
        double Y = y + 0.5;
        for (int x = q->x0; x <= q->x1; x++) {
            double X = x + 0.5, uv[2], b[4], zndc, w[4], xy[2] = {0, 0};
            int facing;
            if (!qgl__patch_hit(q, X, Y, uv, &zndc, &facing))
                continue;
            bilinear_weights(uv[0], uv[1], b);
            for (int i = 0; i < 4; i++)
                for (int k = 0; k < 2; k++)
                    xy[k] += b[i] * pc[i][k];
            qgl_weights_inplane(&p.pl, xy[0], xy[1], w);
            weigh(&p, w, attr);
            qgl__fragment(c, x, y, zndc, facing, attr);
        }
    }
}
