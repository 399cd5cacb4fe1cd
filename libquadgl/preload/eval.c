/* eval.c: evaluators (glEvalMesh2 in GL_FILL mode, glEvalCoord and glEvalPoint between
 * glBegin and glEnd) turned into captured quad vertices.
 *
 * glEvalMesh2(GL_FILL, i1, i2, j1, j2) is, by the GL specification, one quad strip per grid
 * row made of glEvalCoord2 calls at the grid points, and glEvalCoord evaluates every enabled
 * map and issues the resulting colour, normal, texture coordinates and vertex. So we do
 * exactly that on the CPU: the maps' control points, orders and domains are read back from
 * the driver (glGetMap) once per primitive, each map is a tensor-product Bernstein polynomial
 * evaluated by de Casteljau's rule, GL_AUTO_NORMAL takes the cross product of the vertex
 * map's partial derivatives, and the results go through the same capture calls as glColor,
 * glNormal, glTexCoord and glVertex. Line and point meshes, meshes inside a display list
 * being compiled (the grid is read when the list runs) and evaluators outside a captured
 * primitive go to the driver. Colour-index maps are ignored, as in RGBA mode. */
#include "preload.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PL_MAX_ORDER 40 /* above any driver's GL_MAX_EVAL_ORDER we know (Mesa: 30) */

typedef struct pl_map {
    int dim;           /* components per control point; 0 = not used */
    int uorder, vorder;
    float u1, u2, v1, v2;
    float *coeff;      /* uorder * vorder * dim, u major */
} pl_map;

/* The maps that feed one vertex: position, colour, normal, texture coordinates. */
typedef struct pl_maps {
    pl_map vertex, color, normal, tex;
    int auto_normal;
} pl_maps;

static void pl_map_free(pl_map *m)
{
    free(m->coeff);
    memset(m, 0, sizeof *m);
}

static void pl_maps_free(pl_maps *s)
{
    pl_map_free(&s->vertex);
    pl_map_free(&s->color);
    pl_map_free(&s->normal);
    pl_map_free(&s->tex);
}

/* Reads an enabled map of dimension 1 (two = 0) or 2 (two = 1) with dim components. */
static int pl_map_read(pl_map *m, GLenum target, int dim, int two)
{
    GLint order[2] = {1, 1};
    GLfloat domain[4] = {0, 1, 0, 1};
    memset(m, 0, sizeof *m);
    if (!REAL(glIsEnabled)(target))
        return 0;
    REAL(glGetMapiv)(target, GL_ORDER, order);
    REAL(glGetMapfv)(target, GL_DOMAIN, domain);
    if (!two)
        order[1] = 1;
    if (order[0] < 1 || order[1] < 1 || order[0] > PL_MAX_ORDER || order[1] > PL_MAX_ORDER)
        return 0;
    m->coeff = malloc((size_t)order[0] * (size_t)order[1] * (size_t)dim * sizeof *m->coeff);
    if (!m->coeff)
        return -1;
    REAL(glGetMapfv)(target, GL_COEFF, m->coeff);
    m->dim = dim;
    m->uorder = order[0];
    m->vorder = order[1];
    m->u1 = domain[0], m->u2 = domain[1];
    m->v1 = two ? domain[2] : 0, m->v2 = two ? domain[3] : 1;
    return 0;
}

/* The first enabled of several targets (highest dimension first). */
static int pl_map_pick(pl_map *m, const GLenum *targets, const int *dims, int n, int two)
{
    for (int i = 0; i < n; i++) {
        if (pl_map_read(m, targets[i], dims[i], two) != 0)
            return -1;
        if (m->dim)
            return 0;
    }
    return 0;
}

static int pl_maps_read(pl_maps *s, int two)
{
    static const GLenum v2[] = {GL_MAP2_VERTEX_4, GL_MAP2_VERTEX_3}, v1[] = {GL_MAP1_VERTEX_4, GL_MAP1_VERTEX_3};
    static const GLenum t2[] = {GL_MAP2_TEXTURE_COORD_4, GL_MAP2_TEXTURE_COORD_3, GL_MAP2_TEXTURE_COORD_2,
                                GL_MAP2_TEXTURE_COORD_1};
    static const GLenum t1[] = {GL_MAP1_TEXTURE_COORD_4, GL_MAP1_TEXTURE_COORD_3, GL_MAP1_TEXTURE_COORD_2,
                                GL_MAP1_TEXTURE_COORD_1};
    static const GLenum c2[] = {GL_MAP2_COLOR_4}, c1[] = {GL_MAP1_COLOR_4};
    static const GLenum n2[] = {GL_MAP2_NORMAL}, n1[] = {GL_MAP1_NORMAL};
    static const int vdims[] = {4, 3}, tdims[] = {4, 3, 2, 1}, cdims[] = {4}, ndims[] = {3};
    memset(s, 0, sizeof *s);
    if (pl_map_pick(&s->vertex, two ? v2 : v1, vdims, 2, two) || pl_map_pick(&s->tex, two ? t2 : t1, tdims, 4, two) ||
        pl_map_pick(&s->color, two ? c2 : c1, cdims, 1, two) || pl_map_pick(&s->normal, two ? n2 : n1, ndims, 1, two)) {
        pl_maps_free(s);
        return -1;
    }
    s->auto_normal = two && REAL(glIsEnabled)(GL_AUTO_NORMAL);
    return 0;
}

/* Bernstein polynomial of `order` control points (stride floats apart) at t, and its
 * derivative, by de Casteljau's rule; dim components. */
static void pl_bezier(const float *p, int order, int stride, int dim, float t, float *out, float *deriv)
{
    float work[PL_MAX_ORDER][4];
    for (int k = 0; k < order; k++)
        memcpy(work[k], p + (size_t)k * (size_t)stride, (size_t)dim * sizeof(float));
    for (int level = order - 1; level > 0; level--) {
        if (level == 1 && deriv)
            for (int c = 0; c < dim; c++)
                deriv[c] = (float)(order - 1) * (work[1][c] - work[0][c]);
        for (int k = 0; k < level; k++)
            for (int c = 0; c < dim; c++)
                work[k][c] = (1.0f - t) * work[k][c] + t * work[k + 1][c];
    }
    if (order == 1 && deriv)
        memset(deriv, 0, (size_t)dim * sizeof(float));
    memcpy(out, work[0], (size_t)dim * sizeof(float));
}

/* Evaluates map m at (u, v): out (dim floats), and the partial derivatives if du/dv. */
static void pl_map_eval(const pl_map *m, float u, float v, float *out, float *du, float *dv)
{
    float s = m->u2 != m->u1 ? (u - m->u1) / (m->u2 - m->u1) : 0.0f;
    float t = m->v2 != m->v1 ? (v - m->v1) / (m->v2 - m->v1) : 0.0f;
    float along_v[PL_MAX_ORDER][4], dv_rows[PL_MAX_ORDER][4];
    /* First along v for each u row, then along u over the results. */
    for (int i = 0; i < m->uorder; i++)
        pl_bezier(m->coeff + (size_t)i * (size_t)m->vorder * (size_t)m->dim, m->vorder, m->dim, m->dim, t, along_v[i],
                  dv ? dv_rows[i] : NULL);
    pl_bezier(&along_v[0][0], m->uorder, 4, m->dim, s, out, du);
    if (dv)
        pl_bezier(&dv_rows[0][0], m->uorder, 4, m->dim, s, dv, NULL);
    /* Derivatives with respect to u and v, not to the normalized parameters. */
    for (int c = 0; du && c < m->dim; c++)
        du[c] = m->u2 != m->u1 ? du[c] / (m->u2 - m->u1) : 0.0f;
    for (int c = 0; dv && c < m->dim; c++)
        dv[c] = m->v2 != m->v1 ? dv[c] / (m->v2 - m->v1) : 0.0f;
}

/* One evaluated vertex through the capture, attributes first (glEvalCoord's order). */
static void pl_eval_vertex(pl_ctx *x, const pl_maps *s, float u, float v)
{
    float val[4] = {0, 0, 0, 1}, du[4], dv[4];
    if (s->color.dim) {
        pl_map_eval(&s->color, u, v, val, NULL, NULL);
        pl_cap_attrib(x, QGL__AT_COLOR, val[0], val[1], val[2], val[3]);
    }
    if (s->tex.dim) {
        float tc[4] = {0, 0, 0, 1};
        pl_map_eval(&s->tex, u, v, tc, NULL, NULL);
        pl_cap_texcoord(x, 0, tc[0], tc[1], tc[2], tc[3]);
    }
    if (s->vertex.dim && s->auto_normal) {
        float p[4] = {0, 0, 0, 1}, n[3];
        double len;
        pl_map_eval(&s->vertex, u, v, p, du, dv);
        n[0] = du[1] * dv[2] - du[2] * dv[1];
        n[1] = du[2] * dv[0] - du[0] * dv[2];
        n[2] = du[0] * dv[1] - du[1] * dv[0];
        len = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        if (len > 0)
            pl_cap_attrib(x, QGL__AT_NORMAL, (float)(n[0] / len), (float)(n[1] / len), (float)(n[2] / len), 0);
    } else if (s->normal.dim) {
        float n[3];
        pl_map_eval(&s->normal, u, v, n, NULL, NULL);
        pl_cap_attrib(x, QGL__AT_NORMAL, n[0], n[1], n[2], 0);
    }
    if (s->vertex.dim) {
        float p[4] = {0, 0, 0, 1};
        pl_map_eval(&s->vertex, u, v, p, NULL, NULL);
        pl_cap_vertex(x, p[0], p[1], p[2], p[3]);
    }
}

/* ---- glEvalCoord / glEvalPoint inside a captured primitive ------------------------------------ */

static void pl_eval_coord(pl_ctx *x, int two, float u, float v)
{
    pl_maps s;
    if (pl_maps_read(&s, two) != 0) {
        x->prim.lost = 1;
        return;
    }
    pl_eval_vertex(x, &s, u, v);
    pl_maps_free(&s);
}

/* The grid parameter of point i of n segments over [a, b] (i == n gives b exactly). */
static float pl_grid(float a, float b, int n, int i)
{
    return i == n ? b : a + (b - a) * (float)i / (float)(n ? n : 1);
}

static void pl_eval_point(pl_ctx *x, int two, GLint i, GLint j)
{
    GLfloat dom[4] = {0, 1, 0, 1};
    GLint seg[2] = {1, 1};
    REAL(glGetFloatv)(two ? GL_MAP2_GRID_DOMAIN : GL_MAP1_GRID_DOMAIN, dom);
    REAL(glGetIntegerv)(two ? GL_MAP2_GRID_SEGMENTS : GL_MAP1_GRID_SEGMENTS, seg);
    pl_eval_coord(x, two, pl_grid(dom[0], dom[1], seg[0], i), two ? pl_grid(dom[2], dom[3], seg[1], j) : 0.0f);
}

#define PL_EVAL_WRAPPER(name, params, real_args, two, u, v)  \
    PL_EXPORT void name params                               \
    {                                                        \
        pl_ctx *cx = pl_tls_ctx && pl_tls_ctx->capturing ? pl_tls_ctx : NULL;                         \
        if (PL_LIKELY(cx == NULL)) {                         \
            REAL(name) real_args;                            \
            return;                                          \
        }                                                    \
        pl_eval_coord(cx, two, (float)(u), (float)(v));      \
    }

PL_EVAL_WRAPPER(glEvalCoord1f, (GLfloat u), (u), 0, u, 0)
PL_EVAL_WRAPPER(glEvalCoord1d, (GLdouble u), (u), 0, u, 0)
PL_EVAL_WRAPPER(glEvalCoord1fv, (const GLfloat *u), (u), 0, u[0], 0)
PL_EVAL_WRAPPER(glEvalCoord1dv, (const GLdouble *u), (u), 0, u[0], 0)
PL_EVAL_WRAPPER(glEvalCoord2f, (GLfloat u, GLfloat v), (u, v), 1, u, v)
PL_EVAL_WRAPPER(glEvalCoord2d, (GLdouble u, GLdouble v), (u, v), 1, u, v)
PL_EVAL_WRAPPER(glEvalCoord2fv, (const GLfloat *u), (u), 1, u[0], u[1])
PL_EVAL_WRAPPER(glEvalCoord2dv, (const GLdouble *u), (u), 1, u[0], u[1])

PL_EXPORT void glEvalPoint1(GLint i)
{
    pl_ctx *cx = pl_tls_ctx && pl_tls_ctx->capturing ? pl_tls_ctx : NULL;
    if (PL_LIKELY(cx == NULL)) {
        REAL(glEvalPoint1)(i);
        return;
    }
    pl_eval_point(cx, 0, i, 0);
}

PL_EXPORT void glEvalPoint2(GLint i, GLint j)
{
    pl_ctx *cx = pl_tls_ctx && pl_tls_ctx->capturing ? pl_tls_ctx : NULL;
    if (PL_LIKELY(cx == NULL)) {
        REAL(glEvalPoint2)(i, j);
        return;
    }
    pl_eval_point(cx, 1, i, j);
}

/* ---- glEvalMesh2(GL_FILL): one captured quad strip per grid row -------------------------------- */

PL_EXPORT void glEvalMesh2(GLenum mode, GLint i1, GLint i2, GLint j1, GLint j2)
{
    pl_ctx *x = pl_tls_ctx;
    GLfloat dom[4] = {0, 1, 0, 1};
    GLint seg[2] = {1, 1};
    pl_maps s;
    if (!x && pl_cfg.capture)
        x = pl_current();
    if (!x || !pl_cfg.capture || mode != GL_FILL || x->capturing || x->native_begin || x->compiling ||
        i2 <= i1 || j2 <= j1 || pl_maps_read(&s, 1) != 0) {
        REAL(glEvalMesh2)(mode, i1, i2, j1, j2);
        return;
    }
    REAL(glGetFloatv)(GL_MAP2_GRID_DOMAIN, dom);
    REAL(glGetIntegerv)(GL_MAP2_GRID_SEGMENTS, seg);
    for (GLint j = j1; j < j2; j++) {
        float v0 = pl_grid(dom[2], dom[3], seg[1], j), v1 = pl_grid(dom[2], dom[3], seg[1], j + 1);
        pl_prim_reset(&x->prim, GL_QUAD_STRIP);
        x->prim.from_arrays = 1; /* evaluated values do not become the current ones */
        x->capturing = 1;
        pl_update_slow(x);
        for (GLint i = i1; i <= i2; i++) {
            float u = pl_grid(dom[0], dom[1], seg[0], i);
            pl_eval_vertex(x, &s, u, v0);
            pl_eval_vertex(x, &s, u, v1);
        }
        x->capturing = 0;
        pl_update_slow(x);
        pl_draw_prim(x, &x->prim);
    }
    pl_maps_free(&s);
}
