/* dispatch.c: fill the GL dispatch table from a resolver, never from link-time symbols.
 *
 * The names come from the X-macro list in gl_internal.h. With no resolver in the desc we ask
 * whichever window system has a current context (OSMesa, GLX, EGL; each found with dlsym so
 * there is no link-time dependency on any of them) and fall back to dlsym(RTLD_DEFAULT). The
 * order matters with GLVND: its libGL exports every gl* name as a stub that dispatches to the
 * current GLX context, so a plain dlsym would silently route an OSMesa program to no-ops. */
#include <dlfcn.h>
#include <string.h>

#include "gl_internal.h"

typedef void *(*qgl__getproc)(const char *);
typedef void *(*qgl__getcur)(void);

static void *sym(const char *name)
{
    return dlsym(RTLD_DEFAULT, name);
}

/* The GetProcAddress of the window system whose context is current, or NULL. */
static qgl__getproc current_window_system(void)
{
    static const char *const pairs[][2] = {
        {"OSMesaGetCurrentContext", "OSMesaGetProcAddress"},
        {"glXGetCurrentContext", "glXGetProcAddressARB"},
        {"eglGetCurrentContext", "eglGetProcAddress"},
    };
    for (size_t i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
        void *cur = sym(pairs[i][0]);
        void *proc = sym(pairs[i][1]);
        if (cur && proc && ((qgl__getcur)cur)())
            return (qgl__getproc)proc;
    }
    return NULL;
}

static void *resolve(qgl__getproc get_proc, const char *name)
{
    void *f = get_proc ? get_proc(name) : NULL;
    return f ? f : sym(name);
}

/* A missing GL 1.x entry point on a GL 2+ context is a resolver problem: report it. */
int qgl__gl_load(struct qgl__gl *gl, void *(*get_proc)(const char *))
{
    qgl__getproc gp = get_proc ? get_proc : current_window_system();
    int ok = 1;
    memset(gl, 0, sizeof *gl);
#define QGL__LOAD_REQ(ret, name, params) \
    *(void **)&gl->name = resolve(gp, "gl" #name); \
    ok = ok && gl->name;
#define QGL__LOAD_OPT(ret, name, params) *(void **)&gl->name = resolve(gp, "gl" #name);
    QGL__GL_FUNCS(QGL__LOAD_REQ)
    QGL__GL_FUNCS_OPT(QGL__LOAD_OPT)
#undef QGL__LOAD_REQ
#undef QGL__LOAD_OPT
    return ok;
}
