/* mesh.c: the primitives of a display list, kept once and drawn many times.
 *
 * A mesh holds every vertex of a run of primitives of any mode (what a display list draws
 * between two state changes), one array per attribute as captured, a table of primitives
 * (mode, first vertex, count, the glMaterial calls inside), and per quad of its quad
 * primitives the facts that do not depend on the GL state (planar, which attributes are
 * affine: draw.c's qgl__quad_facts). At its first draw the vertices go into a buffer object
 * of their own, so later draws upload nothing. A draw reads the state (the groups that
 * changed), and for each quad primitive decides from the facts alone whether the driver's own
 * split serves it exactly; then runs of consecutive primitives of one mode that the driver
 * draws as they are become one multi-draw from the buffer, as the driver's own display list
 * would merge them (GL_QUADS as indexed quads, each distinct vertex once, as the driver's lists
 * draw them: they split a quad 0-1-3, 1-2-3 where its immediate mode splits 0-1-2, 0-2-3, and
 * a smooth non-affine quad shows which), and only the quad primitives that need smoothing go
 * through the planner (qgl__draw_batch with the cached facts). Order is kept throughout
 * (blending and equal depths make it visible). Primitives with glMaterial calls inside, and
 * meshes with generic attributes, are replayed through immediate mode, the only way to give
 * those per vertex to fixed function. */
#include <stdlib.h>
#include <string.h>

#include "gl_internal.h"

static int grow(void **p, size_t *cap, size_t n, size_t elem)
{
    if (n <= *cap)
        return 1;
    size_t c = n > 2 * *cap ? n : 2 * *cap;
    void *q = realloc(*p, (c ? c : 8) * elem);
    if (!q)
        return 0;
    *p = q;
    *cap = c ? c : 8;
    return 1;
}

int qgl__mesh_add_prim(qgl__mesh *m, GLenum mode, size_t first, size_t count, unsigned given, const qgl__change *chg,
                       size_t nchg)
{
    qgl__mesh_prim *last = m->nprim ? &m->prim[m->nprim - 1] : NULL;
    /* Quads are independent: GL_QUADS primitives in a row are one (a list of single quads is
     * then planned and drawn once, not once a quad). */
    if (last && mode == GL_QUADS && last->mode == GL_QUADS && !nchg && !last->nchg && given == last->given &&
        count % 4 == 0 &&
        last->count % 4 == 0 && last->first + last->count == first) {
        last->count += (uint32_t)count;
        return 1;
    }
    if (!grow((void **)&m->prim, &m->capprim, m->nprim + 1, sizeof *m->prim) ||
        !grow((void **)&m->chg, &m->capchg, m->nchg + nchg, sizeof *m->chg))
        return 0;
    qgl__mesh_prim *p = &m->prim[m->nprim++];
    p->mode = mode;
    p->first = (uint32_t)first;
    p->count = (uint32_t)count;
    p->chg0 = (uint32_t)m->nchg;
    p->nchg = (uint32_t)nchg;
    p->facts0 = 0;
    p->given = given;
    for (size_t c = 0; c < nchg; c++) {
        m->chg[m->nchg + c] = chg[c];
        m->chg[m->nchg + c].vertex += (uint32_t)first;
    }
    m->nchg += nchg;
    return 1;
}

static int is_quads(GLenum mode)
{
    return mode == GL_QUADS || mode == GL_QUAD_STRIP;
}

static qgl_topology topology(GLenum mode)
{
    return mode == GL_QUADS ? QGL_QUADS : QGL_QUAD_STRIP;
}

/* Vertices [first, first + n) of v as arrays of their own. */
static qgl__verts view(const qgl__verts *v, size_t first, size_t n)
{
    qgl__verts w = *v;
    w.n = w.cap = n;
    w.pos = v->pos + 4 * first;
    for (int a = 0; a < QGL__NATTR; a++)
        if (v->mask & (1u << a))
            w.attr[a] = v->attr[a] + (size_t)qgl__attribs[a].floats * first;
    if (v->mask & QGL__A_EDGE)
        w.edge = v->edge + first;
    w.mask &= ~(unsigned)QGL__A_MATERIAL;
    return w;
}

int qgl__mesh_finish(qgl__mesh *m)
{
    size_t nq = 0;
    for (size_t i = 0; i < m->nprim; i++)
        if (is_quads(m->prim[i].mode))
            nq += qgl__nquads(topology(m->prim[i].mode), m->prim[i].count);
    free(m->facts);
    m->facts = malloc((nq ? nq : 1) * sizeof *m->facts);
    m->pfacts = realloc(m->pfacts, (m->nprim ? m->nprim : 1) * sizeof *m->pfacts);
    if (!m->facts || !m->pfacts)
        return 0;
    m->nquads = nq;
    size_t k = 0;
    for (size_t i = 0; i < m->nprim; i++) {
        qgl__mesh_prim *p = &m->prim[i];
        unsigned all = 0xffffu;
        p->facts0 = (uint32_t)k;
        if (is_quads(p->mode)) {
            qgl__verts w = view(&m->v, p->first, p->count);
            size_t n = qgl__nquads(topology(p->mode), p->count);
            for (size_t q = 0; q < n; q++)
                all &= m->facts[k++] = qgl__quad_facts(&w, topology(p->mode), q);
        }
        m->pfacts[i] = (uint16_t)all;
    }
    m->stale = 1;
    return 1;
}

void qgl__mesh_changed(qgl__mesh *m)
{
    m->stale = 1;
}

void qgl__mesh_free(struct qgl__gl *gl, const void *owner, qgl__mesh *m)
{
    if (m->bo && gl && owner == m->owner)
        gl->DeleteBuffers(1, &m->bo);
    qgl__verts_free(&m->v);
    free(m->prim);
    free(m->chg);
    free(m->facts);
    free(m->pfacts);
    memset(m, 0, sizeof *m);
}

/* The arrays a vertex's data is read from: positions, the attributes of mask (by row of
 * QGL__ATTRIBS), edge flags; base, bytes per vertex and the mesh's offset field of each. */
typedef struct vertex_arrays {
    int n;
    const unsigned char *base[QGL__NATTR + 2];
    size_t size[QGL__NATTR + 2], *off[QGL__NATTR + 2];
} vertex_arrays;

static void arrays_of(qgl__mesh *m, vertex_arrays *va)
{
    const qgl__verts *v = &m->v;
    int k = 0;
    va->base[k] = (const unsigned char *)v->pos, va->size[k] = 16, va->off[k++] = &m->off_pos;
    for (int a = 0; a < QGL__NATTR; a++)
        if (v->mask & (1u << a))
            va->base[k] = (const unsigned char *)v->attr[a], va->size[k] = 4 * (size_t)qgl__attribs[a].floats,
            va->off[k++] = &m->off[a];
    if (v->mask & QGL__A_EDGE)
        va->base[k] = v->edge, va->size[k] = 1, va->off[k++] = &m->off_edge;
    va->n = k;
}

/* A vertex's bucket, from its position alone: vertices that differ only elsewhere (a cube's
 * corner with three normals) share it, and same_vertex tells them apart. */
static size_t vertex_bucket(const float *pos, size_t mask)
{
    uint32_t w[4];
    memcpy(w, pos, sizeof w);
    uint64_t h = w[0] * 0x9e3779b97f4a7c15u ^ w[1] * 0xc2b2ae3d27d4eb4fu ^ w[2] * 0x165667b19e3779f9u ^
                 w[3] * 0x27d4eb2f165667c5u;
    return (size_t)(h ^ h >> 29) & mask;
}

static int same_vertex(const vertex_arrays *va, size_t i, size_t j)
{
    for (int k = 0; k < va->n; k++)
        if (memcmp(va->base[k] + i * va->size[k], va->base[k] + j * va->size[k], va->size[k]) != 0)
            return 0;
    return 1;
}

/* Where each vertex goes in the mesh's buffer (at[i]) and which vertex each place holds
 * (order[k]); returns the places used. Primitives drawn as arrays keep their vertices in
 * runs. GL_QUADS ones are drawn by index, and of their vertices with equal data (a sphere's or
 * a grid's quads repeat each corner up to four times) one place serves all: the driver, whose
 * vertex cache is keyed by index, then transforms and lights a shared corner once instead of
 * once per quad, as its own display lists do after merging equal vertices. slot: cap zeroed
 * entries (a power of two above the GL_QUADS vertices). */
static size_t place_vertices(const qgl__mesh *m, const vertex_arrays *va, uint32_t *at, uint32_t *order,
                             uint32_t *slot, size_t cap)
{
    size_t k = 0;
    for (size_t p = 0; p < m->nprim; p++) {
        const qgl__mesh_prim *pr = &m->prim[p];
        size_t end = pr->first + (pr->mode == GL_QUADS ? pr->count / 4 * 4 : pr->count);
        for (size_t i = pr->first; i < end; i++) {
            if (pr->mode == GL_QUADS)
                for (size_t s = vertex_bucket(m->v.pos + 4 * i, cap - 1);; s = (s + 1) & (cap - 1)) {
                    if (!slot[s]) {
                        slot[s] = (uint32_t)i + 1;
                        break;
                    }
                    if (same_vertex(va, i, slot[s] - 1)) {
                        at[i] = at[slot[s] - 1];
                        goto placed;
                    }
                }
            at[i] = (uint32_t)k;
            order[k++] = (uint32_t)i;
        placed:;
        }
    }
    return k;
}

/* The vertices in the mesh's own buffer (made, or refilled when they changed): each array's
 * places (place_vertices), then the GL_QUADS primitives' indices; 0 when the buffer belongs
 * to another share group or the driver refused. */
static int resident(qgl_context *ctx, qgl__mesh *m, const void *owner)
{
    struct qgl__gl *gl = &ctx->gl;
    if (m->bo && m->owner != owner)
        return 0;
    if (m->bo && !m->stale)
        return 1;
    size_t n = m->v.n, nidx = 0, cap = 16;
    for (size_t i = 0; i < m->nprim; i++)
        nidx += m->prim[i].mode == GL_QUADS ? m->prim[i].count / 4 * 4 : 0;
    while (cap < 2 * nidx)
        cap *= 2;
    vertex_arrays va;
    arrays_of(m, &va);
    uint32_t *at = malloc((n ? n : 1) * sizeof *at), *order = malloc((n ? n : 1) * sizeof *order);
    uint32_t *slot = calloc(cap, sizeof *slot);
    unsigned char *data = NULL;
    size_t places = at && order && slot ? place_vertices(m, &va, at, order, slot, cap) : 0, total = 0;
    for (int k = 0; k < va.n; k++)
        total += (places * va.size[k] + 15) & ~(size_t)15;
    if (at && order && slot)
        data = malloc(total + nidx * sizeof(uint32_t) + 1);
    if (!data) {
        free(at), free(order), free(slot);
        return 0;
    }
    size_t off = 0;
    for (int k = 0; k < va.n; k++) {
        for (size_t j = 0; j < places; j++)
            memcpy(data + off + j * va.size[k], va.base[k] + order[j] * va.size[k], va.size[k]);
        *va.off[k] = off;
        off += (places * va.size[k] + 15) & ~(size_t)15;
    }
    uint32_t *idx = (uint32_t *)(data + off);
    size_t q = 0;
    m->off_idx = off;
    for (size_t i = 0; i < m->nprim; i++) {
        qgl__mesh_prim *p = &m->prim[i];
        p->idx0 = (uint32_t)q;
        p->at = p->mode != GL_QUADS && p->count ? at[p->first] : 0;
        for (uint32_t c = p->first; p->mode == GL_QUADS && c < p->first + p->count / 4 * 4; c++)
            idx[q++] = at[c];
    }
    if (!m->bo) {
        gl->GenBuffers(1, &m->bo);
        m->owner = owner;
    }
    gl->BindBuffer(GL_ARRAY_BUFFER, m->bo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(off + nidx * sizeof *idx), data, GL_STATIC_DRAW);
    ctx->stats.uploads++;
    free(at), free(order), free(slot), free(data);
    m->stale = 0;
    return 1;
}

/* Our VAO's arrays at the mesh's buffer. */
static void point(qgl_context *ctx, const qgl__mesh *m)
{
    struct qgl__gl *gl = &ctx->gl;
    gl->BindVertexArray(ctx->vao);
    gl->BindBuffer(GL_ARRAY_BUFFER, m->bo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m->bo); /* our VAO's */
    qgl__point_arrays(ctx, m->v.mask, m->off_pos, m->off, m->off_edge);
    if (ctx->material_arrays)
        for (GLuint k = 0; k < QGL__NMATERIAL; k++)
            gl->DisableVertexAttribArray(QGL__LOC_MATERIAL + k);
    ctx->material_arrays = 0;
}

/* Primitives [i0, i1), all the driver's as they are, in as few calls as their modes allow. */
static void draw_run(qgl_context *ctx, const qgl__mesh *m, size_t i0, size_t i1)
{
    while (i0 < i1) {
        size_t j = i0;
        GLenum mode = m->prim[i0].mode;
        while (j < i1 && m->prim[j].mode == mode)
            j++;
        if (mode == GL_QUADS) { /* consecutive, so are their indices */
            size_t n = (size_t)m->prim[j - 1].idx0 + m->prim[j - 1].count / 4 * 4 - m->prim[i0].idx0;
            ctx->gl.DrawElements(GL_QUADS, (GLsizei)n, GL_UNSIGNED_INT,
                                 (const void *)(uintptr_t)(m->off_idx + 4 * (size_t)m->prim[i0].idx0));
            ctx->stats.draws++;
            i0 = j;
            continue;
        }
        if (!grow((void **)&ctx->multi_first, &ctx->multi_cap, j - i0, sizeof *ctx->multi_first) ||
            !grow((void **)&ctx->multi_count, &ctx->multi_cap2, j - i0, sizeof *ctx->multi_count))
            return;
        for (size_t k = i0; k < j; k++) {
            ctx->multi_first[k - i0] = (GLint)m->prim[k].at;
            ctx->multi_count[k - i0] = (GLsizei)m->prim[k].count;
        }
        if (j - i0 == 1 || !ctx->gl.MultiDrawArrays)
            for (size_t k = 0; k < j - i0; k++)
                ctx->gl.DrawArrays(mode, ctx->multi_first[k], ctx->multi_count[k]);
        else
            ctx->gl.MultiDrawArrays(mode, ctx->multi_first, ctx->multi_count, (GLsizei)(j - i0));
        ctx->stats.draws++;
        i0 = j;
    }
}

/* How primitive i is drawn now: 0 by the driver as it is, 1 through the planner, 2 replayed
 * (materials inside). */
static int prim_way(qgl_context *ctx, const qgl__state *st, const qgl__mesh *m, size_t i, int *quad_path)
{
    const qgl__mesh_prim *p = &m->prim[i];
    if (p->nchg)
        return 2;
    if (!is_quads(p->mode))
        return 0;
    int path = qgl__native_path(ctx, st, m->pfacts[i]);
    if (path < 0)
        return 1;
    *quad_path = path;
    return 0;
}

/* Whether primitive i may join a group the planner draws as one batch. */
static int groups(const qgl__mesh *m, size_t i, int way)
{
    return way == 1 && !m->prim[i].nchg;
}

/* Primitives [i0, i1) (all, or with ways those it marks to group: quads the planner draws,
 * no materials inside) as one GL_QUADS batch with their facts: one plan, one upload and a draw
 * per run of one path, where a primitive at a time took a draw each (a lathed chess piece is
 * hundreds of strips). A strip's quads keep the diagonal the driver splits them on, or under
 * flat shading their provoking vertex. 0 without memory. */
static int draw_group(qgl_context *ctx, const qgl__state *st, qgl__mesh *m, size_t i0, size_t i1,
                      const unsigned char *ways)
{
    size_t nq = 0, n = 0;
    for (size_t i = i0; i < i1; i++)
        if (!ways || groups(m, i, ways[i]))
            nq += qgl__nquads(topology(m->prim[i].mode), m->prim[i].count);
    qgl__verts *u = &ctx->unrolled;
    if (!qgl__verts_reserve(u, 4 * nq, m->v.mask & ~(unsigned)QGL__A_MATERIAL) ||
        !grow((void **)&ctx->unrolled_facts, &ctx->unrolled_facts_cap, nq, sizeof *ctx->unrolled_facts))
        return 0;
    u->mask = m->v.mask & ~(unsigned)QGL__A_MATERIAL;
    int shift = st->shade_model == GL_FLAT && qgl__flat_corner(ctx, st, QGL_QUAD_STRIP) == 2 ? 3 : 0;
    unsigned all = 0xffffu;
    for (size_t i = i0; i < i1; i++) {
        const qgl__mesh_prim *p = &m->prim[i];
        if (ways && !groups(m, i, ways[i]))
            continue;
        size_t k = qgl__nquads(topology(p->mode), p->count);
        qgl__verts w = view(&m->v, p->first, p->count);
        if (p->mode == GL_QUADS)
            qgl__verts_copy_range(u, n, &w, 0, 4 * k);
        else
            qgl__verts_unroll(u, n, &w, 0, k, shift);
        memcpy(ctx->unrolled_facts + n / 4, m->facts + p->facts0, k * sizeof *m->facts);
        all &= m->pfacts[i];
        n += 4 * k;
    }
    u->n = n;
    qgl__facts f = {ctx->unrolled_facts, (uint16_t)all, NULL, NULL};
    qgl__draw_batch(ctx, u, QGL_QUADS, &f, QGL__DRAW_IMMEDIATE | QGL__DRAW_ARRAYS, NULL, 0);
    return 1;
}

/* The quads of native primitive i counted on the path the state gives them. */
static int count_native(qgl_context *ctx, const qgl__mesh *m, size_t i, int path)
{
    if (!is_quads(m->prim[i].mode))
        return 0;
    size_t nq = qgl__nquads(topology(m->prim[i].mode), m->prim[i].count);
    ctx->stats.quads += nq;
    qgl__count_path(ctx, (unsigned char)path, nq);
    return (int)nq;
}

/* Primitive i through the planner, or (materials inside, not quads) replayed; its quads. */
static int draw_one(qgl_context *ctx, qgl__mesh *m, size_t i, int way)
{
    const qgl__mesh_prim *p = &m->prim[i];
    qgl__verts w = view(&m->v, p->first, p->count);
    qgl__facts f = {m->facts + p->facts0, m->pfacts[i], NULL, NULL};
    int k = 0;
    for (size_t c = 0; c < p->nchg; c++)
        m->chg[p->chg0 + c].vertex -= p->first;
    if (way == 1 || is_quads(p->mode))
        k = qgl__draw_batch(ctx, &w, topology(p->mode), &f, QGL__DRAW_IMMEDIATE | QGL__DRAW_LIST, m->chg + p->chg0,
                            p->nchg);
    else
        qgl__replay_prim(ctx, p->mode, &w, m->chg + p->chg0, p->nchg);
    for (size_t c = 0; c < p->nchg; c++)
        m->chg[p->chg0 + c].vertex += p->first;
    return k > 0 ? k : 0;
}

/* The primitives the driver draws as they are, in order: runs between the others. */
static int draw_in_order(qgl_context *ctx, const qgl__state *st, qgl__mesh *m, const void *owner, int *touched)
{
    int quads = 0, pointed = 0, path = QGL__P_SPLIT;
    size_t run = 0;
    for (size_t i = 0; i <= m->nprim; i++) {
        int way = i < m->nprim ? prim_way(ctx, st, m, i, &path) : 3;
        if (way == 0) {
            quads += count_native(ctx, m, i, path);
            continue;
        }
        if (run < i) {
            if (!pointed && !resident(ctx, m, owner))
                break;
            if (!pointed)
                point(ctx, m), pointed = 1;
            draw_run(ctx, m, run, i);
            *touched = 1;
        }
        run = i + 1;
        if (way == 3)
            break;
        size_t j = i + 1;
        while (j < m->nprim && groups(m, i, way) && groups(m, j, prim_way(ctx, st, m, j, &path)))
            j++;
        if (j > i + 1 && draw_group(ctx, st, m, i, j, NULL)) {
            for (size_t k = i; k < j; k++)
                quads += (int)qgl__nquads(topology(m->prim[k].mode), m->prim[k].count);
            run = j;
            i = j - 1;
        } else {
            quads += draw_one(ctx, m, i, way);
        }
        pointed = 0; /* the planner draws through the same VAO from the stream buffer */
    }
    return quads;
}

/* Native primitives (ways[i] == 0) of one mode in one multi-draw. */
static int draw_mode(qgl_context *ctx, const qgl__mesh *m, GLenum mode)
{
    size_t n = 0;
    for (size_t i = 0; i < m->nprim; i++)
        n += !ctx->ways[i] && m->prim[i].mode == mode;
    if (!n)
        return 0;
    if (!grow((void **)&ctx->multi_first, &ctx->multi_cap, n, sizeof *ctx->multi_first) ||
        !grow((void **)&ctx->multi_count, &ctx->multi_cap2, n, sizeof *ctx->multi_count) ||
        !grow((void **)&ctx->multi_offset, &ctx->multi_cap3, n, sizeof *ctx->multi_offset))
        return -1;
    n = 0;
    for (size_t i = 0; i < m->nprim; i++) {
        const qgl__mesh_prim *p = &m->prim[i];
        if (ctx->ways[i] || p->mode != mode)
            continue;
        ctx->multi_first[n] = (GLint)p->at;
        ctx->multi_count[n] = (GLsizei)(mode == GL_QUADS ? p->count / 4 * 4 : p->count);
        ctx->multi_offset[n++] = (const void *)(uintptr_t)(m->off_idx + 4 * (size_t)p->idx0);
    }
    if (mode == GL_QUADS)
        ctx->gl.MultiDrawElements(GL_QUADS, ctx->multi_count, GL_UNSIGNED_INT, ctx->multi_offset, (GLsizei)n);
    else
        ctx->gl.MultiDrawArrays(mode, ctx->multi_first, ctx->multi_count, (GLsizei)n);
    ctx->stats.draws++;
    return 1;
}

/* Where drawing order cannot show (qgl__state.order_free), by kind: the primitives the driver
 * draws as they are, a multi-draw per mode; then every quad primitive the planner draws, as
 * one group; then those with materials inside, one by one. -1: drawn in order instead. */
static int draw_by_kind(qgl_context *ctx, const qgl__state *st, qgl__mesh *m, const void *owner, int *touched)
{
    int quads = 0, natives = 0, grouped = 0, path = QGL__P_SPLIT;
    if (!ctx->gl.MultiDrawArrays || !ctx->gl.MultiDrawElements ||
        !grow((void **)&ctx->ways, &ctx->ways_cap, m->nprim, 1))
        return -1;
    for (size_t i = 0; i < m->nprim; i++) {
        int way = prim_way(ctx, st, m, i, &path);
        ctx->ways[i] = (unsigned char)way;
        natives += way == 0;
        grouped += groups(m, i, way);
        if (way == 0)
            quads += count_native(ctx, m, i, path);
    }
    if (natives) {
        if (!resident(ctx, m, owner))
            return quads;
        point(ctx, m);
        *touched = 1;
        for (GLenum mode = GL_POINTS; mode <= GL_TRIANGLE_STRIP_ADJACENCY; mode++)
            draw_mode(ctx, m, mode);
    }
    if (grouped > 1 && draw_group(ctx, st, m, 0, m->nprim, ctx->ways)) {
        for (size_t i = 0; i < m->nprim; i++)
            if (groups(m, i, ctx->ways[i]))
                quads += (int)qgl__nquads(topology(m->prim[i].mode), m->prim[i].count);
        grouped = -1;
    }
    for (size_t i = 0; i < m->nprim; i++)
        if (ctx->ways[i] && !(grouped < 0 && groups(m, i, ctx->ways[i])))
            quads += draw_one(ctx, m, i, ctx->ways[i]);
    return quads;
}

int qgl__mesh_draw(qgl_context *ctx, qgl__mesh *m, const void *owner)
{
    if (!ctx->has_vao || m->generic || !m->nprim)
        return m->nprim ? -1 : 0;
    qgl__state st;
    qgl__query_state(ctx, &st);
    int touched = 0, quads = -1;
    GLint app_vao = st.vao, app_buffer = st.array_buffer, app_client = st.client_texture;
    if (st.order_free && m->nprim > 1)
        quads = draw_by_kind(ctx, &st, m, owner, &touched);
    if (quads < 0)
        quads = draw_in_order(ctx, &st, m, owner, &touched);
    if (touched) {
        ctx->gl.BindVertexArray((GLuint)app_vao);
        ctx->gl.BindBuffer(GL_ARRAY_BUFFER, (GLuint)app_buffer);
        ctx->gl.ClientActiveTexture((GLenum)app_client);
    }
    return quads;
}
