/* preload.h: the internal interface of libquadgl-preload.so (never installed).
 *
 * The library sits between a legacy GL program and its driver. Exported gl* wrappers
 * (generated, pl_entries.c, and hand-written for glBegin, the draws and the lists) call the
 * real driver through lazily resolved slots (real.c). Quad primitives are captured into a
 * pl_prim: one pl_vertex per vertex holding every attribute the capture tracks, plus which
 * attributes were given and from which vertex on (capture.c, arrays.c). A finished primitive
 * is either drawn (draw.c: through the GL path, or replayed to the driver unchanged) or, while
 * a display list is being compiled, stored in our own list object (lists.c). All state is per
 * GL context (context.c), tracked through the window systems' MakeCurrent calls (winsys.c). */
#ifndef QGL_PRELOAD_H
#define QGL_PRELOAD_H

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <pthread.h>
#include <stddef.h>
#include <stdint.h>

#include <quadgl/quadgl.h>
#include <quadgl/gl.h>

#include "pl_entries.h"

#define PL_EXPORT __attribute__((visibility("default")))
#define PL_LIKELY(x) __builtin_expect(!!(x), 1)
#define PL_UNLIKELY(x) __builtin_expect(!!(x), 0)

/* GL's conversions of normalized integer colour and normal components to float, as Mesa
 * performs them for the immediate-mode entry points (so a replay is bit-exact). */
#define PL_B(c) ((2.0f * (float)(c) + 1.0f) / 255.0f)
#define PL_UB(c) ((float)(c) / 255.0f)
#define PL_S(c) ((2.0f * (float)(c) + 1.0f) / 65535.0f)
#define PL_US(c) ((float)(c) / 65535.0f)
#define PL_I(c) ((float)((2.0 * (double)(c) + 1.0) / 4294967295.0))
#define PL_UI(c) ((float)((double)(c) / 4294967295.0))

/* ---- configuration and logging (control.c) ---------------------------------------------- */

enum { PL_LOG_WARN = 0, PL_LOG_INFO = 1, PL_LOG_DEBUG = 2 };

typedef struct pl_config {
    int capture;      /* 0: QUADGL_METHOD=off, every call goes straight through */
    int replay;       /* QUADGL_METHOD=replay: capture, then redraw through the driver */
    int method;       /* a qgl_method for the GL path */
    float tolerance;  /* QUADGL_TOLERANCE, 0 = the GL path's default */
    int stats;        /* QUADGL_STATS=1 */
    int log_level;
} pl_config;

extern pl_config pl_cfg;
void pl_log(int level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Counters of quads the library drew itself (replayed to the driver), all contexts. */
void pl_count_passthrough(uint64_t quads);

/* ---- real driver functions (real.c) ------------------------------------------------------- */

typedef struct pl_proc {
    const char *name;
    void *fn;
} pl_proc;
extern const pl_proc pl_proc_table[]; /* sorted by name: every exported GL entry point */
extern const int pl_proc_count;

void pl_resolve_slot(int slot);
/* The driver's function for name, never one of ours; NULL when none exists. */
void *pl_real_proc(const char *name);
/* Our exported function for name (GL or window system), NULL when we do not handle it. */
void *pl_own_proc(const char *name);
/* The next definition of a window-system or libc symbol after ours. */
void *pl_next_symbol(const char *name);
/* The file name of this library (for dlopen redirection). */
const char *pl_self_path(void);

/* ---- captured primitives ------------------------------------------------------------------- */

#define PL_TEXUNITS 4 /* = QGL_MAX_TEXUNITS of the GL path */

/* Attribute indices: bit a of pl_prim.given. */
enum { PL_A_COLOR, PL_A_SECONDARY, PL_A_NORMAL, PL_A_FOG, PL_A_TEX0, PL_A_COUNT = PL_A_TEX0 + PL_TEXUNITS };

typedef struct pl_vertex {
    float pos[4];
    float color[4];
    float secondary[4];
    float tex[PL_TEXUNITS][4];
    float normal[3];
    float fog;
} pl_vertex;

/* glMaterial given between glBegin and glEnd, applied before vertex `vertex`. */
typedef struct pl_material {
    uint32_t vertex;
    GLenum face, pname;
    float v[4];
} pl_material;

typedef struct pl_prim {
    GLenum mode;             /* GL_QUADS or GL_QUAD_STRIP */
    pl_vertex *v;
    size_t n, cap;
    pl_vertex cur;           /* the values given so far (the next vertex gets them) */
    unsigned given;          /* bit per attribute given at least once */
    uint32_t first[PL_A_COUNT]; /* vertex from which each given attribute is set; earlier
                                   vertices take the context's current value at draw time */
    pl_material *mat;
    size_t nmat, capmat;
    int edge_off;            /* an edge flag was false: drawn by the driver itself */
    int lost;                /* something the capture cannot represent (texture unit >= 4) */
    int from_arrays;         /* current attributes are restored after a replay */
    GLuint native_list;      /* in a display list: the driver's own compilation of the same
                                calls, what a replay (and a draw the split serves exactly) runs */
    struct pl_retained *retained; /* in a display list: the GL path's retained copy, made at
                                     its first draw (draw.c) */
} pl_prim;

void pl_prim_reset(pl_prim *p, GLenum mode);
void pl_prim_free(pl_prim *p);
int pl_prim_copy(pl_prim *dst, const pl_prim *src);
int pl_prim_push(pl_prim *p);         /* appends p->cur as a vertex; 0 or -1 (no memory) */
size_t pl_prim_quads(const pl_prim *p);
/* Fills attribute a of the vertices before p->first[a] with the context's current value. */
void pl_prim_backfill(pl_prim *p, int a);
/* The context's current value of attribute a (up to 4 floats), and where a vertex keeps it. */
void pl_read_current(int a, float *out);
float *pl_attr_ptr(pl_vertex *v, int a);
size_t pl_attr_size(int a);

/* ---- contexts (context.c) ---------------------------------------------------------------- */

enum { PL_API_NONE = 0, PL_API_GLX, PL_API_EGL, PL_API_OSMESA };

typedef struct pl_share pl_share;
typedef struct pl_list pl_list;

typedef struct pl_ctx {
    int api;
    void *handle;            /* the window system's context */
    pl_share *share;         /* display-list namespace */
    qgl_context *qgl;        /* the GL path, created on the first quad draw */
    int qgl_state;           /* 0 not tried, 1 made, -1 failed */
    int capturing;           /* inside a captured glBegin(GL_QUADS / GL_QUAD_STRIP) */
    int native_begin;        /* inside a glBegin forwarded to the driver */
    pl_prim prim;            /* the primitive being captured */
    pl_prim scratch;         /* vertex-array draws */
    pl_list *compiling;      /* the display list being compiled, or NULL */
    GLenum compile_mode;
    int list_depth;
    int bound;               /* threads it is current on (0 or 1) */
    int dead;                /* destroyed while current elsewhere: freed at release */
    struct pl_ctx *next;
} pl_ctx;

extern __thread pl_ctx *pl_tls_ctx __attribute__((tls_model("initial-exec")));

/* The context whose quad primitive is being captured on this thread, or NULL. */
static inline pl_ctx *pl_capturing(void)
{
    pl_ctx *x = pl_tls_ctx;
    return (x && x->capturing) ? x : NULL;
}

/* The current context of this thread; detects it through the window systems when no
 * MakeCurrent was seen (a program that resolved them past us). NULL when none. */
pl_ctx *pl_current(void);
pl_ctx *pl_ctx_lookup(int api, void *handle, int create);
void pl_ctx_created(int api, void *handle, int share_api, void *share_handle);
void pl_ctx_bind(int api, void *handle);   /* this thread's current (NULL handle: none) */
void pl_ctx_destroyed(int api, void *handle);
qgl_context *pl_ctx_qgl(pl_ctx *x);        /* the GL path, created on first use */
void pl_stats_total(uint64_t out[5]);      /* quads, mvc, split, subdiv, passthrough */

/* ---- capture (capture.c, arrays.c) -------------------------------------------------------- */

void pl_cap_vertex(pl_ctx *x, float a, float b, float c, float d);
void pl_cap_color(pl_ctx *x, float r, float g, float b, float a);
void pl_cap_secondary(pl_ctx *x, float r, float g, float b);
void pl_cap_normal(pl_ctx *x, float a, float b, float c);
void pl_cap_texcoord(pl_ctx *x, GLenum unit, float s, float t, float r, float q);
void pl_cap_fog(pl_ctx *x, float f);
void pl_cap_edgeflag(pl_ctx *x, GLboolean flag);
void pl_cap_material(pl_ctx *x, GLenum face, GLenum pname, const GLfloat *params);
void pl_cap_materiali(pl_ctx *x, GLenum face, GLenum pname, const GLint *params);
void pl_cap_array_element(pl_ctx *x, GLint i);

/* Fills p with the vertices of an array draw (type 0: first .. first + count - 1, else count
 * indices of that type).
 * Returns 0, or -1 when the array state is one the capture does not model (the caller then
 * lets the driver draw). */
int pl_arrays_capture(pl_ctx *x, pl_prim *p, GLenum mode, GLint first, GLsizei count, GLenum type,
                      const void *indices);

/* ---- drawing (draw.c) ------------------------------------------------------------------------ */

/* Draws a finished primitive in the current state: fills attributes given only from a later
 * vertex from the current values, draws, and leaves the current attributes as GL would. */
void pl_draw_prim(pl_ctx *x, pl_prim *p);
/* Sets the current attributes to the last values given in p (what glEnd leaves behind). */
void pl_prim_apply_current(const pl_prim *p);
/* The calls that draw p in the driver (glBegin, attributes, vertices, glEnd, materials). */
void pl_prim_emit(const pl_prim *p);
/* Whether p goes to the driver as it is rather than through the GL path. */
int pl_prim_for_driver(pl_ctx *x, const pl_prim *p);
/* Draws a primitive recorded in a display list (its retained copy when it has one). */
void pl_draw_listed(pl_ctx *x, pl_prim *p);
/* Frees a listed primitive's retained copy. */
void pl_retained_free(struct pl_retained *r);

/* ---- display lists (lists.c) ----------------------------------------------------------------- */

/* While compiling: ends the driver's segment before something we record, and opens the next
 * one after it. */
void pl_list_segment_close(pl_ctx *x);
void pl_list_segment_open(pl_ctx *x);
/* Records a finished primitive in the list being compiled (takes a copy). */
void pl_list_record_prim(pl_ctx *x, const pl_prim *p);
/* The driver also compiles the primitive's own calls (made between these two) into a private
 * list: what a replay runs, so it matches the driver's compilation exactly, and what a draw
 * runs when the current state makes the split exact for every quad. */
void pl_list_native_begin(pl_ctx *x);
void pl_list_native_end(pl_ctx *x);
void pl_share_unref(pl_share *s);
pl_share *pl_share_new(void);
void pl_share_ref(pl_share *s);

#endif
