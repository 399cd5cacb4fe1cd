/* Watertightness: meshes of quads sharing edges cover every pixel of their union exactly once,
 * for every method. Three meshes: a flat grid with jittered inner corners (some exactly on
 * pixel centres, so the tie rule decides), a non-planar height field in perspective, and a
 * closed lat/long sphere drawn with back-face culling (pole quads have a collapsed edge). The
 * union is known independently: the grid's outer rectangle, the split's own union for the
 * height field (boundary edges are the same straight lines for every method), a disc for the
 * sphere (between the inscribed polygon and the true silhouette). */
#include "render_test.h"

#define W 64

static unsigned hash(unsigned x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    return x ^ (x >> 16);
}

static double jitter(unsigned seed)
{
    return (hash(seed) % 1000) / 1000.0 - 0.5;
}

/* An nx x ny grid of quads; corner (i, j) from fn; clip and attr arrays filled. */
typedef void (*corner_fn)(int i, int j, int nx, int ny, float clip[4]);

static int build_grid(int nx, int ny, corner_fn fn, float **clip, float **attr)
{
    *clip = malloc((size_t)nx * ny * 16 * sizeof(float));
    *attr = calloc((size_t)nx * ny * 4, sizeof(float));
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            float *q = *clip + (j * nx + i) * 16;
            fn(i, j, nx, ny, q);
            fn(i + 1, j, nx, ny, q + 4);
            fn(i + 1, j + 1, nx, ny, q + 8);
            fn(i, j + 1, nx, ny, q + 12);
        }
    return nx * ny;
}

static const double X0 = -0.8037, X1 = 0.8123, Y0 = -0.7531, Y1 = 0.7919;

static void flat_corner(int i, int j, int nx, int ny, float c[4])
{
    double x = X0 + (X1 - X0) * i / nx, y = Y0 + (Y1 - Y0) * j / ny;
    double cw = (X1 - X0) / nx, ch = (Y1 - Y0) / ny;
    if (i > 0 && i < nx)
        x += 0.3 * cw * jitter((unsigned)(i * 131 + j * 7));
    if (j > 0 && j < ny)
        y += 0.3 * ch * jitter((unsigned)(i * 17 + j * 901 + 5));
    if ((i + j) % 3 == 0 && i > 0 && i < nx && j > 0 && j < ny) { /* snap to a pixel centre */
        x = (floor((x + 1) * W / 2) + 0.5) * 2 / W - 1;
        y = (floor((y + 1) * W / 2) + 0.5) * 2 / W - 1;
    }
    clip_corner(c, x, y, 0, 1);
}

static void wavy_corner(int i, int j, int nx, int ny, float c[4])
{
    double m[16], p[3] = {2.0 * i / nx - 1, 2.0 * j / ny - 1, 0};
    p[2] = 0.25 * sin(3 * p[0]) * cos(2 * p[1]);
    camera(60, 3.2, m);
    transform(m, p, c);
}

static int inside_rect(int x, int y)
{
    double px = (x + 0.5) * 2 / W - 1, py = (y + 0.5) * 2 / W - 1;
    return px > X0 && px < X1 && py > Y0 && py < Y1;
}

static void check_counts(const char *mesh, const char *method, const qgl_sw_fb *fb, const unsigned char *want)
{
    int over = 0, holes = 0, extra = 0;
    for (int i = 0; i < fb->width * fb->height; i++) {
        over += fb->count[i] > 1;
        holes += want[i] == 1 && fb->count[i] == 0;
        extra += want[i] == 0 && fb->count[i] > 0;
    }
    printf("%-8s %-12s doubly covered %d, holes %d, outside %d\n", mesh, method, over, holes, extra);
    CHECK(over == 0, "%s/%s: %d pixels covered more than once", mesh, method, over);
    CHECK(holes == 0, "%s/%s: %d pixels of the union not covered", mesh, method, holes);
    CHECK(extra == 0, "%s/%s: %d pixels outside the union covered", mesh, method, extra);
}

static void flat_grid(void)
{
    float *clip, *attr;
    int n = build_grid(7, 6, flat_corner, &clip, &attr);
    unsigned char want[W * W];
    for (int y = 0; y < W; y++)
        for (int x = 0; x < W; x++)
            want[y * W + x] = (unsigned char)inside_rect(x, y);
    qgl_sw_fb *fb = test_fb(W, W, 1);
    for (int m = 0; m < N_ALL_METHODS; m++) {
        test_draw(fb, all_methods[m], clip, attr, 1, n, QGL_SW_DEPTH_ALWAYS, QGL_SW_CULL_NONE);
        check_counts("grid", all_methods[m], fb, want);
    }
    qgl_sw_fb_destroy(fb);
    free(clip);
    free(attr);
}

static void wavy_grid(void)
{
    float *clip, *attr;
    int n = build_grid(6, 5, wavy_corner, &clip, &attr);
    unsigned char want[W * W];
    qgl_sw_fb *fb = test_fb(W, W, 1);
    test_draw(fb, "split02", clip, attr, 1, n, QGL_SW_DEPTH_ALWAYS, QGL_SW_CULL_NONE);
    for (int i = 0; i < W * W; i++)
        want[i] = fb->count[i] > 0;
    for (int m = 0; m < N_ALL_METHODS; m++) {
        test_draw(fb, all_methods[m], clip, attr, 1, n, QGL_SW_DEPTH_ALWAYS, QGL_SW_CULL_NONE);
        check_counts("wavy", all_methods[m], fb, want);
    }
    qgl_sw_fb_destroy(fb);
    free(clip);
    free(attr);
}

static void sphere(void)
{
    const char *text = "size 64 64\ncamera perspective 40 0.5 10\nlookat 0 0 3.5 0 0 0 0 1 0\n"
                       "attributes uv\ntexture checker 8 2\nsphere 10 12 1\n";
    char err[256];
    qgl_sw_scene *s;
    if (qgl_sw_scene_parse(text, "sphere", NULL, &s, err, sizeof err)) {
        CHECK(0, "scene: %s", err);
        return;
    }
    float *clip, *attr, *obj;
    qgl_sw_scene_arrays(s, 0, &clip, &attr, &obj);
    /* silhouette of the unit sphere seen from distance d: NDC radius f tan(asin(1/d)) */
    double f = 1 / tan(20 * 3.14159265358979323846 / 180), r = f * tan(asin(1 / 3.5)) * W / 2;
    /* the 12-gon of the equator is inscribed: its inner radius is r cos(pi/12) */
    double r_in = r * cos(3.14159265358979323846 / 12) - 1.0, r_out = r + 1.0;
    unsigned char want[W * W];
    for (int y = 0; y < W; y++)
        for (int x = 0; x < W; x++) {
            double d = hypot(x + 0.5 - W / 2.0, y + 0.5 - W / 2.0);
            want[y * W + x] = d < r_in ? 1 : d > r_out ? 0 : 2; /* 2: either */
        }
    qgl_sw_fb *fb = test_fb(W, W, 2);
    for (int m = 0; m < N_ALL_METHODS; m++) {
        test_draw(fb, all_methods[m], clip, attr, 2, s->nquads, QGL_SW_DEPTH_ALWAYS, QGL_SW_CULL_BACK);
        check_counts("sphere", all_methods[m], fb, want);
    }
    qgl_sw_fb_destroy(fb);
    free(clip);
    free(attr);
    free(obj);
    qgl_sw_scene_free(s);
}

int main(void)
{
    flat_grid();
    wavy_grid();
    sphere();
    return failures ? 1 : 0;
}
