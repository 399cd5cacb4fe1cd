/* arrays.c: the fixed-function client arrays as the driver describes them, read element by element.
 *
 * Used by qglArrayElement and by the preload library's capture of glArrayElement and of quad
 * draws from arrays, so that both read the same state the same way. The descriptions (enabled,
 * size, type, stride, pointer, buffer) are asked of the driver, which keeps
 * glInterleavedArrays, glPushClientAttrib, vertex array objects and buffer objects right for
 * free; arrays of GL versions the context lacks stay disabled (asking about them is an
 * error). Data in a buffer object is copied back over the range of elements needed, once.
 * Conversion follows the driver: an element fed through glArrayElement goes through the
 * immediate-mode entry points, which map a signed normalized c of b bits to
 * (2c + 1) / (2^b - 1); a draw from arrays fetches with the vertex formats' rule,
 * max(c / (2^(b-1) - 1), -1). Replaying either the other way changes colours by a level. */
#include <stdlib.h>
#include <string.h>

#include "gl_internal.h"

size_t qgl__type_size(GLenum type)
{
    switch (type) {
    case GL_BYTE: case GL_UNSIGNED_BYTE: return 1;
    case GL_SHORT: case GL_UNSIGNED_SHORT: return 2;
    case GL_INT: case GL_UNSIGNED_INT: case GL_FLOAT: return 4;
    case GL_DOUBLE: return 8;
    default: return 0;
    }
}

/* The queries of one kind of array: X(enable, size (0: fixed), fixed size, type, stride,
 * pointer, buffer binding). */
typedef struct array_query {
    GLenum enable, size;
    int fixed;
    GLenum type, stride, pointer, binding;
    int version;               /* GL version that has it */
} array_query;

static const array_query vertex_query = {GL_VERTEX_ARRAY, GL_VERTEX_ARRAY_SIZE, 0, GL_VERTEX_ARRAY_TYPE,
                                         GL_VERTEX_ARRAY_STRIDE, GL_VERTEX_ARRAY_POINTER,
                                         GL_VERTEX_ARRAY_BUFFER_BINDING, 11};
static const array_query edge_query = {GL_EDGE_FLAG_ARRAY, 0, 1, 0, GL_EDGE_FLAG_ARRAY_STRIDE,
                                       GL_EDGE_FLAG_ARRAY_POINTER, GL_EDGE_FLAG_ARRAY_BUFFER_BINDING, 11};
/* By row of QGL__ATTRIBS; the texture units share one. */
static const array_query attrib_queries[QGL__AT_TEX0 + 1] = {
    {GL_COLOR_ARRAY, GL_COLOR_ARRAY_SIZE, 0, GL_COLOR_ARRAY_TYPE, GL_COLOR_ARRAY_STRIDE, GL_COLOR_ARRAY_POINTER,
     GL_COLOR_ARRAY_BUFFER_BINDING, 11},
    {GL_NORMAL_ARRAY, 0, 3, GL_NORMAL_ARRAY_TYPE, GL_NORMAL_ARRAY_STRIDE, GL_NORMAL_ARRAY_POINTER,
     GL_NORMAL_ARRAY_BUFFER_BINDING, 11},
    {GL_SECONDARY_COLOR_ARRAY, GL_SECONDARY_COLOR_ARRAY_SIZE, 0, GL_SECONDARY_COLOR_ARRAY_TYPE,
     GL_SECONDARY_COLOR_ARRAY_STRIDE, GL_SECONDARY_COLOR_ARRAY_POINTER, GL_SECONDARY_COLOR_ARRAY_BUFFER_BINDING, 14},
    {GL_FOG_COORD_ARRAY, 0, 1, GL_FOG_COORD_ARRAY_TYPE, GL_FOG_COORD_ARRAY_STRIDE, GL_FOG_COORD_ARRAY_POINTER,
     GL_FOG_COORD_ARRAY_BUFFER_BINDING, 14},
    {GL_TEXTURE_COORD_ARRAY, GL_TEXTURE_COORD_ARRAY_SIZE, 0, GL_TEXTURE_COORD_ARRAY_TYPE,
     GL_TEXTURE_COORD_ARRAY_STRIDE, GL_TEXTURE_COORD_ARRAY_POINTER, GL_TEXTURE_COORD_ARRAY_BUFFER_BINDING, 13},
};

/* One array's description; 0 when enabled with a layout we do not convert. */
static int read_one(struct qgl__gl *gl, int version, const array_query *q, qgl__array *arr)
{
    GLint size = q->fixed, type = GL_UNSIGNED_BYTE, stride = 0, buffer = 0;
    void *ptr = NULL;
    memset(arr, 0, sizeof *arr);
    if (version < q->version || !gl->IsEnabled(q->enable))
        return 1;
    if (q->size)
        gl->GetIntegerv(q->size, &size);
    if (q->type)
        gl->GetIntegerv(q->type, &type);
    gl->GetIntegerv(q->stride, &stride);
    if (version >= 15)
        gl->GetIntegerv(q->binding, &buffer);
    gl->GetPointerv(q->pointer, &ptr);
    arr->bgra = size == GL_BGRA;
    arr->size = arr->bgra ? 4 : size;
    arr->type = (GLenum)type;
    if (!qgl__type_size(arr->type) || arr->size < 1 || arr->size > 4 || (buffer && !gl->GetBufferSubData))
        return 0;
    arr->stride = stride ? (size_t)stride : (size_t)arr->size * qgl__type_size(arr->type);
    arr->ptr = ptr;
    arr->buffer = (GLuint)buffer;
    return 1;
}

int qgl__arrays_read(struct qgl__gl *gl, int version, int units, qgl__arrays *out)
{
    int ok = read_one(gl, version, &vertex_query, &out->vertex) && read_one(gl, version, &edge_query, &out->edge);
    for (int a = 0; a < QGL__AT_TEX0; a++)
        ok = ok && read_one(gl, version, &attrib_queries[a], &out->attr[a]);
    GLint active = GL_TEXTURE0;
    gl->GetIntegerv(GL_CLIENT_ACTIVE_TEXTURE, &active);
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++) {
        qgl__array *arr = &out->attr[QGL__AT_TEX0 + u];
        memset(arr, 0, sizeof *arr);
        if (u >= units || !ok)
            continue;
        gl->ClientActiveTexture(GL_TEXTURE0 + (GLenum)u);
        ok = read_one(gl, version, &attrib_queries[QGL__AT_TEX0], arr);
    }
    gl->ClientActiveTexture((GLenum)active);
    return ok;
}

/* Elements [lo, hi] of an array in a buffer object, copied to memory (ptr then points as if
 * the copy were the whole array). */
static int copy_back(struct qgl__gl *gl, qgl__array *arr, size_t lo, size_t hi)
{
    size_t bytes = (hi - lo) * arr->stride + (size_t)arr->size * qgl__type_size(arr->type);
    GLint saved = 0;
    if (!(arr->copy = malloc(bytes ? bytes : 1)))
        return 0;
    gl->GetIntegerv(GL_ARRAY_BUFFER_BINDING, &saved);
    gl->BindBuffer(GL_ARRAY_BUFFER, arr->buffer);
    gl->GetBufferSubData(GL_ARRAY_BUFFER, (GLintptr)((uintptr_t)arr->ptr + lo * arr->stride), (GLsizeiptr)bytes,
                         arr->copy);
    gl->BindBuffer(GL_ARRAY_BUFFER, (GLuint)saved);
    arr->ptr = arr->copy - lo * arr->stride;
    return 1;
}

int qgl__arrays_fetch(struct qgl__gl *gl, qgl__arrays *s, size_t lo, size_t hi)
{
    int ok = !s->vertex.buffer || copy_back(gl, &s->vertex, lo, hi);
    ok = ok && (!s->edge.buffer || copy_back(gl, &s->edge, lo, hi));
    for (int a = 0; a < QGL__NATTR && ok; a++)
        ok = !s->attr[a].buffer || copy_back(gl, &s->attr[a], lo, hi);
    return ok;
}

void qgl__arrays_free(qgl__arrays *s)
{
    free(s->vertex.copy);
    free(s->edge.copy);
    for (int a = 0; a < QGL__NATTR; a++)
        free(s->attr[a].copy);
    memset(s, 0, sizeof *s);
}

/* Component k of element e, a signed normalized value mapped by the rule of its entry point. */
static float component(const unsigned char *e, GLenum type, int k, int normalized, int immediate)
{
    union { GLbyte b; GLshort s; GLushort us; GLint i; GLuint ui; GLfloat f; GLdouble d; } u;
    size_t n = qgl__type_size(type);
    memcpy(&u, e + n * (size_t)k, n);
    switch (type) {
    case GL_BYTE:
        if (!normalized)
            return u.b;
        return immediate ? (2.0f * u.b + 1.0f) / 255.0f : (u.b / 127.0f < -1.0f ? -1.0f : u.b / 127.0f);
    case GL_UNSIGNED_BYTE: return normalized ? e[k] / 255.0f : e[k];
    case GL_SHORT:
        if (!normalized)
            return u.s;
        return immediate ? (2.0f * u.s + 1.0f) / 65535.0f : (u.s / 32767.0f < -1.0f ? -1.0f : u.s / 32767.0f);
    case GL_UNSIGNED_SHORT: return normalized ? u.us / 65535.0f : u.us;
    case GL_INT:
        if (!normalized)
            return (float)u.i;
        return immediate ? (float)((2.0 * u.i + 1.0) / 4294967295.0)
                         : (float)(u.i / 2147483647.0 < -1.0 ? -1.0 : u.i / 2147483647.0);
    case GL_UNSIGNED_INT: return normalized ? (float)(u.ui / 4294967295.0) : (float)u.ui;
    case GL_FLOAT: return u.f;
    default: return (float)u.d;
    }
}

void qgl__array_element(const qgl__array *arr, size_t i, int normalized, int immediate, float out[4])
{
    const unsigned char *e = arr->ptr + i * arr->stride;
    out[0] = out[1] = out[2] = 0;
    out[3] = 1;
    for (int k = 0; k < arr->size; k++)
        out[k] = component(e, arr->type, k, normalized && arr->type != GL_FLOAT && arr->type != GL_DOUBLE, immediate);
    if (arr->bgra) {
        float r = out[0];
        out[0] = out[2], out[2] = r;
    }
}
