/* libFuzzer target for the numeric core: weights, classification, membership, inverse bilinear,
 * the view-invariant weights.
 *
 * The first byte chooses how the rest becomes 4 clip corners and a point: raw IEEE doubles
 * (NaN, inf, subnormals, anything), small integers on a grid (equal corners, collinear
 * triples, points exactly on edges and vertices), or 16-bit mantissas with a shared binary
 * exponent plus a large offset (tiny quads far from the origin, huge ones). The same values
 * also feed the float entry point. Invariants are the documented contracts; a violation
 * executes __builtin_trap() so libFuzzer records the input (abort() would be a handled exit
 * in some configurations). */
#include <quadgl/quadgl.h>

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#define REQUIRE(cond)                                                                               \
    do {                                                                                           \
        if (!(cond))                                                                               \
            __builtin_trap();                                                                      \
    } while (0)

typedef struct reader {
    const uint8_t *p;
    size_t n;
} reader;

static uint64_t take(reader *r, int bytes)
{
    uint64_t v = 0;
    for (int i = 0; i < bytes; i++) {
        v = (v << 8) | (r->n ? *r->p : 0);
        if (r->n) {
            r->p++;
            r->n--;
        }
    }
    return v;
}

static double raw_double(reader *r)
{
    uint64_t bits = take(r, 8);
    double d;
    memcpy(&d, &bits, sizeof d);
    return d;
}

/* 18 values: clip[4][4] then the point (x, y). */
static void decode(reader *r, double val[18])
{
    int mode = (int)(take(r, 1) % 3);
    if (mode == 0) {
        for (int i = 0; i < 18; i++)
            val[i] = raw_double(r);
    } else if (mode == 1) {
        for (int i = 0; i < 18; i++)
            val[i] = (double)(int8_t)take(r, 1) / 8.0; /* grid of 1/8: exact edge hits */
    } else {
        int e = (int)(take(r, 1) % 256) - 128;
        double off = ldexp((double)(int8_t)take(r, 1), (int)(take(r, 1) % 64));
        for (int i = 0; i < 18; i++) {
            double m = ldexp((double)(int16_t)take(r, 2), e);
            int is_w = i < 16 && i % 4 == 3;
            val[i] = is_w ? 1 + ldexp((double)(int8_t)take(r, 1), -7) : off + m;
        }
    }
}

static int all_finite(const double *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

static int all_finite_f(const float *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

static int valid_rc(int rc)
{
    return rc == QGL_INSIDE || rc == QGL_OUTSIDE || rc == QGL_DEGENERATE || rc == QGL_NONFINITE;
}

static void check_weights(const double clip[4][4], double x, double y, int finite)
{
    double persp[4], screen[4];
    int rc = qgl_weights(clip, x, y, persp, screen);
    REQUIRE(valid_rc(rc));
    REQUIRE((rc == QGL_NONFINITE) == !finite);
    REQUIRE(all_finite(persp, 4) && all_finite(screen, 4));
    if (rc == QGL_NONFINITE)
        for (int i = 0; i < 4; i++)
            REQUIRE(persp[i] == 0.25 && screen[i] == 0.25);
    int wpos = clip[0][3] > 0 && clip[1][3] > 0 && clip[2][3] > 0 && clip[3][3] > 0;
    if (rc == QGL_INSIDE) {
        double sp = 0, ss = 0;
        for (int i = 0; i < 4; i++) {
            REQUIRE(persp[i] >= -1e-9);
            sp += persp[i];
            ss += screen[i];
            if (wpos)
                REQUIRE(screen[i] >= -1e-9);
        }
        REQUIRE(fabs(sp - 1) <= 1e-9);
        if (wpos)
            REQUIRE(fabs(ss - 1) <= 1e-9);
    }
    /* screen may be NULL */
    REQUIRE(qgl_weights(clip, x, y, persp, NULL) == rc);
}

static void check_weightsf(const double clip[4][4], double x, double y)
{
    float c[4][4], persp[4], screen[4];
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++)
            c[i][k] = (float)clip[i][k];
    float fx = (float)x, fy = (float)y;
    int finite = all_finite_f(&c[0][0], 16) && isfinite(fx) && isfinite(fy);
    int rc = qgl_weightsf(c, fx, fy, persp, screen);
    REQUIRE(valid_rc(rc));
    REQUIRE((rc == QGL_NONFINITE) == !finite);
    REQUIRE(all_finite_f(persp, 4) && all_finite_f(screen, 4));
    if (rc == QGL_INSIDE) {
        float sp = 0;
        for (int i = 0; i < 4; i++) {
            REQUIRE(persp[i] >= -1e-4f);
            sp += persp[i];
        }
        REQUIRE(fabsf(sp - 1) <= 1e-4f);
    }
}

static void check_cover(const qgl_cover *c, int rc, int finite)
{
    REQUIRE((rc == QGL_NONFINITE) == !finite);
    if (rc == QGL_NONFINITE) {
        REQUIRE(c->ntri == 0);
        return;
    }
    REQUIRE(rc >= QGL_QUAD_CONVEX && rc <= QGL_QUAD_DEGENERATE && (int)c->kind == rc);
    REQUIRE(isfinite(c->cross[0]) && isfinite(c->cross[1]) && isfinite(c->cross_t));
    switch (rc) {
    case QGL_QUAD_CONVEX:
        REQUIRE((c->ntri == 1 || c->ntri == 2) && (c->orientation == 1 || c->orientation == -1));
        REQUIRE(c->reflex == -1 && c->cross_edge == -1);
        break;
    case QGL_QUAD_CONCAVE:
        REQUIRE(c->ntri == 2 && c->reflex >= 0 && c->reflex < 4 && c->orientation != 0);
        break;
    case QGL_QUAD_BOWTIE:
        REQUIRE(c->ntri == 2 && (c->cross_edge == 0 || c->cross_edge == 1) && c->orientation == 0);
        REQUIRE(c->cross_t >= 0 && c->cross_t <= 1);
        break;
    default: /* external, degenerate: nothing to emit here */
        REQUIRE(c->ntri == 0);
    }
    for (int k = 0; k < c->ntri; k++) {
        int used[5] = {0};
        for (int j = 0; j < 3; j++) {
            int idx = c->tri[k][j];
            REQUIRE(idx < 4 || (idx == 4 && rc == QGL_QUAD_BOWTIE));
            REQUIRE(!used[idx]);
            used[idx] = 1;
        }
    }
}

static void check_geometry(const double clip[4][4], double x, double y, int finite)
{
    qgl_cover c;
    check_cover(&c, qgl_classify_clip(clip, &c), finite);
    double v[4][2];
    for (int i = 0; i < 4; i++) {
        v[i][0] = clip[i][0];
        v[i][1] = clip[i][1];
    }
    int f2 = all_finite(&v[0][0], 8);
    int rc = qgl_classify(v, &c);
    check_cover(&c, rc, f2);
    REQUIRE(rc != QGL_QUAD_EXTERNAL);
    int in = qgl_inside(v, x, y);
    REQUIRE(in >= -1 && in <= 1);
    double uv[2];
    int ib = qgl_inv_bilinear(v, x, y, uv);
    REQUIRE(ib == 0 || ib == 1 || ib == QGL_NONFINITE);
    REQUIRE(isfinite(uv[0]) && isfinite(uv[1]));
    REQUIRE((ib == QGL_NONFINITE) == !(f2 && isfinite(x) && isfinite(y)));
}

/* The view-invariant weights, with the clip corners' x, y, z as object corners and (x, y, z0)
 * as the surface point: finite outputs, the documented codes, a partition of unity inside. */
static void check_plane(const double clip[4][4], double x, double y, int finite)
{
    double pos[4][3], p[3] = {x, y, clip[0][2]}, lam[4];
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            pos[i][k] = clip[i][k];
    qgl_plane pl;
    int fr = qgl_plane_frame(pos, &pl);
    REQUIRE(fr == 0 || fr == QGL_DEGENERATE || fr == QGL_NONFINITE);
    REQUIRE(all_finite(&pl.corner[0][0], 8) && all_finite(pl.height, 4) && all_finite(pl.origin, 3));
    int rc = qgl_weights_plane(pos, p, lam);
    REQUIRE(valid_rc(rc));
    REQUIRE(all_finite(lam, 4));
    REQUIRE((rc == QGL_NONFINITE) == !finite);
    if (rc == QGL_INSIDE) {
        double sum = 0;
        for (int i = 0; i < 4; i++) {
            REQUIRE(lam[i] >= -1e-9);
            sum += lam[i];
        }
        REQUIRE(fabs(sum - 1) <= 1e-9);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    reader r = {data, size};
    double val[18], clip[4][4];
    decode(&r, val);
    memcpy(clip, val, sizeof clip);
    double x = val[16], y = val[17];
    int finite = all_finite(val, 18);
    check_weights(clip, x, y, finite);
    check_weightsf(clip, x, y);
    check_geometry(clip, x, y, all_finite(val, 16));
    int obj_finite = isfinite(x) && isfinite(y);
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            obj_finite = obj_finite && isfinite(clip[i][k]);
    check_plane(clip, x, y, obj_finite);
    return 0;
}
