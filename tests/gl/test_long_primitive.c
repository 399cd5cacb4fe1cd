/* test_long_primitive: one qglBegin/qglEnd with far more vertices than a capture chunk.
 *
 * The immediate API draws a long primitive in chunks as it arrives (so the driver works while
 * the application still sends vertices, and memory stays bounded); the picture must not show
 * where a chunk ended. Two primitives, each drawn natively and through quadgl in one frame of
 * additive blending (every pixel covered once shows the quad's colour, twice shows double):
 * a quad strip of 20 000 sub-pixel slices whose colour is first given at vertex 30 001 (the
 * vertices before use the colour current before qglBegin, as GL says; the chunks drawn
 * before the colour appears must too), and 40 000 GL_QUADS cells with hashed corner colours.
 * Method AUTO (these quads are too small to differ from the split) must equal the driver pixel
 * for pixel; method MVC (the shader path) the same coverage, and on the strip, whose colours
 * are affine in each slice, the same colours within 2/255 (the cells' hashed colours are not
 * affine: there mean value interpolation rightly differs from the split). Both must
 * count every quad, draw in several chunks, and leave the last colour given current. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

enum { SLICES = 20000, CELLS = 200 };

typedef struct api {
    void (*begin)(GLenum);
    void (*end)(void);
    void (*color)(GLfloat, GLfloat, GLfloat, GLfloat);
    void (*vertex)(GLfloat, GLfloat);
} api;

static void q_begin(GLenum m) { qglBegin(m); }
static void q_end(void) { qglEnd(); }
static void q_color(GLfloat r, GLfloat g, GLfloat b, GLfloat a) { qglColor4f(r, g, b, a); }
static void q_vertex(GLfloat x, GLfloat y) { qglVertex2f(x, y); }
static void n_begin(GLenum m) { glBegin(m); }
static void n_end(void) { glEnd(); }
static void n_color(GLfloat r, GLfloat g, GLfloat b, GLfloat a) { glColor4f(r, g, b, a); }
static void n_vertex(GLfloat x, GLfloat y) { glVertex2f(x, y); }

static const api ours = {q_begin, q_end, q_color, q_vertex}, native = {n_begin, n_end, n_color, n_vertex};

static float hash(int i, int j, int k)
{
    unsigned h = ((unsigned)i * 73856093u) ^ ((unsigned)j * 19349663u) ^ ((unsigned)k * 83492791u);
    return (float)((h * 2654435761u) >> 8 & 0xff) / 1024.0f; /* at most 1/4: sums stay unsaturated */
}

static void strip(const api *a)
{
    glColor4f(0.25f, 0, 0, 1);
    a->begin(GL_QUAD_STRIP);
    for (int i = 0; i <= SLICES; i++) {
        float x = -0.98f + 1.96f * (float)i / SLICES;
        for (int k = 0; k < 2; k++) {
            if (2 * i + k >= 30000)
                a->color(0, 0.25f, 0.002f * (float)(i % 50), 1);
            a->vertex(x, k ? 0.9f : 0.1f);
        }
    }
    a->end();
}

static void quads(const api *a)
{
    a->begin(GL_QUADS);
    for (int j = 0; j < CELLS; j++)
        for (int i = 0; i < CELLS; i++) {
            static const int dx[4] = {0, 1, 1, 0}, dy[4] = {0, 0, 1, 1};
            for (int c = 0; c < 4; c++) {
                a->color(hash(i + dx[c], j + dy[c], 0), hash(i + dx[c], j + dy[c], 1), 0.25f, 1);
                a->vertex(-0.98f + 1.96f * (float)(i + dx[c]) / CELLS, -0.9f + 0.9f * (float)(j + dy[c]) / CELLS);
            }
        }
    a->end();
}

static unsigned char *frame(th_ctx *t, const api *a, float last[4])
{
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    strip(a);
    quads(a);
    glDisable(GL_BLEND);
    glGetFloatv(GL_CURRENT_COLOR, last);
    return th_snapshot(t);
}

/* Colours compared on rows y0 and up (the strip is the upper half), coverage everywhere. */
static void run(th_ctx *t, qgl_method method, const char *name, int tol, int y0)
{
    float cn[4], cq[4];
    unsigned char *ref = frame(t, &native, cn);
    qgl_gl_set_method(t->qgl, method);
    qgl_gl_reset_stats(t->qgl);
    unsigned char *img = frame(t, &ours, cq);
    qgl_gl_stats_t st;
    qgl_gl_stats(t->qgl, &st);
    int over = 0, worst = 0, covered = 0, cov_diff = 0;
    for (int i = 0; i < t->w * t->h; i++) {
        int a = ref[4 * i] | ref[4 * i + 1] | ref[4 * i + 2], b = img[4 * i] | img[4 * i + 1] | img[4 * i + 2];
        covered += a != 0;
        cov_diff += (a != 0) != (b != 0);
        if (i / t->w < y0)
            continue;
        int e = 0;
        for (int k = 0; k < 3; k++)
            e = abs(ref[4 * i + k] - img[4 * i + k]) > e ? abs(ref[4 * i + k] - img[4 * i + k]) : e;
        worst = e > worst ? e : worst;
        over += e > tol;
    }
    printf("%-5s covered %d, worst %d/255, %d px over %d, coverage differs %d; quads %llu in %llu draws "
           "(mvc %llu, split %llu); current colour %s\n",
           name, covered, worst, over, tol, cov_diff, (unsigned long long)st.quads, (unsigned long long)st.draws,
           (unsigned long long)st.mvc, (unsigned long long)st.split, memcmp(cn, cq, sizeof cn) ? "DIFFERS" : "equal");
    char file[64];
    snprintf(file, sizeof file, "long_primitive_%s", name);
    th_write(t, img, file);
    th_check(covered > 30000 && over == 0 && cov_diff == 0, "%s: the picture differs from the driver's", name);
    th_check(st.quads == SLICES + CELLS * CELLS && st.draws >= 4, "%s: %llu quads in %llu draws", name,
             (unsigned long long)st.quads, (unsigned long long)st.draws);
    th_check(method != QGL_METHOD_MVC || st.mvc == st.quads, "%s: not every quad on the shader path", name);
    th_check(!memcmp(cn, cq, sizeof cn), "%s: current colour differs", name);
    free(ref);
    free(img);
}

int main(void)
{
    th_ctx t;
    int rc = th_init(&t, 256, 256, NULL);
    if (rc)
        return rc;
    glClearColor(0, 0, 0, 0);
    run(&t, QGL_METHOD_AUTO, "auto", 0, 0);
    if (qgl_gl_shader_level(t.qgl))
        run(&t, QGL_METHOD_MVC, "mvc", 2, t.h / 2);
    th_free(&t);
    return th_failures ? 1 : 0;
}
