/* harness.h: OSMesa contexts, pixel access and image output for the GL tests. */
#ifndef QGL_TEST_HARNESS_H
#define QGL_TEST_HARNESS_H
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <quadgl/quadgl.h>

typedef struct th_ctx {
    int w, h;
    int vp[4]; /* the viewport th_viewport last set (initially the whole framebuffer) */
    unsigned char *buf; /* RGBA, row 0 at the bottom */
    void *osmesa;
    qgl_context *qgl;
} th_ctx;

/* A compatibility-profile context (4.5 asked; llvmpipe gives it) of w x h with depth and
 * stencil, current, plus a qgl context on it (desc may be NULL). Returns 0, or 77 to skip. */
int th_init(th_ctx *t, int w, int h, const qgl_gl_desc *desc);
void th_free(th_ctx *t);
/* 0 where t's qgl context found the geometry shader path (shader level 150); otherwise frees
 * t, says so and returns 77, the skip status, for main to return. */
int th_need_geometry_shaders(th_ctx *t);
void *th_get_proc(const char *name);

/* Pixel (x, y) channel c, from the framebuffer after glFinish. */
const unsigned char *th_px(const th_ctx *t, int x, int y);
/* Copy of the framebuffer (w * h * 4). */
unsigned char *th_snapshot(const th_ctx *t);
/* Write the framebuffer (or img) as a binary PPM named NAME.ppm in the current directory. */
void th_write(const th_ctx *t, const unsigned char *img, const char *name);

/* Count of failed checks; th_check prints the message when cond is false. */
extern int th_failures;
void th_check(int cond, const char *fmt, ...);

/* glViewport, remembered for the references below. */
void th_viewport(th_ctx *t, int x, int y, int w, int h);
/* The core's double weights (perspective, and screen if not NULL) at the centre of pixel
 * (x, y) for clip corners clip under the viewport: x, y scaled to isotropic pixels, the space
 * quadgl computes them in (NDC would squeeze a non-square viewport); the core's return code. */
int th_weights(const th_ctx *t, const double clip[4][4], int x, int y, double lam[4], double scr[4]);
/* Per-pixel reference colour from the core's double weights: attribute a[corner][4] at the
 * centre of pixel (x, y) of a quad with clip corners clip; returns the core's return code. */
int th_ref_color(const th_ctx *t, const double clip[4][4], const float a[4][4], int x, int y, float out[4]);
/* Clip corners of object corners p under the current GL matrices. */
void th_clip_of(const float p[4][3], double clip[4][4]);
#endif
