/* demo_scene.c: the demo's scenes, views, software reference pictures and picture comparison.
 *
 * Scenes come from the software renderer's scene files through its loader, so the demo, the
 * benchmark and the tests all look at the same quads. A view turns the scene's own camera:
 * the object is rotated about its centroid (orbit), the picture is scaled about its centre
 * (zoom) and squeezed so the scene keeps its aspect in any window; the resulting matrix goes
 * unchanged to GL (as the projection, with an identity modelview) and to the software
 * renderer (as the scene's mvp), which is what makes the two pictures comparable pixel for
 * pixel. Comparison reports the RMS and the largest difference in 8-bit levels, plus the
 * 99th percentile, which ignores the handful of edge pixels where two correct rasterizers
 * may disagree. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "demo_app.h"

const float demo_background[4] = {0.1f, 0.1f, 0.12f, 1.0f};

/* ---- methods ------------------------------------------------------------------------------ */

static const char *const method_names[DEMO_NMETHODS] = {"native", "mvc", "auto", "subdiv", "reference"};

const char *demo_method_name(demo_method m)
{
    return m >= 0 && m < DEMO_NMETHODS ? method_names[m] : "?";
}

int demo_method_parse(const char *name)
{
    for (int m = 0; m < DEMO_NMETHODS; m++)
        if (strcmp(name, method_names[m]) == 0)
            return m;
    return -1;
}

int demo_method_available(demo_method m)
{
#if DEMO_HAVE_QGL
    return m >= 0 && m < DEMO_NMETHODS;
#else
    return m == DEMO_NATIVE || m == DEMO_REFERENCE;
#endif
}

/* ---- scenes ------------------------------------------------------------------------------- */

static int scene_file_filter(const struct dirent *e)
{
    size_t n = strlen(e->d_name);
    return n > 6 && strcmp(e->d_name + n - 6, ".scene") == 0;
}

static void scene_centre(demo_scene *s)
{
    const qgl_sw_scene *sw = s->sw;
    for (int k = 0; k < 3; k++) {
        double sum = 0;
        for (int i = 0; i < sw->nverts; i++)
            sum += sw->pos[i * 3 + k];
        s->centre[k] = sw->nverts ? sum / sw->nverts : 0;
    }
}

/* The scene whose vertex order turns every second: the first colour scene (the R-B-G-R quad
 * when the scene set has it), sharing its loaded data. */
static int add_rotating_scene(demo_scene_list *list)
{
    int pick = -1;
    for (int i = 0; i < list->count && pick < 0; i++)
        if (list->items[i].sw->shading == QGL_SW_SHADE_COLOR && strstr(list->items[i].sw->name, "rbgr"))
            pick = i;
    for (int i = 0; i < list->count && pick < 0; i++)
        if (list->items[i].sw->shading == QGL_SW_SHADE_COLOR)
            pick = i;
    if (pick < 0)
        return 0;
    demo_scene *s = &list->items[list->count++];
    *s = list->items[pick];
    s->animate_order = 1;
    snprintf(s->label, sizeof s->label, "%.60s-rotating", list->items[pick].sw->name);
    return 0;
}

int demo_scenes_load(const char *dir, demo_scene_list *out, char *err, size_t errlen)
{
    struct dirent **names = NULL;
    memset(out, 0, sizeof *out);
    int n = scandir(dir, &names, scene_file_filter, alphasort);
    if (n < 0) {
        snprintf(err, errlen, "%s: cannot read the scene directory", dir);
        return -1;
    }
    out->items = calloc((size_t)n + 1, sizeof *out->items);
    int rc = out->items ? 0 : -1;
    if (rc)
        snprintf(err, errlen, "out of memory");
    qgl_sw_scene_load_desc desc = {demo_image_load_texture, NULL};
    for (int i = 0; i < n; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]->d_name);
        demo_scene *s = &out->items[out->count];
        if (rc == 0 && qgl_sw_scene_load(path, &desc, &s->sw, err, errlen) < 0)
            rc = -1;
        if (rc == 0) {
            snprintf(s->label, sizeof s->label, "%s", s->sw->name);
            scene_centre(s);
            out->count++;
        }
        free(names[i]);
    }
    free(names);
    if (rc == 0 && n == 0) {
        snprintf(err, errlen, "%s: no .scene files", dir);
        rc = -1;
    }
    if (rc == 0)
        rc = add_rotating_scene(out);
    if (rc)
        demo_scenes_free(out);
    return rc;
}

void demo_scenes_free(demo_scene_list *list)
{
    for (int i = 0; i < list->count; i++)
        if (!list->items[i].animate_order)
            qgl_sw_scene_free(list->items[i].sw);
    free(list->items);
    memset(list, 0, sizeof *list);
}

int demo_scenes_find(const demo_scene_list *list, const char *name)
{
    for (int i = 0; i < list->count; i++)
        if (strcmp(list->items[i].label, name) == 0)
            return i;
    for (int i = 0; i < list->count; i++)
        if (strstr(list->items[i].label, name))
            return i;
    return -1;
}

/* ---- views -------------------------------------------------------------------------------- */

void demo_view_reset(demo_view *v)
{
    memset(v, 0, sizeof *v);
    v->zoom = 1;
    v->shading = 1;
}

/* r = a * b, column-major 4 x 4. */
static void mat_mul(const double a[16], const double b[16], double r[16])
{
    double t[16];
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            double sum = 0;
            for (int k = 0; k < 4; k++)
                sum += a[k * 4 + row] * b[c * 4 + k];
            t[c * 4 + row] = sum;
        }
    memcpy(r, t, sizeof t);
}

static void mat_identity(double m[16])
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = m[15] = 1;
}

/* Rotation about y by yaw, then about x by pitch, pivoting on c. */
static void orbit_matrix(const double c[3], double yaw, double pitch, double m[16])
{
    double cy = cos(yaw), sy = sin(yaw), cp = cos(pitch), sp = sin(pitch);
    double r[16], t[16];
    mat_identity(r);
    r[0] = cy;
    r[8] = sy;
    r[1] = sp * sy;
    r[5] = cp;
    r[9] = -sp * cy;
    r[2] = -cp * sy;
    r[6] = sp;
    r[10] = cp * cy;
    mat_identity(t);
    t[12] = -c[0];
    t[13] = -c[1];
    t[14] = -c[2];
    mat_mul(r, t, m);
    mat_identity(t);
    t[12] = c[0];
    t[13] = c[1];
    t[14] = c[2];
    mat_mul(t, m, m);
}

void demo_view_mvp(const demo_scene *s, const demo_view *v, int w, int h, double mvp[16])
{
    double orbit[16], screen[16];
    orbit_matrix(s->centre, v->yaw, v->pitch, orbit);
    mat_mul(s->sw->mvp, orbit, mvp);
    /* Keep the scene's aspect: squeeze the longer picture axis. */
    double scene_aspect = (double)s->sw->width / s->sw->height, pic_aspect = (double)w / h;
    double sx = v->zoom, sy = v->zoom;
    if (pic_aspect > scene_aspect)
        sx *= scene_aspect / pic_aspect;
    else
        sy *= pic_aspect / scene_aspect;
    mat_identity(screen);
    screen[0] = sx;
    screen[5] = sy;
    mat_mul(screen, mvp, mvp);
}

/* ---- shading ------------------------------------------------------------------------------ */

static float clamp01(float x)
{
    return x < 0 ? 0 : x > 1 ? 1 : x;
}

void demo_shade(const demo_scene *s, int shading, const float *attr, int facing, float out[4])
{
    const qgl_sw_scene *sw = s->sw;
    if (shading) {
        qgl_sw_scene_shade((void *)sw, attr, sw->nattr, facing, out);
    } else if (strcmp(sw->attr_kind, "normal") == 0) {
        for (int k = 0; k < 3; k++)
            out[k] = 0.5f * attr[k] + 0.5f;
    } else {
        for (int k = 0; k < 3; k++)
            out[k] = k < sw->nattr ? attr[k] : 0;
    }
    for (int k = 0; k < 3; k++)
        out[k] = clamp01(out[k]);
    out[3] = 1;
}

typedef struct shade_ctx {
    const demo_scene *scene;
    int shading;
} shade_ctx;

static int shade_adapter(void *user, const float *attr, int nattr, int facing, float *out)
{
    const shade_ctx *c = user;
    (void)nattr;
    demo_shade(c->scene, c->shading, attr, facing, out);
    return 1;
}

static unsigned char to_level(float v)
{
    v = clamp01(v);
    return (unsigned char)lrintf(v * 255.0f);
}

int demo_sw_render(const demo_scene *s, const demo_view *v, const char *method, int w, int h,
                   unsigned char *rgba)
{
    qgl_sw_method_desc m;
    int rc = qgl_sw_method_parse(method, &m);
    if (rc < 0)
        return rc;
    qgl_sw_scene view = *s->sw;
    demo_view_mvp(s, v, w, h, view.mvp);
    view.width = w;
    view.height = h;
    float *clip = NULL, *attr = NULL, *object = NULL;
    rc = qgl_sw_scene_arrays(&view, v->order, &clip, &attr, &object);
    qgl_sw_fb_desc fd = {.width = w, .height = h, .channels = 4};
    qgl_sw_fb *fb = rc < 0 ? NULL : qgl_sw_fb_create(&fd);
    if (rc >= 0 && !fb)
        rc = QGL_SW_ENOMEM;
    if (fb) {
        shade_ctx sc = {s, v->shading};
        qgl_sw_draw_desc d = {
            .method = m,
            .nquads = view.nquads,
            .nattr = view.nattr,
            .clip = clip,
            .attr = attr,
            .object = object,
            .uv_attr1 = strcmp(view.attr_kind, "uv") == 0 ? 1 : 0,
            .cull = view.cull_back ? QGL_SW_CULL_BACK : QGL_SW_CULL_NONE,
            .shade = shade_adapter,
            .user = &sc,
        };
        qgl_sw_fb_clear(fb, demo_background, 1.0f);
        rc = qgl_sw_draw(fb, &d, NULL);
        for (size_t i = 0; i < (size_t)w * (size_t)h * 4; i++)
            rgba[i] = to_level(fb->color[i]);
        qgl_sw_fb_destroy(fb);
    }
    free(clip);
    free(attr);
    free(object);
    return rc < 0 ? rc : 0;
}

/* ---- comparing pictures ------------------------------------------------------------------- */

static int pixel_diff(const unsigned char *a, const unsigned char *b)
{
    int d = 0;
    for (int k = 0; k < 3; k++) {
        int e = abs((int)a[k] - (int)b[k]);
        d = e > d ? e : d;
    }
    return d;
}

void demo_compare(const unsigned char *a, const unsigned char *b, int w, int h, demo_error *out)
{
    long hist[256] = {0};
    double sum2 = 0;
    int mx = 0;
    size_t n = (size_t)w * (size_t)h;
    for (size_t i = 0; i < n; i++) {
        for (int k = 0; k < 3; k++) {
            double e = (double)a[i * 4 + k] - (double)b[i * 4 + k];
            sum2 += e * e;
        }
        int d = pixel_diff(a + i * 4, b + i * 4);
        hist[d]++;
        mx = d > mx ? d : mx;
    }
    out->rms = n ? sqrt(sum2 / (3.0 * (double)n)) : 0;
    out->max = mx;
    long over = 0, seen = 0;
    out->p99 = -1;
    for (int d = 0; d < 256; d++) {
        seen += hist[d];
        if (d > 8)
            over += hist[d];
        if (out->p99 < 0 && (double)seen >= 0.99 * (double)n)
            out->p99 = d;
    }
    out->frac_over = n ? (double)over / (double)n : 0;
}

/* Black, blue, red, yellow, white at t = 0, 1/4, 1/2, 3/4, 1. */
static void ramp(double t, unsigned char rgb[3])
{
    static const double stops[5][3] = {{0, 0, 0}, {0, 0, 255}, {255, 0, 0}, {255, 255, 0}, {255, 255, 255}};
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    int i = t >= 1 ? 3 : (int)(t * 4);
    double f = t * 4 - i;
    for (int k = 0; k < 3; k++)
        rgb[k] = (unsigned char)lrint(stops[i][k] + f * (stops[i + 1][k] - stops[i][k]));
}

void demo_heatmap(const unsigned char *a, const unsigned char *b, int w, int h, int full_scale,
                  unsigned char *rgba)
{
    size_t n = (size_t)w * (size_t)h;
    for (size_t i = 0; i < n; i++) {
        ramp((double)pixel_diff(a + i * 4, b + i * 4) / full_scale, rgba + i * 4);
        rgba[i * 4 + 3] = 255;
    }
}
