/* test_retained: a retained batch draws what qgl_draw_quads draws, under every state.
 *
 * Two batches are retained once and drawn under a series of states (smooth and flat, unlit
 * and lit by a directional or a positional light, textured or not, polygon mode line): a
 * GL_QUADS batch with a non-affine colour quad and an affine one, and a strip shaped like
 * glxgears' inner cylinder (a normal and a colour per pair of vertices, so the corners
 * sharing them group along parallel edges). Under each state the retained draw must give the
 * pixels and the path counters of qgl_draw_quads on the same batch exactly: the cached facts
 * must plan every quad as the full test does. With a native drawing callback (the batch's
 * own glBegin/glEnd calls, as the preload library's display lists give), the callback must
 * run exactly when the state splits every quad (flat, unlit affine, lit by directional light
 * only, polygon mode line) and match the plain draw within 1/255. The strip lit smoothly by a
 * directional light is the new case of the planner: every quad goes to the split (no shader
 * draw), and the picture equals the driver's own quad strip (the oracle). Lit by a
 * positional light, whose result depends on the position, it must not. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"

#define W 64

static const float qpos[8][3] = {{-0.9f, -0.9f, 0}, {-0.1f, -0.8f, 0}, {-0.2f, -0.1f, 0}, {-0.8f, -0.3f, 0},
                                 {0.1f, -0.9f, 0},  {0.9f, -0.9f, 0},  {0.9f, -0.1f, 0},  {0.1f, -0.1f, 0}};
/* quad 0: no plane fits its colours; quad 1: colour affine in position (a parallelogram). */
static const float qcol[8][4] = {{1, 0, 0, 1},   {0, 1, 0, 1},     {0, 0, 1, 1},     {1, 1, 1, 1},
                                 {0.1f, 0.2f, 0.3f, 1}, {0.9f, 0.2f, 0.3f, 1}, {0.9f, 0.8f, 0.3f, 1},
                                 {0.1f, 0.8f, 0.3f, 1}};
static float qtex[8][2];
static float spos[6][3], snrm[6][3], scol[6][4];

static int calls;

static void emit(GLenum mode, int n, const float (*p)[3], const float (*c)[4], const float (*nr)[3],
                 const float (*t)[2])
{
    glBegin(mode);
    for (int i = 0; i < n; i++) {
        glColor4fv(c[i]);
        if (nr)
            glNormal3fv(nr[i]);
        if (t)
            glTexCoord2fv(t[i]);
        glVertex3fv(p[i]);
    }
    glEnd();
}

static void native_quads(void *user)
{
    (void)user;
    calls++;
    emit(GL_QUADS, 8, qpos, qcol, NULL, qtex);
}

static void native_strip(void *user)
{
    (void)user;
    calls++;
    emit(GL_QUAD_STRIP, 6, spos, scol, snrm, NULL);
}

static void make_data(void)
{
    for (int i = 0; i < 8; i++)
        qtex[i][0] = 0.5f * qpos[i][0] + 0.5f, qtex[i][1] = 0.5f * qpos[i][1] + 0.5f;
    for (int i = 0; i < 6; i++) {
        int k = i / 2;
        spos[i][0] = -0.8f + 0.5f * (float)k;
        spos[i][1] = i % 2 ? 0.9f : 0.2f;
        spos[i][2] = 0;
        snrm[i][0] = 0.6f * (float)k - 0.6f, snrm[i][1] = 0.1f * (float)k, snrm[i][2] = 1;
        scol[i][0] = 0.3f + 0.3f * (float)k, scol[i][1] = 0.9f - 0.2f * (float)k, scol[i][2] = 0.5f, scol[i][3] = 1;
    }
}

typedef struct state_case {
    const char *name;
    int flat, lit, positional, textured, line;
    int native_quads, native_strip; /* the callback must run (every quad split) */
} state_case;

static const state_case cases[] = {
    {"smooth", 0, 0, 0, 0, 0, 0, 1},
    {"flat", 1, 0, 0, 0, 0, 1, 1},
    {"lit smooth", 0, 1, 0, 0, 0, 0, 1},
    {"lit flat", 1, 1, 0, 0, 0, 1, 1},
    {"lit positional", 0, 1, 1, 0, 0, 0, 0},
    {"textured", 0, 0, 0, 1, 0, 0, 1},
    {"textured flat", 1, 0, 0, 1, 0, 1, 1},
    {"polygon line", 0, 0, 0, 0, 1, 1, 1},
};

static void set_state(const state_case *s, GLuint tex)
{
    static const float dir[4] = {0.3f, 0.4f, 1.0f, 0.0f}, point[4] = {0.2f, 0.1f, 0.6f, 1.0f};
    glShadeModel(s->flat ? GL_FLAT : GL_SMOOTH);
    if (s->lit) {
        glEnable(GL_LIGHTING);
        glEnable(GL_LIGHT0);
        glEnable(GL_COLOR_MATERIAL);
        glLightfv(GL_LIGHT0, GL_POSITION, s->positional ? point : dir);
    } else {
        glDisable(GL_LIGHTING);
        glDisable(GL_COLOR_MATERIAL);
    }
    if (s->textured) {
        glBindTexture(GL_TEXTURE_2D, tex);
        glEnable(GL_TEXTURE_2D);
    } else {
        glDisable(GL_TEXTURE_2D);
    }
    glPolygonMode(GL_FRONT_AND_BACK, s->line ? GL_LINE : GL_FILL);
}

static GLuint make_texture(void)
{
    unsigned char px[8 * 8 * 4];
    for (int i = 0; i < 64; i++) {
        int on = ((i % 8) / 2 + (i / 16)) % 2;
        px[4 * i] = on ? 255 : 40, px[4 * i + 1] = on ? 200 : 90, px[4 * i + 2] = 60, px[4 * i + 3] = 255;
    }
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 8, 8, 0, GL_RGBA, GL_UNSIGNED_BYTE, px);
    return t;
}

static int max_diff(const unsigned char *a, const unsigned char *b)
{
    int m = 0;
    for (int i = 0; i < W * W * 4; i++) {
        int d = abs(a[i] - b[i]);
        m = d > m ? d : m;
    }
    return m;
}

/* Draws with draw(), returns the picture and the counters' change. */
static unsigned char *shot(th_ctx *t, void (*draw)(th_ctx *, void *), void *arg, qgl_gl_stats_t *delta)
{
    qgl_gl_stats_t s0, s1;
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    qgl_gl_stats(t->qgl, &s0);
    draw(t, arg);
    qgl_gl_stats(t->qgl, &s1);
    delta->quads = s1.quads - s0.quads;
    delta->mvc = s1.mvc - s0.mvc;
    delta->split = s1.split - s0.split;
    delta->fallback = s1.fallback - s0.fallback;
    delta->passthrough = s1.passthrough - s0.passthrough;
    return th_snapshot(t);
}

static qgl_quad_batch quads_batch(void)
{
    qgl_quad_batch b = {.topology = QGL_QUADS, .count = 8};
    b.position = (qgl_attrib){qpos, 3, GL_FLOAT, 0};
    b.color = (qgl_attrib){qcol, 4, GL_FLOAT, 0};
    b.texcoord[0] = (qgl_attrib){qtex, 2, GL_FLOAT, 0};
    return b;
}

static qgl_quad_batch strip_batch(void)
{
    qgl_quad_batch b = {.topology = QGL_QUAD_STRIP, .count = 6};
    b.position = (qgl_attrib){spos, 3, GL_FLOAT, 0};
    b.color = (qgl_attrib){scol, 4, GL_FLOAT, 0};
    b.normal = (qgl_attrib){snrm, 3, GL_FLOAT, 0};
    return b;
}

static void draw_plain(th_ctx *t, void *arg)
{
    (void)arg;
    qgl_quad_batch a = quads_batch(), b = strip_batch();
    qgl_draw_quads(t->qgl, &a);
    qgl_draw_quads(t->qgl, &b);
}

static void draw_retained(th_ctx *t, void *arg)
{
    qgl_retained **r = arg;
    th_check(qgl_gl_draw_retained(t->qgl, r[0]) == 2 && qgl_gl_draw_retained(t->qgl, r[1]) == 2,
             "qgl_gl_draw_retained draws 2 quads per batch");
}

static void draw_retained_one(th_ctx *t, void *arg)
{
    qgl_gl_draw_retained(t->qgl, arg);
}

static int same_counts(const qgl_gl_stats_t *a, const qgl_gl_stats_t *b)
{
    return a->quads == b->quads && a->mvc == b->mvc && a->split == b->split && a->fallback == b->fallback &&
           a->passthrough == b->passthrough;
}

static void check_case(th_ctx *t, const state_case *s, GLuint tex, qgl_retained *plain[2], qgl_retained *native[2])
{
    qgl_gl_stats_t dp, dr, dn;
    set_state(s, tex);
    unsigned char *p = shot(t, draw_plain, NULL, &dp);
    unsigned char *r = shot(t, draw_retained, plain, &dr);
    int c0 = calls;
    unsigned char *n = shot(t, draw_retained, native, &dn);
    int ran = calls - c0;
    th_check(max_diff(p, r) == 0, "%s: retained picture differs from qgl_draw_quads (max %d)", s->name, max_diff(p, r));
    th_check(same_counts(&dp, &dr), "%s: retained paths (mvc %llu split %llu subdiv %llu pass %llu) differ from "
             "qgl_draw_quads' (mvc %llu split %llu subdiv %llu pass %llu)", s->name,
             (unsigned long long)dr.mvc, (unsigned long long)dr.split, (unsigned long long)dr.fallback,
             (unsigned long long)dr.passthrough, (unsigned long long)dp.mvc, (unsigned long long)dp.split,
             (unsigned long long)dp.fallback, (unsigned long long)dp.passthrough);
    th_check(same_counts(&dp, &dn), "%s: paths with a native callback differ", s->name);
    th_check(ran == s->native_quads + s->native_strip, "%s: native callback ran %d times, expected %d", s->name, ran,
             s->native_quads + s->native_strip);
    th_check(max_diff(p, n) <= 1, "%s: picture with the native callback differs by %d", s->name, max_diff(p, n));
    if (s->lit && !s->flat && !s->line)
        th_check(s->positional ? dp.mvc + dp.fallback == 4 : dp.mvc + dp.fallback == 2,
                 "%s: %llu quads on the smooth path; expected the quads batch's 2%s", s->name,
                 (unsigned long long)(dp.mvc + dp.fallback), s->positional ? " and the strip's 2" : " only");
    printf("%-15s mvc %llu split %llu subdiv %llu pass %llu, native callback %d\n", s->name,
           (unsigned long long)dp.mvc, (unsigned long long)dp.split, (unsigned long long)dp.fallback,
           (unsigned long long)dp.passthrough, ran);
    free(p);
    free(r);
    free(n);
}

/* The strip alone, lit smoothly by a directional light: through AUTO it must be the driver's
 * own quad strip, pixel for pixel (within 2/255). */
static void check_cylinder_oracle(th_ctx *t)
{
    static const state_case lit = {"lit smooth", 0, 1, 0, 0, 0, 0, 1};
    qgl_gl_stats_t d;
    set_state(&lit, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    native_strip(NULL);
    unsigned char *ref = th_snapshot(t);
    qgl_quad_batch b = strip_batch();
    qgl_retained *r = qgl_gl_retain(&b, NULL);
    unsigned char *ours = shot(t, draw_retained_one, r, &d);
    th_check(d.split == 2 && d.mvc == 0, "cylinder: both quads split (split %llu, mvc %llu)",
             (unsigned long long)d.split, (unsigned long long)d.mvc);
    th_check(max_diff(ref, ours) <= 2, "cylinder: differs from the driver's strip by %d", max_diff(ref, ours));
    size_t lit_px = 0;
    for (int i = 0; i < W * W; i++)
        lit_px += ref[4 * i] + ref[4 * i + 1] + ref[4 * i + 2] > 30;
    th_check(lit_px > 300, "cylinder: the strip is drawn (%zu pixels)", lit_px);
    qgl_gl_release(r);
    free(ref);
    free(ours);
}

int main(void)
{
    th_ctx t;
    int rc = th_init(&t, W, W, NULL);
    if (rc)
        return rc;
    if ((rc = th_need_geometry_shaders(&t)) != 0)
        return rc;
    make_data();
    GLuint tex = make_texture();
    qgl_quad_batch a = quads_batch(), b = strip_batch();
    qgl_retain_desc dq = {native_quads, NULL}, ds = {native_strip, NULL};
    qgl_retained *plain[2] = {qgl_gl_retain(&a, NULL), qgl_gl_retain(&b, NULL)};
    qgl_retained *native[2] = {qgl_gl_retain(&a, &dq), qgl_gl_retain(&b, &ds)};
    th_check(plain[0] && plain[1] && native[0] && native[1], "qgl_gl_retain succeeds");
    qgl_quad_batch bad = a;
    bad.position.size = 1;
    th_check(!qgl_gl_retain(&bad, NULL) && !qgl_gl_retain(NULL, NULL), "qgl_gl_retain refuses a bad batch");
    th_check(qgl_gl_draw_retained(NULL, plain[0]) < 0 && qgl_gl_draw_retained(t.qgl, NULL) < 0,
             "qgl_gl_draw_retained refuses NULL");
    if (plain[0] && plain[1] && native[0] && native[1]) {
        /* twice round: a batch drawn under one state, then another, then the first again */
        for (int round = 0; round < 2; round++)
            for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
                check_case(&t, &cases[i], tex, plain, native);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        glDisable(GL_TEXTURE_2D);
        check_cylinder_oracle(&t);
    }
    for (int i = 0; i < 2; i++) {
        qgl_gl_release(plain[i]);
        qgl_gl_release(native[i]);
    }
    qgl_gl_release(NULL);
    glDeleteTextures(1, &tex);
    th_free(&t);
    printf("%s\n", th_failures ? "FAIL" : "ok");
    return th_failures ? 1 : 0;
}
