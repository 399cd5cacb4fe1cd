/* test_batching: assume_exclusive gathers consecutive primitives into one draw, same picture.
 *
 * One frame mixes what batching must get right: quad strips (unrolled into quads), a GL_QUADS
 * primitive that gives no colour (it must use the colour current after the strip before it),
 * texture coordinates given by one primitive only (the others use the current ones), a
 * qgl_draw_quads batch, a colour set outside glBegin/glEnd between primitives (a forwarded
 * call: what waits must be drawn first), and a forwarded GL_TRIANGLES primitive. It is drawn
 * by a context that draws every primitive at once and by one with assume_exclusive followed
 * by qgl_gl_flush; smooth, the pictures must agree within 1/255 per channel (the unrolled
 * strips start at another corner: the same weights, other rounding) with identical coverage;
 * flat shaded, exactly (the provoking vertex must survive the unrolling). The batching
 * context must issue fewer draws, and leave the same current colour and texture coordinate.
 * Before that, qgl_draw_quads' conversion of its source types (see conversion()). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

static const float quad[4][3] = {{-0.95f, 0.55f, 0.1f}, {-0.2f, 0.6f, -0.1f}, {-0.25f, 0.95f, 0.1f}, {-0.9f, 0.9f, 0}};
static const float quad2[4][3] = {{0.3f, 0.6f, 0}, {0.95f, 0.55f, 0.1f}, {0.9f, 0.95f, -0.1f}, {0.2f, 0.9f, 0}};

static void frame(const sc_mesh *m)
{
    int per = 2 * (m->strip_cols + 1);
    for (int r = 0; r < m->strip_rows; r++) {
        qglBegin(GL_QUAD_STRIP);
        for (int i = 0; i < per; i++) {
            const int v = r * per + i;
            qglColor4fv(m->col[v]);
            if (r == 2)
                qglTexCoord2f(m->pos[v][0], m->pos[v][1]);
            qglVertex3fv(m->pos[v]);
        }
        qglEnd();
    }
    qglBegin(GL_QUADS); /* no colour: the last strip's last colour; texcoord: row 2's last */
    for (int i = 0; i < 4; i++)
        qglVertex3fv(quad[i]);
    qglEnd();
    static const float pos[8] = {-0.9f, -0.98f, -0.1f, -0.95f, -0.2f, -0.8f, -0.85f, -0.75f};
    static const unsigned char col[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 0, 255};
    qgl_quad_batch b = {.topology = QGL_QUADS, .count = 4};
    b.position = (qgl_attrib){pos, 2, GL_FLOAT, 0};
    b.color = (qgl_attrib){col, 4, GL_UNSIGNED_BYTE, 0};
    qgl_draw_quads(qgl_gl_current(), &b);
    qglColor3f(0.2f, 0.9f, 0.4f); /* forwarded: flushes */
    qglBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        if (i == 2)
            qglColor3f(0.9f, 0.1f, 0.8f);
        qglVertex3fv(quad2[i]);
    }
    qglEnd();
    qglBegin(GL_TRIANGLES); /* forwarded primitive: flushes */
    qglVertex3f(0.5f, -0.95f, 0);
    qglVertex3f(0.95f, -0.95f, 0);
    qglVertex3f(0.9f, -0.6f, 0);
    qglEnd();
    qglBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        qglColor3f(0.25f * i, 1 - 0.25f * i, 0.5f);
        qglVertex3f(quad2[i][0] - 0.6f, quad2[i][1] - 1.3f, quad2[i][2]);
    }
    qglEnd();
}

typedef struct run {
    unsigned char *img;
    qgl_gl_stats_t st;
    float col[4], tex[4];
} run;

static void draw(th_ctx *t, qgl_context *q, const sc_mesh *m, run *out)
{
    qgl_gl_make_current(q);
    glColor4f(1, 1, 1, 1);
    glMultiTexCoord4f(GL_TEXTURE0, 0.3f, 0.7f, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    qgl_gl_reset_stats(q);
    frame(m);
    qgl_gl_flush(q);
    qgl_gl_stats(q, &out->st);
    out->img = th_snapshot(t);
    glGetFloatv(GL_CURRENT_COLOR, out->col);
    glGetFloatv(GL_CURRENT_TEXTURE_COORDS, out->tex);
}

static void compare(th_ctx *t, qgl_context *direct, qgl_context *batched, const sc_mesh *m, const char *name, int tol)
{
    run a, b;
    draw(t, direct, m, &a);
    draw(t, batched, m, &b);
    int over, worst = sc_diff(t, a.img, b.img, tol, &over), covered = 0, cov_diff = 0;
    for (int i = 0; i < t->w * t->h; i++) {
        covered += a.img[4 * i + 3] != 0;
        cov_diff += (a.img[4 * i + 3] != 0) != (b.img[4 * i + 3] != 0);
    }
    int current = !memcmp(a.col, b.col, sizeof a.col) && !memcmp(a.tex, b.tex, sizeof a.tex);
    printf("%-7s covered %d, worst %d/255, %d pixels over %d, coverage differs %d; draws %llu direct, %llu batched "
           "(quads %llu / %llu); current attributes %s\n",
           name, covered, worst, over, tol, cov_diff, (unsigned long long)a.st.draws, (unsigned long long)b.st.draws,
           (unsigned long long)a.st.quads, (unsigned long long)b.st.quads, current ? "equal" : "DIFFER");
    char file[64];
    snprintf(file, sizeof file, "batching_%s", name);
    th_write(t, b.img, file);
    th_check(covered > 10000 && over == 0 && cov_diff == 0, "%s: batched picture differs", name);
    th_check(a.st.quads == b.st.quads && a.st.mvc == b.st.mvc && b.st.draws < a.st.draws, "%s: counters", name);
    th_check(current, "%s: current attributes differ", name);
    free(a.img);
    free(b.img);
}

/* qgl_draw_quads converts every source type alike: float xy with unsigned byte colours, and
 * the same quads as indexed, strided double xyz with float colours c / 255, must draw the
 * same pixels. */
static void conversion(th_ctx *t)
{
    static const float pos[8] = {-0.9f, -0.8f, 0.7f, -0.9f, 0.8f, 0.85f, -0.75f, 0.7f};
    static const unsigned char col[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 200, 200, 30};
    struct { double xyz[3]; float rgb[3]; } v[4];
    static const uint32_t idx[4] = {2, 0, 3, 1}; /* v holds corner k at slot idx[k] */
    for (int k = 0; k < 4; k++) {
        v[idx[k]].xyz[0] = pos[2 * k], v[idx[k]].xyz[1] = pos[2 * k + 1], v[idx[k]].xyz[2] = 0;
        for (int c = 0; c < 3; c++)
            v[idx[k]].rgb[c] = (float)col[3 * k + c] / 255.0f;
    }
    unsigned char *img[2];
    for (int pass = 0; pass < 2; pass++) {
        qgl_quad_batch b = {.topology = QGL_QUADS, .count = 4};
        if (pass == 0) {
            b.position = (qgl_attrib){pos, 2, GL_FLOAT, 0};
            b.color = (qgl_attrib){col, 3, GL_UNSIGNED_BYTE, 0};
        } else {
            b.indices = idx;
            b.position = (qgl_attrib){v[0].xyz, 3, GL_DOUBLE, (int)sizeof v[0]};
            b.color = (qgl_attrib){v[0].rgb, 3, GL_FLOAT, (int)sizeof v[0]};
        }
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        th_check(qgl_draw_quads(t->qgl, &b) == 1, "conversion pass %d: not drawn", pass);
        img[pass] = th_snapshot(t);
    }
    int covered = 0, differ = 0;
    for (int i = 0; i < t->w * t->h; i++) {
        covered += img[0][4 * i + 3] != 0;
        differ += memcmp(img[0] + 4 * i, img[1] + 4 * i, 4) != 0;
    }
    printf("convert covered %d, pixels differing %d\n", covered, differ);
    th_check(covered > 10000 && differ == 0, "float/ubyte and indexed double/float batches differ");
    free(img[0]);
    free(img[1]);
}

int main(void)
{
    th_ctx t;
    qgl_gl_desc d = {.method = QGL_METHOD_MVC};
    int rc = th_init(&t, 256, 256, &d);
    if (rc)
        return rc;
    if (!qgl_gl_shader_level(t.qgl))
        return 77;
    d.get_proc = th_get_proc;
    d.assume_exclusive = 1;
    qgl_context *batched = qgl_gl_create(&d);
    if (!batched)
        return 1;
    sc_mesh *m = malloc(sizeof *m);
    sc_jitter_grid(m, 8, 0.35f, 0.2f, 5u, 1);
    for (int i = 0; i < m->nverts; i++)
        m->pos[i][1] = m->pos[i][1] * 0.6f - 0.2f;
    conversion(&t);
    sc_camera(-25, 10);
    glEnable(GL_DEPTH_TEST);
    compare(&t, t.qgl, batched, m, "smooth", 1);
    glShadeModel(GL_FLAT);
    compare(&t, t.qgl, batched, m, "flat", 0);
    glShadeModel(GL_SMOOTH);
    qgl_gl_destroy(batched);
    qgl_gl_make_current(t.qgl);
    free(m);
    th_free(&t);
    return th_failures ? 1 : 0;
}
