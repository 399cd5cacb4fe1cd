/* appshim.c: a test-only preload that times, freezes and photographs a real GL program.
 *
 * Preloaded next to libquadgl-preload.so (in either order) or alone, it wraps both
 * glXSwapBuffers and eglSwapBuffers (xscreensaver 6 draws through EGL on X11) and chains
 * to the next definition. Everything happens inside the program's own swap call, never in
 * a signal handler (exit() inside a handler can deadlock in malloc), and the program ends
 * with exit(0), so atexit handlers run, among them quadgl's statistics line. Controlled by
 * the environment:
 *
 *   APPSHIM_SECONDS=S   run S seconds of real time from the end of the first swap, then
 *                       write "frames seconds rss_kib cpu_seconds longest_ms first_ms" (swaps
 *                       after the first, the real time they took, VmRSS, the process's CPU
 *                       time in them, the longest time between two of them: a stall a user
 *                       sees, and the time from the shim's loading to the end of the first
 *                       swap: start-up and first frame) to APPSHIM_OUT (default stderr) and
 *                       exit
 *   APPSHIM_SHOT=FILE   at swap APPSHIM_FRAME (default 20) read the finished back buffer
 *                       (the drawable's size) and write it as a PPM, then exit
 *   APPSHIM_MASK=FILE   with APPSHIM_SHOT: also write, as a PPM, the footprint of every
 *                       draw of that frame in GL_LINES_ADJACENCY (only quadgl's shader path
 *                       draws so: its smooth quads), white on black
 *   APPSHIM_FREEZE=1    time starts at a fixed instant and advances APPSHIM_STEP_US
 *                       (default 40000) at every swap: gettimeofday, time and clock_gettime
 *                       (the REALTIME and MONOTONIC clocks and their variants); getpid returns
 *                       a constant. The xscreensaver hacks seed their random numbers from
 *                       the time and the pid, so a frozen run draws the same frames every time.
 *                       Children the program forks (xscreensaver-getimage, which loads an
 *                       image and answers through a pipe) are waited for, up to 20 s, after
 *                       the swap that started them, so an image arrives at the same frame
 *                       every run, not when the machine's load lets it.
 *   APPSHIM_FREEZE=realtime   the same for the time of day only (gettimeofday, time,
 *                       CLOCK_REALTIME) and getpid: the hacks draw the same frames, while the
 *                       driver and quadgl, which time themselves on CLOCK_MONOTONIC, see real
 *                       time (a timed run compares the same work natively and preloaded).
 *
 * The shim measures its own time with the real clock (the next clock_gettime), whatever is
 * frozen. The mask works by drawing each such draw a second time, state pushed, into a
 * framebuffer object of its own with the colour logic op GL_SET (every fragment the draw
 * produces becomes white whatever its colour) and depth and stencil tests off; to see
 * quadgl's draws the shim must come after libquadgl-preload.so in LD_PRELOAD, where quadgl's
 * lookup of the real glDrawArrays finds ours. Not part of the product. */
#include <GL/gl.h>
#include <GL/glext.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define SHIM_EXPORT __attribute__((visibility("default")))

#define FROZEN_REALTIME 1000000000LL /* 2001-09-09, seconds */
#define FROZEN_MONOTONIC 100000LL

static int frames; /* swaps so far (atomic: other threads read the frozen clocks) */

/* ---- configuration -------------------------------------------------------------------------- */

enum { FREEZE_NONE, FREEZE_ALL, FREEZE_REALTIME };

static struct {
    int read;
    double seconds;
    const char *out, *shot, *mask;
    int shot_frame, freeze;
    long long step_us;
} cfg;

static void read_cfg(void)
{
    const char *s;
    if (__atomic_load_n(&cfg.read, __ATOMIC_ACQUIRE))
        return;
    cfg.seconds = (s = getenv("APPSHIM_SECONDS")) ? atof(s) : 0;
    cfg.out = getenv("APPSHIM_OUT");
    cfg.shot = getenv("APPSHIM_SHOT");
    cfg.mask = getenv("APPSHIM_MASK");
    cfg.shot_frame = (s = getenv("APPSHIM_FRAME")) ? atoi(s) : 20;
    cfg.freeze = FREEZE_NONE;
    if ((s = getenv("APPSHIM_FREEZE")) && strcmp(s, "realtime") == 0)
        cfg.freeze = FREEZE_REALTIME;
    else if (s && atoi(s) != 0)
        cfg.freeze = FREEZE_ALL;
    cfg.step_us = (s = getenv("APPSHIM_STEP_US")) ? atoll(s) : 40000;
    __atomic_store_n(&cfg.read, 1, __ATOMIC_RELEASE);
}

/* ---- the clocks ------------------------------------------------------------------------------ */

typedef int (*clock_gettime_fn)(clockid_t, struct timespec *);
typedef int (*gettimeofday_fn)(struct timeval *, void *);
typedef time_t (*time_fn)(time_t *);
typedef pid_t (*getpid_fn)(void);

static clock_gettime_fn real_clock_gettime(void)
{
    static clock_gettime_fn fn;
    if (!fn)
        fn = (clock_gettime_fn)dlsym(RTLD_NEXT, "clock_gettime");
    return fn;
}

/* Seconds on a real clock (CLOCK_MONOTONIC, CLOCK_PROCESS_CPUTIME_ID). */
static double real_seconds(clockid_t clk)
{
    struct timespec ts = {0, 0};
    real_clock_gettime()(clk, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Microseconds of frozen time elapsed since the fixed start. */
static long long frozen_us(void)
{
    return (long long)__atomic_load_n(&frames, __ATOMIC_RELAXED) * cfg.step_us;
}

/* Whether the time of day (realtime) or all clocks (!realtime) are frozen. */
static int frozen(int realtime)
{
    read_cfg();
    return cfg.freeze == FREEZE_ALL || (realtime && cfg.freeze == FREEZE_REALTIME);
}

/* glibc declares the time functions' arguments nonnull; callers may still pass NULL. */
static void frozen_timespec(struct timespec *ts, long long base)
{
    if (ts) {
        ts->tv_sec = (time_t)(base + frozen_us() / 1000000);
        ts->tv_nsec = (long)(frozen_us() % 1000000 * 1000);
    }
}

static void frozen_timeval(struct timeval *tv)
{
    if (tv) {
        tv->tv_sec = (time_t)(FROZEN_REALTIME + frozen_us() / 1000000);
        tv->tv_usec = (suseconds_t)(frozen_us() % 1000000);
    }
}

SHIM_EXPORT int clock_gettime(clockid_t clk, struct timespec *ts)
{
    long long base;
    int realtime = 0;
    switch (clk) {
    case CLOCK_REALTIME:
    case CLOCK_REALTIME_COARSE:
        base = FROZEN_REALTIME;
        realtime = 1;
        break;
    case CLOCK_MONOTONIC:
    case CLOCK_MONOTONIC_RAW:
    case CLOCK_MONOTONIC_COARSE:
    case CLOCK_BOOTTIME:
        base = FROZEN_MONOTONIC;
        break;
    default:
        base = -1;
    }
    if (base < 0 || !frozen(realtime))
        return real_clock_gettime()(clk, ts);
    frozen_timespec(ts, base);
    return 0;
}

SHIM_EXPORT int gettimeofday(struct timeval *tv, void *tz)
{
    static gettimeofday_fn real;
    if (!frozen(1)) {
        if (!real)
            real = (gettimeofday_fn)dlsym(RTLD_NEXT, "gettimeofday");
        return real(tv, tz);
    }
    frozen_timeval(tv);
    return 0;
}

SHIM_EXPORT time_t time(time_t *t)
{
    static time_fn real;
    time_t now;
    if (!frozen(1)) {
        if (!real)
            real = (time_fn)dlsym(RTLD_NEXT, "time");
        return real(t);
    }
    now = (time_t)(FROZEN_REALTIME + frozen_us() / 1000000);
    if (t)
        *t = now;
    return now;
}

SHIM_EXPORT pid_t getpid(void)
{
    static getpid_fn real;
    if (frozen(1))
        return 4242;
    if (!real)
        real = (getpid_fn)dlsym(RTLD_NEXT, "getpid");
    return real();
}

/* ---- children ---------------------------------------------------------------------------------- */

static pid_t children[16];
static int n_children;

typedef pid_t (*fork_fn)(void);

SHIM_EXPORT pid_t fork(void)
{
    static fork_fn real;
    pid_t pid;
    if (!real)
        real = (fork_fn)dlsym(RTLD_NEXT, "fork");
    pid = real();
    if (pid > 0 && frozen(0) && n_children < (int)(sizeof children / sizeof *children))
        children[n_children++] = pid;
    return pid;
}

/* Waits, without reaping (the program reaps its own), until each child forked since the last
 * swap has exited or 20 s have passed. */
static void wait_children(void)
{
    double end = real_seconds(CLOCK_MONOTONIC) + 20;
    struct timespec ms = {0, 1000000};
    for (int i = 0; i < n_children; i++) {
        for (;;) {
            siginfo_t si = {0};
            if (waitid(P_PID, (id_t)children[i], &si, WEXITED | WNOWAIT | WNOHANG) != 0 ||
                si.si_pid == children[i] || real_seconds(CLOCK_MONOTONIC) > end)
                break;
            nanosleep(&ms, NULL);
        }
    }
    n_children = 0;
}

/* ---- GL, found at run time (the program may reach libGL through dlopen) ------------------------ */

typedef void (*read_pixels_fn)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *);
typedef void (*void_fn)(void);
typedef void (*enum_fn)(GLenum);
typedef GLboolean (*is_enabled_fn)(GLenum);
typedef void (*enum_int_fn)(GLenum, GLint);
typedef void (*uint_fn)(GLuint);
typedef void (*enum_uint_fn)(GLenum, GLuint);
typedef void (*get_integerv_fn)(GLenum, GLint *);
typedef void (*gen_fn)(GLsizei, GLuint *);
typedef void (*storage_fn)(GLenum, GLenum, GLsizei, GLsizei);
typedef void (*attach_fn)(GLenum, GLenum, GLenum, GLuint);
typedef void (*clear_color_fn)(GLfloat, GLfloat, GLfloat, GLfloat);
typedef void (*color_mask_fn)(GLboolean, GLboolean, GLboolean, GLboolean);
typedef void (*draw_arrays_fn)(GLenum, GLint, GLsizei);
typedef void (*draw_elements_fn)(GLenum, GLsizei, GLenum, const void *);
typedef void *(*getproc_fn)(const char *);

static void *gl_proc(const char *name)
{
    void *fn = dlsym(RTLD_DEFAULT, name);
    getproc_fn get;
    if (!fn && (get = (getproc_fn)dlsym(RTLD_DEFAULT, "glXGetProcAddressARB")))
        fn = get(name);
    if (!fn && (get = (getproc_fn)dlsym(RTLD_DEFAULT, "eglGetProcAddress")))
        fn = get(name);
    return fn;
}

#define GL(type, name) ((type)gl_proc(name))

/* ---- the mask of quadgl's smooth quads ---------------------------------------------------------- */

static GLuint mask_fbo, mask_rb;
static int mask_w, mask_h, mask_failed;
static int drawable_w, drawable_h; /* the size the last swap reported, 0 if unknown */

static int mask_frame(void)
{
    read_cfg();
    return cfg.shot && cfg.mask && __atomic_load_n(&frames, __ATOMIC_RELAXED) == cfg.shot_frame - 1;
}

/* Our framebuffer object, cleared, at the drawable's size (else the viewport's); it is left
 * bound for drawing. */
static int mask_create(void)
{
    GLint vp[4] = {0, 0, 0, 0}, read_fb = 0;
    GLboolean scissor = GL(is_enabled_fn, "glIsEnabled")(GL_SCISSOR_TEST);
    GL(get_integerv_fn, "glGetIntegerv")(GL_VIEWPORT, vp);
    GL(get_integerv_fn, "glGetIntegerv")(GL_READ_FRAMEBUFFER_BINDING, &read_fb);
    mask_w = drawable_w > 0 ? drawable_w : vp[0] + vp[2];
    mask_h = drawable_h > 0 ? drawable_h : vp[1] + vp[3];
    GL(gen_fn, "glGenRenderbuffers")(1, &mask_rb);
    GL(enum_uint_fn, "glBindRenderbuffer")(GL_RENDERBUFFER, mask_rb);
    GL(storage_fn, "glRenderbufferStorage")(GL_RENDERBUFFER, GL_RGBA8, mask_w, mask_h);
    GL(gen_fn, "glGenFramebuffers")(1, &mask_fbo);
    GL(enum_uint_fn, "glBindFramebuffer")(GL_FRAMEBUFFER, mask_fbo);
    GL(attach_fn, "glFramebufferRenderbuffer")(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, mask_rb);
    GL(enum_uint_fn, "glBindFramebuffer")(GL_READ_FRAMEBUFFER, (GLuint)read_fb);
    GL(clear_color_fn, "glClearColor")(0, 0, 0, 0);
    GL(color_mask_fn, "glColorMask")(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    GL(enum_fn, "glDisable")(GL_SCISSOR_TEST);
    GL(enum_fn, "glClear")(GL_COLOR_BUFFER_BIT);
    if (scissor)
        GL(enum_fn, "glEnable")(GL_SCISSOR_TEST);
    return mask_w > 0 && mask_h > 0;
}

static void mask_leave(GLint fb)
{
    GL(enum_uint_fn, "glBindFramebuffer")(GL_DRAW_FRAMEBUFFER, (GLuint)fb);
    GL(void_fn, "glPopAttrib")();
}

/* Sets the mask up for one repeated draw; returns the framebuffer to go back to, or -1. */
static GLint mask_enter(void)
{
    GLint fb = 0, rb = 0;
    if (mask_failed)
        return -1;
    GL(get_integerv_fn, "glGetIntegerv")(GL_DRAW_FRAMEBUFFER_BINDING, &fb);
    GL(get_integerv_fn, "glGetIntegerv")(GL_RENDERBUFFER_BINDING, &rb);
    GL(uint_fn, "glPushAttrib")(GL_ALL_ATTRIB_BITS);
    if (!mask_fbo && !mask_create()) {
        mask_failed = 1;
        GL(enum_uint_fn, "glBindRenderbuffer")(GL_RENDERBUFFER, (GLuint)rb);
        mask_leave(fb);
        return -1;
    }
    GL(enum_uint_fn, "glBindRenderbuffer")(GL_RENDERBUFFER, (GLuint)rb);
    GL(enum_uint_fn, "glBindFramebuffer")(GL_DRAW_FRAMEBUFFER, mask_fbo);
    GL(enum_fn, "glDisable")(GL_DEPTH_TEST);
    GL(enum_fn, "glDisable")(GL_STENCIL_TEST);
    GL(enum_fn, "glDisable")(GL_BLEND);
    GL(enum_fn, "glDisable")(GL_ALPHA_TEST);
    GL(color_mask_fn, "glColorMask")(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    GL(enum_fn, "glEnable")(GL_COLOR_LOGIC_OP);
    GL(enum_fn, "glLogicOp")(GL_SET);
    return fb;
}

/* The driver's own footprint of the same quads: which diagonal llvmpipe splits a quad along
 * depends on the primitive (quads or strip), the provoking vertex and whether anything in the
 * driver's batch needed clipping, so a concave or bow-tie quad's notch, or a boundary pixel
 * rounded by one split's triangles and not the other's, may be covered natively and not by the
 * quad's exact cover. Both splits' four triangles, drawn with the program's positions
 * (ftransform, as quadgl's shader path and fixed function compute them), cover every pixel
 * either split can. */
static GLuint footprint_prog, footprint_failed;

typedef GLuint (*create_shader_fn)(GLenum);
typedef void (*shader_source_fn)(GLuint, GLsizei, const GLchar *const *, const GLint *);
typedef GLuint (*create_program_fn)(void);
typedef void (*uint_uint_fn)(GLuint, GLuint);
typedef void (*get_programiv_fn)(GLuint, GLenum, GLint *);

static GLuint footprint_program(void)
{
    static const char *const src[3] = {
        "#version 150 compatibility\nvoid main() { gl_Position = ftransform(); }\n",
        "#version 150 compatibility\nlayout(lines_adjacency) in;\nlayout(triangle_strip, max_vertices = 12) out;\n"
        "void tri(int a, int b, int c) {\n"
        "    gl_Position = gl_in[a].gl_Position; EmitVertex();\n"
        "    gl_Position = gl_in[b].gl_Position; EmitVertex();\n"
        "    gl_Position = gl_in[c].gl_Position; EmitVertex();\n"
        "    EndPrimitive();\n"
        "}\n"
        "void main() { tri(0, 1, 2); tri(0, 2, 3); tri(0, 1, 3); tri(1, 2, 3); }\n",
        "#version 150 compatibility\nvoid main() { gl_FragColor = vec4(1.0); }\n"};
    static const GLenum stage[3] = {GL_VERTEX_SHADER, GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER};
    GLint ok = 0;
    if (footprint_prog || footprint_failed)
        return footprint_prog;
    GLuint p = GL(create_program_fn, "glCreateProgram")();
    for (int i = 0; i < 3; i++) {
        GLuint sh = GL(create_shader_fn, "glCreateShader")(stage[i]);
        GL(shader_source_fn, "glShaderSource")(sh, 1, &src[i], NULL);
        GL(uint_fn, "glCompileShader")(sh);
        GL(uint_uint_fn, "glAttachShader")(p, sh);
        GL(uint_fn, "glDeleteShader")(sh);
    }
    GL(uint_fn, "glLinkProgram")(p);
    GL(get_programiv_fn, "glGetProgramiv")(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        fprintf(stderr, "appshim: the footprint program does not link: the mask is our fragments only\n");
        GL(uint_fn, "glDeleteProgram")(p);
        footprint_failed = 1;
        return 0;
    }
    return footprint_prog = p;
}

/* The mask gets the repeated draw's fragments, then the footprint: clip planes off (this
 * program writes no clip distance), culling and polygon mode as the program left them. */
#define MASK_DRAW(call)                                                                            \
    do {                                                                                           \
        GLint prog = 0;                                                                            \
        call;                                                                                      \
        GL(get_integerv_fn, "glGetIntegerv")(GL_CURRENT_PROGRAM, &prog);                           \
        if (footprint_program()) {                                                                 \
            for (int c = 0; c < 8; c++)                                                            \
                GL(enum_fn, "glDisable")(GL_CLIP_PLANE0 + c);                                      \
            GL(uint_fn, "glUseProgram")(footprint_prog);                                           \
            call;                                                                                  \
            GL(uint_fn, "glUseProgram")((GLuint)prog);                                             \
        }                                                                                          \
    } while (0)

SHIM_EXPORT void glDrawArrays(GLenum mode, GLint first, GLsizei count)
{
    static draw_arrays_fn real;
    GLint fb;
    if (!real)
        real = (draw_arrays_fn)dlsym(RTLD_NEXT, "glDrawArrays");
    real(mode, first, count);
    if (mode == GL_LINES_ADJACENCY && mask_frame() && (fb = mask_enter()) >= 0) {
        MASK_DRAW(real(mode, first, count));
        mask_leave(fb);
    }
}

SHIM_EXPORT void glDrawElements(GLenum mode, GLsizei count, GLenum type, const void *indices)
{
    static draw_elements_fn real;
    GLint fb;
    if (!real)
        real = (draw_elements_fn)dlsym(RTLD_NEXT, "glDrawElements");
    real(mode, count, type, indices);
    if (mode == GL_LINES_ADJACENCY && mask_frame() && (fb = mask_enter()) >= 0) {
        MASK_DRAW(real(mode, count, type, indices));
        mask_leave(fb);
    }
}

/* ---- the photograph ---------------------------------------------------------------------------- */

/* Reads w x h pixels of the bound read framebuffer's `buffer` and writes them top row first. */
static int write_ppm(const char *path, GLenum buffer, int w, int h)
{
    unsigned char *px = malloc((size_t)w * (size_t)h * 4);
    FILE *f = px ? fopen(path, "wb") : NULL;
    if (!f) {
        free(px);
        return 0;
    }
    GL(enum_uint_fn, "glBindBuffer")(GL_PIXEL_PACK_BUFFER, 0);
    GL(enum_int_fn, "glPixelStorei")(GL_PACK_ALIGNMENT, 1);
    GL(enum_int_fn, "glPixelStorei")(GL_PACK_ROW_LENGTH, 0);
    GL(enum_int_fn, "glPixelStorei")(GL_PACK_SKIP_ROWS, 0);
    GL(enum_int_fn, "glPixelStorei")(GL_PACK_SKIP_PIXELS, 0);
    GL(enum_fn, "glReadBuffer")(buffer);
    GL(read_pixels_fn, "glReadPixels")(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    fprintf(f, "P6\n%d %d\n255\n", w, h);
    for (int y = h - 1; y >= 0; y--)
        for (int x = 0; x < w; x++)
            fwrite(px + 4 * ((size_t)y * (size_t)w + (size_t)x), 1, 3, f);
    free(px);
    return fclose(f) == 0;
}

/* The back buffer (and the mask) of the frame about to be swapped, then the end. */
static void shoot(int w, int h)
{
    GLint vp[4] = {0, 0, 0, 0}, fb = 0;
    if (w <= 0 || h <= 0) {
        GL(get_integerv_fn, "glGetIntegerv")(GL_VIEWPORT, vp);
        w = vp[2];
        h = vp[3];
    }
    GL(get_integerv_fn, "glGetIntegerv")(GL_READ_FRAMEBUFFER_BINDING, &fb);
    GL(enum_uint_fn, "glBindFramebuffer")(GL_READ_FRAMEBUFFER, 0);
    if (!write_ppm(cfg.shot, GL_BACK, w, h))
        exit(3);
    if (cfg.mask) {
        if (mask_fbo) {
            GL(enum_uint_fn, "glBindFramebuffer")(GL_READ_FRAMEBUFFER, mask_fbo);
            if (!write_ppm(cfg.mask, GL_COLOR_ATTACHMENT0, mask_w < w ? mask_w : w, mask_h < h ? mask_h : h))
                exit(3);
        } else {
            FILE *f = fopen(cfg.mask, "wb"); /* no smooth quad in this frame: an empty mask */
            if (!f)
                exit(3);
            fprintf(f, "P6\n%d %d\n255\n", w, h);
            for (long i = 0; i < 3L * w * h; i++)
                fputc(0, f);
            fclose(f);
        }
    }
    exit(0);
}

static long rss_kib(void)
{
    char line[256];
    long kib = -1;
    FILE *f = fopen("/proc/self/status", "r");
    while (f && fgets(line, sizeof line, f))
        if (sscanf(line, "VmRSS: %ld", &kib) == 1)
            break;
    if (f)
        fclose(f);
    return kib;
}

static double loaded; /* when the shim was loaded: the program's start, as near as a preload sees it */

__attribute__((constructor)) static void shim_loaded(void)
{
    loaded = real_seconds(CLOCK_MONOTONIC);
}

/* After the real swap: the timed run's end. */
static void after_swap(int n)
{
    static double start, cpu_start, last, longest;
    double now;
    FILE *f;
    if (n_children)
        wait_children();
    if (cfg.seconds <= 0)
        return;
    now = real_seconds(CLOCK_MONOTONIC);
    if (n == 1) {
        start = now;
        cpu_start = real_seconds(CLOCK_PROCESS_CPUTIME_ID);
        last = now;
        return;
    }
    if (now - last > longest)
        longest = now - last;
    last = now;
    if (now - start < cfg.seconds)
        return;
    f = cfg.out ? fopen(cfg.out, "w") : stderr;
    if (f) {
        fprintf(f, "%d %.4f %ld %.4f %.2f %.2f\n", n - 1, now - start, rss_kib(),
                real_seconds(CLOCK_PROCESS_CPUTIME_ID) - cpu_start, 1000 * longest, 1000 * (start - loaded));
        if (f != stderr)
            fclose(f);
    }
    exit(0);
}

/* Before the real swap; returns the number of this swap. w, h: the drawable's size or 0. */
static int before_swap(int w, int h)
{
    int n = __atomic_load_n(&frames, __ATOMIC_RELAXED) + 1;
    drawable_w = w;
    drawable_h = h;
    if (cfg.shot && n == cfg.shot_frame)
        shoot(w, h);
    __atomic_store_n(&frames, n, __ATOMIC_RELAXED);
    return n;
}

/* ---- the swaps --------------------------------------------------------------------------------- */

typedef void (*glx_swap_fn)(void *, unsigned long);
typedef int (*glx_query_fn)(void *, unsigned long, int, unsigned *);
typedef unsigned (*egl_swap_fn)(void *, void *);
typedef unsigned (*egl_query_fn)(void *, void *, int, int *);

#define GLX_WIDTH 0x801D
#define GLX_HEIGHT 0x801E
#define EGL_HEIGHT 0x3056
#define EGL_WIDTH 0x3057

SHIM_EXPORT void glXSwapBuffers(void *dpy, unsigned long drawable)
{
    static glx_swap_fn real;
    glx_query_fn query;
    unsigned w = 0, h = 0;
    int n;
    if (!real)
        real = (glx_swap_fn)dlsym(RTLD_NEXT, "glXSwapBuffers");
    read_cfg();
    if (cfg.shot && (query = (glx_query_fn)dlsym(RTLD_DEFAULT, "glXQueryDrawable"))) {
        query(dpy, drawable, GLX_WIDTH, &w);
        query(dpy, drawable, GLX_HEIGHT, &h);
    }
    n = before_swap((int)w, (int)h);
    if (real)
        real(dpy, drawable);
    after_swap(n);
}

SHIM_EXPORT unsigned eglSwapBuffers(void *dpy, void *surface)
{
    static egl_swap_fn real;
    egl_query_fn query;
    int w = 0, h = 0, n;
    unsigned ok = 0;
    if (!real)
        real = (egl_swap_fn)dlsym(RTLD_NEXT, "eglSwapBuffers");
    read_cfg();
    if (cfg.shot && (query = (egl_query_fn)dlsym(RTLD_DEFAULT, "eglQuerySurface"))) {
        query(dpy, surface, EGL_WIDTH, &w);
        query(dpy, surface, EGL_HEIGHT, &h);
    }
    n = before_swap(w, h);
    if (real)
        ok = real(dpy, surface);
    after_swap(n);
    return ok;
}
