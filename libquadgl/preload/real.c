/* real.c: finding the driver's own functions behind the ones this library exports.
 *
 * Every slot starts at a generated stub that resolves it on its first call, so nothing is
 * looked up before the program uses it and no constructor touches GL. A name is searched,
 * in order, as the next definition after this library (dlsym RTLD_NEXT: libGL, libOSMesa,
 * libOpenGL, whatever the program linked), through the window systems' GetProcAddress (for
 * extension functions a library does not export), and in libGL.so.1 / libOpenGL.so.0 opened
 * by hand. Any candidate that lies inside this library is refused, so a wrapper can never
 * resolve to itself and recurse. A name found nowhere gets a generated stand-in that does
 * nothing, with one warning. */
#include "preload.h"

#include <dlfcn.h>
#include <link.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const char pl_self_marker = 0;

int pl_untracked;

/* The addresses this library is loaded at, to recognise our own functions. dladdr would
 * do, but it searches the symbols of the library an address lies in, and a driver's has
 * thousands: 360 lookups cost glmatrix 41 million instructions at its start. */
static struct {
    pthread_once_t once;
    uintptr_t lo, hi;
} pl_self = {PTHREAD_ONCE_INIT, 0, 0};

static int pl_self_segments(struct dl_phdr_info *info, size_t size, void *data)
{
    uintptr_t marker = (uintptr_t)&pl_self_marker, lo = UINTPTR_MAX, hi = 0;
    (void)size, (void)data;
    for (int i = 0; i < info->dlpi_phnum; i++) {
        const ElfW(Phdr) *ph = &info->dlpi_phdr[i];
        if (ph->p_type != PT_LOAD)
            continue;
        uintptr_t a = info->dlpi_addr + ph->p_vaddr;
        lo = a < lo ? a : lo;
        hi = a + ph->p_memsz > hi ? a + ph->p_memsz : hi;
    }
    if (marker < lo || marker >= hi)
        return 0;
    pl_self.lo = lo, pl_self.hi = hi;
    return 1;
}

const char *pl_self_path(void)
{
    static const char *path;
    if (!path) {
        Dl_info info;
        if (dladdr(&pl_self_marker, &info))
            path = info.dli_fname;
    }
    return path;
}

static void pl_self_find(void)
{
    dl_iterate_phdr(pl_self_segments, NULL);
}

static int pl_is_ours(void *fn)
{
    pthread_once(&pl_self.once, pl_self_find);
    return fn && (uintptr_t)fn >= pl_self.lo && (uintptr_t)fn < pl_self.hi;
}

void *pl_next_symbol(const char *name)
{
    void *fn = dlsym(RTLD_NEXT, name);
    return pl_is_ours(fn) ? NULL : fn;
}

typedef void *(*pl_getproc_fn)(const char *);

/* The window systems' own GetProcAddress functions, each the next definition after ours;
 * the one of the API current on this thread first (glvnd's GLX stubs would dispatch an
 * OSMesa context's calls to nothing). */
static void *pl_getproc_any(const char *name)
{
    static const char *const getters[] = {"glXGetProcAddressARB", "eglGetProcAddress",
                                          "OSMesaGetProcAddress"};
    int first = 0;
    if (pl_tls_ctx && pl_tls_ctx->api == PL_API_EGL)
        first = 1;
    else if (pl_tls_ctx && pl_tls_ctx->api == PL_API_OSMESA)
        first = 2;
    for (int k = 0; k < 3; k++) {
        int i = (first + k) % 3;
        pl_getproc_fn get = (pl_getproc_fn)pl_next_symbol(getters[i]);
        void *fn = get ? get(name) : NULL;
        if (fn && !pl_is_ours(fn))
            return fn;
    }
    return NULL;
}

/* libGL opened by hand when the program reached us without one loaded (dlopen'ed us). */
static void *pl_from_libraries(const char *name)
{
    static const char *const libs[] = {"libGL.so.1", "libOpenGL.so.0"};
    for (size_t i = 0; i < sizeof libs / sizeof libs[0]; i++) {
        void *(*open_fn)(const char *, int) = (void *(*)(const char *, int))pl_next_symbol("dlopen");
        void *h = open_fn ? open_fn(libs[i], RTLD_LAZY | RTLD_GLOBAL) : NULL;
        void *fn = h ? dlsym(h, name) : NULL;
        if (fn && !pl_is_ours(fn))
            return fn;
    }
    return NULL;
}

void *pl_real_proc(const char *name)
{
    void *fn = pl_next_symbol(name);
    if (!fn)
        fn = pl_getproc_any(name);
    if (!fn)
        fn = pl_from_libraries(name);
    return fn;
}

void pl_resolve_slot(int slot)
{
    void *fn = pl_real_proc(pl_slot_name[slot]);
    if (!fn) {
        pl_log(PL_LOG_WARN, "no driver function %s; calls to it do nothing", pl_slot_name[slot]);
        fn = pl_none_slot[slot];
    }
    __atomic_store_n(&pl_real_slot[slot], fn, __ATOMIC_RELEASE);
}

static int pl_proc_cmp(const void *key, const void *row)
{
    return strcmp((const char *)key, ((const pl_proc *)row)->name);
}

/* Window-system entry points we wrap (winsys.c), for GetProcAddress. */
extern const pl_proc pl_winsys_table[];
extern const int pl_winsys_count;

void *pl_own_proc(const char *name)
{
    const pl_proc *p;
    if (!name)
        return NULL;
    p = bsearch(name, pl_proc_table, (size_t)pl_proc_count, sizeof *p, pl_proc_cmp);
    if (p) /* only for functions the driver has: a program may test for them */
        return pl_real_slot[p - pl_proc_table] != pl_none_slot[p - pl_proc_table] && pl_real_proc(name) ? p->fn : NULL;
    for (int i = 0; i < pl_winsys_count; i++)
        if (strcmp(name, pl_winsys_table[i].name) == 0)
            return pl_winsys_table[i].fn;
    return NULL;
}
