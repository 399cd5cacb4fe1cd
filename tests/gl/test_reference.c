/* test_reference: quads of every shape drawn by the shader path against the core's double
 * weights per pixel (convex, concave, bow-tie, corners on pixel centres, a wide viewport,
 * perspective, a floor to the horizon, non-planar with depth, a corner behind the eye).
 *
 * Pixels whose centre and 8 neighbours are inside the quad must match the reference colour
 * within 2/255 (float weights against double); drawn pixels must lie inside or on the
 * boundary band; non-planar quads must write the eq. 4 window depth within 1e-4. A quad with a
 * corner behind the eye is compared where its surface lies between the near and far planes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scenes.h"

/* Compare the framebuffer with the reference for one quad drawn alone on black. */
static void compare(const th_ctx *t, const float p[4][3], const char *name, int check_depth)
{
    double clip[4][4];
    th_clip_of(p, clip);
    glFinish();
    float *depth = malloc(sizeof(float) * t->w * t->h);
    glReadPixels(0, 0, t->w, t->h, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
    int bad_col = 0, bad_cov = 0, missing = 0, bad_depth = 0, inner = 0;
    double worst = 0, worst_depth = 0;
    for (int y = 1; y < t->h - 1; y++)
        for (int x = 1; x < t->w - 1; x++) {
            float ref[4];
            int in = th_ref_color(t, clip, sc_corner_colors, x, y, ref) == QGL_INSIDE;
            int all_in = in, any_in = in;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    float r2[4];
                    int i2 = th_ref_color(t, clip, sc_corner_colors, x + dx, y + dy, r2) == QGL_INSIDE;
                    all_in &= i2;
                    any_in |= i2;
                }
            const unsigned char *px = th_px(t, x, y);
            int drawn = px[0] || px[1] || px[2];
            if (drawn && !any_in)
                bad_cov++;
            if (!all_in)
                continue;
            double lam[4], scr[4], z = 0;
            th_weights(t, clip, x, y, lam, scr);
            for (int i = 0; i < 4; i++)
                z += scr[i] * (clip[i][2] / clip[i][3] * 0.5 + 0.5);
            if (!(z > 0.001 && z < 0.999))
                continue; /* in front of the near plane (or past far): clipped, as GL does */
            inner++;
            if (!drawn) {
                missing++;
                continue;
            }
            for (int k = 0; k < 3; k++) {
                double e = fabs(px[k] - ref[k] * 255.0);
                worst = fmax(worst, e);
                bad_col += e > 2.0;
            }
            if (check_depth) {
                double e = fabs(depth[y * t->w + x] - z);
                worst_depth = fmax(worst_depth, e);
                bad_depth += e > 1e-4;
            }
        }
    free(depth);
    printf("%-14s inner %6d  worst colour %.2f/255  worst depth %.2g  bad colour %d, coverage %d, missing %d, depth %d\n",
           name, inner, worst, worst_depth, bad_col, bad_cov, missing, bad_depth);
    th_check(inner > 500, "%s: too few inner pixels (%d)", name, inner);
    th_check(!bad_col && !bad_cov && !missing && !bad_depth, "%s: mismatches", name);
}

/* Corners exactly on pixel centres (orthographic, identity matrices): there every product of
 * the shader's weights vanishes, and a corner pixel the rasterizer draws must show the
 * corner's own colour. */
static void run_pixel_corners(th_ctx *t)
{
    static const int pix[4][2] = {{20, 30}, {230, 40}, {210, 220}, {40, 200}};
    float p[4][3];
    for (int i = 0; i < 4; i++) {
        p[i][0] = (float)((pix[i][0] + 0.5) / t->w * 2 - 1);
        p[i][1] = (float)((pix[i][1] + 0.5) / t->h * 2 - 1);
        p[i][2] = 0;
    }
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    sc_draw_quad(p);
    glFinish();
    th_write(t, NULL, "ref_pixel_corners");
    int drawn = 0;
    for (int i = 0; i < 4; i++) {
        const unsigned char *px = th_px(t, pix[i][0], pix[i][1]);
        if (!(px[0] || px[1] || px[2]))
            continue;
        drawn++;
        for (int k = 0; k < 3; k++)
            th_check(fabs(px[k] - sc_corner_colors[i][k] * 255.0) <= 2.0, "corner %d on a pixel centre: %d/255, not %.0f",
                     i, px[k], sc_corner_colors[i][k] * 255.0);
    }
    printf("%-14s %d of 4 corner pixels drawn, each with its corner's colour\n", "ref_pixel_corners", drawn);
    th_check(drawn > 0, "no corner pixel drawn");
}

static void run_flat(th_ctx *t, const float p[4][3], const char *name)
{
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    sc_draw_quad(p);
    th_write(t, NULL, name);
    compare(t, p, name, 0);
}

int main(void)
{
    th_ctx t;
    qgl_gl_desc d = {.method = QGL_METHOD_MVC};
    int rc = th_init(&t, 256, 256, &d);
    if (rc)
        return rc;
    if (qgl_gl_shader_level(t.qgl) < 150) {
        fprintf(stderr, "no geometry-shader path\n");
        return 1;
    }
    static const float convex[4][3] = {{-0.9f, -0.9f, 0}, {0.8f, -0.7f, 0}, {0.6f, 0.85f, 0}, {-0.7f, 0.3f, 0}};
    static const float concave[4][3] = {{-0.8f, -0.9f, 0}, {0.9f, 0.0f, 0}, {-0.8f, 0.9f, 0}, {-0.1f, 0.0f, 0}};
    static const float bowtie[4][3] = {{-0.9f, -0.8f, 0}, {0.9f, 0.85f, 0}, {0.85f, -0.9f, 0}, {-0.8f, 0.9f, 0}};
    static const float bowtie2[4][3] = {{-0.9f, -0.8f, 0}, {0.85f, -0.9f, 0}, {-0.8f, 0.9f, 0}, {0.9f, 0.85f, 0}};
    run_flat(&t, convex, "ref_convex");
    run_flat(&t, concave, "ref_concave");
    run_flat(&t, bowtie, "ref_bowtie");
    run_flat(&t, bowtie2, "ref_bowtie2");
    run_pixel_corners(&t);
    /* a wide viewport: the weights are those of the quad as it appears, in square pixels */
    th_viewport(&t, 0, 48, 256, 160);
    run_flat(&t, convex, "ref_wide_viewport");
    th_viewport(&t, 0, 0, 256, 256);

    /* perspective: a planar trapezoid seen obliquely, and a non-planar quad (depth) */
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-0.5, 0.5, -0.5, 0.5, 1, 20);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glTranslatef(0, 0, -3);
    glRotatef(-60, 1, 0, 0);
    glEnable(GL_DEPTH_TEST);
    static const float trapezoid[4][3] = {{-1.2f, -1, 0}, {1.2f, -1, 0}, {0.4f, 1, 0}, {-0.4f, 1, 0}};
    run_flat(&t, trapezoid, "ref_perspective");
    glLoadIdentity();
    glTranslatef(0, 0, -3);
    glRotatef(-30, 1, 0, 0);
    static const float saddle[4][3] = {{-1, -1, 0.5f}, {1, -1, -0.5f}, {1, 1, 0.5f}, {-1, 1, -0.5f}};
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    sc_draw_quad(saddle);
    th_write(&t, NULL, "ref_saddle");
    compare(&t, saddle, "ref_saddle", 1);

    /* floors to the horizon, corners from w = 1.2 to w = 900: inside the window (the range
     * the per-quad scale of g must hold in float), and reaching 50 windows out to the sides
     * and below (the driver clips: g must not be interpolated without perspective there) */
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-0.5, 0.5, -0.5, 0.5, 1, 1000);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    static const float floor_in[4][3] = {{-0.55f, -0.55f, -1.2f}, {0.6f, -0.55f, -1.3f}, {400, -0.55f, -900}, {-350, -0.55f, -800}};
    run_flat(&t, floor_in, "ref_floor");
    static const float floor_out[4][3] = {{-30, -1, -1.2f}, {40, -1, -1.3f}, {300, -1, -900}, {-250, -1, -800}};
    run_flat(&t, floor_out, "ref_floor_clipped");
    static const float floor_near[4][3] = {{-3, -1, -1.2f}, {4, -1, -1.3f}, {30, -1, -9}, {-25, -1, -8}};
    run_flat(&t, floor_near, "ref_floor_clipped2");
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-0.5, 0.5, -0.5, 0.5, 1, 20);
    glMatrixMode(GL_MODELVIEW);

    /* a corner behind the eye: the external quad (H&T 3.2), clipped at the near plane */
    glLoadIdentity();
    /* planar (z = -2 - 1.5 y), so eq. 4 depth and the clipped cover agree */
    static const float behind[4][3] = {{-1.0f, 0.8f, -3.2f}, {1.2f, 0.9f, -3.35f}, {1.5f, -2.0f, 1.0f}, {-1.2f, -1.0f, -0.5f}};
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    sc_draw_quad(behind);
    th_write(&t, NULL, "ref_behind_eye");
    compare(&t, behind, "ref_behind_eye", 0);

    qgl_gl_stats_t st;
    qgl_gl_stats(t.qgl, &st);
    th_check(st.mvc == 12 && st.quads == 12, "stats: %llu quads, %llu by mvc", (unsigned long long)st.quads,
             (unsigned long long)st.mvc);
    th_free(&t);
    return th_failures ? 1 : 0;
}
