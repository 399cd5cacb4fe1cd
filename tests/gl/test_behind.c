/* test_behind: random quads with corners behind the eye (H&T sec. 3.2) on every path.
 *
 * Random quads (fixed seeds) with one, two and three corners behind the eye, planar and
 * non-planar, of every exterior shape: the screen quad's shape in the projective plane of its
 * homogeneous corners (x, y, w), convex, concave or bow-tie (H&T's figure 9), PER_BIN of each.
 * Each is drawn alone on black through the driver (GL_QUADS) and through every path: the
 * geometry shader path with AUTO, MVC, MVC_PLANE, SUBDIV (the CPU fallback: the grid never
 * serves a quad behind the eye) and SPLIT; the GLSL 1.20 path with MVC and MVC_PLANE; the CPU
 * fallback of a context without shaders with MVC and MVC_PLANE.
 *
 * What is right. A pixel belongs to the quad where its centre lies in the screen quad (the
 * core's weights say QGL_INSIDE: H&T's external quad) and the surface there lies between the
 * near and far planes. The driver draws its triangle split. In the projective plane either
 * split of a quad covers it, each point once, so where the screen quad is convex the driver's
 * coverage is the quad's; where it is concave or a bow-tie the split covers more (the notch,
 * the triangles beside the lobes) and the quad itself is right, as in front of the eye (the
 * exact cover of DESIGN.md, the paper's figure 9 shapes). Checked per path:
 * - lost: pixels whose 3 x 3 neighbourhood is inside and visible, not drawn; extra: drawn
 *   pixels whose neighbourhood is outside or hidden, not on the driver's own boundary band
 *   (pixels whose neighbourhood the driver covers in part: rounding of a sliver's tip). Both 0.
 * - convex: the covered set equals the driver's off its boundary band; concave and bow-tie:
 *   nothing drawn off the driver's coverage and band. On a non-planar quad the near plane cuts
 *   the two splits differently: pixels near one where the four triangles of both splits
 *   disagree about visibility are not judged.
 * - values on the inner pixels against the mean value reference: H&T's screen-space weights
 *   (core qgl_weights, double) for MVC and for non-planar quads on every method (draw.c's
 *   plan_quad says why), the in-plane weights of the pixel's surface point (the ray's hit on
 *   the quad's plane, qgl_weights_inplane) for planar quads on the view-invariant methods.
 *   Shader paths: within 2/255 (float weights against double). CPU fallback: 2/255 plus what
 *   its tolerance allows, a displacement of half a pixel (QUADGL_TOLERANCE 0.5): half the
 *   reference's largest change to a neighbouring pixel (the weights are cones at a reflex
 *   corner and jump at a bow-tie's crossing point, where that change is large).
 * - SPLIT: the driver's own picture (1/255); every path drew each quad where it should
 *   (statistics).
 * A failing path writes behind_PATH.ppm: driver, ours, and the difference (red: lost against
 * the driver, green: extra, blue: the quad). A floor mesh through the eye plane is drawn with
 * additive blending on every path: no pixel twice, the driver's coverage. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

enum { W = 160, H = 160, PER_BIN = 8 };

static const double pi = 3.14159265358979323846;

enum { K_CONVEX, K_CONCAVE, K_BOWTIE };
static const char *const kind_name[3] = {"convex", "concave", "bow-tie"};

typedef struct quad {
    float p[4][3], c[4][4];
    double clip[4][4];
    int behind, planar, kind;
} quad;

static double rnd(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return ((*s >> 8) & 0xffffff) / (double)0xffffff;
}

static double det3(const double a[3], const double b[3], const double c[3])
{
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

static void homogeneous(const double c[4], double h[3])
{
    h[0] = c[0], h[1] = c[1], h[2] = c[3];
}

/* The screen quad's shape in the projective plane: the signs of the corner turns
 * det(h_{i-1}, h_i, h_{i+1}); -1 when a turn vanishes. */
static int projective_kind(const double clip[4][4])
{
    int pos = 0, neg = 0;
    for (int i = 0; i < 4; i++) {
        double a[3], b[3], c[3];
        homogeneous(clip[(i + 3) & 3], a);
        homogeneous(clip[i], b);
        homogeneous(clip[(i + 1) & 3], c);
        double d = det3(a, b, c);
        pos += d > 0, neg += d < 0;
    }
    if (pos + neg != 4)
        return -1;
    return pos == 4 || neg == 4 ? K_CONVEX : pos == 2 ? K_BOWTIE : K_CONCAVE;
}

/* Whether the eye lies in the convex hull of the corners (a non-planar quad around the eye):
 * their (x, y, w) then lie in no open half-space and the screen quad is no quad. */
static int eye_in_hull(const double clip[4][4])
{
    double m[3][4], cof[4], det = 0;
    for (int i = 0; i < 4; i++)
        m[0][i] = clip[i][0], m[1][i] = clip[i][1], m[2][i] = clip[i][3];
    /* sum a_i h_i = 0 with sum a_i = 1: a_i are the cofactors of the row of ones */
    for (int j = 0; j < 4; j++) {
        double s[3][3];
        for (int r = 0; r < 3; r++)
            for (int c = 0, cc = 0; c < 4; c++)
                if (c != j)
                    s[r][cc++] = m[r][c];
        cof[j] = (j & 1 ? 1 : -1) * det3(s[0], s[1], s[2]);
        det += cof[j];
    }
    if (!(fabs(det) > 1e-12))
        return 1;
    for (int j = 0; j < 4; j++)
        if (cof[j] / det < 0)
            return 0;
    return 1;
}

/* A 2D quad of a kind around the origin, radius 0.6 to 1. */
static void shape2d(int kind, unsigned *s, double q[4][2])
{
    for (;;) {
        double phase = rnd(s) * 2 * pi;
        for (int i = 0; i < 4; i++) {
            double a = phase + (i + (rnd(s) - 0.5) * 0.6) * pi / 2, r = 0.6 + 0.4 * rnd(s);
            q[i][0] = r * cos(a), q[i][1] = r * sin(a);
        }
        if (kind == K_CONCAVE) { /* corner r into the triangle of the other three */
            int r = (int)(rnd(s) * 4) & 3;
            double b[3] = {0.1 + rnd(s), 0.1 + rnd(s), 0.1 + rnd(s)}, sum = b[0] + b[1] + b[2];
            const double *A = q[(r + 3) & 3], *B = q[(r + 1) & 3], *C = q[(r + 2) & 3];
            for (int k = 0; k < 2; k++)
                q[r][k] = (b[0] * A[k] + b[1] * B[k] + b[2] * C[k]) / sum;
        } else if (kind == K_BOWTIE) {
            int e = rnd(s) < 0.5 ? 1 : 2;
            for (int k = 0; k < 2; k++) {
                double t = q[e][k];
                q[e][k] = q[e + 1][k], q[e + 1][k] = t;
            }
        }
        static const int want[3] = {QGL_QUAD_CONVEX, QGL_QUAD_CONCAVE, QGL_QUAD_BOWTIE};
        qgl_cover cov;
        if (qgl_classify(q, &cov) == want[kind] && cov.ntri == 2)
            return;
    }
}

static void camera(void)
{
    double t = 0.1 * tan(32 * pi / 180);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-t, t, -t, t, 0.1, 50);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
}

/* A random quad in eye space (the modelview is the identity) whose screen quad is of the
 * kind, with `behind` corners behind the eye; non-planar: corners lifted alternately off
 * the plane by 15% to 45% of its size. */
static void make_quad(int kind, int behind, int planar, unsigned *s, quad *out)
{
    for (;;) {
        double q[4][2], n[3], u[3], v[3], c[3];
        shape2d(kind, s, q);
        double z = 2 * rnd(s) - 1, a = 2 * pi * rnd(s), r = sqrt(1 - z * z);
        n[0] = r * cos(a), n[1] = r * sin(a), n[2] = z;
        double t[3] = {fabs(n[0]) < 0.9 ? 1 : 0, fabs(n[0]) < 0.9 ? 0 : 1, 0}, un = 0;
        u[0] = n[1] * t[2] - n[2] * t[1], u[1] = n[2] * t[0] - n[0] * t[2], u[2] = n[0] * t[1] - n[1] * t[0];
        for (int k = 0; k < 3; k++)
            un += u[k] * u[k];
        for (int k = 0; k < 3; k++)
            u[k] /= sqrt(un);
        v[0] = n[1] * u[2] - n[2] * u[1], v[1] = n[2] * u[0] - n[0] * u[2], v[2] = n[0] * u[1] - n[1] * u[0];
        c[0] = 0.8 * (rnd(s) - 0.5), c[1] = 0.8 * (rnd(s) - 0.5), c[2] = -1.0 + 1.3 * rnd(s);
        double size = 0.8 + 1.2 * rnd(s);
        for (int i = 0; i < 4; i++) {
            double h = planar ? 0 : size * (0.15 + 0.3 * rnd(s)) * (i & 1 ? -1 : 1);
            for (int k = 0; k < 3; k++)
                out->p[i][k] = (float)(c[k] + size * (q[i][0] * u[k] + q[i][1] * v[k]) + h * n[k]);
            for (int k = 0; k < 3; k++)
                out->c[i][k] = (float)(0.2 + 0.8 * rnd(s));
            out->c[i][3] = 1;
        }
        th_clip_of(out->p, out->clip);
        int nb = 0, at_eye = 0;
        for (int i = 0; i < 4; i++) {
            nb += out->clip[i][3] < 0;
            at_eye |= fabs(out->clip[i][3]) < 1e-3;
        }
        if (nb == behind && !at_eye && projective_kind(out->clip) == kind && !eye_in_hull(out->clip)) {
            out->behind = behind, out->planar = planar, out->kind = kind;
            return;
        }
    }
}

/* ---- the references, per pixel ---------------------------------------------------------------- */

/* D_VIS / D_HID: every triangle of both splits holding the pixel's centre puts the surface
 * between the near and far planes / none does; D_AMB: they disagree (non-planar quads). */
enum { D_NONE, D_VIS, D_HID, D_AMB };

typedef struct ref_map {
    unsigned char in[W * H];    /* the centre lies in the screen quad */
    unsigned char depth[W * H]; /* D_* */
    float scr[W * H][4];        /* colour by H&T's screen-space weights */
    float pl[W * H][4];         /* colour by the in-plane weights (planar quads) */
} ref_map;

static const int tris[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 1, 3}, {1, 2, 3}};

/* Whether the ray of NDC point (X, Y) meets the clip-space triangle in front of the eye: its
 * homogeneous barycentrics b, all >= 0 (all <= 0 is the mirror image behind the eye). */
static int in_tri(const double clip[4][4], const int t[3], double X, double Y, double b[3])
{
    double h[3][3], p[3] = {X, Y, 1};
    for (int k = 0; k < 3; k++)
        homogeneous(clip[t[k]], h[k]);
    double d = det3(h[0], h[1], h[2]);
    if (d == 0)
        return 0;
    b[0] = det3(p, h[1], h[2]) / d, b[1] = det3(h[0], p, h[2]) / d, b[2] = det3(h[0], h[1], p) / d;
    return b[0] >= 0 && b[1] >= 0 && b[2] >= 0;
}

static void colour_of(const float c[4][4], const double lam[4], float out[4])
{
    for (int k = 0; k < 4; k++)
        out[k] = (float)(lam[0] * c[0][k] + lam[1] * c[1][k] + lam[2] * c[2][k] + lam[3] * c[3][k]);
}

static void reference(const th_ctx *t, const quad *q, ref_map *m)
{
    qgl_plane pl;
    double pos[4][3];
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            pos[i][k] = q->p[i][k];
    qgl_plane_frame(pos, &pl);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x, nin = 0, nvis = 0;
            double lam[4], X = (x + 0.5) / W * 2 - 1, Y = (y + 0.5) / H * 2 - 1, hit[3] = {0, 0, 0};
            m->in[i] = th_weights(t, q->clip, x, y, lam, NULL) == QGL_INSIDE;
            colour_of(q->c, lam, m->scr[i]);
            for (int k = 0; k < 4; k++) {
                double b[3], z = 0, sb = 0;
                if (!in_tri(q->clip, tris[k], X, Y, b))
                    continue;
                for (int j = 0; j < 3; j++)
                    z += b[j] * q->clip[tris[k][j]][2], sb += b[j];
                nin++;
                nvis += z >= -1 && z <= 1; /* b is scaled to the ray's w = 1 */
                if (nin == 1) /* the object point of the ray's hit (planar: on the plane) */
                    for (int j = 0; j < 3; j++)
                        for (int d = 0; d < 3; d++)
                            hit[d] += b[j] / sb * pos[tris[k][j]][d];
            }
            m->depth[i] = !nin ? D_NONE : nvis == nin ? D_VIS : nvis == 0 ? D_HID : D_AMB;
            double xy[2];
            qgl_plane_coords(&pl, hit, xy);
            qgl_weights_inplane(&pl, xy[0], xy[1], lam);
            colour_of(q->c, lam, m->pl[i]);
        }
}

/* ---- drawing ---------------------------------------------------------------------------------- */

static unsigned char *picture(th_ctx *t, const quad *q, int native)
{
    glClear(GL_COLOR_BUFFER_BIT);
    native ? glBegin(GL_QUADS) : qglBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        if (native) {
            glColor4fv(q->c[i]);
            glVertex3fv(q->p[i]);
        } else {
            qglColor4fv(q->c[i]);
            qglVertex3fv(q->p[i]);
        }
    }
    native ? glEnd() : qglEnd();
    return th_snapshot(t);
}

/* ---- judging ---------------------------------------------------------------------------------- */

typedef struct path {
    const char *name;
    qgl_context *ctx;
    qgl_method method;
    int fallback;                /* the CPU fallback draws it */
    long quads, inner, lost, lost_drawn, extra, differ, outside, bad, worst_px;
    double worst;
    unsigned char *shot;         /* the worst picture: driver, ours, difference */
} path;

static int on(const unsigned char *img, int x, int y)
{
    return img[4 * (y * W + x) + 3] != 0;
}

static void keep_worst(path *p, const ref_map *m, const unsigned char *drv, const unsigned char *img, long score)
{
    if (score <= p->worst_px)
        return;
    p->worst_px = score;
    if (!p->shot)
        p->shot = malloc((size_t)3 * W * H * 4);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x, o = on(img, x, y), d = on(drv, x, y);
            unsigned char *a = p->shot + 4 * ((size_t)y * 3 * W + x), *b = a + 4 * W, *c = b + 4 * W;
            memcpy(a, drv + 4 * i, 4);
            memcpy(b, img + 4 * i, 4);
            c[0] = d && !o ? 255 : 0, c[1] = o && !d ? 255 : 0, c[2] = m->in[i] ? 96 : 0, c[3] = 255;
        }
}

/* The reference colour's largest change to a neighbouring pixel, per pixel of distance. */
static double gradient(const float (*ref)[4], int x, int y)
{
    double g = 0;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++)
            for (int k = 0; k < 3 && (dx || dy); k++)
                g = fmax(g, fabs(ref[(y + dy) * W + x + dx][k] - ref[y * W + x][k]) / hypot(dx, dy));
    return g * 255;
}

static void judge(path *p, const quad *q, const ref_map *m, const unsigned char *drv, const unsigned char *img)
{
    int screen = p->method == QGL_METHOD_MVC || !q->planar;
    const float(*ref)[4] = screen ? m->scr : m->pl;
    long inner = 0, lost = 0, lost_drawn = 0, extra = 0, differ = 0, outside = 0, bad = 0;
    for (int y = 1; y < H - 1; y++)
        for (int x = 1; x < W - 1; x++) {
            int all_in = 1, all_out = 1, amb = 0, dall = 1, dany = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int j = (y + dy) * W + x + dx;
                    all_in &= m->in[j] && m->depth[j] == D_VIS;
                    all_out &= !m->in[j] || m->depth[j] == D_HID || m->depth[j] == D_NONE;
                    amb |= m->depth[j] == D_AMB;
                    dall &= on(drv, x + dx, y + dy);
                    dany |= on(drv, x + dx, y + dy);
                }
            int i = y * W + x, o = on(img, x, y), d = on(drv, x, y), band = dany && !dall;
            inner += all_in;
            lost += all_in && !o;
            lost_drawn += all_in && !o && d;
            extra += all_out && o && !band;
            if (!band && !amb && o != d)
                q->kind == K_CONVEX ? differ++ : (outside += o);
            if (!all_in || !o)
                continue;
            double tol = 2 + (p->fallback ? 0.5 * gradient(ref, x, y) : 0);
            for (int k = 0; k < 3; k++) {
                double e = fabs(img[4 * i + k] - ref[i][k] * 255.0);
                p->worst = fmax(p->worst, e);
                bad += e > tol;
            }
        }
    p->quads++;
    p->inner += inner, p->lost += lost, p->lost_drawn += lost_drawn, p->extra += extra, p->differ += differ;
    p->outside += outside, p->bad += bad;
    if (lost + extra + differ + outside + bad)
        printf("  %-14s %-7s %d behind, %-10s: inner %5ld lost %ld (the driver drew %ld) extra %ld differ %ld "
               "outside %ld, %ld values off\n",
               p->name, kind_name[q->kind], q->behind, q->planar ? "planar" : "non-planar", inner, lost, lost_drawn,
               extra, differ, outside, bad);
    keep_worst(p, m, drv, img, lost + extra + differ + outside + bad);
}

/* Every quad on the path the method should take: the shader path, the CPU fallback, the
 * driver's split. */
static void check_stats(path *p, th_ctx *t, const quad *q, const unsigned char *drv, const unsigned char *img)
{
    qgl_gl_stats_t st;
    qgl_gl_stats(p->ctx, &st);
    uint64_t want = p->method == QGL_METHOD_SPLIT ? st.split : p->fallback ? st.fallback : st.mvc;
    th_check(st.quads == 1 && want == 1, "%s: a %s quad took another path", p->name, kind_name[q->kind]);
    if (p->method != QGL_METHOD_SPLIT)
        return;
    int over;
    sc_diff(t, drv, img, 1, &over);
    p->quads++;
    p->differ += over;
}

/* ---- a floor through the eye plane ------------------------------------------------------------- */

/* A jittered non-planar mesh under the eye, from behind it to the distance, drawn with additive
 * blending: no pixel hit twice, and the driver's coverage (its quads are convex on screen and
 * it does not fold over itself); the CPU fallback may miss or double one pixel in 1000 of
 * those covered. */
static void floor_mesh(th_ctx *t, path *p)
{
    sc_mesh *m = malloc(sizeof *m);
    sc_jitter_grid(m, 10, 0.25f, 0.03f, 5u, 0);
    camera();
    glTranslatef(0, -0.6f, -1.6f);
    glRotatef(-90, 1, 0, 0);
    glScalef(1.2f, 2.2f, 1);
    qgl_gl_make_current(p->ctx);
    qgl_gl_set_method(p->ctx, p->method);
    sc_coverage cv;
    sc_coverage_run(t, m, &cv);
    int behind = 0;
    for (int i = 0; i < m->nverts; i++) {
        double c[4][4];
        float pp[4][3];
        for (int k = 0; k < 4; k++)
            memcpy(pp[k], m->pos[i], sizeof pp[k]);
        th_clip_of((const float(*)[3])pp, c);
        behind += c[0][3] < 0;
    }
    printf("floor %-14s covered %d, hit twice %d, differ from the driver %d (%d corners behind the eye)\n", p->name,
           cv.inside, cv.twice, cv.differ, behind);
    /* the fallback's seams with its neighbours are T-junctions (fallback.c's known limit) */
    int slack = p->fallback ? cv.inside / 1000 : 0;
    th_check(cv.inside > 5000 && behind > 10 && cv.twice + cv.differ <= slack, "floor %s: coverage", p->name);
    glDisable(GL_BLEND);
    free(cv.native);
    free(cv.ours);
    free(m);
    camera();
}

int main(void)
{
    th_ctx t;
    qgl_gl_desc d = {.method = QGL_METHOD_AUTO};
    int rc = th_init(&t, W, H, &d);
    if (rc)
        return rc;
    qgl_gl_desc d120 = {.max_glsl = 120, .get_proc = th_get_proc};
    qgl_gl_desc dfb = {.force_fallback = 1, .get_proc = th_get_proc, .tolerance_px = 0.5f};
    qgl_context *c120 = qgl_gl_create(&d120), *cfb = qgl_gl_create(&dfb);
    if (qgl_gl_shader_level(t.qgl) < 150 || !c120 || qgl_gl_shader_level(c120) != 120 || !cfb) {
        fprintf(stderr, "the three paths are not all here\n");
        return 1;
    }
    path paths[] = {
        {.name = "auto", .ctx = t.qgl, .method = QGL_METHOD_AUTO},
        {.name = "mvc", .ctx = t.qgl, .method = QGL_METHOD_MVC},
        {.name = "mvcplane", .ctx = t.qgl, .method = QGL_METHOD_MVC_PLANE},
        {.name = "subdiv", .ctx = t.qgl, .method = QGL_METHOD_SUBDIV, .fallback = 1},
        {.name = "split", .ctx = t.qgl, .method = QGL_METHOD_SPLIT},
        {.name = "glsl120_mvc", .ctx = c120, .method = QGL_METHOD_MVC},
        {.name = "glsl120_mvcplane", .ctx = c120, .method = QGL_METHOD_MVC_PLANE},
        {.name = "fallback_mvc", .ctx = cfb, .method = QGL_METHOD_MVC, .fallback = 1},
        {.name = "fallback_mvcplane", .ctx = cfb, .method = QGL_METHOD_MVC_PLANE, .fallback = 1},
    };
    enum { NP = sizeof paths / sizeof paths[0] };
    camera();
    glDisable(GL_DEPTH_TEST);
    glClearColor(0, 0, 0, 0);
    ref_map *m = malloc(sizeof *m);
    unsigned seed = 2024;
    int nquads = 0;
    for (int behind = 1; behind <= 3; behind++)
        for (int planar = 1; planar >= 0; planar--)
            for (int kind = 0; kind < 3; kind++)
                for (int n = 0; n < PER_BIN;) {
                    quad q;
                    make_quad(kind, behind, planar, &seed, &q);
                    reference(&t, &q, m);
                    int inner = 0;
                    for (int i = 0; i < W * H; i++)
                        inner += m->in[i] && m->depth[i] == D_VIS;
                    if (inner < 300) /* too little of it on screen */
                        continue;
                    n++, nquads++;
                    qgl_gl_make_current(t.qgl);
                    unsigned char *drv = picture(&t, &q, 1);
                    for (int k = 0; k < NP; k++) {
                        path *p = &paths[k];
                        qgl_gl_make_current(p->ctx);
                        qgl_gl_set_method(p->ctx, p->method);
                        qgl_gl_reset_stats(p->ctx);
                        unsigned char *img = picture(&t, &q, 0);
                        check_stats(p, &t, &q, drv, img);
                        if (p->method != QGL_METHOD_SPLIT)
                            judge(p, &q, m, drv, img);
                        free(img);
                    }
                    free(drv);
                }
    printf("%d random quads, 1 to 3 corners behind the eye, planar and not, convex, concave and bow-tie:\n", nquads);
    for (int k = 0; k < NP; k++) {
        path *p = &paths[k];
        if (p->method == QGL_METHOD_SPLIT)
            printf("%-18s %ld pixels off the driver's picture by more than 1/255\n", p->name, p->differ);
        else
            printf("%-18s inner %8ld lost %ld (the driver drew %ld) extra %ld differ %ld outside %ld, values off %ld "
                   "(worst %.1f/255)\n",
                   p->name, p->inner, p->lost, p->lost_drawn, p->extra, p->differ, p->outside, p->bad, p->worst);
        int ok = p->lost + p->extra + p->differ + p->outside + p->bad == 0;
        th_check(ok, "%s: coverage or values differ", p->name);
        if (!ok && p->shot) {
            th_ctx sheet = {.w = 3 * W, .h = H};
            char name[64];
            snprintf(name, sizeof name, "behind_%s", p->name);
            th_write(&sheet, p->shot, name);
        }
        free(p->shot);
    }
    for (int k = 0; k < NP; k++)
        floor_mesh(&t, &paths[k]);
    qgl_gl_make_current(t.qgl);
    free(m);
    qgl_gl_destroy(c120);
    qgl_gl_destroy(cfb);
    th_free(&t);
    return th_failures ? 1 : 0;
}
