/* track.c: what the program's calls change, so the GL path asks the driver only about that.
 *
 * The GL path reads the state it plans with in groups (matrices, rasterization, the
 * fixed-function key, bindings: gl_internal.h's QGL__D_*). Every exported call marks the groups
 * it may change (gen_entries.py's rules; glEnable and glDisable by their capability, here) in
 * the context's dirty set, which the GL path receives before its next draw; so a program that
 * only moves its matrices between primitives costs two matrix queries per draw instead of
 * forty. The current attributes (colour, normal, ...) are kept from the attribute calls
 * themselves; a call that may change them otherwise (glPopAttrib, an array draw, a display
 * list) makes them unknown, and they are asked of the driver when next needed. While a list
 * is compiled, the marks of the calls it records are kept with the open segment, to be
 * applied when the list runs. */
#include "preload.h"

#include <string.h>

void pl_invalid_operation(void)
{
    pl_ctx *x = pl_tls_ctx;
    if (x && x->capturing && x->compiling)
        pl_list_state(x);
    if (x && x->native_begin)
        REAL(glBegin)(GL_POINTS); /* a glBegin inside the driver's: the error, nothing else */
    else
        REAL(glEnd)(); /* the driver saw no glBegin: GL_INVALID_OPERATION, nothing else */
}

void pl_uncaptured_slow(pl_ctx *x)
{
    if (x->capturing)
        pl_cap_to_driver(x);
    if (x->compiling) {
        pl_list_state(x);
        x->seg_dirty |= PL_D_CURRENT;
    }
}

/* A pending batch is drawn before the call can change what it looks like; while compiling,
 * every call that is not geometry goes into a segment the driver compiles. */
void pl_touch_slow(pl_ctx *x, unsigned mask)
{
    pl_batch_flush(x);
    if (x->compiling) {
        pl_list_state(x);
        x->seg_dirty |= mask;
    }
}

void pl_cur_sync(pl_ctx *x)
{
    struct qgl__gl *gl = pl_gl();
    unsigned m = x->cur_lazy;
    x->cur_lazy = 0;
    for (unsigned b = m & QGL__A_ATTRIBS; b; b &= b - 1) {
        int a = __builtin_ctz(b);
        qgl__set_current(gl, a, x->cur[a]);
    }
    if (m & QGL__A_EDGE)
        gl->EdgeFlag(x->cur_edge);
}

void pl_current_value(pl_ctx *x, int a, float out[4])
{
    if (!(x->cur_known & (1u << a))) {
        float v[4] = {0, 0, 0, 1};
        int unit = qgl__attribs[a].unit;
        GLint active = GL_TEXTURE0;
        if (unit >= 0) {
            REAL(glGetIntegerv)(GL_ACTIVE_TEXTURE, &active);
            REAL(glActiveTexture)(GL_TEXTURE0 + (GLenum)unit);
        }
        REAL(glGetFloatv)(qgl__attribs[a].current, v);
        if (unit >= 0)
            REAL(glActiveTexture)((GLenum)active);
        memcpy(x->cur[a], v, sizeof v);
        x->cur_known |= 1u << a;
    }
    memcpy(out, x->cur[a], 4 * sizeof(float));
}

GLboolean pl_current_edge(pl_ctx *x)
{
    if (!(x->cur_known & QGL__A_EDGE)) {
        GLboolean e = GL_TRUE;
        REAL(glGetBooleanv)(GL_EDGE_FLAG, &e);
        x->cur_edge = e;
        x->cur_known |= QGL__A_EDGE;
    }
    return x->cur_edge;
}

/* The groups a capability's glEnable or glDisable changes: whether drawing order shows for
 * depth test, blending, stencil and logic op, none for those the GL path never reads (other
 * per-fragment tests, smoothing, ...), the key for the rest and for any it does not know. */
static unsigned pl_cap_mask(GLenum cap)
{
    switch (cap) {
    case GL_DEPTH_TEST: case GL_BLEND: case GL_STENCIL_TEST: case GL_COLOR_LOGIC_OP:
        return PL_D_ORDER;
    case GL_CULL_FACE: case GL_ALPHA_TEST:
    case GL_SCISSOR_TEST: case GL_DITHER: case GL_LINE_SMOOTH: case GL_POINT_SMOOTH: case GL_POLYGON_SMOOTH:
    case GL_LINE_STIPPLE: case GL_POLYGON_STIPPLE: case GL_INDEX_LOGIC_OP:
    case GL_MULTISAMPLE: case GL_SAMPLE_ALPHA_TO_COVERAGE: case GL_SAMPLE_ALPHA_TO_ONE: case GL_SAMPLE_COVERAGE:
    case GL_POLYGON_OFFSET_LINE: case GL_POLYGON_OFFSET_POINT: case GL_AUTO_NORMAL: case GL_FRAMEBUFFER_SRGB:
    case GL_POINT_SPRITE: case GL_PROGRAM_POINT_SIZE: case GL_PRIMITIVE_RESTART: case GL_DEBUG_OUTPUT:
    case GL_DEBUG_OUTPUT_SYNCHRONOUS: case GL_TEXTURE_CUBE_MAP_SEAMLESS:
    case GL_MAP1_VERTEX_3: case GL_MAP1_VERTEX_4: case GL_MAP1_COLOR_4: case GL_MAP1_NORMAL: case GL_MAP1_INDEX:
    case GL_MAP1_TEXTURE_COORD_1: case GL_MAP1_TEXTURE_COORD_2: case GL_MAP1_TEXTURE_COORD_3:
    case GL_MAP1_TEXTURE_COORD_4: case GL_MAP2_VERTEX_3: case GL_MAP2_VERTEX_4: case GL_MAP2_COLOR_4:
    case GL_MAP2_NORMAL: case GL_MAP2_INDEX: case GL_MAP2_TEXTURE_COORD_1: case GL_MAP2_TEXTURE_COORD_2:
    case GL_MAP2_TEXTURE_COORD_3: case GL_MAP2_TEXTURE_COORD_4:
        return 0;
    case GL_POLYGON_OFFSET_FILL:
        return PL_D_RASTER;
    default:
        return PL_D_FFP;
    }
}

PL_EXPORT void glEnable(GLenum cap)
{
    if (PL_UNLIKELY(pl_touch(pl_cap_mask(cap))))
        return;
    REAL(glEnable)(cap);
}

PL_EXPORT void glDisable(GLenum cap)
{
    if (PL_UNLIKELY(pl_touch(pl_cap_mask(cap))))
        return;
    REAL(glDisable)(cap);
}
