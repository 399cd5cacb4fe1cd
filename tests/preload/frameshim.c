/* frameshim.c: a test-only preload that makes glxgears deterministic and photographs it.
 *
 * glxgears turns its gears by the time of day and redraws forever. Preloaded next to (or
 * without) libquadgl-preload.so, this library freezes gettimeofday at a fixed instant, so
 * every run draws the same frame, and counts glXSwapBuffers calls: at frame PT_SHOT_FRAME
 * (default 5) it reads the finished back buffer with glReadPixels, writes it to the PPM file
 * named by PT_SHOT and exits normally (so atexit handlers, among them quadgl's statistics
 * line, run). Only gettimeofday and glXSwapBuffers are defined here (a test library, not
 * part of the product). */
#include <GL/gl.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/time.h>

/* glibc declares gettimeofday's argument nonnull; callers may still pass NULL. */
static void frozen_time(struct timeval *tv)
{
    if (tv) {
        tv->tv_sec = 1000000;
        tv->tv_usec = 250000;
    }
}

__attribute__((visibility("default"))) int gettimeofday(struct timeval *tv, void *tz)
{
    (void)tz;
    frozen_time(tv);
    return 0;
}

typedef void (*read_pixels_fn)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void *);
typedef void (*glenum_fn)(GLenum);
typedef void (*get_integerv_fn)(GLenum, GLint *);

static void shoot(const char *path)
{
    read_pixels_fn read_pixels = (read_pixels_fn)dlsym(RTLD_DEFAULT, "glReadPixels");
    glenum_fn read_buffer = (glenum_fn)dlsym(RTLD_DEFAULT, "glReadBuffer");
    get_integerv_fn get_integerv = (get_integerv_fn)dlsym(RTLD_DEFAULT, "glGetIntegerv");
    GLint vp[4] = {0, 0, 0, 0};
    unsigned char *px;
    FILE *f;
    if (!read_pixels || !read_buffer || !get_integerv)
        exit(3);
    get_integerv(GL_VIEWPORT, vp);
    px = malloc((size_t)vp[2] * (size_t)vp[3] * 3 + 1);
    if (!px || !(f = fopen(path, "wb")))
        exit(3);
    read_buffer(GL_BACK);
    read_pixels(0, 0, vp[2], vp[3], GL_RGB, GL_UNSIGNED_BYTE, px);
    fprintf(f, "P6\n%d %d\n255\n", vp[2], vp[3]);
    for (int y = vp[3] - 1; y >= 0; y--)
        fwrite(px + (size_t)y * (size_t)vp[2] * 3, 3, (size_t)vp[2], f);
    fclose(f);
    free(px);
}

/* The frame is complete in the back buffer just before it is swapped. */
__attribute__((visibility("default"))) void glXSwapBuffers(void *dpy, unsigned long drawable)
{
    static int frames;
    const char *path = getenv("PT_SHOT"), *n = getenv("PT_SHOT_FRAME");
    void (*real_swap)(void *, unsigned long) = (void (*)(void *, unsigned long))dlsym(RTLD_NEXT, "glXSwapBuffers");
    if (path && ++frames == (n ? atoi(n) : 5)) {
        shoot(path);
        exit(0);
    }
    if (real_swap)
        real_swap(dpy, drawable);
}
