/* quadgl: the gl layer's public API (included by quadgl/quadgl.h).
 *
 * A qgl_context lives inside the application's current GL context. It captures quads (the
 * qgl* immediate API below, or qgl_draw_quads) and draws them through the real driver so that
 * attributes follow the mean value interpolation instead of the diagonal split. Everything
 * that is not a quad goes straight to the driver. The layer never calls a gl* symbol of its
 * own: every GL entry point is looked up through the desc's get_proc (or the window system's
 * own GetProcAddress), so a library that exports gl* names itself can drive it. */
#ifndef QUADGL_GL_H
#define QUADGL_GL_H
#include <quadgl/quadgl.h>
#include <stdint.h>
#ifdef __cplusplus
extern "C" {
#endif

/* How quads are drawn. AUTO plans per quad: the driver's split where it is exact (planar,
 * attributes affine in object space) or invisible (tiny on screen, or a planar quad whose split
 * differs from the smooth result by less than the output shows: split_error), else the mean
 * value grid where its error is within the same budgets and it costs less than the smooth
 * (shader) path, the shader path otherwise. The smooth path of AUTO, MVC_PLANE and SUBDIV
 * weighs view-invariantly: mean value weights of the fragment's position in the quad's own
 * plane (a non-planar quad: of its hit on the bilinear patch, projected onto the best-fit
 * plane), so a surface point keeps its value as the camera moves. MVC forces the smooth path
 * with H&T's screen-space weights (the paper's method: they change with the viewpoint, even on
 * a planar quad), MVC_PLANE the smooth path with the view-invariant ones, SPLIT the driver's
 * own quads, SUBDIV the mean value grid wherever it can serve (an unlit state the shader path
 * models, a convex quad of the grid's class in front of the eye; its finest grid when none is
 * within budget) and the CPU subdivision fallback elsewhere. */
typedef enum qgl_method {
    QGL_METHOD_AUTO = 0,
    QGL_METHOD_MVC = 1,
    QGL_METHOD_SPLIT = 2,
    QGL_METHOD_SUBDIV = 3,
    QGL_METHOD_MVC_PLANE = 4
} qgl_method;

typedef struct qgl_context qgl_context;

/* Zero means default for every field. */
typedef struct qgl_gl_desc {
    qgl_method method;         /* default AUTO, or the environment's QUADGL_METHOD */
    float tolerance_px;        /* fallback's screen tolerance; default QUADGL_TOLERANCE or 0.5 */
    float invisible_area_px;   /* AUTO: quads whose screen bounding box is smaller than this
                                  (pixels^2: a 2 x 2 pixel quad shows no crease) are split;
                                  default 4 */
    void *(*get_proc)(const char *name); /* resolver of GL entry points; default: the window
                                            system's GetProcAddress, then dlsym */
    int force_fallback;        /* never use shaders (as on a GL 1.x context) */
    int max_glsl;              /* cap the GLSL version used (e.g. 120); 0 = no cap */
    int assume_exclusive;      /* the owner sees every GL call and calls qgl_gl_flush before any
                                  that does not go through this layer (state changes, reads,
                                  swaps, another context made current): consecutive quad
                                  primitives are then gathered and drawn as one */
    float split_error;         /* AUTO: a planar quad is also split where the split differs from
                                  the smooth interpolation by less than the output shows: colours
                                  (and fog) by half an 8-bit level, texture coordinates by 1/32
                                  texel of level 0, times this scale. 0 = 1; negative = off */
} qgl_gl_desc;

/* Counters of what took which path; quads counts every quad seen, the others add up to it. */
typedef struct qgl_gl_stats_t {
    uint64_t quads;       /* quads received */
    uint64_t mvc;         /* drawn by the shader path */
    uint64_t split;       /* drawn by the driver's split (exact, invisible or method SPLIT) */
    uint64_t subdiv;      /* drawn as the mean value grid: exact weights at a subdivision's
                             vertices, the driver's fast path between them (AUTO where within
                             the budgets and cheaper than the shader path by qgl_gl_costs,
                             SUBDIV wherever the grid can serve) */
    uint64_t fallback;    /* drawn by the CPU subdivision fallback */
    uint64_t passthrough; /* handed to the driver as is (polygon mode, select/feedback) */
    uint64_t draws;       /* driver draw calls issued by the layer */
    uint64_t subdiv_triangles; /* triangles the grid and the fallback produced */
    uint64_t uploads;     /* display-list geometry copied into a buffer object (once per list,
                             again only when a value it takes from the current state changed) */
} qgl_gl_stats_t;

/* The driver's costs the planner weighs (measured when the context is created, off screen,
 * once per renderer in the process, the timed draws within 20 ms; or given by QUADGL_COSTS=mq,mf,sf,gt in
 * nanoseconds). valid 0: none, or an odd or failed measurement: AUTO never draws the mean
 * value grid then and keeps the shader path. */
typedef struct qgl_gl_costs_t {
    int valid;
    double ms;            /* how long the measurement took (0 when given) */
    double warm_ms;       /* and the untimed first draws before it (the driver's lazy shader
                             compilation), not part of the 20 ms */
    double mvc_quad_ns;   /* shader path, per quad */
    double mvc_px_ns;     /* shader path, per pixel */
    double split_px_ns;   /* the driver's split (and the grid), per pixel */
    double grid_tri_ns;   /* the grid, per triangle (its vertices' weights and upload included) */
} qgl_gl_costs_t;

/* Create inside the current GL context (GL 1.3 or later, compatibility profile); NULL when
 * the entry points cannot be resolved. */
QGL_API qgl_context *qgl_gl_create(const qgl_gl_desc *desc);
QGL_API void qgl_gl_destroy(qgl_context *ctx);
QGL_API void qgl_gl_make_current(qgl_context *ctx); /* per thread */
QGL_API qgl_context *qgl_gl_current(void);
QGL_API void qgl_gl_set_method(qgl_context *ctx, qgl_method method);
QGL_API qgl_method qgl_gl_get_method(const qgl_context *ctx);
/* The scale of qgl_gl_desc.split_error, changed for later draws (the planner forgets how often
 * lit quads passed the old one). */
QGL_API void qgl_gl_set_split_error(qgl_context *ctx, float scale);
/* The shader path the context found: 0 none (CPU fallback only), 120 (GLSL 1.20 on GL 2.x or a
 * context capped by max_glsl: the cover computed on the CPU, corners sent per vertex), 150
 * (geometry shader, GL 3.2 compatibility). */
QGL_API int qgl_gl_shader_level(const qgl_context *ctx);
QGL_API void qgl_gl_stats(const qgl_context *ctx, qgl_gl_stats_t *out);
QGL_API void qgl_gl_reset_stats(qgl_context *ctx);
QGL_API void qgl_gl_costs(const qgl_context *ctx, qgl_gl_costs_t *out);
/* Draw the quads gathered under assume_exclusive (nothing to do otherwise). Every qgl* call
that reaches the driver flushes by itself; the owner flushes before its own GL calls. */
QGL_API void qgl_gl_flush(qgl_context *ctx);

/* ---- batches -------------------------------------------------------------------------- */

typedef enum qgl_topology {
    QGL_QUADS = 0,      /* 4 vertices per quad */
    QGL_QUAD_STRIP = 1  /* 2 + 2 per quad; quad k is v2k, v2k+1, v2k+3, v2k+2 */
} qgl_topology;

/* One attribute array. size 0 = absent. type is a GL type enum: GL_FLOAT for all, and
 * GL_UNSIGNED_BYTE (normalized) or GL_DOUBLE where noted; 0 means GL_FLOAT. stride 0 means
 * tightly packed. */
typedef struct qgl_attrib {
    const void *ptr;
    int size;
    unsigned type;
    int stride;
} qgl_attrib;

#define QGL_MAX_TEXUNITS 4

typedef struct qgl_quad_batch {
    qgl_topology topology;
    int count;                /* vertices (or indices when indices != NULL) */
    const uint32_t *indices;  /* optional */
    qgl_attrib position;      /* size 2, 3 or 4; float or double */
    qgl_attrib color;         /* size 3 or 4; float, double or unsigned byte */
    qgl_attrib normal;        /* size 3 */
    qgl_attrib texcoord[QGL_MAX_TEXUNITS]; /* size 1..4, unit i */
    qgl_attrib secondary_color; /* size 3 */
    qgl_attrib fog_coord;     /* size 1 */
} qgl_quad_batch;

/* Draw the quads of b in the current GL state. Returns the number of quads drawn, or a
 * negative value on bad arguments (nothing drawn). The current colour, normal and texture
 * coordinates are left as they were. */
QGL_API int qgl_draw_quads(qgl_context *ctx, const qgl_quad_batch *b);

/* ---- retained batches: quads drawn many times (display lists) ------------------------------ */

/* A copy of a batch with the part of the plan that does not depend on the GL state worked out
 * once (per quad: planar?, which attributes are affine in object space?). It holds no GL
 * object: it may be drawn in any context and released from any thread (not while a draw of
 * it runs). */
typedef struct qgl_retained qgl_retained;

/* Zero means default for every field. */
typedef struct qgl_retain_desc {
    /* Optional: draws these very quads through the driver as the application itself would
       (e.g. a display list compiled from its own calls), leaving the current attributes as
       it leaves them. When the current state splits every quad exactly (or draws them as
       the driver does: polygon mode line, select), qgl_gl_draw_retained calls it and does
       nothing else. */
    void (*draw_native)(void *user);
    void *user;
} qgl_retain_desc;

/* NULL on bad arguments or no memory. desc may be NULL. */
QGL_API qgl_retained *qgl_gl_retain(const qgl_quad_batch *b, const qgl_retain_desc *desc);
/* Draw r in the current GL state, as qgl_draw_quads would draw its batch. Returns the number
 * of quads drawn, or a negative value (nothing drawn). */
QGL_API int qgl_gl_draw_retained(qgl_context *ctx, const qgl_retained *r);
QGL_API void qgl_gl_release(qgl_retained *r);

/* ---- immediate mode, GL's own signatures, on the current qgl context ---------------------- */
/* GL_QUADS and GL_QUAD_STRIP are captured and drawn at qglEnd; every other primitive, and
 * every call outside qglBegin/qglEnd, goes to the driver unchanged. */

QGL_API void qglBegin(unsigned mode);
QGL_API void qglEnd(void);

QGL_API void qglVertex2f(float x, float y);
QGL_API void qglVertex2d(double x, double y);
QGL_API void qglVertex2i(int x, int y);
QGL_API void qglVertex2s(short x, short y);
QGL_API void qglVertex3f(float x, float y, float z);
QGL_API void qglVertex3d(double x, double y, double z);
QGL_API void qglVertex3i(int x, int y, int z);
QGL_API void qglVertex3s(short x, short y, short z);
QGL_API void qglVertex4f(float x, float y, float z, float w);
QGL_API void qglVertex4d(double x, double y, double z, double w);
QGL_API void qglVertex4i(int x, int y, int z, int w);
QGL_API void qglVertex4s(short x, short y, short z, short w);
QGL_API void qglVertex2fv(const float *v);
QGL_API void qglVertex2dv(const double *v);
QGL_API void qglVertex2iv(const int *v);
QGL_API void qglVertex2sv(const short *v);
QGL_API void qglVertex3fv(const float *v);
QGL_API void qglVertex3dv(const double *v);
QGL_API void qglVertex3iv(const int *v);
QGL_API void qglVertex3sv(const short *v);
QGL_API void qglVertex4fv(const float *v);
QGL_API void qglVertex4dv(const double *v);
QGL_API void qglVertex4iv(const int *v);
QGL_API void qglVertex4sv(const short *v);

QGL_API void qglColor3f(float r, float g, float b);
QGL_API void qglColor3d(double r, double g, double b);
QGL_API void qglColor3ub(unsigned char r, unsigned char g, unsigned char b);
QGL_API void qglColor4f(float r, float g, float b, float a);
QGL_API void qglColor4d(double r, double g, double b, double a);
QGL_API void qglColor4ub(unsigned char r, unsigned char g, unsigned char b, unsigned char a);
QGL_API void qglColor3fv(const float *v);
QGL_API void qglColor3dv(const double *v);
QGL_API void qglColor3ubv(const unsigned char *v);
QGL_API void qglColor4fv(const float *v);
QGL_API void qglColor4dv(const double *v);
QGL_API void qglColor4ubv(const unsigned char *v);

QGL_API void qglNormal3f(float x, float y, float z);
QGL_API void qglNormal3d(double x, double y, double z);
QGL_API void qglNormal3fv(const float *v);
QGL_API void qglNormal3dv(const double *v);

QGL_API void qglTexCoord1f(float s);
QGL_API void qglTexCoord2f(float s, float t);
QGL_API void qglTexCoord3f(float s, float t, float r);
QGL_API void qglTexCoord4f(float s, float t, float r, float q);
QGL_API void qglTexCoord1d(double s);
QGL_API void qglTexCoord2d(double s, double t);
QGL_API void qglTexCoord3d(double s, double t, double r);
QGL_API void qglTexCoord4d(double s, double t, double r, double q);
QGL_API void qglTexCoord2fv(const float *v);
QGL_API void qglTexCoord3fv(const float *v);
QGL_API void qglTexCoord4fv(const float *v);
QGL_API void qglTexCoord2dv(const double *v);
QGL_API void qglMultiTexCoord2f(unsigned unit, float s, float t);
QGL_API void qglMultiTexCoord4f(unsigned unit, float s, float t, float r, float q);
QGL_API void qglMultiTexCoord2fv(unsigned unit, const float *v);
QGL_API void qglMultiTexCoord4fv(unsigned unit, const float *v);

QGL_API void qglSecondaryColor3f(float r, float g, float b);
QGL_API void qglSecondaryColor3fv(const float *v);
QGL_API void qglFogCoordf(float f);
QGL_API void qglFogCoordfv(const float *f);
QGL_API void qglEdgeFlag(unsigned char flag);
QGL_API void qglEdgeFlagv(const unsigned char *flag);
QGL_API void qglMaterialf(unsigned face, unsigned pname, float param);
QGL_API void qglMaterialfv(unsigned face, unsigned pname, const float *params);
/* Inside a captured primitive: element i of every enabled client array (vertex, colour,
 * secondary colour, normal, fog coordinate, edge flag, texture units 0-3; client memory or
 * buffer objects), fed as the attribute calls and the vertex GL specifies. Else forwarded. */
QGL_API void qglArrayElement(int i);

#ifdef __cplusplus
}
#endif
#endif
