/* bench_metrics.c: timed renders and the error, crease and heat-map measures of quadgl-bench.
 *
 * Errors compare attribute images (the interpolated values themselves, before any shading)
 * against the exact reference over the pixels both cover, as a vector norm over the
 * attribute's components times the scene's unit (texels of the texture, or 8-bit levels).
 * The crease measure samples each quad's two screen diagonals and takes the jump of the
 * directional derivative across them, (a(p + 2h n) - a(p + h n)) - (a(p - h n) - a(p - 2h n))
 * over h (h = 1.5 px, bilinear reads of the attribute image): a split has a kink there and
 * scores the jump of its gradient, a smooth method scores about 3 h times its curvature. The
 * larger of the two diagonals' means is reported, in units per pixel. */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

int bench_image_alloc(bench_image *im, int w, int h, int nattr)
{
    im->width = w;
    im->height = h;
    im->nattr = nattr;
    im->attr = calloc((size_t)w * (size_t)h * (size_t)nattr, sizeof(float));
    im->cover = calloc((size_t)w * (size_t)h, 1);
    return im->attr && im->cover ? 0 : -1;
}

void bench_image_free(bench_image *im)
{
    free(im->attr);
    free(im->cover);
    memset(im, 0, sizeof *im);
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static qgl_sw_draw_desc draw_desc(const bench_scene *bs, const qgl_sw_method_desc *m, int rot)
{
    const qgl_sw_scene *s = bs->scene;
    qgl_sw_draw_desc d = {
        .method = *m,
        .nquads = s->nquads,
        .nattr = s->nattr,
        .clip = bs->clip[rot],
        .attr = bs->attr[rot],
        .object = bs->object[rot],
        .uv_attr1 = !strcmp(s->attr_kind, "uv") ? 1 : 0,
        .cull = s->cull_back ? QGL_SW_CULL_BACK : QGL_SW_CULL_NONE,
    };
    return d;
}

double bench_render(const bench_scene *bs, const qgl_sw_method_desc *m, int rot, bench_image *out,
                    long long *fragments)
{
    qgl_sw_fb_desc fd = {.width = bs->width, .height = bs->height, .channels = bs->scene->nattr,
                         .with_count = 1};
    qgl_sw_fb *fb = qgl_sw_fb_create(&fd);
    if (!fb)
        return -1;
    qgl_sw_draw_desc d = draw_desc(bs, m, rot);
    qgl_sw_stats st = {0};
    double t0 = now_ms();
    int r = qgl_sw_draw(fb, &d, &st);
    double ms = now_ms() - t0;
    if (fragments)
        *fragments = st.fragments;
    if (out && r == QGL_SW_OK) {
        size_t n = (size_t)fb->width * (size_t)fb->height;
        memcpy(out->attr, fb->color, n * (size_t)fb->channels * sizeof(float));
        for (size_t i = 0; i < n; i++)
            out->cover[i] = fb->count[i] > 0;
    }
    qgl_sw_fb_destroy(fb);
    return r == QGL_SW_OK ? ms : -1;
}

static double pixel_error(const bench_image *a, const bench_image *ref, size_t i)
{
    double d2 = 0;
    for (int k = 0; k < a->nattr; k++) {
        double d = (double)a->attr[i * (size_t)a->nattr + (size_t)k] - ref->attr[i * (size_t)a->nattr + (size_t)k];
        d2 += d * d;
    }
    return sqrt(d2);
}

void bench_error(const bench_image *a, const bench_image *ref, double unit, double *rms, double *max)
{
    double sum = 0, mx = 0;
    size_t n = 0, total = (size_t)a->width * (size_t)a->height;
    for (size_t i = 0; i < total; i++) {
        if (!a->cover[i] || !ref->cover[i])
            continue;
        double e = pixel_error(a, ref, i) * unit;
        sum += e * e;
        mx = e > mx ? e : mx;
        n++;
    }
    *rms = n ? sqrt(sum / (double)n) : 0;
    *max = mx;
}

/* Bilinear read of the attribute image at window position (x, y); 0 when a texel is uncovered. */
static int read_attr(const bench_image *im, double x, double y, double *out)
{
    double fx = x - 0.5, fy = y - 0.5;
    int x0 = (int)floor(fx), y0 = (int)floor(fy);
    if (x0 < 0 || y0 < 0 || x0 + 1 >= im->width || y0 + 1 >= im->height)
        return 0;
    double ax = fx - x0, ay = fy - y0;
    for (int k = 0; k < im->nattr; k++)
        out[k] = 0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            size_t p = (size_t)(y0 + j) * (size_t)im->width + (size_t)(x0 + i);
            if (!im->cover[p])
                return 0;
            double w = (i ? ax : 1 - ax) * (j ? ay : 1 - ay);
            for (int k = 0; k < im->nattr; k++)
                out[k] += w * im->attr[p * (size_t)im->nattr + (size_t)k];
        }
    return 1;
}

/* Mean jump along the diagonal from window point a to b; adds to *sum and *count. */
static void diagonal_jumps(const bench_image *im, const double a[2], const double b[2], double unit, double *sum,
                           long *count)
{
    const double h = 1.5;
    double dx = b[0] - a[0], dy = b[1] - a[1], len = sqrt(dx * dx + dy * dy);
    if (!(len >= 12))
        return;
    double nx = -dy / len, ny = dx / len;
    for (double t = 0.2; t <= 0.8; t += 1.0 / len) {
        double px = a[0] + t * dx, py = a[1] + t * dy, v[4][16];
        const double off[4] = {-2 * h, -h, h, 2 * h};
        int ok = 1;
        for (int s = 0; s < 4 && ok; s++)
            ok = read_attr(im, px + off[s] * nx, py + off[s] * ny, v[s]);
        if (!ok)
            continue;
        double j2 = 0;
        for (int k = 0; k < im->nattr; k++) {
            double j = ((v[3][k] - v[2][k]) - (v[1][k] - v[0][k])) / h;
            j2 += j * j;
        }
        *sum += sqrt(j2) * unit;
        (*count)++;
    }
}

double bench_crease(const bench_scene *bs, const bench_image *im, double unit)
{
    double sum[2] = {0, 0};
    long count[2] = {0, 0};
    for (int q = 0; q < bs->scene->nquads; q++) {
        const float *c = bs->clip[0] + q * 16;
        double p[4][2];
        int ok = 1;
        for (int i = 0; i < 4 && ok; i++) {
            double w = c[4 * i + 3];
            ok = w > 0;
            p[i][0] = (c[4 * i] / w + 1) * 0.5 * bs->width;
            p[i][1] = (c[4 * i + 1] / w + 1) * 0.5 * bs->height;
        }
        if (!ok)
            continue;
        diagonal_jumps(im, p[0], p[2], unit, &sum[0], &count[0]);
        diagonal_jumps(im, p[1], p[3], unit, &sum[1], &count[1]);
    }
    double m0 = count[0] ? sum[0] / count[0] : 0, m1 = count[1] ? sum[1] / count[1] : 0;
    return m0 > m1 ? m0 : m1;
}

/* Black, blue, red, yellow, white along t in [0, 1]. */
static void heat_color(double t, float *rgb)
{
    static const float stops[5][3] = {{0, 0, 0}, {0.1f, 0.2f, 0.9f}, {0.9f, 0.1f, 0.1f}, {1, 0.9f, 0.1f}, {1, 1, 1}};
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double x = t * 4;
    int i = x >= 4 ? 3 : (int)x;
    double f = x - i;
    for (int k = 0; k < 3; k++)
        rgb[k] = (float)((1 - f) * stops[i][k] + f * stops[i + 1][k]);
}

void bench_heat_units(double e, float rgb[3])
{
    heat_color(e > 0 ? (log10(e) + 3) / 4 : 0, rgb);
}

float *bench_heat(const bench_image *a, const bench_image *ref, double unit)
{
    int w = a->width, h = a->height;
    float *rgb = malloc((size_t)w * (size_t)h * 3 * sizeof(float));
    if (!rgb)
        return NULL;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            float *o = rgb + ((size_t)(h - 1 - y) * (size_t)w + (size_t)x) * 3;
            if (a->cover[i] && ref->cover[i]) {
                double e = pixel_error(a, ref, i) * unit;
                heat_color(e > 0 ? (log10(e) + 3) / 4 : 0, o);
            } else if (a->cover[i] != ref->cover[i]) {
                o[0] = 0.9f, o[1] = 0.2f, o[2] = 0.9f; /* coverage differs: magenta */
            } else {
                o[0] = o[1] = o[2] = 0.12f;
            }
        }
    return rgb;
}

float *bench_shaded(const bench_scene *bs, const qgl_sw_method_desc *m)
{
    qgl_sw_fb_desc fd = {.width = bs->width, .height = bs->height, .channels = 4};
    qgl_sw_fb *fb = qgl_sw_fb_create(&fd);
    float *rgb = malloc((size_t)bs->width * (size_t)bs->height * 3 * sizeof(float));
    if (!fb || !rgb) {
        qgl_sw_fb_destroy(fb);
        free(rgb);
        return NULL;
    }
    const float bg[4] = {0.22f, 0.22f, 0.26f, 1};
    qgl_sw_fb_clear(fb, bg, 1.0f);
    qgl_sw_draw_desc d = draw_desc(bs, m, 0);
    d.shade = qgl_sw_scene_shade;
    d.user = bs->scene;
    qgl_sw_draw(fb, &d, NULL);
    for (int y = 0; y < bs->height; y++)
        for (int x = 0; x < bs->width; x++)
            for (int k = 0; k < 3; k++)
                rgb[((size_t)(bs->height - 1 - y) * (size_t)bs->width + (size_t)x) * 3 + (size_t)k] =
                    fb->color[((size_t)y * (size_t)bs->width + (size_t)x) * 4 + (size_t)k];
    qgl_sw_fb_destroy(fb);
    return rgb;
}
