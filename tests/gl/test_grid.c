/* test_grid: the mean value grid path against the shader path, at seams, and its calibration.
 *
 * Budget: random quads (convex, concave, bow-tie, a corner behind the eye, tiny and window-
 * sized, in perspective, planar and not) with random corner colours are drawn in AUTO with
 * costs that make the grid cheap (QUADGL_COSTS) and in MVC_PLANE (AUTO's weights per
 * fragment); wherever the planner chose the grid, no pixel may differ from the shader path's
 * by more than one 8-bit level (the budget is half a level before rounding), and the grid must
 * have been chosen for some quads and refused for the concave, bow-tie, behind-the-eye and
 * non-planar ones (AUTO weighs planar quads in their plane, and its grid with them). Seams: two quads sharing an edge,
 * one drawn as the grid (coarse and fine: little and much colour variation) and the other by
 * the shader path, the split or another grid, with additive blending: every pixel of the
 * union is hit exactly once, and across the shared edge the colour steps by no more than its
 * gradient on either side plus 2 levels. Grouping: with the depth test on, the quads of one
 * glBegin/glEnd are drawn grouped by path, and each grid planned must move with its quad:
 * a patchwork alternating gentle colours (a coarse grid), wilder ones (a finer grid) and
 * non-planar quads (the shader path) in one batch, against MVC_PLANE, no pixel more than one
 * level apart. Calibration: a measured calibration is valid only
 * within 20 ms of timed draws, and odd given figures (negative) leave the costs invalid, so
 * that AUTO draws a large non-affine quad with the shader path. The measurement, made with
 * every cap it switches off on, per-index state, moved matrices and full attribute and matrix
 * stacks, must leave all of it as it was and raise no GL error. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"

enum { W = 128, H = 128 };

static unsigned seed = 12345;
static double rnd(void)
{
    seed = seed * 1103515245u + 12345u;
    return (double)(seed >> 8 & 0xffffff) / 16777216.0;
}

static void draw_quad(const float p[4][3], const float col[4][4])
{
    qglBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        qglColor4fv(col[i]);
        qglVertex3fv(p[i]);
    }
    qglEnd();
}

static void perspective(void)
{
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-0.5, 0.5, -0.5, 0.5, 1, 20);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glTranslatef(0, 0, -2.5f);
}

/* A random quad of one kind: 0 convex, 1 concave, 2 bow-tie, 3 behind the eye, 4 tiny, 5 large;
 * planar (on a random tilted plane) or not. */
static void random_quad(int kind, int planar, float p[4][3])
{
    double cx = rnd() - 0.5, cy = rnd() - 0.5, r = kind == 4 ? 0.02 : kind == 5 ? 1.2 : 0.2 + 0.4 * rnd();
    double sx = 0.6 * (rnd() - 0.5), sy = 0.6 * (rnd() - 0.5);
    for (int i = 0; i < 4; i++) {
        double a = i * M_PI / 2 + (rnd() - 0.5) * 0.9, rr = r * (0.7 + 0.6 * rnd());
        p[i][0] = (float)(cx + rr * cos(a)), p[i][1] = (float)(cy + rr * sin(a));
        p[i][2] = planar ? (float)(sx * p[i][0] + sy * p[i][1]) : (float)(0.3 * (rnd() - 0.5));
    }
    if (kind == 1) /* corner 2 pulled inside past the diagonal 1-3 */
        p[2][0] = (float)(0.8 * cx + 0.2 * p[0][0]), p[2][1] = (float)(0.8 * cy + 0.2 * p[0][1]);
    if (kind == 2) { /* swap two corners */
        float t[3];
        memcpy(t, p[1], sizeof t), memcpy(p[1], p[2], sizeof t), memcpy(p[2], t, sizeof t);
    }
    if (kind == 3)
        p[0][2] = 3.0f; /* past the eye at z = 2.5 */
}

static void budget(th_ctx *t)
{
    int chosen[6] = {0}, tried[6] = {0}, worst = 0, nonplanar = 0;
    perspective();
    for (int n = 0; n < 240; n++) {
        int kind = n % 6, planar = n / 6 % 2;
        float p[4][3], col[4][4];
        random_quad(kind, planar, p);
        double amp = rnd() < 0.5 ? 0.05 : 1.0; /* gentle or wild colours: fine or coarse grids */
        for (int i = 0; i < 4; i++)
            for (int c = 0; c < 4; c++)
                col[i][c] = c == 3 ? 1.0f : (float)(0.5 + amp * (rnd() - 0.5));
        unsigned char *img[2];
        qgl_gl_stats_t st;
        for (int m = 0; m < 2; m++) {
            qgl_gl_set_method(t->qgl, m ? QGL_METHOD_MVC_PLANE : QGL_METHOD_AUTO);
            qgl_gl_reset_stats(t->qgl);
            glClear(GL_COLOR_BUFFER_BIT);
            draw_quad(p, col);
            glFinish();
            if (!m)
                qgl_gl_stats(t->qgl, &st);
            img[m] = th_snapshot(t);
        }
        tried[kind]++;
        nonplanar += !planar && st.subdiv;
        if (st.subdiv == 1) {
            chosen[kind]++;
            for (int i = 0; i < W * H * 4; i++) {
                int d = abs(img[0][i] - img[1][i]);
                worst = d > worst ? d : worst;
                if (d > 1) {
                    th_check(0, "quad %d (kind %d): grid differs from the shader path by %d levels at pixel %d", n,
                             kind, d, i / 4);
                    break;
                }
            }
        }
        free(img[0]);
        free(img[1]);
    }
    printf("budget: grid chosen for convex %d/%d, concave %d/%d, bow-tie %d/%d, behind the eye %d/%d, tiny %d/%d, "
           "large %d/%d; worst difference %d levels\n",
           chosen[0], tried[0], chosen[1], tried[1], chosen[2], tried[2], chosen[3], tried[3], chosen[4], tried[4],
           chosen[5], tried[5], worst);
    th_check(chosen[0] > 0 && chosen[5] > 0, "the grid was never chosen for convex or large quads");
    th_check(nonplanar == 0, "the grid was chosen for %d non-planar quads (their view-invariant form is the patch)",
             nonplanar);
    th_check(chosen[1] == 0 && chosen[2] == 0 && chosen[3] == 0, "the grid was chosen for a concave, bow-tie or "
             "behind-the-eye quad");
}

static void grouped(th_ctx *t)
{
    enum { N = 6 };
    static const double amp[3] = {0.05, 0.4, 1.0};
    float p[N * N][4][3], col[N * N][4][4];
    for (int q = 0; q < N * N; q++) {
        int i = q % N, j = q / N, kind = (i + j) % 3;
        float x0 = -0.9f + 0.3f * (float)i, y0 = -0.9f + 0.3f * (float)j;
        const float corner[4][2] = {{x0, y0}, {x0 + 0.27f, y0}, {x0 + 0.25f, y0 + 0.26f}, {x0 + 0.02f, y0 + 0.27f}};
        for (int c = 0; c < 4; c++) {
            p[q][c][0] = corner[c][0], p[q][c][1] = corner[c][1];
            p[q][c][2] = kind == 2 && c == 2 ? 0.1f : 0.0f;
            for (int k = 0; k < 4; k++)
                col[q][c][k] = k == 3 ? 1.0f : (float)(0.5 + 0.5 * amp[kind] * sin(1.7 * q + 2.3 * c + 0.9 * k));
        }
    }
    perspective();
    glEnable(GL_DEPTH_TEST);
    unsigned char *img[2];
    qgl_gl_stats_t st;
    for (int m = 0; m < 2; m++) {
        qgl_gl_set_method(t->qgl, m ? QGL_METHOD_MVC_PLANE : QGL_METHOD_AUTO);
        qgl_gl_reset_stats(t->qgl);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        qglBegin(GL_QUADS);
        for (int q = 0; q < N * N; q++)
            for (int c = 0; c < 4; c++) {
                qglColor4fv(col[q][c]);
                qglVertex3fv(p[q][c]);
            }
        qglEnd();
        glFinish();
        if (!m)
            qgl_gl_stats(t->qgl, &st);
        img[m] = th_snapshot(t);
    }
    glDisable(GL_DEPTH_TEST);
    int worst = 0;
    long over = 0, drawn = 0;
    for (int i = 0; i < W * H * 4; i++) {
        int d = abs(img[0][i] - img[1][i]);
        worst = d > worst ? d : worst;
        over += d > 1;
        drawn += i % 4 == 0 && (img[0][i] | img[0][i + 1] | img[0][i + 2]);
    }
    printf("grouped: grid %llu, shader path %llu of %d quads, %ld pixels drawn; worst difference %d levels, %ld "
           "values over 1\n",
           (unsigned long long)st.subdiv, (unsigned long long)st.mvc, N * N, drawn, worst, over);
    th_check(st.subdiv > 0 && st.mvc > 0, "grouped: the batch did not mix the grid and the shader path");
    th_check(drawn > W * H / 4, "grouped: only %ld pixels drawn", drawn);
    th_check(worst <= 1, "grouped: the grid differs from the shader path by %d levels (%ld values over 1)", worst,
             over);
    free(img[0]);
    free(img[1]);
}

/* Pixel-exact coverage and colour continuity across the shared edge (near x = 0) of two
 * quads: colours as given, alpha 1/4 accumulated by blending (RGB replaced), so that alpha
 * counts the hits while the paths are those of the colours. */
static void seam(th_ctx *t, qgl_method left, qgl_method right, double amp_left, double amp_right, float lift,
                 const char *name)
{
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    const float l[4][3] = {{-0.9f, -0.8f, 0}, {0.013f, -0.9f, 0}, {-0.021f, 0.85f, 0}, {-0.8f, 0.7f, 0}};
    const float r[4][3] = {{0.013f, -0.9f, 0}, {0.9f, -0.7f, lift}, {0.8f, 0.9f, 0}, {-0.021f, 0.85f, 0}};
    float cl[4][4], cr[4][4];
    for (int i = 0; i < 4; i++)
        for (int c = 0; c < 4; c++) {
            cl[i][c] = c == 3 ? 0.25f : (float)(0.5 + amp_left * (rnd() - 0.5));
            cr[i][c] = c == 3 ? 0.25f : (float)(0.5 + amp_right * (rnd() - 0.5));
        }
    for (int c = 0; c < 4; c++) /* shared corners: left 1 = right 0, left 2 = right 3 */
        cr[0][c] = cl[1][c], cr[3][c] = cl[2][c];
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_ONE, GL_ZERO, GL_ONE, GL_ONE);
    qgl_gl_stats_t st[2];
    for (int k = 0; k < 2; k++) {
        qgl_gl_set_method(t->qgl, k ? right : left);
        qgl_gl_reset_stats(t->qgl);
        draw_quad(k ? r : l, (const float(*)[4])(k ? cr : cl));
        qgl_gl_stats(t->qgl, &st[k]);
    }
    glDisable(GL_BLEND);
    glFinish();
    int twice = 0, jumps = 0, xl = W / 2 - 1;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            twice += th_px(t, x, y)[3] > 96;
    for (int y = 16; y < H - 16; y++) {
        int x = xl; /* the last column of the left quad in this row */
        while (x + 1 < W && th_px(t, x + 1, y)[3] > 0 && x < W / 2 + 2 &&
               (th_px(t, x + 1, y)[0] != 0 || x + 1 < W / 2))
            x++;
        for (int c = 0; c < 3; c++) {
            int a2 = th_px(t, x - 2, y)[c], a1 = th_px(t, x - 1, y)[c], a = th_px(t, x, y)[c];
            int b = th_px(t, x + 1, y)[c], b1 = th_px(t, x + 2, y)[c], b2 = th_px(t, x + 3, y)[c];
            jumps += abs(a - b) > 2 * (abs(a2 - a1) + abs(b1 - b2) + abs(a1 - a) + abs(b - b1)) + 2;
        }
    }
    printf("seam %-22s paths (grid %llu mvc %llu split %llu | grid %llu mvc %llu split %llu): %d pixels hit twice, "
           "%d colour jumps\n",
           name, (unsigned long long)st[0].subdiv, (unsigned long long)st[0].mvc, (unsigned long long)st[0].split,
           (unsigned long long)st[1].subdiv, (unsigned long long)st[1].mvc, (unsigned long long)st[1].split, twice,
           jumps);
    th_check(st[0].subdiv == 1, "%s: the left quad did not take the grid", name);
    th_check(right != QGL_METHOD_SUBDIV || (st[1].subdiv == 1 && st[1].subdiv_triangles != st[0].subdiv_triangles),
             "%s: the right quad did not take a grid of another size", name);
    th_check(twice == 0, "%s: %d pixels hit twice", name, twice);
    th_check(jumps == 0, "%s: %d colour jumps across the shared edge", name, jumps);
}

/* The state the calibration switches off or moves, as an application may have it, read back
 * whole: caps (texture targets per unit), draw buffer 1's blending and mask and viewport 1
 * (which GL keeps per index), matrices, modes, bindings and the stacks' depths. */
static const GLenum caps[] = {GL_DEPTH_TEST, GL_STENCIL_TEST, GL_BLEND, GL_ALPHA_TEST, GL_SCISSOR_TEST,
                              GL_CULL_FACE, GL_LIGHTING, GL_FOG, GL_COLOR_LOGIC_OP, GL_POLYGON_OFFSET_FILL,
                              GL_POLYGON_STIPPLE, GL_POLYGON_SMOOTH, GL_COLOR_SUM, GL_PRIMITIVE_RESTART,
                              GL_RASTERIZER_DISCARD, GL_CLIP_PLANE0, GL_CLIP_PLANE3};
static const GLenum targets[] = {GL_TEXTURE_1D, GL_TEXTURE_2D, GL_TEXTURE_3D, GL_TEXTURE_CUBE_MAP,
                                 GL_TEXTURE_RECTANGLE};
static const struct {
    GLenum e;
    int n;
} values[] = {{GL_VIEWPORT, 4}, {GL_POLYGON_MODE, 2}, {GL_SHADE_MODEL, 1}, {GL_COLOR_WRITEMASK, 4},
              {GL_ACTIVE_TEXTURE, 1}, {GL_CLIENT_ACTIVE_TEXTURE, 1}, {GL_MATRIX_MODE, 1},
              {GL_MODELVIEW_MATRIX, 16}, {GL_PROJECTION_MATRIX, 16}, {GL_MODELVIEW_STACK_DEPTH, 1},
              {GL_PROJECTION_STACK_DEPTH, 1}, {GL_ATTRIB_STACK_DEPTH, 1}, {GL_CLIENT_ATTRIB_STACK_DEPTH, 1},
              {GL_CURRENT_PROGRAM, 1}, {GL_VERTEX_ARRAY_BINDING, 1}, {GL_ARRAY_BUFFER_BINDING, 1},
              {GL_DRAW_FRAMEBUFFER_BINDING, 1}, {GL_READ_FRAMEBUFFER_BINDING, 1}, {GL_RENDERBUFFER_BINDING, 1},
              {GL_CURRENT_COLOR, 4}};
#define NCAPS (sizeof caps / sizeof caps[0])
#define NTARGETS (sizeof targets / sizeof targets[0])
enum { UNITS = 4, NVALUES = 60 + 4 + 4 + 1 + NCAPS + UNITS * NTARGETS }; /* values[], then the indexed and caps */

static int read_state(float *out)
{
    int n = 0;
    GLint active;
    GLboolean mask[4];
    for (size_t i = 0; i < sizeof values / sizeof values[0]; i++)
        glGetFloatv(values[i].e, out + n), n += values[i].n;
    glGetFloati_v(GL_VIEWPORT, 1, out + n), n += 4;
    glGetBooleani_v(GL_COLOR_WRITEMASK, 1, mask);
    for (int i = 0; i < 4; i++)
        out[n++] = mask[i];
    out[n++] = glIsEnabledi(GL_BLEND, 1);
    for (size_t i = 0; i < NCAPS; i++)
        out[n++] = glIsEnabled(caps[i]);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    for (int u = 0; u < UNITS; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        for (size_t i = 0; i < NTARGETS; i++)
            out[n++] = glIsEnabled(targets[i]);
    }
    glActiveTexture((GLenum)active);
    return n;
}

static void app_state(void)
{
    GLint depth;
    static const GLenum stacks[2][2] = {{GL_PROJECTION, GL_MAX_PROJECTION_STACK_DEPTH},
                                        {GL_MODELVIEW, GL_MAX_MODELVIEW_STACK_DEPTH}};
    for (int i = 0; i < 2; i++) {
        glMatrixMode(stacks[i][0]);
        glGetIntegerv(stacks[i][1], &depth);
        for (int d = 1; d < depth; d++)
            glPushMatrix();
        glRotatef(20.0f + 10.0f * (float)i, 0.3f, 0.4f, 0.5f);
    }
    glGetIntegerv(GL_MAX_ATTRIB_STACK_DEPTH, &depth);
    for (int d = 0; d < depth; d++)
        glPushAttrib(GL_CURRENT_BIT);
    glGetIntegerv(GL_MAX_CLIENT_ATTRIB_STACK_DEPTH, &depth);
    for (int d = 0; d < depth; d++)
        glPushClientAttrib(GL_CLIENT_PIXEL_STORE_BIT);
    for (size_t i = 0; i < NCAPS; i++)
        glEnable(caps[i]);
    glDisablei(GL_BLEND, 1);
    for (int u = 0; u < UNITS; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        glEnable(targets[u]);
        glEnable(targets[(u + 2) % 5]);
    }
    glActiveTexture(GL_TEXTURE2);
    glClientActiveTexture(GL_TEXTURE1);
    glMatrixMode(GL_TEXTURE);
    glPolygonMode(GL_FRONT, GL_LINE);
    glPolygonMode(GL_BACK, GL_POINT);
    glShadeModel(GL_FLAT);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glColorMaski(1, GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
    glViewport(3, 5, 70, 40);
    glViewportIndexedf(1, 1.5f, 2.5f, 33.0f, 44.0f);
    glColor4f(0.1f, 0.2f, 0.3f, 0.4f);
}

static void app_state_undo(void)
{
    GLint depth;
    glGetIntegerv(GL_ATTRIB_STACK_DEPTH, &depth);
    while (depth--)
        glPopAttrib();
    glGetIntegerv(GL_CLIENT_ATTRIB_STACK_DEPTH, &depth);
    while (depth--)
        glPopClientAttrib();
    for (int i = 0; i < 2; i++) {
        glMatrixMode(i ? GL_MODELVIEW : GL_PROJECTION);
        glGetIntegerv(i ? GL_MODELVIEW_STACK_DEPTH : GL_PROJECTION_STACK_DEPTH, &depth);
        while (depth-- > 1)
            glPopMatrix();
        glLoadIdentity();
    }
    for (size_t i = 0; i < NCAPS; i++)
        glDisable(caps[i]);
    for (int u = 0; u < UNITS; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        for (size_t i = 0; i < NTARGETS; i++)
            glDisable(targets[i]);
    }
    glActiveTexture(GL_TEXTURE0);
    glClientActiveTexture(GL_TEXTURE0);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glShadeModel(GL_SMOOTH);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glViewport(0, 0, W, H);
}

static void calibration(th_ctx *t)
{
    qgl_gl_costs_t c;
    float before[NVALUES], after[NVALUES];
    while (glGetError() != GL_NO_ERROR)
        ;
    app_state();
    int n = read_state(before);
    th_check(glGetError() == GL_NO_ERROR, "setting the application's state raised an error");
    qgl_gl_costs(t->qgl, &c); /* the first measurement of this renderer in the process */
    th_check(c.ms + c.warm_ms > 0, "no calibration was measured");
    GLenum err = glGetError();
    th_check(err == GL_NO_ERROR, "the calibration raised GL error 0x%x", err);
    read_state(after);
    for (int i = 0; i < n; i++)
        th_check(before[i] == after[i], "the calibration changed state value %d: %g -> %g", i, before[i], after[i]);
    app_state_undo();
    printf("calibration: valid %d, %.2f ms timed (+ %.0f ms first draws): %.0f ns/quad + %.2f ns/px shader, "
           "%.2f ns/px split, %.0f ns/triangle grid\n",
           c.valid, c.ms, c.warm_ms, c.mvc_quad_ns, c.mvc_px_ns, c.split_px_ns, c.grid_tri_ns);
    th_check(!c.valid || c.ms <= 20.0, "a calibration of %.1f ms was taken as valid", c.ms);
    setenv("QUADGL_COSTS", "1000,-5,3,100", 1);
    qgl_context *odd = qgl_gl_create(&(qgl_gl_desc){.get_proc = th_get_proc});
    unsetenv("QUADGL_COSTS");
    qgl_gl_costs(odd, &c);
    th_check(odd && !c.valid, "odd given costs were taken as valid");
    qgl_gl_make_current(odd);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    const float p[4][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    const float col[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {0, 0, 0, 1}};
    draw_quad(p, col);
    qgl_gl_stats_t st;
    qgl_gl_stats(odd, &st);
    th_check(st.mvc == 1 && st.subdiv == 0, "with invalid costs a non-affine quad took grid %llu mvc %llu",
             (unsigned long long)st.subdiv, (unsigned long long)st.mvc);
    qgl_gl_destroy(odd);
    qgl_gl_make_current(t->qgl);
}

int main(void)
{
    th_ctx t;
    setenv("QUADGL_COSTS", "1000,10,3,1", 1); /* the grid cheap, so that the bound decides */
    int r = th_init(&t, W, H, NULL);
    unsetenv("QUADGL_COSTS");
    if (r)
        return r;
    if ((r = th_need_geometry_shaders(&t)) != 0)
        return r;
    budget(&t);
    grouped(&t);
    seam(&t, QGL_METHOD_AUTO, QGL_METHOD_MVC, 0.05, 1.0, 0.3f, "grid | shader path");
    seam(&t, QGL_METHOD_AUTO, QGL_METHOD_SPLIT, 1.0, 1.0, 0.3f, "grid | split");
    seam(&t, QGL_METHOD_AUTO, QGL_METHOD_SUBDIV, 0.02, 0.2, 0, "coarse grid | fine grid");
    seam(&t, QGL_METHOD_SUBDIV, QGL_METHOD_MVC, 1.0, 0.3, 0.3f, "finest grid | shader");
    th_free(&t);
    qgl_gl_desc d = {.get_proc = th_get_proc};
    if (th_init(&t, W, H, &d) == 0) {
        calibration(&t);
        th_free(&t);
    }
    printf("%s\n", th_failures ? "FAILED" : "ok");
    return th_failures ? 1 : 0;
}
