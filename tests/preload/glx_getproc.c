/* glx_getproc.c: a GLX program that reaches every GL function through glXGetProcAddressARB.
 *
 * Like programs built on GLEW, SDL or their own loaders, it names no gl* symbol directly: each
 * one comes from glXGetProcAddressARB, and so do the GLX queries SDL and GLEW look up that way.
 * With libquadgl-preload.so preloaded those must be the library's own functions (checked with
 * dladdr), and the quad of ref_quad.h must come out smooth. After a first swap (batching starts
 * with the frames a program shows through us) it draws the quad PT_REPEAT times (default 1),
 * each in its own glBegin/glEnd, for the statistics line to show whether they were batched.
 * The frame is written as a PPM to the file named by PT_SHOT. */
#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ref_quad.h"

typedef void (*fn_enum)(GLenum);
typedef void (*fn_void)(void);
typedef void (*fn_3f)(GLfloat, GLfloat, GLfloat);
typedef void (*fn_2fv)(const GLfloat *);
typedef void (*fn_clear_color)(GLfloat, GLfloat, GLfloat, GLfloat);
typedef void (*fn_bitfield)(GLbitfield);
typedef void (*fn_store)(GLenum, GLint);
typedef void (*fn_read)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *);
typedef GLXContext (*fn_current)(void);
typedef const char *(*fn_extensions)(Display *, int);
typedef void (*fn_query_drawable)(Display *, GLXDrawable, int, unsigned int *);

static void *get(const char *name)
{
    void *fn = (void *)glXGetProcAddressARB((const GLubyte *)name);
    if (!fn) {
        fprintf(stderr, "glx_getproc: no %s\n", name);
        exit(2);
    }
    return fn;
}

/* Where a function lives, for the check that the library handed out its own. */
static int from_quadgl(void *fn)
{
    Dl_info info;
    return dladdr(fn, &info) && info.dli_fname && strstr(info.dli_fname, "quadgl-preload");
}

int main(void)
{
    static unsigned char rgb[REF_SIZE * REF_SIZE * 3];
    static int attrs[] = {GLX_RGBA, GLX_RED_SIZE, 8, GLX_GREEN_SIZE, 8, GLX_BLUE_SIZE, 8, None};
    Display *dpy = XOpenDisplay(NULL);
    XVisualInfo *vi;
    XSetWindowAttributes swa;
    Window win;
    GLXContext ctx;
    const char *path = getenv("PT_SHOT");
    FILE *f;
    if (!dpy || !(vi = glXChooseVisual(dpy, DefaultScreen(dpy), attrs)))
        return 2;
    memset(&swa, 0, sizeof swa);
    swa.colormap = XCreateColormap(dpy, RootWindow(dpy, vi->screen), vi->visual, AllocNone);
    win = XCreateWindow(dpy, RootWindow(dpy, vi->screen), 0, 0, REF_SIZE, REF_SIZE, 0, vi->depth, InputOutput,
                        vi->visual, CWColormap, &swa);
    ctx = glXCreateContext(dpy, vi, NULL, True);
    if (!ctx || !glXMakeCurrent(dpy, win, ctx))
        return 2;
    {
        fn_current current = (fn_current)get("glXGetCurrentContext");
        fn_extensions extensions = (fn_extensions)get("glXQueryExtensionsString");
        fn_query_drawable query_drawable = (fn_query_drawable)get("glXQueryDrawable");
        unsigned int width = 0;
        query_drawable(dpy, win, GLX_WIDTH, &width);
        if (current() != ctx || !extensions(dpy, DefaultScreen(dpy)) || width != REF_SIZE) {
            fprintf(stderr, "glx_getproc: the GLX queries answered wrongly\n");
            return 1;
        }
    }
    glXSwapBuffers(dpy, win);
    {
        fn_enum begin = (fn_enum)get("glBegin");
        fn_void end = (fn_void)get("glEnd"), finish = (fn_void)get("glFinish");
        fn_3f color = (fn_3f)get("glColor3f");
        fn_2fv vertex = (fn_2fv)get("glVertex2fv");
        fn_clear_color clear_color = (fn_clear_color)get("glClearColor");
        fn_bitfield clear = (fn_bitfield)get("glClear");
        fn_store store = (fn_store)get("glPixelStorei");
        fn_read read = (fn_read)get("glReadPixels");
        fn_enum read_buffer = (fn_enum)get("glReadBuffer");
        if (getenv("LD_PRELOAD") && strstr(getenv("LD_PRELOAD"), "quadgl-preload") &&
            !(from_quadgl((void *)begin) && from_quadgl((void *)vertex) && from_quadgl((void *)color))) {
            fprintf(stderr, "glx_getproc: glXGetProcAddressARB did not return quadgl's functions\n");
            return 1;
        }
        clear_color(0, 0, 0, 1);
        clear(GL_COLOR_BUFFER_BIT);
        int repeat = getenv("PT_REPEAT") ? atoi(getenv("PT_REPEAT")) : 1;
        for (int k = 0; k < repeat; k++) {
            begin(GL_QUADS);
            for (int i = 0; i < 4; i++) {
                color(ref_c[i][0], ref_c[i][1], ref_c[i][2]);
                vertex(ref_v[i]);
            }
            end();
        }
        finish();
        read_buffer(GL_BACK);
        store(GL_PACK_ALIGNMENT, 1);
        read(0, 0, REF_SIZE, REF_SIZE, GL_RGB, GL_UNSIGNED_BYTE, rgb);
    }
    if (!path || !(f = fopen(path, "wb")))
        return 2;
    fprintf(f, "P6\n%d %d\n255\n", REF_SIZE, REF_SIZE);
    fwrite(rgb, 3, REF_SIZE * REF_SIZE, f);
    fclose(f);
    glXMakeCurrent(dpy, None, NULL);
    glXDestroyContext(dpy, ctx);
    XDestroyWindow(dpy, win);
    XFree(vi);
    XCloseDisplay(dpy);
    return 0;
}
