/* draw.c: drawing a captured quad primitive, through the GL path or back through the driver.
 *
 * A primitive goes to the GL path as its own arrays (the capture's layout is the GL path's),
 * told first what the program's calls changed since the GL path last drew, so it reads only
 * that part of the state, and with the glMaterial calls made between glBegin and glEnd: the
 * driver's own drawing of split quads takes them at their vertex, the GL path's from the quad
 * that holds it. Whatever the GL path cannot take, or when there is
 * none (QUADGL_METHOD=replay, no GL path built, its context failed, an application program is
 * bound, a texture unit beyond the batch's), is replayed to the driver as the very calls it
 * would have seen: glBegin, the attributes given per vertex (edge flags and generic
 * attributes included), glVertex4fv, glEnd. Either way the current attributes end as GL
 * leaves them: the last values given inside glBegin/glEnd, or for an array draw (and an
 * evaluator mesh) the values from before it. A primitive recorded in a display list is
 * retained by the GL path at its first draw (qgl_gl_retain: its per-quad plan worked out once)
 * with the driver's own compilation of its calls as the native way to draw it; each later
 * draw only reads the state, and when that splits every quad exactly the driver's list runs
 * and nothing else. Vertices that take a current value (an attribute first given after them)
 * are filled at the first draw; if that value differs later, the plain path draws. */
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

/* The driver draws vertices [v0, v1) itself, with the materials that fall among them. */
static void pl_replay_range(const pl_prim *p, size_t v0, size_t v1, size_t *mat)
{
    struct qgl__gl *gl = pl_gl();
    const qgl__verts *v = &p->v;
    REAL(glBegin)(p->mode);
    for (size_t i = v0; i < v1; i++) {
        for (; *mat < p->nmat && p->mat[*mat].vertex <= i; ++*mat)
            pl_apply_material(&p->mat[*mat]);
        for (int a = 0; a < QGL__NATTR; a++)
            if ((v->mask & (1u << a)) && i >= p->first[a])
                qgl__set_current(gl, a, v->attr[a] + (size_t)qgl__attribs[a].floats * i);
        if ((v->mask & QGL__A_EDGE) && i >= p->first[QGL__NATTR])
            gl->EdgeFlag(v->edge[i]);
        for (unsigned g = p->generic_given; g; g &= g - 1) {
            int k = __builtin_ctz(g);
            if (i >= p->generic_first[k])
                gl->VertexAttrib4fv((GLuint)k, p->generic[k] + 4 * i);
        }
        gl->Vertex4fv(v->pos + 4 * i);
    }
    REAL(glEnd)();
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

/* The driver draws p: from the list compiled with it when there is one, else from its calls;
 * an array draw's replay puts the current attributes back (they were not its to change). */
static void pl_replay(pl_ctx *x, pl_prim *p)
{
    float saved[QGL__NATTR][4];
    pl_count_passthrough(pl_prim_quads(p));
    if (p->native_list) {
        REAL(glCallList)(p->native_list);
        return;
    }
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

/* A listed primitive's retained copy, and the current values its backfilled vertices (those
 * before an attribute was first given) took when it was made. */
struct pl_retained {
    qgl_retained *r;
    float backfilled[QGL__NATTR][4];
};

static void pl_call_native(void *list)
{
    REAL(glCallList)((GLuint)(uintptr_t)list);
}

static int pl_backfill_changed(pl_ctx *x, const pl_prim *p, const struct pl_retained *r)
{
    for (int a = 0; a < QGL__NATTR; a++)
        if ((p->v.mask & (1u << a)) && p->first[a] > 0) {
            float now[4];
            pl_current_value(x, a, now);
            if (memcmp(now, r->backfilled[a], (size_t)qgl__attribs[a].floats * sizeof(float)) != 0)
                return 1;
        }
    return 0;
}

static void pl_attrib(qgl_attrib *out, const float *ptr, int size)
{
    out->ptr = ptr;
    out->size = size;
    out->type = GL_FLOAT;
    out->stride = 0;
}

static struct pl_retained *pl_retain(pl_ctx *x, const pl_prim *p)
{
    struct pl_retained *r = calloc(1, sizeof *r);
    qgl_retain_desc desc = {pl_call_native, (void *)(uintptr_t)p->native_list};
    qgl_quad_batch b;
    const qgl__verts *v = &p->v;
    if (!r)
        return NULL;
    memset(&b, 0, sizeof b);
    b.topology = pl_topology(p);
    b.count = (int)v->n;
    pl_attrib(&b.position, v->pos, 4);
    if (v->mask & QGL__A_COLOR)
        pl_attrib(&b.color, v->col, 4);
    if (v->mask & QGL__A_COLOR2)
        pl_attrib(&b.secondary_color, v->col2, 3);
    if (v->mask & QGL__A_NORMAL)
        pl_attrib(&b.normal, v->nrm, 3);
    if (v->mask & QGL__A_FOG)
        pl_attrib(&b.fog_coord, v->fog, 1);
    for (int u = 0; u < PL_TEXUNITS; u++)
        if (v->mask & (QGL__A_TEX0 << u))
            pl_attrib(&b.texcoord[u], v->tex[u], 4);
    for (int a = 0; a < QGL__NATTR; a++)
        if ((v->mask & (1u << a)) && p->first[a] > 0)
            pl_current_value(x, a, r->backfilled[a]);
    if (!(r->r = qgl_gl_retain(&b, &desc))) {
        free(r);
        return NULL;
    }
    return r;
}

/* The retained copy of p that matches its vertices as backfilled now; made on first use (a
 * list may run on several threads: the first copy installed wins). NULL when the backfilled
 * values changed since (the plain path draws) or on failure. */
static struct pl_retained *pl_retained_get(pl_ctx *x, pl_prim *p)
{
    struct pl_retained *r = __atomic_load_n(&p->retained, __ATOMIC_ACQUIRE), *none = NULL;
    if (!r) {
        if (!(r = pl_retain(x, p)))
            return NULL;
        if (!__atomic_compare_exchange_n(&p->retained, &none, r, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
            pl_retained_free(r);
            r = none;
        }
    }
    return pl_backfill_changed(x, p, r) ? NULL : r;
}

void pl_retained_free(struct pl_retained *r)
{
    if (r)
        qgl_gl_release(r->r);
    free(r);
}

int pl_prim_for_driver(pl_ctx *x, const pl_prim *p)
{
    qgl_context *qgl;
    if (pl_cfg.replay || p->lost || !(qgl = pl_ctx_qgl(x)))
        return 1;
    return qgl__state_now(qgl)->program != 0;
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

void pl_draw_listed(pl_ctx *x, pl_prim *p)
{
    struct pl_retained *r;
    if (p->native_list && !p->nmat && p->v.n && !p->generic_given && !pl_prim_for_driver(x, p)) {
        pl_prim_backfill(x, p);
        if ((r = pl_retained_get(x, p)) && qgl_gl_draw_retained(pl_ctx_qgl(x), r->r) >= 0) {
            if (!p->from_arrays)
                pl_prim_apply_current(x, p);
            return;
        }
    }
    pl_draw_prim(x, p);
}
