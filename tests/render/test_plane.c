/* The view-invariant methods (mvcplane, mvcpatch, invbilinearplane) against independent
 * references, per pixel, under random cameras:
 *  - the weights themselves (attributes the unit vectors): mvcplane within 2e-6 of the
 *    core's double in-plane weights at each pixel's surface point (its ray's hit on the
 *    plane, solved in double), mvcpatch (double, but from float clip corners and into a float
 *    framebuffer) within 5e-7, on planar quads of every shape;
 *  - view drift: over 12 random cameras (0 to 80 degrees) no weight deviates from that
 *    view-independent reference by more than 1e-5 (twice that bounds the drift: 0.0026 of an
 *    8-bit level, 1/200 texel of a 512-texel texture), while mvc's weights deviate by more
 *    than 0.01 on the same quads;
 *  - linear precision: planar convex, trapezoid and concave quads (split02 splits the last
 *    through its reflex corner) with attributes affine in object space give split02's result
 *    within 1e-6 (invbilinearplane on the convex ones only);
 *  - rotation: turning the corner order by one place changes mvcplane on planar quads, and
 *    mvcpatch and mvcplane on Bailey's non-planar quad (whose split is the shorter diagonal,
 *    chosen from positions), by less than 1e-5. */
#include "render_test.h"

#define W 96

static unsigned seed = 15;

static double rnd(void)
{
    seed = seed * 1664525u + 1013904223u;
    return ((seed >> 8) & 0xffffff) / (double)0xffffff;
}

typedef struct quad3 {
    double p[4][3];
} quad3;

static const double shapes[4][4][2] = {
    {{-0.9, -0.7}, {0.8, -0.9}, {0.6, 0.7}, {-0.7, 0.8}},  /* convex */
    {{-0.9, -0.6}, {0.9, -0.6}, {0.3, 0.6}, {-0.3, 0.6}},  /* trapezoid */
    {{-0.8, -0.8}, {0.9, -0.5}, {0.0, -0.1}, {-0.6, 0.9}}, /* concave */
    {{-0.8, -0.8}, {0.8, 0.7}, {0.8, -0.7}, {-0.8, 0.8}},  /* bow-tie */
};

/* Shape k in a random plane through the origin. */
static void planar(int k, quad3 *q)
{
    double ax = (rnd() - 0.5) * 1.2, ay = (rnd() - 0.5) * 1.2;
    for (int i = 0; i < 4; i++) {
        double x = shapes[k][i][0], y = shapes[k][i][1];
        q->p[i][0] = x * cos(ay), q->p[i][1] = y * cos(ax), q->p[i][2] = x * sin(ay) + y * sin(ax);
    }
}

/* A random camera at distance 3, 0 to 80 degrees from the z axis, looking at the origin. */
static void random_camera(double m[16])
{
    double e = 80 * rnd() * 3.14159265358979323846 / 180, a = 2 * 3.14159265358979323846 * rnd();
    double eye[3] = {3 * sin(e) * cos(a), 3 * sin(e) * sin(a), 3 * cos(e)}, f[3], up[3] = {-sin(a), cos(a), 0}, s[3],
           u[3], n = 0;
    for (int k = 0; k < 3; k++)
        f[k] = -eye[k] / 3;
    s[0] = f[1] * up[2] - f[2] * up[1], s[1] = f[2] * up[0] - f[0] * up[2], s[2] = f[0] * up[1] - f[1] * up[0];
    n = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int k = 0; k < 3; k++)
        s[k] /= n;
    u[0] = s[1] * f[2] - s[2] * f[1], u[1] = s[2] * f[0] - s[0] * f[2], u[2] = s[0] * f[1] - s[1] * f[0];
    double view[16] = {s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0, 0, 0, 0, 1};
    for (int r = 0; r < 3; r++)
        view[12 + r] = -(view[r] * eye[0] + view[4 + r] * eye[1] + view[8 + r] * eye[2]);
    double proj[16];
    camera(50, 0, proj); /* the projection only: distance 0 */
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            m[4 * c + r] = 0;
            for (int j = 0; j < 4; j++)
                m[4 * c + r] += proj[4 * j + r] * view[4 * c + j];
        }
}

static void clip_of(const double m[16], const double p[3], double out[4])
{
    for (int r = 0; r < 4; r++)
        out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

/* Draw quad q (rotated by rot corners) with method under m; attributes attr[4][nattr]. */
static void draw(qgl_sw_fb *fb, const char *method, const double m[16], const quad3 *q, int rot, const float *attr,
                 int nattr)
{
    float clip[16], obj[12], a[4 * 4];
    for (int i = 0; i < 4; i++) {
        int s = (i + rot) & 3;
        double c[4];
        clip_of(m, q->p[s], c);
        for (int k = 0; k < 4; k++)
            clip[4 * i + k] = (float)c[k];
        for (int k = 0; k < 3; k++)
            obj[3 * i + k] = (float)q->p[s][k];
        for (int k = 0; k < nattr; k++)
            a[nattr * i + k] = attr[nattr * s + k];
    }
    qgl_sw_draw_desc d = {.nquads = 1, .nattr = nattr, .clip = clip, .attr = a, .object = obj,
                          .depth = QGL_SW_DEPTH_LESS};
    qgl_sw_method_parse(method, &d.method);
    qgl_sw_fb_clear(fb, NULL, 1.0f);
    qgl_sw_draw(fb, &d, NULL);
}

/* The in-plane weights of the surface point seen at the centre of pixel (x, y); 0 off the quad. */
static int reference(const double m[16], const quad3 *q, int x, int y, double lam[4])
{
    qgl_plane pl;
    qgl_plane_frame(q->p, &pl);
    double X = (x + 0.5) / W * 2 - 1, Y = (y + 0.5) / W * 2 - 1, c[3][4], p[3], A[2][3];
    clip_of(m, pl.origin, c[0]);
    for (int a = 0; a < 2; a++) {
        for (int k = 0; k < 3; k++)
            p[k] = pl.origin[k] + pl.axis[a][k];
        clip_of(m, p, c[1 + a]);
    }
    for (int r = 0; r < 2; r++) {
        double s = r ? Y : X;
        A[r][0] = (c[1][r] - c[0][r]) - s * (c[1][3] - c[0][3]);
        A[r][1] = (c[2][r] - c[0][r]) - s * (c[2][3] - c[0][3]);
        A[r][2] = -(c[0][r] - s * c[0][3]);
    }
    double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
    double a = (A[0][2] * A[1][1] - A[0][1] * A[1][2]) / det, b = (A[0][0] * A[1][2] - A[0][2] * A[1][0]) / det;
    return det != 0 && qgl_weights_inplane(&pl, a, b, lam) == QGL_INSIDE;
}

/* Largest |weight - reference| over the pixels whose 3 x 3 neighbourhood the method covers. */
static double against_reference(const qgl_sw_fb *fb, const double m[16], const quad3 *q, int *n)
{
    double worst = 0;
    *n = 0;
    for (int y = 1; y < W - 1; y++)
        for (int x = 1; x < W - 1; x++) {
            int all = 1;
            for (int d = 0; d < 9; d++)
                all &= fb->count[(y + d / 3 - 1) * W + x + d % 3 - 1] > 0;
            double lam[4];
            if (!all || !reference(m, q, x, y, lam))
                continue;
            (*n)++;
            for (int k = 0; k < 4; k++)
                worst = fmax(worst, fabs(fb->color[(y * W + x) * 4 + k] - lam[k]));
        }
    return worst;
}

static const float unit[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

static void weights_and_drift(void)
{
    static const char *names[4] = {"convex", "trapezoid", "concave", "bow-tie"};
    qgl_sw_fb *fb = test_fb(W, W, 4);
    for (int k = 0; k < 4; k++) {
        quad3 q;
        planar(k, &q);
        double worst_plane = 0, worst_patch = 0, worst_mvc = 0;
        int views = 0;
        for (int v = 0; v < 12; v++) {
            double m[16];
            int n;
            random_camera(m);
            draw(fb, "mvcplane", m, &q, 0, unit, 4);
            worst_plane = fmax(worst_plane, against_reference(fb, m, &q, &n));
            if (n < 20)
                continue;
            views++;
            draw(fb, "mvcpatch", m, &q, 0, unit, 4);
            worst_patch = fmax(worst_patch, against_reference(fb, m, &q, &n));
            draw(fb, "mvc", m, &q, 0, unit, 4);
            worst_mvc = fmax(worst_mvc, against_reference(fb, m, &q, &n));
        }
        printf("%-9s %2d views: largest weight deviation from the view-independent reference: mvcplane %.3g, "
               "mvcpatch %.3g, mvc %.3g\n",
               names[k], views, worst_plane, worst_patch, worst_mvc);
        CHECK(views >= 8, "%s: only %d views with pixels", names[k], views);
        CHECK(worst_plane < 2e-6, "%s: mvcplane deviates by %g", names[k], worst_plane);
        CHECK(worst_patch < 5e-7, "%s: mvcpatch deviates by %g", names[k], worst_patch);
        CHECK(worst_mvc > 0.01, "%s: mvc deviates by only %g: no teeth", names[k], worst_mvc);
    }
    qgl_sw_fb_destroy(fb);
}

static double max_diff(const qgl_sw_fb *a, const qgl_sw_fb *b, int nattr, int *common)
{
    double d = 0;
    *common = 0;
    for (int i = 0; i < a->width * a->height; i++) {
        if (!a->count[i] || !b->count[i])
            continue;
        (*common)++;
        for (int k = 0; k < nattr; k++)
            d = fmax(d, fabs((double)a->color[i * a->channels + k] - b->color[i * b->channels + k]));
    }
    return d;
}

static void linear_precision(void)
{
    static const char *names[3] = {"convex", "trapezoid", "concave"};
    qgl_sw_fb *ref = test_fb(W, W, 2), *fb = test_fb(W, W, 2);
    for (int k = 0; k < 3; k++) {
        quad3 q;
        planar(k, &q);
        float attr[8];
        for (int i = 0; i < 4; i++) {
            const double *p = q.p[i];
            attr[2 * i] = (float)(0.3 * p[0] + 0.2 * p[1] - 0.1 * p[2] + 0.5);
            attr[2 * i + 1] = (float)(-0.2 * p[0] + 0.45 * p[1] + 0.3 * p[2] + 0.25);
        }
        double m[16];
        random_camera(m);
        static const char *methods[3] = {"mvcplane", "mvcpatch", "invbilinearplane"};
        for (int j = 0; j < 3; j++) {
            if (j == 2 && k >= 2)
                continue; /* the inverse bilinear map folds on concave quads */
            int common;
            draw(ref, "split02", m, &q, 0, attr, 2);
            draw(fb, methods[j], m, &q, 0, attr, 2);
            double d = max_diff(fb, ref, 2, &common);
            printf("linear precision %-9s %-16s max |a - split02| = %.3g over %d pixels\n", names[k], methods[j], d,
                   common);
            CHECK(common > 200 && d < 1e-6, "shape %d %s differs from the split by %g", k, methods[j], d);
        }
    }
    qgl_sw_fb_destroy(ref);
    qgl_sw_fb_destroy(fb);
}

/* Corner order turned by one place: the same picture (the attributes turn with the corners). */
static void rotation(void)
{
    static const float colour[12] = {1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 1, 0};
    quad3 bailey = {{{-1, -1, 0.5}, {1, -1, 0}, {1, 1, 0.5}, {-1, 1, 0}}};
    qgl_sw_fb *a = test_fb(W, W, 3), *b = test_fb(W, W, 3);
    static const char *methods[2] = {"mvcplane", "mvcpatch"};
    for (int k = 0; k < 5; k++) {
        quad3 q = bailey;
        if (k < 4)
            planar(k, &q);
        double m[16];
        int covered = 0;
        for (int tries = 0; tries < 8 && covered < 1000; tries++) { /* a view where it is not edge-on */
            random_camera(m);
            draw(a, "split02", m, &q, 0, colour, 3);
            covered = 0;
            for (int i = 0; i < W * W; i++)
                covered += a->count[i] > 0;
        }
        for (int j = 0; j < 2; j++) {
            int common;
            draw(a, methods[j], m, &q, 0, colour, 3);
            draw(b, methods[j], m, &q, 1, colour, 3);
            double d = max_diff(a, b, 3, &common);
            printf("rotation %-8s %-8s max change %.3g over %d pixels\n", k < 4 ? "planar" : "bailey", methods[j], d,
                   common);
            CHECK(common > 200 && d < 1e-5, "quad %d %s changes by %g under rotation", k, methods[j], d);
        }
    }
    qgl_sw_fb_destroy(a);
    qgl_sw_fb_destroy(b);
}

int main(void)
{
    weights_and_drift();
    linear_precision();
    rotation();
    return failures ? 1 : 0;
}
