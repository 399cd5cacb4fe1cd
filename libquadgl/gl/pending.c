/* pending.c: consecutive quad primitives gathered into one draw, for owners that see every GL call.
 *
 * With qgl_gl_desc.assume_exclusive the owner of the context promises to call qgl_gl_flush
 * before any GL call that does not go through this layer. Nothing can then change the GL
 * state between two qgl primitives without a flush, so a finished primitive (qglEnd,
 * qgl_draw_quads) need not be drawn at once: it is appended to one pending batch of GL_QUADS,
 * and a run of primitives costs one state query, one upload and one draw instead of one each
 * (rlgl's batching; a mesh drawn as 64 strips is the case it is for). Strips are unrolled into
 * quads whose corner order keeps the quad's provoking vertex (the MVC picture does not depend
 * on the corner order). An attribute that some primitives give and others do not is filled,
 * for the others, with the driver's current value at the time they were finished, which is
 * what the driver would have used for them. A primitive that could draw differently once
 * unrolled is drawn at once after a flush: method SPLIT (the driver's own strip split was
 * asked for), edge flags (strips ignore them) and per-vertex materials. Every qgl* call that
 * reaches the driver flushes first (qgl__flush), so the driver sees the same sequence as
 * without batching. */
#include <string.h>

#include "gl_internal.h"

/* Beyond this many pending vertices a primitive flushes first: bounds the memory held. */
#define PENDING_MAX ((size_t)1 << 21)

/* Attribute bit of v at vertex i to the value val (the layout of the qgl__verts arrays). */
static void set_attr(qgl__verts *v, size_t i, unsigned bit, const float val[4])
{
    int a = __builtin_ctz(bit), k = qgl__attribs[a].floats;
    memcpy(v->attr[a] + (size_t)k * i, val, (size_t)k * sizeof(float));
}

/* Vertices [from, to) of v get the driver's current value of every attribute in bits. */
static void fill_current(qgl_context *ctx, qgl__verts *v, size_t from, size_t to, unsigned bits)
{
    bits &= QGL__A_ATTRIBS;
    for (unsigned bit = 1; bits; bit <<= 1) {
        if (!(bits & bit))
            continue;
        bits &= ~bit;
        float cur[4];
        qgl__driver_current(ctx, bit, cur);
        for (size_t i = from; i < to; i++)
            set_attr(v, i, bit, cur);
    }
}

/* Append the nq quads of v to the pending batch. GL_QUADS keep their order; strip quad k
 * (corners v2k, v2k+1, v2k+3, v2k+2) starts at the corner that puts its provoking vertex
 * where a GL_QUADS quad has it: v2k+3 last under the last-vertex convention, v2k first under
 * the first-vertex one. */
static int append(qgl_context *ctx, const qgl__verts *v, qgl_topology topo, size_t nq)
{
    qgl__verts *p = &ctx->pend;
    size_t n0 = p->n;
    if (!qgl__verts_reserve(p, n0 + 4 * nq, p->mask | v->mask))
        return 0;
    fill_current(ctx, p, 0, n0, v->mask & ~p->mask & ~(unsigned)QGL__A_EDGE);
    if (topo == QGL_QUADS) {
        qgl__verts_copy_range(p, n0, v, 0, 4 * nq);
    } else {
        qgl__verts_unroll(p, n0, v, 0, nq, qgl__flat_corner(ctx, NULL, topo) == 2 ? 3 : 0);
    }
    p->n = n0 + 4 * nq;
    fill_current(ctx, p, n0, p->n, p->mask & ~v->mask);
    p->mask |= v->mask;
    return 1;
}

int qgl__submit(qgl_context *ctx, qgl__verts *v, qgl_topology topo)
{
    size_t nq = qgl__nquads(topo, v->n);
    if (!nq)
        return 0;
    int defer = ctx->exclusive && ctx->method != QGL_METHOD_SPLIT &&
                !(v->mask & (QGL__A_EDGE | QGL__A_MATERIAL));
    if (!defer || ctx->pend.n + 4 * nq > PENDING_MAX)
        qgl__flush(ctx);
    if (!defer)
        return qgl__draw(ctx, v, topo);
    if (!ctx->pend.n && topo == QGL_QUADS && v == &ctx->cap) {
        /* the first primitive of a batch: take the capture's arrays instead of copying */
        qgl__verts t = ctx->pend;
        ctx->pend = *v;
        ctx->pend.n = 4 * nq;
        *v = t;
        v->n = 0;
        return (int)nq;
    }
    if (append(ctx, v, topo, nq))
        return (int)nq;
    qgl__flush(ctx); /* out of memory for the batch: draw what waits, then this one */
    return qgl__draw(ctx, v, topo);
}

void qgl__flush_pending(qgl_context *ctx)
{
    qgl__verts *p = &ctx->pend;
    size_t n = p->n;
    p->n = 0; /* first: the draw must not find a batch pending */
    if (n) {
        qgl__verts batch = *p;
        batch.n = n;
        qgl__draw(ctx, &batch, QGL_QUADS);
    }
    p->mask = 0;
}

QGL_API void qgl_gl_flush(qgl_context *ctx)
{
    if (ctx)
        qgl__flush(ctx);
}
