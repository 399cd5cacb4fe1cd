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
 * GL_INVALID_OPERATION with no other effect, exactly what the native glBegin would raise. */
#include "gl_internal.h"

enum { OUTSIDE = 0, CAPTURE = 1, FORWARD = 2 };

#define CTX_OR_RETURN(c) \
    qgl_context *c = qgl__tls_current; \
    if (!c) \
        return

/* The driver's current value of one attribute, for back-filling. */
static void driver_current(qgl_context *c, unsigned bit, float out[4])
{
    struct qgl__gl *gl = &c->gl;
    out[0] = out[1] = out[2] = 0;
    out[3] = 1;
    if (bit == QGL__A_COLOR) {
        gl->GetFloatv(GL_CURRENT_COLOR, out);
    } else if (bit == QGL__A_NORMAL) {
        gl->GetFloatv(GL_CURRENT_NORMAL, out);
    } else if (bit == QGL__A_COLOR2) {
        gl->GetFloatv(GL_CURRENT_SECONDARY_COLOR, out);
    } else if (bit == QGL__A_FOG) {
        gl->GetFloatv(GL_CURRENT_FOG_COORD, out);
    } else if (bit == QGL__A_EDGE) {
        GLboolean e = GL_TRUE;
        gl->GetBooleanv(GL_EDGE_FLAG, &e);
        out[0] = e;
    } else {
        int unit = 0;
        while ((unsigned)(QGL__A_TEX0 << unit) != bit)
            unit++;
        GLint active = GL_TEXTURE0;
        gl->GetIntegerv(GL_ACTIVE_TEXTURE, &active);
        gl->ActiveTexture(GL_TEXTURE0 + unit);
        gl->GetFloatv(GL_CURRENT_TEXTURE_COORDS, out);
        gl->ActiveTexture((GLenum)active);
    }
}

/* An attribute given for the first time in this capture: allocate and back-fill it. */
static int join(qgl_context *c, unsigned bit)
{
    qgl__verts *v = &c->cap;
    if (!qgl__verts_reserve(v, v->n, c->given | bit))
        return 0;
    float cur[4];
    driver_current(c, bit, cur);
    for (size_t i = 0; i < v->n; i++) {
        switch (bit) {
        case QGL__A_COLOR: for (int k = 0; k < 4; k++) v->col[4 * i + k] = cur[k]; break;
        case QGL__A_NORMAL: for (int k = 0; k < 3; k++) v->nrm[3 * i + k] = cur[k]; break;
        case QGL__A_COLOR2: for (int k = 0; k < 3; k++) v->col2[3 * i + k] = cur[k]; break;
        case QGL__A_FOG: v->fog[i] = cur[0]; break;
        case QGL__A_EDGE: v->edge[i] = cur[0] != 0; break;
        default:
            for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
                if (bit == (unsigned)(QGL__A_TEX0 << u))
                    for (int k = 0; k < 4; k++)
                        v->tex[u][4 * i + k] = cur[k];
        }
    }
    c->given |= bit;
    return 1;
}

static void copy_attribs(qgl_context *c, qgl__verts *v, size_t i, unsigned g)
{
    if (g & QGL__A_COLOR) {
        float *d = v->col + 4 * i;
        d[0] = c->cur_col[0], d[1] = c->cur_col[1], d[2] = c->cur_col[2], d[3] = c->cur_col[3];
    }
    if (g & QGL__A_NORMAL) {
        float *d = v->nrm + 3 * i;
        d[0] = c->cur_nrm[0], d[1] = c->cur_nrm[1], d[2] = c->cur_nrm[2];
    }
    if (g & QGL__A_COLOR2) {
        float *d = v->col2 + 3 * i;
        d[0] = c->cur_col2[0], d[1] = c->cur_col2[1], d[2] = c->cur_col2[2];
    }
    if (g & QGL__A_FOG)
        v->fog[i] = c->cur_fog;
    if (g & QGL__A_EDGE)
        v->edge[i] = c->cur_edge;
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
        if (g & (QGL__A_TEX0 << u)) {
            float *d = v->tex[u] + 4 * i;
            const float *s = c->cur_tex[u];
            d[0] = s[0], d[1] = s[1], d[2] = s[2], d[3] = s[3];
        }
}

static void capture_vertex(qgl_context *c, float x, float y, float z, float w)
{
    qgl__verts *v = &c->cap;
    if (v->n >= v->cap && !qgl__verts_reserve(v, v->n + 1, c->given))
        return; /* out of memory: the vertex is lost, the application goes on */
    size_t i = v->n++;
    float *p = v->pos + 4 * i;
    p[0] = x, p[1] = y, p[2] = z, p[3] = w;
    if (c->given)
        copy_attribs(c, v, i, c->given);
}

/* ---- begin / end -------------------------------------------------------------------------- */

QGL_API void qglBegin(unsigned mode)
{
    CTX_OR_RETURN(c);
    if (c->in_begin == CAPTURE) {
        c->gl.End(); /* GL_INVALID_OPERATION, as the native nested glBegin */
        return;
    }
    if (c->in_begin == OUTSIDE && (mode == GL_QUADS || mode == GL_QUAD_STRIP)) {
        c->in_begin = CAPTURE;
        c->mode = mode;
        c->cap.n = 0;
        c->given = 0;
        return;
    }
    c->gl.Begin(mode);
    if (c->in_begin == OUTSIDE)
        c->in_begin = FORWARD;
}

/* The driver's current attributes become the last ones given, as after a native glEnd. */
static void set_current(qgl_context *c)
{
    struct qgl__gl *gl = &c->gl;
    unsigned g = c->given;
    if (g & QGL__A_COLOR)
        gl->Color4fv(c->cur_col);
    if (g & QGL__A_NORMAL)
        gl->Normal3fv(c->cur_nrm);
    if (g & QGL__A_COLOR2)
        gl->SecondaryColor3fv(c->cur_col2);
    if (g & QGL__A_FOG)
        gl->FogCoordf(c->cur_fog);
    if (g & QGL__A_EDGE)
        gl->EdgeFlag(c->cur_edge);
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
        if (g & (QGL__A_TEX0 << u))
            gl->MultiTexCoord4fv(GL_TEXTURE0 + u, c->cur_tex[u]);
}

QGL_API void qglEnd(void)
{
    CTX_OR_RETURN(c);
    if (c->in_begin != CAPTURE) {
        c->gl.End(); /* a forwarded primitive, or GL_INVALID_OPERATION outside one */
        c->in_begin = OUTSIDE;
        return;
    }
    c->in_begin = OUTSIDE;
    qgl_topology topo = c->mode == GL_QUADS ? QGL_QUADS : QGL_QUAD_STRIP;
    c->cap.mask = c->given;
    if (qgl__nquads(topo, c->cap.n) > 0)
        qgl__draw(c, &c->cap, topo);
    set_current(c);
}

/* ---- vertices ------------------------------------------------------------------------------- */

#define VERTEX(x, y, z, w, forward) \
    CTX_OR_RETURN(c); \
    if (c->in_begin == CAPTURE) \
        capture_vertex(c, (float)(x), (float)(y), (float)(z), (float)(w)); \
    else \
        forward

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
    } else \
        forward

#define UB(x) ((float)(x) / 255.0f)

static void set4(float *d, float a, float b, float c, float e)
{
    d[0] = a, d[1] = b, d[2] = c, d[3] = e;
}

QGL_API void qglColor3f(float r, float g, float b) { ATTRIB(QGL__A_COLOR, set4(c->cur_col, r, g, b, 1), c->gl.Color3f(r, g, b)); }
QGL_API void qglColor3d(double r, double g, double b) { ATTRIB(QGL__A_COLOR, set4(c->cur_col, (float)r, (float)g, (float)b, 1), c->gl.Color3d(r, g, b)); }
QGL_API void qglColor3ub(unsigned char r, unsigned char g, unsigned char b) { ATTRIB(QGL__A_COLOR, set4(c->cur_col, UB(r), UB(g), UB(b), 1), c->gl.Color3ub(r, g, b)); }
QGL_API void qglColor4f(float r, float g, float b, float a) { ATTRIB(QGL__A_COLOR, set4(c->cur_col, r, g, b, a), c->gl.Color4f(r, g, b, a)); }
QGL_API void qglColor4d(double r, double g, double b, double a) { ATTRIB(QGL__A_COLOR, set4(c->cur_col, (float)r, (float)g, (float)b, (float)a), c->gl.Color4d(r, g, b, a)); }
QGL_API void qglColor4ub(unsigned char r, unsigned char g, unsigned char b, unsigned char a) { ATTRIB(QGL__A_COLOR, set4(c->cur_col, UB(r), UB(g), UB(b), UB(a)), c->gl.Color4ub(r, g, b, a)); }
QGL_API void qglColor3fv(const float *v) { ATTRIB(QGL__A_COLOR, set4(c->cur_col, v[0], v[1], v[2], 1), c->gl.Color3fv(v)); }
QGL_API void qglColor3dv(const double *v) { ATTRIB(QGL__A_COLOR, set4(c->cur_col, (float)v[0], (float)v[1], (float)v[2], 1), c->gl.Color3dv(v)); }
QGL_API void qglColor3ubv(const unsigned char *v) { ATTRIB(QGL__A_COLOR, set4(c->cur_col, UB(v[0]), UB(v[1]), UB(v[2]), 1), c->gl.Color3ubv(v)); }
QGL_API void qglColor4fv(const float *v) { ATTRIB(QGL__A_COLOR, set4(c->cur_col, v[0], v[1], v[2], v[3]), c->gl.Color4fv(v)); }
QGL_API void qglColor4dv(const double *v) { ATTRIB(QGL__A_COLOR, set4(c->cur_col, (float)v[0], (float)v[1], (float)v[2], (float)v[3]), c->gl.Color4dv(v)); }
QGL_API void qglColor4ubv(const unsigned char *v) { ATTRIB(QGL__A_COLOR, set4(c->cur_col, UB(v[0]), UB(v[1]), UB(v[2]), UB(v[3])), c->gl.Color4ubv(v)); }

static void set3(float *d, float a, float b, float e)
{
    d[0] = a, d[1] = b, d[2] = e;
}

QGL_API void qglNormal3f(float x, float y, float z) { ATTRIB(QGL__A_NORMAL, set3(c->cur_nrm, x, y, z), c->gl.Normal3f(x, y, z)); }
QGL_API void qglNormal3d(double x, double y, double z) { ATTRIB(QGL__A_NORMAL, set3(c->cur_nrm, (float)x, (float)y, (float)z), c->gl.Normal3d(x, y, z)); }
QGL_API void qglNormal3fv(const float *v) { ATTRIB(QGL__A_NORMAL, set3(c->cur_nrm, v[0], v[1], v[2]), c->gl.Normal3fv(v)); }
QGL_API void qglNormal3dv(const double *v) { ATTRIB(QGL__A_NORMAL, set3(c->cur_nrm, (float)v[0], (float)v[1], (float)v[2]), c->gl.Normal3dv(v)); }

#define T0 (c->cur_tex[0])
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
    } else \
        forward

QGL_API void qglMultiTexCoord2f(unsigned t, float s, float tt) { MULTI(t, set4(c->cur_tex[u], s, tt, 0, 1), c->gl.MultiTexCoord2f(t, s, tt)); }
QGL_API void qglMultiTexCoord4f(unsigned t, float s, float tt, float r, float q) { MULTI(t, set4(c->cur_tex[u], s, tt, r, q), c->gl.MultiTexCoord4f(t, s, tt, r, q)); }
QGL_API void qglMultiTexCoord2fv(unsigned t, const float *v) { MULTI(t, set4(c->cur_tex[u], v[0], v[1], 0, 1), c->gl.MultiTexCoord2fv(t, v)); }
QGL_API void qglMultiTexCoord4fv(unsigned t, const float *v) { MULTI(t, set4(c->cur_tex[u], v[0], v[1], v[2], v[3]), c->gl.MultiTexCoord4fv(t, v)); }

QGL_API void qglSecondaryColor3f(float r, float g, float b) { ATTRIB(QGL__A_COLOR2, set3(c->cur_col2, r, g, b), c->gl.SecondaryColor3f(r, g, b)); }
QGL_API void qglSecondaryColor3fv(const float *v) { ATTRIB(QGL__A_COLOR2, set3(c->cur_col2, v[0], v[1], v[2]), c->gl.SecondaryColor3fv(v)); }
QGL_API void qglFogCoordf(float f) { ATTRIB(QGL__A_FOG, c->cur_fog = f, c->gl.FogCoordf(f)); }
QGL_API void qglFogCoordfv(const float *f) { ATTRIB(QGL__A_FOG, c->cur_fog = f[0], c->gl.FogCoordfv(f)); }
QGL_API void qglEdgeFlag(unsigned char flag) { ATTRIB(QGL__A_EDGE, c->cur_edge = flag != 0, c->gl.EdgeFlag(flag)); }
QGL_API void qglEdgeFlagv(const unsigned char *flag) { ATTRIB(QGL__A_EDGE, c->cur_edge = flag[0] != 0, c->gl.EdgeFlagv(flag)); }

/* Materials are not captured per vertex: inside a quad the change reaches the driver at once,
 * so it applies to the whole primitive rather than from its vertex on (documented limit). */
QGL_API void qglMaterialf(unsigned face, unsigned pname, float param)
{
    CTX_OR_RETURN(c);
    c->gl.Materialf(face, pname, param);
}

QGL_API void qglMaterialfv(unsigned face, unsigned pname, const float *params)
{
    CTX_OR_RETURN(c);
    c->gl.Materialfv(face, pname, params);
}
