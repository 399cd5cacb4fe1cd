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

/* Element i of a into dst[0..dim), components past a->size set from def. */
static void fetch(const qgl_attrib *a, size_t i, float *dst, int dim, const float def[4])
{
    size_t es = type_size(a->type);
    size_t stride = a->stride ? (size_t)a->stride : es * (size_t)a->size;
    const unsigned char *p = (const unsigned char *)a->ptr + i * stride;
    for (int k = 0; k < dim; k++) {
        if (k >= a->size) {
            dst[k] = def[k];
        } else if (a->type == GL_DOUBLE) {
            double d;
            memcpy(&d, p + 8 * (size_t)k, 8);
            dst[k] = (float)d;
        } else if (a->type == GL_UNSIGNED_BYTE) {
            dst[k] = p[k] / 255.0f;
        } else {
            memcpy(&dst[k], p + 4 * (size_t)k, 4);
        }
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

static unsigned batch_mask(const qgl_quad_batch *b)
{
    unsigned m = 0;
    m |= b->color.size ? QGL__A_COLOR : 0;
    m |= b->normal.size ? QGL__A_NORMAL : 0;
    m |= b->secondary_color.size ? QGL__A_COLOR2 : 0;
    m |= b->fog_coord.size ? QGL__A_FOG : 0;
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
        m |= b->texcoord[u].size ? (unsigned)QGL__A_TEX0 << u : 0;
    return m;
}

static void convert(const qgl_quad_batch *b, qgl__verts *v)
{
    static const float def[4] = {0, 0, 0, 1};
    for (size_t i = 0; i < v->n; i++) {
        size_t s = b->indices ? b->indices[i] : i;
        fetch(&b->position, s, v->pos + 4 * i, 4, def);
        if (v->mask & QGL__A_COLOR)
            fetch(&b->color, s, v->col + 4 * i, 4, def);
        if (v->mask & QGL__A_NORMAL)
            fetch(&b->normal, s, v->nrm + 3 * i, 3, def);
        if (v->mask & QGL__A_COLOR2)
            fetch(&b->secondary_color, s, v->col2 + 3 * i, 3, def);
        if (v->mask & QGL__A_FOG)
            fetch(&b->fog_coord, s, v->fog + i, 1, def);
        for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
            if (v->mask & (QGL__A_TEX0 << u))
                fetch(&b->texcoord[u], s, v->tex[u] + 4 * i, 4, def);
    }
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
