/* test_glsl120: the GLSL 1.20 path (no geometry shader, cover computed on the CPU).
 *
 * Run twice. On the 4.5 context with max_glsl = 120 (the path streams from its own vertex
 * array object): the same picture as the geometry shader path (every channel within 2/255,
 * the same covered pixels except within 2 px of a bow-tie's crossing point, whose position
 * the two paths compute differently; window depth of a non-planar quad within 1e-5), the
 * driver as oracle for planar affine quads (2/255), watertightness, state restoration. On a
 * real GL 2.1 / GLSL 1.20 context (Mesa's version override, in a child process since Mesa
 * reads it once; immediate-mode submission): the core's double weights per pixel (2/255
 * on pixels whose 3 x 3 neighbourhood is inside), the oracle, watertightness, state
 * restoration including the generic attributes' current values. */
/* Before osmesa.h, whose GL/gl.h pulls in glext.h: declare the GL 2.0 entry points we call. */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "scenes.h"

static const float cols[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
static const float uvs[4][2] = {{0, 0}, {1.3f, 0.1f}, {1, 1}, {-0.2f, 0.8f}};

static const float convex[4][3] = {{-0.9f, -0.9f, 0}, {0.8f, -0.7f, 0}, {0.6f, 0.85f, 0}, {-0.7f, 0.3f, 0}};
static const float concave[4][3] = {{-0.8f, -0.9f, 0}, {0.9f, 0.0f, 0}, {-0.8f, 0.9f, 0}, {-0.1f, 0.0f, 0}};
static const float bowtie[4][3] = {{-0.9f, -0.8f, 0}, {0.9f, 0.85f, 0}, {0.85f, -0.9f, 0}, {-0.8f, 0.9f, 0}};
static const float bowtie2[4][3] = {{-0.9f, -0.8f, 0}, {0.85f, -0.9f, 0}, {-0.8f, 0.9f, 0}, {0.9f, 0.85f, 0}};
static const float saddle[4][3] = {{-1, -1, 0.5f}, {1, -0.8f, -0.5f}, {0.9f, 1, 0.5f}, {-1, 0.9f, -0.5f}};
static const float trapezoid[4][3] = {{-1.2f, -1, 0}, {1.2f, -1, 0}, {0.4f, 1, 0}, {-0.4f, 1, 0}};
/* a corner behind the eye (identity modelview, the frustum of ortho_or_frustum(1)) */
static const float behind[4][3] = {{-1.0f, 0.8f, -3.2f}, {1.2f, 0.9f, -3.35f}, {1.5f, -2.0f, 1.0f}, {-1.2f, -1.0f, -0.5f}};

static void draw_quad(const float p[4][3], int tex)
{
    qglBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        qglColor4fv(cols[i]);
        if (tex)
            qglTexCoord2fv(uvs[i]);
        qglVertex3fv(p[i]);
    }
    qglEnd();
}

/* 0: identity; 1: a frustum with identity modelview; 2: the oblique camera of sc_camera */
static void camera(int kind)
{
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    if (kind == 1)
        glFrustum(-0.5, 0.5, -0.5, 0.5, 1, 20);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    if (kind == 2)
        sc_camera(-40, 20);
}

static const struct shape {
    const char *name;
    const float (*p)[3];
    int cam, tex, bow;
} shapes[] = {
    {"convex", convex, 0, 0, 0},     {"concave", concave, 0, 0, 0}, {"bowtie", bowtie, 0, 0, 1},
    {"bowtie2", bowtie2, 0, 0, 1},   {"saddle", saddle, 2, 0, 0},   {"persp_tex", trapezoid, 2, 1, 0},
    {"behind_eye", behind, 1, 0, 0},
};
#define NSHAPES (int)(sizeof shapes / sizeof shapes[0])

/* ---- against the geometry shader path --------------------------------------------------------- */

static void snapshot(th_ctx *t, unsigned char **img, float **depth)
{
    *img = th_snapshot(t);
    *depth = malloc(sizeof(float) * t->w * t->h);
    glReadPixels(0, 0, t->w, t->h, GL_DEPTH_COMPONENT, GL_FLOAT, *depth);
}

static void same_as_gs(th_ctx *t, qgl_context *gs, qgl_context *g120, const struct shape *s)
{
    unsigned char *img[2];
    float *dep[2];
    camera(s->cam);
    if (s->tex)
        glEnable(GL_TEXTURE_2D);
    for (int k = 0; k < 2; k++) {
        qgl_gl_make_current(k ? g120 : gs);
        qgl_gl_reset_stats(qgl_gl_current());
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        draw_quad(s->p, s->tex);
        snapshot(t, &img[k], &dep[k]);
        qgl_gl_stats_t st;
        qgl_gl_stats(qgl_gl_current(), &st);
        th_check(st.mvc == 1, "%s: not on the shader path (level %d)", s->name, qgl_gl_shader_level(qgl_gl_current()));
    }
    glDisable(GL_TEXTURE_2D);
    double clip[4][4], cx = -100, cy = -100;
    qgl_cover cov;
    th_clip_of(s->p, clip);
    if (qgl_classify_clip(clip, &cov) == QGL_QUAD_BOWTIE)
        cx = (cov.cross[0] + 1) * 0.5 * t->w, cy = (cov.cross[1] + 1) * 0.5 * t->h;
    int covered = 0, cov_diff = 0, over = 0, worst = 0;
    double worst_depth = 0;
    for (int y = 0; y < t->h; y++)
        for (int x = 0; x < t->w; x++) {
            int i = y * t->w + x, on0 = img[0][4 * i + 3] != 0, on1 = img[1][4 * i + 3] != 0;
            int near_cross = hypot(x + 0.5 - cx, y + 0.5 - cy) < 2;
            covered += on0;
            cov_diff += on0 != on1 && !near_cross;
            if (!on0 || !on1)
                continue;
            for (int c = 0; c < 4; c++) {
                int d = abs(img[0][4 * i + c] - img[1][4 * i + c]);
                worst = d > worst ? d : worst;
                over += d > 2;
            }
            worst_depth = fmax(worst_depth, fabs(dep[0][i] - dep[1][i]));
        }
    printf("vs gs %-12s covered %6d, coverage differs %d, worst colour %d/255 (%d over 2), worst depth %.2g\n",
           s->name, covered, cov_diff, worst, over, worst_depth);
    char name[64];
    snprintf(name, sizeof name, "glsl120_%s", s->name);
    th_write(t, img[1], name);
    th_check(covered > 2000 && cov_diff == 0 && over == 0 && worst_depth <= 1e-5, "%s: differs from the GS path",
             s->name);
    for (int k = 0; k < 2; k++)
        free(img[k]), free(dep[k]);
}

/* ---- against the core's double weights (no geometry shader to compare with) ------------------- */

static void against_core(th_ctx *t, const struct shape *s)
{
    camera(s->cam);
    glEnable(GL_DEPTH_TEST);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    qgl_gl_reset_stats(t->qgl);
    draw_quad(s->p, 0);
    glFinish();
    glDisable(GL_DEPTH_TEST);
    qgl_gl_stats_t st;
    qgl_gl_stats(t->qgl, &st);
    th_check(st.mvc == 1 && st.quads == 1, "%s: not on the shader path", s->name);
    double clip[4][4];
    th_clip_of(s->p, clip);
    int inner = 0, bad = 0, stray = 0;
    double worst = 0;
    for (int y = 1; y < t->h - 1; y++)
        for (int x = 1; x < t->w - 1; x++) {
            int all_in = 1, any_in = 0;
            float ref[4];
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int in = th_ref_color(t, clip, cols, x + dx, y + dy, ref) == QGL_INSIDE;
                    all_in &= in, any_in |= in;
                }
            const unsigned char *px = th_px(t, x, y);
            stray += px[3] != 0 && !any_in;
            if (!all_in)
                continue;
            double lam[4], scr[4], z = 0;
            th_weights(t, clip, x, y, lam, scr);
            for (int i = 0; i < 4; i++)
                z += scr[i] * (clip[i][2] / clip[i][3] * 0.5 + 0.5);
            if (!(z > 0.001 && z < 0.999))
                continue; /* clipped by the near or far plane, as GL does */
            th_ref_color(t, clip, cols, x, y, ref);
            inner++;
            for (int k = 0; k < 3; k++) {
                double e = fabs(px[k] - ref[k] * 255.0);
                worst = fmax(worst, e);
                bad += e > 2.0 || px[3] == 0;
            }
        }
    printf("vs core %-10s inner %6d, worst %.2f/255, bad %d, stray %d\n", s->name, inner, worst, bad, stray);
    char name[64];
    snprintf(name, sizeof name, "glsl120_gl21_%s", s->name);
    th_write(t, NULL, name);
    th_check(inner > 1000 && bad == 0 && stray == 0, "%s: differs from the core's weights", s->name);
}

/* ---- the driver as oracle, and watertightness --------------------------------------------------- */

static void st_plain(void) {}
static void st_flat(void) { glShadeModel(GL_FLAT); }
static void st_modulate(void)
{
    sc_texture(1);
    glEnable(GL_TEXTURE_2D);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
}
static void st_replace_rgb(void)
{
    sc_texture(0);
    glEnable(GL_TEXTURE_2D);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
}
static void st_texmatrix(void)
{
    st_modulate();
    glMatrixMode(GL_TEXTURE);
    glRotatef(25, 0, 0, 1);
    glScalef(1.5f, 0.8f, 1);
    glMatrixMode(GL_MODELVIEW);
}

static const struct {
    const char *name;
    void (*setup)(void);
    int uv;
} states[] = {{"colour", st_plain, 0}, {"flat", st_flat, 0}, {"modulate", st_modulate, 1},
              {"replace_rgb", st_replace_rgb, 1}, {"texmatrix", st_texmatrix, 1}};

static void oracle(th_ctx *t, int si, int strips)
{
    sc_mesh *m = malloc(sizeof *m);
    sc_affine_grid(m, 4, strips);
    sc_camera(-50, 20);
    states[si].setup();
    glEnable(GL_DEPTH_TEST);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    sc_draw(m, 1, 1, states[si].uv);
    unsigned char *native = th_snapshot(t);
    qgl_gl_reset_stats(t->qgl);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    sc_draw(m, 0, 1, states[si].uv);
    unsigned char *ours = th_snapshot(t);
    qgl_gl_stats_t st;
    qgl_gl_stats(t->qgl, &st);
    int over, worst = sc_diff(t, native, ours, 2, &over);
    printf("oracle %-12s %-6s worst %d/255, %d pixels over 2, mvc %llu of %llu\n", states[si].name,
           strips ? "strip" : "quads", worst, over, (unsigned long long)st.mvc, (unsigned long long)st.quads);
    th_check(over == 0 && st.mvc == st.quads && st.quads == 16, "oracle %s %s", states[si].name,
             strips ? "strip" : "quads");
    glDisable(GL_TEXTURE_2D);
    glDisable(GL_DEPTH_TEST);
    glShadeModel(GL_SMOOTH);
    glMatrixMode(GL_TEXTURE);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    free(native);
    free(ours);
    free(m);
}

static void watertight(th_ctx *t, int strips, int persp)
{
    sc_mesh *m = malloc(sizeof *m);
    sc_jitter_grid(m, 12, 0.45f, persp ? 0.08f : 0, 7u + (unsigned)strips, strips);
    if (persp)
        sc_camera(-30, 15);
    else
        camera(0);
    sc_coverage cv;
    sc_coverage_run(t, m, &cv);
    unsigned char *native = cv.native, *ours = cv.ours;
    qgl_gl_stats_t st = cv.st;
    int twice = cv.twice, differ = cv.differ, inside = cv.inside;
    printf("watertight %-6s%-6s covered %d, twice %d, differ from native %d, mvc %llu of %llu\n",
           strips ? "strip" : "quads", persp ? " persp" : "", inside, twice, differ, (unsigned long long)st.mvc,
           (unsigned long long)st.quads);
    th_check(inside > 10000 && twice == 0 && differ == 0 && st.mvc == st.quads, "watertight %d %d", strips, persp);
    glDisable(GL_BLEND);
    glColor4f(1, 1, 1, 1);
    free(native);
    free(ours);
    free(m);
}

/* ---- state restoration -------------------------------------------------------------------------- */

typedef struct snap {
    GLint program, vao, abuf, active, client, varr, carr;
    float col[4], tex[4], gen[4];
    void *vptr;
} snap;

static void take(snap *s, int has_vao)
{
    memset(s, 0, sizeof *s);
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    if (has_vao)
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &s->abuf);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &s->active);
    glGetIntegerv(GL_CLIENT_ACTIVE_TEXTURE, &s->client);
    s->varr = glIsEnabled(GL_VERTEX_ARRAY);
    s->carr = glIsEnabled(GL_COLOR_ARRAY);
    glGetPointerv(GL_VERTEX_ARRAY_POINTER, &s->vptr);
    glGetFloatv(GL_CURRENT_COLOR, s->col);
    glGetVertexAttribfv(5, GL_CURRENT_VERTEX_ATTRIB, s->gen);
}

static void state(th_ctx *t, int has_vao)
{
    static float app_array[12];
    static const float gen[4] = {0.5f, 0.25f, 0.125f, 2};
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, app_array);
    glActiveTexture(GL_TEXTURE1);
    glClientActiveTexture(GL_TEXTURE1);
    glVertexAttrib4fv(5, gen);
    glColor4f(0.9f, 0.8f, 0.7f, 0.6f);
    camera(2);
    snap before, after;
    take(&before, has_vao);
    while (glGetError() != GL_NO_ERROR)
        ;
    qgl_gl_reset_stats(t->qgl);
    static const float last[4] = {0.25f, 0.5f, 0.75f, 1};
    qglBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        qglColor4fv(i == 3 ? last : cols[i]);
        qglVertex3fv(saddle[i]);
    }
    qglEnd();
    GLenum err = glGetError();
    take(&after, has_vao);
    qgl_gl_stats_t st;
    qgl_gl_stats(t->qgl, &st);
    int kept = before.program == after.program && before.vao == after.vao && before.abuf == after.abuf &&
               before.active == after.active && before.client == after.client && before.varr == after.varr &&
               before.carr == after.carr && before.vptr == after.vptr && !memcmp(before.gen, after.gen, sizeof gen);
    printf("state: bindings and generic attribute %s, error %#x, colour %s, mvc %llu\n", kept ? "kept" : "CHANGED",
           err, memcmp(after.col, last, sizeof last) ? "WRONG" : "last given", (unsigned long long)st.mvc);
    th_check(kept && err == GL_NO_ERROR && !memcmp(after.col, last, sizeof last) && st.mvc == 1, "state restoration");
    glDisableClientState(GL_VERTEX_ARRAY);
    glActiveTexture(GL_TEXTURE0);
    glClientActiveTexture(GL_TEXTURE0);
}

/* ---- the two runs --------------------------------------------------------------------------------- */

static void common(th_ctx *t, int has_vao)
{
    qgl_gl_make_current(t->qgl);
    for (size_t si = 0; si < sizeof states / sizeof states[0]; si++)
        for (int strips = 0; strips < 2; strips++)
            oracle(t, (int)si, strips);
    for (int persp = 0; persp < 2; persp++)
        for (int strips = 0; strips < 2; strips++)
            watertight(t, strips, persp);
    state(t, has_vao);
}

static int forced_run(void)
{
    th_ctx t;
    qgl_gl_desc d = {.method = QGL_METHOD_MVC, .max_glsl = 120};
    int rc = th_init(&t, 256, 256, &d);
    if (rc)
        return rc;
    qgl_gl_desc gd = {.method = QGL_METHOD_MVC, .get_proc = th_get_proc};
    qgl_context *gs = qgl_gl_create(&gd);
    printf("forced: shader level %d (geometry shader context: %d)\n", qgl_gl_shader_level(t.qgl),
           gs ? qgl_gl_shader_level(gs) : -1);
    if (!gs || qgl_gl_shader_level(t.qgl) != 120 || qgl_gl_shader_level(gs) != 150) {
        fprintf(stderr, "FAIL: could not create the two paths\n");
        return 1;
    }
    sc_texture(1);
    glClearColor(0, 0, 0, 0);
    glEnable(GL_DEPTH_TEST);
    for (int i = 0; i < NSHAPES; i++)
        same_as_gs(&t, gs, t.qgl, &shapes[i]);
    glDisable(GL_DEPTH_TEST);
    qgl_gl_make_current(t.qgl);
    qgl_gl_destroy(gs);
    common(&t, 1);
    th_free(&t);
    return th_failures ? 1 : 0;
}

/* A real GL 2.1 context: Mesa caps the version it reports and the GLSL it accepts. */
static int gl21_run(void)
{
    setenv("MESA_GL_VERSION_OVERRIDE", "2.1", 1);
    setenv("MESA_GLSL_VERSION_OVERRIDE", "120", 1);
    static const int attr[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE,
                               OSMESA_COMPAT_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 2,
                               OSMESA_CONTEXT_MINOR_VERSION, 1, 0};
    th_ctx t = {.w = 256, .h = 256};
    t.osmesa = OSMesaCreateContextAttribs(attr, NULL);
    t.buf = calloc((size_t)t.w * t.h, 4);
    if (!t.osmesa || !t.buf || !OSMesaMakeCurrent(t.osmesa, t.buf, GL_UNSIGNED_BYTE, t.w, t.h))
        return 77;
    const char *ver = (const char *)glGetString(GL_VERSION);
    qgl_gl_desc d = {.method = QGL_METHOD_MVC, .get_proc = th_get_proc};
    t.qgl = qgl_gl_create(&d);
    printf("GL 2.1 run: GL_VERSION %s, shader level %d\n", ver, t.qgl ? qgl_gl_shader_level(t.qgl) : -1);
    if (!ver || strncmp(ver, "2.1", 3) || !t.qgl)
        return 77; /* the override is not honoured by this Mesa */
    th_check(qgl_gl_shader_level(t.qgl) == 120, "GL 2.1: expected the GLSL 1.20 path");
    qgl_gl_make_current(t.qgl);
    th_viewport(&t, 0, 0, t.w, t.h);
    glClearColor(0, 0, 0, 0);
    for (int i = 0; i < NSHAPES; i++)
        if (!shapes[i].tex)
            against_core(&t, &shapes[i]);
    /* a wide viewport: weights in square pixels, as on the geometry shader path */
    th_viewport(&t, 0, 48, t.w, 160);
    against_core(&t, &shapes[0]);
    th_viewport(&t, 0, 0, t.w, t.h);
    common(&t, 0);
    th_free(&t);
    return th_failures ? 1 : 0;
}

int main(void)
{
    fflush(stdout);
    pid_t pid = fork(); /* before any GL: the child sets Mesa's override for its own process */
    if (pid == 0) {
        int rc = gl21_run();
        fflush(stdout);
        _exit(rc);
    }
    int status = 0;
    if (pid < 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status))
        return 1;
    int gl21 = WEXITSTATUS(status);
    int forced = forced_run();
    printf("forced run: %d, GL 2.1 run: %d\n", forced, gl21);
    if (forced == 1 || gl21 == 1)
        return 1;
    return forced == 77 && gl21 == 77 ? 77 : 0;
}
