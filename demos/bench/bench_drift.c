/* bench_drift.c: the view drift of a method: how much the value at a fixed surface point
 * changes as the camera moves.
 *
 * For a sample of the scene's quads, each alone: fixed surface points are the bilinear
 * patch's points at a DRIFT_GRID x DRIFT_GRID grid of parameters (on a planar quad, points of
 * the plane; on a non-planar one, of the exact reference's surface). The camera orbits the
 * quad's centroid at three times its radius, from head-on along the plane's normal to
 * DRIFT_MAX_DEG degrees oblique in steps of DRIFT_STEP_DEG, at four azimuths, looking at the
 * centroid through a perspective that holds the whole quad. Each point is evaluated exactly
 * where it projects: the projection is followed by a translation and scale of NDC that puts
 * the point at the centre of a 1 x 1 framebuffer while keeping the pixel size of a
 * DRIFT_VIEWPORT square viewport (the weights are computed in pixels relative to the
 * framebuffer's centre, and mean value weights do not change under translation), so every
 * method renders the value it would show there, its own coverage and depth test included.
 * Views in which the point is not the nearest hit of the ray on the patch (a fold hides it)
 * are skipped. The drift is the largest difference, over pairs of views and over points, of
 * the attribute vector (Euclidean norm) times the scene's unit. */
#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef QGL_HAVE_IMAGES
#include "qgl_image.h"
#endif

#define DRIFT_QUADS 12
#define DRIFT_GRID 5
#define DRIFT_MAX_DEG 80
#define DRIFT_STEP_DEG 20
#define DRIFT_AZIMUTHS 4
#define DRIFT_VIEWPORT 512
#define DRIFT_VIEWS (1 + (DRIFT_MAX_DEG / DRIFT_STEP_DEG) * DRIFT_AZIMUTHS)

static const double pi = 3.14159265358979323846;

typedef struct drift_quad {
    double pos[4][3];
    float attr[4 * QGL_SW_MAX_ATTR];
    double centre[3], normal[3], axis[2][3], radius;
} drift_quad;

static void normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        v[k] /= l;
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Quad q of the scene with its frame; 0 when it spans no plane. */
static int load_quad(const qgl_sw_scene *s, int q, drift_quad *dq)
{
    for (int i = 0; i < 4; i++) {
        int v = s->quad[4 * q + i];
        for (int k = 0; k < 3; k++)
            dq->pos[i][k] = s->pos[3 * v + k];
        for (int k = 0; k < s->nattr; k++)
            dq->attr[i * s->nattr + k] = s->attr[v * s->nattr + k];
    }
    qgl_plane pl;
    if (qgl_plane_frame(dq->pos, &pl) != 0)
        return 0;
    memcpy(dq->centre, pl.origin, sizeof dq->centre);
    memcpy(dq->normal, pl.normal, sizeof dq->normal);
    memcpy(dq->axis, pl.axis, sizeof dq->axis);
    dq->radius = 0;
    for (int i = 0; i < 4; i++) {
        double d2 = 0;
        for (int k = 0; k < 3; k++)
            d2 += (dq->pos[i][k] - pl.origin[k]) * (dq->pos[i][k] - pl.origin[k]);
        dq->radius = fmax(dq->radius, sqrt(d2));
    }
    return dq->radius > 0;
}

/* Projection * view (column-major) of the camera elev radians from dq's normal at azimuth
 * azim (radians, from the plane's first axis), at three times its radius, looking at its
 * centroid through a perspective that holds the whole quad (zoom 1; larger zooms in). */
static void orbit_camera(const drift_quad *dq, double elev, double azim, double zoom, double m[16])
{
    double dist = 3 * dq->radius, eye[3], f[3], up[3], side[3];
    for (int j = 0; j < 3; j++) {
        double tangent = cos(azim) * dq->axis[0][j] + sin(azim) * dq->axis[1][j];
        eye[j] = dq->centre[j] + dist * (cos(elev) * dq->normal[j] + sin(elev) * tangent);
        f[j] = dq->centre[j] - eye[j];
        up[j] = -sin(azim) * dq->axis[0][j] + cos(azim) * dq->axis[1][j];
    }
    normalize3(f);
    cross3(f, up, side);
    normalize3(side);
    cross3(side, f, up);
    double fovy = 2 * atan(1.1 * dq->radius / (dist - dq->radius) / zoom), t = 1 / tan(fovy / 2);
    double n = 0.05 * dq->radius, fa = 10 * dist;
    double view[16] = {side[0], up[0], -f[0], 0, side[1], up[1], -f[1], 0, side[2], up[2], -f[2], 0, 0, 0, 0, 1};
    for (int r = 0; r < 3; r++)
        view[12 + r] = -(view[r] * eye[0] + view[4 + r] * eye[1] + view[8 + r] * eye[2]);
    double proj[16] = {t, 0, 0, 0, 0, t, 0, 0, 0, 0, (fa + n) / (n - fa), -1, 0, 0, 2 * fa * n / (n - fa), 0};
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double s = 0;
            for (int j = 0; j < 4; j++)
                s += proj[4 * j + r] * view[4 * c + j];
            m[4 * c + r] = s;
        }
}

/* View number k of the orbit: 0 head-on, then each elevation step at every azimuth. */
static void orbit_view(const drift_quad *dq, int k, double m[16])
{
    double elev = 0, azim = 0;
    if (k > 0) {
        elev = (1 + (k - 1) / DRIFT_AZIMUTHS) * DRIFT_STEP_DEG * pi / 180;
        azim = ((k - 1) % DRIFT_AZIMUTHS) * 2 * pi / DRIFT_AZIMUTHS;
    }
    orbit_camera(dq, elev, azim, 1, m);
}

static void apply(const double m[16], const double p[3], double out[4])
{
    for (int r = 0; r < 4; r++)
        out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
}

/* The value method m shows at the point whose clip position is at: the quad rendered into
 * a 1 x 1 framebuffer centred there. Returns 0 when nothing covers it. */
static int value_at(qgl_sw_fb *fb, const qgl_sw_method_desc *m, const drift_quad *dq, const double mvp[16],
                    const double at[4], const float *attr, int nattr, float *out)
{
    float clip[16], obj[12];
    double cx = at[0] / at[3], cy = at[1] / at[3];
    for (int i = 0; i < 4; i++) {
        double c[4];
        apply(mvp, dq->pos[i], c);
        clip[4 * i] = (float)(DRIFT_VIEWPORT * (c[0] - cx * c[3]));
        clip[4 * i + 1] = (float)(DRIFT_VIEWPORT * (c[1] - cy * c[3]));
        clip[4 * i + 2] = (float)c[2];
        clip[4 * i + 3] = (float)c[3];
        for (int k = 0; k < 3; k++)
            obj[3 * i + k] = (float)dq->pos[i][k];
    }
    qgl_sw_draw_desc d = {.method = *m, .nquads = 1, .nattr = nattr, .clip = clip, .attr = attr, .object = obj,
                          .uv_attr1 = 0};
    qgl_sw_fb_clear(fb, NULL, 1.0f);
    if (qgl_sw_draw(fb, &d, NULL) != QGL_SW_OK || fb->count[0] == 0)
        return 0;
    memcpy(out, fb->color, (size_t)nattr * sizeof(float));
    return 1;
}

static void patch_point(const drift_quad *dq, double s, double t, double p[3])
{
    const double b[4] = {(1 - s) * (1 - t), s * (1 - t), s * t, (1 - s) * t};
    for (int k = 0; k < 3; k++)
        p[k] = b[0] * dq->pos[0][k] + b[1] * dq->pos[1][k] + b[2] * dq->pos[2][k] + b[3] * dq->pos[3][k];
}

/* Whether the surface point p is what the exact reference sees where it projects. */
static int visible(qgl_sw_fb *fb, const drift_quad *dq, const double mvp[16], const double at[4], const double p[3])
{
    static const float params[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    qgl_sw_method_desc exact = {.method = QGL_SW_EXACT};
    float uv[2];
    double hit[3], d2 = 0;
    if (!value_at(fb, &exact, dq, mvp, at, params, 2, uv))
        return 0;
    patch_point(dq, uv[0], uv[1], hit);
    for (int k = 0; k < 3; k++)
        d2 += (hit[k] - p[k]) * (hit[k] - p[k]);
    return sqrt(d2) <= 1e-5 * dq->radius;
}

/* The largest pairwise difference of the nviews values (nattr each; NAN where unseen). */
static double spread(const float (*v)[QGL_SW_MAX_ATTR], int nviews, int nattr)
{
    double worst = 0;
    for (int a = 0; a < nviews; a++)
        for (int b = a + 1; b < nviews; b++) {
            if (isnan(v[a][0]) || isnan(v[b][0]))
                continue;
            double d2 = 0;
            for (int k = 0; k < nattr; k++)
                d2 += (double)(v[a][k] - v[b][k]) * (v[a][k] - v[b][k]);
            worst = fmax(worst, sqrt(d2));
        }
    return worst;
}

static double quad_drift(qgl_sw_fb *fb, const qgl_sw_method_desc *m, const drift_quad *dq, int nattr)
{
    double mvp[DRIFT_VIEWS][16], worst = 0;
    for (int k = 0; k < DRIFT_VIEWS; k++)
        orbit_view(dq, k, mvp[k]);
    for (int gi = 0; gi < DRIFT_GRID; gi++)
        for (int gj = 0; gj < DRIFT_GRID; gj++) {
            double p[3];
            patch_point(dq, (gi + 0.5) / DRIFT_GRID, (gj + 0.5) / DRIFT_GRID, p);
            float vals[DRIFT_VIEWS][QGL_SW_MAX_ATTR];
            for (int k = 0; k < DRIFT_VIEWS; k++) {
                double at[4];
                apply(mvp[k], p, at);
                if (!visible(fb, dq, mvp[k], at, p) || !value_at(fb, m, dq, mvp[k], at, dq->attr, nattr, vals[k]))
                    vals[k][0] = NAN;
            }
            worst = fmax(worst, spread((const float(*)[QGL_SW_MAX_ATTR])vals, DRIFT_VIEWS, nattr));
        }
    return worst;
}

double bench_drift(const bench_scene *bs, const qgl_sw_method_desc *m)
{
    const qgl_sw_scene *s = bs->scene;
    qgl_sw_fb_desc fd = {.width = 1, .height = 1, .channels = s->nattr, .with_count = 1};
    qgl_sw_fb *fb = qgl_sw_fb_create(&fd);
    if (!fb)
        return -1;
    int n = s->nquads < DRIFT_QUADS ? s->nquads : DRIFT_QUADS;
    double worst = 0;
    for (int k = 0; k < n; k++) {
        drift_quad dq;
        if (load_quad(s, (int)((long long)k * s->nquads / n), &dq))
            worst = fmax(worst, quad_drift(fb, m, &dq, s->nattr));
    }
    qgl_sw_fb_destroy(fb);
    return worst * s->unit_scale;
}

/* ---- the picture ------------------------------------------------------------------------- */

#define SHEET_VIEWS 4

/* The head-on value (the in-plane weights, which a head-on view's screen-space weights equal:
 * the view is a similarity of the plane) at the surface point seen at the centre of pixel
 * (x, y) of a size x size image: the point origin + a u + b v whose clip position projects
 * there, two linear equations in (a, b). Returns 0 off the quad. */
static int head_on_value(const drift_quad *dq, const qgl_plane *pl, const double mvp[16], int size, int x, int y,
                         int nattr, double *out)
{
    double X = (x + 0.5) / size * 2 - 1, Y = (y + 0.5) / size * 2 - 1, c[3][4], p[3], A[2][3], lam[4];
    apply(mvp, pl->origin, c[0]);
    for (int a = 0; a < 2; a++) {
        for (int k = 0; k < 3; k++)
            p[k] = pl->origin[k] + pl->axis[a][k];
        apply(mvp, p, c[1 + a]);
    }
    for (int r = 0; r < 2; r++) {
        double s = r ? Y : X;
        A[r][0] = (c[1][r] - c[0][r]) - s * (c[1][3] - c[0][3]);
        A[r][1] = (c[2][r] - c[0][r]) - s * (c[2][3] - c[0][3]);
        A[r][2] = -(c[0][r] - s * c[0][3]);
    }
    double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
    if (det == 0)
        return 0;
    double a = (A[0][2] * A[1][1] - A[0][1] * A[1][2]) / det, b = (A[0][0] * A[1][2] - A[0][2] * A[1][0]) / det;
    if (qgl_weights_inplane(pl, a, b, lam) != QGL_INSIDE)
        return 0;
    for (int k = 0; k < nattr; k++)
        out[k] = lam[0] * dq->attr[k] + lam[1] * dq->attr[nattr + k] + lam[2] * dq->attr[2 * nattr + k] +
                 lam[3] * dq->attr[3 * nattr + k];
    return 1;
}

/* One image of the sheet: the quad drawn by m from mvp, shaded (with_shade) or as the heat map
 * of its change against the head-on value, into canvas at (x0, y0); returns the largest change. */
static double sheet_cell(const bench_scene *bs, const drift_quad *dq, const qgl_sw_method_desc *m,
                         const double mvp[16], int size, int with_shade, float *canvas, int cw, int x0, int y0)
{
    const qgl_sw_scene *s = bs->scene;
    float clip[16], obj[12];
    for (int i = 0; i < 4; i++) {
        double c[4];
        apply(mvp, dq->pos[i], c);
        for (int k = 0; k < 4; k++)
            clip[4 * i + k] = (float)c[k];
        for (int k = 0; k < 3; k++)
            obj[3 * i + k] = (float)dq->pos[i][k];
    }
    qgl_sw_fb_desc fd = {.width = size, .height = size, .channels = with_shade ? 4 : s->nattr, .with_count = 1};
    qgl_sw_fb *fb = qgl_sw_fb_create(&fd);
    if (!fb)
        return -1;
    const float bg[4] = {0.22f, 0.22f, 0.26f, 1};
    qgl_sw_fb_clear(fb, with_shade ? bg : NULL, 1.0f);
    qgl_sw_draw_desc d = {.method = *m, .nquads = 1, .nattr = s->nattr, .clip = clip, .attr = dq->attr, .object = obj};
    if (with_shade) {
        d.shade = qgl_sw_scene_shade;
        d.user = (void *)s;
    }
    qgl_sw_draw(fb, &d, NULL);
    qgl_plane pl;
    qgl_plane_frame(dq->pos, &pl);
    double worst = 0;
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            size_t i = (size_t)y * (size_t)size + (size_t)x;
            float *o = canvas + ((size_t)(y0 + size - 1 - y) * (size_t)cw + (size_t)(x0 + x)) * 3;
            double ref[QGL_SW_MAX_ATTR];
            if (with_shade) {
                for (int k = 0; k < 3; k++)
                    o[k] = fb->color[4 * i + (size_t)k];
                continue;
            }
            o[0] = o[1] = o[2] = 0.12f;
            if (!fb->count[i] || !head_on_value(dq, &pl, mvp, size, x, y, s->nattr, ref))
                continue;
            double d2 = 0;
            for (int k = 0; k < s->nattr; k++)
                d2 += (fb->color[i * (size_t)s->nattr + (size_t)k] - ref[k]) *
                      (fb->color[i * (size_t)s->nattr + (size_t)k] - ref[k]);
            double e = sqrt(d2) * s->unit_scale;
            worst = fmax(worst, e);
            bench_heat_units(e, o);
        }
    qgl_sw_fb_destroy(fb);
    return worst;
}

int bench_drift_sheet(const char *path, const bench_scene *bs, int size)
{
    static const char *const methods[2] = {"mvc", "mvcplane"};
    static const double elev[SHEET_VIEWS] = {0, 40, 60, 80};
    drift_quad dq;
    if (!bs->scene->nquads || !load_quad(bs->scene, 0, &dq))
        return -1;
    const int left = 90, top = 40, gap = 10;
    int w = left + 4 * (size + gap), h = top + SHEET_VIEWS * (size + gap + 16) + 12;
    float *canvas = malloc((size_t)w * (size_t)h * 3 * sizeof(float));
    if (!canvas)
        return -1;
    for (size_t i = 0; i < (size_t)w * (size_t)h * 3; i++)
        canvas[i] = 0.05f;
    enum { MAXLAB = 5 + SHEET_VIEWS * 5 };
    int xy[2 * MAXLAB], nlab = 0;
    char text[MAXLAB][160];
    static const char *const heads[4] = {"mvc (screen space)", "mvc: change (%s)", "mvcplane (in plane)",
                                         "mvcplane: change (%s)"};
    for (int c = 0; c < 4; c++) {
        xy[2 * nlab] = left + c * (size + gap), xy[2 * nlab + 1] = 24;
        snprintf(text[nlab++], sizeof text[0], heads[c], bs->scene->unit);
    }
    xy[2 * nlab] = 4, xy[2 * nlab + 1] = h - 6;
    snprintf(text[nlab++], sizeof text[0], "change against the head-on value at the same surface point, log scale "
                                           "from 0.001 (black) to 10 %s (white)", bs->scene->unit);
    for (int v = 0; v < SHEET_VIEWS; v++) {
        double mvp[16];
        int y0 = top + v * (size + gap + 16);
        orbit_camera(&dq, elev[v] * pi / 180, 0, 1.4, mvp);
        xy[2 * nlab] = 4, xy[2 * nlab + 1] = y0 + size / 2;
        snprintf(text[nlab++], sizeof text[0], "%s", v ? "" : "head-on");
        if (v)
            snprintf(text[nlab - 1], sizeof text[0], "%.0f deg", elev[v]);
        for (int m = 0; m < 2; m++) {
            qgl_sw_method_desc md;
            qgl_sw_method_parse(methods[m], &md);
            int x0 = left + 2 * m * (size + gap);
            sheet_cell(bs, &dq, &md, mvp, size, 1, canvas, w, x0, y0);
            double worst = sheet_cell(bs, &dq, &md, mvp, size, 0, canvas, w, x0 + size + gap, y0);
            xy[2 * nlab] = x0 + size + gap, xy[2 * nlab + 1] = y0 + size + 13;
            snprintf(text[nlab++], sizeof text[0], "max %.3g", worst);
        }
    }
    int rc = -1;
#ifdef QGL_HAVE_IMAGES
    const char *labels[MAXLAB];
    for (int i = 0; i < nlab; i++)
        labels[i] = text[i];
    char err[512];
    rc = qgl_image_write_labeled(path, w, h, 3, canvas, nlab, xy, labels, 13, err, sizeof err);
    if (rc < 0)
        fprintf(stderr, "quadgl-bench: %s: %s\n", path, err);
    rc = rc < 0 ? -1 : 0;
#else
    fprintf(stderr, "quadgl-bench: --drift-sheet needs OpenImageIO (built without it)\n");
#endif
    free(canvas);
    return rc;
}
