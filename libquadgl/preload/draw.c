/* draw.c: drawing a captured quad primitive, through the GL path or back through the driver.
 *
 * A primitive goes to the GL path as its own arrays (the capture's layout is the GL path's),
 * told first what the program's calls changed since the GL path last drew, so it reads only
 * that part of the state, and with the glMaterial calls made between glBegin and glEnd: the
 * driver's own drawing of split quads takes them at their vertex, the GL path's from the quad
 * that holds it. Whatever the GL path cannot take, or when there is
 * none (QUADGL_METHOD=replay, no GL path built, its context failed, a GLSL or ARB program is
 * bound, a texture unit beyond the batch's), is replayed to the driver as the very calls it
 * would have seen: glBegin, the attributes given per vertex (edge flags and generic
 * attributes included), glVertex4fv, glEnd. Either way the current attributes end as GL
 * leaves them: the last values given inside glBegin/glEnd, or for an array draw (and an
 * evaluator mesh) the values from before it. (Display lists keep their geometry as meshes of
 * the GL layer: lists.c; a list's primitive replayed here is drawn as the driver's lists draw.) */
#include "preload.h"

#include <stdlib.h>
#include <string.h>

static struct qgl__gl pl_gl_table;
static pthread_once_t pl_gl_once = PTHREAD_ONCE_INIT;

static void pl_gl_load(void)
{
    qgl__gl_load(&pl_gl_table, pl_real_proc);
}

struct qgl__gl *pl_gl(void)
{
    pthread_once(&pl_gl_once, pl_gl_load);
    return &pl_gl_table;
}

void pl_prim_apply_current(pl_ctx *x, const pl_prim *p)
{
    struct qgl__gl *gl = pl_gl();
    for (int a = 0; a < QGL__NATTR; a++)
        if (p->v.mask & (1u << a))
            qgl__set_current(gl, a, p->cur[a]);
    if (p->v.mask & QGL__A_EDGE)
        gl->EdgeFlag(p->cur_edge);
    for (unsigned g = p->generic_given; g; g &= g - 1)
        gl->VertexAttrib4fv((GLuint)__builtin_ctz(g), p->cur_generic[__builtin_ctz(g)]);
    (void)x;
}

static void pl_apply_material(const pl_material *m)
{
    REAL(glMaterialfv)(m->face, m->pname, m->v);
}

int pl_polygons_filled(void)
{
    GLint mode[2] = {GL_FILL, GL_FILL};
    REAL(glGetIntegerv)(GL_POLYGON_MODE, mode);
    return mode[0] == GL_FILL && mode[1] == GL_FILL;
}

/* The driver gets vertices [v0, v1) of p, with the materials that fall among them; with
 * list_split, GL_QUADS as the triangles 0-1-3, 1-2-3 of each quad, every vertex with its own
 * values (p was back-filled). */
static void pl_replay_vertices(const pl_prim *p, size_t v0, size_t v1, size_t *mat, int list_split)
{
    static const int split[6] = {0, 1, 3, 1, 2, 3};
    struct qgl__gl *gl = pl_gl();
    const qgl__verts *v = &p->v;
    size_t n = list_split ? 6 * ((v1 - v0) / 4) : v1 - v0;
    for (size_t j = 0; j < n; j++) {
        size_t i = list_split ? v0 + 4 * (j / 6) + (size_t)split[j % 6] : v0 + j;
        size_t given = list_split ? 0 : i; /* compared with the first vertex giving a value */
        for (; *mat < p->nmat && p->mat[*mat].vertex <= i; ++*mat)
            pl_apply_material(&p->mat[*mat]);
        for (int a = 0; a < QGL__NATTR; a++)
            if ((v->mask & (1u << a)) && given >= p->first[a])
                qgl__set_current(gl, a, v->attr[a] + (size_t)qgl__attribs[a].floats * i);
        if ((v->mask & QGL__A_EDGE) && given >= p->first[QGL__NATTR])
            gl->EdgeFlag(v->edge[i]);
        for (unsigned g = p->generic_given; g; g &= g - 1) {
            int k = __builtin_ctz(g);
            if (given >= p->generic_first[k])
                gl->VertexAttrib4fv((GLuint)k, p->generic[k] + 4 * i);
        }
        gl->Vertex4fv(v->pos + 4 * i);
    }
}

/* The driver draws vertices [v0, v1) itself; a display list's GL_QUADS as its own lists draw
 * them when the polygons are filled (lists.c). */
static void pl_replay_range(const pl_prim *p, size_t v0, size_t v1, size_t *mat)
{
    int split = p->in_list && p->mode == GL_QUADS && pl_polygons_filled();
    REAL(glBegin)(split ? GL_TRIANGLES : p->mode);
    pl_replay_vertices(p, v0, v1, mat, split);
    REAL(glEnd)();
}

void pl_prim_to_driver(pl_ctx *x, const pl_prim *p)
{
    size_t mat = 0;
    REAL(glBegin)(p->mode);
    pl_replay_vertices(p, 0, p->v.n, &mat, 0);
    for (; mat < p->nmat; mat++)
        pl_apply_material(&p->mat[mat]);
    pl_prim_apply_current(x, p);
}

void pl_prim_emit(pl_ctx *x, const pl_prim *p)
{
    size_t mat = 0;
    pl_replay_range(p, 0, p->v.n, &mat);
    for (; mat < p->nmat; mat++)
        pl_apply_material(&p->mat[mat]);
    if (!p->from_arrays)
        pl_prim_apply_current(x, p);
}

/* The driver draws p from its calls; an array draw's replay puts the current attributes back (they were not its to change). */
static void pl_replay(pl_ctx *x, pl_prim *p)
{
    float saved[QGL__NATTR][4];
    pl_count_passthrough(pl_prim_quads(p));
    if (p->from_arrays)
        for (int a = 0; a < QGL__NATTR; a++)
            if (p->v.mask & (1u << a))
                pl_current_value(x, a, saved[a]);
    pl_prim_emit(x, p);
    if (p->from_arrays)
        for (int a = 0; a < QGL__NATTR; a++)
            if (p->v.mask & (1u << a))
                qgl__set_current(pl_gl(), a, saved[a]);
}

static qgl_topology pl_topology(const pl_prim *p)
{
    return p->mode == GL_QUADS ? QGL_QUADS : QGL_QUAD_STRIP;
}

/* p through the GL path, its materials applied where they fall (or the driver draws it all,
 * if the GL path refuses). */
static void pl_draw_gl(qgl_context *qgl, pl_prim *p)
{
    qgl__verts v = p->v;
    v.mask &= ~(unsigned)QGL__A_MATERIAL;
    if (qgl__draw_batch(qgl, &v, pl_topology(p), NULL, p->from_arrays ? 0 : QGL__DRAW_IMMEDIATE, p->mat, p->nmat) < 0) {
        size_t mat = 0;
        pl_log(PL_LOG_DEBUG, "the GL path refused %zu quads; the driver draws them", pl_prim_quads(p));
        pl_replay_range(p, 0, p->v.n, &mat);
        for (; mat < p->nmat; mat++)
            pl_apply_material(&p->mat[mat]);
        pl_count_passthrough(pl_prim_quads(p));
    }
}

int pl_prim_for_driver(pl_ctx *x, const pl_prim *p)
{
    qgl_context *qgl;
    if (pl_cfg.replay || p->lost || !(qgl = pl_ctx_qgl(x)))
        return 1;
    return qgl__state_now(qgl)->own_pipeline;
}

void pl_draw_prim(pl_ctx *x, pl_prim *p)
{
    pl_prim_backfill(x, p);
    if (!pl_prim_for_driver(x, p)) {
        pl_draw_gl(pl_ctx_qgl(x), p);
        if (!p->from_arrays)
            pl_prim_apply_current(x, p);
        return;
    }
    pl_replay(x, p);
}
