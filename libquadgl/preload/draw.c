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

int pl_polygons_filled(void)
{
    GLint mode[2] = {GL_FILL, GL_FILL};
    REAL(glGetIntegerv)(GL_POLYGON_MODE, mode);
    return mode[0] == GL_FILL && mode[1] == GL_FILL;
}

/* The driver gets vertices [v0, v1) of p, with the materials that fall among them; with
 * list_split, GL_QUADS as the triangles 0-1-3, 1-2-3 of each quad, every vertex with its own
 * values and materials (p was back-filled). */
static void pl_replay_vertices(const pl_prim *p, size_t v0, size_t v1, qgl__matrun *mat, int list_split)
{
    static const int split[6] = {0, 1, 3, 1, 2, 3};
    struct qgl__gl *gl = pl_gl();
    const qgl__verts *v = &p->v;
    size_t n = list_split ? 6 * ((v1 - v0) / 4) : v1 - v0;
    for (size_t j = 0; j < n; j++) {
        size_t i = list_split ? v0 + 4 * (j / 6) + (size_t)split[j % 6] : v0 + j;
        size_t given = list_split ? 0 : i; /* compared with the first vertex giving a value */
        if (list_split && j % 6 == 0)
            qgl__matrun_quad(mat, i);
        if (list_split)
            qgl__matrun_emit(gl, mat, split[j % 6]);
        else
            qgl__matrun_to(gl, mat, i);
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
static void pl_replay_range(const pl_prim *p, size_t v0, size_t v1)
{
    int split = p->in_list && p->mode == GL_QUADS && pl_polygons_filled();
    qgl__matrun mat;
    qgl__matrun_start(split ? pl_gl() : NULL, &mat, p->mat, p->nmat);
    REAL(glBegin)(split ? GL_TRIANGLES : p->mode);
    pl_replay_vertices(p, v0, v1, &mat, split);
    REAL(glEnd)();
    qgl__matrun_to(pl_gl(), &mat, SIZE_MAX);
}

void pl_prim_to_driver(pl_ctx *x, const pl_prim *p)
{
    qgl__matrun mat;
    qgl__matrun_start(NULL, &mat, p->mat, p->nmat);
    REAL(glBegin)(p->mode);
    pl_replay_vertices(p, 0, p->v.n, &mat, 0);
    qgl__matrun_to(pl_gl(), &mat, SIZE_MAX);
    pl_prim_apply_current(x, p);
}

void pl_prim_emit(pl_ctx *x, const pl_prim *p)
{
    pl_replay_range(p, 0, p->v.n);
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
/* From this many vertices on, the split quads of a primitive are drawn from our arrays (one
 * upload, one draw) rather than handed back to the driver's immediate mode call by call. */
#define PL_ARRAYS_FROM 64

static void pl_draw_gl(qgl_context *qgl, pl_prim *p)
{
    qgl__verts v = p->v;
    v.mask &= ~(unsigned)QGL__A_MATERIAL;
    unsigned flags = p->from_arrays ? 0 : QGL__DRAW_IMMEDIATE;
    if (!p->from_arrays && !p->nmat && v.n >= PL_ARRAYS_FROM)
        flags |= QGL__DRAW_ARRAYS; /* materials inside are given between vertices: replayed */
    if (qgl__draw_batch(qgl, &v, pl_topology(p), NULL, flags, p->mat, p->nmat) < 0) {
        pl_log(PL_LOG_DEBUG, "the GL path refused %zu quads; the driver draws them", pl_prim_quads(p));
        pl_replay_range(p, 0, p->v.n);
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
    pl_batch_flush(x);
    pl_prim_backfill(x, p);
    if (!pl_prim_for_driver(x, p)) {
        pl_draw_gl(pl_ctx_qgl(x), p);
        if (!p->from_arrays)
            pl_prim_apply_current(x, p);
        return;
    }
    pl_replay(x, p);
}

/* ---- batches ------------------------------------------------------------------------------- */

static unsigned pl_slot_bit(int a)
{
    return a == QGL__NATTR ? QGL__A_EDGE : 1u << a;
}

void pl_batch_keep(pl_ctx *x, int a)
{
    qgl__verts *v = &x->batch.v;
    unsigned bit = pl_slot_bit(a);
    if (!qgl__verts_reserve(v, v->n, v->mask | bit)) {
        pl_batch_flush(x);
        return;
    }
    pl_fill_current(x, v, a, 0, v->n);
    v->mask |= bit;
}

/* Whether quads of p may wait in the batch at all: a context whose frames end through us (a
 * program that swaps through a pointer we never handed out would show frames without their
 * last quads), and quads the GL path draws. */
static int pl_batch_open(pl_ctx *x, const pl_prim *p)
{
    if (!x->swapped && x->api != PL_API_OSMESA)
        return 0;
    return !__atomic_load_n(&pl_untracked, __ATOMIC_RELAXED) && !pl_prim_for_driver(x, p);
}

/* Whether p, just finished, may wait in the batch: whole quads that fit, of a kind the batch
 * carries, where pl_batch_open allows. */
static int pl_batchable(pl_ctx *x, const pl_prim *p)
{
    size_t nq = pl_prim_quads(p);
    /* method split promises the driver's own drawing, strips included */
    if ((p->mode == GL_QUAD_STRIP && pl_cfg.method == QGL_METHOD_SPLIT) || p->nmat || p->generic_given ||
        p->lost || !nq || x->batch.v.n + 4 * nq > PL_BATCH_MAX)
        return 0;
    if (!pl_batch_open(x, p))
        return 0;
    if (p->mode == GL_QUADS)
        return 1;
    /* strips are unrolled: not where the driver draws them as they are (outlines, feedback),
     * nor where its own triangles' vertex order shows: the unrolled quads' triangles are the
     * strip's, but begin at other vertices, and the rasterizer may then give a pixel on their
     * shared edge to both or neither, which blending adds up (hypnowheel) */
    const qgl__state *st = qgl__state_now(pl_ctx_qgl(x));
    return st->render_mode == GL_RENDER && st->polygon_mode[0] == GL_FILL && st->polygon_mode[1] == GL_FILL &&
           st->blend_free;
}

/* Appends p's whole quads to the batch (a strip's unrolled as the GL path draws a list's:
 * qgl__verts_unroll). An attribute one of them carries and the other does not is, for the
 * other's vertices, the current value: the batch's vertices were made with it and it has not
 * changed since (pl_batch_keep), and p's own ones were given none. */
static int pl_batch_join(pl_ctx *x, const pl_prim *p)
{
    qgl__verts *b = &x->batch.v;
    size_t n0 = b->n, nq = pl_prim_quads(p), n = 4 * nq;
    unsigned mask = b->mask | p->v.mask, fresh = p->v.mask & ~b->mask, missing = b->mask & ~p->v.mask;
    if (!qgl__verts_reserve(b, n0 + n, mask))
        return 0;
    for (int a = 0; fresh && a <= QGL__NATTR; a++) /* mostly none: the primitives give alike */
        if (fresh & pl_slot_bit(a))
            pl_fill_current(x, b, a, 0, n0);
    if (p->mode == GL_QUADS) {
        qgl__verts_copy_range(b, n0, &p->v, 0, n);
    } else {
        qgl_context *qgl = pl_ctx_qgl(x);
        const qgl__state *st = qgl__state_now(qgl);
        int flat = st->shade_model == GL_FLAT && qgl__flat_corner(qgl, st, QGL_QUAD_STRIP) == 2;
        qgl__verts_unroll(b, n0, &p->v, 0, nq, flat ? 3 : 0);
    }
    for (int a = 0; missing && a <= QGL__NATTR; a++)
        if (missing & pl_slot_bit(a))
            pl_fill_current(x, b, a, n0, n0 + n);
    b->n = n0 + n;
    b->mask = mask;
    return 1;
}

void pl_end_prim(pl_ctx *x, pl_prim *p)
{
    if (x->batch.v.n + 4 * pl_prim_quads(p) > PL_BATCH_MAX)
        pl_batch_flush(x); /* full: drawn, and p may begin the next */
    if (!pl_batchable(x, p)) {
        pl_draw_prim(x, p);
        return;
    }
    pl_prim_backfill(x, p);
    if (!pl_batch_join(x, p)) {
        pl_draw_prim(x, p);
        return;
    }
    if (!p->from_arrays)
        pl_prim_apply_current(x, p);
    pl_update_slow(x);
}

void pl_prim_direct(pl_ctx *x)
{
    pl_prim *p = &x->prim;
    const qgl__verts *b = &x->batch.v;
    /* Vertices in the batch: it was open for the primitive before, and a call since that
     * could close it (a program bound) would have drawn it first, so only what no call
     * marks is asked again (a program's first quad per batch pays the whole question). */
    int open = b->n ? !__atomic_load_n(&pl_untracked, __ATOMIC_RELAXED) : pl_batch_open(x, p);
    if (!open)
        return;
    if (b->n + 4 > PL_BATCH_MAX)
        pl_batch_flush(x); /* full: drawn, and the primitive begins the next */
    /* what the primitive does not give its vertices take, as the batch's earlier ones did:
     * the current values (known, mostly) */
    float unused[4];
    for (unsigned m = b->mask & QGL__A_ATTRIBS & ~x->cur_known; m; m &= m - 1)
        pl_current_value(x, __builtin_ctz(m), unused);
    if (b->mask & QGL__A_EDGE)
        pl_current_edge(x);
    p->direct = 1;
    p->base = b->n;
}

void pl_end_direct(pl_ctx *x, pl_prim *p)
{
    p->direct = 0;
    x->batch.v.n = p->base + 4 * (p->v.n / 4); /* whole quads */
    x->cur_lazy |= p->v.mask & (QGL__A_ATTRIBS | QGL__A_EDGE); /* given by the batch's drawing */
    if (!x->batch.v.n)
        pl_cur_sync(x);
    pl_update_slow(x);
}

void pl_batch_flush(pl_ctx *x)
{
    pl_prim *b = &x->batch;
    size_t n = b->v.n;
    if (PL_UNLIKELY(x->prim.direct))
        pl_prim_settle(x); /* a primitive in the making keeps its vertices */
    if (PL_LIKELY(n == 0))
        return;
    b->v.n = 0; /* first: nothing below may find it pending */
    pl_update_slow(x);
    qgl_context *qgl = pl_ctx_qgl(x);
    qgl__verts v = b->v;
    v.n = n;
    unsigned flags = QGL__DRAW_IMMEDIATE | (n >= PL_ARRAYS_FROM ? QGL__DRAW_ARRAYS : 0);
    if (!qgl || qgl__draw_batch(qgl, &v, QGL_QUADS, NULL, flags, NULL, 0) < 0) {
        b->mode = GL_QUADS;
        b->v.n = n;
        memset(b->first, 0, sizeof b->first);
        pl_replay_range(b, 0, n);
        pl_count_passthrough(n / 4);
        b->v.n = 0;
    }
    /* A replay left the batch's last values current, an array draw undefined ones; the program
     * has set its own since: they are put back (known: a call that could change them unseen
     * would have drawn the batch first), with those not given to the driver yet. */
    x->cur_lazy |= v.mask & x->cur_known & (QGL__A_ATTRIBS | QGL__A_EDGE);
    pl_cur_sync(x);
    b->v.mask = 0;
}
