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
    const float pos[4] = {x, y, z, w};
    qgl__put_vertex(v, i, (const float (*)[4])c->cur, c->cur_edge, c->given, pos);
    if (c->given & QGL__A_MATERIAL)
        memcpy(v->mat + QGL__MATERIAL_FLOATS * i, c->cur_mat, sizeof c->cur_mat);
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

struct qgl__client_arrays {
    int valid;                 /* read since the capture's qglBegin */
    int ok;                    /* every enabled array has a layout we convert */
    qgl__arrays a;
};

/* A new capture reads the arrays afresh: the application may have changed them. */
static void forget_arrays(qgl_context *c)
{
    if (c->arrays)
        c->arrays->valid = 0;
}

static int read_arrays(qgl_context *c)
{
    if (!c->arrays && !(c->arrays = calloc(1, sizeof *c->arrays)))
        return 0;
    if (!c->arrays->valid) {
        c->arrays->ok = qgl__arrays_read(&c->gl, c->version, c->max_units, &c->arrays->a);
        c->arrays->valid = 1;
    }
    return c->arrays->ok;
}

static void feed_element(qgl_context *c, GLint i)
{
    qgl__arrays e = c->arrays->a; /* this element's copy of buffer data, if any */
    float v[4];
    if (!qgl__arrays_fetch(&c->gl, &e, (size_t)i, (size_t)i)) {
        qgl__arrays_free(&e);
        return;
    }
    for (int a = 0; a < QGL__NATTR; a++)
        if (e.attr[a].size) {
            qgl__array_element(&e.attr[a], (size_t)i, qgl__attribs[a].normalized, 1, v);
            if (!(c->given & (1u << a)) && !join(c, 1u << a))
                continue;
            memcpy(c->cur[a], v, sizeof v);
        }
    if (e.edge.size) {
        qgl__array_element(&e.edge, (size_t)i, 0, 1, v);
        qglEdgeFlag(v[0] != 0);
    }
    if (e.vertex.size) {
        qgl__array_element(&e.vertex, (size_t)i, 0, 1, v);
        qglVertex4fv(v);
    }
    qgl__arrays_free(&e);
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
