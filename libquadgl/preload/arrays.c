/* arrays.c: quads drawn from vertex arrays (glDrawArrays, glDrawElements and their kin).
 *
 * The client-array state is read back from the driver at each quad draw rather than tracked
 * call by call, so glInterleavedArrays, glLockArraysEXT, glPushClientAttrib, VAOs and
 * buffer objects are all seen as the driver sees them. Each enabled fixed-function array
 * (vertex, colour, secondary colour, normal, fog coordinate, texture units 0-3) is read with
 * its type and converted to floats as GL converts it; an array in a buffer object is first
 * copied back over the range of indices the draw uses. Indices (8, 16 or 32 bit, client
 * memory or element buffer) are resolved on the CPU, so the result is a plain primitive of
 * vertices like one from glBegin/glEnd, drawn or recorded the same way. State the capture
 * does not model (an edge-flag array, generic attribute 0, a texture unit above 3, primitive
 * restart, an unknown type), and any draw the GL path would not take anyway, goes to the
 * driver as the program's own call. */
#include "preload.h"
#include "gl_internal.h" /* qgl__type_size */

#include <stdlib.h>
#include <string.h>

enum { PL_ARR_VERTEX = PL_A_COUNT, PL_ARR_COUNT };

typedef struct pl_array {
    int size;          /* components; 0 = disabled */
    GLenum type;
    int bgra;
    size_t stride;     /* bytes between elements */
    const unsigned char *base; /* element `lo` (client memory or our copy) */
    size_t lo;
    unsigned char *copy;
} pl_array;

typedef struct pl_arrays {
    pl_array a[PL_ARR_COUNT]; /* indexed by PL_A_* and PL_ARR_VERTEX */
} pl_arrays;


typedef struct pl_array_query {
    GLenum enable, size, type, stride, pointer, binding;
    int fixed_size;
} pl_array_query;

static const pl_array_query pl_queries[PL_ARR_COUNT] = {
    [PL_A_COLOR] = {GL_COLOR_ARRAY, GL_COLOR_ARRAY_SIZE, GL_COLOR_ARRAY_TYPE, GL_COLOR_ARRAY_STRIDE,
                    GL_COLOR_ARRAY_POINTER, GL_COLOR_ARRAY_BUFFER_BINDING, 0},
    [PL_A_SECONDARY] = {GL_SECONDARY_COLOR_ARRAY, GL_SECONDARY_COLOR_ARRAY_SIZE, GL_SECONDARY_COLOR_ARRAY_TYPE,
                        GL_SECONDARY_COLOR_ARRAY_STRIDE, GL_SECONDARY_COLOR_ARRAY_POINTER,
                        GL_SECONDARY_COLOR_ARRAY_BUFFER_BINDING, 0},
    [PL_A_NORMAL] = {GL_NORMAL_ARRAY, 0, GL_NORMAL_ARRAY_TYPE, GL_NORMAL_ARRAY_STRIDE, GL_NORMAL_ARRAY_POINTER,
                     GL_NORMAL_ARRAY_BUFFER_BINDING, 3},
    [PL_A_FOG] = {GL_FOG_COORD_ARRAY, 0, GL_FOG_COORD_ARRAY_TYPE, GL_FOG_COORD_ARRAY_STRIDE,
                  GL_FOG_COORD_ARRAY_POINTER, GL_FOG_COORD_ARRAY_BUFFER_BINDING, 1},
    [PL_ARR_VERTEX] = {GL_VERTEX_ARRAY, GL_VERTEX_ARRAY_SIZE, GL_VERTEX_ARRAY_TYPE, GL_VERTEX_ARRAY_STRIDE,
                       GL_VERTEX_ARRAY_POINTER, GL_VERTEX_ARRAY_BUFFER_BINDING, 0},
};

static const pl_array_query pl_texcoord_query = {
    GL_TEXTURE_COORD_ARRAY, GL_TEXTURE_COORD_ARRAY_SIZE, GL_TEXTURE_COORD_ARRAY_TYPE,
    GL_TEXTURE_COORD_ARRAY_STRIDE, GL_TEXTURE_COORD_ARRAY_POINTER,
    GL_TEXTURE_COORD_ARRAY_BUFFER_BINDING, 0};

/* Copies elements [lo, hi] of an array living in buffer object `buffer` back to memory. */
static int pl_array_fetch_buffer(pl_array *arr, GLuint buffer, size_t offset, size_t lo, size_t hi)
{
    GLint saved = 0;
    size_t bytes = (hi - lo) * arr->stride + (size_t)arr->size * qgl__type_size(arr->type);
    arr->copy = malloc(bytes ? bytes : 1);
    if (!arr->copy)
        return -1;
    REAL(glGetIntegerv)(GL_ARRAY_BUFFER_BINDING, &saved);
    REAL(glBindBuffer)(GL_ARRAY_BUFFER, buffer);
    REAL(glGetBufferSubData)(GL_ARRAY_BUFFER, (GLintptr)(offset + lo * arr->stride), (GLsizeiptr)bytes, arr->copy);
    REAL(glBindBuffer)(GL_ARRAY_BUFFER, (GLuint)saved);
    arr->base = arr->copy;
    arr->lo = lo;
    return 0;
}

/* Reads one array's state; -1 when its type is one we do not convert. */
static int pl_array_read(pl_array *arr, const pl_array_query *q, size_t lo, size_t hi)
{
    GLint size = q->fixed_size, type = 0, stride = 0, buffer = 0;
    void *ptr = NULL;
    memset(arr, 0, sizeof *arr);
    if (!REAL(glIsEnabled)(q->enable))
        return 0;
    if (q->size)
        REAL(glGetIntegerv)(q->size, &size);
    REAL(glGetIntegerv)(q->type, &type);
    REAL(glGetIntegerv)(q->stride, &stride);
    REAL(glGetIntegerv)(q->binding, &buffer);
    REAL(glGetPointerv)(q->pointer, &ptr);
    arr->bgra = (size == GL_BGRA);
    arr->size = arr->bgra ? 4 : size;
    arr->type = (GLenum)type;
    if (!qgl__type_size(arr->type) || arr->size < 1 || arr->size > 4)
        return -1;
    arr->stride = stride ? (size_t)stride : (size_t)arr->size * qgl__type_size(arr->type);
    if (buffer)
        return pl_array_fetch_buffer(arr, (GLuint)buffer, (size_t)(uintptr_t)ptr, lo, hi);
    arr->base = (const unsigned char *)ptr + lo * arr->stride;
    arr->lo = lo;
    return arr->base ? 0 : -1;
}

static void pl_arrays_free(pl_arrays *s)
{
    for (int i = 0; i < PL_ARR_COUNT; i++)
        free(s->a[i].copy);
}

/* State the capture cannot represent: the driver draws the call itself. */
static int pl_arrays_unmodelled(void)
{
    GLint attrib0 = 0, units = 1, active = 0, bad = 0;
    if (REAL(glIsEnabled)(GL_EDGE_FLAG_ARRAY))
        return 1;
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

static int pl_arrays_query(pl_arrays *s, size_t lo, size_t hi)
{
    GLint active = 0, units = 1;
    int rc = 0;
    memset(s, 0, sizeof *s);
    if (pl_arrays_unmodelled())
        return -1;
    for (int i = 0; i < PL_ARR_COUNT && rc == 0; i++)
        if (i < PL_A_TEX0 || i == PL_ARR_VERTEX)
            rc = pl_array_read(&s->a[i], &pl_queries[i], lo, hi);
    REAL(glGetIntegerv)(GL_MAX_TEXTURE_COORDS, &units);
    if (units > PL_TEXUNITS)
        units = PL_TEXUNITS;
    REAL(glGetIntegerv)(GL_CLIENT_ACTIVE_TEXTURE, &active);
    for (GLint u = 0; u < units && rc == 0; u++) {
        REAL(glClientActiveTexture)(GL_TEXTURE0 + (GLenum)u);
        rc = pl_array_read(&s->a[PL_A_TEX0 + u], &pl_texcoord_query, lo, hi);
    }
    REAL(glClientActiveTexture)((GLenum)active);
    if (rc != 0)
        pl_arrays_free(s);
    return rc;
}

/* Component k of an element, converted as GL converts it (normalized or not). */
static float pl_component(const unsigned char *e, GLenum type, int k, int normalized)
{
    switch (type) {
    case GL_BYTE: return normalized ? PL_B(((const GLbyte *)e)[k]) : (float)((const GLbyte *)e)[k];
    case GL_UNSIGNED_BYTE: return normalized ? PL_UB(e[k]) : (float)e[k];
    case GL_SHORT: return normalized ? PL_S(((const GLshort *)e)[k]) : (float)((const GLshort *)e)[k];
    case GL_UNSIGNED_SHORT: return normalized ? PL_US(((const GLushort *)e)[k]) : (float)((const GLushort *)e)[k];
    case GL_INT: return normalized ? PL_I(((const GLint *)e)[k]) : (float)((const GLint *)e)[k];
    case GL_UNSIGNED_INT: return normalized ? PL_UI(((const GLuint *)e)[k]) : (float)((const GLuint *)e)[k];
    case GL_FLOAT: return ((const GLfloat *)e)[k];
    default: return (float)((const GLdouble *)e)[k];
    }
}

/* Element i of an array into out (4 floats, missing components from def). */
static void pl_array_get(const pl_array *arr, size_t i, int normalized, const float def[4], float out[4])
{
    const unsigned char *e = arr->base + (i - arr->lo) * arr->stride;
    float c[4];
    memcpy(c, def, sizeof c);
    for (int k = 0; k < arr->size; k++)
        c[k] = pl_component(e, arr->type, k, normalized);
    if (arr->bgra) {
        float r = c[2];
        c[2] = c[0];
        c[0] = r;
    }
    memcpy(out, c, sizeof c);
}

/* Feeds element i through the capture as glArrayElement would: attributes, then the vertex. */
static void pl_arrays_element(pl_ctx *x, const pl_arrays *s, size_t i)
{
    static const float def_pos[4] = {0, 0, 0, 1}, def_col[4] = {0, 0, 0, 1}, def_tex[4] = {0, 0, 0, 1};
    float v[4];
    if (s->a[PL_A_COLOR].size) {
        pl_array_get(&s->a[PL_A_COLOR], i, 1, def_col, v);
        pl_cap_color(x, v[0], v[1], v[2], v[3]);
    }
    if (s->a[PL_A_SECONDARY].size) {
        pl_array_get(&s->a[PL_A_SECONDARY], i, 1, def_col, v);
        pl_cap_secondary(x, v[0], v[1], v[2]);
    }
    if (s->a[PL_A_NORMAL].size) {
        pl_array_get(&s->a[PL_A_NORMAL], i, 1, def_col, v);
        pl_cap_normal(x, v[0], v[1], v[2]);
    }
    if (s->a[PL_A_FOG].size) {
        pl_array_get(&s->a[PL_A_FOG], i, 0, def_col, v);
        pl_cap_fog(x, v[0]);
    }
    for (int u = 0; u < PL_TEXUNITS; u++)
        if (s->a[PL_A_TEX0 + u].size) {
            pl_array_get(&s->a[PL_A_TEX0 + u], i, 0, def_tex, v);
            pl_cap_texcoord(x, (GLenum)u, v[0], v[1], v[2], v[3]);
        }
    if (s->a[PL_ARR_VERTEX].size) {
        pl_array_get(&s->a[PL_ARR_VERTEX], i, 0, def_pos, v);
        pl_cap_vertex(x, v[0], v[1], v[2], v[3]);
    }
}

void pl_cap_array_element(pl_ctx *x, GLint i)
{
    pl_arrays s;
    if (i < 0 || pl_arrays_query(&s, (size_t)i, (size_t)i) != 0) {
        REAL(glArrayElement)(i);
        return;
    }
    pl_arrays_element(x, &s, (size_t)i);
    pl_arrays_free(&s);
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
    pl_arrays s;
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
            pl_arrays_element(x, &s, idx ? idx[k] : (size_t)first + (size_t)k);
        if (x->prim.lost)
            rc = -1;
        *p = x->prim;
        x->prim = saved;
    }
    pl_arrays_free(&s);
    free(idx);
    return rc;
}

/* ---- the draw entry points ----------------------------------------------------------------- */

static int pl_quad_mode(GLenum mode)
{
    return mode == GL_QUADS || mode == GL_QUAD_STRIP;
}

/* The driver's own draw call for the arrays. */
static void pl_array_draw_native(GLenum mode, GLint first, GLsizei count, GLenum type, const void *indices)
{
    if (type)
        REAL(glDrawElements)(mode, count, type, indices);
    else
        REAL(glDrawArrays)(mode, first, count);
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
    if (x->compiling)
        pl_list_segment_close(x);
    rc = pl_arrays_capture(x, &x->scratch, mode, first, count, type, indices);
    if (rc == 0 && x->compiling) {
        pl_list_record_prim(x, &x->scratch);
        pl_list_native_begin(x);
        pl_array_draw_native(mode, first, count, type, indices);
        pl_list_native_end(x);
        if (x->compile_mode == GL_COMPILE_AND_EXECUTE)
            pl_draw_prim(x, &x->scratch);
    } else if (rc == 0 && pl_prim_for_driver(x, &x->scratch)) {
        /* The driver's own call draws exactly what it always drew. */
        pl_count_passthrough(pl_prim_quads(&x->scratch));
        rc = -1;
    } else if (rc == 0) {
        pl_draw_prim(x, &x->scratch);
    }
    if (x->compiling)
        pl_list_segment_open(x);
    return rc;
}

PL_EXPORT void glDrawArrays(GLenum mode, GLint first, GLsizei count)
{
    if (PL_LIKELY(!pl_quad_mode(mode)) || pl_array_draw(mode, first, count, 0, NULL) != 0)
        REAL(glDrawArrays)(mode, first, count);
}

PL_EXPORT void glDrawArraysEXT(GLenum mode, GLint first, GLsizei count)
{
    if (PL_LIKELY(!pl_quad_mode(mode)) || pl_array_draw(mode, first, count, 0, NULL) != 0)
        REAL(glDrawArraysEXT)(mode, first, count);
}

PL_EXPORT void glDrawElements(GLenum mode, GLsizei count, GLenum type, const void *indices)
{
    if (PL_LIKELY(!pl_quad_mode(mode)) || pl_array_draw(mode, 0, count, type, indices) != 0)
        REAL(glDrawElements)(mode, count, type, indices);
}

PL_EXPORT void glDrawRangeElements(GLenum mode, GLuint start, GLuint end, GLsizei count, GLenum type,
                                   const void *indices)
{
    if (PL_LIKELY(!pl_quad_mode(mode)) || pl_array_draw(mode, 0, count, type, indices) != 0)
        REAL(glDrawRangeElements)(mode, start, end, count, type, indices);
}

PL_EXPORT void glDrawRangeElementsEXT(GLenum mode, GLuint start, GLuint end, GLsizei count, GLenum type,
                                      const void *indices)
{
    if (PL_LIKELY(!pl_quad_mode(mode)) || pl_array_draw(mode, 0, count, type, indices) != 0)
        REAL(glDrawRangeElementsEXT)(mode, start, end, count, type, indices);
}

PL_EXPORT void glMultiDrawArrays(GLenum mode, const GLint *first, const GLsizei *count, GLsizei drawcount)
{
    if (PL_LIKELY(!pl_quad_mode(mode)) || drawcount < 0) {
        REAL(glMultiDrawArrays)(mode, first, count, drawcount);
        return;
    }
    for (GLsizei i = 0; i < drawcount; i++)
        if (count[i] > 0 && pl_array_draw(mode, first[i], count[i], 0, NULL) != 0)
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
        REAL(glMultiDrawElements)(mode, count, type, indices, drawcount);
        return;
    }
    for (GLsizei i = 0; i < drawcount; i++)
        if (count[i] > 0 && pl_array_draw(mode, 0, count[i], type, indices[i]) != 0)
            REAL(glDrawElements)(mode, count[i], type, indices[i]);
}

PL_EXPORT void glMultiDrawElementsEXT(GLenum mode, const GLsizei *count, GLenum type, const void *const *indices,
                                      GLsizei primcount)
{
    glMultiDrawElements(mode, count, type, indices, primcount);
}
