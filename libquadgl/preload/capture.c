/* capture.c: glBegin/glEnd with GL_QUADS and GL_QUAD_STRIP, and every call legal between them.
 *
 * A captured glBegin is not passed to the driver: the vertices collect in the context's
 * pl_prim, one array per attribute in the GL path's layout (qgl__verts), and are drawn at
 * glEnd (draw.c), or recorded when a display list is being compiled (lists.c). Each attribute
 * call sets the prim's value for the next vertex; glVertex appends one. The first time an
 * attribute is given after some vertices, those earlier vertices take the value GL had at
 * glBegin: outside a list it is known now (our copy of the current attributes, or the driver,
 * which has not seen the glBegin), inside a list it is read when the list runs. Edge flags and
 * generic attributes (glVertexAttrib) are captured the same way, for the driver's own drawing
 * of the primitive: edge flags matter in polygon mode line, generic attributes to a program.
 * Immediate primitives are drawn in chunks of whole quads, so memory stays bounded however
 * many vertices one glBegin/glEnd holds. A glBegin(GL_QUADS) outside a list whose quads may
 * wait in the pending batch (draw.c) is captured straight into the batch's arrays, as Mesa's
 * immediate mode writes into its vertex buffer: no arrays of its own, no copy at glEnd; the
 * values it gives go to the context's current ones, which the driver gets when the batch is
 * drawn or before anything can read them (pl_cur_sync). Whatever the batch does not carry
 * (materials, generic attributes, a list called inside, a full batch) sends it back to arrays
 * of its own first (pl_prim_settle). Misuse keeps the driver's errors: a call GL forbids
 * inside glBegin/glEnd (another glBegin, a state change, a query) makes the driver report
 * GL_INVALID_OPERATION through a glEnd it sees with no glBegin, and has no other effect; a
 * glEnd with no glBegin is the driver's own; vertices outside go to the driver. A display
 * list called inside the primitive runs its calls there, and only the driver can run the
 * calls of its segments (lists.c) in a primitive, legal ones and errors alike: the driver then
 * takes over the primitive (pl_cap_to_driver: glBegin and the vertices so far), and the rest
 * reaches it as the program's calls. So does a primitive a list leaves open at glEndList
 * (legal under GL_COMPILE): its calls are compiled into the list as they came. */
#include "preload.h"

#include <stdlib.h>
#include <string.h>

/* Vertices per immediate-mode chunk (a multiple of 4; a strip keeps its last two). */
#define PL_CHUNK 16384

void pl_prim_reset(pl_prim *p, GLenum mode)
{
    p->mode = mode;
    p->v.n = 0;
    p->v.mask = 0;
    p->generic_given = 0;
    p->nmat = 0;
    p->lost = 0;
    p->from_arrays = 0;
    p->in_list = 0;
    p->mat_inert = -1;
    p->direct = 0;
    memset(p->first, 0, sizeof p->first);
    p->cur_edge = GL_TRUE;
}

void pl_prim_free(pl_prim *p)
{
    qgl__verts_free(&p->v);
    for (int g = 0; g < PL_GENERICS; g++)
        free(p->generic[g]);
    free(p->mat);
    memset(p, 0, sizeof *p);
}

/* Room for n vertices in every array the prim uses (mask, and the generic ones). */
static int pl_prim_reserve(pl_prim *p, size_t n, unsigned mask)
{
    size_t old = p->v.cap;
    if (!qgl__verts_reserve(&p->v, n, mask))
        return -1;
    for (unsigned m = p->generic_given; m; m &= m - 1) { /* the indices given: mostly none */
        int g = __builtin_ctz(m);
        if (!p->generic[g] || p->v.cap != old) {
            float *grown = realloc(p->generic[g], p->v.cap * 4 * sizeof(float));
            if (!grown)
                return -1;
            p->generic[g] = grown;
        }
    }
    return 0;
}

int pl_prim_copy(pl_prim *dst, const pl_prim *src)
{
    size_t n = src->v.n;
    *dst = *src;
    memset(&dst->v, 0, sizeof dst->v);
    memset(dst->generic, 0, sizeof dst->generic);
    dst->mat = NULL;
    dst->capmat = src->nmat;
    if (pl_prim_reserve(dst, n ? n : 1, src->v.mask) != 0 ||
        (src->nmat && !(dst->mat = malloc(src->nmat * sizeof *dst->mat)))) {
        pl_prim_free(dst);
        return -1;
    }
    dst->v.mask = src->v.mask;
    dst->v.n = n;
    for (size_t i = 0; i < n; i++)
        qgl__verts_copy(&dst->v, i, &src->v, i);
    for (int g = 0; g < PL_GENERICS; g++)
        if (src->generic_given & (1u << g))
            memcpy(dst->generic[g], src->generic[g], n * 4 * sizeof(float));
    if (src->nmat)
        memcpy(dst->mat, src->mat, src->nmat * sizeof *dst->mat);
    return 0;
}

size_t pl_prim_quads(const pl_prim *p)
{
    return qgl__nquads(p->mode == GL_QUADS ? QGL_QUADS : QGL_QUAD_STRIP, p->v.n);
}

/* ---- attributes ------------------------------------------------------------------------------- */

void pl_verts_fill(qgl__verts *v, int a, size_t from, size_t to, const float *val, unsigned char edge)
{
    if (a == QGL__NATTR) {
        if (to > from)
            memset(v->edge + from, edge, to - from);
        return;
    }
    int k = qgl__attribs[a].floats;
    for (size_t i = from; i < to; i++)
        memcpy(v->attr[a] + (size_t)k * i, val, (size_t)k * sizeof(float));
}

void pl_fill_current(pl_ctx *x, qgl__verts *v, int a, size_t from, size_t to)
{
    float value[4] = {0, 0, 0, 1};
    if (a < QGL__NATTR)
        pl_current_value(x, a, value);
    pl_verts_fill(v, a, from, to, value, a == QGL__NATTR ? pl_current_edge(x) : 0);
}

static void pl_fill_generic(pl_prim *p, int g, size_t end)
{
    float value[4] = {0, 0, 0, 1};
    REAL(glGetVertexAttribfv)((GLuint)g, GL_CURRENT_VERTEX_ATTRIB, value);
    for (size_t i = 0; i < end; i++)
        memcpy(p->generic[g] + 4 * i, value, sizeof value);
}

void pl_prim_backfill(pl_ctx *x, pl_prim *p)
{
    size_t n = p->v.n;
    for (int a = 0; a <= QGL__NATTR; a++) {
        unsigned bit = a == QGL__NATTR ? QGL__A_EDGE : 1u << a;
        if ((p->v.mask & bit) && p->first[a] > 0)
            pl_fill_current(x, &p->v, a, 0, p->first[a] < n ? p->first[a] : n);
    }
    for (unsigned m = p->generic_given; m; m &= m - 1) {
        int g = __builtin_ctz(m);
        if (p->generic_first[g] > 0)
            pl_fill_generic(p, g, p->generic_first[g] < n ? p->generic_first[g] : n);
    }
}

/* Attribute slot a is given from the next vertex on: its array joins the prim. Outside a list
 * the earlier vertices' value is known now and will not change. */
static int pl_given(pl_ctx *x, int a)
{
    pl_prim *p = &x->prim;
    unsigned bit = a == QGL__NATTR ? QGL__A_EDGE : 1u << a;
    if (PL_LIKELY(p->v.mask & bit))
        return 0;
    if (p->direct) {
        /* the batch's vertices so far, this primitive's among them, were made with the value
         * current now */
        qgl__verts *b = &x->batch.v;
        size_t n = p->base + p->v.n;
        if (!(b->mask & bit) && qgl__verts_reserve(b, n ? n : 1, b->mask | bit)) {
            pl_fill_current(x, b, a, 0, n);
            b->mask |= bit;
        }
        if (b->mask & bit) {
            p->v.mask |= bit;
            return 0;
        }
        pl_prim_settle(x);
    }
    if (pl_prim_reserve(p, p->v.n ? p->v.n : 1, p->v.mask | bit) != 0) {
        p->lost = 1;
        return -1;
    }
    p->v.mask |= bit;
    p->first[a] = (uint32_t)p->v.n;
    if (p->v.n && !x->compiling) {
        pl_fill_current(x, &p->v, a, 0, p->v.n);
        p->first[a] = 0;
    }
    return 0;
}

void pl_cap_attrib(pl_ctx *x, int a, float s, float t, float r, float q)
{
    if (pl_given(x, a) != 0)
        return;
    float *c = x->prim.direct ? x->cur[a] : x->prim.cur[a];
    c[0] = s, c[1] = t, c[2] = r, c[3] = q;
    if (x->prim.direct)
        x->cur_known |= 1u << a;
}

void pl_cap_texcoord(pl_ctx *x, GLenum unit, float s, float t, float r, float q)
{
    if (unit >= PL_TEXUNITS) {
        /* Beyond the units a batch carries: the driver draws the primitive, with the last
         * coordinates given for this unit on every vertex. */
        x->prim.lost = 1;
        REAL(glMultiTexCoord4f)(GL_TEXTURE0 + unit, s, t, r, q);
        return;
    }
    pl_cap_attrib(x, QGL__AT_TEX0 + (int)unit, s, t, r, q);
}

void pl_cap_edgeflag(pl_ctx *x, GLboolean flag)
{
    if (pl_given(x, QGL__NATTR) != 0)
        return;
    if (x->prim.direct) {
        x->cur_edge = flag ? GL_TRUE : GL_FALSE;
        x->cur_known |= QGL__A_EDGE;
    } else {
        x->prim.cur_edge = flag ? GL_TRUE : GL_FALSE;
    }
}

int pl_hook_edgeflag(pl_ctx *x, GLboolean flag)
{
    if (x->capturing) {
        pl_cap_edgeflag(x, flag);
        return 1;
    }
    if (x->batch.v.n && !(x->batch.v.mask & QGL__A_EDGE))
        pl_batch_keep(x, QGL__NATTR);
    if (x->compiling) {
        const float v[4] = {flag ? 1.0f : 0.0f, 0, 0, 0};
        pl_list_attrib(x, QGL__NATTR, v);
        if (x->compile_mode == GL_COMPILE)
            return 1;
    }
    if (!x->compiling || x->compile_mode == GL_COMPILE_AND_EXECUTE) {
        x->cur_edge = flag ? GL_TRUE : GL_FALSE;
        x->cur_known |= QGL__A_EDGE;
        x->cur_lazy &= ~QGL__A_EDGE;
    }
    return 0;
}

void pl_cap_generic(pl_ctx *x, GLuint index, float s, float t, float r, float q)
{
    pl_prim *p = &x->prim;
    if (index == 0) { /* generic attribute 0 is the vertex position */
        pl_cap_vertex(x, s, t, r, q);
        return;
    }
    if (index >= PL_GENERICS) {
        p->lost = 1;
        return;
    }
    if (!(p->generic_given & (1u << index))) {
        pl_prim_settle(x); /* a batch carries no generic attributes */
        p->generic_given |= 1u << index;
        if (pl_prim_reserve(p, p->v.n ? p->v.n : 1, p->v.mask) != 0) {
            p->generic_given &= ~(1u << index);
            p->lost = 1;
            return;
        }
        p->generic_first[index] = (uint32_t)p->v.n;
        if (p->v.n && !x->compiling) {
            pl_fill_generic(p, (int)index, p->v.n);
            p->generic_first[index] = 0;
        }
    }
    float *c = p->cur_generic[index];
    c[0] = s, c[1] = t, c[2] = r, c[3] = q;
}

int pl_hook_generic(pl_ctx *x, GLuint index, float s, float t, float r, float q)
{
    if (!x->capturing) {
        pl_batch_flush(x);
        if (x->compiling)
            pl_list_state(x);
        return 0;
    }
    pl_cap_generic(x, index, s, t, r, q);
    return 1;
}

static int pl_material_count(GLenum pname)
{
    switch (pname) {
    case GL_AMBIENT: case GL_DIFFUSE: case GL_SPECULAR: case GL_EMISSION: case GL_AMBIENT_AND_DIFFUSE:
        return 4;
    case GL_SHININESS: return 1;
    case GL_COLOR_INDEXES: return 3;
    default: return 0;
    }
}

static void pl_push_material(pl_ctx *x, GLenum face, GLenum pname, const float *v, int n)
{
    pl_prim *p = &x->prim;
    pl_material *m;
    if (p->nmat == p->capmat) {
        size_t cap = p->capmat ? p->capmat * 2 : 8;
        pl_material *grown = realloc(p->mat, cap * sizeof *grown);
        if (!grown)
            return;
        p->mat = grown;
        p->capmat = cap;
    }
    m = &p->mat[p->nmat++];
    memset(m, 0, sizeof *m);
    m->vertex = (uint32_t)p->v.n;
    m->face = face;
    m->pname = pname;
    memcpy(m->v, v, (size_t)n * sizeof *v);
}

/* Whether a material call changes no pixel of the quads drawn until lighting or colour material
 * is enabled, which draws the batch first: neither is on. The prim's own answer is kept, as
 * neither can change inside glBegin/glEnd. The driver must not be inside a glBegin of its own. */
static int pl_material_inert(pl_ctx *x)
{
    pl_prim *p = &x->prim;
    if (x->capturing && p->mat_inert >= 0)
        return p->mat_inert;
    int inert = !REAL(glIsEnabled)(GL_LIGHTING) && !REAL(glIsEnabled)(GL_COLOR_MATERIAL);
    if (x->capturing)
        p->mat_inert = (signed char)inert;
    return inert;
}

/* Integer colours map [-2^31, 2^31 - 1] onto [-1, 1]; shininess and indexes are plain. The
 * scalar forms give one value, which the driver takes unconverted for any parameter (what it
 * reads past it is undefined; here zeros). */
static const float *material_values(const GLfloat *fv, const GLint *iv, int n, int given, float v[4])
{
    for (int i = 0; i < n && i < given; i++)
        v[i] = fv ? fv[i] : (n == 4 && given == 4) ? PL_I(iv[i]) : (float)iv[i];
    return v;
}

int pl_hook_material(pl_ctx *x, GLenum face, GLenum pname, const GLfloat *fv, const GLint *iv, int given)
{
    float v[4] = {0, 0, 0, 0};
    int n = pl_material_count(pname);
    if (!x->capturing) {
        if (x->compiling) {
            pl_list_state(x);
            x->seg_dirty |= PL_D_LIGHT;
        }
        if (x->batch.v.n && (x->compiling || x->native_begin || !pl_material_inert(x)))
            pl_batch_flush(x);
        /* the planner lights corners with the driver's materials: a copy of the values, or
         * (inside a list, a form the driver may refuse) read again */
        if (x->compiling || !x->qgl || n == 0 || given != n || (!fv && !iv) ||
            !qgl__material_set(x->qgl, face, pname, material_values(fv, iv, n, given, v)))
            pl_mark(x, PL_D_LIGHT);
        return 0;
    }
    if (!x->compiling && pl_material_inert(x)) {
        pl_mark(x, PL_D_LIGHT);
        return 0; /* it shows in no vertex: the driver takes it now, in its order among materials */
    }
    if (n == 0 || (!fv && !iv))
        return 0; /* the driver's own error (it saw no glBegin: the same one) */
    pl_prim_settle(x); /* nor materials */
    pl_push_material(x, face, pname, material_values(fv, iv, n, given, v), n);
    return 1;
}

int pl_hook_array_element(pl_ctx *x, GLint i)
{
    if (x->capturing) {
        pl_cap_array_element(x, i);
        return 1;
    }
    pl_batch_flush(x);
    x->cur_known = 0; /* its attributes become the current ones */
    if (x->compiling) {
        pl_list_state(x);
        x->seg_dirty |= PL_D_CURRENT;
    }
    return 0;
}

/* ---- vertices and chunks ---------------------------------------------------------------------- */

/* Draws the whole quads collected so far and keeps what the next quad still needs. */
static void pl_flush_chunk(pl_ctx *x)
{
    pl_prim *p = &x->prim;
    size_t keep = p->mode == GL_QUAD_STRIP ? 2 : 0;
    size_t n = p->v.n;
    pl_draw_prim(x, p); /* applies the chunk's materials: they are not kept */
    for (size_t k = 0; k < keep; k++) {
        qgl__verts_copy(&p->v, k, &p->v, n - keep + k);
        for (int g = 0; g < PL_GENERICS; g++)
            if (p->generic_given & (1u << g))
                memcpy(p->generic[g] + 4 * k, p->generic[g] + 4 * (n - keep + k), 4 * sizeof(float));
    }
    p->v.n = keep;
    p->nmat = 0;
}

/* One vertex of the primitive: into the batch where it writes there (direct), else into its
 * own arrays, which a long primitive draws in chunks. */
void pl_cap_vertex(pl_ctx *x, float a, float b, float c, float d)
{
    pl_prim *p = &x->prim;
    const float pos[4] = {a, b, c, d};
    if (p->direct) {
        qgl__verts *bv = &x->batch.v;
        size_t j = p->base + p->v.n;
        if (PL_LIKELY(j < bv->cap) || (j < PL_BATCH_MAX && qgl__verts_reserve(bv, j + 1, bv->mask))) {
            if (PL_LIKELY(j < PL_BATCH_MAX)) {
                qgl__put_vertex(bv, j, (const float (*)[4])x->cur, x->cur_edge, bv->mask, pos);
                p->v.n++;
                return;
            }
        }
        pl_prim_settle(x); /* the batch is full: the primitive goes on in its own arrays */
    }
    size_t i = p->v.n;
    if (PL_UNLIKELY(i >= PL_CHUNK) && i % 4 == 0 && !x->compiling && !p->from_arrays) {
        pl_flush_chunk(x);
        i = p->v.n;
    }
    if (PL_UNLIKELY(i >= p->v.cap) && pl_prim_reserve(p, i + 1, p->v.mask) != 0) {
        p->lost = 1;
        return;
    }
    qgl__put_vertex(&p->v, i, (const float (*)[4])p->cur, p->cur_edge, p->v.mask, pos);
    for (unsigned g = p->generic_given; g; g &= g - 1) {
        int k = __builtin_ctz(g);
        memcpy(p->generic[k] + 4 * i, p->cur_generic[k], 4 * sizeof(float));
    }
    p->v.n = i + 1;
}

void pl_prim_settle(pl_ctx *x)
{
    pl_prim *p = &x->prim;
    const qgl__verts *b = &x->batch.v;
    size_t n = p->v.n;
    if (!p->direct)
        return;
    p->direct = 0;
    /* every attribute the batch carries was written with the vertices: given from the first */
    if (pl_prim_reserve(p, n ? n : 1, b->mask) != 0) {
        p->lost = 1;
        p->v.n = 0;
        return;
    }
    if (n) /* the batch may have no arrays yet */
        qgl__verts_copy_range(&p->v, 0, b, p->base, n);
    p->v.mask = b->mask;
    memset(p->first, 0, sizeof p->first);
    memcpy(p->cur, x->cur, sizeof p->cur); /* the values given so far, and the rest current */
    p->cur_edge = x->cur_edge;
}

/* ---- glBegin / glEnd ---------------------------------------------------------------------------- */

static int pl_valid_mode(GLenum mode)
{
    return mode <= GL_TRIANGLE_STRIP_ADJACENCY;
}

PL_EXPORT void glBegin(GLenum mode)
{
    pl_ctx *x = pl_tls_ctx;
    int quad = (mode == GL_QUADS || mode == GL_QUAD_STRIP);
    if (PL_UNLIKELY(!x) && quad && pl_cfg.capture)
        x = pl_current();
    if (!x || !pl_cfg.capture) {
        REAL(glBegin)(mode);
        return;
    }
    if (x->capturing) {
        pl_invalid_operation();
        return;
    }
    /* In a list every primitive is ours (the list's geometry); outside, only quads. */
    if ((!quad && !(x->compiling && pl_valid_mode(mode))) || x->native_begin) {
        pl_batch_flush(x);
        if (x->compiling && pl_valid_mode(mode))
            pl_list_begin_end(x, 1);
        else if (x->compiling)
            pl_list_state(x);
        if (pl_valid_mode(mode) && (!x->compiling || x->compile_mode == GL_COMPILE_AND_EXECUTE))
            x->native_begin = 1;
        REAL(glBegin)(mode);
        return;
    }
    pl_prim_reset(&x->prim, mode);
    if (mode == GL_QUADS && !x->compiling)
        pl_prim_direct(x);
    x->capturing = 1;
    pl_update_slow(x);
}

/* The current attributes after glEnd are the last ones the primitive gave (a list's geometry
 * keeps its own: lists.c). */
static void pl_note_prim_current(pl_ctx *x, const pl_prim *p)
{
    for (int a = 0; a < QGL__NATTR; a++)
        if (p->v.mask & (1u << a))
            pl_note_current(x, a, p->cur[a]);
    if ((p->v.mask & QGL__A_EDGE) && (!x->compiling || x->compile_mode == GL_COMPILE_AND_EXECUTE)) {
        x->cur_edge = p->cur_edge;
        x->cur_known |= QGL__A_EDGE;
    }
}

void pl_cap_to_driver(pl_ctx *x)
{
    pl_prim *p = &x->prim;
    pl_prim_settle(x);
    x->capturing = 0;
    pl_batch_flush(x); /* what came before goes first */
    pl_update_slow(x);
    if (x->compiling && x->compile_mode == GL_COMPILE_AND_EXECUTE)
        pl_list_defer(x);
    if (x->compiling)
        pl_list_begin_end(x, 1);
    pl_prim_to_driver(x, p);
    if (!x->compiling || x->compile_mode == GL_COMPILE_AND_EXECUTE) {
        x->native_begin = 1;
        pl_count_passthrough(pl_prim_quads(p));
        pl_note_prim_current(x, p);
    }
}

PL_EXPORT void glEnd(void)
{
    pl_ctx *x = pl_tls_ctx;
    if (!x || !x->capturing) {
        if (x && x->compiling)
            pl_list_begin_end(x, 0);
        if (x && (!x->compiling || x->compile_mode == GL_COMPILE_AND_EXECUTE))
            x->native_begin = 0;
        REAL(glEnd)();
        if (x && x->compiling)
            pl_list_end_prim(x);
        return;
    }
    x->capturing = 0;
    pl_update_slow(x);
    if (x->compiling) {
        pl_list_add_prim(x, &x->prim);
        if (x->compile_mode == GL_COMPILE_AND_EXECUTE) {
            if (x->prim.mode == GL_QUADS || x->prim.mode == GL_QUAD_STRIP)
                pl_draw_prim(x, &x->prim);
            else
                pl_prim_emit(x, &x->prim);
            pl_note_prim_current(x, &x->prim);
        }
        return;
    }
    if (x->prim.direct && !x->prim.lost) {
        PL_TIMED(pl_end_direct(x, &x->prim)); /* its values are the current ones already */
        return;
    }
    pl_prim_settle(x);
    PL_TIMED(pl_end_prim(x, &x->prim));
    pl_note_prim_current(x, &x->prim);
}
