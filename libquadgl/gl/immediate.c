/* immediate.c: the qgl* immediate-mode API: capture quads, forward everything else.
 *
 * qglBegin(GL_QUADS or GL_QUAD_STRIP) starts a capture: vertices go into one array per
 * attribute (rlgl's layout), and an attribute joins the capture the first time it is given,
 * its earlier vertices back-filled with the driver's current value (which cannot have changed
 * since qglBegin: nothing reached the driver). qglEnd drops an incomplete trailing quad as GL
 * does, draws the capture in one go, and leaves the driver's current attributes at the last
 * values given. Any other primitive, and every call outside qglBegin/qglEnd, goes to the
 * driver as the same call. Misuse is forwarded so the driver records GL's own error: a
 * glBegin inside a captured primitive becomes a driver glEnd outside any primitive, which is
 * GL_INVALID_OPERATION with no other effect, exactly what the native glBegin would raise.
 * qglArrayElement inside a captured primitive reads the enabled client arrays and feeds
 * their element through the same capture. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl_internal.h"

enum { OUTSIDE = 0, CAPTURE = 1, FORWARD = 2 };

#define CTX_OR_RETURN(c) \
    qgl_context *c = qgl__tls_current; \
    if (!c) \
        return

/* The driver's current value of one attribute (QGL__A_* bit), for back-filling. */
void qgl__driver_current(qgl_context *c, unsigned bit, float out[4])
{
    struct qgl__gl *gl = &c->gl;
    out[0] = out[1] = out[2] = 0;
    out[3] = 1;
    if (bit == QGL__A_EDGE) {
        GLboolean e = GL_TRUE;
        gl->GetBooleanv(GL_EDGE_FLAG, &e);
        out[0] = e;
        return;
    }
    int a = __builtin_ctz(bit), unit = qgl__attribs[a].unit;
    GLint active = GL_TEXTURE0;
    if (unit >= 0) {
        gl->GetIntegerv(GL_ACTIVE_TEXTURE, &active);
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    }
    gl->GetFloatv(qgl__attribs[a].current, out);
    if (unit >= 0)
        gl->ActiveTexture((GLenum)active);
}

/* An attribute given for the first time in this capture: allocate and back-fill it. */
static int join(qgl_context *c, unsigned bit)
{
    qgl__verts *v = &c->cap;
    if (!qgl__verts_reserve(v, v->n, c->given | bit))
        return 0;
    float cur[4];
    qgl__driver_current(c, bit, cur);
    if (bit == QGL__A_EDGE) {
        memset(v->edge, cur[0] != 0, v->n);
    } else {
        int a = __builtin_ctz(bit), k = qgl__attribs[a].floats;
        for (size_t i = 0; i < v->n; i++)
            memcpy(v->attr[a] + (size_t)k * i, cur, (size_t)k * sizeof(float));
    }
    c->given |= bit;
    return 1;
}

static void copy_attribs(qgl_context *c, qgl__verts *v, size_t i, unsigned g)
{
    for (int a = 0; a < QGL__NATTR; a++)
        if (g & (1u << a)) {
            int k = qgl__attribs[a].floats;
            memcpy(v->attr[a] + (size_t)k * i, c->cur[a], (size_t)k * sizeof(float));
        }
    if (g & QGL__A_EDGE)
        v->edge[i] = c->cur_edge;
    if (g & QGL__A_MATERIAL)
        memcpy(v->mat + QGL__MATERIAL_FLOATS * i, c->cur_mat, sizeof c->cur_mat);
}

/* Vertices captured before a long primitive is drawn in part: the driver works on the first
 * quads while the application sends the rest (as its own immediate mode does, which keeps
 * its rasterizer threads busy meanwhile), and memory stays bounded. A multiple of 4. */
#ifndef QGL__CHUNK
#define QGL__CHUNK 16384
#endif

/* Draw the quads captured so far (after anything batched before them) and go on capturing
 * the same primitive; a strip keeps its last two vertices, the first edge of what follows. */
static void draw_chunk(qgl_context *c)
{
    qgl__verts *v = &c->cap;
    qgl_topology topo = c->mode == GL_QUADS ? QGL_QUADS : QGL_QUAD_STRIP;
    v->mask = c->given;
    qgl__flush(c);
    qgl__draw(c, v, topo);
    size_t n = v->n;
    v->n = 0;
    if (topo == QGL_QUAD_STRIP) {
        qgl__verts_copy(v, 0, v, n - 2);
        qgl__verts_copy(v, 1, v, n - 1);
        v->n = 2;
    }
}

static void capture_vertex(qgl_context *c, float x, float y, float z, float w)
{
    qgl__verts *v = &c->cap;
    if (v->n >= QGL__CHUNK && v->n % 4 == 0)
        draw_chunk(c);
    if (v->n >= v->cap && !qgl__verts_reserve(v, v->n + 1, c->given))
        return; /* out of memory: the vertex is lost, the application goes on */
    size_t i = v->n++;
    float *p = v->pos + 4 * i;
    p[0] = x, p[1] = y, p[2] = z, p[3] = w;
    if (c->given)
        copy_attribs(c, v, i, c->given);
}

static void forget_arrays(qgl_context *c);

/* ---- begin / end -------------------------------------------------------------------------- */

QGL_API void qglBegin(unsigned mode)
{
    CTX_OR_RETURN(c);
    if (c->in_begin == CAPTURE) {
        qgl__flush(c);
        c->gl.End(); /* GL_INVALID_OPERATION, as the native nested glBegin */
        return;
    }
    if (c->in_begin == OUTSIDE && (mode == GL_QUADS || mode == GL_QUAD_STRIP)) {
        c->in_begin = CAPTURE;
        c->mode = mode;
        c->cap.n = 0;
        c->given = 0;
        forget_arrays(c);
        return;
    }
    qgl__flush(c);
    c->gl.Begin(mode);
    if (c->in_begin == OUTSIDE)
        c->in_begin = FORWARD;
}

/* The driver's current attributes become the last ones given, as after a native glEnd. */
static void set_current(qgl_context *c)
{
    for (int a = 0; a < QGL__NATTR; a++)
        if (c->given & (1u << a))
            qgl__set_current(&c->gl, a, c->cur[a]);
    if (c->given & QGL__A_EDGE)
        c->gl.EdgeFlag(c->cur_edge);
}

QGL_API void qglEnd(void)
{
    CTX_OR_RETURN(c);
    if (c->in_begin != CAPTURE) {
        qgl__flush(c);
        c->gl.End(); /* a forwarded primitive, or GL_INVALID_OPERATION outside one */
        c->in_begin = OUTSIDE;
        return;
    }
    c->in_begin = OUTSIDE;
    qgl_topology topo = c->mode == GL_QUADS ? QGL_QUADS : QGL_QUAD_STRIP;
    c->cap.mask = c->given;
    qgl__submit(c, &c->cap, topo);
    set_current(c);
}

/* ---- vertices ------------------------------------------------------------------------------- */

#define VERTEX(x, y, z, w, forward) \
    CTX_OR_RETURN(c); \
    if (c->in_begin == CAPTURE) \
        capture_vertex(c, (float)(x), (float)(y), (float)(z), (float)(w)); \
    else { \
        qgl__flush(c); \
        forward; \
    }

QGL_API void qglVertex2f(float x, float y) { VERTEX(x, y, 0, 1, c->gl.Vertex2f(x, y)); }
QGL_API void qglVertex2d(double x, double y) { VERTEX(x, y, 0, 1, c->gl.Vertex2d(x, y)); }
QGL_API void qglVertex2i(int x, int y) { VERTEX(x, y, 0, 1, c->gl.Vertex2i(x, y)); }
QGL_API void qglVertex2s(short x, short y) { VERTEX(x, y, 0, 1, c->gl.Vertex2s(x, y)); }
QGL_API void qglVertex3f(float x, float y, float z) { VERTEX(x, y, z, 1, c->gl.Vertex3f(x, y, z)); }
QGL_API void qglVertex3d(double x, double y, double z) { VERTEX(x, y, z, 1, c->gl.Vertex3d(x, y, z)); }
QGL_API void qglVertex3i(int x, int y, int z) { VERTEX(x, y, z, 1, c->gl.Vertex3i(x, y, z)); }
QGL_API void qglVertex3s(short x, short y, short z) { VERTEX(x, y, z, 1, c->gl.Vertex3s(x, y, z)); }
QGL_API void qglVertex4f(float x, float y, float z, float w) { VERTEX(x, y, z, w, c->gl.Vertex4f(x, y, z, w)); }
QGL_API void qglVertex4d(double x, double y, double z, double w) { VERTEX(x, y, z, w, c->gl.Vertex4d(x, y, z, w)); }
QGL_API void qglVertex4i(int x, int y, int z, int w) { VERTEX(x, y, z, w, c->gl.Vertex4i(x, y, z, w)); }
QGL_API void qglVertex4s(short x, short y, short z, short w) { VERTEX(x, y, z, w, c->gl.Vertex4s(x, y, z, w)); }
QGL_API void qglVertex2fv(const float *v) { VERTEX(v[0], v[1], 0, 1, c->gl.Vertex2fv(v)); }
QGL_API void qglVertex2dv(const double *v) { VERTEX(v[0], v[1], 0, 1, c->gl.Vertex2dv(v)); }
QGL_API void qglVertex2iv(const int *v) { VERTEX(v[0], v[1], 0, 1, c->gl.Vertex2iv(v)); }
QGL_API void qglVertex2sv(const short *v) { VERTEX(v[0], v[1], 0, 1, c->gl.Vertex2sv(v)); }
QGL_API void qglVertex3fv(const float *v) { VERTEX(v[0], v[1], v[2], 1, c->gl.Vertex3fv(v)); }
QGL_API void qglVertex3dv(const double *v) { VERTEX(v[0], v[1], v[2], 1, c->gl.Vertex3dv(v)); }
QGL_API void qglVertex3iv(const int *v) { VERTEX(v[0], v[1], v[2], 1, c->gl.Vertex3iv(v)); }
QGL_API void qglVertex3sv(const short *v) { VERTEX(v[0], v[1], v[2], 1, c->gl.Vertex3sv(v)); }
QGL_API void qglVertex4fv(const float *v) { VERTEX(v[0], v[1], v[2], v[3], c->gl.Vertex4fv(v)); }
QGL_API void qglVertex4dv(const double *v) { VERTEX(v[0], v[1], v[2], v[3], c->gl.Vertex4dv(v)); }
QGL_API void qglVertex4iv(const int *v) { VERTEX(v[0], v[1], v[2], v[3], c->gl.Vertex4iv(v)); }
QGL_API void qglVertex4sv(const short *v) { VERTEX(v[0], v[1], v[2], v[3], c->gl.Vertex4sv(v)); }

/* ---- attributes ------------------------------------------------------------------------------ */

/* Inside a capture: record into cur (joining the capture on first use); else forward. */
#define ATTRIB(bit, store, forward) \
    CTX_OR_RETURN(c); \
    if (c->in_begin == CAPTURE) { \
        if (!(c->given & (bit)) && !join(c, (bit))) \
            return; \
        store; \
    } else { \
        qgl__flush(c); \
        forward; \
    }

#define UB(x) ((float)(x) / 255.0f)

static void set4(float *d, float a, float b, float c, float e)
{
    d[0] = a, d[1] = b, d[2] = c, d[3] = e;
}

QGL_API void qglColor3f(float r, float g, float b) { ATTRIB(QGL__A_COLOR, set4(c->cur[QGL__AT_COLOR], r, g, b, 1), c->gl.Color3f(r, g, b)); }
QGL_API void qglColor3d(double r, double g, double b) { ATTRIB(QGL__A_COLOR, set4(c->cur[QGL__AT_COLOR], (float)r, (float)g, (float)b, 1), c->gl.Color3d(r, g, b)); }
QGL_API void qglColor3ub(unsigned char r, unsigned char g, unsigned char b) { ATTRIB(QGL__A_COLOR, set4(c->cur[QGL__AT_COLOR], UB(r), UB(g), UB(b), 1), c->gl.Color3ub(r, g, b)); }
QGL_API void qglColor4f(float r, float g, float b, float a) { ATTRIB(QGL__A_COLOR, set4(c->cur[QGL__AT_COLOR], r, g, b, a), c->gl.Color4f(r, g, b, a)); }
QGL_API void qglColor4d(double r, double g, double b, double a) { ATTRIB(QGL__A_COLOR, set4(c->cur[QGL__AT_COLOR], (float)r, (float)g, (float)b, (float)a), c->gl.Color4d(r, g, b, a)); }
QGL_API void qglColor4ub(unsigned char r, unsigned char g, unsigned char b, unsigned char a) { ATTRIB(QGL__A_COLOR, set4(c->cur[QGL__AT_COLOR], UB(r), UB(g), UB(b), UB(a)), c->gl.Color4ub(r, g, b, a)); }
QGL_API void qglColor3fv(const float *v) { ATTRIB(QGL__A_COLOR, set4(c->cur[QGL__AT_COLOR], v[0], v[1], v[2], 1), c->gl.Color3fv(v)); }
QGL_API void qglColor3dv(const double *v) { ATTRIB(QGL__A_COLOR, set4(c->cur[QGL__AT_COLOR], (float)v[0], (float)v[1], (float)v[2], 1), c->gl.Color3dv(v)); }
QGL_API void qglColor3ubv(const unsigned char *v) { ATTRIB(QGL__A_COLOR, set4(c->cur[QGL__AT_COLOR], UB(v[0]), UB(v[1]), UB(v[2]), 1), c->gl.Color3ubv(v)); }
QGL_API void qglColor4fv(const float *v) { ATTRIB(QGL__A_COLOR, set4(c->cur[QGL__AT_COLOR], v[0], v[1], v[2], v[3]), c->gl.Color4fv(v)); }
QGL_API void qglColor4dv(const double *v) { ATTRIB(QGL__A_COLOR, set4(c->cur[QGL__AT_COLOR], (float)v[0], (float)v[1], (float)v[2], (float)v[3]), c->gl.Color4dv(v)); }
QGL_API void qglColor4ubv(const unsigned char *v) { ATTRIB(QGL__A_COLOR, set4(c->cur[QGL__AT_COLOR], UB(v[0]), UB(v[1]), UB(v[2]), UB(v[3])), c->gl.Color4ubv(v)); }

static void set3(float *d, float a, float b, float e)
{
    d[0] = a, d[1] = b, d[2] = e;
}

QGL_API void qglNormal3f(float x, float y, float z) { ATTRIB(QGL__A_NORMAL, set3(c->cur[QGL__AT_NORMAL], x, y, z), c->gl.Normal3f(x, y, z)); }
QGL_API void qglNormal3d(double x, double y, double z) { ATTRIB(QGL__A_NORMAL, set3(c->cur[QGL__AT_NORMAL], (float)x, (float)y, (float)z), c->gl.Normal3d(x, y, z)); }
QGL_API void qglNormal3fv(const float *v) { ATTRIB(QGL__A_NORMAL, set3(c->cur[QGL__AT_NORMAL], v[0], v[1], v[2]), c->gl.Normal3fv(v)); }
QGL_API void qglNormal3dv(const double *v) { ATTRIB(QGL__A_NORMAL, set3(c->cur[QGL__AT_NORMAL], (float)v[0], (float)v[1], (float)v[2]), c->gl.Normal3dv(v)); }

#define T0 (c->cur[QGL__AT_TEX0])
QGL_API void qglTexCoord1f(float s) { ATTRIB(QGL__A_TEX0, set4(T0, s, 0, 0, 1), c->gl.TexCoord1f(s)); }
QGL_API void qglTexCoord2f(float s, float t) { ATTRIB(QGL__A_TEX0, set4(T0, s, t, 0, 1), c->gl.TexCoord2f(s, t)); }
QGL_API void qglTexCoord3f(float s, float t, float r) { ATTRIB(QGL__A_TEX0, set4(T0, s, t, r, 1), c->gl.TexCoord3f(s, t, r)); }
QGL_API void qglTexCoord4f(float s, float t, float r, float q) { ATTRIB(QGL__A_TEX0, set4(T0, s, t, r, q), c->gl.TexCoord4f(s, t, r, q)); }
QGL_API void qglTexCoord1d(double s) { ATTRIB(QGL__A_TEX0, set4(T0, (float)s, 0, 0, 1), c->gl.TexCoord1d(s)); }
QGL_API void qglTexCoord2d(double s, double t) { ATTRIB(QGL__A_TEX0, set4(T0, (float)s, (float)t, 0, 1), c->gl.TexCoord2d(s, t)); }
QGL_API void qglTexCoord3d(double s, double t, double r) { ATTRIB(QGL__A_TEX0, set4(T0, (float)s, (float)t, (float)r, 1), c->gl.TexCoord3d(s, t, r)); }
QGL_API void qglTexCoord4d(double s, double t, double r, double q) { ATTRIB(QGL__A_TEX0, set4(T0, (float)s, (float)t, (float)r, (float)q), c->gl.TexCoord4d(s, t, r, q)); }
QGL_API void qglTexCoord2fv(const float *v) { ATTRIB(QGL__A_TEX0, set4(T0, v[0], v[1], 0, 1), c->gl.TexCoord2fv(v)); }
QGL_API void qglTexCoord3fv(const float *v) { ATTRIB(QGL__A_TEX0, set4(T0, v[0], v[1], v[2], 1), c->gl.TexCoord3fv(v)); }
QGL_API void qglTexCoord4fv(const float *v) { ATTRIB(QGL__A_TEX0, set4(T0, v[0], v[1], v[2], v[3]), c->gl.TexCoord4fv(v)); }
QGL_API void qglTexCoord2dv(const double *v) { ATTRIB(QGL__A_TEX0, set4(T0, (float)v[0], (float)v[1], 0, 1), c->gl.TexCoord2dv(v)); }
#undef T0

/* Units past QGL_MAX_TEXUNITS cannot be captured; inside a quad they are dropped (only their
 * last value reaches the driver, at qglEnd's next forward), outside they are forwarded. */
static int unit_of(unsigned target)
{
    int u = (int)target - GL_TEXTURE0;
    return u >= 0 && u < QGL_MAX_TEXUNITS ? u : -1;
}

#define MULTI(target, store, forward) \
    CTX_OR_RETURN(c); \
    int u = unit_of(target); \
    if (c->in_begin == CAPTURE && u >= 0) { \
        if (!(c->given & (QGL__A_TEX0 << u)) && !join(c, QGL__A_TEX0 << u)) \
            return; \
        store; \
    } else { \
        qgl__flush(c); \
        forward; \
    }

QGL_API void qglMultiTexCoord2f(unsigned t, float s, float tt) { MULTI(t, set4(c->cur[QGL__AT_TEX0 + u], s, tt, 0, 1), c->gl.MultiTexCoord2f(t, s, tt)); }
QGL_API void qglMultiTexCoord4f(unsigned t, float s, float tt, float r, float q) { MULTI(t, set4(c->cur[QGL__AT_TEX0 + u], s, tt, r, q), c->gl.MultiTexCoord4f(t, s, tt, r, q)); }
QGL_API void qglMultiTexCoord2fv(unsigned t, const float *v) { MULTI(t, set4(c->cur[QGL__AT_TEX0 + u], v[0], v[1], 0, 1), c->gl.MultiTexCoord2fv(t, v)); }
QGL_API void qglMultiTexCoord4fv(unsigned t, const float *v) { MULTI(t, set4(c->cur[QGL__AT_TEX0 + u], v[0], v[1], v[2], v[3]), c->gl.MultiTexCoord4fv(t, v)); }

QGL_API void qglSecondaryColor3f(float r, float g, float b) { ATTRIB(QGL__A_COLOR2, set3(c->cur[QGL__AT_COLOR2], r, g, b), c->gl.SecondaryColor3f(r, g, b)); }
QGL_API void qglSecondaryColor3fv(const float *v) { ATTRIB(QGL__A_COLOR2, set3(c->cur[QGL__AT_COLOR2], v[0], v[1], v[2]), c->gl.SecondaryColor3fv(v)); }
QGL_API void qglFogCoordf(float f) { ATTRIB(QGL__A_FOG, c->cur[QGL__AT_FOG][0] = f, c->gl.FogCoordf(f)); }
QGL_API void qglFogCoordfv(const float *f) { ATTRIB(QGL__A_FOG, c->cur[QGL__AT_FOG][0] = f[0], c->gl.FogCoordfv(f)); }
QGL_API void qglEdgeFlag(unsigned char flag) { ATTRIB(QGL__A_EDGE, c->cur_edge = flag != 0, c->gl.EdgeFlag(flag)); }
QGL_API void qglEdgeFlagv(const unsigned char *flag) { ATTRIB(QGL__A_EDGE, c->cur_edge = flag[0] != 0, c->gl.EdgeFlagv(flag)); }

/* Materials given inside a captured quad are per-vertex attributes, as in the driver: the
 * first one joins the capture with both faces' complete material read from the driver
 * (back-filled into the earlier vertices), and every change is also forwarded at once so
 * the driver's material ends as the last one given. The shader path lights each corner with
 * its own material; the split and the CPU fallback see only the last (a documented limit). */
static const GLenum material_pnames[4] = {GL_AMBIENT, GL_DIFFUSE, GL_SPECULAR, GL_EMISSION};

static int join_material(qgl_context *c)
{
    qgl__verts *v = &c->cap;
    if (!qgl__verts_reserve(v, v->n, c->given | QGL__A_MATERIAL))
        return 0;
    for (int f = 0; f < 2; f++) {
        GLenum face = f ? GL_BACK : GL_FRONT;
        for (int k = 0; k < 4; k++)
            c->gl.GetMaterialfv(face, material_pnames[k], c->cur_mat + 16 * f + 4 * k);
        c->gl.GetMaterialfv(face, GL_SHININESS, c->cur_mat + 32 + f);
    }
    c->cur_mat[34] = 0, c->cur_mat[35] = 0;
    for (size_t i = 0; i < v->n; i++)
        memcpy(v->mat + QGL__MATERIAL_FLOATS * i, c->cur_mat, sizeof c->cur_mat);
    c->given |= QGL__A_MATERIAL;
    return 1;
}

/* Record a material change of the capture (values as glMaterialfv takes them). */
static void capture_material(qgl_context *c, GLenum face, GLenum pname, const float *p)
{
    if (!(c->given & QGL__A_MATERIAL) && !join_material(c))
        return;
    for (int f = 0; f < 2; f++) {
        if ((f == 0 && face == GL_BACK) || (f == 1 && face == GL_FRONT))
            continue;
        for (int k = 0; k < 4; k++)
            if (pname == material_pnames[k] || (pname == GL_AMBIENT_AND_DIFFUSE && k < 2))
                memcpy(c->cur_mat + 16 * f + 4 * k, p, 4 * sizeof(float));
        if (pname == GL_SHININESS)
            c->cur_mat[32 + f] = p[0];
    }
}

QGL_API void qglMaterialf(unsigned face, unsigned pname, float param)
{
    CTX_OR_RETURN(c);
    if (c->in_begin == CAPTURE && pname == GL_SHININESS)
        capture_material(c, face, pname, &param);
    qgl__flush(c); /* quads already waiting were given under the old material */
    c->gl.Materialf(face, pname, param);
}

QGL_API void qglMaterialfv(unsigned face, unsigned pname, const float *params)
{
    CTX_OR_RETURN(c);
    if (c->in_begin == CAPTURE && params)
        capture_material(c, face, pname, params);
    qgl__flush(c);
    c->gl.Materialfv(face, pname, params);
}

/* ---- vertex arrays: qglArrayElement ---------------------------------------------------------- */

/* Inside a captured primitive, element i of every enabled client array is fed through the
 * capture as GL specifies: the attributes, then the vertex (if the vertex array is enabled).
 * The arrays' descriptions are read from the driver once per capture (nothing can change
 * them before qglEnd: no call reaches the driver meanwhile); data in a buffer object is read
 * back element by element. Outside a captured primitive the call goes to the driver. */

enum { ARR_VERTEX, ARR_COLOR, ARR_COLOR2, ARR_NORMAL, ARR_FOG, ARR_EDGE, ARR_TEX0, ARR_COUNT = ARR_TEX0 + QGL_MAX_TEXUNITS };

typedef struct client_array {
    int size;                  /* components; 0 = disabled */
    GLenum type;
    int bgra;
    size_t stride;
    const unsigned char *ptr;  /* client memory, or the offset into buffer */
    GLuint buffer;
} client_array;

struct qgl__client_arrays {
    int valid;                 /* read since the capture's qglBegin */
    client_array a[ARR_COUNT];
};

/* A new capture reads the arrays afresh: the application may have changed them. */
static void forget_arrays(qgl_context *c)
{
    if (c->arrays)
        c->arrays->valid = 0;
}

static const struct {
    GLenum enable, size, type, stride, pointer, binding;
    int fixed_size;            /* arrays with no size query */
} array_queries[ARR_TEX0 + 1] = {
    {GL_VERTEX_ARRAY, GL_VERTEX_ARRAY_SIZE, GL_VERTEX_ARRAY_TYPE, GL_VERTEX_ARRAY_STRIDE, GL_VERTEX_ARRAY_POINTER,
     GL_VERTEX_ARRAY_BUFFER_BINDING, 0},
    {GL_COLOR_ARRAY, GL_COLOR_ARRAY_SIZE, GL_COLOR_ARRAY_TYPE, GL_COLOR_ARRAY_STRIDE, GL_COLOR_ARRAY_POINTER,
     GL_COLOR_ARRAY_BUFFER_BINDING, 0},
    {GL_SECONDARY_COLOR_ARRAY, GL_SECONDARY_COLOR_ARRAY_SIZE, GL_SECONDARY_COLOR_ARRAY_TYPE,
     GL_SECONDARY_COLOR_ARRAY_STRIDE, GL_SECONDARY_COLOR_ARRAY_POINTER, GL_SECONDARY_COLOR_ARRAY_BUFFER_BINDING, 0},
    {GL_NORMAL_ARRAY, 0, GL_NORMAL_ARRAY_TYPE, GL_NORMAL_ARRAY_STRIDE, GL_NORMAL_ARRAY_POINTER,
     GL_NORMAL_ARRAY_BUFFER_BINDING, 3},
    {GL_FOG_COORD_ARRAY, 0, GL_FOG_COORD_ARRAY_TYPE, GL_FOG_COORD_ARRAY_STRIDE, GL_FOG_COORD_ARRAY_POINTER,
     GL_FOG_COORD_ARRAY_BUFFER_BINDING, 1},
    {GL_EDGE_FLAG_ARRAY, 0, 0, GL_EDGE_FLAG_ARRAY_STRIDE, GL_EDGE_FLAG_ARRAY_POINTER,
     GL_EDGE_FLAG_ARRAY_BUFFER_BINDING, 1},
    {GL_TEXTURE_COORD_ARRAY, GL_TEXTURE_COORD_ARRAY_SIZE, GL_TEXTURE_COORD_ARRAY_TYPE,
     GL_TEXTURE_COORD_ARRAY_STRIDE, GL_TEXTURE_COORD_ARRAY_POINTER, GL_TEXTURE_COORD_ARRAY_BUFFER_BINDING, 0},
};

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

/* Arrays of GL versions the context lacks stay disabled (querying them is an error). */
static void read_array(qgl_context *c, int q, client_array *arr)
{
    struct qgl__gl *gl = &c->gl;
    GLint size = array_queries[q].fixed_size, type = GL_UNSIGNED_BYTE, stride = 0, buffer = 0;
    void *ptr = NULL;
    memset(arr, 0, sizeof *arr);
    if ((q == ARR_COLOR2 || q == ARR_FOG) && c->version < 14)
        return;
    if (!gl->IsEnabled(array_queries[q].enable))
        return;
    if (array_queries[q].size)
        gl->GetIntegerv(array_queries[q].size, &size);
    if (array_queries[q].type)
        gl->GetIntegerv(array_queries[q].type, &type);
    gl->GetIntegerv(array_queries[q].stride, &stride);
    if (c->version >= 15)
        gl->GetIntegerv(array_queries[q].binding, &buffer);
    gl->GetPointerv(array_queries[q].pointer, &ptr);
    arr->bgra = size == GL_BGRA;
    arr->type = (GLenum)type;
    arr->size = arr->bgra ? 4 : size;
    if (!qgl__type_size(arr->type) || arr->size < 1 || arr->size > 4 || (buffer && !gl->GetBufferSubData)) {
        arr->size = 0; /* a layout we do not convert: ignored */
        return;
    }
    arr->stride = stride ? (size_t)stride : (size_t)arr->size * qgl__type_size(arr->type);
    arr->ptr = ptr;
    arr->buffer = (GLuint)buffer;
}

static int read_arrays(qgl_context *c)
{
    struct qgl__gl *gl = &c->gl;
    if (!c->arrays && !(c->arrays = calloc(1, sizeof *c->arrays)))
        return 0;
    if (c->arrays->valid)
        return 1;
    for (int q = 0; q < ARR_TEX0; q++)
        read_array(c, q, &c->arrays->a[q]);
    GLint active = GL_TEXTURE0;
    gl->GetIntegerv(GL_CLIENT_ACTIVE_TEXTURE, &active);
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++) {
        client_array *arr = &c->arrays->a[ARR_TEX0 + u];
        memset(arr, 0, sizeof *arr);
        if (u >= c->max_units)
            continue;
        gl->ClientActiveTexture(GL_TEXTURE0 + (GLenum)u);
        read_array(c, ARR_TEX0, arr);
    }
    gl->ClientActiveTexture((GLenum)active);
    c->arrays->valid = 1;
    return 1;
}

/* Component k of element e as GL converts it: integer colours and normals are normalized. */
static float component(const unsigned char *e, GLenum type, int k, int normalized)
{
    union { GLbyte b; GLshort s; GLushort us; GLint i; GLuint ui; GLfloat f; GLdouble d; } u;
    size_t n = qgl__type_size(type);
    memcpy(&u, e + n * (size_t)k, n);
    switch (type) {
    case GL_BYTE: return normalized ? fmaxf(u.b / 127.0f, -1.0f) : u.b;
    case GL_UNSIGNED_BYTE: return normalized ? e[k] / 255.0f : e[k];
    case GL_SHORT: return normalized ? fmaxf(u.s / 32767.0f, -1.0f) : u.s;
    case GL_UNSIGNED_SHORT: return normalized ? u.us / 65535.0f : u.us;
    case GL_INT: return normalized ? fmaxf((float)(u.i / 2147483647.0), -1.0f) : (float)u.i;
    case GL_UNSIGNED_INT: return normalized ? (float)(u.ui / 4294967295.0) : (float)u.ui;
    case GL_FLOAT: return u.f;
    default: return (float)u.d;
    }
}

/* Element i of arr into out, components it lacks from GL's defaults (0, 0, 0, 1). */
static void fetch_element(qgl_context *c, const client_array *arr, GLint i, int normalized, float out[4])
{
    unsigned char tmp[32];
    size_t bytes = (size_t)arr->size * qgl__type_size(arr->type);
    const unsigned char *e = arr->ptr + (size_t)i * arr->stride;
    if (arr->buffer) {
        GLint saved = 0;
        c->gl.GetIntegerv(GL_ARRAY_BUFFER_BINDING, &saved);
        c->gl.BindBuffer(GL_ARRAY_BUFFER, arr->buffer);
        c->gl.GetBufferSubData(GL_ARRAY_BUFFER, (GLintptr)(uintptr_t)e, (GLsizeiptr)bytes, tmp);
        c->gl.BindBuffer(GL_ARRAY_BUFFER, (GLuint)saved);
        e = tmp;
    }
    out[0] = out[1] = out[2] = 0;
    out[3] = 1;
    for (int k = 0; k < arr->size; k++)
        out[k] = component(e, arr->type, k, normalized);
    if (arr->bgra) {
        float r = out[0];
        out[0] = out[2], out[2] = r;
    }
}

static int is_float(GLenum type)
{
    return type == GL_FLOAT || type == GL_DOUBLE;
}

static void feed_element(qgl_context *c, GLint i)
{
    const client_array *a = c->arrays->a;
    float v[4];
    if (a[ARR_COLOR].size) {
        fetch_element(c, &a[ARR_COLOR], i, !is_float(a[ARR_COLOR].type), v);
        qglColor4fv(v);
    }
    if (a[ARR_COLOR2].size) {
        fetch_element(c, &a[ARR_COLOR2], i, !is_float(a[ARR_COLOR2].type), v);
        qglSecondaryColor3fv(v);
    }
    if (a[ARR_NORMAL].size) {
        fetch_element(c, &a[ARR_NORMAL], i, !is_float(a[ARR_NORMAL].type), v);
        qglNormal3fv(v);
    }
    if (a[ARR_FOG].size) {
        fetch_element(c, &a[ARR_FOG], i, 0, v);
        qglFogCoordf(v[0]);
    }
    if (a[ARR_EDGE].size) {
        fetch_element(c, &a[ARR_EDGE], i, 0, v);
        qglEdgeFlag(v[0] != 0);
    }
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
        if (a[ARR_TEX0 + u].size) {
            fetch_element(c, &a[ARR_TEX0 + u], i, 0, v);
            qglMultiTexCoord4fv(GL_TEXTURE0 + (unsigned)u, v);
        }
    if (a[ARR_VERTEX].size) {
        fetch_element(c, &a[ARR_VERTEX], i, 0, v);
        qglVertex4fv(v);
    }
}

QGL_API void qglArrayElement(int i)
{
    CTX_OR_RETURN(c);
    if (c->in_begin != CAPTURE || i < 0 || !read_arrays(c)) {
        qgl__flush(c);
        if (c->gl.ArrayElement)
            c->gl.ArrayElement(i);
        return;
    }
    feed_element(c, i);
}
