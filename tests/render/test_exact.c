/* The exact reference against analytic cases, and the behind-eye coverage.
 *  - A non-planar quad seen orthographically from above with a trapezoid footprint: the
 *    screen map is the footprint's bilinear map, whose inverse is closed-form (v from y,
 *    u from x along the row), so uv and depth are known per pixel; coverage is the
 *    trapezoid.
 *  - A planar parallelogram in perspective: each pixel's ray meets the plane at a point whose
 *    parallelogram coordinates are the attribute (affine interpolation), solved here by
 *    Cramer's rule independently of the renderer; the split must agree too.
 *  - A planar quad with one corner behind the eye: an independent homogeneous clipper (clip
 *    the polygon against w > 0 and the near plane in clip space, project, test pixel centres
 *    against the convex result) decides coverage; every method must cover the same pixels
 *    (centres within 1e-3 px of an edge are not judged), and facing must agree. */
#include "render_test.h"

#define W 64

static void ortho_trapezoid(void)
{
    /* footprint: (-0.8,-0.7) (0.8,-0.7) (0.4,0.7) (-0.4,0.7); heights make it non-planar */
    static const double fp[4][2] = {{-0.8, -0.7}, {0.8, -0.7}, {0.4, 0.7}, {-0.4, 0.7}};
    static const double z[4] = {0.3, -0.2, 0.4, -0.5};
    float clip[16], attr[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    for (int i = 0; i < 4; i++)
        clip_corner(clip + 4 * i, fp[i][0], fp[i][1], z[i], 1);
    qgl_sw_fb *fb = test_fb(W, W, 2);
    test_draw(fb, "exact", clip, attr, 2, 1, QGL_SW_DEPTH_ALWAYS, QGL_SW_CULL_NONE);
    double worst = 0, worst_z = 0;
    int wrong_cover = 0, n = 0;
    for (int y = 0; y < W; y++)
        for (int x = 0; x < W; x++) {
            double px = (x + 0.5) * 2 / W - 1, py = (y + 0.5) * 2 / W - 1;
            double v = (py + 0.7) / 1.4, half = 0.8 - 0.4 * v, u = (px / half + 1) / 2;
            int in = v > 1e-9 && v < 1 - 1e-9 && u > 1e-9 && u < 1 - 1e-9;
            int got = fb->count[y * W + x] > 0;
            int edge = fabs(v) < 1e-6 || fabs(v - 1) < 1e-6 || fabs(u) < 1e-6 || fabs(u - 1) < 1e-6;
            if (!edge && got != in)
                wrong_cover++;
            if (!got || !in)
                continue;
            n++;
            worst = fmax(worst, fabs(fb->color[(y * W + x) * 2] - u));
            worst = fmax(worst, fabs(fb->color[(y * W + x) * 2 + 1] - v));
            double zz = (1 - u) * (1 - v) * z[0] + u * (1 - v) * z[1] + u * v * z[2] + (1 - u) * v * z[3];
            worst_z = fmax(worst_z, fabs(fb->depth[y * W + x] - (0.5 * zz + 0.5)));
        }
    printf("exact ortho trapezoid: %d pixels, max uv error %.3g, max depth error %.3g, coverage errors %d\n", n,
           worst, worst_z, wrong_cover);
    CHECK(n > 1000 && worst < 1e-6 && worst_z < 1e-6 && wrong_cover == 0, "exact vs analytic trapezoid");
    qgl_sw_fb_destroy(fb);
}

static double det3(const double a[3], const double b[3], const double c[3])
{
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

static void perspective_parallelogram(void)
{
    /* P(s, t) = O + s E + t F in world space; camera at (0, 0, 3) looking down -z, fovy 50 */
    const double O[3] = {-0.9, -0.6, 0.4}, E[3] = {1.6, 0.3, -0.8}, F[3] = {0.2, 1.3, -0.3};
    double m[16], f = 1 / tan(25 * 3.14159265358979323846 / 180);
    camera(50, 3, m);
    float clip[16], attr[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    const double st[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; i++) {
        double p[3];
        for (int k = 0; k < 3; k++)
            p[k] = O[k] + st[i][0] * E[k] + st[i][1] * F[k];
        transform(m, p, clip + 4 * i);
    }
    qgl_sw_fb *fb = test_fb(W, W, 2), *sp = test_fb(W, W, 2);
    test_draw(fb, "exact", clip, attr, 2, 1, QGL_SW_DEPTH_LESS, QGL_SW_CULL_NONE);
    test_draw(sp, "split02", clip, attr, 2, 1, QGL_SW_DEPTH_LESS, QGL_SW_CULL_NONE);
    double worst = 0, worst_split = 0;
    int n = 0;
    for (int y = 0; y < W; y++)
        for (int x = 0; x < W; x++) {
            if (!fb->count[y * W + x])
                continue;
            /* ray from the eye through the pixel: eye + l (px/f, py/f, -1); solve
             * s E + t F - l d = eye - O by Cramer's rule (det3 of rows = det of columns) */
            double px = (x + 0.5) * 2 / W - 1, py = (y + 0.5) * 2 / W - 1;
            double d[3] = {px / f, py / f, -1}, rhs[3] = {0 - O[0], 0 - O[1], 3 - O[2]};
            double nd[3] = {-d[0], -d[1], -d[2]};
            double D = det3(E, F, nd);
            double sol_s = det3(rhs, F, nd) / D, sol_t = det3(E, rhs, nd) / D;
            worst = fmax(worst, fabs(fb->color[(y * W + x) * 2] - sol_s));
            worst = fmax(worst, fabs(fb->color[(y * W + x) * 2 + 1] - sol_t));
            if (sp->count[y * W + x])
                for (int k = 0; k < 2; k++)
                    worst_split = fmax(worst_split, fabs(fb->color[(y * W + x) * 2 + k] - sp->color[(y * W + x) * 2 + k]));
            n++;
        }
    printf("exact perspective parallelogram: %d pixels, max error vs ray-plane %.3g, vs split02 %.3g\n", n, worst,
           worst_split);
    CHECK(n > 500 && worst < 1e-6 && worst_split < 1e-6, "exact vs analytic parallelogram");
    qgl_sw_fb_destroy(fb);
    qgl_sw_fb_destroy(sp);
}

/* Sutherland-Hodgman against the clip-space plane a.x + b.y + c.z + d.w >= 0. */
static int clip_poly(double (*p)[4], int n, const double pl[4], double (*out)[4])
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const double *a = p[i], *b = p[(i + 1) % n];
        double da = pl[0] * a[0] + pl[1] * a[1] + pl[2] * a[2] + pl[3] * a[3];
        double db = pl[0] * b[0] + pl[1] * b[1] + pl[2] * b[2] + pl[3] * b[3];
        if (da >= 0)
            memcpy(out[m++], a, sizeof(double) * 4);
        if ((da >= 0) != (db >= 0)) {
            double t = da / (da - db);
            for (int k = 0; k < 4; k++)
                out[m][k] = a[k] + t * (b[k] - a[k]);
            m++;
        }
    }
    return m;
}

static void behind_eye(void)
{
    static const double P[4][3] = {{-1.5, -0.6, -3}, {1.5, -0.6, -3}, {1.0, -0.6, 3.5}, {-1.5, -0.6, 0}};
    double m[16];
    camera(60, 3, m); /* eye at z = 3: corner 2 (z = 3.5) is behind it */
    float clip[16], attr[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    double poly[12][4], tmp[12][4];
    for (int i = 0; i < 4; i++) {
        transform(m, P[i], clip + 4 * i);
        for (int k = 0; k < 4; k++)
            poly[i][k] = clip[4 * i + k];
    }
    CHECK(clip[11] < 0, "corner 2 should be behind the eye (w = %g)", clip[11]);
    const double near[4] = {0, 0, 1, 1}, far[4] = {0, 0, -1, 1};
    int n = clip_poly(poly, 4, near, tmp);
    n = clip_poly(tmp, n, far, poly);
    double v[12][2];
    for (int i = 0; i < n; i++) {
        v[i][0] = (poly[i][0] / poly[i][3] + 1) * W / 2;
        v[i][1] = (poly[i][1] / poly[i][3] + 1) * W / 2;
    }
    qgl_sw_fb *fb = test_fb(W, W, 2);
    for (int mth = 0; mth < N_ALL_METHODS; mth++) {
        const char *name = all_methods[mth];
        if (!strcmp(name, "invbilinear") || !strcmp(name, "projective"))
            continue; /* screen-space parametrizations: meaningless across the eye plane */
        test_draw(fb, name, clip, attr, 2, 1, QGL_SW_DEPTH_LESS, QGL_SW_CULL_NONE);
        int wrong = 0, inside = 0, facing_bad = 0;
        for (int y = 0; y < W; y++)
            for (int x = 0; x < W; x++) {
                double X = x + 0.5, Y = y + 0.5, mind = INFINITY;
                int pos = 0, neg = 0;
                for (int i = 0; i < n; i++) {
                    const double *a = v[i], *b = v[(i + 1) % n];
                    double cr = (b[0] - a[0]) * (Y - a[1]) - (b[1] - a[1]) * (X - a[0]);
                    double len = hypot(b[0] - a[0], b[1] - a[1]);
                    mind = fmin(mind, fabs(cr) / (len > 0 ? len : 1));
                    pos += cr > 0;
                    neg += cr < 0;
                }
                if (mind < 1e-3)
                    continue;
                int in = pos == n || neg == n;
                inside += in;
                wrong += in != (fb->count[y * W + x] > 0);
                if (in && fb->facing[y * W + x] != (pos == n ? 1 : -1))
                    facing_bad++;
            }
        printf("behind eye %-11s %d pixels inside the clipped polygon, %d disagree, %d wrong facing\n", name,
               inside, wrong, facing_bad);
        CHECK(inside > 500 && wrong == 0 && facing_bad == 0, "%s: behind-eye coverage differs from the clipper",
              name);
    }
    qgl_sw_fb_destroy(fb);
}

int main(void)
{
    ortho_trapezoid();
    perspective_parallelogram();
    behind_eye();
    return failures ? 1 : 0;
}
