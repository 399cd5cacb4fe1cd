/* harness.c: OSMesa contexts, pixel access, PPM output and the per-pixel reference. */
#include "harness.h"

#include <GL/osmesa.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int th_failures;

void th_check(int cond, const char *fmt, ...)
{
    if (cond)
        return;
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "FAIL: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    th_failures++;
}

void *th_get_proc(const char *name)
{
    return (void *)OSMesaGetProcAddress(name);
}

int th_init(th_ctx *t, int w, int h, const qgl_gl_desc *desc)
{
    static const int attr[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
                               OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 4,
                               OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    memset(t, 0, sizeof *t);
    t->w = w, t->h = h;
    t->osmesa = OSMesaCreateContextAttribs(attr, NULL);
    if (!t->osmesa)
        return 77;
    t->buf = calloc((size_t)w * h, 4);
    if (!t->buf || !OSMesaMakeCurrent(t->osmesa, t->buf, GL_UNSIGNED_BYTE, w, h))
        return 77;
    qgl_gl_desc d = desc ? *desc : (qgl_gl_desc){0};
    if (!d.get_proc)
        d.get_proc = th_get_proc;
    t->qgl = qgl_gl_create(&d);
    if (!t->qgl)
        return 77;
    qgl_gl_make_current(t->qgl);
    th_viewport(t, 0, 0, w, h);
    return 0;
}

void th_free(th_ctx *t)
{
    qgl_gl_destroy(t->qgl);
    OSMesaDestroyContext(t->osmesa);
    free(t->buf);
}

int th_need_geometry_shaders(th_ctx *t)
{
    if (qgl_gl_shader_level(t->qgl) == 150)
        return 0;
    th_free(t);
    printf("no geometry shader path: skipped\n");
    return 77;
}

const unsigned char *th_px(const th_ctx *t, int x, int y)
{
    return t->buf + 4 * ((size_t)y * t->w + x);
}

unsigned char *th_snapshot(const th_ctx *t)
{
    glFinish();
    unsigned char *img = malloc((size_t)t->w * t->h * 4);
    if (img)
        memcpy(img, t->buf, (size_t)t->w * t->h * 4);
    return img;
}

void th_write(const th_ctx *t, const unsigned char *img, const char *name)
{
    char path[256];
    snprintf(path, sizeof path, "%s.ppm", name);
    FILE *f = fopen(path, "wb");
    if (!f)
        return;
    if (!img) {
        glFinish();
        img = t->buf;
    }
    fprintf(f, "P6\n%d %d\n255\n", t->w, t->h);
    for (int y = t->h - 1; y >= 0; y--)
        for (int x = 0; x < t->w; x++)
            fwrite(img + 4 * ((size_t)y * t->w + x), 1, 3, f);
    fclose(f);
}

void th_viewport(th_ctx *t, int x, int y, int w, int h)
{
    glViewport(x, y, w, h);
    t->vp[0] = x, t->vp[1] = y, t->vp[2] = w, t->vp[3] = h;
}

int th_weights(const th_ctx *t, const double clip[4][4], int x, int y, double lam[4], double scr[4])
{
    double hw = 0.5 * t->vp[2], hh = 0.5 * t->vp[3], px[4][4];
    for (int i = 0; i < 4; i++) {
        px[i][0] = clip[i][0] * hw, px[i][1] = clip[i][1] * hh;
        px[i][2] = clip[i][2], px[i][3] = clip[i][3];
    }
    return qgl_weights(px, x + 0.5 - t->vp[0] - hw, y + 0.5 - t->vp[1] - hh, lam, scr);
}

int th_ref_color(const th_ctx *t, const double clip[4][4], const float a[4][4], int x, int y, float out[4])
{
    double lam[4];
    int r = th_weights(t, clip, x, y, lam, NULL);
    for (int k = 0; k < 4; k++)
        out[k] = (float)(lam[0] * a[0][k] + lam[1] * a[1][k] + lam[2] * a[2][k] + lam[3] * a[3][k]);
    return r;
}

void th_clip_of(const float p[4][3], double clip[4][4])
{
    double mv[16], pr[16];
    glGetDoublev(GL_MODELVIEW_MATRIX, mv);
    glGetDoublev(GL_PROJECTION_MATRIX, pr);
    for (int i = 0; i < 4; i++) {
        double e[4];
        for (int r = 0; r < 4; r++)
            e[r] = mv[r] * p[i][0] + mv[4 + r] * p[i][1] + mv[8 + r] * p[i][2] + mv[12 + r];
        for (int r = 0; r < 4; r++)
            clip[i][r] = pr[r] * e[0] + pr[4 + r] * e[1] + pr[8 + r] * e[2] + pr[12 + r] * e[3];
    }
}
