/* demo_gl.c: GL state, textures, panels, text and read-back for the demo's pictures.
 *
 * A scene is drawn with its view matrix as the projection and an identity modelview, so the
 * driver transforms exactly as the software renderer does. Textured scenes upload the
 * scene's own texture (filter and repeat as the scene says); Phong scenes get a cube map
 * whose texel in direction n holds the scene's shading of the normal n, so looking it up
 * with the interpolated normal as texture coordinate is per-pixel Phong shading in plain
 * fixed-function GL (the cube map lookup normalizes the direction for free). Text is drawn
 * with glBitmap from demo_font.c's glyphs, scaled by building bigger bitmaps. */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "demo_gl.h"

#define CUBE_SIZE 128

void demo_gl_init(demo_gl *g, int nscenes, void *(*get_proc)(const char *name))
{
    memset(g, 0, sizeof *g);
    g->nscenes = nscenes;
    g->tex = calloc((size_t)nscenes, sizeof *g->tex);
    g->tex_target = calloc((size_t)nscenes, sizeof *g->tex_target);
#if DEMO_HAVE_QGL
    qgl_gl_desc d = {.get_proc = get_proc};
    g->qgl = qgl_gl_create(&d);
    if (!g->qgl)
        snprintf(g->qgl_error, sizeof g->qgl_error, "qgl_gl_create failed in this GL context");
#else
    (void)get_proc;
    snprintf(g->qgl_error, sizeof g->qgl_error, "built without the GL helper (libquadgl/gl)");
#endif
}

void demo_gl_fini(demo_gl *g)
{
    for (int i = 0; g->tex && i < g->nscenes; i++)
        if (g->tex[i])
            glDeleteTextures(1, &g->tex[i]);
#if DEMO_HAVE_QGL
    if (g->qgl)
        qgl_gl_destroy(g->qgl);
#endif
    free(g->tex);
    free(g->tex_target);
    memset(g, 0, sizeof *g);
}

/* ---- textures ----------------------------------------------------------------------------- */

static void upload_texture2d(const qgl_sw_texture *t, qgl_sw_filter filter)
{
    static const GLenum formats[5] = {0, GL_LUMINANCE, GL_LUMINANCE_ALPHA, GL_RGB, GL_RGBA};
    GLint f = filter == QGL_SW_FILTER_NEAREST ? GL_NEAREST : GL_LINEAR;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, t->width, t->height, 0, formats[t->channels], GL_FLOAT,
                 t->texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, f);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, f);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
}

/* Direction of texel (sc, tc) in [-1, 1]^2 of cube face f, as the GL spec's face table
 * maps directions to faces (+X, -X, +Y, -Y, +Z, -Z). */
static void cube_direction(int f, double sc, double tc, float d[3])
{
    double r[3];
    switch (f) {
    case 0: r[0] = 1, r[1] = -tc, r[2] = -sc; break;
    case 1: r[0] = -1, r[1] = -tc, r[2] = sc; break;
    case 2: r[0] = sc, r[1] = 1, r[2] = tc; break;
    case 3: r[0] = sc, r[1] = -1, r[2] = -tc; break;
    case 4: r[0] = sc, r[1] = -tc, r[2] = 1; break;
    default: r[0] = -sc, r[1] = -tc, r[2] = -1; break;
    }
    double n = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (int k = 0; k < 3; k++)
        d[k] = (float)(r[k] / n);
}

static void upload_phong_cube(const demo_scene *s)
{
    float *face = malloc((size_t)CUBE_SIZE * CUBE_SIZE * 3 * sizeof *face);
    if (!face)
        return;
    for (int f = 0; f < 6; f++) {
        for (int j = 0; j < CUBE_SIZE; j++)
            for (int i = 0; i < CUBE_SIZE; i++) {
                float n[3], c[4];
                cube_direction(f, 2.0 * (i + 0.5) / CUBE_SIZE - 1, 2.0 * (j + 0.5) / CUBE_SIZE - 1, n);
                demo_shade(s, 1, n, 1, c);
                memcpy(face + ((size_t)j * CUBE_SIZE + (size_t)i) * 3, c, 3 * sizeof *c);
            }
        glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)f, 0, GL_RGB8, CUBE_SIZE, CUBE_SIZE, 0, GL_RGB,
                     GL_FLOAT, face);
    }
    free(face);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
}

/* The scene's texture, created on first use; 0 when it has none. */
static GLenum scene_texture(demo_gl *g, const demo_scene_list *list, int si)
{
    const demo_scene *s = &list->items[si];
    if (!g->tex[si]) {
        GLenum target = s->sw->shading == QGL_SW_SHADE_PHONG ? GL_TEXTURE_CUBE_MAP
                        : s->sw->shading == QGL_SW_SHADE_TEXTURE && s->sw->texture.texels ? GL_TEXTURE_2D
                                                                                          : 0;
        if (!target)
            return 0;
        glGenTextures(1, &g->tex[si]);
        glBindTexture(target, g->tex[si]);
        if (target == GL_TEXTURE_2D)
            upload_texture2d(&s->sw->texture, s->sw->filter);
        else
            upload_phong_cube(s);
        g->tex_target[si] = target;
    }
    glBindTexture(g->tex_target[si], g->tex[si]);
    return g->tex_target[si];
}

/* ---- drawing ------------------------------------------------------------------------------ */

void demo_gl_panel(int x, int y, int w, int h)
{
    glViewport(x, y, w, h);
    glScissor(x, y, w, h);
    glEnable(GL_SCISSOR_TEST);
    glClearColor(demo_background[0], demo_background[1], demo_background[2], demo_background[3]);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

/* Texture and emit mode for the scene's shading. */
static demo_emit_mode setup_shading(demo_gl *g, const demo_scene_list *list, int si, const demo_view *v)
{
    GLenum target = v->shading ? scene_texture(g, list, si) : 0;
    if (!target)
        return DEMO_EMIT_COLOR;
    glEnable(target);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, target == GL_TEXTURE_2D ? GL_MODULATE : GL_REPLACE);
    if (target == GL_TEXTURE_CUBE_MAP)
        glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    glColor4f(1, 1, 1, 1);
    return target == GL_TEXTURE_2D ? DEMO_EMIT_TEX2 : DEMO_EMIT_TEX3;
}

static void line(const double *a, const double *b)
{
    glVertex3dv(a);
    glVertex3dv(b);
}

/* The diagonal Mesa splits a GL_QUADS quad along: 0-2, except when the clipper cuts the quad
 * at the near or far plane (a corner behind the eye), where it is 1-3 (measured against the
 * software renderer's two splits by the demo suite). Returns the first corner of it. */
static int native_diagonal(const qgl_sw_scene *sw, const int *quad, const double mvp[16])
{
    for (int k = 0; k < 4; k++) {
        const double *p = sw->pos + 3 * quad[k];
        double z = mvp[2] * p[0] + mvp[6] * p[1] + mvp[10] * p[2] + mvp[14];
        double w = mvp[3] * p[0] + mvp[7] * p[1] + mvp[11] * p[2] + mvp[15];
        if (!(w > 0) || z < -w || z > w)
            return 1;
    }
    return 0;
}

static void wire_done(void)
{
    glDepthRange(0.0, 1.0);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
}

/* Quad outlines on top of the picture; for the native method also the diagonal the driver
 * splits along, dotted. */
static void draw_wire(const demo_scene *s, const demo_view *v, const double mvp[16], int diagonal)
{
    const qgl_sw_scene *sw = s->sw;
    /* hidden edges stay hidden where the panel has the surface's depth (not the reference's
     * pixels, which carry none) */
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthRange(0.0, 0.9995); /* pull the lines in front of the surface they lie on */
    glColor3f(1.0f, 0.9f, 0.3f);
    glBegin(GL_LINES);
    for (int q = 0; q < sw->nquads; q++)
        for (int k = 0; k < 4; k++)
            line(sw->pos + 3 * sw->quad[q * 4 + k], sw->pos + 3 * sw->quad[q * 4 + (k + 1) % 4]);
    glEnd();
    if (!diagonal) {
        wire_done();
        return;
    }
    glEnable(GL_LINE_STIPPLE);
    glLineStipple(2, 0x5555);
    glColor3f(0.3f, 1.0f, 1.0f);
    glBegin(GL_LINES);
    for (int q = 0; q < sw->nquads; q++) {
        int a = (v->order + native_diagonal(sw, sw->quad + q * 4, mvp)) % 4;
        line(sw->pos + 3 * sw->quad[q * 4 + a], sw->pos + 3 * sw->quad[q * 4 + (a + 2) % 4]);
    }
    glEnd();
    glDisable(GL_LINE_STIPPLE);
    wire_done();
}

#if DEMO_HAVE_QGL
static qgl_method helper_method(demo_method m)
{
    return m == DEMO_MVC ? QGL_METHOD_MVC : m == DEMO_SUBDIV ? QGL_METHOD_SUBDIV : QGL_METHOD_AUTO;
}
#endif

/* plane: the GL helper with QGL_METHOD_MVC_PLANE instead of m's method. */
static int emit(demo_gl *g, const demo_scene *s, const demo_view *v, demo_method m, int plane, demo_emit_mode mode)
{
    if (m == DEMO_NATIVE) {
        demo_emit_native(s, v, mode);
        return 0;
    }
#if DEMO_HAVE_QGL
    if (g->qgl && m != DEMO_REFERENCE) {
        qgl_gl_make_current(g->qgl);
        qgl_gl_set_method(g->qgl, plane ? QGL_METHOD_MVC_PLANE : helper_method(m));
        demo_emit_qgl(s, v, mode);
        return 0;
    }
#else
    (void)g;
    (void)plane;
#endif
    return -1;
}

static int draw(demo_gl *g, const demo_scene_list *list, int si, const demo_view *v, demo_method m, int plane,
                int w, int h)
{
    const demo_scene *s = &list->items[si];
    double mvp[16];
    demo_view_mvp(s, v, w, h, mvp);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixd(mvp);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glShadeModel(GL_SMOOTH);
    glDisable(GL_LIGHTING);
    if (s->sw->cull_back) {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        glFrontFace(GL_CCW);
    }
    demo_emit_mode mode = setup_shading(g, list, si, v);
    int rc = emit(g, s, v, m, plane, mode);
    glDisable(GL_TEXTURE_2D);
    glDisable(GL_TEXTURE_CUBE_MAP);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    return rc;
}

int demo_gl_draw(demo_gl *g, const demo_scene_list *list, int si, const demo_view *v, demo_method m,
                 int w, int h)
{
    return draw(g, list, si, v, m, 0, w, h);
}

int demo_gl_draw_plane(demo_gl *g, const demo_scene_list *list, int si, const demo_view *v, int w, int h)
{
    return draw(g, list, si, v, DEMO_AUTO, 1, w, h);
}

void demo_gl_wire(const demo_scene_list *list, int si, const demo_view *v, demo_method m, int w, int h)
{
    const demo_scene *s = &list->items[si];
    double mvp[16];
    demo_view_mvp(s, v, w, h, mvp);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixd(mvp);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    draw_wire(s, v, mvp, m == DEMO_NATIVE);
}

void demo_gl_draw_rgba(int x, int y, int w, int h, const unsigned char *rgba)
{
    glDisable(GL_DEPTH_TEST);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glWindowPos2i(x, y);
    glDrawPixels(w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
}

/* ---- text --------------------------------------------------------------------------------- */

#define TEXT_SCALE 2

/* The glyph of c scaled up, as glBitmap wants it: bottom row first, each row padded to whole
 * bytes, most significant bit leftmost. */
static void glyph_bitmap(int c, unsigned char out[7 * TEXT_SCALE][2])
{
    const unsigned char *g = demo_glyph(c);
    memset(out, 0, 7 * TEXT_SCALE * 2);
    for (int r = 0; r < 7 * TEXT_SCALE; r++) {
        unsigned bits = g[6 - r / TEXT_SCALE];
        for (int col = 0; col < 5 * TEXT_SCALE; col++)
            if (bits & (0x10u >> (col / TEXT_SCALE)))
                out[r][col / 8] |= (unsigned char)(0x80u >> (col % 8));
    }
}

static void text_pass(int x, int y_top, const char *text, const unsigned char rgb[3])
{
    glColor3ub(rgb[0], rgb[1], rgb[2]);
    int line_y = y_top - 7 * TEXT_SCALE;
    glWindowPos2i(x, line_y);
    for (const char *c = text; *c; c++) {
        if (*c == '\n') {
            line_y -= DEMO_GLYPH_H * TEXT_SCALE;
            glWindowPos2i(x, line_y);
            continue;
        }
        unsigned char bm[7 * TEXT_SCALE][2];
        glyph_bitmap((unsigned char)*c, bm);
        glBitmap(5 * TEXT_SCALE, 7 * TEXT_SCALE, 0, 0, DEMO_GLYPH_W * TEXT_SCALE, 0, &bm[0][0]);
    }
}

void demo_gl_text(int x, int y_top, const char *text, const unsigned char rgb[3])
{
    static const unsigned char shadow[3] = {0, 0, 0};
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_TEXTURE_2D);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    text_pass(x + 1, y_top - 1, text, shadow);
    text_pass(x, y_top, text, rgb);
}

void demo_gl_read(int x, int y, int w, int h, unsigned char *rgba)
{
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(x, y, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
}
