/* draw.c: drawing a captured quad primitive, through the GL path or back through the driver.
 *
 * A primitive goes to the GL path as one batch (qgl_draw_quads) pointing straight into its
 * vertex array: position always, every other attribute only if the program gave it (the GL
 * path takes absent ones from the current state). glMaterial calls made between glBegin and
 * glEnd split the batch at the quad that holds the vertex they precede. Whatever the GL path
 * cannot take, or when there is none (QUADGL_METHOD=replay, no GL path built, its context
 * failed, an application program is bound, an edge flag is off, a texture unit beyond the
 * batch's), is replayed to the driver as the very calls it would have seen: glBegin, the
 * attributes given per vertex, glVertex4fv, glEnd. Either way the current attributes end as
 * GL leaves them: the last values given inside glBegin/glEnd, or for an array draw (and an
 * evaluator mesh) the values from before it. A primitive recorded in a display list is
 * retained by the GL path at its first draw (qgl_gl_retain: its per-quad plan worked out once)
 * with the driver's own compilation of its calls as the native way to draw it; each later
 * draw only reads the state, and when that splits every quad exactly the driver's list runs
 * and nothing else. Vertices that take a current value (an attribute first given after them)
 * are filled at the first draw; if that value differs later, the plain path draws. */
#include "preload.h"

#include <stdlib.h>
#include <string.h>

static void pl_set_attr(int a, const pl_vertex *v)
{
    switch (a) {
    case PL_A_COLOR: REAL(glColor4fv)(v->color); break;
    case PL_A_SECONDARY: REAL(glSecondaryColor3fv)(v->secondary); break;
    case PL_A_NORMAL: REAL(glNormal3fv)(v->normal); break;
    case PL_A_FOG: REAL(glFogCoordf)(v->fog); break;
    default: REAL(glMultiTexCoord4fv)(GL_TEXTURE0 + (GLenum)(a - PL_A_TEX0), v->tex[a - PL_A_TEX0]); break;
    }
}

void pl_prim_apply_current(const pl_prim *p)
{
    for (int a = 0; a < PL_A_COUNT; a++)
        if (p->given & (1u << a))
            pl_set_attr(a, &p->cur);
}

static void pl_apply_material(const pl_material *m)
{
    REAL(glMaterialfv)(m->face, m->pname, m->v);
}

/* The driver draws vertices [v0, v1) itself, with the materials that fall among them. */
static void pl_replay_range(const pl_prim *p, size_t v0, size_t v1, size_t *mat)
{
    REAL(glBegin)(p->mode);
    for (size_t i = v0; i < v1; i++) {
        for (; *mat < p->nmat && p->mat[*mat].vertex <= i; ++*mat)
            pl_apply_material(&p->mat[*mat]);
        for (int a = 0; a < PL_A_COUNT; a++)
            if ((p->given & (1u << a)) && i >= p->first[a])
                pl_set_attr(a, &p->v[i]);
        REAL(glVertex4fv)(p->v[i].pos);
    }
    REAL(glEnd)();
}

void pl_prim_emit(const pl_prim *p)
{
    size_t mat = 0;
    pl_replay_range(p, 0, p->n, &mat);
    for (; mat < p->nmat; mat++)
        pl_apply_material(&p->mat[mat]);
    if (!p->from_arrays)
        pl_prim_apply_current(p);
}

/* The driver draws p: from the list compiled with it when there is one, else from its calls. */
static void pl_replay(pl_prim *p)
{
    pl_vertex saved;
    memset(&saved, 0, sizeof saved);
    pl_count_passthrough(pl_prim_quads(p));
    if (p->native_list) {
        REAL(glCallList)(p->native_list);
        return;
    }
    if (p->from_arrays)
        for (int a = 0; a < PL_A_COUNT; a++)
            if (p->given & (1u << a))
                pl_read_current(a, pl_attr_ptr(&saved, a));
    pl_prim_emit(p);
    if (p->from_arrays)
        for (int a = 0; a < PL_A_COUNT; a++)
            if (p->given & (1u << a))
                pl_set_attr(a, &saved);
}

static void pl_attrib(qgl_attrib *out, const float *ptr, int size)
{
    out->ptr = ptr;
    out->size = size;
    out->type = GL_FLOAT;
    out->stride = (int)sizeof(pl_vertex);
}

/* The batch of quads [q0, q1) of p, pointing into its vertices. */
static void pl_fill_batch(qgl_quad_batch *b, const pl_prim *p, size_t q0, size_t q1)
{
    size_t v0 = p->mode == GL_QUADS ? 4 * q0 : 2 * q0;
    size_t count = p->mode == GL_QUADS ? 4 * (q1 - q0) : 2 * (q1 - q0) + 2;
    const pl_vertex *v = p->v + v0;
    memset(b, 0, sizeof *b);
    b->topology = p->mode == GL_QUADS ? QGL_QUADS : QGL_QUAD_STRIP;
    b->count = q1 > q0 ? (int)count : 0;
    pl_attrib(&b->position, v->pos, 4);
    if (p->given & (1u << PL_A_COLOR))
        pl_attrib(&b->color, v->color, 4);
    if (p->given & (1u << PL_A_SECONDARY))
        pl_attrib(&b->secondary_color, v->secondary, 3);
    if (p->given & (1u << PL_A_NORMAL))
        pl_attrib(&b->normal, v->normal, 3);
    if (p->given & (1u << PL_A_FOG))
        pl_attrib(&b->fog_coord, &v->fog, 1);
    for (int u = 0; u < PL_TEXUNITS; u++)
        if (p->given & (1u << (PL_A_TEX0 + u)))
            pl_attrib(&b->texcoord[u], v->tex[u], 4);
}

/* Quads [q0, q1) of p through the GL path (or the driver, if it refuses them). */
static void pl_batch(qgl_context *qgl, const pl_prim *p, size_t q0, size_t q1)
{
    qgl_quad_batch b;
    size_t v0 = p->mode == GL_QUADS ? 4 * q0 : 2 * q0;
    if (q1 <= q0)
        return;
    pl_fill_batch(&b, p, q0, q1);
    if (qgl_draw_quads(qgl, &b) < 0) {
        size_t no_materials = p->nmat;
        pl_log(PL_LOG_DEBUG, "the GL path refused %zu quads; the driver draws them", q1 - q0);
        pl_replay_range(p, v0, v0 + (size_t)b.count, &no_materials);
        pl_count_passthrough(q1 - q0);
    }
}

/* The quad that holds vertex i (a material before it applies from that quad on). */
static size_t pl_quad_of(const pl_prim *p, size_t i)
{
    if (p->mode == GL_QUADS)
        return i / 4;
    return i < 4 ? 0 : (i - 2) / 2;
}

static void pl_draw_gl(qgl_context *qgl, pl_prim *p)
{
    size_t nq = pl_prim_quads(p), q = 0;
    for (size_t m = 0; m < p->nmat; m++) {
        size_t qm = pl_quad_of(p, p->mat[m].vertex);
        if (qm > nq)
            qm = nq;
        if (qm > q) {
            pl_batch(qgl, p, q, qm);
            q = qm;
        }
        pl_apply_material(&p->mat[m]);
    }
    pl_batch(qgl, p, q, nq);
}

/* A listed primitive's retained copy, and the current values its backfilled vertices (those
 * before an attribute was first given) took when it was made. */
struct pl_retained {
    qgl_retained *r;
    pl_vertex backfilled;
};

static void pl_call_native(void *list)
{
    REAL(glCallList)((GLuint)(uintptr_t)list);
}

static int pl_backfill_changed(const pl_prim *p, pl_vertex *bf)
{
    for (int a = 0; a < PL_A_COUNT; a++)
        if ((p->given & (1u << a)) && p->first[a] > 0 &&
            memcmp(pl_attr_ptr(bf, a), pl_attr_ptr(&p->v[0], a), pl_attr_size(a) * sizeof(float)) != 0)
            return 1;
    return 0;
}

static struct pl_retained *pl_retain(const pl_prim *p)
{
    struct pl_retained *r = calloc(1, sizeof *r);
    qgl_retain_desc desc = {pl_call_native, (void *)(uintptr_t)p->native_list};
    qgl_quad_batch b;
    if (!r)
        return NULL;
    pl_fill_batch(&b, p, 0, pl_prim_quads(p));
    r->backfilled = p->v[0];
    if (!(r->r = qgl_gl_retain(&b, &desc))) {
        free(r);
        return NULL;
    }
    return r;
}

/* The retained copy of p that matches its vertices as backfilled now; made on first use (a
 * list may run on several threads: the first copy installed wins). NULL when the backfilled
 * values changed since (the plain path draws) or on failure. */
static struct pl_retained *pl_retained_get(pl_prim *p)
{
    struct pl_retained *r = __atomic_load_n(&p->retained, __ATOMIC_ACQUIRE), *none = NULL;
    if (!r) {
        if (!(r = pl_retain(p)))
            return NULL;
        if (!__atomic_compare_exchange_n(&p->retained, &none, r, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
            pl_retained_free(r);
            r = none;
        }
    }
    return pl_backfill_changed(p, &r->backfilled) ? NULL : r;
}

void pl_retained_free(struct pl_retained *r)
{
    if (r)
        qgl_gl_release(r->r);
    free(r);
}

static int pl_program_bound(void)
{
    GLint prog = 0;
    REAL(glGetIntegerv)(GL_CURRENT_PROGRAM, &prog);
    return prog != 0;
}

int pl_prim_for_driver(pl_ctx *x, const pl_prim *p)
{
    return pl_cfg.replay || p->edge_off || p->lost || pl_program_bound() || !pl_ctx_qgl(x);
}

void pl_draw_prim(pl_ctx *x, pl_prim *p)
{
    for (int a = 0; a < PL_A_COUNT; a++)
        if ((p->given & (1u << a)) && p->first[a] > 0)
            pl_prim_backfill(p, a);
    if (!pl_prim_for_driver(x, p)) {
        pl_draw_gl(pl_ctx_qgl(x), p);
        if (!p->from_arrays)
            pl_prim_apply_current(p);
        return;
    }
    pl_replay(p);
}

void pl_draw_listed(pl_ctx *x, pl_prim *p)
{
    struct pl_retained *r;
    if (p->native_list && !p->nmat && p->n && !pl_prim_for_driver(x, p)) {
        for (int a = 0; a < PL_A_COUNT; a++)
            if ((p->given & (1u << a)) && p->first[a] > 0)
                pl_prim_backfill(p, a);
        if ((r = pl_retained_get(p)) && qgl_gl_draw_retained(pl_ctx_qgl(x), r->r) >= 0) {
            if (!p->from_arrays)
                pl_prim_apply_current(p);
            return;
        }
    }
    pl_draw_prim(x, p);
}
