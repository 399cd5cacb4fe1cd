/* arrays.c: quads drawn from vertex arrays (glDrawArrays, glDrawElements and their kin).
 *
 * The client-array state is read back from the driver at each quad draw (the GL layer's
 * qgl__arrays_read, the same reader qglArrayElement uses) rather than tracked call by call,
 * so glInterleavedArrays, glLockArraysEXT, glPushClientAttrib, VAOs and buffer objects are
 * all seen as the driver sees them. Each enabled fixed-function array (vertex, colour,
 * secondary colour, normal, fog coordinate, edge flag, texture units 0-3) is read with its
 * type and converted to floats as the driver converts it for that entry point; an array in a
 * buffer object is first copied back over the range of indices the draw uses. Indices (8, 16
 * or 32 bit, client memory or element buffer) are resolved on the CPU, so the result is a
 * plain primitive of vertices like one from glBegin/glEnd, drawn or recorded the same way.
 * State the capture does not model (generic attribute 0, a texture unit above 3, primitive
 * restart, an unknown type), and any draw the GL path would not take anyway, goes to the
 * driver as the program's own call. */
#include "preload.h"

#include <stdlib.h>
#include <string.h>

/* State the capture cannot represent: the driver draws the call itself. */
static int pl_arrays_unmodelled(void)
{
    GLint attrib0 = 0, units = 1, active = 0, bad = 0;
    REAL(glGetVertexAttribiv)(0, GL_VERTEX_ATTRIB_ARRAY_ENABLED, &attrib0);
    if (attrib0)
        return 1;
    REAL(glGetIntegerv)(GL_MAX_TEXTURE_COORDS, &units);
    if (units <= PL_TEXUNITS)
        return 0;
    REAL(glGetIntegerv)(GL_CLIENT_ACTIVE_TEXTURE, &active);
    for (GLint u = PL_TEXUNITS; u < units && !bad; u++) {
        REAL(glClientActiveTexture)(GL_TEXTURE0 + (GLenum)u);
        bad = REAL(glIsEnabled)(GL_TEXTURE_COORD_ARRAY);
    }
    REAL(glClientActiveTexture)((GLenum)active);
    return bad;
}

/* The enabled arrays with elements [lo, hi] in memory; -1 when the capture cannot take them. */
static int pl_arrays_query(qgl__arrays *s, size_t lo, size_t hi)
{
    GLint units = 1;
    memset(s, 0, sizeof *s);
    if (pl_arrays_unmodelled())
        return -1;
    REAL(glGetIntegerv)(GL_MAX_TEXTURE_COORDS, &units);
    if (!qgl__arrays_read(pl_gl(), 99, units, s) || !qgl__arrays_fetch(pl_gl(), s, lo, hi)) {
        qgl__arrays_free(s);
        return -1;
    }
    return 0;
}

/* Feeds element i through the capture: attributes, then the vertex; immediate: as
 * glArrayElement converts, else as a draw from arrays fetches. */
static void pl_arrays_element(pl_ctx *x, const qgl__arrays *s, size_t i, int immediate)
{
    float v[4];
    for (int a = 0; a < QGL__NATTR; a++)
        if (s->attr[a].size) {
            qgl__array_element(&s->attr[a], i, qgl__attribs[a].normalized, immediate, v);
            pl_cap_attrib(x, a, v[0], v[1], v[2], v[3]);
        }
    if (s->edge.size) {
        qgl__array_element(&s->edge, i, 0, immediate, v);
        pl_cap_edgeflag(x, v[0] != 0);
    }
    if (s->vertex.size) {
        qgl__array_element(&s->vertex, i, 0, immediate, v);
        pl_cap_vertex(x, v[0], v[1], v[2], v[3]);
    }
}

void pl_cap_array_element(pl_ctx *x, GLint i)
{
    qgl__arrays s;
    if (i < 0 || pl_arrays_query(&s, (size_t)i, (size_t)i) != 0) {
        REAL(glArrayElement)(i);
        return;
    }
    pl_arrays_element(x, &s, (size_t)i, 1);
    qgl__arrays_free(&s);
}

/* The draw's indices as 32-bit values, from memory or the element buffer; -1 on an unknown
 * type. */
static int pl_read_indices(GLenum type, const void *indices, GLsizei count, uint32_t **out)
{
    size_t isz = type == GL_UNSIGNED_BYTE ? 1 : type == GL_UNSIGNED_SHORT ? 2 : type == GL_UNSIGNED_INT ? 4 : 0;
    GLint ebo = 0;
    const unsigned char *src = indices;
    unsigned char *copy = NULL;
    uint32_t *idx;
    if (!isz)
        return -1;
    idx = malloc((size_t)count * sizeof *idx + 1);
    if (!idx)
        return -1;
    REAL(glGetIntegerv)(GL_ELEMENT_ARRAY_BUFFER_BINDING, &ebo);
    if (ebo) {
        copy = malloc((size_t)count * isz + 1);
        if (!copy) {
            free(idx);
            return -1;
        }
        REAL(glGetBufferSubData)(GL_ELEMENT_ARRAY_BUFFER, (GLintptr)(uintptr_t)indices,
                                 (GLsizeiptr)((size_t)count * isz), copy);
        src = copy;
    } else if (!src) {
        free(idx);
        return -1;
    }
    for (GLsizei k = 0; k < count; k++)
        idx[k] = isz == 1 ? src[k] : isz == 2 ? ((const uint16_t *)src)[k] : ((const uint32_t *)src)[k];
    free(copy);
    *out = idx;
    return 0;
}

int pl_arrays_capture(pl_ctx *x, pl_prim *p, GLenum mode, GLint first, GLsizei count, GLenum type,
                      const void *indices)
{
    qgl__arrays s;
    uint32_t *idx = NULL;
    size_t lo = (size_t)first, hi = (size_t)first + (size_t)count - 1;
    int rc = 0;
    if (count <= 0 || first < 0)
        return -1;
    if (type) {
        if (REAL(glIsEnabled)(GL_PRIMITIVE_RESTART) || pl_read_indices(type, indices, count, &idx) != 0)
            return -1;
        lo = hi = idx[0];
        for (GLsizei k = 1; k < count; k++) {
            lo = idx[k] < lo ? idx[k] : lo;
            hi = idx[k] > hi ? idx[k] : hi;
        }
    }
    if (pl_arrays_query(&s, lo, hi) != 0) {
        free(idx);
        return -1;
    }
    /* The capture functions write into x->prim; lend them p for the draw's vertices. */
    {
        pl_prim saved = x->prim;
        x->prim = *p;
        pl_prim_reset(&x->prim, mode);
        x->prim.from_arrays = 1;
        for (GLsizei k = 0; k < count; k++)
            pl_arrays_element(x, &s, idx ? idx[k] : (size_t)first + (size_t)k, 0);
        if (x->prim.lost)
            rc = -1;
        *p = x->prim;
        x->prim = saved;
    }
    qgl__arrays_free(&s);
    free(idx);
    return rc;
}

/* ---- the draw entry points ----------------------------------------------------------------- */

static int pl_quad_mode(GLenum mode)
{
    return mode == GL_QUADS || mode == GL_QUAD_STRIP;
}

/* A quad draw from arrays, captured and drawn or recorded; -1 leaves it to the driver. */
static int pl_array_draw(GLenum mode, GLint first, GLsizei count, GLenum type, const void *indices)
{
    pl_ctx *x = pl_tls_ctx;
    int rc;
    if (!x && pl_cfg.capture)
        x = pl_current();
    if (!x || !pl_cfg.capture || x->capturing || x->native_begin)
        return -1;
    rc = pl_arrays_capture(x, &x->scratch, mode, first, count, type, indices);
    if (rc != 0 && x->compiling)
        pl_list_state(x); /* the driver compiles the call */
    if (rc == 0 && x->compiling) {
        pl_list_add_prim(x, &x->scratch);
        if (x->compile_mode == GL_COMPILE_AND_EXECUTE)
            pl_draw_prim(x, &x->scratch);
    } else if (rc == 0 && pl_prim_for_driver(x, &x->scratch)) {
        /* The driver's own call draws exactly what it always drew. */
        pl_count_passthrough(pl_prim_quads(&x->scratch));
        rc = -1;
    } else if (rc == 0) {
        PL_TIMED(pl_end_prim(x, &x->scratch));
    }
    return rc;
}

PL_EXPORT void glDrawArrays(GLenum mode, GLint first, GLsizei count)
{
    if ((PL_LIKELY(!pl_quad_mode(mode)) || pl_array_draw(mode, first, count, 0, NULL) != 0) && !pl_touch(PL_D_CURRENT))
        REAL(glDrawArrays)(mode, first, count);
}

PL_EXPORT void glDrawArraysEXT(GLenum mode, GLint first, GLsizei count)
{
    if ((PL_LIKELY(!pl_quad_mode(mode)) || pl_array_draw(mode, first, count, 0, NULL) != 0) && !pl_touch(PL_D_CURRENT))
        REAL(glDrawArraysEXT)(mode, first, count);
}

PL_EXPORT void glDrawElements(GLenum mode, GLsizei count, GLenum type, const void *indices)
{
    if ((PL_LIKELY(!pl_quad_mode(mode)) || pl_array_draw(mode, 0, count, type, indices) != 0) && !pl_touch(PL_D_CURRENT))
        REAL(glDrawElements)(mode, count, type, indices);
}

PL_EXPORT void glDrawRangeElements(GLenum mode, GLuint start, GLuint end, GLsizei count, GLenum type,
                                   const void *indices)
{
    if ((PL_LIKELY(!pl_quad_mode(mode)) || pl_array_draw(mode, 0, count, type, indices) != 0) && !pl_touch(PL_D_CURRENT))
        REAL(glDrawRangeElements)(mode, start, end, count, type, indices);
}

PL_EXPORT void glDrawRangeElementsEXT(GLenum mode, GLuint start, GLuint end, GLsizei count, GLenum type,
                                      const void *indices)
{
    if ((PL_LIKELY(!pl_quad_mode(mode)) || pl_array_draw(mode, 0, count, type, indices) != 0) && !pl_touch(PL_D_CURRENT))
        REAL(glDrawRangeElementsEXT)(mode, start, end, count, type, indices);
}

PL_EXPORT void glMultiDrawArrays(GLenum mode, const GLint *first, const GLsizei *count, GLsizei drawcount)
{
    if (PL_LIKELY(!pl_quad_mode(mode)) || drawcount < 0) {
        if (!pl_touch(PL_D_CURRENT))
            REAL(glMultiDrawArrays)(mode, first, count, drawcount);
        return;
    }
    for (GLsizei i = 0; i < drawcount; i++)
        if (count[i] > 0 && pl_array_draw(mode, first[i], count[i], 0, NULL) != 0 && !pl_touch(PL_D_CURRENT))
            REAL(glDrawArrays)(mode, first[i], count[i]);
}

PL_EXPORT void glMultiDrawArraysEXT(GLenum mode, const GLint *first, const GLsizei *count, GLsizei primcount)
{
    glMultiDrawArrays(mode, first, count, primcount);
}

PL_EXPORT void glMultiDrawElements(GLenum mode, const GLsizei *count, GLenum type, const void *const *indices,
                                   GLsizei drawcount)
{
    if (PL_LIKELY(!pl_quad_mode(mode)) || drawcount < 0) {
        if (!pl_touch(PL_D_CURRENT))
            REAL(glMultiDrawElements)(mode, count, type, indices, drawcount);
        return;
    }
    for (GLsizei i = 0; i < drawcount; i++)
        if (count[i] > 0 && pl_array_draw(mode, 0, count[i], type, indices[i]) != 0 && !pl_touch(PL_D_CURRENT))
            REAL(glDrawElements)(mode, count[i], type, indices[i]);
}

PL_EXPORT void glMultiDrawElementsEXT(GLenum mode, const GLsizei *count, GLenum type, const void *const *indices,
                                      GLsizei primcount)
{
    glMultiDrawElements(mode, count, type, indices, primcount);
}
