/* retain.c: retained batches: quads drawn many times (display lists) planned once.
 *
 * Planning a quad is the expensive part of a draw: the planarity and affinity tests of the
 * core, in double precision with exact scaling, for every quad at every draw. Most of what
 * they answer does not depend on the GL state: whether the quad is planar, whether each
 * attribute (colour, secondary colour, fog coordinate, each unit's texture coordinates) is
 * affine in object space over it, and whether corners with equal attributes group affinely.
 * A retained batch keeps its vertices in the capture layout with those facts per quad (and
 * their conjunction over the batch); at a draw the state, read once, only selects which facts
 * matter. When it makes every quad the driver's (split exact everywhere, polygon mode line,
 * select, method SPLIT) and the owner gave a way for the driver to draw the quads itself, that
 * is all the draw does: no upload, no program, nothing to restore. The object holds no GL
 * name, so any context may draw it and any thread may release it. */
#include <stdlib.h>

#include "gl_internal.h"

struct qgl_retained {
    qgl__verts v;
    qgl_topology topology;
    uint16_t *quad_facts;
    qgl__facts facts;
};

QGL_API qgl_retained *qgl_gl_retain(const qgl_quad_batch *b, const qgl_retain_desc *desc)
{
    qgl_retained *r = calloc(1, sizeof *r);
    if (!r)
        return NULL;
    if (!qgl__batch_to_verts(b, &r->v)) {
        qgl_gl_release(r);
        return NULL;
    }
    r->topology = b->topology;
    size_t nq = qgl__nquads(r->topology, r->v.n);
    r->quad_facts = malloc((nq ? nq : 1) * sizeof *r->quad_facts);
    if (!r->quad_facts) {
        qgl_gl_release(r);
        return NULL;
    }
    unsigned all = 0xffffu;
    for (size_t q = 0; q < nq; q++)
        all &= r->quad_facts[q] = qgl__quad_facts(&r->v, r->topology, q);
    r->facts.quad = r->quad_facts;
    r->facts.all = (uint16_t)all;
    if (desc) {
        r->facts.native = desc->draw_native;
        r->facts.user = desc->user;
    }
    return r;
}

QGL_API int qgl_gl_draw_retained(qgl_context *ctx, const qgl_retained *r)
{
    if (!ctx || !r || ctx->in_begin)
        return -1;
    qgl__flush(ctx);
    return qgl__draw_with_facts(ctx, &r->v, r->topology, &r->facts);
}

QGL_API void qgl_gl_release(qgl_retained *r)
{
    if (!r)
        return;
    qgl__verts_free(&r->v);
    free(r->quad_facts);
    free(r);
}
