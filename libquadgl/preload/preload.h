/* preload.h: the internal interface of libquadgl-preload.so (never installed).
 *
 * The library sits between a legacy GL program and its driver. It exports every GL entry
 * point (generated, pl_entries.c, and hand-written for glBegin, the draws and the lists) and
 * calls the real driver through lazily resolved slots (real.c). Every call passes a hook on
 * its way: attribute and vertex calls are captured inside a captured quad primitive and
 * otherwise update our copy of the current attributes; other calls mark which groups of the
 * state the GL path reads they may change (track.c), so that the GL path asks the driver only
 * for what changed. Quad primitives are captured into a pl_prim, one array per attribute in
 * the GL path's own layout (capture.c, arrays.c). A finished primitive is drawn (draw.c:
 * through the GL path, or replayed to the driver unchanged) or, while a display list is being
 * compiled, stored in our own list object (lists.c). All state is per GL context (context.c),
 * tracked through the window systems' MakeCurrent calls (winsys.c). */
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

#include "gl_internal.h"
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
    double stats_interval; /* QUADGL_STATS_INTERVAL, seconds (0: none) */
    int log_level;
} pl_config;

extern pl_config pl_cfg;
void pl_log(int level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* ---- statistics (stats.c) ------------------------------------------------------------------ */

typedef struct pl_ctx pl_ctx;

enum { PL_ST_QUADS, PL_ST_MVC, PL_ST_SPLIT, PL_ST_SUBDIV, PL_ST_PASS, PL_ST_DRAWS, PL_ST_UPLOADS, PL_ST_FRAMES,
       PL_ST_NS, PL_ST_COUNT };

/* Quads the library drew itself (replayed to the driver), all contexts. */
void pl_count_passthrough(uint64_t quads);
void pl_stats_init(void);
/* A frame ended (a swap) on x's thread; every context's counters join the totals then. */
void pl_stats_frame(pl_ctx *x);
void pl_stats_publish(pl_ctx *x);
void pl_stats_totals(uint64_t out[PL_ST_COUNT]);
/* Time in quadgl's drawing, counted only for QUADGL_STATS_INTERVAL. */
uint64_t pl_clock_ns(void);
void pl_stats_spent(uint64_t ns);
#define PL_TIMED(call)                                      \
    do {                                                    \
        if (PL_UNLIKELY(pl_cfg.stats_interval > 0)) {       \
            uint64_t pl_t0_ = pl_clock_ns();                \
            call;                                           \
            pl_stats_spent(pl_clock_ns() - pl_t0_);         \
        } else {                                            \
            call;                                           \
        }                                                   \
    } while (0)

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
/* Our exported function for name (GL or window system), NULL when we do not handle it or the
 * driver has no such function. */
void *pl_own_proc(const char *name);
/* The next definition of a window-system or libc symbol after ours. */
void *pl_next_symbol(const char *name);
/* Set when the program got a GL function that is not ours (winsys.c): calls to it go unseen. */
extern int pl_untracked;
/* The file name of this library (for dlopen redirection). */
const char *pl_self_path(void);

/* ---- captured primitives ------------------------------------------------------------------- */

#define PL_TEXUNITS QGL_MAX_TEXUNITS
/* Vertices a batch may hold: about the 64 KB the driver's own immediate mode hands over at a
 * time. A frame's quads held for one draw at its end took about 10% longer on llvmpipe (its
 * threads and the X server overlapped less): glmatrix under tools/frame-time.sh, 16384 and
 * 4096 vertices 11% longer than 1024, 2048 3%. */
#define PL_BATCH_MAX 1024
#define PL_GENERICS 16 /* generic attributes a primitive may give (replayed to the driver) */

/* glMaterial given between glBegin and glEnd, applied before vertex `vertex`. */
typedef qgl__change pl_material;

typedef struct pl_prim {
    GLenum mode;             /* GL_QUADS or GL_QUAD_STRIP */
    qgl__verts v;            /* positions, and the attributes given (v.mask), edge flags too */
    float cur[QGL__NATTR][4];/* the values given so far (the next vertex takes them) */
    unsigned char cur_edge;
    uint32_t first[QGL__NATTR + 1]; /* vertex from which each given attribute (and the edge
                                flag, last) is set; earlier ones take the context's current
                                value at draw time (in a list: when it runs) */
    float *generic[PL_GENERICS]; /* 4 per vertex, only for the indices given */
    float cur_generic[PL_GENERICS][4];
    unsigned generic_given;
    uint32_t generic_first[PL_GENERICS];
    pl_material *mat;
    size_t nmat, capmat;
    int lost;                /* something the capture cannot represent (texture unit >= 4) */
    int from_arrays;         /* current attributes are restored after a replay */
    int in_list;             /* a display list's own: replayed as the driver's lists draw */
    signed char mat_inert;   /* pl_material_inert's answer for this primitive, -1 unknown */
    int direct;              /* vertices written straight into the batch's arrays from vertex
                                `base` on (v holds the count and the given mask, no arrays),
                                every attribute the batch carries with them; the values given
                                go to the context's cur (cur here is unused) */
    size_t base;
} pl_prim;

void pl_prim_reset(pl_prim *p, GLenum mode);
void pl_prim_free(pl_prim *p);
int pl_prim_copy(pl_prim *dst, const pl_prim *src);
size_t pl_prim_quads(const pl_prim *p);
/* Fills the vertices before each given attribute's first one with the current value (a listed
 * primitive keeps its first ones: the value is read anew each time the list runs). */
void pl_prim_backfill(pl_ctx *x, pl_prim *p);

/* ---- contexts (context.c) ---------------------------------------------------------------- */

enum { PL_API_NONE = 0, PL_API_GLX, PL_API_EGL, PL_API_OSMESA };

/* What a GL call may change (track.c): the GL path's state groups, and the preload's own copy
 * of the current attributes. */
enum {
    PL_D_XFORM = QGL__D_XFORM,
    PL_D_RASTER = QGL__D_RASTER,
    PL_D_FFP = QGL__D_FFP,
    PL_D_BIND = QGL__D_BIND,
    PL_D_ORDER = QGL__D_ORDER,
    PL_D_TEX = QGL__D_TEX,
    PL_D_TEXIMAGE = QGL__D_TEXIMAGE,
    PL_D_LIGHT = QGL__D_LIGHT,
    PL_D_CURRENT = 1 << 8,
    PL_D_LIST_BASE = 1 << 9,
    PL_D_STATE = QGL__D_ALL
};

typedef struct pl_share pl_share;
typedef struct pl_list pl_list;

struct pl_ctx {
    int api;
    void *handle;            /* the window system's context */
    pl_share *share;         /* display-list namespace */
    qgl_context *qgl;        /* the GL path, created on the first quad draw */
    int qgl_state;           /* 0 not tried, 1 made, -1 failed */
    int capturing;           /* inside a captured glBegin(GL_QUADS / GL_QUAD_STRIP) */
    int native_begin;        /* inside a glBegin forwarded to the driver */
    int slow;                /* capturing or compiling: calls take the slow path of pl_touch */
    unsigned dirty;          /* PL_D_STATE groups changed since the GL path last drew */
    unsigned images_seen;    /* pl_share_images when the GL path last drew */
    float cur[QGL__NATTR][4];/* the driver's current attributes as the calls left them */
    unsigned char cur_edge;
    unsigned cur_known;      /* attributes (and QGL__A_EDGE) whose value above is known */
    unsigned cur_lazy;       /* of those, the ones the driver has not been given yet: set by
                                primitives that joined the pending batch (pl_cur_sync) */
    pl_prim prim;            /* the primitive being captured */
    pl_prim scratch;         /* vertex-array draws */
    pl_prim batch;           /* finished GL_QUADS primitives not drawn yet (draw.c) */
    int swapped;             /* a swap went through us: batches are drawn before every frame ends */
    pl_list *compiling;      /* the display list being compiled, or NULL */
    GLenum compile_mode;
    unsigned seg_dirty;      /* while compiling: what the open segment's calls change */
    int list_depth;
    GLint list_base;         /* glListBase's value, kept because glCallLists inside the driver's
                                glBegin (after a hand-over) may not ask the driver */
    int list_base_known;
    int bound;               /* threads it is current on (0 or 1) */
    int dead;                /* destroyed while current elsewhere: freed at release */
    uint64_t published[PL_ST_COUNT]; /* its GL path's counters already in the totals */
    struct pl_ctx *next;
};

extern __thread pl_ctx *pl_tls_ctx __attribute__((tls_model("initial-exec")));

/* The current context of this thread; detects it through the window systems when no
 * MakeCurrent was seen (a program that resolved them past us). NULL when none. */
pl_ctx *pl_current(void);
pl_ctx *pl_ctx_lookup(int api, void *handle, int create);
void pl_ctx_created(int api, void *handle, int share_api, void *share_handle);
void pl_ctx_bind(int api, void *handle);   /* this thread's current (NULL handle: none) */
void pl_ctx_destroyed(int api, void *handle);
/* The GL path, created on first use, told what changed since it last drew. */
qgl_context *pl_ctx_qgl(pl_ctx *x);
void pl_ctx_publish_all(void);              /* every live context's counters into the totals */

/* ---- tracking what calls change (track.c) ------------------------------------------------ */

/* Capturing, compiling or a pending batch sends every call through pl_touch's slow path. */
static inline void pl_update_slow(pl_ctx *x)
{
    x->slow = x->capturing || x->compiling != NULL || x->batch.v.n != 0;
}

/* The driver's entry points as the GL path's table (resolved once, for replays). */
struct qgl__gl *pl_gl(void);

/* GL_INVALID_OPERATION from the driver, as a call GL forbids inside glBegin/glEnd gives (or,
 * inside the driver's own glBegin, as a primitive begun there gives). Inside a primitive of a
 * list being compiled the error is compiled (and raised when the list runs), as the call
 * itself would be. */
void pl_invalid_operation(void);
void pl_touch_slow(pl_ctx *x, unsigned mask);
void pl_share_images_changed(pl_share *s);
unsigned pl_share_images(const pl_share *s);

/* The driver gets the current values it has not been given (x->cur_lazy). */
void pl_cur_sync(pl_ctx *x);

/* Notes what a call (or a list segment of calls) changed, for the GL path's next draw. */
static inline void pl_mark(pl_ctx *x, unsigned mask)
{
    x->dirty |= mask & PL_D_STATE;
    if (mask & PL_D_TEXIMAGE)
        pl_share_images_changed(x->share);
    if (mask & PL_D_CURRENT) {
        if (x->cur_lazy)
            pl_cur_sync(x);
        x->cur_known = 0;
    }
    if (mask & PL_D_LIST_BASE)
        x->list_base_known = 0;
}

/* Every call that is not an attribute or a vertex: draws the pending batch, notes what the
 * call changes; returns 1 when the call must not reach the driver (it was made inside a
 * captured glBegin/glEnd, where GL forbids it: the driver's error has been raised instead). */
static inline int pl_touch(unsigned mask)
{
    pl_ctx *x = pl_tls_ctx;
    if (PL_LIKELY(x == NULL))
        return 0;
    if (PL_UNLIKELY(x->slow)) {
        if (x->capturing) {
            pl_invalid_operation();
            return 1;
        }
        pl_touch_slow(x, mask); /* draws a pending batch in the state it was made in */
    }
    pl_mark(x, mask);
    return 0;
}

/* A pure query: only its place inside a captured glBegin/glEnd matters (under GL_COMPILE
 * that glBegin is only compiled, and the query is legal). */
static inline int pl_inside_capture(void)
{
    pl_ctx *x = pl_tls_ctx;
    if (PL_LIKELY(x == NULL))
        return 0;
    if (PL_UNLIKELY(x->cur_lazy) && !x->capturing)
        pl_cur_sync(x); /* the query may read them */
    if (PL_LIKELY(!x->capturing) || (x->compiling && x->compile_mode == GL_COMPILE))
        return 0;
    pl_invalid_operation();
    return 1;
}

void pl_uncaptured_slow(pl_ctx *x);

/* A call GL allows inside glBegin/glEnd that the capture does not represent (colour indices,
 * integer, double, packed and half-float attributes): it may change the current attributes;
 * inside a captured primitive the driver takes the primitive over first (pl_cap_to_driver),
 * and while compiling it goes into a segment. */
static inline void pl_touch_uncaptured(void)
{
    pl_ctx *x = pl_tls_ctx;
    if (PL_LIKELY(x == NULL))
        return;
    if (x->cur_lazy)
        pl_cur_sync(x);
    x->cur_known = 0;
    if (PL_UNLIKELY(x->slow))
        pl_uncaptured_slow(x);
}

/* The current value of attribute a (QGL__AT_*; 4 floats), asked of the driver if unknown. */
void pl_current_value(pl_ctx *x, int a, float out[4]);
GLboolean pl_current_edge(pl_ctx *x);
/* Vertices [from, to) of slot a (a row of QGL__ATTRIBS, QGL__NATTR for the edge flag) take
 * val (edge, for the edge flag); pl_fill_current: the context's current value. */
void pl_verts_fill(qgl__verts *v, int a, size_t from, size_t to, const float *val, unsigned char edge);
void pl_fill_current(pl_ctx *x, qgl__verts *v, int a, size_t from, size_t to);
/* The driver's current value of a changes to v (not while only compiling a list). */
static inline void pl_note_current(pl_ctx *x, int a, const float v[4])
{
    if (PL_UNLIKELY(x->compiling) && x->compile_mode == GL_COMPILE)
        return;
    float *c = x->cur[a];
    c[0] = v[0], c[1] = v[1], c[2] = v[2], c[3] = v[3];
    x->cur_known |= 1u << a;
    x->cur_lazy &= ~(1u << a); /* the driver is given it as well */
}

/* While compiling: a call the driver must compile comes next (a segment is opened for it). */
void pl_list_state(pl_ctx *x);
/* While compiling: a finished primitive (of any mode) joins the list's geometry. */
void pl_list_add_prim(pl_ctx *x, const pl_prim *p);
/* While compiling: an attribute call between primitives (slot QGL__NATTR: the edge flag). */
void pl_list_attrib(pl_ctx *x, int slot, const float v[4]);
/* While compiling: the driver compiles a glBegin (inside 1) or a glEnd (0) that its list leaves
 * open or closes, so that running the list tells whether the driver is inside a primitive. */
void pl_list_begin_end(pl_ctx *x, int inside);
/* While compiling under GL_COMPILE_AND_EXECUTE: the driver takes over a primitive (see
 * pl_cap_to_driver); its calls are compiled only until its glEnd (or glEndList), then run
 * (pl_list_end_prim, a no-op otherwise). */
void pl_list_defer(pl_ctx *x);
void pl_list_end_prim(pl_ctx *x);

/* ---- batches of finished primitives (draw.c) --------------------------------------------- */

/* Draws the pending batch, if any. */
void pl_batch_flush(pl_ctx *x);
/* Captures x->prim, a glBegin(GL_QUADS) outside a list, straight into the batch when it may
 * join it (capture.c). */
void pl_prim_direct(pl_ctx *x);
/* A primitive captured into the batch takes its own arrays (before anything but the capture's
 * calls reads it, and before the batch is drawn). */
void pl_prim_settle(pl_ctx *x);
/* glEnd of a primitive captured into the batch: its whole quads join it. */
void pl_end_direct(pl_ctx *x, pl_prim *p);
/* An attribute call outside glBegin/glEnd is about to change slot a's current value (slot
 * QGL__NATTR: the edge flag), which the pending batch does not carry: its vertices keep the
 * value they were given. */
void pl_batch_keep(pl_ctx *x, int a);

/* ---- capture (capture.c, arrays.c) -------------------------------------------------------- */

void pl_cap_vertex(pl_ctx *x, float a, float b, float c, float d);
void pl_cap_attrib(pl_ctx *x, int a, float s, float t, float r, float q);
void pl_cap_texcoord(pl_ctx *x, GLenum unit, float s, float t, float r, float q);
void pl_cap_edgeflag(pl_ctx *x, GLboolean flag);
void pl_cap_generic(pl_ctx *x, GLuint index, float s, float t, float r, float q);
void pl_cap_array_element(pl_ctx *x, GLint i);
/* The driver takes over the primitive being captured (into the list's segment while compiling). */
void pl_cap_to_driver(pl_ctx *x);

/* The hooks of the generated attribute and vertex wrappers: 1 when the call was captured (it
 * must not reach the driver), 0 when it goes on to the driver. */
/* Between primitives while compiling, an attribute call joins the list's geometry; under
 * GL_COMPILE it does not run now. */
/* always inlined: a test and four stores for an attribute given again inside a primitive */
static inline __attribute__((always_inline)) int pl_hook_attrib(pl_ctx *x, int a, float s, float t, float r, float q)
{
    if (x->capturing) {
        pl_prim *p = &x->prim;
        if (PL_LIKELY(p->v.mask & (1u << a))) { /* given before in this primitive: only the value changes */
            float *c = p->direct ? x->cur[a] : p->cur[a];
            c[0] = s, c[1] = t, c[2] = r, c[3] = q;
        } else {
            pl_cap_attrib(x, a, s, t, r, q);
        }
        return 1;
    }
    const float v[4] = {s, t, r, q};
    if (PL_UNLIKELY(x->compiling)) {
        pl_list_attrib(x, a, v);
        if (x->compile_mode == GL_COMPILE)
            return 1;
    }
    if (PL_UNLIKELY(x->batch.v.n) && !(x->batch.v.mask & (1u << a)))
        pl_batch_keep(x, a);
    pl_note_current(x, a, v);
    return 0;
}

static inline int pl_hook_texcoord(pl_ctx *x, GLenum unit, float s, float t, float r, float q)
{
    if (unit < PL_TEXUNITS)
        return pl_hook_attrib(x, QGL__AT_TEX0 + (int)unit, s, t, r, q);
    if (x->capturing) {
        pl_cap_texcoord(x, unit, s, t, r, q);
        return 1;
    }
    pl_batch_flush(x);
    if (PL_UNLIKELY(x->compiling))
        pl_list_state(x);
    return 0;
}

static inline int pl_hook_vertex(pl_ctx *x, float a, float b, float c, float d)
{
    if (!x->capturing) {
        if (PL_UNLIKELY(x->compiling))
            pl_list_state(x);
        return 0;
    }
    pl_cap_vertex(x, a, b, c, d);
    return 1;
}

int pl_hook_edgeflag(pl_ctx *x, GLboolean flag);
int pl_hook_generic(pl_ctx *x, GLuint index, float s, float t, float r, float q);
/* fv or iv holds `given` values (1 for glMaterialf/i, which the driver pads with zeros). */
int pl_hook_material(pl_ctx *x, GLenum face, GLenum pname, const GLfloat *fv, const GLint *iv, int given);
int pl_hook_array_element(pl_ctx *x, GLint i);

/* Fills p with the vertices of an array draw (type 0: first .. first + count - 1, else count
 * indices of that type).
 * Returns 0, or -1 when the array state is one the capture does not model (the caller then
 * lets the driver draw). */
int pl_arrays_capture(pl_ctx *x, pl_prim *p, GLenum mode, GLint first, GLsizei count, GLenum type,
                      const void *indices);

/* ---- drawing (draw.c) ------------------------------------------------------------------------ */

/* Draws a finished primitive in the current state (after the pending batch): fills attributes
 * given only from a later vertex from the current values, draws, and leaves the current
 * attributes as GL would. */
void pl_draw_prim(pl_ctx *x, pl_prim *p);
/* The same for a primitive just finished outside a list (glEnd, an array draw): it may join
 * the pending batch instead of being drawn now. */
void pl_end_prim(pl_ctx *x, pl_prim *p);
/* Sets the current attributes to the last values given in p (what glEnd leaves behind). */
void pl_prim_apply_current(pl_ctx *x, const pl_prim *p);
/* The calls that draw p in the driver (glBegin, attributes, vertices, glEnd, materials). */
void pl_prim_emit(pl_ctx *x, const pl_prim *p);
/* The driver's glBegin and p's vertices so far, then the values its next vertex takes: the rest
 * of the primitive goes to the driver as the program's own calls. */
void pl_prim_to_driver(pl_ctx *x, const pl_prim *p);
/* Whether the driver fills both faces' polygons (its display lists then draw GL_QUADS as the
 * triangles 0-1-3, 1-2-3; otherwise as quads, keeping their outlines and edge flags). */
int pl_polygons_filled(void);
/* Whether p goes to the driver as it is rather than through the GL path. */
int pl_prim_for_driver(pl_ctx *x, const pl_prim *p);

/* ---- display lists (lists.c) ----------------------------------------------------------------- */

void pl_share_unref(pl_share *s);
pl_share *pl_share_new(void);
void pl_share_ref(pl_share *s);

#endif
