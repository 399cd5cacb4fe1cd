/* render_test.h: small helpers shared by the render suite's tests (header-only, static). */
#ifndef QGL_RENDER_TEST_H
#define QGL_RENDER_TEST_H

#include <quadgl/quadgl.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;

#define CHECK(cond, ...)                                                     \
    do {                                                                     \
        if (!(cond)) {                                                       \
            failures++;                                                      \
            fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);             \
            fprintf(stderr, __VA_ARGS__);                                    \
            fprintf(stderr, "\n");                                           \
        }                                                                    \
    } while (0)

static const char *const all_methods[] = {"split02",  "split13",  "mvc",        "mvc64",    "bilinear:4",
                                          "adaptive", "invbilinear", "projective", "exact", "mvcplane",
                                          "mvcpatch", "invbilinearplane", "mvcgrid:4", "mvcgrid:16"};
#define N_ALL_METHODS ((int)(sizeof all_methods / sizeof all_methods[0]))

/* A framebuffer of nattr channels with depth, counts and facing. */
static inline qgl_sw_fb *test_fb(int w, int h, int channels)
{
    qgl_sw_fb_desc fd = {.width = w, .height = h, .channels = channels, .with_count = 1, .with_facing = 1};
    qgl_sw_fb *fb = qgl_sw_fb_create(&fd);
    if (!fb) {
        fprintf(stderr, "cannot create framebuffer\n");
        exit(1);
    }
    return fb;
}

/* Clear and draw quads with a method given by name; returns qgl_sw_draw's code. */
static inline int test_draw(qgl_sw_fb *fb, const char *method, const float *clip, const float *attr, int nattr,
                     int nquads, qgl_sw_depth depth, qgl_sw_cull cull)
{
    qgl_sw_draw_desc d = {.nquads = nquads, .nattr = nattr, .clip = clip, .attr = attr, .depth = depth,
                          .cull = cull};
    if (qgl_sw_method_parse(method, &d.method)) {
        fprintf(stderr, "bad method %s\n", method);
        exit(1);
    }
    qgl_sw_fb_clear(fb, NULL, 1.0f);
    return qgl_sw_draw(fb, &d, NULL);
}

/* Clip corner from an NDC position and a w (x, y scaled by w) and a z in NDC. */
static inline void clip_corner(float *c, double x, double y, double z, double w)
{
    c[0] = (float)(x * w);
    c[1] = (float)(y * w);
    c[2] = (float)(z * w);
    c[3] = (float)w;
}

/* Column-major m times (x, y, z, 1). */
static inline void transform(const double m[16], const double p[3], float out[4])
{
    for (int r = 0; r < 4; r++)
        out[r] = (float)(m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r]);
}

/* A perspective camera at (0, 0, dist) looking down -z: gluPerspective(fovy, 1, 0.1, 100). */
static inline void camera(double fovy_deg, double dist, double m[16])
{
    double f = 1 / tan(fovy_deg * 3.14159265358979323846 / 360), n = 0.1, fa = 100;
    memset(m, 0, 16 * sizeof(double));
    m[0] = f;
    m[5] = f;
    m[10] = (fa + n) / (n - fa);
    m[11] = -1;
    m[14] = 2 * fa * n / (n - fa) - dist * (fa + n) / (n - fa);
    m[15] = dist;
}

#endif
