/* test_edge: a quad with a corner behind the eye whose edges run exactly through pixel centres.
 *
 * Such a quad's cover is the driver's clipped split, and the fragment shader discards the
 * fragments outside the quad by the sign of its weights. On an edge through pixel centres the
 * weight of the far corners is zero up to float rounding, and the rasterizer's own tie rule
 * has already decided which of those pixels belong to the quad: the discard must not take any
 * of them away. The quad is convex on screen, so the driver's coverage is the quad's: under
 * auto, mvc and mvcplane the covered pixels must be exactly the driver's (every pixel, for
 * edges on columns and rows of pixel centres, the quad in both orientations), on both shader
 * paths. The cover must be the driver's own split: the other diagonal's, clipped, left most
 * of such a quad out. */
#include <stdio.h>
#include <stdlib.h>

#include "harness.h"

#define W 64
#define H 64

/* Covered pixels (any channel lit) of one picture of the quad p. */
static unsigned char *picture(th_ctx *t, const float p[4][3], int native)
{
    static const float c[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 0.2f, 1}};
    glClear(GL_COLOR_BUFFER_BIT);
    native ? glBegin(GL_QUADS) : qglBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        if (native) {
            glColor4fv(c[i]);
            glVertex3fv(p[i]);
        } else {
            qglColor4fv(c[i]);
            qglVertex3fv(p[i]);
        }
    }
    native ? glEnd() : qglEnd();
    qgl_gl_flush(qgl_gl_current());
    return th_snapshot(t);
}

/* NDC of the centre of pixel k along an axis of W pixels, times -z (exact in binary). */
static float centre(int k, float z)
{
    return ((float)k + 0.5f) / (W / 2) * -z - 1.0f * -z;
}

typedef struct path {
    const char *name;
    qgl_context *ctx;
    qgl_method method;
} path;

static path paths[5];

static void compare(th_ctx *t, const char *name, const float p[4][3])
{
    unsigned char *native = picture(t, p, 1);
    int covered = 0;
    for (int i = 0; i < W * H; i++)
        covered += native[4 * i] || native[4 * i + 1] || native[4 * i + 2];
    th_check(covered > W * H / 8, "%s: the driver covers only %d pixels", name, covered);
    for (size_t m = 0; m < sizeof paths / sizeof paths[0]; m++) {
        qgl_gl_make_current(paths[m].ctx);
        qgl_gl_set_method(paths[m].ctx, paths[m].method);
        unsigned char *ours = picture(t, p, 0);
        int lost = 0, extra = 0, inside = 0;
        double clip[4][4], lam[4];
        th_clip_of(p, clip);
        for (int i = 0; i < W * H; i++) {
            int a = native[4 * i] || native[4 * i + 1] || native[4 * i + 2];
            int b = ours[4 * i] || ours[4 * i + 1] || ours[4 * i + 2];
            if (a && !b && th_weights(t, clip, i % W, i / W, lam, NULL) == QGL_INSIDE)
                inside++;
            lost += a && !b;
            extra += b && !a;
        }
        th_check(lost == 0 && extra == 0, "%s (%s): %d pixels the driver covers lost (%d inside by the core), %d extra", name,
                 paths[m].name, lost, inside, extra);
        if (lost || extra) {
            th_write(t, ours, paths[m].name);
            th_write(t, native, "edge_native");
        }
        free(ours);
    }
    free(native);
}

int main(void)
{
    th_ctx t;
    int rc = th_init(&t, W, H, NULL);
    if (rc)
        return rc;
    qgl_gl_desc d120 = {.max_glsl = 120, .get_proc = th_get_proc};
    qgl_context *c120 = qgl_gl_create(&d120);
    if (qgl_gl_shader_level(t.qgl) < 150 || !c120 || qgl_gl_shader_level(c120) != 120) {
        fprintf(stderr, "test_edge: the shader paths are not all here\n");
        return 1;
    }
    paths[0] = (path){"auto", t.qgl, QGL_METHOD_AUTO};
    paths[1] = (path){"mvc", t.qgl, QGL_METHOD_MVC};
    paths[2] = (path){"mvcplane", t.qgl, QGL_METHOD_MVC_PLANE};
    paths[3] = (path){"glsl120_mvc", c120, QGL_METHOD_MVC};
    paths[4] = (path){"glsl120_mvcplane", c120, QGL_METHOD_MVC_PLANE};
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-1, 1, -1, 1, 1, 10);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    const float z = -2;
    /* left edge on the centres of column 20, bottom edge on those of row 12; the fourth corner
     * behind the eye */
    float x0 = centre(20, z), x1 = centre(50, z), y0 = centre(12, z), y1 = centre(52, z);
    const float ccw[4][3] = {{x0, y0, z}, {x1, y0, z}, {1.0f, 1.0f, 1.0f}, {x0, y1, z}};
    const float cw[4][3] = {{x0, y0, z}, {x0, y1, z}, {1.0f, 1.0f, 1.0f}, {x1, y0, z}};
    compare(&t, "counter-clockwise", ccw);
    compare(&t, "clockwise", cw);
    /* right and top edges on pixel centres (the tie rule leaves those pixels out) */
    float r0 = centre(8, z), r1 = centre(40, z), u0 = centre(6, z), u1 = centre(44, z);
    const float right[4][3] = {{r1, u1, z}, {r0, u1, z}, {-1.0f, -1.0f, 1.0f}, {r1, u0, z}};
    compare(&t, "right and top", right);
    qgl_gl_make_current(t.qgl);
    qgl_gl_destroy(c120);
    th_free(&t);
    printf("test_edge: %d failures\n", th_failures);
    return th_failures ? 1 : 0;
}
