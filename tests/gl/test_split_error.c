/* test_split_error: AUTO splits a planar quad whose split differs invisibly from its smooth
 * path (the view-invariant weights, forced by MVC_PLANE).
 *
 * A 16 x 16 grid of square quads on a plane seen in perspective carries attributes with a
 * small bilinear term (not affine, so the split is not exact). Where the planner's bound
 * says the split differs from the mean value interpolation by under half an 8-bit level
 * (colours) or 1/32 texel (texture coordinates), AUTO must split most quads (the counters)
 * and still draw the picture of the forced shader path (MVC_PLANE): within 1/255 for colours, within
 * 2/255 for a LINEAR texture with 64-level steps between neighbouring texels (1/32 texel of
 * error moves such a sample by 2 levels), except at most 0.2 % of the pixels. Where the
 * difference is visible (vertex colours in a checker; texture coordinates with a bilinear
 * term 20 times larger) every quad must take the shader path; so must Bailey's large R-B-G-R
 * quad; and split_error < 0 turns the rule off.
 * Lit quads (smooth lighting: the colours come from the driver's lighting of each corner,
 * which the planner redoes on the CPU) are held to the same: normals that bend gently over
 * the grid under a directional and a positional light with specular highlights, one-sided and
 * two-sided, split (more than half) within 1/255 of MVC_PLANE, also after a run of quads that
 * failed (the planner then judges only some); normals that alternate from vertex to vertex
 * never split; with the budget 1000 times larger they do and the pictures part. So are
 * sharper lights, where every term the planner lights the corners with counts: a directional
 * light well off the view axis with a tight highlight, and a spot over the plane seen by a
 * local viewer (some quads split, some not, each picture within 1/255). Under these and a
 * narrow hot spot, quad by quad, the verdict is held to the corners' colours the test lights
 * itself from GL's lighting equations and the state read back: a quad whose twist is well
 * inside the bound splits, one far outside does not (a spot direction left unnormalized or a
 * wrong spot exponent in the planner's lighting fails this; the pictures alone did not).
 * Corners given with their own w (glVertex4f) are held to the same picture, and so are
 * colours affine as given but not once the pipeline clamps them to [0, 1]. Unlit, each
 * parallelogram is judged against its own twist (corner colour or texture coordinate off the
 * affine value by a multiple of the budget): well inside must split, well outside must not.
 * The retained path (cached facts) plans the same. The costs are fixed (QUADGL_COSTS), so that
 * the planner judges every lit quad rather than leave some untested where this machine's
 * calibration says judging would not pay. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

enum { W = 256, H = 256, N = 16, NV = 4 * N * N };

static float pos[NV][3], col[NV][4], tex[NV][2], nrm[NV][3], hpos[NV][4];

/* Corner attributes at (x, y) of the plane z = 0, [-1, 1]^2; k scales the bilinear term (of
 * blue: 0.5 + k x y); k_col < 0 makes blue a checker of the vertices instead (0 or 1). */
static void grid(double k_col, double k_tex)
{
    int i = 0;
    for (int gy = 0; gy < N; gy++)
        for (int gx = 0; gx < N; gx++)
            for (int c = 0; c < 4; c++, i++) {
                static const int cx[4] = {0, 1, 1, 0}, cy[4] = {0, 0, 1, 1};
                float x = -1 + 2.0f * (gx + cx[c]) / N, y = -1 + 2.0f * (gy + cy[c]) / N;
                pos[i][0] = x, pos[i][1] = y, pos[i][2] = 0;
                col[i][0] = (x + 1) / 2, col[i][1] = (y + 1) / 2;
                col[i][2] = (float)(0.5 + k_col * x * y), col[i][3] = 1;
                if (k_col < 0)
                    col[i][2] = (float)((gx + cx[c] + gy + cy[c]) & 1);
                tex[i][0] = (float)((x + 1) / 2 + k_tex * x * y), tex[i][1] = (y + 1) / 2;
            }
}

/* Red 4 (x + y): affine as given, but clamped to [0, 1] at each corner, as the pipeline does,
 * it is not on the quads that straddle red = 0 or red = 1 (0.25 off there: far from
 * invisible), where the split shows a crease the smooth path does not. */
static void clamped_grid(void)
{
    grid(0, 0);
    for (int i = 0; i < NV; i++)
        col[i][0] = 4 * (pos[i][0] + pos[i][1]);
}

/* Normals of a bump over the grid, n ~ (-k x, -k y, 1); k < 0: a vertex checker of normals
 * tilted by 0.8 the one way or the other. */
static void normals(double k)
{
    for (int i = 0; i < NV; i++) {
        double x = pos[i][0], y = pos[i][1], n[3] = {-k * x, -k * y, 1};
        if (k < 0) {
            int odd = (int)lround((x + 1) * N / 2 + (y + 1) * N / 2) & 1;
            n[0] = odd ? 0.8 : -0.8, n[1] = 0.3;
        }
        double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int c = 0; c < 3; c++)
            nrm[i][c] = (float)(n[c] / l);
    }
}

/* Positions given as (w x, w y, w z, w), w varying over the grid: the rasterizer weighs each
 * corner by its clip w, which includes this w. */
static int homogeneous;

static qgl_quad_batch batch(int textured)
{
    qgl_quad_batch b = {.topology = QGL_QUADS, .count = NV};
    b.position = (qgl_attrib){pos, 3, 0, 0};
    if (homogeneous) {
        for (int i = 0; i < NV; i++) {
            float w = 0.5f + 1.5f * (pos[i][0] + 1) * (pos[i][1] + 2) / 6;
            for (int k = 0; k < 3; k++)
                hpos[i][k] = w * pos[i][k];
            hpos[i][3] = w;
        }
        b.position = (qgl_attrib){hpos, 4, 0, 0};
    }
    b.color = (qgl_attrib){col, 4, 0, 0};
    b.normal = (qgl_attrib){nrm, 3, 0, 0};
    if (textured)
        b.texcoord[0] = (qgl_attrib){tex, 2, 0, 0};
    return b;
}

/* A white directional light from above-left and a warm positional one near the plane with a
 * tight specular highlight; a grey-blue material. */
static void lights(int on, int two_sided)
{
    if (!on) {
        glDisable(GL_LIGHTING);
        return;
    }
    static const float dir[4] = {-0.3f, 0.5f, 1, 0}, posl[4] = {0.6f, -0.4f, 0.8f, 1};
    static const float white[4] = {0.8f, 0.8f, 0.8f, 1}, warm[4] = {0.9f, 0.6f, 0.3f, 1};
    static const float amb[4] = {0.2f, 0.25f, 0.3f, 1}, dif[4] = {0.5f, 0.6f, 0.8f, 1}, spe[4] = {0.6f, 0.6f, 0.6f, 1};
    glMatrixMode(GL_MODELVIEW);
    glPushMatrix();
    glLoadIdentity(); /* lights in eye space near the camera's view of the plane */
    glLightfv(GL_LIGHT0, GL_POSITION, dir);
    glLightfv(GL_LIGHT0, GL_DIFFUSE, white);
    glLightfv(GL_LIGHT0, GL_SPECULAR, white);
    glPopMatrix();
    glLightfv(GL_LIGHT1, GL_POSITION, posl);
    glLightfv(GL_LIGHT1, GL_DIFFUSE, warm);
    glLightfv(GL_LIGHT1, GL_SPECULAR, warm);
    glLightf(GL_LIGHT1, GL_LINEAR_ATTENUATION, 0.3f);
    glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, amb);
    glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, dif);
    glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, spe);
    glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 24);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, two_sided);
    glEnable(GL_LIGHT0);
    glEnable(GL_LIGHT1);
    glEnable(GL_LIGHTING);
}

/* Sharper lighting, where each light term the planner redoes matters: a directional light
 * well off the view axis (its half vector differs from its direction) with a tight highlight,
 * then a spot light seen by a local viewer. */
static void sharp_lights(int spot)
{
    static const float dir[4] = {0.7f, 0.2f, 0.6f, 0}, posl[4] = {0.2f, -0.1f, 0.9f, 1}, sdir[3] = {0, 0.1f, -1};
    static const float white[4] = {0.9f, 0.9f, 0.9f, 1}, none[4] = {0, 0, 0, 1};
    glMatrixMode(GL_MODELVIEW);
    glPushMatrix();
    if (!spot) /* the spot stands over the plane, in its coordinates */
        glLoadIdentity();
    glLightfv(GL_LIGHT0, GL_POSITION, spot ? posl : dir);
    glLightfv(GL_LIGHT0, GL_DIFFUSE, white);
    glLightfv(GL_LIGHT0, GL_SPECULAR, white);
    glLightfv(GL_LIGHT0, GL_SPOT_DIRECTION, sdir);
    glLightf(GL_LIGHT0, GL_SPOT_CUTOFF, spot ? 40 : 180);
    glLightf(GL_LIGHT0, GL_SPOT_EXPONENT, spot ? 6 : 0);
    glPopMatrix();
    glLightfv(GL_LIGHT1, GL_DIFFUSE, none);
    glLightfv(GL_LIGHT1, GL_SPECULAR, none);
    glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 60);
    glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, spot);
}

/* For the quad-by-quad check alone: a narrow spot close over the plane with a tight
 * highlight, seen by a local viewer, so that the corners' twists run from nothing to many
 * levels across the grid. */
static void hot_lights(void)
{
    static const float posl[4] = {0.3f, 0.2f, 0.45f, 1}, sdir[3] = {-0.2f, 0, -1};
    static const float white[4] = {0.9f, 0.9f, 0.9f, 1};
    glLightfv(GL_LIGHT0, GL_POSITION, posl);
    glLightfv(GL_LIGHT0, GL_DIFFUSE, white);
    glLightfv(GL_LIGHT0, GL_SPECULAR, white);
    glLightfv(GL_LIGHT0, GL_SPOT_DIRECTION, sdir);
    glLightf(GL_LIGHT0, GL_SPOT_CUTOFF, 50);
    glLightf(GL_LIGHT0, GL_SPOT_EXPONENT, 20);
    glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 40);
    glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, 1);
}

static void view(void)
{
    glViewport(0, 0, W, H);
    sc_camera(-55, 0);
}

/* 64 x 64, LINEAR: an 8-texel checker of 64 levels over gentle gradients. */
static void texture(void)
{
    static unsigned char t[64][64][4];
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) {
            int on = ((x / 8) ^ (y / 8)) & 1;
            t[y][x][0] = (unsigned char)(96 + 64 * on);
            t[y][x][1] = (unsigned char)(60 + 2 * x);
            t[y][x][2] = (unsigned char)(200 - 2 * y);
            t[y][x][3] = 255;
        }
    GLuint id;
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_2D, id);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 64, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
}

/* Draw b (or r when given) with method m; returns the picture, stats in st. */
static unsigned char *draw(th_ctx *t, qgl_method m, const qgl_quad_batch *b, const qgl_retained *r,
                           qgl_gl_stats_t *st)
{
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    qgl_gl_set_method(t->qgl, m);
    qgl_gl_reset_stats(t->qgl);
    int n = r ? qgl_gl_draw_retained(t->qgl, r) : qgl_draw_quads(t->qgl, b);
    th_check(n == N * N, "drew %d quads", n);
    glFinish();
    qgl_gl_stats(t->qgl, st);
    return th_snapshot(t);
}

/* Pixels whose channels differ by more than tol; the largest difference in *worst. */
static int count_diff(const unsigned char *a, const unsigned char *b, int tol, int *worst)
{
    int bad = 0;
    *worst = 0;
    for (int i = 0; i < W * H; i++) {
        int over = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs(a[4 * i + c] - b[4 * i + c]);
            *worst = d > *worst ? d : *worst;
            over |= d > tol;
        }
        bad += over;
    }
    return bad;
}

/* AUTO against MVC_PLANE on the grid: returns the quads AUTO split, checks the pixels. */
static int compare(th_ctx *t, const char *name, int textured, int tol, int allowed_bad, int retained)
{
    qgl_quad_batch b = batch(textured);
    qgl_retained *r = retained ? qgl_gl_retain(&b, NULL) : NULL;
    qgl_gl_stats_t sa, sm;
    unsigned char *a = draw(t, QGL_METHOD_AUTO, &b, r, &sa);
    unsigned char *m = draw(t, QGL_METHOD_MVC_PLANE, &b, r, &sm);
    int worst, bad = count_diff(a, m, tol, &worst);
    printf("%-28s auto split %3llu mvc %3llu | pixels over %d/255: %d (allowed %d), largest %d/255\n", name,
           (unsigned long long)sa.split, (unsigned long long)sa.mvc, tol, bad, allowed_bad, worst);
    th_check(sm.mvc == N * N, "%s: MVC_PLANE forced must take the shader path for every quad", name);
    th_check(bad <= allowed_bad, "%s: %d pixels differ from MVC_PLANE by more than %d/255", name, bad, tol);
    if (bad > allowed_bad) {
        th_write(t, a, "split_error_auto");
        th_write(t, m, "split_error_mvc");
    }
    qgl_gl_release(r);
    free(a);
    free(m);
    return (int)sa.split;
}

/* The comparison can fail: with the budget 1000 times larger the checker grid (colours, or
 * normals when lit) splits and its picture differs from MVC_PLANE's by many levels. */
static void teeth(th_ctx *t, const char *name, int min_bad, int min_worst)
{
    qgl_quad_batch b = batch(0);
    qgl_gl_stats_t sa, sm;
    qgl_gl_set_split_error(t->qgl, 1000);
    unsigned char *a = draw(t, QGL_METHOD_AUTO, &b, NULL, &sa);
    unsigned char *m = draw(t, QGL_METHOD_MVC_PLANE, &b, NULL, &sm);
    int worst, bad = count_diff(a, m, 1, &worst);
    printf("%-28s auto split %3llu | pixels over 1/255: %d, largest %d/255\n", name, (unsigned long long)sa.split, bad,
           worst);
    th_check(sa.split == N * N && bad > min_bad && worst > min_worst,
             "%s: split %llu, %d pixels over 1/255, largest %d: the comparison has no teeth", name,
             (unsigned long long)sa.split, bad, worst);
    qgl_gl_set_split_error(t->qgl, 0);
    free(a);
    free(m);
}

/* The lit colour of grid vertex i as the fixed-function pipeline defines it (one-sided, no
 * separate specular, lights 0 and 1: those the scenes set), from the lighting state read back
 * from GL: the reference the planner's own lighting of the corners is held to. */
static void lit_reference(int i, float out[4])
{
    double mv[16], e[3], n[3], v[3] = {0, 0, 1}, c[4];
    float ma[4], md[4], ms[4], me[4], sh, lma[4];
    GLint local = 0;
    glGetDoublev(GL_MODELVIEW_MATRIX, mv);
    glGetMaterialfv(GL_FRONT, GL_AMBIENT, ma);
    glGetMaterialfv(GL_FRONT, GL_DIFFUSE, md);
    glGetMaterialfv(GL_FRONT, GL_SPECULAR, ms);
    glGetMaterialfv(GL_FRONT, GL_EMISSION, me);
    glGetMaterialfv(GL_FRONT, GL_SHININESS, &sh);
    glGetFloatv(GL_LIGHT_MODEL_AMBIENT, lma);
    glGetIntegerv(GL_LIGHT_MODEL_LOCAL_VIEWER, &local);
    for (int r = 0; r < 3; r++) /* the view is a rotation and a translation: normals turn alike */
        e[r] = mv[r] * pos[i][0] + mv[4 + r] * pos[i][1] + mv[8 + r] * pos[i][2] + mv[12 + r],
        n[r] = mv[r] * nrm[i][0] + mv[4 + r] * nrm[i][1] + mv[8 + r] * nrm[i][2];
    double ln = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), le = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    for (int r = 0; r < 3; r++)
        n[r] /= ln, v[r] = local ? -e[r] / le : v[r];
    for (int k = 0; k < 3; k++)
        c[k] = me[k] + ma[k] * lma[k];
    for (int l = 0; l < 2; l++) {
        GLenum L = GL_LIGHT0 + (GLenum)l;
        float p[4], sd[3], la[4], ld[4], ls[4], cut, ex, k0, k1, k2;
        if (!glIsEnabled(L))
            continue;
        glGetLightfv(L, GL_POSITION, p), glGetLightfv(L, GL_SPOT_DIRECTION, sd);
        glGetLightfv(L, GL_AMBIENT, la), glGetLightfv(L, GL_DIFFUSE, ld), glGetLightfv(L, GL_SPECULAR, ls);
        glGetLightfv(L, GL_SPOT_CUTOFF, &cut), glGetLightfv(L, GL_SPOT_EXPONENT, &ex);
        glGetLightfv(L, GL_CONSTANT_ATTENUATION, &k0), glGetLightfv(L, GL_LINEAR_ATTENUATION, &k1);
        glGetLightfv(L, GL_QUADRATIC_ATTENUATION, &k2);
        double vp[3], att = 1, d = 0;
        for (int r = 0; r < 3; r++)
            vp[r] = p[3] != 0 ? p[r] / p[3] - e[r] : p[r];
        d = sqrt(vp[0] * vp[0] + vp[1] * vp[1] + vp[2] * vp[2]);
        for (int r = 0; r < 3; r++)
            vp[r] /= d;
        if (p[3] != 0)
            att = 1 / (k0 + k1 * d + k2 * d * d);
        if (cut != 180) {
            double sl = sqrt(sd[0] * sd[0] + sd[1] * sd[1] + sd[2] * sd[2]);
            double cs = -(vp[0] * sd[0] + vp[1] * sd[1] + vp[2] * sd[2]) / sl;
            att *= cs >= cos(cut * M_PI / 180) ? pow(fmax(cs, 0), ex) : 0;
        }
        double nv = n[0] * vp[0] + n[1] * vp[1] + n[2] * vp[2], h[3], hl = 0, nh = 0;
        for (int r = 0; r < 3; r++)
            h[r] = vp[r] + v[r], hl += h[r] * h[r];
        for (int r = 0; r < 3; r++)
            nh += n[r] * h[r] / sqrt(hl);
        for (int k = 0; k < 3; k++) {
            c[k] += att * la[k] * ma[k];
            if (nv > 0)
                c[k] += att * (nv * ld[k] * md[k] + (nh > 0 ? pow(nh, sh) : sh == 0) * ls[k] * ms[k]);
        }
    }
    for (int k = 0; k < 3; k++)
        out[k] = (float)fmin(fmax(c[k], 0), 1);
    out[3] = md[3];
}

/* Quad by quad under AUTO, against the reference lighting: a square quad (the grid's, with
 * one w) splits where its lit corners' twist c0 - c1 + c2 - c3 is within the budget's bound
 * (0.5/255 for a parallelogram) and is drawn smooth where it is eight times over (where the
 * planner does not even sample); the reference decides only quads well inside either side.
 * A planner that lights its corners otherwise than GL (a half vector, a spot's direction)
 * misjudges some. */
static void lit_verdicts(th_ctx *t, const char *name)
{
    int sure_split = 0, sure_mvc = 0, wrong = 0;
    qgl_gl_set_method(t->qgl, QGL_METHOD_AUTO);
    for (int q = 0; q < N * N; q++) {
        float c[4][4];
        double twist = 0;
        for (int k = 0; k < 4; k++)
            lit_reference(4 * q + k, c[k]);
        for (int k = 0; k < 4; k++)
            twist = fmax(twist, fabs((double)c[0][k] - c[1][k] + c[2][k] - c[3][k]));
        int expect = twist <= 0.45 / 255 ? 1 : twist >= 5.0 / 255 ? 0 : -1;
        if (expect < 0)
            continue;
        qgl_quad_batch b = {.topology = QGL_QUADS, .count = 4};
        b.position = (qgl_attrib){pos[4 * q], 3, 0, 0};
        b.color = (qgl_attrib){col[4 * q], 4, 0, 0};
        b.normal = (qgl_attrib){nrm[4 * q], 3, 0, 0};
        qgl_gl_reset_stats(t->qgl);
        qgl_draw_quads(t->qgl, &b);
        qgl_gl_stats_t st;
        qgl_gl_stats(t->qgl, &st);
        sure_split += expect, sure_mvc += !expect;
        if ((int)st.split != expect) {
            if (wrong++ < 5)
                printf("  %s: quad %d twist %.2f/255 %s\n", name, q, twist * 255, expect ? "not split" : "split");
        }
    }
    glFinish();
    printf("%-28s reference: %d quads surely split, %d surely smooth; misjudged %d\n", name, sure_split, sure_mvc,
           wrong);
    th_check(sure_split + sure_mvc >= N * N / 4, "%s: the reference decides too few quads (%d split, %d smooth)",
             name, sure_split, sure_mvc);
    th_check(wrong == 0, "%s: %d quads judged against the reference lighting", name, wrong);
}

/* Quad by quad on the grid's parallelograms, unlit: a twist t = c0 - c1 + c2 - c3 added at
 * corner 2 to blue (colour) or to s (texture, in texels of the 64-texel texture) against the
 * budget B, half a level or 1/32 texel. At the centre of such a quad the split and the mean
 * value weights differ by t / 4, which the planner doubles for safety: t <= 0.9 B must split
 * (its first bound passes), t >= 5 B must not (2.5 B). Most twists pass, so the planner keeps
 * trying its shortcut for parallelograms on every quad. */
static void twist_verdicts(th_ctx *t, const char *name, int textured)
{
    static const double twists[6] = {0, 0.3, 0.6, 0.9, 5, 12};
    double budget = textured ? 1.0 / 32 / 64 : 0.5 / 255;
    int wrong = 0, splits = 0;
    grid(0, 0);
    qgl_gl_set_method(t->qgl, QGL_METHOD_AUTO);
    for (int q = 0; q < N * N; q++) {
        double tw = twists[q % 6] * budget;
        float c[4][4], s[4][2];
        memcpy(c, col[4 * q], sizeof c);
        memcpy(s, tex[4 * q], sizeof s);
        if (textured)
            s[2][0] += (float)tw;
        else
            c[2][2] += (float)tw;
        qgl_quad_batch b = {.topology = QGL_QUADS, .count = 4};
        b.position = (qgl_attrib){pos[4 * q], 3, 0, 0};
        b.color = (qgl_attrib){c, 4, 0, 0};
        if (textured)
            b.texcoord[0] = (qgl_attrib){s, 2, 0, 0};
        qgl_gl_reset_stats(t->qgl);
        qgl_draw_quads(t->qgl, &b);
        qgl_gl_stats_t st;
        qgl_gl_stats(t->qgl, &st);
        int expect = twists[q % 6] < 1;
        splits += (int)st.split;
        if ((int)st.split != expect && wrong++ < 5)
            printf("  %s: quad %d twist %.2f budgets %s\n", name, q, twists[q % 6], expect ? "not split" : "split");
    }
    glFinish();
    printf("%-28s split %d of %d; misjudged %d\n", name, splits, N * N, wrong);
    th_check(wrong == 0, "%s: %d quads judged against their twist", name, wrong);
}

/* Bailey's quad: red, blue, green, red corners over most of the screen. */
static void bailey(th_ctx *t)
{
    static const float p[4][3] = {{-0.9f, -0.9f, 0}, {0.9f, -0.9f, 0}, {0.9f, 0.9f, 0}, {-0.9f, 0.9f, 0}};
    static const float c[4][4] = {{1, 0, 0, 1}, {0, 0, 1, 1}, {0, 1, 0, 1}, {1, 0, 0, 1}};
    qgl_quad_batch b = {.topology = QGL_QUADS, .count = 4};
    b.position = (qgl_attrib){p, 3, 0, 0};
    b.color = (qgl_attrib){c, 4, 0, 0};
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    qgl_gl_set_method(t->qgl, QGL_METHOD_AUTO);
    qgl_gl_reset_stats(t->qgl);
    qgl_draw_quads(t->qgl, &b);
    qgl_gl_stats_t st;
    qgl_gl_stats(t->qgl, &st);
    th_check(st.mvc == 1 && st.split == 0, "Bailey's quad: mvc %llu split %llu, expected the shader path",
             (unsigned long long)st.mvc, (unsigned long long)st.split);
}

int main(void)
{
    th_ctx t;
    /* Costs fixed for the planner (shader path 1000 ns a pixel against the split's 1, the grid
     * never cheaper): it judges every lit quad, whatever this machine would measure. */
    setenv("QUADGL_COSTS", "100,1000,1,100000000", 1);
    int rc = th_init(&t, W, H, NULL);
    if (rc)
        return rc;
    if (qgl_gl_shader_level(t.qgl) == 0) {
        th_free(&t);
        return 77;
    }
    view();
    glEnable(GL_DEPTH_TEST);
    grid(0.15, 0);
    int split = compare(&t, "colour, invisible", 0, 1, 0, 0);
    th_check(split >= N * N * 3 / 4, "colour: only %d of %d quads split", split, N * N);
    split = compare(&t, "colour, invisible, retained", 0, 1, 0, 1);
    th_check(split >= N * N * 3 / 4, "colour, retained: only %d of %d quads split", split, N * N);
    /* corners with their own w keep the test in clip space (the object-space bound assumes
     * one w for the four): whatever splits must still draw the shader path's picture */
    homogeneous = 1;
    grid(0.05, 0);
    compare(&t, "colour, own w", 0, 1, 0, 0);
    homogeneous = 0;
    grid(0.15, 0);
    qgl_gl_set_split_error(t.qgl, -1);
    split = compare(&t, "colour, rule off", 0, 1, 0, 0);
    th_check(split == 0, "split_error < 0: %d quads split", split);
    qgl_gl_set_split_error(t.qgl, 0);
    grid(-1, 0);
    split = compare(&t, "colour, visible", 0, 255, 0, 0);
    th_check(split == 0, "colour checker: %d quads split", split);
    teeth(&t, "colour, budget x1000", W * H / 20, 16);
    twist_verdicts(&t, "colour, per quad", 0);
    clamped_grid();
    for (int retained = 0; retained < 2; retained++) {
        split = compare(&t, retained ? "colour, clamped, retained" : "colour, clamped", 0, 1, 0, retained);
        th_check(split < N * N - 8, "colours clamped: %d of %d quads split, those across the clamp too", split,
                 N * N);
    }

    grid(0, 0);
    for (int two = 0; two < 2; two++) {
        lights(1, two);
        normals(0.6);
        qgl_gl_set_split_error(t.qgl, 0); /* forget the pass rate of the quads before */
        split = compare(&t, two ? "lit two-sided, invisible" : "lit, invisible", 0, 1, 0, 0);
        th_check(split >= N * N / 2, "lit%s: only %d of %d quads split", two ? " two-sided" : "", split, N * N);
        if (!two) {
            split = compare(&t, "lit, invisible, retained", 0, 1, 0, 1);
            th_check(split >= N * N / 2, "lit, retained: only %d of %d quads split", split, N * N);
        }
        normals(-1);
        split = compare(&t, two ? "lit two-sided, visible" : "lit, visible", 0, 255, 0, 0);
        th_check(split == 0, "lit%s, normals in a checker: %d quads split", two ? " two-sided" : "", split);
    }
    /* after a screenful of lit quads that all failed, the planner judges only some (their
     * expected saving is below the judging's cost), but keeps judging: invisible ones split */
    normals(0.6);
    split = compare(&t, "lit, after visible ones", 0, 1, 0, 0);
    th_check(split > 0, "lit quads after failures: none split (the planner stopped judging)");
    /* where the planner's lighting is wrong it splits quads whose highlight shows */
    for (int spot = 0; spot < 2; spot++) {
        sharp_lights(spot);
        qgl_gl_set_split_error(t.qgl, 0);
        split = compare(&t, spot ? "lit, spot, local viewer" : "lit, off-axis highlight", 0, 1, 0, 0);
        th_check(split > 0 && split < N * N, "lit%s: %d of %d quads split, expected some", spot ? ", spot" : "",
                 split, N * N);
        lit_verdicts(&t, spot ? "lit, spot, per quad" : "lit, off-axis, per quad");
    }
    hot_lights();
    lit_verdicts(&t, "lit, hot spot, per quad");
    sharp_lights(0); /* the spot's cone and the local viewer off again */
    lights(1, 0);
    normals(-1);
    teeth(&t, "lit, budget x1000", W * H / 50, 8);
    lights(0, 0);

    texture();
    glEnable(GL_TEXTURE_2D);
    grid(0, 0.04);
    split = compare(&t, "texture, invisible", 1, 2, W * H / 500, 0);
    th_check(split >= N * N * 3 / 4, "texture: only %d of %d quads split", split, N * N);
    grid(0, 0.8);
    split = compare(&t, "texture, visible", 1, 255, 0, 0);
    th_check(split == 0, "texture with a visible bilinear term: %d quads split", split);
    twist_verdicts(&t, "texture, per quad", 1);
    glDisable(GL_TEXTURE_2D);

    bailey(&t);
    th_free(&t);
    return th_failures ? 1 : 0;
}
