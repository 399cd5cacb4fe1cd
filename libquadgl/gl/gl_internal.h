/* gl_internal.h: the GL layer's private types: dispatch table, captured vertices, context.
 *
 * Every GL entry point the layer uses is a member of struct qgl__gl, named after the GL
 * function without its prefix, filled once per context from a resolver. The list is one
 * X-macro (QGL__GL_FUNCS) so the table, its loader and the names cannot drift apart. Code in
 * this directory never names a gl* symbol: a library that exports those names itself (the
 * preload library) can drive this layer without recursing into itself. GL headers are
 * included for types and enums only. */
#ifndef QGL_GL_INTERNAL_H
#define QGL_GL_INTERNAL_H

#include <GL/gl.h>
#include <GL/glext.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <quadgl/quadgl.h>

/* X(return type, name without "gl", parameter list) */
#define QGL__GL_FUNCS(X) \
    X(void, Begin, (GLenum)) \
    X(void, End, (void)) \
    X(void, Vertex2f, (GLfloat, GLfloat)) \
    X(void, Vertex2d, (GLdouble, GLdouble)) \
    X(void, Vertex2i, (GLint, GLint)) \
    X(void, Vertex2s, (GLshort, GLshort)) \
    X(void, Vertex3f, (GLfloat, GLfloat, GLfloat)) \
    X(void, Vertex3d, (GLdouble, GLdouble, GLdouble)) \
    X(void, Vertex3i, (GLint, GLint, GLint)) \
    X(void, Vertex3s, (GLshort, GLshort, GLshort)) \
    X(void, Vertex4f, (GLfloat, GLfloat, GLfloat, GLfloat)) \
    X(void, Vertex4d, (GLdouble, GLdouble, GLdouble, GLdouble)) \
    X(void, Vertex4i, (GLint, GLint, GLint, GLint)) \
    X(void, Vertex4s, (GLshort, GLshort, GLshort, GLshort)) \
    X(void, Vertex2fv, (const GLfloat *)) \
    X(void, Vertex2dv, (const GLdouble *)) \
    X(void, Vertex2iv, (const GLint *)) \
    X(void, Vertex2sv, (const GLshort *)) \
    X(void, Vertex3fv, (const GLfloat *)) \
    X(void, Vertex3dv, (const GLdouble *)) \
    X(void, Vertex3iv, (const GLint *)) \
    X(void, Vertex3sv, (const GLshort *)) \
    X(void, Vertex4fv, (const GLfloat *)) \
    X(void, Vertex4dv, (const GLdouble *)) \
    X(void, Vertex4iv, (const GLint *)) \
    X(void, Vertex4sv, (const GLshort *)) \
    X(void, Color3f, (GLfloat, GLfloat, GLfloat)) \
    X(void, Color3d, (GLdouble, GLdouble, GLdouble)) \
    X(void, Color3ub, (GLubyte, GLubyte, GLubyte)) \
    X(void, Color4f, (GLfloat, GLfloat, GLfloat, GLfloat)) \
    X(void, Color4d, (GLdouble, GLdouble, GLdouble, GLdouble)) \
    X(void, Color4ub, (GLubyte, GLubyte, GLubyte, GLubyte)) \
    X(void, Color3fv, (const GLfloat *)) \
    X(void, Color3dv, (const GLdouble *)) \
    X(void, Color3ubv, (const GLubyte *)) \
    X(void, Color4fv, (const GLfloat *)) \
    X(void, Color4dv, (const GLdouble *)) \
    X(void, Color4ubv, (const GLubyte *)) \
    X(void, Normal3f, (GLfloat, GLfloat, GLfloat)) \
    X(void, Normal3d, (GLdouble, GLdouble, GLdouble)) \
    X(void, Normal3fv, (const GLfloat *)) \
    X(void, Normal3dv, (const GLdouble *)) \
    X(void, TexCoord1f, (GLfloat)) \
    X(void, TexCoord2f, (GLfloat, GLfloat)) \
    X(void, TexCoord3f, (GLfloat, GLfloat, GLfloat)) \
    X(void, TexCoord4f, (GLfloat, GLfloat, GLfloat, GLfloat)) \
    X(void, TexCoord1d, (GLdouble)) \
    X(void, TexCoord2d, (GLdouble, GLdouble)) \
    X(void, TexCoord3d, (GLdouble, GLdouble, GLdouble)) \
    X(void, TexCoord4d, (GLdouble, GLdouble, GLdouble, GLdouble)) \
    X(void, TexCoord2fv, (const GLfloat *)) \
    X(void, TexCoord3fv, (const GLfloat *)) \
    X(void, TexCoord4fv, (const GLfloat *)) \
    X(void, TexCoord2dv, (const GLdouble *)) \
    X(void, MultiTexCoord2f, (GLenum, GLfloat, GLfloat)) \
    X(void, MultiTexCoord4f, (GLenum, GLfloat, GLfloat, GLfloat, GLfloat)) \
    X(void, MultiTexCoord2fv, (GLenum, const GLfloat *)) \
    X(void, MultiTexCoord4fv, (GLenum, const GLfloat *)) \
    X(void, SecondaryColor3f, (GLfloat, GLfloat, GLfloat)) \
    X(void, SecondaryColor3fv, (const GLfloat *)) \
    X(void, FogCoordf, (GLfloat)) \
    X(void, FogCoordfv, (const GLfloat *)) \
    X(void, EdgeFlag, (GLboolean)) \
    X(void, EdgeFlagv, (const GLboolean *)) \
    X(void, Materialf, (GLenum, GLenum, GLfloat)) \
    X(void, Materialfv, (GLenum, GLenum, const GLfloat *)) \
    X(const GLubyte *, GetString, (GLenum)) \
    X(void, GetIntegerv, (GLenum, GLint *)) \
    X(void, GetFloatv, (GLenum, GLfloat *)) \
    X(void, GetDoublev, (GLenum, GLdouble *)) \
    X(void, GetBooleanv, (GLenum, GLboolean *)) \
    X(GLboolean, IsEnabled, (GLenum)) \
    X(void, GetTexEnviv, (GLenum, GLenum, GLint *)) \
    X(void, GetTexGeniv, (GLenum, GLenum, GLint *)) \
    X(void, GetLightfv, (GLenum, GLenum, GLfloat *)) \
    X(void, GetMaterialfv, (GLenum, GLenum, GLfloat *)) \
    X(void, GetTexLevelParameteriv, (GLenum, GLint, GLenum, GLint *)) \
    X(GLenum, GetError, (void)) \
    X(void, ActiveTexture, (GLenum)) \
    X(void, ClientActiveTexture, (GLenum)) \
    X(void, VertexPointer, (GLint, GLenum, GLsizei, const void *)) \
    X(void, ColorPointer, (GLint, GLenum, GLsizei, const void *)) \
    X(void, NormalPointer, (GLenum, GLsizei, const void *)) \
    X(void, TexCoordPointer, (GLint, GLenum, GLsizei, const void *)) \
    X(void, EdgeFlagPointer, (GLsizei, const void *)) \
    X(void, EnableClientState, (GLenum)) \
    X(void, DisableClientState, (GLenum)) \
    X(void, DrawArrays, (GLenum, GLint, GLsizei)) \
    X(void, DrawElements, (GLenum, GLsizei, GLenum, const void *))

/* Entry points from GL 1.4 - 3.2, and those only the calibration (calibrate.c) needs; absent
 * ones are NULL, which the layer checks. */
#define QGL__GL_FUNCS_OPT(X) \
    X(void, SecondaryColorPointer, (GLint, GLenum, GLsizei, const void *)) \
    X(void, FogCoordPointer, (GLenum, GLsizei, const void *)) \
    X(const GLubyte *, GetStringi, (GLenum, GLuint)) \
    X(void, GenBuffers, (GLsizei, GLuint *)) \
    X(void, DeleteBuffers, (GLsizei, const GLuint *)) \
    X(void, BindBuffer, (GLenum, GLuint)) \
    X(void, BufferData, (GLenum, GLsizeiptr, const void *, GLenum)) \
    X(void, BufferSubData, (GLenum, GLintptr, GLsizeiptr, const void *)) \
    X(void, GenVertexArrays, (GLsizei, GLuint *)) \
    X(void, DeleteVertexArrays, (GLsizei, const GLuint *)) \
    X(void, BindVertexArray, (GLuint)) \
    X(GLuint, CreateShader, (GLenum)) \
    X(void, ShaderSource, (GLuint, GLsizei, const GLchar *const *, const GLint *)) \
    X(void, CompileShader, (GLuint)) \
    X(void, GetShaderiv, (GLuint, GLenum, GLint *)) \
    X(void, GetShaderInfoLog, (GLuint, GLsizei, GLsizei *, GLchar *)) \
    X(void, DeleteShader, (GLuint)) \
    X(GLuint, CreateProgram, (void)) \
    X(void, AttachShader, (GLuint, GLuint)) \
    X(void, LinkProgram, (GLuint)) \
    X(void, GetProgramiv, (GLuint, GLenum, GLint *)) \
    X(void, GetProgramInfoLog, (GLuint, GLsizei, GLsizei *, GLchar *)) \
    X(void, DeleteProgram, (GLuint)) \
    X(void, UseProgram, (GLuint)) \
    X(GLint, GetUniformLocation, (GLuint, const GLchar *)) \
    X(void, Uniform1i, (GLint, GLint)) \
    X(void, Uniform2f, (GLint, GLfloat, GLfloat)) \
    X(void, BindAttribLocation, (GLuint, GLuint, const GLchar *)) \
    X(void, VertexAttrib4fv, (GLuint, const GLfloat *)) \
    X(void, GetVertexAttribfv, (GLuint, GLenum, GLfloat *)) \
    X(void, VertexAttribPointer, (GLuint, GLint, GLenum, GLboolean, GLsizei, const void *)) \
    X(void, EnableVertexAttribArray, (GLuint)) \
    X(void, DisableVertexAttribArray, (GLuint)) \
    X(void, ArrayElement, (GLint)) \
    X(void, GetPointerv, (GLenum, void **)) \
    X(void, GetBufferSubData, (GLenum, GLintptr, GLsizeiptr, void *)) \
    X(void, BufferStorage, (GLenum, GLsizeiptr, const void *, GLbitfield)) \
    X(void *, MapBufferRange, (GLenum, GLintptr, GLsizeiptr, GLbitfield)) \
    X(GLboolean, UnmapBuffer, (GLenum)) \
    X(void, MultiDrawArrays, (GLenum, const GLint *, const GLsizei *, GLsizei)) \
    X(void, MultiDrawElements, (GLenum, const GLsizei *, GLenum, const void *const *, GLsizei)) \
    X(GLsync, FenceSync, (GLenum, GLbitfield)) \
    X(GLenum, ClientWaitSync, (GLsync, GLbitfield, GLuint64)) \
    X(void, DeleteSync, (GLsync)) \
    X(void, Enable, (GLenum)) \
    X(void, Disable, (GLenum)) \
    X(void, Finish, (void)) \
    X(void, Viewport, (GLint, GLint, GLsizei, GLsizei)) \
    X(void, MatrixMode, (GLenum)) \
    X(void, LoadIdentity, (void)) \
    X(void, LoadMatrixf, (const GLfloat *)) \
    X(GLboolean, IsEnabledi, (GLenum, GLuint)) \
    X(void, Enablei, (GLenum, GLuint)) \
    X(void, Disablei, (GLenum, GLuint)) \
    X(void, ColorMaski, (GLuint, GLboolean, GLboolean, GLboolean, GLboolean)) \
    X(void, GetBooleani_v, (GLenum, GLuint, GLboolean *)) \
    X(void, ViewportIndexedf, (GLuint, GLfloat, GLfloat, GLfloat, GLfloat)) \
    X(void, GetFloati_v, (GLenum, GLuint, GLfloat *)) \
    X(void, PolygonMode, (GLenum, GLenum)) \
    X(void, ShadeModel, (GLenum)) \
    X(void, ColorMask, (GLboolean, GLboolean, GLboolean, GLboolean)) \
    X(void, GenFramebuffers, (GLsizei, GLuint *)) \
    X(void, DeleteFramebuffers, (GLsizei, const GLuint *)) \
    X(void, BindFramebuffer, (GLenum, GLuint)) \
    X(void, GenRenderbuffers, (GLsizei, GLuint *)) \
    X(void, DeleteRenderbuffers, (GLsizei, const GLuint *)) \
    X(void, BindRenderbuffer, (GLenum, GLuint)) \
    X(void, RenderbufferStorage, (GLenum, GLenum, GLsizei, GLsizei)) \
    X(void, FramebufferRenderbuffer, (GLenum, GLenum, GLenum, GLuint)) \
    X(GLenum, CheckFramebufferStatus, (GLenum))

#define QGL__MEMBER(ret, name, params) ret (*name) params;
struct qgl__gl {
    QGL__GL_FUNCS(QGL__MEMBER)
    QGL__GL_FUNCS_OPT(QGL__MEMBER)
};
#undef QGL__MEMBER

/* Fill the table; returns 0 when a required entry point is missing. */
int qgl__gl_load(struct qgl__gl *gl, void *(*get_proc)(const char *));

/* ---- captured vertices: one array per attribute (structure of arrays) ------------------- */

/* The attributes a vertex carries besides its position, one row each: X(name, floats stored
 * per vertex, the GL_CURRENT_* value, the client array, integer data normalized). Everything
 * that handles attributes one by one (capture, conversion, upload, replay, current values)
 * walks this table; the texture units' rows differ only by unit. */
#define QGL__ATTRIBS(X) \
    X(COLOR, 4, GL_CURRENT_COLOR, GL_COLOR_ARRAY, 1) \
    X(NORMAL, 3, GL_CURRENT_NORMAL, GL_NORMAL_ARRAY, 1) \
    X(COLOR2, 3, GL_CURRENT_SECONDARY_COLOR, GL_SECONDARY_COLOR_ARRAY, 1) \
    X(FOG, 1, GL_CURRENT_FOG_COORD, GL_FOG_COORD_ARRAY, 0) \
    X(TEX0, 4, GL_CURRENT_TEXTURE_COORDS, GL_TEXTURE_COORD_ARRAY, 0) \
    X(TEX1, 4, GL_CURRENT_TEXTURE_COORDS, GL_TEXTURE_COORD_ARRAY, 0) \
    X(TEX2, 4, GL_CURRENT_TEXTURE_COORDS, GL_TEXTURE_COORD_ARRAY, 0) \
    X(TEX3, 4, GL_CURRENT_TEXTURE_COORDS, GL_TEXTURE_COORD_ARRAY, 0)

#define QGL__AT_ENUM(name, floats, current, array, normalized) QGL__AT_##name,
enum { QGL__ATTRIBS(QGL__AT_ENUM) QGL__NATTR };
#undef QGL__AT_ENUM

typedef struct qgl__attrib_info {
    int floats;
    GLenum current, array;
    int normalized;
    int unit;                 /* texture unit, -1 for the others */
} qgl__attrib_info;
extern const qgl__attrib_info qgl__attribs[QGL__NATTR];

/* Attribute bits: bit a is row a of QGL__ATTRIBS; edge flags and materials follow. */
enum {
    QGL__A_COLOR = 1 << QGL__AT_COLOR,
    QGL__A_NORMAL = 1 << QGL__AT_NORMAL,
    QGL__A_COLOR2 = 1 << QGL__AT_COLOR2,
    QGL__A_FOG = 1 << QGL__AT_FOG,
    QGL__A_TEX0 = 1 << QGL__AT_TEX0, /* unit u is QGL__A_TEX0 << u */
    QGL__A_ATTRIBS = (1 << QGL__NATTR) - 1,
    QGL__A_EDGE = 1 << QGL__NATTR,
    QGL__A_MATERIAL = 1 << (QGL__NATTR + 1)
};
/* Materials given per vertex inside qglBegin/qglEnd: QGL__MATERIAL_FLOATS per vertex, the
 * vec4s front ambient, diffuse, specular, emission, back the same, then the shininesses. */
enum { QGL__MATERIAL_FLOATS = 36 };

typedef struct qgl__verts {
    size_t n, cap;
    unsigned mask;            /* attributes present (QGL__A_*) */
    unsigned alloc;           /* arrays allocated */
    float *pos;               /* 4 per vertex, object coordinates */
    union {
        struct {
            float *col;       /* 4 */
            float *nrm;       /* 3 */
            float *col2;      /* 3 */
            float *fog;       /* 1 */
            float *tex[QGL_MAX_TEXUNITS]; /* 4 */
        };
        float *attr[QGL__NATTR]; /* the same arrays by row of QGL__ATTRIBS */
    };
    unsigned char *edge;      /* 1 */
    float *mat;               /* QGL__MATERIAL_FLOATS */
} qgl__verts;

/* arrays.c: a fixed-function client array as the driver describes it (size 0: disabled). */
typedef struct qgl__array {
    int size;
    GLenum type;
    int bgra;
    size_t stride;
    const unsigned char *ptr;  /* element 0 in client memory, or the offset in buffer */
    GLuint buffer;
    unsigned char *copy;       /* qgl__arrays_fetch's copy of buffer data */
} qgl__array;
typedef struct qgl__arrays {
    qgl__array vertex, edge, attr[QGL__NATTR];
} qgl__arrays;
/* The enabled arrays (units: texture units the context has); 0 when one has a layout we do not
 * convert. */
int qgl__arrays_read(struct qgl__gl *gl, int version, int units, qgl__arrays *out);
/* Copies elements [lo, hi] of the arrays in buffer objects back to memory; 0 on failure. */
int qgl__arrays_fetch(struct qgl__gl *gl, qgl__arrays *s, size_t lo, size_t hi);
void qgl__arrays_free(qgl__arrays *s);
/* Element i (in memory) into out, GL's defaults past its size; immediate: converted as the
 * glArrayElement path converts it, else as a draw from arrays fetches it. */
void qgl__array_element(const qgl__array *arr, size_t i, int normalized, int immediate, float out[4]);

/* A glMaterial given inside glBegin/glEnd before vertex `vertex` of a batch. */
typedef struct qgl__change {
    uint32_t vertex;
    GLenum face, pname;
    float v[4];
} qgl__change;

/* The materials of GL_QUADS drawn as the driver's display lists draw them, the triangles 0-1-3,
 * 1-2-3 of each quad: every vertex is lit with the material in force when it was given, so
 * before each vertex given again or early, every component the changes set is given anew
 * (qgl__matrun_emit), as the driver's lists keep a material per vertex. */
typedef struct qgl__matrun {
    const qgl__change *chg;
    size_t nchg, next;        /* the changes, the first not yet in cur */
    unsigned given;           /* components the changes set (draw.c's material_bits) */
    float cur[QGL__MATERIAL_FLOATS];       /* as of the last corner passed */
    float corner[4][QGL__MATERIAL_FLOATS]; /* the current quad's corners' */
} qgl__matrun;
/* Reads the driver's values of the components the changes set (outside glBegin/glEnd); with gl
 * NULL nothing is read, for qgl__matrun_to only. */
void qgl__matrun_start(struct qgl__gl *gl, qgl__matrun *r, const qgl__change *chg, size_t nchg);
/* Whether the changes before vertex first (a primitive's first) set every component the changes
 * set: then no vertex of the primitive takes a material from before it. */
int qgl__matrun_leading(const qgl__change *chg, size_t nchg, size_t first);
/* The materials of the quad of vertices first .. first + 3 (quads in order). */
void qgl__matrun_quad(qgl__matrun *r, size_t first);
/* Gives the driver corner c's materials (inside glBegin/glEnd, before its vertex). */
void qgl__matrun_emit(struct qgl__gl *gl, const qgl__matrun *r, int corner);
/* Vertices given in order: the driver gets the changes due up to vertex (SIZE_MAX: all, after
 * glEnd) as they were made. */
void qgl__matrun_to(struct qgl__gl *gl, qgl__matrun *r, size_t vertex);

/* The driver's current value of attribute a is set to v (qgl__attribs[a].floats of them). */
void qgl__set_current(struct qgl__gl *gl, int a, const float *v);
/* Our VAO's fixed-function arrays at offsets into the bound GL_ARRAY_BUFFER (floats, tightly
 * packed): positions (4) at pos, the attributes of mask at off[a], edge flags (QGL__A_EDGE in
 * mask) at edge; the other arrays disabled. */
void qgl__point_arrays(qgl_context *ctx, unsigned mask, size_t pos, const size_t off[QGL__NATTR], size_t edge);

int qgl__verts_reserve(qgl__verts *v, size_t n, unsigned mask);
void qgl__verts_free(qgl__verts *v);
/* Vertex j of s (its position and every attribute in s->mask) to vertex i of d, which has room;
 * d may be s (i != j). */
void qgl__verts_copy(qgl__verts *d, size_t i, const qgl__verts *s, size_t j);
/* Vertices j .. j + n - 1 of s to i .. i + n - 1 of d (distinct arrays). */
void qgl__verts_copy_range(qgl__verts *d, size_t i, const qgl__verts *s, size_t j, size_t n);
/* The nq quads of the strip at vertex j of s as GL_QUADS at vertex i of d (4 nq vertices of
 * room): corner c of each takes the strip quad's corner (c + shift) & 3, in the strip's corner
 * order v2k, v2k+1, v2k+3, v2k+2 (shift 0 keeps the diagonal the driver splits a strip quad
 * on, shift 3 puts the provoking vertex v2k+3 last, where GL_QUADS has it). */
void qgl__verts_unroll(qgl__verts *d, size_t i, const qgl__verts *s, size_t j, size_t nq, int shift);

/* Vertex i of v from pos and, for each attribute in mask, its row of cur (and the edge flag):
 * the capture's per-vertex work. Row by row of the table, sizes as constants, so that each copy
 * is a move or two. */
static inline __attribute__((always_inline)) void qgl__put_vertex(qgl__verts *v, size_t i, const float (*cur)[4],
                                                                  unsigned char edge, unsigned mask, const float pos[4])
{
    memcpy(v->pos + 4 * i, pos, 4 * sizeof(float));
#define QGL__PUT(name, floats, current, array, normalized)                                                             \
    if (mask & (1u << QGL__AT_##name))                                                                               \
        memcpy(v->attr[QGL__AT_##name] + (size_t)(floats) * i, cur[QGL__AT_##name], (floats) * sizeof(float));
    QGL__ATTRIBS(QGL__PUT)
#undef QGL__PUT
    if (mask & QGL__A_EDGE)
        v->edge[i] = edge;
}

/* ---- the fixed-function state a generated program reproduces (its key) ------------------ */

/* Texture targets, texgen modes, env modes and base-format classes of a unit's key. */
enum { QGL__T_NONE, QGL__T_1D, QGL__T_2D, QGL__T_3D, QGL__T_CUBE, QGL__T_RECT };
enum { QGL__G_NONE, QGL__G_OBJECT, QGL__G_EYE, QGL__G_SPHERE, QGL__G_REFLECT, QGL__G_NORMAL };
enum { QGL__E_MODULATE, QGL__E_REPLACE, QGL__E_DECAL, QGL__E_BLEND, QGL__E_ADD, QGL__E_COMBINE };
/* RGBA also stands for LUMINANCE_ALPHA, RGB for LUMINANCE, RED, RG (the sampler's alpha is 1). */
enum { QGL__F_RGBA, QGL__F_RGB, QGL__F_ALPHA, QGL__F_INTENSITY };
/* COMBINE functions, sources (QGL__S_UNIT0 + n: GL_TEXTUREn) and operands. */
enum { QGL__C_REPLACE, QGL__C_MODULATE, QGL__C_ADD, QGL__C_ADD_SIGNED, QGL__C_INTERPOLATE, QGL__C_SUBTRACT,
       QGL__C_DOT3_RGB, QGL__C_DOT3_RGBA };
enum { QGL__S_TEXTURE, QGL__S_CONSTANT, QGL__S_PRIMARY, QGL__S_PREVIOUS, QGL__S_UNIT0 };
enum { QGL__O_COLOR, QGL__O_ONE_MINUS_COLOR, QGL__O_ALPHA, QGL__O_ONE_MINUS_ALPHA };
enum { QGL__FOG_OFF, QGL__FOG_LINEAR, QGL__FOG_EXP, QGL__FOG_EXP2 };
/* Colour material: faces are bits (front 1, back 2), modes the property tracked. */
enum { QGL__CM_EMISSION = 1, QGL__CM_AMBIENT, QGL__CM_DIFFUSE, QGL__CM_SPECULAR, QGL__CM_AMBIENT_AND_DIFFUSE };

/* One texture unit. Fields that cannot affect the picture are zero (a disabled unit is all
 * zero, the COMBINE fields are zero unless env is COMBINE, arguments a function does not read
 * are zero), so equal pictures give equal keys. */
typedef struct qgl__unit_key {
    uint8_t target, env, format, pad;
    uint8_t gen[4];                     /* s, t, r, q */
    uint8_t func_rgb, func_a, shift_rgb, shift_a; /* COMBINE; scale = 1 << shift */
    uint8_t src_rgb[3], src_a[3], op_rgb[3], op_a[3];
} qgl__unit_key;

/* Key flags. */
enum {
    QGL__KF_FLAT = 1 << 0,
    QGL__KF_DEPTH = 1 << 1,        /* non-planar: gl_FragDepth from the screen weights */
    QGL__KF_DISCARD = 1 << 2,      /* corners behind the eye: kill fragments outside the quad */
    QGL__KF_LIGHTING = 1 << 3,
    QGL__KF_TWO_SIDE = 1 << 4,
    QGL__KF_LOCAL_VIEWER = 1 << 5,
    QGL__KF_SEPARATE_SPEC = 1 << 6,
    QGL__KF_NORMALIZE = 1 << 7,
    QGL__KF_RESCALE = 1 << 8,
    QGL__KF_COLOR_SUM = 1 << 9,    /* unlit: add the secondary colour */
    QGL__KF_FOG_DEPTH = 1 << 10,   /* fog source is the fragment depth (else the fog coordinate) */
    QGL__KF_MATERIAL = 1 << 11,    /* materials given per vertex (generic attributes) */
    QGL__KF_CLIPPED = 1 << 12,     /* the driver may clip: g perspective-interpolated */
    QGL__KF_PLANE = 1 << 13        /* view-invariant weights in the quad's plane: planar (no
                                      DEPTH), the cover in the plane and the in-plane position
                                      as a varying; non-planar (DEPTH), the ray against the
                                      bilinear patch per fragment, its projection weighed */
};

typedef struct qgl__key {
    uint32_t flags;
    uint8_t lights, light_pos, light_spot; /* bit i: light i enabled, positional, a spot */
    uint8_t cm_face, cm_mode;      /* colour material (QGL__CM_*; 0: off) */
    uint8_t fog, clip, corner;     /* fog mode, enabled clip planes (bits), flat provoking corner */
    uint8_t nunits, pad[3];        /* units 0 .. nunits-1 have a target */
    qgl__unit_key unit[QGL_MAX_TEXUNITS];
} qgl__key;

/* Generic attribute locations of per-vertex materials (QGL__KF_MATERIAL): front ambient,
 * diffuse, specular, emission, then back, then (front shininess, back shininess). */
enum { QGL__LOC_MATERIAL = 6, QGL__NMATERIAL = 9 };

/* ---- GL state the paths need, queried at each draw --------------------------------------- */

/* Groups of the state, re-read only when marked changed by an owner that sees every GL call
 * (qgl__state_track); otherwise every draw reads all of it. */
enum {
    QGL__D_XFORM = 1 << 0,  /* matrices, viewport */
    QGL__D_RASTER = 1 << 1, /* render and polygon modes, program, shade model, active texture unit,
                               polygon offset, vertex colour clamping, provoking vertex */
    QGL__D_FFP = 1 << 2,    /* the fixed-function key: textures, lighting, fog, clip planes, ... */
    QGL__D_BIND = 1 << 3,   /* vertex array and array buffer bindings, client active texture */
    QGL__D_ORDER = 1 << 4,  /* what decides whether drawing order shows: depth test, function and
                               writes, the draw framebuffer's depth bits, blending, stencil, logic op */
    QGL__D_TEX = 1 << 5,      /* the textures bound to the units (their formats and sizes) */
    QGL__D_TEXIMAGE = 1 << 6, /* some texture's level 0 may have changed format or size */
    QGL__D_LIGHT = 1 << 7,    /* material values (light values change the FFP group) */
    QGL__D_ALL = (1 << 8) - 1
};

/* What the key and the planner need of a texture's level 0, kept by name (state.c): asked of
 * the driver once per image, not at every bind (GetTexLevelParameter makes some drivers
 * validate their whole state). */
enum { QGL__TEX_FACTS = 64 };
typedef struct qgl__texfacts {
    GLuint name;
    uint8_t target, used, ok, format; /* ok: not a depth texture; format: QGL__F_* */
    float size[3];
} qgl__texfacts;

/* The transform group (QGL__D_XFORM), which only planning and the smooth paths read: a draw
 * asks for it with qgl__state_xform, so it is read from the driver only then. */
typedef struct qgl__xform {
    GLint viewport[4];
    double mvp[16];           /* projection * modelview, column-major */
    double modelview[16];
    double texmat[QGL_MAX_TEXUNITS][16]; /* texture matrices */
    unsigned texmat_identity; /* bit u: unit u's texture matrix is the identity (the usual case:
                                 the planner reads the coordinates as they are) */
} qgl__xform;

typedef struct qgl__state {
    GLint program, render_mode, polygon_mode[2], shade_model, active_texture;
    GLint vao, array_buffer, client_texture; /* bindings a draw puts back */
    int clamp;                /* GL_CLAMP_VERTEX_COLOR */
    int first_vertex_pv;      /* GL_FIRST_VERTEX_CONVENTION, and quads follow it */
    int ffp_ok;               /* the key describes the state (the programs can reproduce it) */
    int arb_program;          /* an ARB vertex or fragment program or an ATI fragment shader is
                                 enabled (FFP group) */
    GLint pipeline;           /* the program pipeline object bound (RASTER group) */
    int own_pipeline;         /* the application's own programs replace fixed function (a GLSL
                                 program or pipeline, ARB programs): the driver draws its quads
                                 as they are, since no path of ours runs its programs */
    qgl__xform xf;            /* valid once the draw has asked (qgl__state_xform) */
    int texture2d;            /* unit 0 samples GL_TEXTURE_2D */
    int tex_replace;          /* env mode REPLACE (else MODULATE) */
    int tex_no_alpha;         /* the texture's base format has no alpha (REPLACE keeps Af) */
    int simple;               /* within issue 4's subset (colour, one 2D MODULATE/REPLACE unit) */
    int modelled;             /* the shader path reproduces every enabled feature */
    int nonaffine;            /* per-vertex work whose result is not affine in the captured
                                 attributes (smooth lighting, sphere map...): never split exactly */
    int polygon_offset;       /* GL_POLYGON_OFFSET_FILL (needs rasterizer depth) */
    int blend_free;           /* no blending, stencil test or logic op (ORDER group): a pixel a
                                 triangle edge covers twice or not at all shows as no more than
                                 the colour one triangle or the other gives it */
    int order_free;           /* the nearest fragment wins whatever the order quads are drawn in
                                 (depth tested against a depth buffer, written, no blending,
                                 stencil or logic op): a batch may be drawn grouped by path */
    int pv_material;          /* lit quads with per-vertex materials: the split draws a run of
                                 quads with one material, so only quads whose corners share one
                                 may take it */
    int quad_materials;       /* with pv_material: the batch's material changes all fall between
                                 quads, so every quad's corners share one (no comparison) */
    int lit_cpu;              /* smooth fixed-function lighting alone makes the per-vertex work
                                 non-affine: light.c computes the corners' colours */
    int lit_by_inputs;        /* the per-vertex work is a function of the captured attributes
                                 alone (directional lights, infinite viewer, no texgen reading
                                 the eye position): where corners with equal attributes group
                                 affinely (QGL__F_GROUPED) its result is affine, split exactly */
    qgl__key ffp;             /* the fixed-function part of the program key */
    float texsize[QGL_MAX_TEXUNITS][3]; /* level 0 width, height, depth of each enabled unit's
                                 texture (1 for a rectangle texture: its coordinates are texels) */
    double fog_slope;         /* bound on |d fog factor / d fog coordinate| (fog from the
                                 coordinate; 0 otherwise) */
} qgl__state;

/* light.c: light and material values as the driver holds them, read when the planner first
 * needs them after a change, and the normal matrix. */
typedef struct qgl__lightval {
    GLfloat amb[4], dif[4], spe[4], pos[4], dir[4], exponent, cos_cutoff, att[3];
    /* per vertex the same, so worked out when read: the position over its w (positional), the
     * unit direction to the light and its half vector for an infinite viewer (directional),
     * the unit spot direction */
    double at[3], to[3], half[3], spot[3];
} qgl__lightval;
/* How often a test that only saves time where it passes has passed lately: tested and passed
 * halve together past a window, so older results count half at each halving; skipped counts
 * the tests left out, so that one in several is made all the same. */
typedef struct qgl__rate {
    unsigned tested, passed, skipped;
} qgl__rate;
typedef struct qgl__lightvals {
    int lights_valid, materials_valid, normal_valid, normal_ok, current_valid;
    GLfloat cur_normal[4], cur_colour[4]; /* the driver's current values, read once per draw */
    qgl__lightval light[8];
    GLfloat model_ambient[4];
    GLfloat mat[2][4][4];     /* front, back: emission, ambient, diffuse, specular */
    GLfloat shininess[2];
    double nmat[3][3], rescale;
} qgl__lightvals;

/* Whether corners idx of v (per-vertex materials) have one material: the split, which draws
 * a quad with its first corner's, then lights it as the shader path does. */
int qgl__same_material(const qgl__verts *v, const size_t idx[4]);
int qgl__material_set(qgl_context *ctx, GLenum face, GLenum pname, const float v[4]);

/* Per corner: primary RGBA, secondary RGB. */
enum { QGL__LIT_FLOATS = 7 };

/* The lit colours of corners idx of v, per face (front, then back under two-sided lighting):
 * the number of faces, 0 where they cannot be computed (a singular model-view). Per-vertex
 * materials are taken from the first corner: the caller has checked that all four share it. */
int qgl__lit_colours(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4],
                     float out[2][4 * QGL__LIT_FLOATS]);

/* ---- programs ------------------------------------------------------------------------------ */

/* Issue 4's key bits, still what the GLSL 1.20 path (glsl120.c) reads; QGL__K_EXTRA marks a
 * state beyond that subset. */
enum {
    QGL__K_COLOR = 1 << 0,    /* per-vertex colour (else the current colour, constant) */
    QGL__K_FLAT = 1 << 1,
    QGL__K_TEX = 1 << 2,
    QGL__K_REPLACE = 1 << 3,
    QGL__K_NOALPHA = 1 << 4,
    QGL__K_DEPTH = 1 << 5,    /* non-planar: write gl_FragDepth from the screen weights */
    QGL__K_DISCARD = 1 << 6,  /* corners behind the eye: cover is the clipped split, kill outside */
    QGL__K_CORNER_SHIFT = 7,  /* 2 bits: the provoking corner */
    QGL__K_EXTRA = 1 << 9,
    QGL__K_PLANE = 1 << 10    /* view-invariant weights, as QGL__KF_PLANE */
};

#define QGL__MAX_PROGRAMS 64

/* stream.c: the buffer batches are copied into for the driver (see there). */
typedef struct qgl__stream_buf {
    GLuint buf;
    unsigned char *map;       /* persistent mapping, or NULL */
    size_t size;
    GLsync done;              /* retired: signalled once the driver has read it all */
} qgl__stream_buf;

enum { QGL__STREAM_POOL = 4 };

typedef struct qgl__stream {
    GLuint buf;
    unsigned char *map;       /* persistent mapping, or NULL */
    size_t size, head;        /* bytes in buf, bytes used */
    int persistent;           /* buffer storage available */
    qgl__stream_buf pool[QGL__STREAM_POOL]; /* retired buffers, oldest first */
    int npool;
} qgl__stream;

struct qgl_context {
    struct qgl__gl gl;
    qgl_method method;
    float tolerance_px, invisible_area_px;
    float split_error;        /* desc.split_error: scale of the invisible-split budgets, 0 = 1,
                                 negative = only exact splits (and the area rule) */
    int version;              /* GL version * 10 (e.g. 45) */
    int shader_level;         /* 0, 120 (glsl120.c), 150 (shader.c); before the first smooth quad
                                 the level the driver promises, not yet compiled (ready) */
    int ready;                /* context.c: the shader path compiled and the costs measured */
    int glsl120_ok;
    int has_vao;              /* GL >= 3.0: VAO + VBO drawing (else immediate replay) */
    int gl_gone;              /* being freed while its GL context is gone or current elsewhere:
                                 no GL call (qgl__gl_forget) */
    int quads_follow_pv;
    int has_arb_vp, has_arb_fp, has_ati_fs, has_pipelines; /* programs that replace fixed function */
    GLint max_units, max_clip_planes;
    qgl_gl_stats_t stats;

    /* immediate capture */
    int in_begin;             /* 0 outside, 1 capturing quads, 2 forwarding another primitive */
    GLenum mode;
    qgl__verts cap;
    unsigned given;           /* attributes given since qglBegin */
    float cur[QGL__NATTR][4]; /* the values the next vertex takes, by attribute */
    unsigned char cur_edge;
    float cur_mat[QGL__MATERIAL_FLOATS];

    /* drawing */
    GLuint vao;               /* ours: its arrays point into the stream buffer */
    unsigned vao_arrays;      /* its arrays enabled (qgl__point_arrays: attribute bits and
                                 QGL__A_EDGE; positions always) */
    qgl__stream stream;
    qgl__verts sub;           /* fallback output */
    qgl__verts pvmat;         /* draw.c: a batch's glMaterial calls as per-vertex materials */
    qgl__verts unrolled;      /* mesh.c: a run of quad primitives as one GL_QUADS batch */
    qgl__verts grouped;       /* draw.c: a batch's quads grouped by path */
    double *grouped_clip;
    size_t grouped_clip_cap;
    size_t *grouped_to;       /* where each quad went */
    size_t grouped_to_cap;
    uint16_t *unrolled_facts;
    size_t unrolled_facts_cap;
    double *clip;             /* 4 per vertex */
    unsigned plan_read, plan_need; /* the batch's attributes that reach the picture, facts it needs */
    int plan_fast;            /* draw.c: its state judged by parallel_invisible */
    unsigned char *path;      /* per quad */
    size_t idx_offset;        /* the batch's strip indices in the stream buffer */
    size_t clip_cap, path_cap;
    struct {
        uint32_t hash;
        GLuint prog;
        int failed;
        GLint px_loc;  /* u_px: the viewport's half size, the scale of the weights' space */
        float px[2];   /* its value last set (0: never) */
        qgl__key key;
    } programs[QGL__MAX_PROGRAMS];
    int nprograms, next_evict; /* cache (failures too, so a bad key is compiled once) */
    int material_arrays;      /* our VAO's material attribute arrays are enabled */
    const qgl__change *chg;   /* the drawing batch's material changes, the next one due */
    size_t nchg, chg_next;
    const qgl__verts *chg_verts;
    int list_quads;           /* the drawing batch is a display list's (QGL__DRAW_LIST) */
    GLint *multi_first;       /* mesh.c: glMultiDrawArrays' arguments */
    const void **multi_offset;
    size_t multi_cap3;
    unsigned char *ways;      /* mesh.c: how each primitive of a mesh is drawn */
    size_t ways_cap;
    GLsizei *multi_count;
    size_t multi_cap, multi_cap2;
    qgl__state state;         /* the state of the last draw (state.c) */
    qgl__lightvals lightvals; /* light.c's copy of the light values, for the planner */
    qgl__rate lit_rate;       /* lit quads judged lately (split_invisible) */
    qgl__rate par_rate;       /* parallelograms' values tested lately (draw.c) */
    qgl__rate fast_rate;      /* parallelograms' invisible splits tested lately (draw.c) */
    unsigned state_valid;     /* QGL__D_* groups of it unchanged since */
    int xform_stale;          /* the transform group changed since it was last read */
    qgl__texfacts tex_facts[QGL__TEX_FACTS]; /* by texture name modulo the size */
    int state_tracked;        /* the owner marks changes (qgl__state_dirty) */
    struct qgl__glsl120 *glsl120; /* the GLSL 1.20 path's programs and buffers, or NULL */
    struct qgl__client_arrays *arrays; /* immediate.c: client arrays qglArrayElement reads */
    struct qgl__grid *grid;   /* subdiv.c: the mean value grid path's buffers and plan, or NULL */
    struct qgl__costs *costs; /* calibrate.c: this driver's measured costs, or NULL (not
                                 calibrated, or the measurement failed: no grid in AUTO) */
    int exclusive;            /* desc.assume_exclusive: primitives may wait in pend */
    qgl__verts pend;          /* pending.c: finished primitives not drawn yet, as GL_QUADS */
};

/* Paths a quad can take: SUBDIV is the CPU fallback of fallback.c, GRID the mean value grid
 * of subdiv.c. */
enum { QGL__P_SPLIT = 0, QGL__P_MVC = 1, QGL__P_SUBDIV = 2, QGL__P_PASS = 3, QGL__P_GRID = 4, QGL__P_KIND = 7 };
/* Bits on top of QGL__P_MVC in the per-quad path byte (the path itself is path & QGL__P_KIND).
 * SCREEN: H&T's screen-space weights whatever the method (a non-planar quad with a corner
 * behind the eye, see plan_quad). */
enum { QGL__P_SCREEN = 1 << 3, QGL__P_DEPTH = 1 << 4, QGL__P_EXTERNAL = 1 << 5, QGL__P_CLIPPED = 1 << 7 };
/* While planning: a split quad that the shader path would draw the same (AUTO: exact, or too
 * small to differ), free to join a neighbouring shader-path run. */
enum { QGL__P_EITHER = 1 << 6 };

/* Per-quad facts that do not depend on the GL state (cached by retained batches). */
enum {
    QGL__F_PLANAR = 1 << 0,  /* every corner has w > 0 and the quad is planar */
    QGL__F_GROUPED = 1 << 1, /* the corners whose lighting inputs (normal, colours, material)
                                are all equal form groups whose indicator functions are affine:
                                then any per-vertex function of those alone is affine over
                                the quad */
    QGL__F_AFFINE = 1 << 2   /* QGL__F_AFFINE << class: that attribute (QGL__FC_*) is affine in
                                object space over the quad, or absent */
};
enum { QGL__FC_COLOR, QGL__FC_COLOR2, QGL__FC_FOG, QGL__FC_TEX0 }; /* unit u: QGL__FC_TEX0 + u */

/* A retained batch's cached plan, handed to the drawing code. */
typedef struct qgl__facts {
    const uint16_t *quad;    /* per quad */
    uint16_t all;            /* the facts every quad has */
    void (*native)(void *user); /* optional: the driver draws the batch as the application would */
    void *user;
} qgl__facts;

/* batch.c: a batch in the capture layout; 0 on bad arguments or no memory. */
int qgl__batch_to_verts(const qgl_quad_batch *b, qgl__verts *v);

/* draw.c */
int qgl__draw(qgl_context *ctx, const qgl__verts *v, qgl_topology topo);
/* qgl__draw with the cached facts of a retained batch (NULL: none) and QGL__DRAW_* flags. */
enum {
    QGL__DRAW_IMMEDIATE = 1, /* v was captured from glBegin/glEnd and the caller sets the current
                                attributes afterwards: split runs may be replayed as such */
    QGL__DRAW_ARRAYS = 2,    /* with IMMEDIATE: split runs are drawn from our arrays all the same
                                (a batch large enough that one upload costs less than its calls) */
    QGL__DRAW_LIST = 4       /* v is a display list's: its GL_QUADS replayed as the driver's lists
                                draw them (qgl__matrun) */
};
int qgl__draw_batch(qgl_context *ctx, const qgl__verts *v, qgl_topology topo, const qgl__facts *facts, unsigned flags,
                    const qgl__change *chg, size_t nchg);
int qgl__draw_with_facts(qgl_context *ctx, const qgl__verts *v, qgl_topology topo, const qgl__facts *facts);
uint16_t qgl__quad_facts(const qgl__verts *v, qgl_topology topo, size_t q);
/* Planarity of object-space corners given as floats: within 1e-6 of the quad's extent, or
 * within what rounding the corners to float can do (a small quad far from the origin, as a
 * fine sphere's, is planar only to its coordinates' precision). 2 for a parallelogram with
 * an area (planar too), 1 for another planar quad, 0 otherwise. */
int qgl__planar(const double p[4][3]);
/* x clamped to [0, 1] as the pipeline clamps colours (NaN passes through). */
static inline double qgl__clamp01(double x)
{
    return x < 0 ? 0 : x > 1 ? 1 : x;
}
void qgl__query_state(qgl_context *ctx, qgl__state *st);
/* state.c: the 4 x 4 identity, column-major (texture matrices are compared with it). */
extern const double qgl__identity[16];
/* state.c: the owner will mark every change of the groups from now on; a group changed. */
void qgl__state_track(qgl_context *ctx);
void qgl__state_dirty(qgl_context *ctx, unsigned groups);
/* The state as a draw now would read it (refreshing what changed), but for the transform
 * group (st->xf), which a draw asks for with qgl__state_xform, into ctx->state and its copy st. */
const qgl__state *qgl__state_now(qgl_context *ctx);
void qgl__state_xform(qgl_context *ctx, qgl__state *st);
/* Number of quads in n vertices of a topology; corner c of quad q is vertex corner(q, c). */
size_t qgl__nquads(qgl_topology topo, size_t n);
size_t qgl__corner(qgl_topology topo, size_t q, int c);
/* The corner flat shading takes its colour from; st the draw's state, or NULL to ask the driver. */
int qgl__flat_corner(qgl_context *ctx, const qgl__state *st, qgl_topology topo);

/* draw.c: the path every quad of a batch takes without planning, given the conjunction of
 * its facts (QGL__P_SPLIT or QGL__P_PASS), or -1 when the quads must be planned; counting. */
int qgl__native_path(qgl_context *ctx, const qgl__state *st, unsigned all_facts);
void qgl__count_path(qgl_context *ctx, unsigned char path, size_t nq);
/* draw.c: v drawn by the driver's immediate mode as one primitive, glMaterial calls inline. */
void qgl__replay_prim(qgl_context *ctx, GLenum mode, const qgl__verts *v, const qgl__change *chg, size_t nchg);
/* draw.c: whether a quad with a corner behind the eye keeps its in-plane weights: its object
 * corners are finite and within 1e-5 of its extent from their plane (the plane frame's
 * heights, which unlike qgl_is_planar's distance between the diagonals' lines stay well
 * conditioned on a bow-tie, whose diagonals may be nearly parallel). */
int qgl__external_planar(const qgl__verts *v, const size_t idx[4]);

/* mesh.c: a display list's primitives of any mode, drawn many times (see there). */
typedef struct qgl__mesh_prim {
    GLenum mode;
    uint32_t first, count;    /* vertices of the mesh */
    uint32_t chg0, nchg;      /* its glMaterial calls (vertex indices of the mesh) */
    uint32_t facts0;          /* its first quad's facts */
    uint32_t idx0;            /* GL_QUADS: its first index in the buffer */
    uint32_t at;              /* others: its first vertex in the buffer */
    unsigned given;           /* attributes (QGL__A_EDGE too) given inside its glBegin/glEnd; the
                                 others were current values (a replay sets them outside) */
} qgl__mesh_prim;

typedef struct qgl__mesh {
    qgl__verts v;             /* every vertex, in order */
    qgl__mesh_prim *prim;
    size_t nprim, capprim;
    qgl__change *chg;
    size_t nchg, capchg;
    uint16_t *facts;          /* per quad of the quad primitives */
    uint16_t *pfacts;         /* per primitive: the conjunction of its quads' */
    size_t nquads;
    int generic;              /* generic attributes given: only the driver's immediate mode */
    GLuint bo;                /* the vertices in a buffer object of the share group of owner */
    const void *owner;
    int stale;                /* the vertices changed since they were put in bo */
    size_t off_pos, off[QGL__NATTR], off_edge, off_idx;
} qgl__mesh;

int qgl__mesh_add_prim(qgl__mesh *m, GLenum mode, size_t first, size_t count, unsigned given, const qgl__change *chg,
                       size_t nchg);
/* After the last primitive: the facts. 0 without memory. */
int qgl__mesh_finish(qgl__mesh *m);
/* Vertex values changed (a current value the mesh takes from the state). */
void qgl__mesh_changed(qgl__mesh *m);
/* Draws m (owner: the share group its buffer may live in); the quads drawn, or -1 when the
 * driver's immediate mode must draw it (no vertex array objects, generic attributes). */
int qgl__mesh_draw(qgl_context *ctx, qgl__mesh *m, const void *owner);
/* Frees m; its buffer too when a context of its share group (owner) is current (gl non-NULL). */
void qgl__mesh_free(struct qgl__gl *gl, const void *owner, qgl__mesh *m);

/* shader.c: the program for a key (NULL: plain smooth colour), built on first use; 0 when
 * it cannot be built (a warning is logged once). */
GLuint qgl__program(qgl_context *ctx, const qgl__key *key);
void qgl__programs_free(qgl_context *ctx);
/* Frees ctx without a GL call, for a GL context destroyed while not current here: its GL
 * objects go with it, or stay with its share group. */
void qgl__gl_forget(qgl_context *ctx);
/* Give the bound program prog the viewport's half size (u_px) if it changed since last set. */
void qgl__program_viewport(qgl_context *ctx, GLuint prog, const GLint viewport[4]);
/* Varying vec4 slots a key's programs pass per fragment; above 32 the driver may refuse. */
int qgl__key_slots(const qgl__key *key);

/* immediate.c: bytes of one component of a GL array type (0 for a type arrays cannot have). */
size_t qgl__type_size(GLenum type);

/* shader.c: the weights as a GLSL function, vec4 quad_weights(vec4 sx, vec4 sy), GLSL 1.20 and
 * later; and the bilinear patch's hit, vec4 patch_hit(vec4 sx, vec4 sy, vec4 w, vec4 z, out
 * float depth) (its bilinear weights and window depth), after qgl__glsl_weights. */
extern const char qgl__glsl_weights[];
extern const char qgl__glsl_patch[];
/* shader.c: compile count sources as one shader / link a program; on failure 0, with the
 * driver's log in log (size bytes). Both shader paths report failures their own way. */
GLuint qgl__shader_compile(struct qgl__gl *gl, GLenum type, int count, const char *const *src, char *log, int size);
int qgl__program_link(struct qgl__gl *gl, GLuint prog, char *log, int size);

/* glsl120.c: the shader path without geometry shaders. draw returns 0 when it cannot draw
 * the run (a key it does not implement, a program the driver refuses): use the fallback. */
int qgl__glsl120_supported(qgl_context *ctx);
int qgl__glsl120_init(qgl_context *ctx);
void qgl__glsl120_free(qgl_context *ctx);
int qgl__glsl120_draw(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t q0,
                      size_t nq, unsigned key, GLint *bound);

/* external.c: the visible part of a quad with a corner behind the eye (clip corners, any
 * sign of w) on its split along diagonal diag (0: corners 0-2, 1: 1-3), cut by its screen
 * quad (H&T's external quad, eq. 12 in the projective plane) and the view volume: convex
 * pieces, each vertex as the four corner weights of its clip (and homogeneous object)
 * position. Returns how many, at most max (QGL__PIECES_MAX always suffices). */
#define QGL__PIECE_VERTS 16
#define QGL__PIECES_MAX 16
typedef struct qgl__piece {
    int n;
    double cw[QGL__PIECE_VERTS][4];
} qgl__piece;
int qgl__external_pieces(const double clip[4][4], int diag, qgl__piece *out, int max);

/* fallback.c: append the subdivision of quad q of v to out (same attributes as v). */
int qgl__subdivide(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo,
                   size_t q, qgl__verts *out);

/* stream.c: bytes of room in the stream buffer (bound to GL_ARRAY_BUFFER), its offset in
 * *offset; write it, then qgl__stream_end before drawing. NULL when the driver refuses. */
void qgl__stream_init(qgl_context *ctx);
void *qgl__stream_begin(qgl_context *ctx, size_t bytes, size_t *offset);
void qgl__stream_end(qgl_context *ctx);
void qgl__stream_free(qgl_context *ctx);

/* context.c: whether the context's driver offers an extension. */
int qgl__has_extension(qgl_context *ctx, const char *name);

/* draw.c: the largest gain (the interpolation weights' error along the corners' dependency n,
 * n_i per corner) at which every attribute reaching the picture stays within the planner's
 * budgets (colours and fog half an 8-bit level, texture coordinates 1/32 texel, times
 * split_error): INFINITY when nothing varies, 0 when the state cannot be judged. n need not
 * sum to 0 (non-planar quads): the residuals then allow for the value's own range. */
double qgl__gain_limit(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4],
                       const double n[4]);

/* subdiv.c: the mean value grid path. plan: whether quad q (corners idx, clip positions
 * clip, every w > 0) takes it, by the grid's error bound and (AUTO) the calibrated costs; the
 * chosen grid is kept for draw, which draws the run q0 .. q0 + nq - 1 of such quads. */
int qgl__grid_plan(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4],
                   const double *clip[4], int planar, size_t q);
int qgl__grid_draw(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t q0,
                   size_t nq, GLint *bound);
void qgl__grid_free(qgl_context *ctx);
/* The batch's quads are drawn in another order (draw.c's grouping by path): quad q moves to
 * to[q], and the grid planned for it goes with it. 0 without memory (nothing moved). */
int qgl__grid_regroup(qgl_context *ctx, const unsigned char *path, const size_t *to, size_t nq);
/* subdiv.c, for the calibration: draw quads of v (QGL_QUADS; their clip positions in
 * ctx->clip) each as grid number g; draw v's positions and colours as they are in mode. */
int qgl__grid_draw_all(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, int g);
int qgl__grid_draw_arrays(qgl_context *ctx, const qgl__verts *v, GLenum mode);

/* calibrate.c: measure this driver's costs (once per renderer string in the process, within
 * 20 ms; ctx->costs stays NULL when it cannot or a figure is odd), and the model: whether
 * grid number g is cheaper than the shader path for a quad covering area_px pixels. */
struct qgl__costs {
    int valid;
    double ms, warm_ms, mvc_quad, mvc_px, split_px, grid_tri; /* milliseconds; the others nanoseconds */
};
void qgl__calibrate(qgl_context *ctx);
/* The costs QUADGL_COSTS gives, read when the context is made (none: measured when ready). */
void qgl__costs_given(qgl_context *ctx);
/* context.c: at the first quad that needs it (not when the context is made, so that a program
 * whose quads all split never pays a compile's memory and time): the shader path compiled,
 * falling back to GLSL 1.20 or none, and the costs measured. Returns whether the shader
 * level changed (the state must be read again). */
int qgl__ready(qgl_context *ctx);
int qgl__grid_cheaper(const qgl_context *ctx, double area_px, int g);
/* Nanoseconds the split saves against the shader path in the pixels of a quad of area_px
 * (INFINITY when the costs are not known). The per-quad part is not counted: in real programs
 * it is spent beside the application's thread, and splitting lit quads of a few pixels saved
 * nothing measurable (engine, peepers in tools/apps-bench.sh). */
double qgl__split_saving(const qgl_context *ctx, double area_px);

/* Per-thread current context (read directly on the immediate-mode hot path). */
extern __attribute__((tls_model("initial-exec"))) _Thread_local qgl_context *qgl__tls_current;
qgl_context *qgl__current(void);

/* immediate.c: the driver's current value of one attribute (QGL__A_* bit). */
void qgl__driver_current(qgl_context *c, unsigned bit, float out[4]);

/* pending.c: draw a finished primitive now, or (assume_exclusive) append it to the pending
   batch; returns its number of quads, or -1. qgl__flush draws the pending batch first: call
   it before anything reaches the driver. */
int qgl__submit(qgl_context *ctx, qgl__verts *v, qgl_topology topo);
void qgl__flush_pending(qgl_context *ctx);
static inline void qgl__flush(qgl_context *ctx)
{
    if (ctx->pend.n)
        qgl__flush_pending(ctx);
}

#endif
