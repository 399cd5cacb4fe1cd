/* test_fallback: the CPU subdivision (a context created with force_fallback, as on GL 1.x)
 * must draw the same picture as the shader path within its tolerance.
 *
 * QUADGL_TOLERANCE is 0.5 px: the attribute pattern may shift by half a pixel, so a colour
 * changing by at most G levels per pixel may differ by G/2 levels; with our corner colours
 * G <= 3 levels per pixel here, and we allow 3/255 on interior pixels. The outline is the
 * same cover, drawn by the same rasterizer from vertices computed differently (driver's
 * transform of recombined object points), so a few outline pixels may flip; we allow 1% of
 * the outline. Pixels within 6 px of a bow-tie's crossing point (a singularity of the weights,
 * where neither path converges) are not compared. Both paths must also agree on quads in
 * perspective, non-planar and concave, with the screen-space weights (MVC) and with the
 * view-invariant ones (MVC_PLANE: in the plane, and on the bilinear patch for the saddle). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scenes.h"


static void compare(th_ctx *t, qgl_context *shader, qgl_context *fallback, const float p[4][3], const char *name)
{
    unsigned char *img[2];
    qgl_gl_stats_t st;
    for (int k = 0; k < 2; k++) {
        qgl_gl_make_current(k ? fallback : shader);
        qgl_gl_reset_stats(qgl_gl_current());
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        sc_draw_quad(p);
        img[k] = th_snapshot(t);
        qgl_gl_stats(qgl_gl_current(), &st);
        th_check(k ? st.fallback == 1 : st.mvc == 1, "%s: wrong path", name);
    }
    /* a bow-tie's crossing point is a singularity of the weights: its neighbourhood is skipped */
    double clip[4][4], cx = -100, cy = -100;
    qgl_cover cov;
    th_clip_of(p, clip);
    if (qgl_classify_clip(clip, &cov) == QGL_QUAD_BOWTIE)
        cx = (cov.cross[0] + 1) * 0.5 * t->w, cy = (cov.cross[1] + 1) * 0.5 * t->h;
    int interior = 0, bad = 0, outline = 0, flipped = 0, worst = 0;
    for (int y = 1; y < t->h - 1; y++)
        for (int x = 1; x < t->w - 1; x++) {
            int i = y * t->w + x, on[2], all = 1, any = 0;
            for (int k = 0; k < 2; k++)
                on[k] = img[k][4 * i + 3] != 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int j = (y + dy) * t->w + x + dx;
                    all &= img[0][4 * j + 3] != 0;
                    any |= img[0][4 * j + 3] != 0;
                }
            if (any && !all) {
                outline++;
                flipped += on[0] != on[1];
                continue;
            }
            if (!all || hypot(x + 0.5 - cx, y + 0.5 - cy) < 6)
                continue;
            interior++;
            for (int c = 0; c < 3; c++) {
                int d = abs(img[0][4 * i + c] - img[1][4 * i + c]);
                worst = d > worst ? d : worst;
                bad += d > 3;
            }
        }
    qgl_gl_stats(fallback, &st);
    printf("%-18s interior %6d worst %d/255 (%d over 3), outline %d flipped %d, %llu triangles\n", name, interior,
           worst, bad, outline, flipped, (unsigned long long)st.subdiv_triangles);
    th_write(t, img[1], name);
    th_check(interior > 1000 && bad == 0 && flipped * 100 <= outline, "%s: fallback differs from the shader path", name);
    free(img[0]);
    free(img[1]);
}

/* Both contexts with one method: MVC (screen-space weights) or MVC_PLANE (view-invariant:
 * the in-plane cover for planar quads, the bilinear patch for the saddle). */
static void run(th_ctx *t, qgl_method method, const char *suffix)
{
    qgl_gl_set_method(t->qgl, method);
    qgl_gl_desc fd = {.method = method, .force_fallback = 1, .get_proc = th_get_proc, .tolerance_px = 0.5f};
    qgl_context *fb = qgl_gl_create(&fd);
    if (!fb || qgl_gl_shader_level(fb) != 0 || qgl_gl_shader_level(t->qgl) == 0) {
        th_check(0, "could not create the two contexts");
        return;
    }
    char name[64];
    static const float convex[4][3] = {{-0.9f, -0.9f, 0}, {0.8f, -0.7f, 0}, {0.6f, 0.85f, 0}, {-0.7f, 0.3f, 0}};
    static const float concave[4][3] = {{-0.8f, -0.9f, 0}, {0.9f, 0.0f, 0}, {-0.8f, 0.9f, 0}, {-0.1f, 0.0f, 0}};
    static const float bowtie[4][3] = {{-0.9f, -0.8f, 0}, {0.9f, 0.85f, 0}, {0.85f, -0.9f, 0}, {-0.8f, 0.9f, 0}};
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    snprintf(name, sizeof name, "fallback_convex%s", suffix);
    compare(t, t->qgl, fb, convex, name);
    snprintf(name, sizeof name, "fallback_concave%s", suffix);
    compare(t, t->qgl, fb, concave, name);
    snprintf(name, sizeof name, "fallback_bowtie%s", suffix);
    compare(t, t->qgl, fb, bowtie, name);
    sc_camera(-40, 20);
    static const float saddle[4][3] = {{-1, -1, 0.4f}, {1, -0.8f, -0.4f}, {0.9f, 1, 0.4f}, {-1, 0.9f, -0.4f}};
    static const float trapezoid[4][3] = {{-1.2f, -1, 0}, {1.2f, -1, 0}, {0.4f, 1, 0}, {-0.4f, 1, 0}};
    snprintf(name, sizeof name, "fallback_saddle%s", suffix);
    compare(t, t->qgl, fb, saddle, name);
    snprintf(name, sizeof name, "fallback_persp%s", suffix);
    compare(t, t->qgl, fb, trapezoid, name);
    qgl_gl_make_current(t->qgl);
    qgl_gl_destroy(fb);
}

int main(void)
{
    th_ctx t;
    qgl_gl_desc d = {.method = QGL_METHOD_MVC};
    int rc = th_init(&t, 256, 256, &d);
    if (rc)
        return rc;
    glClearColor(0, 0, 0, 0);
    glEnable(GL_DEPTH_TEST);
    run(&t, QGL_METHOD_MVC, "");
    run(&t, QGL_METHOD_MVC_PLANE, "_plane");
    th_free(&t);
    return th_failures ? 1 : 0;
}
