/* test_plane: the view-invariant shader path (method MVC_PLANE, AUTO's smooth path) against
 * independent references, under random cameras.
 *
 * Planar quads of every shape (convex, trapezoid, concave, bow-tie) in random planes, a floor
 * with a corner behind the eye and one reaching towards the horizon (corner w from 0.25 to
 * 15), each from several random viewpoints (0 to 80 degrees
 * from head-on): every pixel whose 3 x 3 neighbourhood is inside the quad must match the
 * core's double in-plane weights at the pixel's surface point (the ray's hit on the plane,
 * solved in double) within 2/255, and no pixel outside the quad may be drawn. The view drift
 * itself, in a float framebuffer over 8 views at two distances: the value at fixed surface
 * points (bins of the quad's plane) may change from view to view by < 0.5/255 on the shader
 * path (which also stays within 0.25/255 of the reference) and on the grid (SUBDIV: its
 * layout is fixed in the plane, so only float rounding moves it), by < 3/255 on the CPU
 * fallback (its grid follows the quad's size in pixels: within 0.5 px of the view-invariant
 * pattern from every view), while the screen-space method (MVC) must exceed 2/255 on the
 * same quads: the comparison has teeth.
 * Linear precision against the driver: planar convex quads with colours affine in object
 * space equal the driver's own GL_QUADS within 2/255 from every view. Non-planar quads (the
 * patch form) match the software renderer's mvcpatch (double) within 2/255 and its depth
 * within 1e-4. Turning the corner order changes no pixel by more than 1/255. A mesh of
 * planar jittered quads and a non-planar one are watertight (additive blending: no pixel hit
 * twice, coverage equal to the driver's). Two planar quads folded along a shared edge that
 * runs through pixel centres show on that edge the perspective-correct linear interpolation
 * of its two corners (1/255), whichever path draws the neighbour: its own (MVC_PLANE), the
 * screen-space one, the driver's split or the subdivision. A quad with a corner at infinity (object w = 0) is
 * drawn where the driver draws it. All of it on the geometry shader path and on the
 * GLSL 1.20 path (max_glsl 120). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

enum { W = 255, H = 255 };

static const double pi = 3.14159265358979323846;

static double rnd(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return ((*s >> 8) & 0xffffff) / (double)0xffffff;
}

/* A camera at distance dist from the origin, elev degrees from the z axis at azimuth azim,
 * looking at target, with a perspective of 50 degrees. */
static void camera(double dist, double elev, double azim, const double target[3])
{
    double e = elev * pi / 180, a = azim * pi / 180;
    double eye[3] = {dist * sin(e) * cos(a), dist * sin(e) * sin(a), dist * cos(e)}, f[3], up[3] = {-sin(a), cos(a), 0};
    double n = 0, s[3], u[3];
    for (int k = 0; k < 3; k++)
        f[k] = target[k] - eye[k], n += f[k] * f[k];
    for (int k = 0; k < 3; k++)
        f[k] /= sqrt(n);
    s[0] = f[1] * up[2] - f[2] * up[1], s[1] = f[2] * up[0] - f[0] * up[2], s[2] = f[0] * up[1] - f[1] * up[0];
    n = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int k = 0; k < 3; k++)
        s[k] /= n;
    u[0] = s[1] * f[2] - s[2] * f[1], u[1] = s[2] * f[0] - s[0] * f[2], u[2] = s[0] * f[1] - s[1] * f[0];
    double m[16] = {s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0, 0, 0, 0, 1};
    for (int r = 0; r < 3; r++)
        m[12 + r] = -(m[r] * eye[0] + m[4 + r] * eye[1] + m[8 + r] * eye[2]);
    double t = tan(25 * pi / 180) * 0.1;
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-t, t, -t, t, 0.1, 20);
    glMatrixMode(GL_MODELVIEW);
    glLoadMatrixd(m);
}

/* ---- the reference: the pixel's surface point on the quad's plane, weighed there ------------- */

typedef struct ref_quad {
    float p[4][3], c[4][4];
    double clip[4][4];
    qgl_plane pl;
    double c0[4], cu[4], cv[4]; /* clip positions of the frame's origin and of origin + each axis */
} ref_quad;

/* Clip position of p under the current matrices (mv then pr, both column-major). */
static void clip_of_point(const double mv[16], const double pr[16], const double p[3], double out[4])
{
    double e[4];
    for (int r = 0; r < 4; r++)
        e[r] = mv[r] * p[0] + mv[4 + r] * p[1] + mv[8 + r] * p[2] + mv[12 + r];
    for (int r = 0; r < 4; r++)
        out[r] = pr[r] * e[0] + pr[4 + r] * e[1] + pr[8 + r] * e[2] + pr[12 + r] * e[3];
}

static void ref_setup(ref_quad *q)
{
    double pos[4][3], mv[16], pr[16], p[3];
    th_clip_of((const float(*)[3])q->p, q->clip);
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            pos[i][k] = q->p[i][k];
    qgl_plane_frame(pos, &q->pl);
    glGetDoublev(GL_MODELVIEW_MATRIX, mv);
    glGetDoublev(GL_PROJECTION_MATRIX, pr);
    clip_of_point(mv, pr, q->pl.origin, q->c0);
    for (int a = 0; a < 2; a++) {
        for (int k = 0; k < 3; k++)
            p[k] = q->pl.origin[k] + q->pl.axis[a][k];
        clip_of_point(mv, pr, p, a ? q->cv : q->cu);
    }
}

/* The reference at the centre of pixel (x, y): 1 inside (colour and weights), 0 outside or not
 * in front of the eye between the near and far planes. The surface point c + a u + b v is the
 * one whose clip position projects to the pixel: two linear equations in (a, b). */
static int ref_at(const ref_quad *q, int x, int y, float out[4], double ab[2])
{
    double X = (x + 0.5) / W * 2 - 1, Y = (y + 0.5) / H * 2 - 1;
    const double *c0 = q->c0, *cu = q->cu, *cv = q->cv;
    const qgl_plane *pl = &q->pl;
    double A[2][3];
    for (int r = 0; r < 2; r++) {
        double s = r ? Y : X;
        A[r][0] = (cu[r] - c0[r]) - s * (cu[3] - c0[3]);
        A[r][1] = (cv[r] - c0[r]) - s * (cv[3] - c0[3]);
        A[r][2] = -(c0[r] - s * c0[3]);
    }
    double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
    if (det == 0)
        return 0;
    double a = (A[0][2] * A[1][1] - A[0][1] * A[1][2]) / det, b = (A[0][0] * A[1][2] - A[0][2] * A[1][0]) / det;
    double w = c0[3] + a * (cu[3] - c0[3]) + b * (cv[3] - c0[3]);
    double z = c0[2] + a * (cu[2] - c0[2]) + b * (cv[2] - c0[2]);
    double lam[4];
    if (!(w > 0) || fabs(z) > w || qgl_weights_inplane(pl, a, b, lam) != QGL_INSIDE)
        return 0;
    if (ab)
        ab[0] = a, ab[1] = b;
    for (int k = 0; k < 4; k++)
        out[k] = (float)(lam[0] * q->c[0][k] + lam[1] * q->c[1][k] + lam[2] * q->c[2][k] + lam[3] * q->c[3][k]);
    return 1;
}

static void draw_quad(const ref_quad *q, int rot)
{
    qglBegin(GL_QUADS);
    for (int k = 0; k < 4; k++) {
        int i = (k + rot) & 3;
        qglColor4fv(q->c[i]);
        qglVertex3fv(q->p[i]);
    }
    qglEnd();
}

/* ---- a float framebuffer for the drift ---------------------------------------------------- */

typedef struct float_fb {
    GLuint fbo, tex, depth;
} float_fb;

static int float_fb_bind(float_fb *f)
{
    PFNGLGENFRAMEBUFFERSPROC gen = (PFNGLGENFRAMEBUFFERSPROC)th_get_proc("glGenFramebuffers");
    PFNGLBINDFRAMEBUFFERPROC bind = (PFNGLBINDFRAMEBUFFERPROC)th_get_proc("glBindFramebuffer");
    PFNGLFRAMEBUFFERTEXTURE2DPROC attach = (PFNGLFRAMEBUFFERTEXTURE2DPROC)th_get_proc("glFramebufferTexture2D");
    PFNGLGENRENDERBUFFERSPROC genr = (PFNGLGENRENDERBUFFERSPROC)th_get_proc("glGenRenderbuffers");
    PFNGLBINDRENDERBUFFERPROC bindr = (PFNGLBINDRENDERBUFFERPROC)th_get_proc("glBindRenderbuffer");
    PFNGLRENDERBUFFERSTORAGEPROC store = (PFNGLRENDERBUFFERSTORAGEPROC)th_get_proc("glRenderbufferStorage");
    PFNGLFRAMEBUFFERRENDERBUFFERPROC attachr =
        (PFNGLFRAMEBUFFERRENDERBUFFERPROC)th_get_proc("glFramebufferRenderbuffer");
    PFNGLCHECKFRAMEBUFFERSTATUSPROC status = (PFNGLCHECKFRAMEBUFFERSTATUSPROC)th_get_proc("glCheckFramebufferStatus");
    if (!gen || !bind || !attach || !genr || !bindr || !store || !attachr || !status)
        return 0;
    glGenTextures(1, &f->tex);
    glBindTexture(GL_TEXTURE_2D, f->tex);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, W, H, 0, GL_RGBA, GL_FLOAT, NULL);
    glBindTexture(GL_TEXTURE_2D, 0);
    gen(1, &f->fbo);
    bind(GL_FRAMEBUFFER, f->fbo);
    attach(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, f->tex, 0);
    genr(1, &f->depth);
    bindr(GL_RENDERBUFFER, f->depth);
    store(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, W, H);
    attachr(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, f->depth);
    return status(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

static void float_fb_unbind(float_fb *f)
{
    PFNGLBINDFRAMEBUFFERPROC bind = (PFNGLBINDFRAMEBUFFERPROC)th_get_proc("glBindFramebuffer");
    bind(GL_FRAMEBUFFER, 0);
    glDeleteTextures(1, &f->tex);
}

/* ---- planar quads under random cameras ------------------------------------------------------ */

/* A 2D quad of a kind placed in a random plane through the origin. */
static void planar_quad(int kind, unsigned *seed, ref_quad *q)
{
    static const double shapes[4][4][2] = {
        {{-0.9, -0.7}, {0.8, -0.9}, {0.6, 0.7}, {-0.7, 0.8}},  /* convex */
        {{-0.9, -0.6}, {0.9, -0.6}, {0.3, 0.6}, {-0.3, 0.6}},  /* trapezoid */
        {{-0.8, -0.8}, {0.9, -0.5}, {0.0, -0.1}, {-0.6, 0.9}}, /* concave at corner 2 */
        {{-0.8, -0.8}, {0.8, 0.7}, {0.8, -0.7}, {-0.8, 0.8}},  /* bow-tie */
    };
    static const float colours[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
    double ax = (rnd(seed) - 0.5) * 1.2, ay = (rnd(seed) - 0.5) * 1.2;
    for (int i = 0; i < 4; i++) {
        double x = shapes[kind][i][0], y = shapes[kind][i][1];
        q->p[i][0] = (float)(x * cos(ay));
        q->p[i][1] = (float)(y * cos(ax));
        q->p[i][2] = (float)(x * sin(ay) + y * sin(ax));
        memcpy(q->c[i], colours[i], sizeof colours[i]);
    }
}

/* The floor of test_reference's behind-the-eye case, in the plane y = -0.6. */
static void floor_quad(ref_quad *q)
{
    static const float p[4][3] = {{-1.5f, -0.6f, -3}, {1.5f, -0.6f, -3}, {1.0f, -0.6f, 3.5f}, {-1.5f, -0.6f, 0}};
    static const float colours[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
    memcpy(q->p, p, sizeof p);
    memcpy(q->c, colours, sizeof colours);
}

typedef struct view_result {
    int inner, bad, outside;
    double worst; /* largest |value - reference| over inner pixels, in [0, 1] units */
} view_result;

/* Compare the framebuffer (8-bit, or float when pixels != NULL) with the reference. */
static void compare_view(const ref_quad *q, const float *pixels, const unsigned char *bytes, view_result *r)
{
    float(*ref)[4] = malloc(sizeof *ref * W * H);
    unsigned char *in = malloc(W * H);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            in[y * W + x] = (unsigned char)ref_at(q, x, y, ref[y * W + x], NULL);
    memset(r, 0, sizeof *r);
    for (int y = 1; y < H - 1; y++)
        for (int x = 1; x < W - 1; x++) {
            int all = 1, any = 0;
            for (int d = 0; d < 9; d++) {
                int i2 = in[(y + d / 3 - 1) * W + x + d % 3 - 1];
                all &= i2;
                any |= i2;
            }
            const float *pf = pixels ? pixels + 4 * (y * W + x) : NULL;
            const unsigned char *pb = bytes ? bytes + 4 * (y * W + x) : NULL;
            double v[3];
            for (int k = 0; k < 3; k++)
                v[k] = pf ? pf[k] : pb[k] / 255.0;
            int drawn = v[0] > 0 || v[1] > 0 || v[2] > 0;
            r->outside += drawn && !any;
            if (!all)
                continue;
            r->inner++;
            double e = 0;
            for (int k = 0; k < 3; k++)
                e = fmax(e, fabs(v[k] - ref[y * W + x][k]));
            r->worst = fmax(r->worst, e);
            r->bad += e > 2.0 / 255;
        }
    free(ref);
    free(in);
}

static unsigned char *render_bytes(th_ctx *t, const ref_quad *q, qgl_method m, int rot)
{
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    qgl_gl_set_method(t->qgl, m);
    draw_quad(q, rot);
    return th_snapshot(t);
}

static float *render_floats(th_ctx *t, const ref_quad *q, qgl_method m)
{
    float *px = malloc(sizeof(float) * 4 * W * H);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    qgl_gl_set_method(t->qgl, m);
    draw_quad(q, 0);
    glFinish();
    glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, px);
    return px;
}

/* One quad from nviews random views (the first head-on; none: the current matrices): the
 * 8-bit picture of MVC_PLANE against the reference and its rotations. */
static void views(th_ctx *t, ref_quad *q, const char *name, int nviews, unsigned *seed)
{
    static const double target[3] = {0, 0, 0};
    for (int v = 0; v < (nviews ? nviews : 1); v++) {
        double elev = v == 0 ? 0 : 80 * rnd(seed), azim = 360 * rnd(seed);
        if (nviews)
            camera(3.0, elev, azim, target);
        ref_setup(q);
        view_result r;
        unsigned char *img = render_bytes(t, q, QGL_METHOD_MVC_PLANE, 0);
        compare_view(q, NULL, img, &r);
        int worst_rot = 0;
        for (int rot = 1; rot < 4; rot++) {
            unsigned char *b = render_bytes(t, q, QGL_METHOD_MVC_PLANE, rot);
            int d = sc_diff(t, img, b, 1, NULL);
            worst_rot = d > worst_rot ? d : worst_rot;
            free(b);
        }
        printf("%-10s view %d (%4.1f deg): inner %6d worst %.2f/255 bad %d outside %d; rotation %d/255\n", name, v,
               elev, r.inner, r.worst * 255, r.bad, r.outside, worst_rot);
        th_check(r.inner > 300 && r.bad == 0 && r.outside == 0, "%s view %d: mismatches", name, v);
        th_check(worst_rot <= 1, "%s view %d: turning the corner order changes pixels by %d/255", name, v, worst_rot);
        if (r.bad || r.outside)
            th_write(t, img, name);
        free(img);
    }
}

static void planar_views(th_ctx *t)
{
    static const char *names[4] = {"convex", "trapezoid", "concave", "bow-tie"};
    unsigned seed = 15;
    for (int kind = 0; kind < 4; kind++) {
        ref_quad q;
        planar_quad(kind, &seed, &q);
        views(t, &q, names[kind], 5, &seed);
    }
    ref_quad f;
    floor_quad(&f);
    sc_camera(0, 0);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    views(t, &f, "behind eye", 0, &seed);
    /* a floor towards the horizon inside the view volume (not clipped: s_i / w without
     * perspective), its corners' w from 0.25 to 15 */
    static const float horizon[4][3] = {{-0.05f, -0.1f, -0.25f}, {0.05f, -0.1f, -0.25f}, {3, -0.1f, -15}, {-2, -0.1f, -15}};
    static const double target[3] = {0, 0, 0};
    memcpy(f.p, horizon, sizeof horizon);
    camera(3.0, 0, 0, target);
    glLoadIdentity();
    views(t, &f, "horizon", 0, &seed);
}

/* The view drift itself: the change, from view to view, of the value at fixed surface points.
 * Each inner pixel's surface point falls in a bin of the quad's plane (BINS x BINS over its
 * in-plane extent); per bin the lowest and highest deviation from the view-independent
 * reference seen over all views. The reference is subtracted so that a bin's own extent adds
 * only the deviation's variation across it (small: bins of under a pixel at head-on view). */
enum { BINS = 512 };

typedef struct drift_path {
    const char *name;
    int fallback;
    qgl_method method;
    double drift; /* largest over bins and channels of hi - lo, in [0, 1] units */
} drift_path;

static void drift_bin(const ref_quad *q, const float *px, float (*lo)[3], float (*hi)[3])
{
    /* a bow-tie's crossing point is a singularity of the weights: the subdivisions converge
     * there only in the limit (test_fallback skips it likewise) */
    qgl_cover cov;
    double cx = -100, cy = -100;
    if (qgl_classify_clip(q->clip, &cov) == QGL_QUAD_BOWTIE)
        cx = (cov.cross[0] + 1) * 0.5 * W, cy = (cov.cross[1] + 1) * 0.5 * H;
    double x0 = q->pl.corner[0][0], x1 = x0, y0 = q->pl.corner[0][1], y1 = y0;
    for (int i = 1; i < 4; i++) {
        x0 = fmin(x0, q->pl.corner[i][0]), x1 = fmax(x1, q->pl.corner[i][0]);
        y0 = fmin(y0, q->pl.corner[i][1]), y1 = fmax(y1, q->pl.corner[i][1]);
    }
    for (int y = 1; y < H - 1; y++)
        for (int x = 1; x < W - 1; x++) {
            float ref[4], nb[4];
            double ab[2];
            int all = ref_at(q, x, y, ref, ab);
            for (int d = 0; all && d < 9; d++)
                all = ref_at(q, x + d % 3 - 1, y + d / 3 - 1, nb, NULL);
            if (!all || hypot(x + 0.5 - cx, y + 0.5 - cy) < 6)
                continue;
            int bx = (int)((ab[0] - x0) / (x1 - x0) * BINS), by = (int)((ab[1] - y0) / (y1 - y0) * BINS);
            int b = (by < 0 ? 0 : by >= BINS ? BINS - 1 : by) * BINS + (bx < 0 ? 0 : bx >= BINS ? BINS - 1 : bx);
            for (int k = 0; k < 3; k++) {
                float dev = px[4 * (y * W + x) + k] - ref[k];
                lo[b][k] = fminf(lo[b][k], dev);
                hi[b][k] = fmaxf(hi[b][k], dev);
            }
        }
}

static void drift(th_ctx *t)
{
    float_fb fb;
    if (!float_fb_bind(&fb)) {
        printf("drift: no float framebuffer, skipped\n");
        return;
    }
    qgl_gl_desc fd = {.method = QGL_METHOD_MVC_PLANE, .force_fallback = 1, .get_proc = th_get_proc, .tolerance_px = 0.5f};
    qgl_context *cpu = qgl_gl_create(&fd);
    th_check(cpu != NULL, "no fallback context");
    /* the grid's size depends on the quad alone (its in-plane error bound), so a grid drifts
     * by float rounding; the fallback's size on the quad's size in pixels, so its picture
     * moves within its tolerance (0.5 px) of the view-invariant one */
    drift_path paths[] = {{"mvcplane", 0, QGL_METHOD_MVC_PLANE, 0}, {"grid", 0, QGL_METHOD_SUBDIV, 0},
                          {"fallback", 1, QGL_METHOD_MVC_PLANE, 0}, {"mvc", 0, QGL_METHOD_MVC, 0}};
    enum { NPATHS = sizeof paths / sizeof paths[0] };
    float(*lo)[3] = malloc(sizeof *lo * BINS * BINS), (*hi)[3] = malloc(sizeof *hi * BINS * BINS);
    static const double target[3] = {0, 0, 0};
    static const char *names[4] = {"convex", "trapezoid", "concave", "bow-tie"};
    unsigned seed = 64;
    double dev_plane = 0;
    for (int kind = 0; kind < 4; kind++) {
        ref_quad q;
        planar_quad(kind, &seed, &q);
        double elev[8], azim[8], dist[8];
        for (int v = 0; v < 8; v++)
            elev[v] = v == 0 ? 0 : 80 * rnd(&seed), azim[v] = 360 * rnd(&seed), dist[v] = 3 + 6 * (v & 1);
        printf("drift %-9s", names[kind]);
        for (int p = 0; p < NPATHS && cpu; p++) {
            int by_grid = 1;
            uint64_t grid_tris = 0;
            for (int b = 0; b < BINS * BINS; b++)
                for (int k = 0; k < 3; k++)
                    lo[b][k] = INFINITY, hi[b][k] = -INFINITY;
            qgl_gl_make_current(paths[p].fallback ? cpu : t->qgl);
            for (int v = 0; v < 8; v++) {
                camera(dist[v], elev[v], azim[v], target);
                ref_setup(&q);
                qgl_gl_stats_t st;
                qgl_gl_reset_stats(qgl_gl_current());
                float *px = render_floats(t, &q, paths[p].method);
                qgl_gl_stats(qgl_gl_current(), &st);
                /* SUBDIV leaves to the fallback the quads outside the grid's bound (concave,
                 * bow-tie): those count as the fallback's */
                int grid = st.subdiv == 1, cpu_drawn = st.fallback == 1;
                th_check(paths[p].fallback ? cpu_drawn : paths[p].method == QGL_METHOD_SUBDIV ? grid || cpu_drawn : st.mvc == 1,
                         "drift %s %s view %d: not drawn by its path", names[kind], paths[p].name, v);
                if (paths[p].method == QGL_METHOD_SUBDIV) {
                    by_grid &= grid;
                    th_check(v == 0 || st.subdiv_triangles == grid_tris, "drift %s: the grid changed with the view",
                             names[kind]);
                    grid_tris = st.subdiv_triangles;
                }
                drift_bin(&q, px, lo, hi);
                if (p == 0) {
                    view_result r;
                    compare_view(&q, px, NULL, &r);
                    dev_plane = fmax(dev_plane, r.worst);
                    th_check(r.inner > 0 && r.outside == 0, "drift %s view %d: %d inner pixels, %d outside",
                             names[kind], v, r.inner, r.outside);
                }
                free(px);
            }
            double d = 0;
            for (int b = 0; b < BINS * BINS; b++)
                for (int k = 0; k < 3; k++)
                    if (hi[b][k] >= lo[b][k])
                        d = fmax(d, hi[b][k] - lo[b][k]);
            drift_path *into = &paths[p];
            if (paths[p].method == QGL_METHOD_SUBDIV && !by_grid)
                into = &paths[2];
            into->drift = fmax(into->drift, d);
            printf(" %s %.3g", by_grid || paths[p].method != QGL_METHOD_SUBDIV ? paths[p].name : "grid(fallback)", d * 255);
        }
        printf(" levels\n");
    }
    qgl_gl_make_current(t->qgl);
    qgl_gl_destroy(cpu);
    free(lo);
    free(hi);
    float_fb_unbind(&fb);
    printf("view drift over 8 views of 4 planar quads (levels at fixed surface points):");
    for (int p = 0; p < NPATHS; p++)
        printf(" %s %.3g", paths[p].name, paths[p].drift * 255);
    printf("; mvcplane's largest deviation from the reference %.3g levels\n", dev_plane * 255);
    th_check(dev_plane < 0.25 / 255, "MVC_PLANE deviates from the view-independent reference by %g levels",
             dev_plane * 255);
    th_check(paths[0].drift < 0.5 / 255, "MVC_PLANE drifts by %g levels", paths[0].drift * 255);
    th_check(paths[1].drift < 0.5 / 255, "the grid drifts by %g levels", paths[1].drift * 255);
    /* the fallback's pattern lies within 0.5 px of the view-invariant one (test_fallback): with
     * these colours' gradients (<= 3 levels a pixel) a drift of up to 2 x 1.5 levels */
    th_check(paths[2].drift < 3.0 / 255, "the fallback drifts by %g levels", paths[2].drift * 255);
    th_check(paths[3].drift > 2.0 / 255, "MVC drifts by only %g levels: the comparison has no teeth",
             paths[3].drift * 255);
}

/* ---- linear precision against the driver --------------------------------------------------- */

static void oracle(th_ctx *t)
{
    unsigned seed = 7;
    static const double target[3] = {0, 0, 0};
    for (int kind = 0; kind < 2; kind++) {
        ref_quad q;
        planar_quad(kind, &seed, &q);
        for (int i = 0; i < 4; i++) { /* colours affine in object space */
            const float *p = q.p[i];
            float c[4] = {0.5f + 0.3f * p[0], 0.5f + 0.25f * p[1] - 0.1f * p[2], 0.4f + 0.2f * p[0] + 0.2f * p[2], 1};
            memcpy(q.c[i], c, sizeof c);
        }
        for (int v = 0; v < 4; v++) {
            camera(3.0, v == 0 ? 0 : 80 * rnd(&seed), 360 * rnd(&seed), target);
            glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            glBegin(GL_QUADS);
            for (int i = 0; i < 4; i++) {
                glColor4fv(q.c[i]);
                glVertex3fv(q.p[i]);
            }
            glEnd();
            unsigned char *native = th_snapshot(t);
            static const qgl_method methods[2] = {QGL_METHOD_MVC_PLANE, QGL_METHOD_SUBDIV};
            for (int m = 0; m < 2; m++) {
                unsigned char *ours = render_bytes(t, &q, methods[m], 0);
                int over, worst = sc_diff(t, ours, native, 2, &over);
                printf("oracle %d view %d %s: worst %d/255 against the driver's split, %d pixels over 2/255\n", kind, v,
                       m ? "subdiv" : "mvcplane", worst, over);
                th_check(over == 0, "oracle %d view %d: %d pixels differ from the driver's split", kind, v, over);
                free(ours);
            }
            free(native);
        }
    }
}

/* ---- non-planar quads: the patch form against the software mvcpatch ------------------------ */

static void patch_views(th_ctx *t)
{
    /* a gentle saddle, then one twisted so far that grazing rays meet it twice and the
     * nearer hit is the quadratic's other root; its patch then bulges out of the corners'
     * screen outline, which the GL path covers as the driver's split does (the software
     * reference draws the patch's whole projection): there only pixels both drew count */
    static const float saddles[2][4][3] = {{{-1, -1, -0.35f}, {1, -1, 0.3f}, {0.9f, 1, -0.3f}, {-1, 0.9f, 0.35f}},
                                           {{-1, -1, -1.2f}, {1, -1, 1.1f}, {0.9f, 1, -1.2f}, {-1, 0.9f, 1.1f}}};
    static const float colours[4][4] = {{1, 0, 0, 1}, {0, 0, 1, 1}, {0, 1, 0, 1}, {1, 0, 0, 1}};
    static const double target[3] = {0, 0, 0};
    unsigned seed = 21;
    ref_quad q;
    memcpy(q.c, colours, sizeof colours);
    qgl_sw_fb_desc fd = {.width = W, .height = H, .channels = 4, .with_count = 1};
    qgl_sw_fb *sw = qgl_sw_fb_create(&fd);
    glEnable(GL_DEPTH_TEST);
    for (int v = 0; v < 10; v++) {
        memcpy(q.p, saddles[v / 5], sizeof q.p);
        camera(3.2, v % 5 == 0 ? 0 : 70 * rnd(&seed), 360 * rnd(&seed), target);
        ref_setup(&q);
        float clip[16], attr[16], obj[12];
        for (int i = 0; i < 4; i++) {
            for (int k = 0; k < 4; k++) {
                clip[4 * i + k] = (float)q.clip[i][k];
                attr[4 * i + k] = q.c[i][k];
            }
            memcpy(obj + 3 * i, q.p[i], sizeof q.p[i]);
        }
        qgl_sw_draw_desc d = {.nquads = 1, .nattr = 4, .clip = clip, .attr = attr, .object = obj};
        qgl_sw_method_parse("mvcpatch", &d.method);
        qgl_sw_fb_clear(sw, NULL, 1.0f);
        qgl_sw_draw(sw, &d, NULL);
        qgl_gl_stats_t st;
        qgl_gl_reset_stats(t->qgl);
        unsigned char *img = render_bytes(t, &q, QGL_METHOD_MVC_PLANE, 0);
        qgl_gl_stats(t->qgl, &st);
        float *depth = malloc(sizeof(float) * W * H);
        glReadPixels(0, 0, W, H, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
        int inner = 0, bad = 0, bad_depth = 0, outside = 0;
        double worst = 0, worst_depth = 0;
        for (int y = 1; y < H - 1; y++)
            for (int x = 1; x < W - 1; x++) {
                int all = 1;
                for (int n = 0; n < 9; n++)
                    all &= sw->count[(y + n / 3 - 1) * W + x + n % 3 - 1] > 0;
                if (!all)
                    continue;
                if (v >= 5 && depth[y * W + x] == 1.0f) {
                    outside++;
                    continue;
                }
                inner++;
                const float *ref = sw->color + 4 * (y * W + x);
                double e = 0;
                for (int k = 0; k < 3; k++)
                    e = fmax(e, fabs(img[4 * (y * W + x) + k] / 255.0 - ref[k]));
                worst = fmax(worst, e);
                bad += e > 2.0 / 255;
                double ed = fabs(depth[y * W + x] - sw->depth[y * W + x]);
                worst_depth = fmax(worst_depth, ed);
                bad_depth += ed > 1e-4;
            }
        printf("patch view %d: inner %6d worst %.2f/255 depth %.2g, bad %d depth %d (shader path %llu, %d px of the "
               "patch outside the cover)\n",
               v, inner, worst * 255, worst_depth, bad, bad_depth, (unsigned long long)st.mvc, outside);
        th_check(inner > 2000 && bad == 0 && bad_depth == 0 && st.mvc == 1, "patch view %d: mismatches", v);
        int worst_rot = 0;
        for (int rot = 1; rot < 4; rot++) {
            unsigned char *b = render_bytes(t, &q, QGL_METHOD_MVC_PLANE, rot);
            int dr = sc_diff(t, img, b, 1, NULL);
            worst_rot = dr > worst_rot ? dr : worst_rot;
            free(b);
        }
        th_check(worst_rot <= 1, "patch view %d: turning the corner order changes pixels by %d/255", v, worst_rot);
        free(depth);
        free(img);
    }
    glDisable(GL_DEPTH_TEST);
    qgl_sw_fb_destroy(sw);
}

/* ---- meshes and shared edges ----------------------------------------------------------------- */

static void watertight(th_ctx *t)
{
    sc_mesh *m = malloc(sizeof *m);
    for (int persp = 0; persp < 2; persp++) {
        sc_jitter_grid(m, 12, 0.45f, persp ? 0.08f : 0, 11u, 0);
        sc_camera(persp ? -30 : -50, 15);
        qgl_gl_set_method(t->qgl, QGL_METHOD_MVC_PLANE);
        sc_coverage cv;
        sc_coverage_run(t, m, &cv);
        printf("watertight %s: covered %d, hit twice %d, differ from native %d\n", persp ? "non-planar" : "planar",
               cv.inside, cv.twice, cv.differ);
        th_check(cv.inside > 10000 && cv.twice == 0 && cv.differ == 0 && cv.st.mvc == cv.st.quads,
                 "watertight %d: coverage", persp);
        glDisable(GL_BLEND);
        free(cv.native);
        free(cv.ours);
    }
    free(m);
}

/* Colour on the shared edge x = 0 (eye and screen x = 0: the pixel column W / 2) at row y: the
 * edge's two corners interpolated at the point whose projection is the pixel centre. */
static void edge_reference(const float e0[3], const float e1[3], const float c0[4], const float c1[4], int y, float out[4])
{
    float p[4][3];
    memcpy(p[0], e0, sizeof p[0]);
    memcpy(p[1], e1, sizeof p[1]);
    memcpy(p[2], e1, sizeof p[2]);
    memcpy(p[3], e1, sizeof p[3]);
    double clip[4][4], Y = (y + 0.5) / H * 2 - 1;
    th_clip_of((const float(*)[3])p, clip);
    double f0 = clip[0][1] - Y * clip[0][3], f1 = clip[1][1] - Y * clip[1][3], s = f0 / (f0 - f1);
    for (int k = 0; k < 4; k++)
        out[k] = (float)((1 - s) * c0[k] + s * c1[k]);
}

static void shared_edge(th_ctx *t)
{
    static const float e0[3] = {0, -1, 0}, e1[3] = {0, 1, 0.5f}, ce0[4] = {1, 0.2f, 0, 1}, ce1[4] = {0, 0.3f, 1, 1};
    static const float dA[3] = {-1, 0, 0.3f}, dB[3] = {1, 0, -0.5f};
    ref_quad a, b;
    for (int k = 0; k < 3; k++) {
        a.p[0][k] = e0[k] + dA[k], a.p[1][k] = e0[k], a.p[2][k] = e1[k], a.p[3][k] = e1[k] + 0.8f * dA[k];
        b.p[0][k] = e0[k], b.p[1][k] = e0[k] + dB[k], b.p[2][k] = e1[k] + 0.7f * dB[k], b.p[3][k] = e1[k];
    }
    a.p[3][1] += 0.1f, b.p[2][1] -= 0.1f; /* still in each plane: along the edge's direction */
    a.p[3][2] += 0.025f, b.p[2][2] -= 0.025f;
    static const float ca[2][4] = {{0.9f, 0.9f, 0.1f, 1}, {0.2f, 1, 0.6f, 1}}, cb[2][4] = {{0.1f, 0.8f, 0.8f, 1}, {1, 1, 1, 1}};
    memcpy(a.c[0], ca[0], 16), memcpy(a.c[1], ce0, 16), memcpy(a.c[2], ce1, 16), memcpy(a.c[3], ca[1], 16);
    memcpy(b.c[0], ce0, 16), memcpy(b.c[1], cb[0], 16), memcpy(b.c[2], cb[1], 16), memcpy(b.c[3], ce1, 16);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-0.06, 0.06, -0.06, 0.06, 0.1, 20);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glTranslatef(0, 0, -2.4f);
    glRotatef(-35, 1, 0, 0);
    /* the edge's pixel centres belong to the quad whose inside lies towards +x: B */
    static const qgl_method methods[4] = {QGL_METHOD_MVC_PLANE, QGL_METHOD_MVC, QGL_METHOD_SPLIT, QGL_METHOD_SUBDIV};
    static const char *names[4] = {"mvcplane", "mvc", "split", "subdiv"};
    unsigned char *both = render_bytes(t, &a, QGL_METHOD_MVC_PLANE, 0);
    int taken = 0;
    for (int y = 0; y < H; y++)
        taken += both[4 * (y * W + W / 2)] != 0;
    th_check(taken == 0, "quad A drew %d pixels on the shared edge (tie rule)", taken);
    free(both);
    for (int m = 0; m < 4; m++) {
        unsigned char *img = render_bytes(t, &b, methods[m], 0);
        int on = 0, worst = 0;
        for (int y = 0; y < H; y++) {
            const unsigned char *px = img + 4 * (y * W + W / 2);
            if (!(px[0] || px[1] || px[2]))
                continue;
            float ref[4];
            edge_reference(e0, e1, ce0, ce1, y, ref);
            on++;
            for (int k = 0; k < 3; k++) {
                int d = abs(px[k] - (int)lround(ref[k] * 255));
                worst = d > worst ? d : worst;
            }
        }
        printf("shared edge, quad B by %-8s: %3d pixels on the edge, worst %d/255 from its interpolation\n", names[m],
               on, worst);
        th_check(on > 50, "quad B %s: only %d edge pixels", names[m], on);
        th_check(worst <= 1, "quad B %s: edge colour off by %d/255", names[m], worst);
        free(img);
    }
}

/* A quad with a corner at infinity (object w = 0) is still drawn (NDC stands in for the
 * object positions): the driver's split's pixels but for 1% (the far plane cuts the region
 * near that corner, each by its own depth). */
static void at_infinity(th_ctx *t)
{
    static const float p[4][4] = {{-0.8f, -0.6f, -2, 1}, {0.7f, -0.7f, -2.5f, 1}, {0.3f, 0.2f, -1, 0}, {-0.6f, 0.8f, -3, 1}};
    static const float c[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glFrustum(-0.1, 0.1, -0.1, 0.1, 0.1, 20);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    unsigned char *img[2];
    qgl_gl_stats_t st;
    for (int k = 0; k < 2; k++) {
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        qgl_gl_set_method(t->qgl, QGL_METHOD_MVC_PLANE);
        qgl_gl_reset_stats(t->qgl);
        if (k) {
            glBegin(GL_QUADS);
            for (int i = 0; i < 4; i++)
                glColor4fv(c[i]), glVertex4fv(p[i]);
            glEnd();
        } else {
            qglBegin(GL_QUADS);
            for (int i = 0; i < 4; i++)
                qglColor4fv(c[i]), qglVertex4fv(p[i]);
            qglEnd();
            qgl_gl_stats(t->qgl, &st);
        }
        img[k] = th_snapshot(t);
    }
    int ours = 0, differ = 0;
    for (int i = 0; i < W * H; i++) {
        int a = img[0][4 * i] || img[0][4 * i + 1] || img[0][4 * i + 2];
        int b = img[1][4 * i] || img[1][4 * i + 1] || img[1][4 * i + 2];
        ours += a;
        differ += a != b;
    }
    printf("corner at infinity: %d pixels drawn, %d differ in coverage from the driver's split\n", ours, differ);
    th_check(ours > 2000 && differ * 100 <= ours && st.mvc == 1, "corner at infinity: %d drawn, %d differ", ours,
             differ);
    free(img[0]);
    free(img[1]);
}

/* Every check on one context: the geometry shader path, or (max_glsl 120) the GLSL 1.20 one. */
static int run(int max_glsl)
{
    th_ctx t;
    qgl_gl_desc d = {.method = QGL_METHOD_MVC_PLANE, .max_glsl = max_glsl};
    int rc = th_init(&t, W, H, &d);
    if (rc)
        return rc;
    int want = max_glsl ? max_glsl : 150;
    if (qgl_gl_shader_level(t.qgl) != want) {
        th_free(&t);
        return 77;
    }
    printf("---- shader path %d\n", want);
    planar_views(&t);
    drift(&t);
    oracle(&t);
    patch_views(&t);
    watertight(&t);
    shared_edge(&t);
    at_infinity(&t);
    th_free(&t);
    return 0;
}

int main(void)
{
    int a = run(0), b = run(120);
    if (a == 77 && b == 77)
        return 77;
    return th_failures || (a && a != 77) || (b && b != 77) ? 1 : 0;
}
