/* batch.c: qgl_draw_quads: arrays of quads (any stride, float/double/ubyte, optional 32-bit
 * indices) converted into the capture layout, then drawn like an immediate-mode primitive.
 *
 * Converting costs one pass over the vertices but gives every path the same input (float
 * arrays per attribute, 4-component positions and texture coordinates with GL's defaults for
 * missing components), so quads drawn through either entry point are planned and drawn alike. */
#include <string.h>

#include "gl_internal.h"

static int attrib_ok(const qgl_attrib *a, int min, int max, int allow_ubyte)
{
    if (!a->size)
        return 1;
    if (!a->ptr || a->size < min || a->size > max || a->stride < 0)
        return 0;
    return a->type == 0 || a->type == GL_FLOAT || a->type == GL_DOUBLE || (allow_ubyte && a->type == GL_UNSIGNED_BYTE);
}

static size_t type_size(unsigned type)
{
    return type == GL_DOUBLE ? 8 : type == GL_UNSIGNED_BYTE ? 1 : 4;
}

/* c / 255 as GL converts unsigned bytes, computed by the compiler: a division per component
 * costs more than the rest of the copy. */
#define U1(c) ((float)(c) / 255.0f)
#define U4(c) U1(c), U1((c) + 1), U1((c) + 2), U1((c) + 3)
#define U16(c) U4(c), U4((c) + 4), U4((c) + 8), U4((c) + 12)
#define U64(c) U16(c), U16((c) + 16), U16((c) + 32), U16((c) + 48)
static const float unorm[256] = {U64(0), U64(64), U64(128), U64(192)};

/* Attribute a of the n vertices (idx[i], or i) into dst, dim floats each, components past
 * a->size set from def. One loop per source type, so the per-vertex work is copies. */
static void convert_attrib(const qgl_attrib *a, const uint32_t *idx, size_t n, float *dst, int dim,
                           const float def[4])
{
    size_t es = type_size(a->type);
    size_t stride = a->stride ? (size_t)a->stride : es * (size_t)a->size;
    int size = a->size < dim ? a->size : dim;
    for (size_t i = 0; i < n; i++, dst += dim) {
        const unsigned char *p = (const unsigned char *)a->ptr + (idx ? idx[i] : i) * stride;
        if (a->type == GL_DOUBLE) {
            for (int k = 0; k < size; k++) {
                double d;
                memcpy(&d, p + 8 * (size_t)k, 8);
                dst[k] = (float)d;
            }
        } else if (a->type == GL_UNSIGNED_BYTE) {
            for (int k = 0; k < size; k++)
                dst[k] = unorm[p[k]];
        } else {
            for (int k = 0; k < size; k++) /* fixed-size copies, inlined (a call per vertex is not) */
                memcpy(&dst[k], p + 4 * (size_t)k, 4);
        }
        for (int k = size; k < dim; k++)
            dst[k] = def[k];
    }
}

static int batch_ok(const qgl_quad_batch *b)
{
    int ok = b->count >= 0 && (b->topology == QGL_QUADS || b->topology == QGL_QUAD_STRIP);
    ok = ok && b->position.size >= 2 && attrib_ok(&b->position, 2, 4, 0);
    ok = ok && attrib_ok(&b->color, 3, 4, 1) && attrib_ok(&b->normal, 3, 3, 0);
    ok = ok && attrib_ok(&b->secondary_color, 3, 3, 1) && attrib_ok(&b->fog_coord, 1, 1, 0);
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
        ok = ok && attrib_ok(&b->texcoord[u], 1, 4, 0);
    return ok;
}

/* The batch's array of attribute a (a row of QGL__ATTRIBS). */
static const qgl_attrib *batch_attrib(const qgl_quad_batch *b, int a)
{
    switch (a) {
    case QGL__AT_COLOR: return &b->color;
    case QGL__AT_NORMAL: return &b->normal;
    case QGL__AT_COLOR2: return &b->secondary_color;
    case QGL__AT_FOG: return &b->fog_coord;
    default: return &b->texcoord[qgl__attribs[a].unit];
    }
}

static unsigned batch_mask(const qgl_quad_batch *b)
{
    unsigned m = 0;
    for (int a = 0; a < QGL__NATTR; a++)
        m |= batch_attrib(b, a)->size ? 1u << a : 0;
    return m;
}

static void convert(const qgl_quad_batch *b, qgl__verts *v)
{
    static const float def[4] = {0, 0, 0, 1};
    const uint32_t *idx = b->indices;
    size_t n = v->n;
    convert_attrib(&b->position, idx, n, v->pos, 4, def);
    for (int a = 0; a < QGL__NATTR; a++)
        if (v->mask & (1u << a))
            convert_attrib(batch_attrib(b, a), idx, n, v->attr[a], qgl__attribs[a].floats, def);
}

int qgl__batch_to_verts(const qgl_quad_batch *b, qgl__verts *v)
{
    if (!b || !batch_ok(b))
        return 0;
    unsigned mask = batch_mask(b);
    if (!qgl__verts_reserve(v, (size_t)b->count, mask))
        return 0;
    v->n = (size_t)b->count;
    v->mask = mask;
    convert(b, v);
    return 1;
}

QGL_API int qgl_draw_quads(qgl_context *ctx, const qgl_quad_batch *b)
{
    if (!ctx || ctx->in_begin || !qgl__batch_to_verts(b, &ctx->cap))
        return -1;
    return qgl__submit(ctx, &ctx->cap, b->topology);
}
