/* draw.c: draw a batch of captured quads: read the GL state, plan each quad, run the paths.
 *
 * The state is read once per batch (state.c: matrices, viewport, shade model, the
 * fixed-function key) and decides whether the shader path can reproduce it ("modelled").
 * Each quad is then planned:
 * polygon mode line/point, select/feedback render modes and the application's own programs
 * (GLSL, ARB, a pipeline: nothing of ours can run them) go to the driver as quads; in
 * AUTO a quad the diagonal split renders exactly (planar, attributes affine in object space)
 * or invisibly (bounding box under invisible_area_px, or a planar quad whose split differs from
 * the mean value interpolation by less than the output can show: split_invisible below) is
 * split by the driver; the rest takes the shader path when the state is modelled and the CPU
 * subdivision otherwise. A short run of such split quads next to shader-path quads joins
 * their run (the same picture, one draw fewer). Smooth
 * lighting is exact too where it reads no position (directional lights, infinite viewer),
 * corners with equal normals and colours group along parallel edges (a cylinder's quads, a
 * billboard's one normal) and the texture and fog coordinates are affine: the lit colour is
 * then affine over the quad. A retained batch (retain.c) brings these per-quad
 * facts precomputed, and skips everything when they make every quad the driver's. Quads are
 * drawn in their original order, as runs of consecutive quads sharing a path (blending and
 * equal depths make order visible). All vertices are uploaded once into our own buffer,
 * behind our own vertex array object; afterwards the program, the bindings, the client
 * active texture and the current values of every attribute we streamed are restored. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../core/core_util.h"
#include "gl_internal.h"

size_t qgl__nquads(qgl_topology topo, size_t n)
{
    if (topo == QGL_QUADS)
        return n / 4;
    return n >= 4 ? (n - 2) / 2 : 0;
}

size_t qgl__corner(qgl_topology topo, size_t q, int c)
{
    static const int strip[4] = {0, 1, 3, 2};
    return topo == QGL_QUADS ? 4 * q + (size_t)c : 2 * q + (size_t)strip[c];
}

/* ---- planning --------------------------------------------------------------------------------- */

static void transform(const double m[16], const float p[4], double out[4])
{
    for (int r = 0; r < 4; r++)
        out[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r] * p[3];
}

/* Every vertex's clip position: the hot loop of planning many small quads. The matrix's
 * columns stay in registers and the four rows are one vector expression (the same sums, in
 * the same order, as transform: each lane is one row, with no contraction), which the
 * compiler left scalar, the inner loop rolled, when written per row. */
typedef double qgl__v4d __attribute__((vector_size(32)));

#if defined(__x86_64__) && defined(__GNUC__) && defined(__has_attribute)
#if __has_attribute(target_clones)
__attribute__((target_clones("avx2", "default")))
#endif
#endif
static void transform_all(const double m[16], const float *p, size_t n, double *out)
{
    qgl__v4d c[4];
    memcpy(c, m, sizeof c);
    for (size_t i = 0; i < n; i++, p += 4, out += 4) {
        qgl__v4d r = c[0] * (double)p[0] + c[1] * (double)p[1] + c[2] * (double)p[2] + c[3] * (double)p[3];
        memcpy(out, &r, sizeof r);
    }
}


/* Attributes per corner the affinity test may see: colour, secondary, fog, 4 units. */
#define QGL__ATTR_MAX (4 + 3 + 1 + 4 * QGL_MAX_TEXUNITS)

static int ensure(void **p, size_t *cap, size_t n, size_t elem)
{
    if (n <= *cap)
        return 1;
    size_t c = n > 2 * *cap ? n : 2 * *cap;
    void *q = realloc(*p, c * elem);
    if (!q)
        return 0;
    *p = q;
    *cap = c;
    return 1;
}

/* The corners on screen (every w > 0), in pixels from the viewport's centre: what the
 * bounding box and the gain's samples measure. */
static void pixel_corners(const double *clip[4], const GLint vp[4], double px[4][2])
{
    double hx = 0.5 * vp[2], hy = 0.5 * vp[3];
    for (int i = 0; i < 4; i++) {
        double inv = 1.0 / clip[i][3];
        px[i][0] = clip[i][0] * inv * hx, px[i][1] = clip[i][1] * inv * hy;
    }
}

/* Bounding box of the projected quad, in pixels squared. */
static double bbox_area_px(const double px[4][2])
{
    double x0 = px[0][0], x1 = x0, y0 = px[0][1], y1 = y0;
    for (int i = 1; i < 4; i++) { /* comparisons, not fmin/fmax: those are library calls here */
        double x = px[i][0], y = px[i][1];
        x0 = x < x0 ? x : x0, x1 = x > x1 ? x : x1, y0 = y < y0 ? y : y0, y1 = y > y1 ? y : y1;
    }
    return (x1 - x0) * (y1 - y0);
}

/* The attributes that reach the picture (QGL__A_* bits among mask), for the affinity test:
 * the colours when smooth and unlit (primary, and secondary under colour sum), every
 * textured unit's coordinates (texgen, where on, is linear in the position: affine), the fog
 * coordinate when it is fog's source; with a state the shader path does not model, every
 * captured attribute. */
static unsigned attribs_read(const qgl__state *st, unsigned mask)
{
    const qgl__key *key = &st->ffp;
    int smooth = st->shade_model != GL_FLAT, all = !st->modelled;
    unsigned m = 0;
    if (smooth)
        m |= QGL__A_COLOR;
    if ((smooth && (key->flags & QGL__KF_COLOR_SUM)) || all)
        m |= QGL__A_COLOR2;
    if ((key->fog && !(key->flags & QGL__KF_FOG_DEPTH)) || all)
        m |= QGL__A_FOG;
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
        if (key->unit[u].target || all)
            m |= QGL__A_TEX0 << u;
    return m & mask;
}

/* Whether the pipeline clamps attribute a to [0, 1] at each vertex before interpolating it
 * (the colours): values affine as given can then reach the split, or the smooth path,
 * unaffine, as colours of 0, 1, 2 and 1 clamped to 0, 1, 1 and 1. */
static int clamped(int a)
{
    return a == QGL__AT_COLOR || a == QGL__AT_COLOR2;
}

/* Whether n floats are the same to the bit (memcmp's verdict, without a call for a few). */
static inline int same_bits(const float *a, const float *b, int n)
{
    if (n == 4) /* a colour or texture coordinates: two loads a side, inline */
        return !memcmp(a, b, 4 * sizeof *a);
    if (n == 3)
        return !memcmp(a, b, 3 * sizeof *a);
    for (int k = 0; k < n; k++) {
        uint32_t x, y;
        memcpy(&x, a + k, sizeof x), memcpy(&y, b + k, sizeof y);
        if (x != y)
            return 0;
    }
    return 1;
}

/* Whether every attribute that reaches the picture is the same at the four corners, as
 * captured (equal inputs give equal values after any texture matrix). */
static int attribs_constant(const qgl__verts *v, unsigned read, const size_t idx[4])
{
    for (unsigned bits = read; bits; bits &= bits - 1) {
        int a = __builtin_ctz(bits), k = qgl__attribs[a].floats;
        const float *f = v->attr[a];
        for (int c = 1; c < 4; c++)
            if (!same_bits(f + (size_t)k * idx[0], f + (size_t)k * idx[c], k))
                return 0;
    }
    return 1;
}

/* On a planar quad with affine dependency m (sum m_i p_i = 0, sum m_i = 0: m_i is the signed
 * area of the triangle of the other three corners), whether the attributes of read are affine
 * by qgl_split_is_exact's rule at 1e-5: the corner of largest |m_i|, whose opposite triangle
 * is the best conditioned, predicted from the other three by barycentrics -m_j / m_i. Its
 * values only, with no geometry again. Texture coordinates are judged before their texture
 * matrix (a linear map keeps affine coordinates affine). */
static int values_affine(const double m[4], const qgl__verts *v, unsigned read, const size_t idx[4])
{
    int i = 0;
    for (int c = 1; c < 4; c++)
        i = fabs(m[c]) > fabs(m[i]) ? c : i;
    size_t i1 = idx[(i + 1) & 3], i2 = idx[(i + 2) & 3], i3 = idx[(i + 3) & 3];
    double b1 = -m[(i + 1) & 3] / m[i], b2 = -m[(i + 2) & 3] / m[i], b3 = -m[(i + 3) & 3] / m[i];
    double bsum = fabs(b1) + fabs(b2) + fabs(b3);
    for (unsigned bits = read; bits; bits &= bits - 1) {
        int a = __builtin_ctz(bits), k = qgl__attribs[a].floats, clamp = clamped(a);
        const float *f0 = v->attr[a] + (size_t)k * idx[i], *f1 = v->attr[a] + (size_t)k * i1;
        const float *f2 = v->attr[a] + (size_t)k * i2, *f3 = v->attr[a] + (size_t)k * i3;
        if (same_bits(f0, f1, k) && same_bits(f0, f2, k) && same_bits(f0, f3, k))
            continue; /* one value (a glyph's colour), constant as attribs_constant judges it */
        for (int j = 0; j < k; j++) {
            double c0 = f0[j], c1 = f1[j], c2 = f2[j], c3 = f3[j];
            if (clamp)
                c0 = qgl__clamp01(c0), c1 = qgl__clamp01(c1), c2 = qgl__clamp01(c2), c3 = qgl__clamp01(c3);
            double pred = b1 * c1 + b2 * c2 + b3 * c3;
            if (pred - c0 == 0) /* most: equal values, or a grid's steps (infinities: NaN, not 0) */
                continue;
            if (!qgl__value_affine(c0, c1, c2, c3, pred, bsum, 1e-5))
                return 0;
        }
    }
    return 1;
}

/* A parallelogram's dependency: its diagonals halve each other. */
static const double parallel_m[4] = {0.5, -0.5, 0.5, -0.5};

/* For a shortcut whose verdict the later tests reach as well, which only saves time where it
 * passes (a colour map's cells seldom pass the parallelogram's affinity test, random corner
 * colours never its invisible split): where fewer than one in eight passed lately, only one
 * quad in 16 tries it, so that the rate follows the scene. */
static int worth_trying(qgl__rate *r)
{
    return 8 * r->passed >= r->tested || (r->skipped++ & 15) == 0;
}

/* One more result of a test into its recent rate, halved past window tests. */
static void rate_note(qgl__rate *r, int passed, unsigned window)
{
    r->tested++, r->passed += (unsigned)passed;
    if (r->tested >= window)
        r->tested /= 2, r->passed /= 2;
}

static int parallel_attribs(qgl_context *ctx, const qgl__verts *v, unsigned read, const size_t idx[4])
{
    int ok = values_affine(parallel_m, v, read, idx);
    rate_note(&ctx->par_rate, ok, 256);
    return ok;
}

/* The batch's attributes that reach the picture (ctx->plan_read) per corner, texture
 * coordinates after their unit's texture matrix. */
static int gather_attribs(const qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4],
                          double *attr)
{
    unsigned read = ctx->plan_read;
    int n = 0;
    for (int c = 0; c < 4; c++) {
        double *a = attr + c * QGL__ATTR_MAX;
        int k = 0;
        for (unsigned bits = read; bits; bits &= bits - 1) {
            int b = __builtin_ctz(bits), f = qgl__attribs[b].floats, u = qgl__attribs[b].unit;
            const float *src = v->attr[b] + (size_t)f * idx[c];
            if (u < 0) {
                for (int j = 0; j < f; j++)
                    a[k++] = clamped(b) ? qgl__clamp01(src[j]) : src[j];
                continue;
            }
            double t[4];
            transform(st->ffp.unit[u].target ? st->xf.texmat[u] : qgl__identity, src, t);
            for (int j = 0; j < 4; j++)
                a[k++] = t[j];
        }
        n = k;
    }
    return n;
}

static int split_invisible(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4],
                           const double *clip[4], const double px[4][2], const double p[4][3]);

/* Whether the split draws the quad as the smooth path would: exactly, or (invisible set) by
 * split_invisible's bound, which is tried before the affinity test, being cheaper where it
 * passes. */
static int split_is_exact(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4],
                          const double *clip[4], const double px[4][2], const double p[4][3], int invisible,
                          int *planar)
{
    double attr[4 * QGL__ATTR_MAX], packed[4 * QGL__ATTR_MAX];
    *planar = qgl__planar(p);
    if (!*planar || st->nonaffine)
        return 0;
    /* nothing varies over the quad (a flat-coloured face: the commonest case), or on a
     * parallelogram (a glyph, a grid cell) every value is affine: the later tests' verdict */
    unsigned read = ctx->plan_read;
    if (*planar == 2 ? worth_trying(&ctx->par_rate) && parallel_attribs(ctx, v, read, idx) : attribs_constant(v, read, idx))
        return 1;
    if (invisible && split_invisible(ctx, st, v, idx, clip, px, p))
        return 1;
    int n = gather_attribs(ctx, st, v, idx, attr);
    for (int c = 0; c < 4; c++)
        for (int k = 0; k < n; k++)
            packed[c * n + k] = attr[c * QGL__ATTR_MAX + k];
    return qgl_split_is_exact(p, packed, n, 1e-5);
}

/* What smooth lighting reads at a vertex besides its position (and a material): corners equal
 * in these light alike. A normal-based texgen reads the normal too. The other attributes (texture
 * and fog coordinates) pass on to the picture through affine maps. */
enum { LIGHT_INPUTS = QGL__A_NORMAL | QGL__A_COLOR | QGL__A_COLOR2 };

/* Whether corners i and j carry the same lighting inputs, and the same material where asked:
 * compared in place, the first difference ending it. */
static int same_inputs(const qgl__verts *v, size_t i, size_t j, int materials)
{
    for (unsigned bits = v->mask & LIGHT_INPUTS; bits; bits &= bits - 1) {
        int a = __builtin_ctz(bits), n = qgl__attribs[a].floats;
        if (!same_bits(v->attr[a] + (size_t)n * i, v->attr[a] + (size_t)n * j, n))
            return 0;
    }
    return !(materials && (v->mask & QGL__A_MATERIAL)) ||
           same_bits(v->mat + QGL__MATERIAL_FLOATS * i, v->mat + QGL__MATERIAL_FLOATS * j, QGL__MATERIAL_FLOATS);
}

/* QGL__F_GROUPED: corners with equal lighting inputs are grouped; a per-vertex function of
 * those inputs is a combination of the groups' indicators (1 on the group, 0 elsewhere), so it
 * is affine whenever they all are. Two corners sharing a normal on each long side of a
 * cylinder's quad, and a billboard's one normal and colour, are the common cases: smooth
 * lighting is then exactly the split. */
static int quad_grouped(const qgl__verts *v, const size_t idx[4], const double p[4][3], int materials)
{
    int group[4], ngroups = 0;
    for (int c = 0; c < 4; c++) {
        group[c] = ngroups;
        for (int d = 0; d < c; d++)
            if (same_inputs(v, idx[c], idx[d], materials)) {
                group[c] = group[d];
                break;
            }
        if (group[c] == ngroups)
            ngroups++;
    }
    if (ngroups == 1)
        return 1;
    if (ngroups == 4)
        return 0; /* a lone corner's indicator is never affine on a quad with an interior */
    double ind[4 * 3];
    for (int c = 0; c < 4; c++)
        for (int g = 0; g < ngroups; g++)
            ind[c * ngroups + g] = group[c] == g;
    return qgl_split_is_exact(p, ind, ngroups, 1e-5);
}

/* Whether corners with diagonals d02, d13 and first edge d01 form an exact parallelogram of
 * nonzero, finite area; n the diagonals' cross product and n2 its squared length either way. */
static inline int true_parallelogram(const double d02[3], const double d13[3], const double d01[3], double n[3],
                                     double *n2)
{
    n[0] = d02[1] * d13[2] - d02[2] * d13[1];
    n[1] = d02[2] * d13[0] - d02[0] * d13[2];
    n[2] = d02[0] * d13[1] - d02[1] * d13[0];
    *n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    return qgl__parallelogram(d02, d13, d01) && *n2 > 0 && *n2 < INFINITY;
}

int qgl__planar(const double p[4][3])
{
    double d01[3], d02[3], d13[3], n[3], n2, big = 0, ext = 0;
    for (int k = 0; k < 3; k++)
        d01[k] = p[1][k] - p[0][k], d02[k] = p[2][k] - p[0][k], d13[k] = p[3][k] - p[1][k];
    if (true_parallelogram(d02, d13, d01, n, &n2))
        return 2; /* the test below passes it as well, at several times the cost */
    for (int k = 0; k < 3; k++)
        for (int c = 0; c < 4; c++) {
            double a = fabs(p[c][k]), e = fabs(p[c][k] - p[0][k]);
            big = a > big ? a : big;
            ext = e > ext ? e : ext;
        }
    /* each coordinate is off by up to half an ulp; the diagonals' distance by a few of them */
    double tol = ext > 0 && 8 * FLT_EPSILON * big > 1e-6 * ext ? 8 * FLT_EPSILON * big / ext : 1e-6;
    double h = fabs(n[0] * d01[0] + n[1] * d01[1] + n[2] * d01[2]), nn = sqrt(n2);
    /* the distance between the diagonals' lines, h / nn, against tol times the extent; the
     * core's scaled form where these products leave the range of doubles */
    if (!(isfinite(h) && isfinite(nn) && nn > 1e-290 && ext < 1e75 && ext > 1e-75))
        return qgl_is_planar(p, tol);
    return h <= tol * ext * nn + 32 * DBL_EPSILON * ext * ext * ext;
}

/* Object-space corners (w > 0 each); 0 when a corner is at or behind infinity. */
static int object_corners(const qgl__verts *v, const size_t idx[4], double p[4][3])
{
    for (int c = 0; c < 4; c++) {
        const float *q = v->pos + 4 * idx[c];
        if (!(q[3] > 0))
            return 0;
        if (q[3] == 1) /* nearly always: three divisions saved */
            p[c][0] = q[0], p[c][1] = q[1], p[c][2] = q[2];
        else
            for (int k = 0; k < 3; k++)
                p[c][k] = q[k] / q[3];
    }
    return 1;
}

int qgl__external_planar(const qgl__verts *v, const size_t idx[4])
{
    double p[4][3], extent = 0, height = 0;
    qgl_plane pl;
    if (!object_corners(v, idx, p) || qgl_plane_frame(p, &pl) != 0)
        return 0;
    for (int c = 0; c < 4; c++) {
        extent = fmax(extent, hypot(pl.corner[c][0], pl.corner[c][1]));
        height = fmax(height, fabs(pl.height[c]));
    }
    return height <= 1e-5 * extent;
}

/* The attributes of bits (the normal aside) affine over the quad as the pipeline clamps them,
 * or absent: one test of them all. Texture coordinates are judged before their texture
 * matrix, which keeps affine coordinates affine. */
static int class_affine(const double p[4][3], const qgl__verts *v, unsigned bits, const size_t idx[4])
{
    double attr[4 * QGL__ATTR_MAX];
    int n = 0;
    bits &= v->mask & QGL__A_ATTRIBS & ~QGL__A_NORMAL;
    for (unsigned b = bits; b; b &= b - 1)
        n += qgl__attribs[__builtin_ctz(b)].floats;
    if (!n)
        return 1;
    for (int c = 0; c < 4; c++) {
        double *a = attr + c * n;
        for (unsigned b = bits; b; b &= b - 1) {
            int at = __builtin_ctz(b), f = qgl__attribs[at].floats;
            const float *src = v->attr[at] + (size_t)f * idx[c];
            for (int k = 0; k < f; k++)
                *a++ = clamped(at) ? qgl__clamp01(src[k]) : src[k];
        }
    }
    return qgl_split_is_exact(p, attr, n, 1e-5);
}

uint16_t qgl__quad_facts(const qgl__verts *v, qgl_topology topo, size_t q)
{
    size_t idx[4];
    double p[4][3];
    for (int c = 0; c < 4; c++)
        idx[c] = qgl__corner(topo, q, c);
    if (!object_corners(v, idx, p) || !qgl__planar(p))
        return 0;
    uint16_t f = QGL__F_PLANAR;
    f |= quad_grouped(v, idx, p, 1) ? QGL__F_GROUPED : 0;
    f |= class_affine(p, v, QGL__A_COLOR, idx) ? QGL__F_AFFINE << QGL__FC_COLOR : 0;
    f |= class_affine(p, v, QGL__A_COLOR2, idx) ? QGL__F_AFFINE << QGL__FC_COLOR2 : 0;
    f |= class_affine(p, v, QGL__A_FOG, idx) ? QGL__F_AFFINE << QGL__FC_FOG : 0;
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
        if (class_affine(p, v, QGL__A_TEX0 << u, idx))
            f |= (uint16_t)(QGL__F_AFFINE << (QGL__FC_TEX0 + u));
    return f;
}

/* The facts a quad needs under this state for its split to be exact (as gather_attribs
 * chooses the attributes that reach the picture). Texture coordinates are judged before
 * their texture matrix: a linear map keeps affine coordinates affine. */
static unsigned needed_facts(const qgl__state *st)
{
    const qgl__key *key = &st->ffp;
    int smooth = st->shade_model != GL_FLAT, all = !st->modelled;
    unsigned need = QGL__F_PLANAR;
    if (smooth)
        need |= QGL__F_AFFINE << QGL__FC_COLOR;
    if ((smooth && (key->flags & QGL__KF_COLOR_SUM)) || all)
        need |= QGL__F_AFFINE << QGL__FC_COLOR2;
    if ((key->fog && !(key->flags & QGL__KF_FOG_DEPTH)) || all)
        need |= QGL__F_AFFINE << QGL__FC_FOG;
    for (int u = 0; u < QGL_MAX_TEXUNITS; u++)
        if (key->unit[u].target || all)
            need |= QGL__F_AFFINE << (QGL__FC_TEX0 + u);
    return need;
}

/* Under smooth lighting (or a normal-based texgen) that reads no position, the colours are
 * the lighting's, affine where its inputs group; the attributes it passes on must be affine
 * as for an unlit quad. */
static int exact_by_facts(const qgl__state *st, unsigned need, unsigned f)
{
    if (st->nonaffine) {
        if (!st->lit_by_inputs)
            return 0;
        need = (need & ~(QGL__F_AFFINE << QGL__FC_COLOR | QGL__F_AFFINE << QGL__FC_COLOR2)) | QGL__F_GROUPED;
    }
    return (f & need) == need;
}

/* exact_by_facts' rule for a lit quad, tested now: the lighting inputs grouped, then the
 * attributes passed on affine (by their values alone on a parallelogram). */
static int lit_exact(const qgl_context *ctx, const qgl__verts *v, const size_t idx[4], const double p[4][3],
                     int planar, int materials)
{
    unsigned rest = ctx->plan_read & ~LIGHT_INPUTS;
    if (!quad_grouped(v, idx, p, materials))
        return 0;
    double m[4];
    if (planar == 2)
        return values_affine(parallel_m, v, rest, idx);
    if (qgl__affine_dependency(p, m)) /* convex: its area weights serve as the core's would */
        return values_affine(m, v, rest, idx);
    return class_affine(p, v, rest, idx);
}

/* Whether the split is exact, and whether the quad is planar: from the cached facts of a
 * retained batch, else tested now. Under per-vertex materials the split lights a quad with
 * one material, so its corners must have one. */
static int quad_exact(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4],
                      const double *clip[4], const double px[4][2], int invisible, const qgl__facts *facts, size_t q,
                      int *planar)
{
    int one_material = !st->pv_material || st->quad_materials || qgl__same_material(v, idx);
    double p[4][3];
    if (!object_corners(v, idx, p))
        return *planar = 0;
    if (facts) {
        *planar = facts->quad[q] & QGL__F_PLANAR;
        return one_material && (exact_by_facts(st, ctx->plan_need, facts->quad[q]) ||
                                (invisible && *planar && split_invisible(ctx, st, v, idx, clip, px, p)));
    }
    if (!one_material) {
        *planar = qgl__planar(p);
        return 0;
    }
    int exact = split_is_exact(ctx, st, v, idx, clip, px, p, invisible, planar);
    if (!exact && *planar && st->nonaffine && st->lit_by_inputs)
        exact = lit_exact(ctx, v, idx, p, *planar, !st->quad_materials); /* one material: no group by it */
    /* lit corners, not grouped: judged by their colours, which light.c computes */
    if (!exact && *planar && st->nonaffine && invisible && st->lit_cpu)
        exact = split_invisible(ctx, st, v, idx, clip, px, p);
    return exact;
}

/* ---- invisible splits: the split's error against the mean value interpolant ----------------
 *
 * Both interpolants are sums w_i(p) f_i of the corner values with weights summing to 1 (the
 * split's perspective-correct barycentrics of the triangle holding p, the mean value weights
 * of p's surface point in the quad's plane, which AUTO's smooth path draws). On a planar quad
 * both reproduce every attribute affine in object space, so their difference d(p) = w_split(p) - w_mvc(p) is orthogonal to those: d(p) = delta(p) n, n
 * the affine dependency of the corners (sum n_i c_i = 0 in clip space, sum n_i = 0). The error
 * of any attribute is then delta(p) (n . f): one geometric gain, max |delta|, times a residual
 * per attribute component, whatever the state does to the attribute linearly (texture
 * matrices). Both interpolants are linear on the edges (delta = 0 on the boundary), the split
 * adds a crease on its diagonal, so |delta| peaks inside, along the diagonals; it is sampled
 * at the diagonals' crossing, half-way from there to each corner, and at the centroids of the
 * four triangles the diagonals cut, for both diagonals (drivers differ in which they use), and
 * multiplied by SPLIT_SAFETY. Measured over 19 000 random planar convex quads in random
 * perspective (corner angles jittered by +-36 degrees, radii 0.3 to 1.3, near-triangles
 * included), a 121 x 121 grid's maximum was at most 1.65 times the sampled one for the
 * screen-space weights, and d(p) was parallel to n everywhere on it; for the in-plane weights
 * tests/core/test_plane measures the same ratio (below SPLIT_SAFETY). Sampling costs nine
 * weight evaluations, so a bound that needs none comes first: on a convex quad both weight
 * vectors lie in [0, 1], so |delta| <= 1 / max |n_i| (at most 2). The residuals over that
 * maximum do not depend on the scale of n, and a planar quad's n is the same in object space
 * as in clip space up to scale, so this bound needs no screen work at all: quads within the
 * budget by it (a smooth colour map on a fine mesh) are split at once, and quads more than 8
 * times over it (where the samples, which find about a quarter of it, could not pass) are not
 * sampled. */

/* The sampled maximum of |delta| times this bounds the true maximum (measured: see above). */
#define SPLIT_SAFETY 2.0
/* Colour budget: half an 8-bit level. Two values closer than that round to levels at most one
 * apart, and mostly to the same level. */
#define SPLIT_COLOUR (0.5 / 255)
/* Texture coordinate budget in texels of level 0 (mipmap levels have larger texels). With
 * linear filtering the sampled colour moves by at most the budget times the difference of
 * neighbouring texels: under 1/255 where neighbours differ by 32 levels or less (images,
 * gradients), up to 8 levels only at a hard black-to-white texel edge. With nearest filtering
 * a texel changes only for samples within the budget of a texel boundary: at most 1/32 of the
 * pixels per texel crossed, where the error peaks. */
#define SPLIT_TEXEL (1.0 / 32)

/* Perspective-correct barycentrics of (x, y) in the triangle tri of screen points v with clip
 * w, as the rasterizer interpolates; 0 for the corner outside it. */
static void triangle_weights(const double v[4][2], const double w[4], const int tri[3], double x, double y,
                             double out[4])
{
    double b[3], sum = 0;
    for (int k = 0; k < 3; k++) {
        const double *p = v[tri[(k + 1) % 3]], *q = v[tri[(k + 2) % 3]];
        b[k] = ((p[0] - x) * (q[1] - y) - (p[1] - y) * (q[0] - x)) / w[tri[k]];
        sum += b[k];
    }
    out[0] = out[1] = out[2] = out[3] = 0;
    for (int k = 0; k < 3; k++)
        out[tri[k]] = b[k] / sum;
}

/* The split's weights at (x, y) for the diagonal from corner a to a + 2. */
static void split_weights(const double v[4][2], const double w[4], int a, double x, double y, double out[4])
{
    int b = (a + 1) & 3, c = (a + 2) & 3, d = (a + 3) & 3;
    double ex = v[c][0] - v[a][0], ey = v[c][1] - v[a][1];
    double side_b = ex * (v[b][1] - v[a][1]) - ey * (v[b][0] - v[a][0]);
    double side_p = ex * (y - v[a][1]) - ey * (x - v[a][0]);
    const int tri_b[3] = {a, b, c}, tri_d[3] = {a, c, d};
    triangle_weights(v, w, side_p * side_b >= 0 ? tri_b : tri_d, x, y, out);
}

static double det3(const double *a, const double *b, const double *c)
{
    return a[0] * (b[1] * c[3] - b[3] * c[1]) - a[1] * (b[0] * c[3] - b[3] * c[0]) + a[3] * (b[0] * c[1] - b[1] * c[0]);
}

/* n, the null vector of the corners' clip (x, y, w) (cofactors), and its squared length; 0
 * when the quad has no extent on screen. It is left unnormalised: the gain's first bound is
 * the same for any scale of n, and most quads need no more. */
static double dependency(const double *clip[4], double n[4])
{
    n[0] = det3(clip[1], clip[2], clip[3]), n[1] = -det3(clip[0], clip[2], clip[3]);
    n[2] = det3(clip[0], clip[1], clip[3]), n[3] = -det3(clip[0], clip[1], clip[2]);
    double len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2] + n[3] * n[3];
    return len2 > 0 && len2 < INFINITY ? len2 : 0;
}

/* Whether the screen quad v is strictly convex: its diagonals cross inside both, at fractions
 * within (0.01, 0.99) of each; *t the fraction along the diagonal from corner 0, when asked
 * (a division, which most calls do not need). */
static int crossing(const double v[4][2], double *t)
{
    double d1x = v[2][0] - v[0][0], d1y = v[2][1] - v[0][1], d2x = v[3][0] - v[1][0], d2y = v[3][1] - v[1][1];
    double den = d1x * d2y - d1y * d2x, rx = v[1][0] - v[0][0], ry = v[1][1] - v[0][1];
    double a = rx * d2y - ry * d2x, b = rx * d1y - ry * d1x;
    if (den < 0)
        den = -den, a = -a, b = -b;
    if (!(den > 0 && a > 0.01 * den && a < 0.99 * den && b > 0.01 * den && b < 0.99 * den))
        return 0;
    if (t)
        *t = a / den;
    return 1;
}

/* The sample points: the diagonals' crossing, half-way from it to each corner, the centroids
 * of the triangles it forms with each edge (v strictly convex). */
static void gain_samples(const double v[4][2], double pts[9][2])
{
    double t = 0.5;
    crossing(v, &t);
    double cx = v[0][0] + t * (v[2][0] - v[0][0]), cy = v[0][1] + t * (v[2][1] - v[0][1]);
    pts[0][0] = cx, pts[0][1] = cy;
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        pts[1 + i][0] = 0.5 * (cx + v[i][0]), pts[1 + i][1] = 0.5 * (cy + v[i][1]);
        pts[5 + i][0] = (cx + v[i][0] + v[j][0]) / 3, pts[5 + i][1] = (cy + v[i][1] + v[j][1]) / 3;
    }
}

/* AUTO's smooth weights at a screen point: the in-plane weights of the surface point there,
 * which the split's weights sp at that point (either diagonal: the quad is planar) put in the
 * plane. */
static int plane_weights(const qgl_plane *pl, const double sp[4], double out[4])
{
    double xy[2] = {0, 0};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 2; k++)
            xy[k] += sp[i] * pl->corner[i][k];
    return qgl_weights_inplane(pl, xy[0], xy[1], out);
}

/* Whether the sampled gain max |delta| times SPLIT_SAFETY stays within limit, for n of squared
 * length len2 and limit from that n (qgl__gain_limit). The screen corners v are in pixels, as
 * the shader path weighs (the dependency in clip space is the same). The crossing comes first:
 * most quads that fail, fail there, after one weight evaluation. */
static int gain_within(const double v[4][2], const double *clip[4], const double n[4], double len2, double limit,
                       const double obj[4][3])
{
    qgl_plane pl; /* the samples need AUTO's in-plane weights */
    if (!crossing(v, NULL) || qgl_plane_frame(obj, &pl) != 0)
        return 0;
    /* |delta| / |n| <= limit |n| for the unit-length gain against the unit-length limit */
    limit *= len2 / SPLIT_SAFETY;
    double w[4] = {clip[0][3], clip[1][3], clip[2][3], clip[3][3]}, pts[9][2];
    gain_samples(v, pts);
    for (int k = 0; k < 9; k++) {
        double mvc[4], sp[4];
        split_weights(v, w, 0, pts[k][0], pts[k][1], sp);
        if (plane_weights(&pl, sp, mvc) != QGL_INSIDE)
            return 0;
        for (int a = 0; a < 2; a++) {
            split_weights(v, w, a, pts[k][0], pts[k][1], sp);
            double delta = 0;
            for (int i = 0; i < 4; i++)
                delta += (sp[i] - mvc[i]) * n[i];
            if (!(fabs(delta) <= limit))
                return 0;
        }
    }
    return 1;
}

/* Largest |n . (f - a)| over the values a that f takes on the quad (between its corners'
 * smallest and largest value f[c]), sn = sum n; for a planar quad (sum n = 0) this is |n . f|. */
static inline double range_residual(const double n[4], double sn, const double f[4])
{
    double r = n[0] * f[0] + n[1] * f[1] + n[2] * f[2] + n[3] * f[3];
    if (sn == 0) /* the offsets vanish (an infinite value then counts, as it should) */
        return fabs(r);
    double lo = f[0] < f[1] ? f[0] : f[1], hi = f[0] < f[1] ? f[1] : f[0];
    lo = f[2] < lo ? f[2] : lo, hi = f[2] > hi ? f[2] : hi;
    lo = f[3] < lo ? f[3] : lo, hi = f[3] > hi ? f[3] : hi;
    double a = fabs(r - sn * lo), b = fabs(r - sn * hi);
    return a > b ? a : b;
}

/* Largest residual over the components of an attribute (size floats per vertex at a), values
 * clamped to [0, 1] where the pipeline clamps them (colours). */
static double residual(const double n[4], double sn, const float *a, int size, const size_t idx[4], int clamp)
{
    double worst = 0;
    const float *cn[4] = {a + (size_t)size * idx[0], a + (size_t)size * idx[1], a + (size_t)size * idx[2],
                          a + (size_t)size * idx[3]};
    for (int k = 0; k < size; k++) {
        double f[4] = {cn[0][k], cn[1][k], cn[2][k], cn[3][k]};
        if (clamp)
            f[0] = qgl__clamp01(f[0]), f[1] = qgl__clamp01(f[1]), f[2] = qgl__clamp01(f[2]), f[3] = qgl__clamp01(f[3]);
        double r = range_residual(n, sn, f);
        worst = r > worst ? r : worst;
    }
    return worst;
}

/* Unit u's texel residual: its coordinates after the texture matrix, whose q must be one
 * positive constant over the quad (s/q then errs by the residual of s over q), in texels of
 * level 0; INFINITY for generated coordinates and cube maps (not judged). */
static double texel_residual(const qgl__state *st, const qgl__verts *v, const size_t idx[4], const double n[4],
                             double sn, int u)
{
    const qgl__unit_key *uk = &st->ffp.unit[u];
    if (uk->target == QGL__T_CUBE || uk->gen[0] || uk->gen[1] || uk->gen[2] || uk->gen[3])
        return INFINITY;
    if (!(v->mask & (QGL__A_TEX0 << u)))
        return 0; /* the current coordinates: constant */
    double t[4][4];
    for (int c = 0; c < 4; c++) {
        const float *s = v->tex[u] + 4 * idx[c];
        if (st->xf.texmat_identity & (1u << u))
            t[c][0] = s[0], t[c][1] = s[1], t[c][2] = s[2], t[c][3] = s[3];
        else
            transform(st->xf.texmat[u], s, t[c]);
        if (!(t[c][3] > 0) || fabs(t[c][3] - t[0][3]) > 1e-6 * t[0][3])
            return INFINITY;
    }
    int dims = uk->target == QGL__T_1D ? 1 : uk->target == QGL__T_3D ? 3 : 2;
    double worst = 0;
    for (int k = 0; k < dims; k++) {
        double f[4] = {t[0][k], t[1][k], t[2][k], t[3][k]};
        double e = range_residual(n, sn, f) / t[0][3] * st->texsize[u][k];
        worst = e > worst ? e : worst;
    }
    return worst;
}

/* The largest gain within the budgets above scaled by the context's split_error, for colours
 * (primary, secondary under colour sum, and the fog factor from the fog coordinate, whose
 * errors add in the output colour) and each unit's texture coordinates: the budgets over
 * the residuals along n. Only for states that the shader path models and whose per-vertex
 * work is affine in the attributes or is smooth lighting: both paths then interpolate the
 * corners' lit colours, which light.c computes (the primary and the separate specular colour
 * add up; under two-sided lighting the worse face counts). COMBINE arithmetic (scales, dot
 * products) may magnify a difference, so it is not judged (0). */
double qgl__gain_limit(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4],
                       const double n[4])
{
    double scale = ctx->split_error > 0 ? ctx->split_error : 1.0;
    if (ctx->split_error < 0 || !st->modelled || ((st->nonaffine || st->pv_material) && !st->lit_cpu))
        return 0;
    int smooth = st->shade_model != GL_FLAT;
    double colour = 0, sn = n[0] + n[1] + n[2] + n[3];
    if (st->lit_cpu) {
        float lit[2][4 * QGL__LIT_FLOATS];
        int faces = qgl__lit_colours(ctx, st, v, idx, lit);
        if (!faces)
            return 0;
        for (int f = 0; f < faces; f++) { /* the primary and the separate specular colour add up */
            double pri = 0, sec = 0;
            for (int k = 0; k < QGL__LIT_FLOATS; k++) {
                double c[4];
                for (int i = 0; i < 4; i++)
                    c[i] = lit[f][QGL__LIT_FLOATS * i + k];
                double r = range_residual(n, sn, c);
                if (k < 4)
                    pri = fmax(pri, r);
                else
                    sec = fmax(sec, r);
            }
            colour = fmax(colour, pri + sec);
        }
    } else if ((v->mask & QGL__A_COLOR) && smooth)
        colour += residual(n, sn, v->col, 4, idx, 1);
    if ((v->mask & QGL__A_COLOR2) && smooth && (st->ffp.flags & QGL__KF_COLOR_SUM))
        colour += residual(n, sn, v->col2, 3, idx, 1);
    if ((v->mask & QGL__A_FOG) && st->fog_slope > 0)
        colour += residual(n, sn, v->fog, 1, idx, 0) * st->fog_slope;
    double limit = colour > 0 ? SPLIT_COLOUR * scale / colour : INFINITY;
    for (int u = 0; u < st->ffp.nunits; u++) {
        const qgl__unit_key *uk = &st->ffp.unit[u];
        if (!uk->target)
            continue;
        if (uk->env == QGL__E_COMBINE)
            return 0;
        double texels = texel_residual(st, v, idx, n, sn, u);
        if (texels > 0) {
            double l = SPLIT_TEXEL * scale / texels;
            limit = l < limit ? l : limit;
        }
    }
    return limit;
}

/* What judging a lit quad costs (lighting its corners, the gain's samples): about 500 ns here
 * (perf on peepers, whose quads mostly fail it). */
#define LIT_TEST_NS 500.0

/* Whether to leave a lit quad to the shader path untested: where the split's expected saving
 * on it (the calibrated costs of its pixels, times the rate at which the quads judged lately
 * passed) is below what judging it costs. One in 16 is judged all the same, so that the rate
 * follows the scene. The picture is right either way. */
static int skip_lit_test(qgl_context *ctx, double area_px)
{
    qgl__rate *r = &ctx->lit_rate;
    double rate = (r->passed + 1.0) / (r->tested + 2.0);
    return rate * qgl__split_saving(ctx, area_px) < LIT_TEST_NS && (r->skipped++ & 15) != 0;
}

/* Whether the split of a planar quad (every w > 0) shows the same pixels as the mean value
 * interpolation AUTO's smooth path draws (weighed in the quad's plane): the gain its samples
 * find within qgl__gain_limit along the corners' clip dependency. */
static int split_invisible(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4],
                           const double *clip[4], const double px[4][2], const double p[4][3])
{
    double n[4], m[4], limit = 0, len2 = 0;
    int lit = st->lit_cpu && (st->nonaffine || st->pv_material), invisible = 0, ok;
    if (lit && skip_lit_test(ctx, bbox_area_px(px)))
        return 0;
    float w0 = v->pos[4 * idx[0] + 3];
    if (v->pos[4 * idx[1] + 3] == w0 && v->pos[4 * idx[2] + 3] == w0 && v->pos[4 * idx[3] + 3] == w0)
        ok = qgl__affine_dependency(p, m); /* clip positions are one factor times M (p, 1) */
    else { /* the rasterizer weighs the corners by their own w: the dependency is the clip one */
        ok = (len2 = dependency(clip, m)) > 0 && crossing(px, NULL);
        memcpy(n, m, sizeof n);
    }
    if (ok && (limit = qgl__gain_limit(ctx, st, v, idx, m)) > 0) {
        /* the first bound, |delta| <= 1 / max |n_i| on a convex quad, for any scale of n:
         * from m, with no screen work where the corners share one w (most quads) */
        double nmax = 0;
        for (int i = 0; i < 4; i++)
            nmax = fabs(m[i]) > nmax ? fabs(m[i]) : nmax;
        if (limit * nmax >= 1)
            invisible = 1;
        else if (limit * nmax >= 0.125 && (len2 > 0 || (len2 = dependency(clip, n)) > 0)) {
            /* the samples (which find about a quarter of the bound: below an eighth they
             * could not pass), in clip space: n = s m there, and the limit is m's over |s| */
            double nm = 0, mm = 0;
            for (int i = 0; i < 4; i++)
                nm += n[i] * m[i], mm += m[i] * m[i];
            invisible = nm * nm >= 0.999 * len2 * mm && gain_within(px, clip, n, len2, limit * mm / fabs(nm), p);
        }
    }
    if (lit)
        rate_note(&ctx->lit_rate, invisible, 512);
    return invisible;
}

typedef float qgl__v4f __attribute__((vector_size(16)));
typedef int32_t qgl__v4i __attribute__((vector_size(16)));

/* c1 - c2 + c3 - c0 of four floats at each corner (texture coordinates), in doubles as
 * range_residual sums: the floats' differences are exact there, however large the values. */
static inline void parallel_diff4(const float *a, const size_t idx[4], double out[4])
{
    qgl__v4d f[4];
    for (int c = 0; c < 4; c++) {
        qgl__v4f x;
        memcpy(&x, a + 4 * idx[c], sizeof x);
        f[c] = __builtin_convertvector(x, qgl__v4d);
    }
    qgl__v4d d = f[1] - f[2] + f[3] - f[0];
    memcpy(out, &d, sizeof d);
}

/* parallel_residual of four colour components, in floats: clamped to [0, 1], the sum's
 * rounding (1e-7) is nothing against SPLIT_COLOUR. The largest magnitude is the largest as
 * integers (NaN's bits above infinity's, so NaN wins and fails every bound). */
static inline float parallel_colour4(const float *a, const size_t idx[4])
{
    const qgl__v4f zero = {0, 0, 0, 0}, one = {1, 1, 1, 1};
    const qgl__v4i magnitude = {INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX};
    qgl__v4f f[4];
    for (int c = 0; c < 4; c++) {
        memcpy(&f[c], a + 4 * idx[c], sizeof f[c]);
        qgl__v4i lo = f[c] < zero, hi = f[c] > one;
        f[c] = (qgl__v4f)(((qgl__v4i)f[c] & ~lo & ~hi) | ((qgl__v4i)one & hi));
    }
    qgl__v4i m = (qgl__v4i)(f[1] - f[2] + f[3] - f[0]) & magnitude;
    int32_t a01 = m[0] > m[1] ? m[0] : m[1], a23 = m[2] > m[3] ? m[2] : m[3], worst = a01 > a23 ? a01 : a23;
    float r;
    memcpy(&r, &worst, sizeof r);
    return r;
}

/* Largest |c1 - c2 + c3 - c0| over an attribute's components (size floats at a; four: the
 * primary colour), clamped where clamp says (always for four): on a parallelogram, whose
 * dependency is (1, -1, 1, -1) / 2, twice the residual range_residual finds. NaN where a value
 * is NaN. */
static double parallel_residual(const float *a, int size, const size_t idx[4], int clamp)
{
    if (size == 4)
        return parallel_colour4(a, idx);
    double worst = 0;
    for (int k = 0; k < size; k++) {
        double f[4];
        for (int c = 0; c < 4; c++) {
            f[c] = a[(size_t)size * idx[c] + (size_t)k];
            f[c] = clamp ? qgl__clamp01(f[c]) : f[c];
        }
        double d = f[1] - f[2] + f[3] - f[0];
        worst = fabs(d) > worst || d != d ? fabs(d) : worst;
    }
    return worst;
}

/* Whether split_invisible would judge a quad of this state by its residuals alone, with no
 * lighting, texture matrix or combiner between the captured values and the picture: the
 * batch's, worked out once (ctx->plan_fast). Lit quads that are not non-affine are flat
 * shaded: one colour each, and with one material each (quad_materials) nothing the
 * residuals leave out varies over the quad. */
static int parallel_state(const qgl_context *ctx, const qgl__state *st)
{
    if (ctx->method != QGL_METHOD_AUTO || ctx->split_error < 0 || !st->modelled || st->nonaffine ||
        (st->pv_material && !st->quad_materials) || st->lit_cpu)
        return 0;
    for (int u = 0; u < st->ffp.nunits; u++) {
        const qgl__unit_key *uk = &st->ffp.unit[u];
        if (uk->target && (uk->env == QGL__E_COMBINE || uk->target == QGL__T_CUBE || uk->gen[0] || uk->gen[1] ||
                           uk->gen[2] || uk->gen[3] || !(st->xf.texmat_identity & (1u << u))))
            return 0;
    }
    return 1;
}

/* split_invisible's first bound on a parallelogram (object corners p0 + p2 = p1 + p3 with one
 * w, every clip w > 0: convex on screen), taken before any screen or geometric work. Its
 * dependency is (1, -1, 1, -1) / 2, so |delta| <= 2 and the bound holds where the colours'
 * residuals add up to at most SPLIT_COLOUR and every unit's to at most SPLIT_TEXEL texels, in
 * parallel_residual's units. The values come first: random corner colours fail there, after a
 * few instructions. A quad this does not pass takes the general tests. */
static int parallel_invisible(const qgl_context *ctx, const qgl__state *st, const qgl__verts *v, const size_t idx[4])
{
    double scale = ctx->split_error > 0 ? ctx->split_error : 1.0, colour = 0;
    int smooth = st->shade_model != GL_FLAT;
    if ((v->mask & QGL__A_COLOR) && smooth)
        colour += parallel_residual(v->col, 4, idx, 1);
    if ((v->mask & QGL__A_COLOR2) && smooth && (st->ffp.flags & QGL__KF_COLOR_SUM))
        colour += parallel_residual(v->col2, 3, idx, 1);
    if ((v->mask & QGL__A_FOG) && st->fog_slope > 0)
        colour += parallel_residual(v->fog, 1, idx, 0) * st->fog_slope;
    if (!(colour <= SPLIT_COLOUR * scale))
        return 0;
    for (int u = 0; u < st->ffp.nunits; u++) {
        const qgl__unit_key *uk = &st->ffp.unit[u];
        if (!uk->target || !(v->mask & (QGL__A_TEX0 << u)))
            continue; /* untextured, or the current coordinates: constant */
        const float *t = v->tex[u];
        double q = t[4 * idx[0] + 3], d[4];
        for (int c = 1; c < 4; c++) /* one positive q (NaN fails) */
            if (!(q > 0) || !(fabs(t[4 * idx[c] + 3] - q) <= 1e-6 * q))
                return 0;
        parallel_diff4(t, idx, d);
        int dims = uk->target == QGL__T_1D ? 1 : uk->target == QGL__T_3D ? 3 : 2;
        for (int k = 0; k < dims; k++)
            if (!(fabs(d[k]) / q * st->texsize[u][k] <= SPLIT_TEXEL * scale))
                return 0;
    }
    const float *p[4];
    for (int c = 0; c < 4; c++)
        p[c] = v->pos + 4 * idx[c];
    if (!(p[0][3] > 0) || p[1][3] != p[0][3] || p[2][3] != p[0][3] || p[3][3] != p[0][3])
        return 0;
    double d02[3], d13[3], d01[3], n[3], n2;
    for (int k = 0; k < 3; k++)
        d02[k] = (double)p[2][k] - p[0][k], d13[k] = (double)p[3][k] - p[1][k], d01[k] = (double)p[1][k] - p[0][k];
    return true_parallelogram(d02, d13, d01, n, &n2);
}

/* Whether the driver may clip at this clip coordinate: outside, or so close inside that the
 * GPU's float transform may land outside (exactly on the plane, as a window-filling quad's
 * corners are, is inside on both). */
static int near_or_out(double c, double w)
{
    double a = fabs(c);
    return !(a <= w) || (a != w && a > w * (1 - 1e-6));
}

/* judge: whether a split the invisible-split bound allows can matter (see plan_runs). */
static unsigned char plan_quad(qgl_context *ctx, const qgl__state *st, const qgl__verts *v,
                               qgl_topology topo, size_t q, const qgl__facts *facts, int judge)
{
    size_t idx[4];
    const double *clip[4];
    double px[4][2];
    int external = 0, behind = 0;
    for (int c = 0; c < 4; c++) {
        idx[c] = qgl__corner(topo, q, c);
        clip[c] = ctx->clip + 4 * idx[c];
        external |= !(clip[c][3] > 0);
        behind += !(clip[c][3] > 0);
    }
    if (behind == 4)
        return QGL__P_SPLIT; /* entirely behind the eye: the clipper removes it */
    if (ctx->method == QGL_METHOD_SPLIT)
        return QGL__P_SPLIT;
    if (ctx->plan_fast && judge && !external && worth_trying(&ctx->fast_rate)) {
        int ok = parallel_invisible(ctx, st, v, idx);
        rate_note(&ctx->fast_rate, ok, 256);
        if (ok)
            return QGL__P_SPLIT | QGL__P_EITHER;
    }
    int planar = 0;
    if (ctx->method == QGL_METHOD_SUBDIV) {
        double p[4][3];
        planar = object_corners(v, idx, p) && qgl__planar(p);
        return !external && qgl__grid_plan(ctx, st, v, idx, clip, planar, q) ? QGL__P_GRID : QGL__P_SUBDIV;
    }
    int auto_ = ctx->method == QGL_METHOD_AUTO;
    if (auto_ && !external) /* the bounding box and the invisible split's samples measure them */
        pixel_corners(clip, st->xf.viewport, px);
    if (auto_ && !external && !st->pv_material && bbox_area_px(px) < ctx->invisible_area_px)
        return QGL__P_SPLIT | QGL__P_EITHER;
    int exact = quad_exact(ctx, st, v, idx, clip, px, auto_ && !external && judge, facts, q, &planar);
    if (auto_ && exact)
        return QGL__P_SPLIT | QGL__P_EITHER;
    if (!st->modelled || (!planar && st->polygon_offset))
        return QGL__P_SUBDIV;
    if (auto_ && !external && qgl__grid_plan(ctx, st, v, idx, clip, planar, q))
        return QGL__P_GRID;
    /* With a corner behind the eye the cover is the clipped split; its rasterized depth is the
     * one consistent with that clipping, so eq. 4 depth is used for visible quads only. A
     * planar quad keeps its in-plane weights (the cover in its plane is exact); a non-planar
     * one takes H&T's screen-space weights of the external quad (sec. 3.2) on every method:
     * the view-invariant forms need a surface point per pixel, and neither the bilinear patch
     * (a ray's hits may lie behind the eye) nor the split projected onto the best-fit plane
     * (it leaves the in-plane quad where that quad is not convex, and the weights extrapolate
     * without bound) gives one inside the whole screen quad. */
    if (external) {
        unsigned char screen = qgl__external_planar(v, idx) ? 0 : QGL__P_SCREEN;
        return QGL__P_MVC | QGL__P_EXTERNAL | QGL__P_CLIPPED | screen;
    }
    /* the driver clips quads reaching out of the view volume: see shader.c's persp(); asked
     * only here, since most quads are split before */
    int outside = 0;
    for (int c = 0; c < 4; c++)
        outside |= near_or_out(clip[c][0], clip[c][3]) || near_or_out(clip[c][1], clip[c][3]) ||
                   near_or_out(clip[c][2], clip[c][3]);
    return QGL__P_MVC | (planar ? 0 : QGL__P_DEPTH) | (outside ? QGL__P_CLIPPED : 0);
}

QGL_API void qgl_gl_set_split_error(qgl_context *ctx, float scale)
{
    if (!ctx)
        return;
    ctx->split_error = scale;
    ctx->lit_rate = (qgl__rate){0}; /* the rate was for the old budget */
}

/* ---- drawing through the driver ---------------------------------------------------------------- */

typedef struct saved {
    GLint program, vao, vbo, client_tex;
    unsigned restore_current; /* attributes whose current value we must put back */
    float cur[QGL__NATTR][4];
    GLboolean edge;
} saved;

/* The driver's current value of attribute a into out (4 floats, GL's defaults past its own). */
static void read_current(qgl_context *ctx, const qgl__state *st, int a, float out[4])
{
    struct qgl__gl *gl = &ctx->gl;
    out[0] = out[1] = out[2] = 0, out[3] = 1;
    int unit = qgl__attribs[a].unit;
    if (unit >= 0)
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    gl->GetFloatv(qgl__attribs[a].current, out);
    if (unit >= 0)
        gl->ActiveTexture((GLenum)st->active_texture);
}

static void save(qgl_context *ctx, const qgl__state *st, unsigned mask, saved *s)
{
    s->program = st->program;
    s->restore_current = mask;
    s->vao = st->vao;
    s->vbo = st->array_buffer;
    s->client_tex = st->client_texture;
    for (int a = 0; a < QGL__NATTR; a++)
        if (mask & (1u << a))
            read_current(ctx, st, a, s->cur[a]);
    if (mask & QGL__A_EDGE)
        ctx->gl.GetBooleanv(GL_EDGE_FLAG, &s->edge);
}

static void restore(qgl_context *ctx, const saved *s)
{
    struct qgl__gl *gl = &ctx->gl;
    unsigned m = s->restore_current;
    gl->UseProgram((GLuint)s->program);
    gl->BindVertexArray((GLuint)s->vao);
    gl->BindBuffer(GL_ARRAY_BUFFER, (GLuint)s->vbo);
    gl->ClientActiveTexture((GLenum)s->client_tex);
    for (int a = 0; a < QGL__NATTR; a++)
        if (m & (1u << a))
            qgl__set_current(gl, a, s->cur[a]);
    if (m & QGL__A_EDGE)
        gl->EdgeFlag(s->edge);
}

/* Per-vertex materials (shader path only) as generic attributes of our VAO, at off. */
static void point_materials(qgl_context *ctx, const qgl__verts *v, size_t off)
{
    struct qgl__gl *gl = &ctx->gl;
    int on = (v->mask & QGL__A_MATERIAL) != 0;
    if (!on && !ctx->material_arrays)
        return;
    const GLsizei stride = QGL__MATERIAL_FLOATS * sizeof(float);
    for (GLuint k = 0; k < QGL__NMATERIAL; k++) {
        if (on) {
            gl->VertexAttribPointer(QGL__LOC_MATERIAL + k, k < 8 ? 4 : 2, GL_FLOAT, GL_FALSE, stride,
                                    (const void *)(uintptr_t)(off + 16 * k));
            gl->EnableVertexAttribArray(QGL__LOC_MATERIAL + k);
        } else {
            gl->DisableVertexAttribArray(QGL__LOC_MATERIAL + k);
        }
    }
    ctx->material_arrays = on;
}

/* Copy v into the stream buffer (position, each attribute, edge flags, materials, then the
 * strip indices of nidx quads) and point our VAO's arrays at it; 0 when the driver refused. */
static int upload(qgl_context *ctx, const qgl__verts *v, size_t nidx)
{
    struct qgl__gl *gl = &ctx->gl;
    size_t n = v->n, base = 0, at = 0, off[QGL__NATTR + 3];
    const void *data[QGL__NATTR + 3];
    size_t size[QGL__NATTR + 3];
    unsigned bit[QGL__NATTR + 3];
    for (int a = 0; a < QGL__NATTR; a++)
        data[a] = v->attr[a], size[a] = 4 * (size_t)qgl__attribs[a].floats, bit[a] = 1u << a;
    data[QGL__NATTR] = v->pos, size[QGL__NATTR] = 16, bit[QGL__NATTR] = 0;
    data[QGL__NATTR + 1] = v->edge, size[QGL__NATTR + 1] = 1, bit[QGL__NATTR + 1] = QGL__A_EDGE;
    data[QGL__NATTR + 2] = v->mat, size[QGL__NATTR + 2] = QGL__MATERIAL_FLOATS * sizeof(float);
    bit[QGL__NATTR + 2] = QGL__A_MATERIAL;
    size_t total = 16 * nidx;
    for (int b = 0; b < QGL__NATTR + 3; b++)
        if (!bit[b] || (v->mask & bit[b]))
            total += (n * size[b] + 15) & ~(size_t)15;
    gl->BindVertexArray(ctx->vao);
    unsigned char *map = qgl__stream_begin(ctx, total, &base);
    if (!map)
        return 0;
    for (int b = 0; b < QGL__NATTR + 3; b++) {
        off[b] = base + at;
        if (!bit[b] || (v->mask & bit[b])) {
            memcpy(map + at, data[b], n * size[b]);
            at += (n * size[b] + 15) & ~(size_t)15;
        }
    }
    uint32_t *idx = (uint32_t *)(map + at);
    for (size_t q = 0; q < nidx; q++)
        for (int c = 0; c < 4; c++)
            idx[4 * q + c] = (uint32_t)qgl__corner(QGL_QUAD_STRIP, q, c);
    ctx->idx_offset = base + at;
    qgl__stream_end(ctx);
    if (nidx)
        gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, ctx->stream.buf); /* our VAO's */
    qgl__point_arrays(ctx, v->mask, off[QGL__NATTR], off, off[QGL__NATTR + 1]);
    point_materials(ctx, v, off[QGL__NATTR + 2]);
    return 1;
}

static void draw_split(qgl_context *ctx, qgl_topology topo, size_t q0, size_t nq, GLint app_program,
                       GLint *bound)
{
    if (*bound != app_program)
        ctx->gl.UseProgram((GLuint)(*bound = app_program));
    if (topo == QGL_QUADS)
        ctx->gl.DrawArrays(GL_QUADS, (GLint)(4 * q0), (GLsizei)(4 * nq));
    else
        ctx->gl.DrawArrays(GL_QUAD_STRIP, (GLint)(2 * q0), (GLsizei)(2 * nq + 2));
    ctx->stats.draws++;
}

/* The corner of a captured quad whose colour flat shading uses: the last vertex of the quad
 * (GL_QUADS 4k+3, corner 3; strip 2k+3, corner 2) unless quads follow a first-vertex
 * provoking convention. */
int qgl__flat_corner(qgl_context *ctx, const qgl__state *st, qgl_topology topo)
{
    if (ctx->quads_follow_pv) {
        GLint pv = GL_LAST_VERTEX_CONVENTION;
        if (!st)
            ctx->gl.GetIntegerv(GL_PROVOKING_VERTEX, &pv);
        if (st ? st->first_vertex_pv : pv == GL_FIRST_VERTEX_CONVENTION)
            return 0;
    }
    return topo == QGL_QUADS ? 3 : 2;
}

/* Issue 4's key bits for the GLSL 1.20 path; QGL__K_EXTRA when the state is beyond them. */
static unsigned program_key(qgl_context *ctx, const qgl__state *st, qgl_topology topo, unsigned char path)
{
    unsigned key = QGL__K_COLOR | (st->simple ? 0 : QGL__K_EXTRA);
    int corner = qgl__flat_corner(ctx, st, topo);
    if (st->shade_model == GL_FLAT)
        key |= QGL__K_FLAT | (unsigned)corner << QGL__K_CORNER_SHIFT;
    if (st->texture2d)
        key |= QGL__K_TEX | (st->tex_replace ? QGL__K_REPLACE : 0) | (st->tex_no_alpha ? QGL__K_NOALPHA : 0);
    if (path & QGL__P_DEPTH)
        key |= QGL__K_DEPTH;
    if (path & QGL__P_EXTERNAL)
        key |= QGL__K_DISCARD;
    if (ctx->method != QGL_METHOD_MVC && !(path & QGL__P_SCREEN))
        key |= QGL__K_PLANE;
    return key;
}

/* The geometry shader path's key: the state's fixed-function key plus what the run adds. */
static void ffp_key(qgl_context *ctx, const qgl__state *st, qgl_topology topo, unsigned char path, unsigned mask,
                    qgl__key *k)
{
    *k = st->ffp;
    if (st->shade_model == GL_FLAT) {
        k->flags |= QGL__KF_FLAT;
        k->corner = (uint8_t)qgl__flat_corner(ctx, st, topo);
    }
    /* Unlit colours nobody gave per vertex are the current ones, equal at every corner: the
     * flat program passes one value instead of four and interpolates nothing. */
    if (!(k->flags & QGL__KF_LIGHTING) && !(mask & QGL__A_COLOR) &&
        (!(k->flags & QGL__KF_COLOR_SUM) || !(mask & QGL__A_COLOR2)))
        k->flags |= QGL__KF_FLAT;
    if (path & QGL__P_DEPTH)
        k->flags |= QGL__KF_DEPTH;
    if (path & QGL__P_EXTERNAL)
        k->flags |= QGL__KF_DISCARD;
    if (path & QGL__P_CLIPPED)
        k->flags |= QGL__KF_CLIPPED;
    if (ctx->method != QGL_METHOD_MVC && !(path & QGL__P_SCREEN))
        k->flags |= QGL__KF_PLANE;
}

static int draw_mvc(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t q0,
                    size_t nq, unsigned char path, GLint *bound)
{
    qgl__key key;
    ffp_key(ctx, st, topo, path, v->mask, &key);
    GLuint prog = qgl__program(ctx, &key);
    if (!prog)
        return 0;
    if (*bound != (GLint)prog)
        ctx->gl.UseProgram(prog), *bound = (GLint)prog;
    qgl__program_viewport(ctx, prog, st->xf.viewport);
    if (topo == QGL_QUADS)
        ctx->gl.DrawArrays(GL_LINES_ADJACENCY, (GLint)(4 * q0), (GLsizei)(4 * nq));
    else
        ctx->gl.DrawElements(GL_LINES_ADJACENCY, (GLsizei)(4 * nq), GL_UNSIGNED_INT,
                             (const void *)(uintptr_t)(ctx->idx_offset + 16 * q0));
    ctx->stats.draws++;
    return 1;
}

static void draw_subdiv(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo,
                        size_t q0, size_t nq, GLint app_program, GLint *bound)
{
    ctx->sub.n = 0;
    ctx->sub.mask = v->mask & ~(unsigned)(QGL__A_EDGE | QGL__A_MATERIAL);
    for (size_t q = q0; q < q0 + nq; q++)
        qgl__subdivide(ctx, st, v, topo, q, &ctx->sub);
    if (!ctx->sub.n)
        return;
    if (*bound != app_program)
        ctx->gl.UseProgram((GLuint)(*bound = app_program));
    if (upload(ctx, &ctx->sub, 0))
        ctx->gl.DrawArrays(GL_TRIANGLES, 0, (GLsizei)ctx->sub.n);
    ctx->stats.draws++;
    ctx->stats.subdiv_triangles += ctx->sub.n / 3;
    upload(ctx, v, topo == QGL_QUAD_STRIP ? qgl__nquads(topo, v->n) : 0); /* later runs draw from the batch again */
}

static void count(qgl_context *ctx, unsigned char path, size_t nq)
{
    switch (path & QGL__P_KIND) {
    case QGL__P_SPLIT: ctx->stats.split += nq; break;
    case QGL__P_MVC: ctx->stats.mvc += nq; break;
    case QGL__P_GRID: ctx->stats.subdiv += nq; break;
    case QGL__P_SUBDIV: ctx->stats.fallback += nq; break;
    default: ctx->stats.passthrough += nq;
    }
}

/* A run planned for the shader path that its program could not serve went to the fallback:
 * the counters say where it really went (tests rely on them to prove the shader path ran). */
static void recount_as_fallback(qgl_context *ctx, size_t nq)
{
    ctx->stats.mvc -= nq;
    ctx->stats.fallback += nq;
}

/* ---- immediate replay (contexts without vertex array objects) ------------------------------- */

static void replay_vertex(struct qgl__gl *gl, const qgl__verts *v, size_t i)
{
    unsigned m = v->mask;
    for (unsigned b = m & QGL__A_ATTRIBS; b; b &= b - 1) { /* the attributes given: one or two */
        int a = __builtin_ctz(b);
        qgl__set_current(gl, a, v->attr[a] + (size_t)qgl__attribs[a].floats * i);
    }
    if (m & QGL__A_EDGE)
        gl->EdgeFlag(v->edge[i]);
    gl->Vertex4fv(v->pos + 4 * i);
}

/* The batch's glMaterial changes due before vertex `before` (inside glBegin/glEnd they are
 * legal and per vertex, as the application gave them). */
static void apply_changes(qgl_context *ctx, size_t before)
{
    for (; ctx->chg_next < ctx->nchg && ctx->chg[ctx->chg_next].vertex < before; ctx->chg_next++) {
        const qgl__change *m = &ctx->chg[ctx->chg_next];
        ctx->gl.Materialfv(m->face, m->pname, m->v);
    }
}

/* Quads [first, first + n) of a display list's GL_QUADS as the driver's lists draw them where
 * polygons are filled: the triangles 0-1-3, 1-2-3, each vertex with its own materials. */
static void replay_list_quads(qgl_context *ctx, const qgl__verts *v, size_t first, size_t n)
{
    static const int split[6] = {0, 1, 3, 1, 2, 3};
    int own = v == ctx->chg_verts && ctx->chg_next < ctx->nchg;
    qgl__matrun r;
    qgl__matrun_start(&ctx->gl, &r, own ? ctx->chg + ctx->chg_next : NULL, own ? ctx->nchg - ctx->chg_next : 0);
    ctx->gl.Begin(GL_TRIANGLES);
    for (size_t j = 0; j < 6 * (n / 4); j++) {
        size_t i = first + 4 * (j / 6) + (size_t)split[j % 6];
        if (j % 6 == 0)
            qgl__matrun_quad(&r, i);
        qgl__matrun_emit(&ctx->gl, &r, split[j % 6]);
        replay_vertex(&ctx->gl, v, i);
    }
    ctx->gl.End();
    ctx->chg_next += r.next;
    ctx->stats.draws++;
}

static void replay(qgl_context *ctx, GLenum mode, const qgl__verts *v, size_t first, size_t n)
{
    ctx->gl.Begin(mode);
    for (size_t i = first; i < first + n; i++) {
        if (ctx->chg_next < ctx->nchg && v == ctx->chg_verts)
            apply_changes(ctx, i + 1);
        replay_vertex(&ctx->gl, v, i);
    }
    ctx->gl.End();
    ctx->stats.draws++;
}

void qgl__replay_prim(qgl_context *ctx, GLenum mode, const qgl__verts *v, const qgl__change *chg, size_t nchg)
{
    ctx->chg = chg, ctx->nchg = nchg, ctx->chg_next = 0, ctx->chg_verts = v;
    replay(ctx, mode, v, 0, v->n);
    apply_changes(ctx, SIZE_MAX);
    ctx->nchg = 0;
}

/* Without VAOs we cannot stream arrays without touching the application's client state, so
 * the driver gets the vertices as immediate calls (split, pass-through, subdivision). */
static void draw_replay(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo,
                        size_t q0, size_t nq, unsigned char path)
{
    if ((path & QGL__P_KIND) == QGL__P_SUBDIV) {
        ctx->sub.n = 0;
        ctx->sub.mask = v->mask & ~(unsigned)(QGL__A_EDGE | QGL__A_MATERIAL);
        for (size_t q = q0; q < q0 + nq; q++)
            qgl__subdivide(ctx, st, v, topo, q, &ctx->sub);
        ctx->stats.subdiv_triangles += ctx->sub.n / 3;
        replay(ctx, GL_TRIANGLES, &ctx->sub, 0, ctx->sub.n);
    } else if (topo == QGL_QUADS && ctx->list_quads && st->polygon_mode[0] == GL_FILL &&
               st->polygon_mode[1] == GL_FILL) {
        replay_list_quads(ctx, v, 4 * q0, 4 * nq);
    } else if (topo == QGL_QUADS) {
        replay(ctx, GL_QUADS, v, 4 * q0, 4 * nq);
    } else {
        replay(ctx, GL_QUAD_STRIP, v, 2 * q0, 2 * nq + 2);
    }
}

/* The GLSL 1.20 path (glsl120.c), or the CPU fallback for a run it cannot serve. */
static void draw_glsl120(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t q0,
                         size_t nq, unsigned char path, GLint *bound)
{
    if (qgl__glsl120_draw(ctx, st, v, topo, q0, nq, program_key(ctx, st, topo, path), bound))
        return;
    recount_as_fallback(ctx, nq);
    if (ctx->has_vao)
        draw_subdiv(ctx, st, v, topo, q0, nq, st->program, bound);
    else
        draw_replay(ctx, st, v, topo, q0, nq, QGL__P_SUBDIV);
}

/* ---- the batch -------------------------------------------------------------------------------- */

/* Split runs shorter than this between shader-path quads join them. */
#define QGL__SHORT_RUN 32

static int joins_shader_run(unsigned char p)
{
    return (p & QGL__P_KIND) == QGL__P_MVC && !(p & QGL__P_EXTERNAL);
}

/* A short run of quads the split may draw (exact, or too small to differ) next to quads on
 * the shader path is drawn with them: the picture is the same, and each extra draw (with its
 * program switch and state round trip) costs more than shading a few small quads. */
static void merge_runs(unsigned char *path, size_t nq)
{
    for (size_t a = 0; a < nq;) {
        if (!(path[a] & QGL__P_EITHER)) {
            a++;
            continue;
        }
        size_t b = a;
        while (b < nq && (path[b] & QGL__P_EITHER))
            b++;
        unsigned char p = QGL__P_SPLIT;
        if (b - a < QGL__SHORT_RUN) {
            if (a > 0 && joins_shader_run(path[a - 1]))
                p = path[a - 1];
            else if (b < nq && joins_shader_run(path[b]))
                p = path[b];
        }
        memset(path + a, p, b - a);
        a = b;
    }
}

/* Whether the quad's screen corners (every w > 0) turn one way: the depth-writing form of the
 * view-invariant weights serves a planar quad then (its patch is the quad; a concave one's
 * folds over). */
static int screen_convex(const qgl_context *ctx, qgl_topology topo, size_t q)
{
    double x[4], y[4];
    int pos = 0, neg = 0;
    for (int c = 0; c < 4; c++) {
        const double *h = ctx->clip + 4 * qgl__corner(topo, q, c);
        x[c] = h[0] / h[3], y[c] = h[1] / h[3];
    }
    for (int c = 0; c < 4; c++) {
        int d = (c + 1) & 3, e = (c + 2) & 3;
        double cross = (x[d] - x[c]) * (y[e] - y[d]) - (y[d] - y[c]) * (x[e] - x[d]);
        pos += cross > 0, neg += cross < 0;
    }
    return pos == 4 || neg == 4;
}

/* Shader-path quads whose forms alternate (a lathed surface's planar and non-planar quads,
 * clipped and unclipped ones) are drawn by the one program that serves them all, one draw
 * instead of one per change: the clipped form (per-fragment normalisation) serves any quad,
 * the depth-writing one any planar quad (its weights are the plane's; in the view-invariant
 * form convex ones only). Quads with a corner behind the eye keep their own. */
static void merge_forms(qgl_context *ctx, qgl_topology topo, unsigned char *path, size_t nq)
{
    const unsigned char forms = QGL__P_DEPTH | QGL__P_CLIPPED;
    for (size_t a = 0; a < nq;) {
        if ((path[a] & QGL__P_KIND) != QGL__P_MVC || (path[a] & QGL__P_EXTERNAL)) {
            a++;
            continue;
        }
        size_t b = a;
        unsigned char all = 0, any_change = 0;
        while (b < nq && (path[b] & QGL__P_KIND) == QGL__P_MVC && !(path[b] & QGL__P_EXTERNAL)) {
            any_change |= b > a && path[b] != path[b - 1];
            all |= path[b++] & forms;
        }
        int ok = any_change;
        for (size_t q = a; q < b && ok && (all & QGL__P_DEPTH) && ctx->method != QGL_METHOD_MVC; q++)
            ok = (path[q] & QGL__P_DEPTH) || screen_convex(ctx, topo, q);
        if (ok)
            for (size_t q = a; q < b; q++)
                path[q] = (unsigned char)((path[q] & ~forms) | all);
        a = b;
    }
}

static void plan_one(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t q,
                     const qgl__facts *facts, int judge)
{
    unsigned char p = plan_quad(ctx, st, v, topo, q, facts, judge);
    if ((p & QGL__P_KIND) == QGL__P_MVC && !ctx->has_vao && ctx->shader_level != 120)
        p = QGL__P_SUBDIV;
    ctx->path[q] = p;
}

/* Every quad's path, judging the split only where its verdict can survive merge_runs: a run
 * of split quads shorter than QGL__SHORT_RUN next to a shader-path quad is drawn smooth
 * anyway, and judging a lit quad costs about as much as shading a small one. After a
 * shader-path quad L, the quad QGL__SHORT_RUN on (the last that could close a short run) is
 * planned first and the window scanned back from it: at the first shader-path quad c found,
 * the quads between L and c take the shader path unjudged, as the merge would give them
 * (only a run walled in by grid, fallback or behind-the-eye quads could have stayed split,
 * and smooth is right for any quad). A window with no shader-path quad is a long run, planned
 * on until the next one. After the last shader-path quad, a tail shorter than the window
 * merges whatever it holds. */
static void plan_runs(qgl_context *ctx, const qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t nq,
                      const qgl__facts *facts)
{
    const size_t S = QGL__SHORT_RUN;
    size_t hi = 0;          /* quads [0, hi) are planned */
    ptrdiff_t last = -1;    /* the last shader-path quad among them, -1 for none */
    while (hi < nq) {
        size_t top = (size_t)(last + (ptrdiff_t)S);
        if (top >= nq) {
            for (; hi < nq; hi++)
                plan_one(ctx, st, v, topo, hi, facts, last < 0);
            break;
        }
        size_t c = top + 1;
        for (size_t b = top + 1; b-- > hi;) {
            plan_one(ctx, st, v, topo, b, facts, 1);
            if (joins_shader_run(ctx->path[b])) {
                c = b;
                break;
            }
        }
        if (c <= top) {
            for (; hi < c; hi++)
                plan_one(ctx, st, v, topo, hi, facts, 0);
            hi = top + 1, last = (ptrdiff_t)c;
            continue;
        }
        for (hi = top + 1; hi < nq;) { /* a long run: on to its end */
            plan_one(ctx, st, v, topo, hi, facts, 1);
            if (joins_shader_run(ctx->path[hi++])) {
                last = (ptrdiff_t)hi - 1;
                break;
            }
        }
    }
}

static int plan(qgl_context *ctx, qgl__state *st, const qgl__verts *v, qgl_topology topo, size_t nq,
                const qgl__facts *facts)
{
    if (!ensure((void **)&ctx->path, &ctx->path_cap, nq, 1))
        return 0;
    int pass = st->render_mode != GL_RENDER || st->polygon_mode[0] != GL_FILL || st->polygon_mode[1] != GL_FILL ||
               st->own_pipeline;
    if (pass || ctx->method == QGL_METHOD_SPLIT) {
        memset(ctx->path, pass ? QGL__P_PASS : QGL__P_SPLIT, nq);
        return 1;
    }
    qgl__state_xform(ctx, st); /* every path but these two reads it */
    if (!ensure((void **)&ctx->clip, &ctx->clip_cap, 4 * v->n, sizeof(double)))
        return 0;
    transform_all(st->xf.mvp, v->pos, v->n, ctx->clip);
    ctx->plan_read = attribs_read(st, v->mask); /* the state's, the same for every quad */
    ctx->plan_need = needed_facts(st);
    ctx->plan_fast = parallel_state(ctx, st);
    plan_runs(ctx, st, v, topo, nq, facts);
    merge_runs(ctx->path, nq);
    if (ctx->shader_level != 120)
        merge_forms(ctx, topo, ctx->path, nq);
    return 1;
}

/* Whether a plan made before the shader path was ready draws a quad smooth. */
static int needs_shaders(const unsigned char *path, size_t nq)
{
    for (size_t q = 0; q < nq; q++)
        if ((path[q] & QGL__P_KIND) == QGL__P_MVC || (path[q] & QGL__P_KIND) == QGL__P_GRID)
            return 1;
    return 0;
}

/* A retained batch the driver can draw as the application would, when this state plans every
 * quad the driver's way (polygon mode line/point, select/feedback, method SPLIT, or the split
 * exact for all); counted as that path. */
int qgl__native_path(qgl_context *ctx, const qgl__state *st, unsigned all_facts)
{
    if (st->render_mode != GL_RENDER || st->polygon_mode[0] != GL_FILL || st->polygon_mode[1] != GL_FILL ||
        st->own_pipeline)
        return QGL__P_PASS;
    if (ctx->method == QGL_METHOD_SPLIT ||
        (ctx->method == QGL_METHOD_AUTO && exact_by_facts(st, needed_facts(st), all_facts)))
        return QGL__P_SPLIT;
    return -1;
}

void qgl__count_path(qgl_context *ctx, unsigned char path, size_t nq)
{
    count(ctx, path, nq);
}

static int draw_natively(qgl_context *ctx, const qgl__state *st, const qgl__facts *facts, size_t nq)
{
    if (!facts || !facts->native)
        return 0;
    int path = qgl__native_path(ctx, st, facts->all);
    if (path < 0)
        return 0;
    ctx->stats.quads += nq;
    count(ctx, (unsigned char)path, nq);
    ctx->stats.draws++;
    facts->native(facts->user);
    return 1;
}

int qgl__draw(qgl_context *ctx, const qgl__verts *v, qgl_topology topo)
{
    return qgl__draw_batch(ctx, v, topo, NULL, 0, NULL, 0);
}

int qgl__draw_with_facts(qgl_context *ctx, const qgl__verts *v, qgl_topology topo, const qgl__facts *facts)
{
    return qgl__draw_batch(ctx, v, topo, facts, 0, NULL, 0);
}

/* The quad a material change before vertex i applies from (a quad drawn by the GL path has one
 * material; the driver's own replay applies it at the very vertex). */
static size_t change_quad(qgl_topology topo, size_t i)
{
    if (topo == QGL_QUADS)
        return i / 4;
    return i < 4 ? 0 : (i - 2) / 2;
}

/* Whether a run of this path is drawn by handing its vertices to the driver's immediate mode
 * (the split and the driver's own quads of a small captured primitive: the driver then merges
 * it with the primitives around it, as it would have natively). */
static int replayed(const qgl_context *ctx, unsigned char path, unsigned flags)
{
    int kind = path & QGL__P_KIND;
    return !ctx->has_vao || ((flags & (QGL__DRAW_IMMEDIATE | QGL__DRAW_ARRAYS)) == QGL__DRAW_IMMEDIATE &&
                             (kind == QGL__P_SPLIT || kind == QGL__P_PASS));
}

/* Where drawing order cannot show (st->order_free), a batch's quads are drawn grouped by path,
 * stably: one draw per path instead of one per change of path (a lathed surface alternates
 * planar and non-planar quads, a sphere's clipped and unclipped ones). The vertices, their
 * clip positions, the paths and the grids planned are permuted; 0 when that saves no draw or
 * without memory. */
static int group_by_path(qgl_context *ctx, const qgl__verts *v, size_t nq)
{
    size_t runs = 1, kinds = 0, count[256] = {0}, start[256], at = 0;
    unsigned char *path = ctx->path;
    for (size_t q = 0; q < nq; q++) {
        runs += q > 0 && path[q] != path[q - 1];
        kinds += count[path[q]]++ == 0;
    }
    qgl__verts *g = &ctx->grouped;
    if (runs <= kinds || !qgl__verts_reserve(g, 4 * nq, v->mask) ||
        !ensure((void **)&ctx->grouped_clip, &ctx->grouped_clip_cap, 16 * nq, sizeof(double)) ||
        !ensure((void **)&ctx->grouped_to, &ctx->grouped_to_cap, nq, sizeof(size_t)))
        return 0;
    for (int p = 0; p < 256; p++)
        start[p] = at, at += count[p];
    for (size_t q = 0; q < nq; q++)
        ctx->grouped_to[q] = start[path[q]]++;
    if (!qgl__grid_regroup(ctx, path, ctx->grouped_to, nq))
        return 0;
    for (size_t q = 0; q < nq; q++) {
        size_t d = ctx->grouped_to[q];
        qgl__verts_copy_range(g, 4 * d, v, 4 * q, 4);
        memcpy(ctx->grouped_clip + 16 * d, ctx->clip + 16 * q, 16 * sizeof(double));
    }
    at = 0;
    for (int p = 0; p < 256; p++)
        memset(path + at, p, count[p]), at += count[p];
    double *c = ctx->clip;
    size_t cap = ctx->clip_cap;
    ctx->clip = ctx->grouped_clip, ctx->clip_cap = ctx->grouped_clip_cap;
    ctx->grouped_clip = c, ctx->grouped_clip_cap = cap;
    g->n = 4 * nq;
    g->mask = v->mask;
    return 1;
}

/* The material components per vertex, in QGL__MATERIAL_FLOATS' order. */
static const GLenum material_pnames[4] = {GL_AMBIENT, GL_DIFFUSE, GL_SPECULAR, GL_EMISSION};

static void material_change(float cur[QGL__MATERIAL_FLOATS], const qgl__change *c)
{
    for (int f = 0; f < 2; f++) {
        if ((f == 0 && c->face == GL_BACK) || (f == 1 && c->face == GL_FRONT))
            continue;
        for (int k = 0; k < 4; k++)
            if (c->pname == material_pnames[k] || (c->pname == GL_AMBIENT_AND_DIFFUSE && k < 2))
                memcpy(cur + 16 * f + 4 * k, c->v, 4 * sizeof(float));
        if (c->pname == GL_SHININESS)
            cur[32 + f] = c->v[0];
    }
}

/* The components (bit f * 5 + k: face f, material_pnames[k], k = 4 the shininess) a change sets. */
static unsigned material_bits(const qgl__change *c)
{
    unsigned bits = 0;
    for (int f = 0; f < 2; f++) {
        if ((f == 0 && c->face == GL_BACK) || (f == 1 && c->face == GL_FRONT))
            continue;
        for (int k = 0; k < 4; k++)
            if (c->pname == material_pnames[k] || (c->pname == GL_AMBIENT_AND_DIFFUSE && k < 2))
                bits |= 1u << (5 * f + k);
        if (c->pname == GL_SHININESS)
            bits |= 1u << (5 * f + 4);
    }
    return bits;
}

void qgl__matrun_start(struct qgl__gl *gl, qgl__matrun *r, const qgl__change *chg, size_t nchg)
{
    r->chg = chg, r->nchg = nchg, r->next = 0, r->given = 0;
    for (size_t c = 0; c < nchg && gl; c++)
        r->given |= material_bits(&chg[c]);
    for (int f = 0; f < 2; f++) {
        GLenum face = f ? GL_BACK : GL_FRONT;
        for (int k = 0; k < 4; k++)
            if (r->given & (1u << (5 * f + k)))
                gl->GetMaterialfv(face, material_pnames[k], r->cur + 16 * f + 4 * k);
        if (r->given & (1u << (5 * f + 4)))
            gl->GetMaterialfv(face, GL_SHININESS, r->cur + 32 + f);
    }
}

int qgl__matrun_leading(const qgl__change *chg, size_t nchg, size_t first)
{
    unsigned all = 0, lead = 0;
    for (size_t c = 0; c < nchg; c++) {
        all |= material_bits(&chg[c]);
        if (chg[c].vertex <= first)
            lead |= material_bits(&chg[c]);
    }
    return all == lead;
}

void qgl__matrun_quad(qgl__matrun *r, size_t first)
{
    for (int c = 0; c < 4; c++) {
        for (; r->next < r->nchg && r->chg[r->next].vertex <= first + (size_t)c; r->next++)
            material_change(r->cur, &r->chg[r->next]);
        memcpy(r->corner[c], r->cur, sizeof r->cur);
    }
}

void qgl__matrun_emit(struct qgl__gl *gl, const qgl__matrun *r, int corner)
{
    const float *m = r->corner[corner];
    for (int f = 0; f < 2; f++) {
        GLenum face = f ? GL_BACK : GL_FRONT;
        for (int k = 0; k < 4; k++)
            if (r->given & (1u << (5 * f + k)))
                gl->Materialfv(face, material_pnames[k], m + 16 * f + 4 * k);
        if (r->given & (1u << (5 * f + 4)))
            gl->Materialfv(face, GL_SHININESS, m + 32 + f);
    }
}

void qgl__matrun_to(struct qgl__gl *gl, qgl__matrun *r, size_t vertex)
{
    for (; r->next < r->nchg && r->chg[r->next].vertex <= vertex; r->next++)
        gl->Materialfv(r->chg[r->next].face, r->chg[r->next].pname, r->chg[r->next].v);
}

/* The glMaterial calls of a lit batch as per-vertex materials (the driver's material before
 * the batch, then each change from its vertex on), so the shader path lights every corner
 * with its own material in one draw, as fixed function does per vertex, instead of one draw
 * per change. 0 without memory (the runs are then cut at each change). */
static int per_vertex_materials(qgl_context *ctx, const qgl__verts *v, const qgl__change *chg, size_t nchg,
                                size_t step, qgl__verts *out)
{
    qgl__verts *m = &ctx->pvmat;
    float cur[QGL__MATERIAL_FLOATS] = {0};
    if (!qgl__verts_reserve(m, v->n, QGL__A_MATERIAL))
        return 0;
    for (int f = 0; f < 2; f++) {
        GLenum face = f ? GL_BACK : GL_FRONT;
        for (int k = 0; k < 4; k++)
            ctx->gl.GetMaterialfv(face, material_pnames[k], cur + 16 * f + 4 * k);
        ctx->gl.GetMaterialfv(face, GL_SHININESS, cur + 32 + f);
    }
    size_t c = 0;
    for (size_t i = 0; i < v->n; i += step) {
        for (; c < nchg && chg[c].vertex <= i; c++)
            material_change(cur, &chg[c]);
        memcpy(m->mat + QGL__MATERIAL_FLOATS * i, cur, sizeof cur);
    }
    *out = *v;
    out->mat = m->mat;
    out->mask |= QGL__A_MATERIAL;
    return 1;
}

/* Whether every change applies from a quad's first corner on (GL_QUADS: vertex 4q), as where
 * a program sets materials between its glBegin/glEnd pairs. Each quad then has one material,
 * and per_vertex_materials writes it at the first corner alone: the planner reads no other
 * (quad_materials), and the other corners are filled only for a draw that uploads them. */
static int changes_between_quads(const qgl__change *chg, size_t nchg)
{
    for (size_t c = 0; c < nchg; c++)
        if (chg[c].vertex % 4)
            return 0;
    return 1;
}

static void fill_quad_materials(const qgl__verts *v)
{
    for (size_t i = 0; i + 4 <= v->n; i += 4)
        for (size_t c = 1; c < 4; c++)
            memcpy(v->mat + QGL__MATERIAL_FLOATS * (i + c), v->mat + QGL__MATERIAL_FLOATS * i,
                   QGL__MATERIAL_FLOATS * sizeof(float));
}

static int draw_batch(qgl_context *ctx, const qgl__verts *v, qgl_topology topo, const qgl__facts *facts, unsigned flags,
                      const qgl__change *chg, size_t nchg)
{
    size_t nq = qgl__nquads(topo, v->n);
    if (!nq) {
        for (size_t c = 0; c < nchg; c++)
            ctx->gl.Materialfv(chg[c].face, chg[c].pname, chg[c].v);
        return 0;
    }
    qgl__state st;
    qgl__query_state(ctx, &st);
    qgl__verts with_mat;
    int pv_changes = 0;
    int between = topo == QGL_QUADS && changes_between_quads(chg, nchg);
    if (nchg && (st.ffp.flags & QGL__KF_LIGHTING) && !(v->mask & QGL__A_MATERIAL) && ctx->has_vao &&
        ctx->shader_level != 120 && per_vertex_materials(ctx, v, chg, nchg, between ? 4 : 1, &with_mat)) {
        v = &with_mat;
        pv_changes = 1;
        st.quad_materials = between;
    }
    if ((v->mask & QGL__A_MATERIAL) && (st.ffp.flags & QGL__KF_LIGHTING)) {
        st.ffp.flags |= QGL__KF_MATERIAL;
        st.pv_material = 1; /* a quad splits only with one material at its corners */
        st.lit_by_inputs = 0;
    }
    if (!nchg && draw_natively(ctx, &st, facts, nq))
        return (int)nq;
    if (!plan(ctx, &st, v, topo, nq, facts))
        return -1;
    if (!ctx->ready && needs_shaders(ctx->path, nq)) {
        if (qgl__ready(ctx)) {
            qgl__state_dirty(ctx, QGL__D_ALL);
            qgl__query_state(ctx, &st);
        }
        if (!plan(ctx, &st, v, topo, nq, facts)) /* with the costs, at the level compiled */
            return -1;
    }
    if (st.order_free && topo == QGL_QUADS && !nchg && group_by_path(ctx, v, nq))
        v = &ctx->grouped;
    ctx->chg = chg, ctx->nchg = nchg, ctx->chg_next = 0, ctx->chg_verts = v;
    ctx->list_quads = (flags & QGL__DRAW_LIST) != 0;
    ctx->stats.quads += nq;
    int arrays = 0;
    for (size_t q = 0; q < nq && !arrays; q++)
        arrays = !replayed(ctx, ctx->path[q], flags);
    saved sv;
    if (arrays && st.quad_materials)
        fill_quad_materials(v);
    if (arrays) {
        save(ctx, &st, (flags & QGL__DRAW_IMMEDIATE) ? 0 : v->mask, &sv);
        if (!upload(ctx, v, topo == QGL_QUAD_STRIP ? nq : 0)) {
            restore(ctx, &sv);
            return -1;
        }
    }
    GLint bound = st.program;
    for (size_t q0 = 0; q0 < nq;) {
        unsigned char p = ctx->path[q0];
        size_t q1 = q0 + 1, limit = nq;
        if (!replayed(ctx, p, flags) && !(pv_changes && (p & QGL__P_KIND) == QGL__P_MVC)) {
            /* its quads share the material in force at the first */
            while (ctx->chg_next < nchg && change_quad(topo, chg[ctx->chg_next].vertex) <= q0)
                apply_changes(ctx, chg[ctx->chg_next].vertex + 1);
            if (ctx->chg_next < nchg)
                limit = change_quad(topo, chg[ctx->chg_next].vertex);
        }
        while (q1 < nq && q1 < limit && ctx->path[q1] == p)
            q1++;
        count(ctx, p, q1 - q0);
        if ((p & QGL__P_KIND) == QGL__P_MVC && ctx->shader_level == 120)
            draw_glsl120(ctx, &st, v, topo, q0, q1 - q0, p, &bound);
        else if (replayed(ctx, p, flags)) {
            if (bound != st.program)
                ctx->gl.UseProgram((GLuint)(bound = st.program));
            draw_replay(ctx, &st, v, topo, q0, q1 - q0, p);
        } else if ((p & QGL__P_KIND) == QGL__P_MVC) {
            if (!draw_mvc(ctx, &st, v, topo, q0, q1 - q0, p, &bound)) {
                recount_as_fallback(ctx, q1 - q0);
                draw_subdiv(ctx, &st, v, topo, q0, q1 - q0, st.program, &bound);
            }
        } else if ((p & QGL__P_KIND) == QGL__P_GRID) {
            if (!qgl__grid_draw(ctx, &st, v, topo, q0, q1 - q0, &bound))
                draw_split(ctx, topo, q0, q1 - q0, st.program, &bound);
        } else if ((p & QGL__P_KIND) == QGL__P_SUBDIV)
            draw_subdiv(ctx, &st, v, topo, q0, q1 - q0, st.program, &bound);
        else
            draw_split(ctx, topo, q0, q1 - q0, st.program, &bound);
        q0 = q1;
    }
    apply_changes(ctx, SIZE_MAX);
    ctx->nchg = 0;
    if (arrays)
        restore(ctx, &sv);
    else if (bound != st.program)
        ctx->gl.UseProgram((GLuint)st.program);
    return (int)nq;
}

int qgl__draw_batch(qgl_context *ctx, const qgl__verts *v, qgl_topology topo, const qgl__facts *facts, unsigned flags,
                    const qgl__change *chg, size_t nchg)
{
    ctx->lightvals.current_valid = 0;
    int n = draw_batch(ctx, v, topo, facts, flags, chg, nchg);
    if (nchg) /* the batch's glMaterial calls have reached the driver (or will, replayed) */
        ctx->lightvals.materials_valid = 0;
    return n;
}
