/* winsys.c: the window-system entry points the preload library wraps (GLX, EGL, OSMesa, dlopen).
 *
 * Context creation, MakeCurrent and destruction are passed to the real functions and then
 * reported to context.c, which keeps one record per context and the current one per thread.
 * The GetProcAddress functions answer with our own wrapper for every name we handle, so a
 * program that looks its functions up (GLEW, GLFW, SDL, PyOpenGL) gets the same capture as
 * one that links them. A program that opens libGL.so.1, libGLX or libOpenGL itself is handed
 * a handle to this library instead (after the real library is loaded): dlsym on it finds our
 * wrappers first and, through our dependency on libGL, the driver's functions for everything
 * else. Any other dlopen is a tail call to the real one, so the loader still sees the
 * program as the caller (its RUNPATH applies). The window-system types are opaque here; the
 * wrappers only pass them on. */
#include "preload.h"

#include <dlfcn.h>
#include <string.h>

typedef void (*pl_voidfn)(void);

/* The real function `name`, looked up once; the pointer type is the caller's. */
#define PL_NEXT(type, name)                                         \
    static type real_fn;                                            \
    if (!real_fn)                                                   \
        real_fn = (type)pl_next_symbol(name);

/* Before the current context changes (or its drawable), its pending batch is drawn. */
static void pl_leave_current(void)
{
    pl_ctx *x = pl_tls_ctx;
    if (x && !x->capturing)
        pl_batch_flush(x);
}

/* ---- GLX ----------------------------------------------------------------------------------- */

typedef int (*pl_glx_make_current)(void *, unsigned long, void *);
typedef int (*pl_glx_make_context_current)(void *, unsigned long, unsigned long, void *);
typedef void *(*pl_glx_create)(void *, void *, void *, int);
typedef void *(*pl_glx_create_new)(void *, void *, int, void *, int);
typedef void *(*pl_glx_create_attribs)(void *, void *, void *, int, const int *);
typedef void (*pl_glx_destroy)(void *, void *);
typedef pl_voidfn (*pl_getproc)(const char *);

PL_EXPORT int glXMakeCurrent(void *dpy, unsigned long drawable, void *ctx)
{
    int ok;
    PL_NEXT(pl_glx_make_current, "glXMakeCurrent");
    if (!real_fn)
        return 0;
    pl_leave_current();
    ok = real_fn(dpy, drawable, ctx);
    if (ok)
        pl_ctx_bind(PL_API_GLX, ctx);
    return ok;
}

PL_EXPORT int glXMakeContextCurrent(void *dpy, unsigned long draw, unsigned long read, void *ctx)
{
    int ok;
    PL_NEXT(pl_glx_make_context_current, "glXMakeContextCurrent");
    if (!real_fn)
        return 0;
    pl_leave_current();
    ok = real_fn(dpy, draw, read, ctx);
    if (ok)
        pl_ctx_bind(PL_API_GLX, ctx);
    return ok;
}

PL_EXPORT void *glXCreateContext(void *dpy, void *vis, void *share, int direct)
{
    void *ctx;
    PL_NEXT(pl_glx_create, "glXCreateContext");
    ctx = real_fn ? real_fn(dpy, vis, share, direct) : NULL;
    pl_ctx_created(PL_API_GLX, ctx, PL_API_GLX, share);
    return ctx;
}

PL_EXPORT void *glXCreateNewContext(void *dpy, void *config, int type, void *share, int direct)
{
    void *ctx;
    PL_NEXT(pl_glx_create_new, "glXCreateNewContext");
    ctx = real_fn ? real_fn(dpy, config, type, share, direct) : NULL;
    pl_ctx_created(PL_API_GLX, ctx, PL_API_GLX, share);
    return ctx;
}

PL_EXPORT void *glXCreateContextAttribsARB(void *dpy, void *config, void *share, int direct, const int *attribs)
{
    void *ctx;
    PL_NEXT(pl_glx_create_attribs, "glXCreateContextAttribsARB");
    if (!real_fn)
        real_fn = (pl_glx_create_attribs)pl_real_proc("glXCreateContextAttribsARB");
    ctx = real_fn ? real_fn(dpy, config, share, direct, attribs) : NULL;
    pl_ctx_created(PL_API_GLX, ctx, PL_API_GLX, share);
    return ctx;
}

PL_EXPORT void glXDestroyContext(void *dpy, void *ctx)
{
    PL_NEXT(pl_glx_destroy, "glXDestroyContext");
    pl_ctx_destroyed(PL_API_GLX, ctx);
    if (real_fn)
        real_fn(dpy, ctx);
}

/* GLX functions that neither change GL state nor show a frame: configurations, drawables,
 * queries, swap intervals. SDL and GLEW look these up through glXGetProcAddress, and taking
 * them for unknown GL calls turned off batching and state tracking in every such program (a
 * full state query per draw, whose texture-unit switches make llvmpipe store its fragment
 * state again at every draw: tools/sdl-bench.sh). Any other glX name still counts as unknown
 * (glXCopyContext, glXBindTexImageEXT, glXUseXFont, glXWaitGL, a swap). */
static const char *const pl_glx_inert[] = {
    "glXChooseFBConfig", "glXChooseFBConfigSGIX", "glXChooseVisual", "glXCreateGLXPixmap", "glXCreatePbuffer",
    "glXCreatePixmap", "glXCreateWindow", "glXDestroyGLXPixmap", "glXDestroyPbuffer", "glXDestroyPixmap",
    "glXDestroyWindow", "glXGetClientString", "glXGetConfig", "glXGetContextIDEXT", "glXGetCurrentContext",
    "glXGetCurrentDisplay", "glXGetCurrentDisplayEXT", "glXGetCurrentDrawable", "glXGetCurrentReadDrawable",
    "glXGetCurrentReadDrawableSGI", "glXGetFBConfigAttrib", "glXGetFBConfigAttribSGIX", "glXGetFBConfigFromVisualSGIX",
    "glXGetFBConfigs", "glXGetMscRateOML", "glXGetSelectedEvent", "glXGetSwapIntervalMESA", "glXGetSyncValuesOML",
    "glXGetVideoSyncSGI", "glXGetVisualFromFBConfig", "glXGetVisualFromFBConfigSGIX", "glXIsDirect",
    "glXQueryContext", "glXQueryContextInfoEXT", "glXQueryCurrentRendererIntegerMESA",
    "glXQueryCurrentRendererStringMESA", "glXQueryDrawable", "glXQueryExtension", "glXQueryExtensionsString",
    "glXQueryRendererIntegerMESA", "glXQueryRendererStringMESA", "glXQueryServerString", "glXQueryVersion",
    "glXSelectEvent", "glXSwapIntervalEXT", "glXSwapIntervalMESA", "glXSwapIntervalSGI", "glXWaitForMscOML",
    "glXWaitForSbcOML", "glXWaitVideoSyncSGI", "glXWaitX",
};

static int pl_glx_is_inert(const char *name)
{
    for (size_t i = 0; i < sizeof pl_glx_inert / sizeof pl_glx_inert[0]; i++)
        if (strcmp(name, pl_glx_inert[i]) == 0)
            return 1;
    return 0;
}

/* A GL function the program gets past us could change any state: from then on the GL path
 * reads all of it at every draw. */
static pl_voidfn pl_getproc_via(const char *real_name, const char *name)
{
    pl_getproc real_fn = (pl_getproc)pl_next_symbol(real_name);
    void *own = pl_own_proc(name);
    pl_voidfn fn;
    if (own)
        return (pl_voidfn)own;
    fn = real_fn ? real_fn(name) : NULL;
    if (fn && name && name[0] == 'g' && name[1] == 'l' && !pl_glx_is_inert(name) &&
        !__atomic_load_n(&pl_untracked, __ATOMIC_RELAXED)) {
        __atomic_store_n(&pl_untracked, 1, __ATOMIC_RELAXED);
        pl_log(PL_LOG_INFO, "%s is not one of ours: the state is read at every draw", name);
    }
    return fn;
}

typedef void (*pl_glx_swap)(void *, unsigned long);

/* The frame ends: what waits in a batch is drawn into it first. */
static void pl_end_frame(void)
{
    pl_ctx *x = pl_tls_ctx;
    if (x && !x->capturing) {
        pl_batch_flush(x);
        x->swapped = 1;
    }
    if (pl_cfg.stats)
        pl_stats_frame(x);
}

PL_EXPORT void glXSwapBuffers(void *dpy, unsigned long drawable)
{
    PL_NEXT(pl_glx_swap, "glXSwapBuffers");
    pl_end_frame();
    if (real_fn)
        real_fn(dpy, drawable);
}

PL_EXPORT pl_voidfn glXGetProcAddressARB(const GLubyte *name)
{
    return pl_getproc_via("glXGetProcAddressARB", (const char *)name);
}

PL_EXPORT pl_voidfn glXGetProcAddress(const GLubyte *name)
{
    return pl_getproc_via("glXGetProcAddress", (const char *)name);
}

/* ---- EGL ------------------------------------------------------------------------------------ */

typedef unsigned (*pl_egl_make_current)(void *, void *, void *, void *);
typedef void *(*pl_egl_create)(void *, void *, void *, const int *);
typedef unsigned (*pl_egl_destroy)(void *, void *);

PL_EXPORT unsigned eglMakeCurrent(void *dpy, void *draw, void *read, void *ctx)
{
    unsigned ok;
    PL_NEXT(pl_egl_make_current, "eglMakeCurrent");
    if (!real_fn)
        return 0;
    pl_leave_current();
    ok = real_fn(dpy, draw, read, ctx);
    if (ok)
        pl_ctx_bind(PL_API_EGL, ctx);
    return ok;
}

PL_EXPORT void *eglCreateContext(void *dpy, void *config, void *share, const int *attribs)
{
    void *ctx;
    PL_NEXT(pl_egl_create, "eglCreateContext");
    ctx = real_fn ? real_fn(dpy, config, share, attribs) : NULL;
    pl_ctx_created(PL_API_EGL, ctx, PL_API_EGL, share);
    return ctx;
}

PL_EXPORT unsigned eglDestroyContext(void *dpy, void *ctx)
{
    PL_NEXT(pl_egl_destroy, "eglDestroyContext");
    pl_ctx_destroyed(PL_API_EGL, ctx);
    return real_fn ? real_fn(dpy, ctx) : 0;
}

typedef unsigned (*pl_egl_swap)(void *, void *);

PL_EXPORT unsigned eglSwapBuffers(void *dpy, void *surface)
{
    PL_NEXT(pl_egl_swap, "eglSwapBuffers");
    pl_end_frame();
    return real_fn ? real_fn(dpy, surface) : 0;
}

PL_EXPORT pl_voidfn eglGetProcAddress(const char *name)
{
    return pl_getproc_via("eglGetProcAddress", name);
}

/* ---- OSMesa --------------------------------------------------------------------------------- */

typedef GLboolean (*pl_os_make_current)(void *, void *, GLenum, GLsizei, GLsizei);
typedef void *(*pl_os_create)(GLenum, void *);
typedef void *(*pl_os_create_ext)(GLenum, GLint, GLint, GLint, void *);
typedef void *(*pl_os_create_attribs)(const int *, void *);
typedef void (*pl_os_destroy)(void *);

PL_EXPORT GLboolean OSMesaMakeCurrent(void *ctx, void *buffer, GLenum type, GLsizei width, GLsizei height)
{
    GLboolean ok;
    PL_NEXT(pl_os_make_current, "OSMesaMakeCurrent");
    if (!real_fn)
        return GL_FALSE;
    pl_leave_current();
    ok = real_fn(ctx, buffer, type, width, height);
    if (ok)
        pl_ctx_bind(PL_API_OSMESA, ctx);
    return ok;
}

PL_EXPORT void *OSMesaCreateContext(GLenum format, void *share)
{
    void *ctx;
    PL_NEXT(pl_os_create, "OSMesaCreateContext");
    ctx = real_fn ? real_fn(format, share) : NULL;
    pl_ctx_created(PL_API_OSMESA, ctx, PL_API_OSMESA, share);
    return ctx;
}

PL_EXPORT void *OSMesaCreateContextExt(GLenum format, GLint depth, GLint stencil, GLint accum, void *share)
{
    void *ctx;
    PL_NEXT(pl_os_create_ext, "OSMesaCreateContextExt");
    ctx = real_fn ? real_fn(format, depth, stencil, accum, share) : NULL;
    pl_ctx_created(PL_API_OSMESA, ctx, PL_API_OSMESA, share);
    return ctx;
}

PL_EXPORT void *OSMesaCreateContextAttribs(const int *attribs, void *share)
{
    void *ctx;
    PL_NEXT(pl_os_create_attribs, "OSMesaCreateContextAttribs");
    ctx = real_fn ? real_fn(attribs, share) : NULL;
    pl_ctx_created(PL_API_OSMESA, ctx, PL_API_OSMESA, share);
    return ctx;
}

PL_EXPORT void OSMesaDestroyContext(void *ctx)
{
    PL_NEXT(pl_os_destroy, "OSMesaDestroyContext");
    pl_ctx_destroyed(PL_API_OSMESA, ctx);
    if (real_fn)
        real_fn(ctx);
}

PL_EXPORT pl_voidfn OSMesaGetProcAddress(const char *name)
{
    return pl_getproc_via("OSMesaGetProcAddress", name);
}

/* ---- dlopen ---------------------------------------------------------------------------------- */

typedef void *(*pl_dlopen_fn)(const char *, int);

static pl_dlopen_fn pl_real_dlopen(void)
{
    static pl_dlopen_fn real_fn;
    if (!real_fn)
        real_fn = (pl_dlopen_fn)pl_next_symbol("dlopen");
    return real_fn;
}

/* The GL libraries a program may open for itself: their file name, any directory. */
static int pl_is_gl_library(const char *file)
{
    static const char *const names[] = {"libGL.so", "libGL.so.1", "libGLX.so", "libGLX.so.0",
                                        "libOpenGL.so", "libOpenGL.so.0"};
    const char *base = strrchr(file, '/');
    base = base ? base + 1 : file;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (strcmp(base, names[i]) == 0)
            return 1;
    return 0;
}

static void *pl_dlopen_gl(const char *file, int flags)
{
    pl_dlopen_fn real_fn = pl_real_dlopen();
    void *lib, *self;
    if (!real_fn)
        return NULL;
    flags &= ~RTLD_DEEPBIND; /* deep binding would let the library skip our wrappers */
    lib = real_fn(file, flags);
    if (!lib || !pl_self_path())
        return lib;
    self = real_fn(pl_self_path(), flags);
    if (!self)
        return lib;
    pl_log(PL_LOG_DEBUG, "dlopen(\"%s\") answered with the preload library", file);
    return self;
}

PL_EXPORT void *dlopen(const char *file, int flags)
{
    pl_dlopen_fn real_fn;
    if (file && pl_is_gl_library(file))
        return pl_dlopen_gl(file, flags);
    real_fn = pl_real_dlopen();
    if (!real_fn)
        return NULL;
    return real_fn(file, flags);
}

/* ---- the table for GetProcAddress ------------------------------------------------------------ */

const pl_proc pl_winsys_table[] = {
    {"glXGetProcAddress", (void *)glXGetProcAddress},
    {"glXGetProcAddressARB", (void *)glXGetProcAddressARB},
    {"glXMakeCurrent", (void *)glXMakeCurrent},
    {"glXMakeContextCurrent", (void *)glXMakeContextCurrent},
    {"glXCreateContext", (void *)glXCreateContext},
    {"glXCreateNewContext", (void *)glXCreateNewContext},
    {"glXCreateContextAttribsARB", (void *)glXCreateContextAttribsARB},
    {"glXDestroyContext", (void *)glXDestroyContext},
    {"glXSwapBuffers", (void *)glXSwapBuffers},
    {"eglGetProcAddress", (void *)eglGetProcAddress},
    {"eglMakeCurrent", (void *)eglMakeCurrent},
    {"eglCreateContext", (void *)eglCreateContext},
    {"eglDestroyContext", (void *)eglDestroyContext},
    {"eglSwapBuffers", (void *)eglSwapBuffers},
    {"OSMesaGetProcAddress", (void *)OSMesaGetProcAddress},
    {"OSMesaMakeCurrent", (void *)OSMesaMakeCurrent},
    {"OSMesaCreateContext", (void *)OSMesaCreateContext},
    {"OSMesaCreateContextExt", (void *)OSMesaCreateContextExt},
    {"OSMesaCreateContextAttribs", (void *)OSMesaCreateContextAttribs},
    {"OSMesaDestroyContext", (void *)OSMesaDestroyContext},
};
const int pl_winsys_count = (int)(sizeof pl_winsys_table / sizeof pl_winsys_table[0]);
