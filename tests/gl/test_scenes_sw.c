/* test_scenes_sw: every scene of data/scenes through the GL path (MVC) against the software mvc picture.
 *
 * Each scene is loaded with the software renderer's loader and drawn twice with the scene's
 * own matrix, size, depth test and culling: by the software renderer's mvc method
 * (qgl_sw_draw) and by the GL path (qglBegin(GL_QUADS) with method MVC, the scene matrix as
 * the projection, identity modelview) on OSMesa into a float (RGBA32F) framebuffer object.
 * What is compared is the interpolation itself: both pictures show the attributes as colour,
 * mapped affinely into [0, 1] per scene (uv by the scene's range, normals as n / 2 + 1/2;
 * weights sum to 1, so the map commutes with the interpolation), read back as floats, and
 * the difference is converted back to the scene's own error unit (texels, or 8-bit levels).
 *
 * Tolerances. Interior pixels (covered in both pictures, centre farther than EDGE_BAND px
 * from every projected quad edge, so the two rasterizers agree on which quad owns them)
 * must match within ATTR_TOL units. Coverage may differ only on that edge band: the GL
 * rasterizer snaps vertices to a subpixel grid and breaks ties by its own rule, the software
 * one works in double with its own tie rule, and the bow-tie's crossing point is computed
 * on different sides; such pixels are counted and reported, never compared. For the
 * textured scenes the shaded pictures (scene texture, its filter; 8-bit on both sides) are
 * compared too: interior pixels within SHADE_TOL levels (GL filters an 8-bit texture with
 * fixed-point weights). Side-by-side pictures (GL | software | difference x 16) are written
 * as scene_<name>_attr.ppm and scene_<name>_shaded.ppm in the working directory. */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#ifdef QGL_HAVE_IMAGES
#include "qgl_image.h"
#endif

#define EDGE_BAND 1.0  /* pixels */
#define ATTR_TOL 0.01  /* scene units (texels or 8-bit levels) on interior pixels */
#define SHADE_TOL 2    /* 8-bit levels, shaded textured scenes, interior pixels */

typedef struct picture {
    int w, h;
    float *rgba;       /* w * h * 4, row 0 at the bottom */
    unsigned char *on; /* covered */
} picture;

/* The per-scene affine map of attribute k into [0, 1]: a' = (a - lo[k]) * scale[k]. */
typedef struct attr_map {
    float lo[3], scale[3];
} attr_map;

static attr_map make_map(const qgl_sw_scene *s)
{
    attr_map m;
    for (int k = 0; k < 3; k++) {
        m.lo[k] = 0, m.scale[k] = 1;
        if (k >= s->nattr)
            continue;
        if (s->shading == QGL_SW_SHADE_PHONG) {
            m.lo[k] = -1, m.scale[k] = 0.5f;
            continue;
        }
        float lo = INFINITY, hi = -INFINITY;
        for (int i = 0; i < s->nverts; i++) {
            float a = s->attr[i * s->nattr + k];
            lo = fminf(lo, a), hi = fmaxf(hi, a);
        }
        m.lo[k] = lo;
        m.scale[k] = hi > lo ? 1.0f / (hi - lo) : 1.0f;
    }
    return m;
}

static void mapped(const attr_map *m, const float *a, int nattr, float out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = k < nattr ? (a[k] - m->lo[k]) * m->scale[k] : 0;
}

static int picture_alloc(picture *p, int w, int h)
{
    p->w = w, p->h = h;
    p->rgba = calloc((size_t)w * h * 4, sizeof(float));
    p->on = calloc((size_t)w * h, 1);
    return p->rgba && p->on;
}

static void picture_free(picture *p)
{
    free(p->rgba);
    free(p->on);
}

/* ---- the software picture ---------------------------------------------------------------------- */

typedef struct sw_shader {
    const qgl_sw_scene *scene;
    const attr_map *map;
    int shaded;
} sw_shader;

static int sw_shade(void *user, const float *attr, int nattr, int facing, float *out)
{
    const sw_shader *s = user;
    if (s->shaded) {
        qgl_sw_scene_shade((void *)s->scene, attr, nattr, facing, out);
        for (int k = 0; k < 3; k++) /* as the 8-bit GL framebuffer stores it */
            out[k] = roundf(fminf(fmaxf(out[k], 0), 1) * 255.0f) / 255.0f;
    } else {
        mapped(s->map, attr, nattr, out);
    }
    out[3] = 1;
    return 1;
}

static int sw_picture(const qgl_sw_scene *s, const attr_map *map, int shaded, picture *out)
{
    float *clip = NULL, *attr = NULL, *object = NULL;
    int rc = qgl_sw_scene_arrays(s, 0, &clip, &attr, &object);
    qgl_sw_fb_desc fd = {.width = s->width, .height = s->height, .channels = 4};
    qgl_sw_fb *fb = rc < 0 ? NULL : qgl_sw_fb_create(&fd);
    if (fb) {
        sw_shader sh = {s, map, shaded};
        qgl_sw_draw_desc d = {.nquads = s->nquads, .nattr = s->nattr, .clip = clip, .attr = attr, .object = object,
                              .cull = s->cull_back ? QGL_SW_CULL_BACK : QGL_SW_CULL_NONE, .shade = sw_shade,
                              .user = &sh};
        d.method.method = QGL_SW_MVC;
        static const float clear[4] = {0, 0, 0, 0};
        qgl_sw_fb_clear(fb, clear, 1.0f);
        rc = qgl_sw_draw(fb, &d, NULL);
        for (int i = 0; rc >= 0 && i < s->width * s->height; i++) {
            memcpy(out->rgba + 4 * i, fb->color + 4 * i, 4 * sizeof(float));
            out->on[i] = fb->color[4 * i + 3] > 0;
        }
    }
    qgl_sw_fb_destroy(fb);
    free(clip);
    free(attr);
    free(object);
    return fb && rc >= 0;
}

/* ---- the GL picture ------------------------------------------------------------------------------- */

static GLuint upload_texture(const qgl_sw_texture *t, qgl_sw_filter filter)
{
    static const GLenum formats[5] = {0, GL_LUMINANCE, GL_LUMINANCE_ALPHA, GL_RGB, GL_RGBA};
    GLint f = filter == QGL_SW_FILTER_NEAREST ? GL_NEAREST : GL_LINEAR;
    GLuint id;
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_2D, id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, t->width, t->height, 0, formats[t->channels], GL_FLOAT, t->texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, f);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, f);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    return id;
}

/* A float colour buffer (attributes keep their precision) with depth, bound for drawing. */
static GLuint make_fbo(int w, int h, GLenum format, GLuint rb[2])
{
    GLuint fbo;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(2, rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
    glRenderbufferStorage(GL_RENDERBUFFER, format, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return 0;
    return fbo;
}

static void emit_quads(const qgl_sw_scene *s, const attr_map *map, int shaded)
{
    qglBegin(GL_QUADS);
    for (int q = 0; q < s->nquads; q++)
        for (int c = 0; c < 4; c++) {
            int i = s->quad[4 * q + c];
            const float *a = s->attr + i * s->nattr;
            if (shaded) {
                qglTexCoord2f(a[0], a[1]);
            } else {
                float m[3];
                mapped(map, a, s->nattr, m);
                qglColor4f(m[0], m[1], m[2], 1);
            }
            qglVertex3dv(s->pos + 3 * i);
        }
    qglEnd();
}

static int gl_picture(th_ctx *t, const qgl_sw_scene *s, const attr_map *map, int shaded, picture *out,
                      qgl_gl_stats_t *st)
{
    GLuint rb[2], tex = 0;
    GLuint fbo = make_fbo(s->width, s->height, shaded ? GL_RGBA8 : GL_RGBA32F, rb);
    if (!fbo)
        return 0;
    glViewport(0, 0, s->width, s->height);
    glMatrixMode(GL_PROJECTION);
    glLoadMatrixd(s->mvp);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glClearColor(0, 0, 0, 0);
    glClearDepth(1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    if (s->cull_back) {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        glFrontFace(GL_CCW);
    }
    if (shaded) {
        tex = upload_texture(&s->texture, s->filter);
        glEnable(GL_TEXTURE_2D);
        glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
        glColor4f(1, 1, 1, 1);
    }
    qgl_gl_reset_stats(t->qgl);
    emit_quads(s, map, shaded);
    qgl_gl_stats(t->qgl, st);
    glFinish();
    glReadPixels(0, 0, s->width, s->height, GL_RGBA, GL_FLOAT, out->rgba);
    for (int i = 0; i < s->width * s->height; i++)
        out->on[i] = out->rgba[4 * i + 3] > 0;
    glDisable(GL_TEXTURE_2D);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    if (tex)
        glDeleteTextures(1, &tex);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(2, rb);
    (void)t;
    return 1;
}

/* ---- the edge band: pixels within EDGE_BAND of a projected quad edge ----------------------------- */

static void clip_of(const qgl_sw_scene *s, int i, double c[4])
{
    const double *p = s->pos + 3 * i;
    for (int r = 0; r < 4; r++)
        c[r] = s->mvp[r] * p[0] + s->mvp[4 + r] * p[1] + s->mvp[8 + r] * p[2] + s->mvp[12 + r];
}

/* The part of segment ab in front of the eye (w >= eps), in window pixels; 0 if none. */
static int window_segment(const qgl_sw_scene *s, const double a[4], const double b[4], double out[4])
{
    const double eps = 1e-6;
    double ta = 0, tb = 1;
    if (a[3] < eps && b[3] < eps)
        return 0;
    if (a[3] < eps)
        ta = (eps - a[3]) / (b[3] - a[3]);
    if (b[3] < eps)
        tb = (eps - a[3]) / (b[3] - a[3]);
    for (int e = 0; e < 2; e++) {
        double t = e ? tb : ta, p[4];
        for (int k = 0; k < 4; k++)
            p[k] = a[k] + t * (b[k] - a[k]);
        out[2 * e] = (p[0] / p[3] + 1) * 0.5 * s->width;
        out[2 * e + 1] = (p[1] / p[3] + 1) * 0.5 * s->height;
    }
    return 1;
}

static double seg_dist(double px, double py, const double g[4])
{
    double dx = g[2] - g[0], dy = g[3] - g[1], l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((px - g[0]) * dx + (py - g[1]) * dy) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(px - (g[0] + t * dx), py - (g[1] + t * dy));
}

static void mark_segment(unsigned char *band, int w, int h, const double g[4])
{
    int x0 = (int)floor(fmax(fmin(g[0], g[2]) - EDGE_BAND - 1, 0)), x1 = (int)ceil(fmin(fmax(g[0], g[2]) + EDGE_BAND, w - 1));
    int y0 = (int)floor(fmax(fmin(g[1], g[3]) - EDGE_BAND - 1, 0)), y1 = (int)ceil(fmin(fmax(g[1], g[3]) + EDGE_BAND, h - 1));
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++)
            if (!band[y * w + x] && seg_dist(x + 0.5, y + 0.5, g) <= EDGE_BAND)
                band[y * w + x] = 1;
}

static unsigned char *edge_band(const qgl_sw_scene *s)
{
    unsigned char *band = calloc((size_t)s->width * s->height, 1);
    if (!band)
        return NULL;
    for (int q = 0; q < s->nquads; q++)
        for (int c = 0; c < 4; c++) {
            double a[4], b[4], g[4];
            clip_of(s, s->quad[4 * q + c], a);
            clip_of(s, s->quad[4 * q + (c + 1) % 4], b);
            if (window_segment(s, a, b, g))
                mark_segment(band, s->width, s->height, g);
        }
    return band;
}

/* ---- comparison ----------------------------------------------------------------------------------- */

typedef struct result {
    int interior, bad, cov_diff, cov_diff_off_band, covered;
    double worst, p99;
} result;

/* Difference of pixel i in scene units: attributes unmapped and scaled, or 8-bit levels. */
static double pixel_error(const qgl_sw_scene *s, const attr_map *map, int shaded, const float *a, const float *b)
{
    double e = 0;
    int n = shaded ? 3 : s->nattr;
    for (int k = 0; k < n; k++) {
        double d = fabs((double)a[k] - b[k]);
        d = shaded ? d * 255.0 : d / map->scale[k] * s->unit_scale;
        e = fmax(e, d);
    }
    return e;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static result compare(const qgl_sw_scene *s, const attr_map *map, int shaded, const picture *gl, const picture *sw,
                      const unsigned char *band, double tol)
{
    result r = {0};
    int n = s->width * s->height;
    double *errs = malloc(sizeof(double) * (size_t)n);
    for (int i = 0; i < n; i++) {
        r.covered += sw->on[i];
        if (gl->on[i] != sw->on[i]) {
            r.cov_diff++;
            r.cov_diff_off_band += !band[i];
            continue;
        }
        if (!gl->on[i] || band[i])
            continue;
        double e = pixel_error(s, map, shaded, gl->rgba + 4 * i, sw->rgba + 4 * i);
        if (errs)
            errs[r.interior] = e;
        r.interior++;
        r.worst = fmax(r.worst, e);
        r.bad += e > tol;
    }
    if (errs && r.interior) {
        qsort(errs, (size_t)r.interior, sizeof(double), cmp_double);
        r.p99 = errs[(size_t)(0.99 * (r.interior - 1))];
    }
    free(errs);
    return r;
}

/* GL | software | |difference| x 16, top row first. */
static void write_side_by_side(const char *name, const picture *gl, const picture *sw)
{
    FILE *f = fopen(name, "wb");
    if (!f)
        return;
    int w = gl->w, h = gl->h;
    fprintf(f, "P6\n%d %d\n255\n", 3 * w, h);
    unsigned char *row = malloc((size_t)w * 9);
    for (int y = h - 1; row && y >= 0; y--) {
        for (int x = 0; x < w; x++)
            for (int k = 0; k < 3; k++) {
                int i = 4 * (y * w + x) + k;
                float d = fabsf(gl->rgba[i] - sw->rgba[i]) * 16;
                row[3 * x + k] = (unsigned char)lrintf(fminf(fmaxf(gl->rgba[i], 0), 1) * 255);
                row[3 * (w + x) + k] = (unsigned char)lrintf(fminf(fmaxf(sw->rgba[i], 0), 1) * 255);
                row[3 * (2 * w + x) + k] = (unsigned char)lrintf(fminf(d, 1) * 255);
            }
        fwrite(row, 3, (size_t)w * 3, f);
    }
    free(row);
    fclose(f);
}

static void run_pass(th_ctx *t, const qgl_sw_scene *s, const attr_map *map, const unsigned char *band, int shaded)
{
    picture gl = {0}, sw = {0};
    qgl_gl_stats_t st = {0};
    int ok = picture_alloc(&gl, s->width, s->height) && picture_alloc(&sw, s->width, s->height) &&
             sw_picture(s, map, shaded, &sw) && gl_picture(t, s, map, shaded, &gl, &st);
    th_check(ok, "%s: could not draw", s->name);
    if (ok) {
        double tol = shaded ? SHADE_TOL : ATTR_TOL;
        result r = compare(s, map, shaded, &gl, &sw, band, tol);
        const char *unit = shaded ? "levels" : s->unit;
        printf("%-20s %-6s covered %6d interior %6d  worst %7.4f %s  p99 %7.4f  over %g: %d  coverage differs %d "
               "(off the edge band %d)  mvc %llu of %llu\n",
               s->name, shaded ? "shaded" : "attr", r.covered, r.interior, r.worst, unit, r.p99, tol, r.bad,
               r.cov_diff, r.cov_diff_off_band, (unsigned long long)st.mvc, (unsigned long long)st.quads);
        char name[160];
        snprintf(name, sizeof name, "scene_%s_%s.ppm", s->name, shaded ? "shaded" : "attr");
        write_side_by_side(name, &gl, &sw);
        th_check(r.interior > r.covered / 4 && r.interior > 1000, "%s: too few interior pixels", s->name);
        th_check(r.bad == 0, "%s %s: %d interior pixels over %g %s", s->name, shaded ? "shaded" : "attr", r.bad, tol,
                 unit);
        th_check(r.cov_diff_off_band == 0, "%s: coverage differs off the edge band", s->name);
        th_check(st.mvc == st.quads && st.quads == (uint64_t)s->nquads, "%s: not all quads on the shader path",
                 s->name);
    }
    picture_free(&gl);
    picture_free(&sw);
}

static int scene_filter(const struct dirent *e)
{
    size_t n = strlen(e->d_name);
    return n > 6 && strcmp(e->d_name + n - 6, ".scene") == 0;
}

int main(void)
{
    th_ctx t;
    qgl_gl_desc d = {.method = QGL_METHOD_MVC};
    int rc = th_init(&t, 64, 64, &d);
    if (rc)
        return rc;
    if (qgl_gl_shader_level(t.qgl) < 150) {
        fprintf(stderr, "no geometry shader path on this context\n");
        return 77;
    }
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/data/scenes", QGL_SOURCE_DIR);
    struct dirent **names = NULL;
    int n = scandir(dir, &names, scene_filter, alphasort);
    th_check(n >= 10, "%s: expected the shipped scenes, found %d", dir, n);
    qgl_sw_scene_load_desc ld = {0};
#ifdef QGL_HAVE_IMAGES
    ld.load_image = qgl_image_load_texture;
#endif
    int done = 0;
    for (int i = 0; i < n; i++) {
        char path[2048], err[512] = "";
        snprintf(path, sizeof path, "%s/%s", dir, names[i]->d_name);
        free(names[i]);
        qgl_sw_scene *s = NULL;
        if (qgl_sw_scene_load(path, &ld, &s, err, sizeof err) < 0) {
            printf("%s skipped: %s\n", path, err);
            continue;
        }
        attr_map map = make_map(s);
        unsigned char *band = edge_band(s);
        run_pass(&t, s, &map, band, 0);
        if (s->shading == QGL_SW_SHADE_TEXTURE)
            run_pass(&t, s, &map, band, 1);
        free(band);
        qgl_sw_scene_free(s);
        done++;
    }
    free(names);
    printf("%d scenes compared\n", done);
    th_check(done >= 10, "only %d scenes compared", done);
    th_free(&t);
    return th_failures ? 1 : 0;
}
