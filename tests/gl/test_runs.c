/* test_runs: quads too small to differ from the split, between quads on the shader path, are
 * drawn with them (one draw, not one per run) in AUTO, and long runs of them still go to the
 * driver's split.
 *
 * 48 quad strips alternate a large quad with random corner colours (shader path) and a sliver
 * of 0.5 x 4 pixels (split, or free to join): AUTO must draw each strip in one draw with every quad on the shader path, and its
 * picture must equal method MVC_PLANE's exactly (the same program, AUTO's view-invariant
 * weights, over the same quads). A second
 * frame draws a strip of 100 slivers (0.25 x 8 pixels) followed by one large quad: the slivers are a run long
 * enough to be worth the driver's own draw, so AUTO splits them (2 draws), and its picture
 * equals the driver's quads there within 0 (the split is what the driver does) and method
 * MVC_PLANE on the large quad. A third draws four such runs, each followed by a large quad,
 * in one GL_QUADS primitive: in order that is 8 draws; with the depth test on (order cannot
 * show) the runs are grouped by path into 2, and the picture must not change.
 *
 * A fourth frame draws quads large enough to be judged (3 x 10 pixels) whose colours are
 * affine but for a tenth of a level at one corner, so the split passes only by the invisible-
 * split bound, in runs of 1 to 40 between quads of random colours (shader path), at the
 * start and end of a primitive and in a primitive with no shader-path quad at all. The
 * planner skips judging quads whose runs would be merged anyway; the counters must be those
 * of judging every quad and merging runs under 32 (computed here from the pattern), and the
 * picture within 1 level of MVC_PLANE's. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

static float hash(int i, int k)
{
    unsigned h = ((unsigned)i * 73856093u) ^ ((unsigned)k * 19349663u);
    return (float)((h * 2654435761u) >> 8 & 0xff) / 255.0f;
}

static void vertex(int i, float x, float y)
{
    qglColor3f(hash(i, 0), hash(i, 1), hash(i, 2));
    qglVertex2f(x, y);
}

/* Strip r: pairs at x = x0, x0 + big, x0 + big + sliver, ... (alternating widths). */
static void alternating(void)
{
    const float px = 2.0f / 256;
    for (int r = 0; r < 48; r++) {
        float y0 = -0.95f + r * 0.04f, y1 = y0 + 0.03f, x = -0.95f;
        qglBegin(GL_QUAD_STRIP);
        for (int i = 0; i < 12; i++) {
            vertex(100 * r + 2 * i, x, y0);
            vertex(100 * r + 2 * i + 1, x, y1);
            x += i % 2 ? 0.5f * px : 0.15f;
        }
        qglEnd();
    }
}

static void long_run(void)
{
    const float px = 2.0f / 256;
    qglBegin(GL_QUAD_STRIP);
    float x = -0.9f;
    for (int i = 0; i <= 101; i++) {
        vertex(2 * i, x, -4 * px);
        vertex(2 * i + 1, x, 4 * px);
        x += i < 100 ? 0.25f * px : 0.9f;
    }
    qglEnd();
}

/* Four long runs of slivers, each followed by a large quad, as GL_QUADS in one primitive. */
static void interleaved(void)
{
    const float px = 2.0f / 256;
    qglBegin(GL_QUADS);
    for (int r = 0; r < 4; r++) {
        float y0 = -0.9f + 0.45f * (float)r, x = -0.9f;
        for (int i = 0; i <= 40; i++) {
            float w = i < 40 ? 0.25f * px : 0.9f, h = i < 40 ? 8 * px : 0.3f;
            vertex(4 * (50 * r + i), x, y0);
            vertex(4 * (50 * r + i) + 1, x + w, y0);
            vertex(4 * (50 * r + i) + 2, x + w, y0 + h);
            vertex(4 * (50 * r + i) + 3, x, y0 + h + (i < 40 ? 0 : 0.1f));
            x += i < 40 ? 0.5f * px : 0;
        }
    }
    qglEnd();
}

/* The judged runs: each primitive a list of run lengths of invisible-split quads, a quad on
 * the shader path after each but the last (-1 ends a primitive). */
static const int judged_runs[] = {31, 1, 5, 30, 31, 32, 33, 40, 10, -1, 32, 31, -1, 20, -1};
#define JUDGED_PER_ROW 64

static void judged_quad(int n, int smooth)
{
    const float px = 2.0f / 256;
    float x0 = -0.95f + (float)(n % JUDGED_PER_ROW) * 3 * px, y0 = -0.95f + (float)(n / JUDGED_PER_ROW) * 12 * px;
    float xs[4] = {x0, x0 + 3 * px, x0 + 3 * px, x0}, ys[4] = {y0, y0, y0 + 10 * px, y0 + 10 * px};
    for (int c = 0; c < 4; c++) {
        if (smooth)
            qglColor3f(hash(n, 3 * c), hash(n, 3 * c + 1), hash(n, 3 * c + 2));
        else /* affine in the pixel position, a tenth of a level off at corner 2 */
            qglColor3f(0.2f + 0.3f * (xs[c] + 1), 0.6f - 0.2f * (ys[c] + 1), c == 2 ? 0.5004f : 0.5f);
        qglVertex2f(xs[c], ys[c]);
    }
}

static void judged(void)
{
    int n = 0;
    qglBegin(GL_QUADS);
    for (size_t r = 0; r < sizeof judged_runs / sizeof *judged_runs; r++) {
        if (judged_runs[r] < 0) {
            qglEnd();
            if (r + 1 < sizeof judged_runs / sizeof *judged_runs)
                qglBegin(GL_QUADS);
            continue;
        }
        for (int i = 0; i < judged_runs[r]; i++)
            judged_quad(n++, 0);
        if (judged_runs[r + 1] >= 0)
            judged_quad(n++, 1);
    }
}

/* What judging every quad and merging short runs gives: quads, split quads and draws. */
static void judged_expected(int *quads, int *split, int *draws)
{
    *quads = *split = *draws = 0;
    size_t r0 = 0;
    for (size_t r = 0; r < sizeof judged_runs / sizeof *judged_runs; r++) {
        if (judged_runs[r] >= 0)
            continue;
        int shader = (int)(r - r0) - 1, prev_smooth = 0; /* runs in [r0, r), one shader quad between each */
        *quads += shader;
        for (size_t k = r0; k < r; k++) {
            int n = judged_runs[k], kept = n >= 32 || shader == 0;
            *quads += n;
            *split += kept ? n : 0;
            *draws += kept && n > 0 ? 1 : 0;
            if (kept)
                prev_smooth = 0;
            if (k + 1 < r) { /* the shader quad after it, with the merged runs around it */
                *draws += !prev_smooth;
                prev_smooth = 1;
            }
        }
        r0 = r + 1;
    }
}

static unsigned char *frame(th_ctx *t, qgl_method m, void (*draw)(void), qgl_gl_stats_t *st)
{
    qgl_gl_set_method(t->qgl, m);
    qgl_gl_reset_stats(t->qgl);
    glClear(GL_COLOR_BUFFER_BIT);
    draw();
    qgl_gl_stats(t->qgl, st);
    return th_snapshot(t);
}

static int differ(const th_ctx *t, const unsigned char *a, const unsigned char *b, int x0, int x1)
{
    int n = 0;
    for (int y = 0; y < t->h; y++)
        for (int x = x0; x < x1; x++)
            n += memcmp(a + 4 * (y * t->w + x), b + 4 * (y * t->w + x), 3) != 0;
    return n;
}

int main(void)
{
    th_ctx t;
    int rc = th_init(&t, 256, 256, NULL);
    if (rc)
        return rc;
    if (!qgl_gl_shader_level(t.qgl))
        return 77;
    glClearColor(0, 0, 0, 0);
    qgl_gl_stats_t sa, sm, ss;
    unsigned char *a = frame(&t, QGL_METHOD_AUTO, alternating, &sa);
    unsigned char *m = frame(&t, QGL_METHOD_MVC_PLANE, alternating, &sm);
    int d = differ(&t, a, m, 0, t.w);
    printf("alternating: auto %llu quads in %llu draws (mvc %llu, split %llu); differs from MVC_PLANE in %d px\n",
           (unsigned long long)sa.quads, (unsigned long long)sa.draws, (unsigned long long)sa.mvc,
           (unsigned long long)sa.split, d);
    th_write(&t, a, "runs_alternating");
    th_check(sa.quads == 48 * 11 && sa.mvc == sa.quads && sa.draws == 48, "alternating: slivers not joined");
    th_check(d == 0, "alternating: AUTO differs from MVC_PLANE");
    free(a);
    free(m);

    a = frame(&t, QGL_METHOD_AUTO, long_run, &sa);
    m = frame(&t, QGL_METHOD_MVC_PLANE, long_run, &sm);
    unsigned char *s = frame(&t, QGL_METHOD_SPLIT, long_run, &ss);
    /* the slivers cover pixels 12.8 to 37.8, the large quad 37.8 to 153 */
    int ds = differ(&t, a, s, 0, 37), dm = differ(&t, a, m, 39, t.w);
    printf("long run: auto %llu quads in %llu draws (mvc %llu, split %llu); slivers differ from the split in %d px, "
           "the large quad from MVC_PLANE in %d px\n",
           (unsigned long long)sa.quads, (unsigned long long)sa.draws, (unsigned long long)sa.mvc,
           (unsigned long long)sa.split, ds, dm);
    th_write(&t, a, "runs_long");
    th_check(sa.quads == 101 && sa.split == 100 && sa.mvc == 1 && sa.draws == 2, "long run: counters");
    th_check(ds == 0 && dm == 0, "long run: picture");
    free(a);
    free(m);
    free(s);

    /* With the depth test on, drawing order cannot show: the split slivers are drawn in one
     * draw and the large quads in another, and the picture is the one drawn in order. */
    glClear(GL_DEPTH_BUFFER_BIT);
    a = frame(&t, QGL_METHOD_AUTO, interleaved, &sa);
    glEnable(GL_DEPTH_TEST);
    glClear(GL_DEPTH_BUFFER_BIT);
    m = frame(&t, QGL_METHOD_AUTO, interleaved, &sm);
    glDisable(GL_DEPTH_TEST);
    d = differ(&t, a, m, 0, t.w);
    printf("interleaved runs: in order %llu draws, depth-tested %llu draws (split %llu, mvc %llu); pictures differ in %d px\n",
           (unsigned long long)sa.draws, (unsigned long long)sm.draws, (unsigned long long)sm.split,
           (unsigned long long)sm.mvc, d);
    th_check(sa.draws == 8 && sm.draws == 2 && sm.split == 160 && sm.mvc == 4, "interleaved runs: draws");
    th_check(d == 0, "interleaved runs: grouping by path changed the picture");
    free(a);
    free(m);

    int eq, es, ed;
    judged_expected(&eq, &es, &ed);
    a = frame(&t, QGL_METHOD_AUTO, judged, &sa);
    m = frame(&t, QGL_METHOD_MVC_PLANE, judged, &sm);
    int worst = 0;
    for (int i = 0; i < 4 * t.w * t.h; i++) {
        int e = abs((int)a[i] - (int)m[i]);
        worst = e > worst ? e : worst;
    }
    printf("judged runs: auto %llu quads in %llu draws (mvc %llu, split %llu), expected %d in %d (split %d); "
           "largest difference from MVC_PLANE %d levels\n",
           (unsigned long long)sa.quads, (unsigned long long)sa.draws, (unsigned long long)sa.mvc,
           (unsigned long long)sa.split, eq, ed, es, worst);
    th_write(&t, a, "runs_judged");
    th_check(sa.quads == (unsigned long long)eq && sa.split == (unsigned long long)es &&
                 sa.draws == (unsigned long long)ed && sa.mvc == sa.quads - sa.split,
             "judged runs: counters");
    th_check(worst <= 1, "judged runs: picture");
    free(a);
    free(m);
    th_free(&t);
    return th_failures ? 1 : 0;
}
