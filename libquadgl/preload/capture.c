/* capture.c: glBegin/glEnd with GL_QUADS and GL_QUAD_STRIP, and every call legal between them.
 *
 * A captured glBegin is not passed to the driver: the vertices collect in the context's
 * pl_prim and are drawn at glEnd (draw.c), or recorded when a display list is being compiled
 * (lists.c). Each attribute call updates the prim's current vertex; glVertex appends it. The
 * first time an attribute is given after some vertices, those earlier vertices take the value
 * GL had at glBegin; outside a list that value is read right away (the driver has not seen
 * the glBegin, so glGet is legal), inside a list it is read when the list runs. Immediate
 * primitives are drawn in chunks of whole quads, so memory stays bounded however many
 * vertices one glBegin/glEnd holds. Misuse keeps the driver's errors: glBegin inside a
 * captured glBegin makes the driver report GL_INVALID_OPERATION (through a glEnd it sees with
 * no glBegin), a glEnd with no glBegin is the driver's own, vertices outside go to the driver. */
#include "preload.h"

#include <stdlib.h>
#include <string.h>

/* Vertices per immediate-mode chunk (a multiple of 4; a strip keeps its last two). */
#define PL_CHUNK 16384

void pl_prim_reset(pl_prim *p, GLenum mode)
{
    p->mode = mode;
    p->n = 0;
    p->given = 0;
    p->nmat = 0;
    p->edge_off = 0;
    p->lost = 0;
    p->from_arrays = 0;
    p->native_list = 0;
    p->retained = NULL;
    memset(p->first, 0, sizeof p->first);
    memset(&p->cur, 0, sizeof p->cur);
    p->cur.pos[3] = 1.0f;
}

void pl_prim_free(pl_prim *p)
{
    pl_retained_free(p->retained);
    free(p->v);
    free(p->mat);
    memset(p, 0, sizeof *p);
}

int pl_prim_copy(pl_prim *dst, const pl_prim *src)
{
    *dst = *src;
    dst->retained = NULL;
    dst->v = NULL;
    dst->mat = NULL;
    dst->cap = src->n;
    dst->capmat = src->nmat;
    if (src->n && !(dst->v = malloc(src->n * sizeof *dst->v)))
        return -1;
    if (src->nmat && !(dst->mat = malloc(src->nmat * sizeof *dst->mat))) {
        free(dst->v);
        dst->v = NULL;
        return -1;
    }
    if (src->n)
        memcpy(dst->v, src->v, src->n * sizeof *dst->v);
    if (src->nmat)
        memcpy(dst->mat, src->mat, src->nmat * sizeof *dst->mat);
    return 0;
}

static int pl_prim_grow(pl_prim *p)
{
    size_t cap = p->cap ? p->cap * 2 : 256;
    pl_vertex *v = realloc(p->v, cap * sizeof *v);
    if (!v)
        return -1;
    p->v = v;
    p->cap = cap;
    return 0;
}

int pl_prim_push(pl_prim *p)
{
    if (p->n == p->cap && pl_prim_grow(p) != 0)
        return -1;
    p->v[p->n++] = p->cur;
    return 0;
}

size_t pl_prim_quads(const pl_prim *p)
{
    if (p->mode == GL_QUADS)
        return p->n / 4;
    return p->n >= 4 ? (p->n - 2) / 2 : 0;
}

/* ---- attributes ------------------------------------------------------------------------------- */

float *pl_attr_ptr(pl_vertex *v, int a)
{
    switch (a) {
    case PL_A_COLOR: return v->color;
    case PL_A_SECONDARY: return v->secondary;
    case PL_A_NORMAL: return v->normal;
    case PL_A_FOG: return &v->fog;
    default: return v->tex[a - PL_A_TEX0];
    }
}

size_t pl_attr_size(int a)
{
    switch (a) {
    case PL_A_COLOR: return 4;
    case PL_A_SECONDARY: case PL_A_NORMAL: return 3;
    case PL_A_FOG: return 1;
    default: return 4;
    }
}

/* Reads the context's current value of attribute a (pl_attr_size(a) floats to out). */
void pl_read_current(int a, float *out)
{
    static const GLenum pnames[] = {GL_CURRENT_COLOR, GL_CURRENT_SECONDARY_COLOR, GL_CURRENT_NORMAL,
                                    GL_CURRENT_FOG_COORD};
    float value[4] = {0, 0, 0, 0};
    GLint active = 0;
    if (a < PL_A_TEX0) {
        REAL(glGetFloatv)(pnames[a], value);
    } else {
        /* The current texture coordinates are per active texture unit. */
        REAL(glGetIntegerv)(GL_ACTIVE_TEXTURE, &active);
        REAL(glActiveTexture)(GL_TEXTURE0 + (GLenum)(a - PL_A_TEX0));
        REAL(glGetFloatv)(GL_CURRENT_TEXTURE_COORDS, value);
        REAL(glActiveTexture)((GLenum)active);
    }
    memcpy(out, value, pl_attr_size(a) * sizeof *out);
}

void pl_prim_backfill(pl_prim *p, int a)
{
    float value[4];
    size_t end = p->first[a] < p->n ? p->first[a] : p->n;
    if (end == 0)
        return;
    pl_read_current(a, value);
    for (size_t i = 0; i < end; i++)
        memcpy(pl_attr_ptr(&p->v[i], a), value, pl_attr_size(a) * sizeof(float));
}

/* Notes that attribute a is given from the next vertex on. */
static inline void pl_given(pl_ctx *x, int a)
{
    pl_prim *p = &x->prim;
    if (PL_LIKELY(p->given & (1u << a)))
        return;
    p->given |= 1u << a;
    p->first[a] = (uint32_t)p->n;
    /* Outside a list the earlier vertices' value is known now and will not change. */
    if (p->n && !x->compiling) {
        pl_prim_backfill(p, a);
        p->first[a] = 0;
    }
}

void pl_cap_color(pl_ctx *x, float r, float g, float b, float a)
{
    float *c = x->prim.cur.color;
    pl_given(x, PL_A_COLOR);
    c[0] = r, c[1] = g, c[2] = b, c[3] = a;
}

void pl_cap_secondary(pl_ctx *x, float r, float g, float b)
{
    float *c = x->prim.cur.secondary;
    pl_given(x, PL_A_SECONDARY);
    c[0] = r, c[1] = g, c[2] = b;
}

void pl_cap_normal(pl_ctx *x, float a, float b, float c)
{
    float *n = x->prim.cur.normal;
    pl_given(x, PL_A_NORMAL);
    n[0] = a, n[1] = b, n[2] = c;
}

void pl_cap_texcoord(pl_ctx *x, GLenum unit, float s, float t, float r, float q)
{
    float *tc;
    if (unit >= PL_TEXUNITS) {
        /* Beyond the units a batch carries: the driver draws the primitive, with the last
         * coordinates given for this unit on every vertex. */
        x->prim.lost = 1;
        REAL(glMultiTexCoord4f)(GL_TEXTURE0 + unit, s, t, r, q);
        return;
    }
    pl_given(x, PL_A_TEX0 + (int)unit);
    tc = x->prim.cur.tex[unit];
    tc[0] = s, tc[1] = t, tc[2] = r, tc[3] = q;
}

void pl_cap_fog(pl_ctx *x, float f)
{
    pl_given(x, PL_A_FOG);
    x->prim.cur.fog = f;
}

void pl_cap_edgeflag(pl_ctx *x, GLboolean flag)
{
    if (!flag)
        x->prim.edge_off = 1;
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
    m->vertex = (uint32_t)p->n;
    m->face = face;
    m->pname = pname;
    memcpy(m->v, v, (size_t)n * sizeof *v);
}

void pl_cap_material(pl_ctx *x, GLenum face, GLenum pname, const GLfloat *params)
{
    int n = pl_material_count(pname);
    if (n == 0) {
        REAL(glMaterialfv)(face, pname, params); /* the driver's own error */
        return;
    }
    pl_push_material(x, face, pname, params, n);
}

void pl_cap_materiali(pl_ctx *x, GLenum face, GLenum pname, const GLint *params)
{
    float v[4] = {0, 0, 0, 0};
    int n = pl_material_count(pname);
    if (n == 0) {
        REAL(glMaterialiv)(face, pname, params);
        return;
    }
    /* Integer colours map [-2^31, 2^31 - 1] onto [-1, 1]; shininess and indexes are plain. */
    for (int i = 0; i < n; i++)
        v[i] = (n == 4) ? PL_I(params[i]) : (float)params[i];
    pl_push_material(x, face, pname, v, n);
}

/* ---- vertices and chunks ---------------------------------------------------------------------- */

/* Draws the whole quads collected so far and keeps what the next quad still needs. */
static void pl_flush_chunk(pl_ctx *x)
{
    pl_prim *p = &x->prim;
    size_t keep = p->mode == GL_QUAD_STRIP ? 2 : 0;
    size_t n = p->n;
    pl_draw_prim(x, p); /* applies the chunk's materials: they are not kept */
    memmove(p->v, p->v + n - keep, keep * sizeof *p->v);
    p->n = keep;
    p->nmat = 0;
}

void pl_cap_vertex(pl_ctx *x, float a, float b, float c, float d)
{
    pl_prim *p = &x->prim;
    float *pos = p->cur.pos;
    pos[0] = a, pos[1] = b, pos[2] = c, pos[3] = d;
    if (PL_UNLIKELY(p->n == p->cap) && p->n >= PL_CHUNK && !x->compiling && !p->from_arrays)
        pl_flush_chunk(x);
    if (pl_prim_push(p) != 0)
        p->lost = 1;
}

/* ---- glBegin / glEnd ---------------------------------------------------------------------------- */

/* GL_INVALID_OPERATION in the driver, as the native glBegin inside glBegin would give. */
static void pl_invalid_operation(void)
{
    REAL(glEnd)();
}

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
    if (!quad || x->native_begin) {
        if (!x->native_begin && pl_valid_mode(mode))
            x->native_begin = 1;
        REAL(glBegin)(mode);
        return;
    }
    if (x->compiling)
        pl_list_segment_close(x);
    pl_prim_reset(&x->prim, mode);
    x->capturing = 1;
}

PL_EXPORT void glEnd(void)
{
    pl_ctx *x = pl_tls_ctx;
    if (!x || !x->capturing) {
        if (x)
            x->native_begin = 0;
        REAL(glEnd)();
        return;
    }
    x->capturing = 0;
    if (x->compiling) {
        pl_list_record_prim(x, &x->prim);
        pl_list_native_begin(x);
        pl_prim_emit(&x->prim);
        pl_list_native_end(x);
        if (x->compile_mode == GL_COMPILE_AND_EXECUTE)
            pl_draw_prim(x, &x->prim);
        pl_list_segment_open(x);
        return;
    }
    pl_draw_prim(x, &x->prim);
}
