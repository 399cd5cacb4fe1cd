/* Interpolation properties against independent references, per pixel:
 *  - linear precision: planar quads whose attributes are affine in object space give the
 *    split's result within 1e-6 for mvc, mvc64, exact, bilinear:N and adaptive (the
 *    projective map and Quilez's screen-space inverse do not, and are shown);
 *  - rotation: turning the corner order by one place changes mvc, mvc64, exact and
 *    bilinear:N (cells split around their centres) by less than 1e-5 on a non-planar quad,
 *    while each split changes (it becomes the other split);
 *  - mvc (float, spans) against qgl_weights (double) at every covered pixel, with the
 *    attributes set to the unit vectors so that the colour is the weight vector itself, also
 *    on a non-square image (weights in square pixels). */
#include "render_test.h"

#define W 64

static double max_diff(const qgl_sw_fb *a, const qgl_sw_fb *b, int nattr, int *common)
{
    double m = 0;
    *common = 0;
    for (int i = 0; i < a->width * a->height; i++) {
        if (!a->count[i] || !b->count[i])
            continue;
        (*common)++;
        for (int k = 0; k < nattr; k++)
            m = fmax(m, fabs((double)a->color[i * a->channels + k] - b->color[i * b->channels + k]));
    }
    return m;
}

/* Planar quads in the tilted plane z = 0.3 x - 0.2 y, attributes affine in position. */
static int planar_quads(float *clip, float *attr)
{
    static const double xy[3][4][2] = {
        {{-0.9, -0.8}, {0.7, -0.9}, {0.5, 0.6}, {-0.6, 0.8}},  /* general convex */
        {{-0.8, -0.5}, {0.8, -0.5}, {0.3, 0.5}, {-0.3, 0.5}},  /* trapezoid */
        {{-0.7, -0.7}, {0.2, -0.6}, {0.8, 0.7}, {-0.1, 0.6}},  /* parallelogram-ish */
    };
    double m[16];
    camera(50, 3, m);
    for (int q = 0; q < 3; q++)
        for (int i = 0; i < 4; i++) {
            double p[3] = {xy[q][i][0], xy[q][i][1], 0};
            p[2] = 0.3 * p[0] - 0.2 * p[1];
            transform(m, p, clip + (q * 4 + i) * 4);
            attr[(q * 4 + i) * 2] = (float)(0.3 * p[0] + 0.2 * p[1] - 0.1 * p[2] + 0.5);
            attr[(q * 4 + i) * 2 + 1] = (float)(-0.2 * p[0] + 0.45 * p[1] + 0.3 * p[2] + 0.25);
        }
    return 3;
}

static void linear_precision(void)
{
    static const char *exact_ones[] = {"split13", "mvc", "mvc64", "exact", "bilinear:4", "adaptive"};
    static const char *shown[] = {"invbilinear", "projective"};
    float clip[3 * 16], attr[3 * 8];
    int n = planar_quads(clip, attr);
    qgl_sw_fb *ref = test_fb(W, W, 2), *fb = test_fb(W, W, 2);
    for (int q = 0; q < n; q++) {
        test_draw(ref, "split02", clip + q * 16, attr + q * 8, 2, 1, QGL_SW_DEPTH_LESS, QGL_SW_CULL_NONE);
        for (size_t m = 0; m < sizeof exact_ones / sizeof *exact_ones; m++) {
            int common;
            test_draw(fb, exact_ones[m], clip + q * 16, attr + q * 8, 2, 1, QGL_SW_DEPTH_LESS, QGL_SW_CULL_NONE);
            double d = max_diff(fb, ref, 2, &common);
            printf("linear precision quad %d %-11s max |a - split02| = %.3g over %d pixels\n", q, exact_ones[m], d,
                   common);
            CHECK(common > 200, "quad %d %s: only %d common pixels", q, exact_ones[m], common);
            CHECK(d < 1e-6, "quad %d %s differs from split02 by %g", q, exact_ones[m], d);
        }
        for (size_t m = 0; m < sizeof shown / sizeof *shown; m++) {
            int common;
            test_draw(fb, shown[m], clip + q * 16, attr + q * 8, 2, 1, QGL_SW_DEPTH_LESS, QGL_SW_CULL_NONE);
            printf("linear precision quad %d %-11s max |a - split02| = %.3g (not linear-precise in general)\n", q, shown[m],
                   max_diff(fb, ref, 2, &common));
        }
    }
    qgl_sw_fb_destroy(ref);
    qgl_sw_fb_destroy(fb);
}

/* Bailey's non-planar quad, rotated by r corners. */
static void bailey(int r, float *clip, float *attr)
{
    static const double p[4][3] = {{-1, -1, 0.5}, {1, -1, 0}, {1, 1, 0.5}, {-1, 1, 0}};
    static const float col[4][3] = {{1, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
    double m[16];
    camera(60, 3, m);
    for (int i = 0; i < 4; i++) {
        int s = (i + r) % 4;
        transform(m, p[s], clip + 4 * i);
        memcpy(attr + 3 * i, col[s], sizeof col[s]);
    }
}

static void rotation(void)
{
    static const char *inv[] = {"mvc", "mvc64", "exact", "bilinear:8", "bilinear:32"};
    static const char *changing[] = {"split02", "split13"};
    float c0[16], a0[12], c1[16], a1[12];
    bailey(0, c0, a0);
    bailey(1, c1, a1);
    qgl_sw_fb *fa = test_fb(W, W, 3), *fb = test_fb(W, W, 3);
    int common;
    for (size_t m = 0; m < 5; m++) {
        test_draw(fa, inv[m], c0, a0, 3, 1, QGL_SW_DEPTH_LESS, QGL_SW_CULL_NONE);
        test_draw(fb, inv[m], c1, a1, 3, 1, QGL_SW_DEPTH_LESS, QGL_SW_CULL_NONE);
        double d = max_diff(fa, fb, 3, &common);
        printf("rotation %-11s max change %.3g over %d pixels\n", inv[m], d, common);
        CHECK(common > 1000 && d < 1e-5, "%s changes by %g under rotation", inv[m], d);
    }
    for (size_t m = 0; m < 2; m++) {
        test_draw(fa, changing[m], c0, a0, 3, 1, QGL_SW_DEPTH_LESS, QGL_SW_CULL_NONE);
        test_draw(fb, changing[m], c1, a1, 3, 1, QGL_SW_DEPTH_LESS, QGL_SW_CULL_NONE);
        double d = max_diff(fa, fb, 3, &common);
        printf("rotation %-11s max change %.3g (the other diagonal)\n", changing[m], d);
        CHECK(d > 0.1, "%s should change under rotation, changed by %g", changing[m], d);
    }
    qgl_sw_fb_destroy(fa);
    qgl_sw_fb_destroy(fb);
}

/* mvc's float weights against qgl_weights at every covered pixel of a W x h image, the
 * reference in isotropic pixel units (clip x, y times the half size; on a non-square image
 * NDC would squeeze the quad). */
static void against_weights(const char *what, const char *method, const float clip[16], double tol, int h)
{
    static const float unit[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    qgl_sw_fb *fb = test_fb(W, h, 4);
    test_draw(fb, method, clip, unit, 4, 1, QGL_SW_DEPTH_ALWAYS, QGL_SW_CULL_NONE);
    double cd[4][4], worst = 0;
    for (int i = 0; i < 16; i++)
        cd[i / 4][i % 4] = clip[i] * (i % 4 == 0 ? 0.5 * W : i % 4 == 1 ? 0.5 * h : 1);
    int n = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < W; x++) {
            if (!fb->count[y * W + x])
                continue;
            double persp[4];
            qgl_weights((const double(*)[4])cd, x + 0.5 - 0.5 * W, y + 0.5 - 0.5 * h, persp, NULL);
            for (int k = 0; k < 4; k++)
                worst = fmax(worst, fabs(fb->color[(y * W + x) * 4 + k] - persp[k]));
            n++;
        }
    printf("weights %-10s %-6s max |w - qgl_weights| = %.3g over %d pixels\n", what, method, worst, n);
    CHECK(n > 100, "%s: only %d pixels", what, n);
    CHECK(worst < tol, "%s %s: weights differ from qgl_weights by %g (tolerance %g)", what, method, worst, tol);
    qgl_sw_fb_destroy(fb);
}

/* mvc stores whole spans of plain fragments (no facing or count buffer, no callback) on a
 * fast path: its colour, depth and fragment count must equal the per-lane path's bit for bit. */
static void plain_store(const char *what, const float clip[16])
{
    static const float attr[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5f, 0.5f, 0};
    qgl_sw_fb_desc plain_desc = {.width = W, .height = W, .channels = 3};
    qgl_sw_fb *plain = qgl_sw_fb_create(&plain_desc), *lanes = test_fb(W, W, 3);
    qgl_sw_draw_desc d = {.nquads = 1, .nattr = 3, .clip = clip, .attr = attr};
    qgl_sw_method_parse("mvc", &d.method);
    qgl_sw_stats sp = {0}, sl = {0};
    qgl_sw_fb_clear(plain, NULL, 1.0f);
    qgl_sw_fb_clear(lanes, NULL, 1.0f);
    qgl_sw_draw(plain, &d, &sp);
    qgl_sw_draw(lanes, &d, &sl);
    size_t n = (size_t)W * W, diff = 0;
    for (size_t i = 0; i < n; i++) {
        diff += plain->depth[i] != lanes->depth[i];
        for (int k = 0; k < 3; k++)
            diff += plain->color[3 * i + k] != lanes->color[3 * i + k];
    }
    printf("plain store %-9s %lld fragments, %zu values differ from the per-lane path\n", what, sp.fragments, diff);
    CHECK(sp.fragments > 1000 && sp.fragments == sl.fragments && diff == 0, "%s: the span store differs", what);
    qgl_sw_fb_destroy(plain);
    qgl_sw_fb_destroy(lanes);
}

static void weights(void)
{
    float convex[16], concave[16], bowtie[16], collapsed[16], behind[16];
    double m[16];
    camera(60, 3, m);
    static const double pc[4][3] = {{-1, -1, 0.6}, {1, -0.8, -0.3}, {0.8, 1, 0.5}, {-0.9, 0.9, -0.4}};
    for (int i = 0; i < 4; i++)
        transform(m, pc[i], convex + 4 * i);
    const double cc[4][2] = {{-0.8, -0.8}, {0.8, -0.7}, {0.0, -0.1}, {-0.7, 0.8}};
    const double bt[4][2] = {{-0.8, -0.8}, {0.8, 0.7}, {0.8, -0.7}, {-0.8, 0.8}};
    const double cl[4][2] = {{-0.8, -0.8}, {0.8, -0.7}, {0.1, 0.8}, {0.1, 0.8}};
    for (int i = 0; i < 4; i++) {
        clip_corner(concave + 4 * i, cc[i][0], cc[i][1], 0, 1 + 0.2 * i);
        clip_corner(bowtie + 4 * i, bt[i][0], bt[i][1], 0, 1.5 - 0.2 * i);
        clip_corner(collapsed + 4 * i, cl[i][0], cl[i][1], 0, 1);
    }
    static const double pb[4][3] = {{-1.5, -0.6, -3}, {1.5, -0.6, -3}, {1.0, -0.6, 3.5}, {-1.5, -0.6, 0}};
    for (int i = 0; i < 4; i++)
        transform(m, pb[i], behind + 4 * i);
    /* float weights: a few float roundings of the weights (<= 1), plus the span's finite
     * differences, whose error grows with the span's size against rho near a corner */
    const double tol = 2e-6;
    against_weights("convex", "mvc", convex, tol, W);
    against_weights("concave", "mvc", concave, tol, W);
    against_weights("bowtie", "mvc", bowtie, tol, W);
    against_weights("collapsed", "mvc", collapsed, tol, W);
    against_weights("behind", "mvc", behind, tol, W);
    against_weights("convex", "mvc64", convex, 1e-6, W);
    against_weights("behind", "mvc64", behind, 1e-6, W);
    against_weights("wide", "mvc", convex, tol, W / 2);
    against_weights("wide", "mvc64", convex, 1e-6, W / 2);
    plain_store("convex", convex);
    plain_store("bow-tie", bowtie);
    plain_store("behind", behind);
}

int main(void)
{
    linear_precision();
    rotation();
    weights();
    return failures ? 1 : 0;
}
