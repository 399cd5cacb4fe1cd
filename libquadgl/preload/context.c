/* context.c: one record per GL context of the program, and which one each thread uses.
 *
 * The window-system wrappers (winsys.c) report contexts as they are created (with the
 * context whose display lists they share), made current and destroyed; a record holds the
 * capture state, the display-list namespace it shares, and the GL path's context, which is
 * made lazily on the first quad drawn in it (the GL path needs the context current, and
 * most contexts of most programs never draw a quad). Each thread keeps its current record
 * in a thread-local pointer, so the wrappers' common path reads one variable. Records are
 * found by the window system's handle in a short list under a mutex; lookups happen only at
 * creation, MakeCurrent and destruction. A context nobody told us about (a program that
 * reached MakeCurrent past us) is detected through GetCurrentContext when it first draws a
 * quad. A context's counters join the statistics' totals at each frame and when it goes. */
#include "preload.h"

#include <stdlib.h>
#include <string.h>

__thread pl_ctx *pl_tls_ctx __attribute__((tls_model("initial-exec")));

static pthread_mutex_t pl_ctx_lock = PTHREAD_MUTEX_INITIALIZER;
static pl_ctx *pl_ctx_head;

static pl_ctx *pl_find_locked(int api, void *handle)
{
    for (pl_ctx *x = pl_ctx_head; x; x = x->next)
        if (x->api == api && x->handle == handle)
            return x;
    return NULL;
}

static pl_ctx *pl_new_locked(int api, void *handle, pl_share *share)
{
    pl_ctx *x = calloc(1, sizeof *x);
    if (!x)
        return NULL;
    x->api = api;
    x->handle = handle;
    x->share = share ? share : pl_share_new();
    if (share)
        pl_share_ref(share);
    if (!x->share) {
        free(x);
        return NULL;
    }
    x->next = pl_ctx_head;
    pl_ctx_head = x;
    return x;
}

pl_ctx *pl_ctx_lookup(int api, void *handle, int create)
{
    pl_ctx *x;
    if (!handle)
        return NULL;
    pthread_mutex_lock(&pl_ctx_lock);
    x = pl_find_locked(api, handle);
    if (!x && create)
        x = pl_new_locked(api, handle, NULL);
    pthread_mutex_unlock(&pl_ctx_lock);
    return x;
}

void pl_ctx_created(int api, void *handle, int share_api, void *share_handle)
{
    pl_ctx *s;
    if (!handle)
        return;
    pthread_mutex_lock(&pl_ctx_lock);
    /* A context made through another of our wrappers (OSMesaCreateContextExt calls
     * OSMesaCreateContextAttribs) is already known. */
    if (!pl_find_locked(api, handle)) {
        s = share_handle ? pl_find_locked(share_api, share_handle) : NULL;
        if (share_handle && !s)
            s = pl_new_locked(share_api, share_handle, NULL);
        pl_new_locked(api, handle, s ? s->share : NULL);
    }
    pthread_mutex_unlock(&pl_ctx_lock);
}

static void pl_ctx_free(pl_ctx *x)
{
    qgl__gl_forget(x->qgl);
    pl_prim_free(&x->prim);
    pl_prim_free(&x->scratch);
    pl_prim_free(&x->batch);
    pl_share_unref(x->share);
    free(x);
}

/* Unlinks x; frees it unless a thread still has it current. Called with the lock held. */
static void pl_retire_locked(pl_ctx *x)
{
    for (pl_ctx **p = &pl_ctx_head; *p; p = &(*p)->next)
        if (*p == x) {
            *p = x->next;
            break;
        }
    if (x->bound)
        x->dead = 1;
    else
        pl_ctx_free(x);
}

/* Drops the GL path's context; its GL objects can only be deleted while x is current here
 * (else they go with the GL context, or stay with its share group). Current on another
 * thread, it is freed when that thread lets x go (pl_ctx_free). */
static void pl_drop_qgl(pl_ctx *x, int is_current)
{
    if (x->qgl && is_current) {
        qgl_gl_make_current(NULL);
        qgl_gl_destroy(x->qgl);
        x->qgl = NULL;
    } else if (x->qgl && !x->bound) {
        pl_log(PL_LOG_DEBUG, "context destroyed while not current: its GL path's objects go with it");
        qgl__gl_forget(x->qgl);
        x->qgl = NULL;
    }
}

void pl_ctx_destroyed(int api, void *handle)
{
    pl_ctx *x;
    pthread_mutex_lock(&pl_ctx_lock);
    x = pl_find_locked(api, handle);
    if (x) {
        pl_stats_publish(x);
        pl_drop_qgl(x, x == pl_tls_ctx);
        pl_retire_locked(x);
    }
    pthread_mutex_unlock(&pl_ctx_lock);
}

static void pl_unbind(pl_ctx *x)
{
    if (!x)
        return;
    pthread_mutex_lock(&pl_ctx_lock);
    x->bound = 0;
    if (x->dead)
        pl_ctx_free(x);
    pthread_mutex_unlock(&pl_ctx_lock);
}

void pl_ctx_bind(int api, void *handle)
{
    pl_ctx *old = pl_tls_ctx, *x = handle ? pl_ctx_lookup(api, handle, 1) : NULL;
    if (old == x)
        return;
    pl_unbind(old);
    if (x)
        x->bound = 1;
    pl_tls_ctx = x;
    qgl_gl_make_current(x ? x->qgl : NULL);
}

typedef void *(*pl_current_fn)(void);

/* Which window system has a context current on this thread, asked directly. */
pl_ctx *pl_current(void)
{
    static const struct {
        const char *name;
        int api;
    } getters[] = {{"glXGetCurrentContext", PL_API_GLX},
                   {"OSMesaGetCurrentContext", PL_API_OSMESA},
                   {"eglGetCurrentContext", PL_API_EGL}};
    if (pl_tls_ctx)
        return pl_tls_ctx;
    for (size_t i = 0; i < sizeof getters / sizeof getters[0]; i++) {
        pl_current_fn get = (pl_current_fn)pl_next_symbol(getters[i].name);
        void *h = get ? get() : NULL;
        if (h) {
            pl_log(PL_LOG_DEBUG, "found a current context through %s", getters[i].name);
            pl_ctx_bind(getters[i].api, h);
            return pl_tls_ctx;
        }
    }
    return NULL;
}

qgl_context *pl_ctx_qgl(pl_ctx *x)
{
    if (x->qgl_state == 0) {
        qgl_gl_desc desc;
        memset(&desc, 0, sizeof desc);
        desc.method = (qgl_method)pl_cfg.method;
        desc.tolerance_px = pl_cfg.tolerance;
        desc.get_proc = pl_real_proc;
        x->qgl = qgl_gl_create(&desc);
        x->qgl_state = x->qgl ? 1 : -1;
        if (x->qgl)
            qgl__state_track(x->qgl); /* every call passes track.c: it marks what changes */
        if (!x->qgl)
            pl_log(PL_LOG_WARN, "the GL path could not start in this context; quads go to the driver");
        else
            pl_log(PL_LOG_INFO, "GL path ready");
        qgl_gl_make_current(x->qgl);
    }
    if (PL_UNLIKELY(__atomic_load_n(&pl_untracked, __ATOMIC_RELAXED)))
        x->dirty |= PL_D_STATE;
    unsigned images = pl_share_images(x->share);
    if (images != x->images_seen) {
        x->images_seen = images;
        x->dirty |= PL_D_TEXIMAGE;
    }
    if (x->qgl && x->dirty) {
        qgl__state_dirty(x->qgl, x->dirty);
        x->dirty = 0;
    }
    return x->qgl;
}

void pl_ctx_publish_all(void)
{
    pthread_mutex_lock(&pl_ctx_lock);
    for (pl_ctx *x = pl_ctx_head; x; x = x->next)
        pl_stats_publish(x);
    pthread_mutex_unlock(&pl_ctx_lock);
}
