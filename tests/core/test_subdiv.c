/* Tests of the bilinear (SuperQuad) and adaptive (Oliveira) subdivisions.
 *
 * References: the bilinear formula written out here; watertightness as "every directed
 * half-edge has its bitwise-identical reverse, except 4n on the border"; Oliveira's
 * parallelogram differences recomputed here for every leaf; areas by the shoelace formula. */
#include <quadgl/quadgl.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

static double bilinear(const double *q, int stride, int k, double s, double t)
{
    return (1 - s) * (1 - t) * q[k] + s * (1 - t) * q[stride + k] + s * t * q[2 * stride + k] +
           (1 - s) * t * q[3 * stride + k];
}

static const double *vert(const qgl_mesh *m, int tri, int j)
{
    return m->v + ((size_t)tri * 3 + j) * m->stride;
}

static int same_pos(const double *a, const double *b)
{
    return memcmp(a, b, 3 * sizeof(double)) == 0;
}

/* Directed half-edges without a bitwise reverse partner (the mesh's border). */
static int border_halfedges(const qgl_mesh *m)
{
    int border = 0;
    for (int t = 0; t < m->ntri; t++)
        for (int j = 0; j < 3; j++) {
            const double *a = vert(m, t, j), *b = vert(m, t, (j + 1) % 3);
            int partners = 0;
            for (int u = 0; u < m->ntri; u++)
                for (int i = 0; i < 3; i++)
                    partners += same_pos(vert(m, u, i), b) && same_pos(vert(m, u, (i + 1) % 3), a);
            CHECK(partners <= 1, "half-edge with %d reverse partners", partners);
            border += partners == 0;
        }
    return border;
}

static double tri_area_xy(const double *a, const double *b, const double *c)
{
    return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
}

/* Non-planar quad: position (3) + colour (3), the R-B-G-R example of the SuperQuad slides. */
static const double superquad[4 * 6] = {
    0, 0, 0.5, 1, 0, 0, /* corner 0: red */
    1, 0, 0, 0, 0, 1,   /* corner 1: blue */
    1, 1, 0.5, 1, 0, 0, /* corner 2: red */
    0, 1, 0, 0, 1, 0,   /* corner 3: green */
};

static void check_bilinear(void)
{
    const int ns[] = {1, 2, 3, 7};
    for (size_t a = 0; a < sizeof ns / sizeof ns[0]; a++) {
        int n = ns[a];
        qgl_mesh m = {0};
        CHECK(qgl_subdiv_bilinear(superquad, 6, n, &m) == 0, "bilinear n=%d failed", n);
        CHECK(m.ntri == 4 * n * n && m.stride == 6, "n=%d: %d triangles", n, m.ntri);
        double maxerr = 0;
        /* documented order: cells row by row (t), then along s; cell (i,j) = four triangles
         * (0,1,m),(1,2,m),(2,3,m),(3,0,m) around its centre m */
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                const double st[5][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}, {i + 0.5, j + 0.5}};
                const int idx[4][3] = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
                for (int h = 0; h < 4; h++)
                    for (int c = 0; c < 3; c++) {
                        const double *v = vert(&m, 4 * (j * n + i) + h, c);
                        for (int k = 0; k < 6; k++) {
                            double ref = bilinear(superquad, 6, k, st[idx[h][c]][0] / n, st[idx[h][c]][1] / n);
                            maxerr = fmax(maxerr, fabs(v[k] - ref));
                        }
                    }
            }
        CHECK(maxerr < 1e-15, "n=%d: bilinear error %g", n, maxerr);
        CHECK(border_halfedges(&m) == 4 * n, "n=%d: border half-edges != 4n", n);
        /* winding kept: the xy projection of this quad is the CCW unit square */
        double area = 0;
        for (int t = 0; t < m.ntri; t++) {
            double ar = tri_area_xy(vert(&m, t, 0), vert(&m, t, 1), vert(&m, t, 2));
            CHECK(ar > 0, "n=%d: triangle %d not counter-clockwise", n, t);
            area += ar;
        }
        CHECK(fabs(area - 1) < 1e-14, "n=%d: area %.17g", n, area);
        qgl_mesh_free(&m);
        CHECK(m.v == NULL && m.ntri == 0, "mesh_free");
    }
}

/* Two quads sharing the edge 1-2 of the first (as 3-0 of the second) emit identical points
 * along it, whichever direction each one walks it. */
static void check_shared_edge(void)
{
    const double qa[12] = {0, 0, 0, 1.1, 0.1, 0.3, 0.9, 1.3, 0.2, -0.2, 1, 0};
    const double qb[12] = {1.1, 0.1, 0.3, 2.3, -0.4, 0, 2, 1.7, 1, 0.9, 1.3, 0.2};
    for (int rot = 0; rot < 4; rot++) /* the second quad's corners rotated: each walk direction */
        for (int n = 1; n <= 9; n++) {
            double qr[12];
            for (int i = 0; i < 4; i++)
                memcpy(qr + 3 * i, qb + 3 * ((i + rot) & 3), 3 * sizeof(double));
            qgl_mesh m = {0};
            CHECK(qgl_subdiv_bilinear(qa, 3, n, &m) == 0 && qgl_subdiv_bilinear(qr, 3, n, &m) == 0, "append");
            CHECK(m.ntri == 8 * n * n, "two quads: %d triangles", m.ntri);
            CHECK(border_halfedges(&m) == 6 * n, "n=%d rot %d: two quads not watertight along their edge", n, rot);
            qgl_mesh_free(&m);
        }
}

/* Rotating the corner order gives the same triangles (as sets of points, up to rounding). */
static void check_rotation(void)
{
    for (int rot = 1; rot < 4; rot++) {
        double qr[24];
        for (int i = 0; i < 4; i++)
            memcpy(qr + 6 * i, superquad + 6 * ((i + rot) & 3), 6 * sizeof(double));
        qgl_mesh a = {0}, b = {0};
        CHECK(qgl_subdiv_bilinear(superquad, 6, 3, &a) == 0 && qgl_subdiv_bilinear(qr, 6, 3, &b) == 0, "rotation");
        int unmatched = 0;
        for (int t = 0; t < b.ntri; t++) {
            int found = 0;
            for (int u = 0; u < a.ntri && !found; u++)
                for (int shift = 0; shift < 3 && !found; shift++) {
                    double err = 0;
                    for (int c = 0; c < 3; c++)
                        for (int k = 0; k < 6; k++)
                            err = fmax(err, fabs(vert(&b, t, c)[k] - vert(&a, u, (c + shift) % 3)[k]));
                    found = err < 1e-14;
                }
            unmatched += !found;
        }
        CHECK(unmatched == 0, "rotation by %d: %d triangles differ", rot, unmatched);
        qgl_mesh_free(&a);
        qgl_mesh_free(&b);
    }
}

static void check_bad_args(void)
{
    qgl_mesh m = {0};
    CHECK(qgl_subdiv_bilinear(superquad, 6, 0, &m) < 0 && m.ntri == 0, "n = 0 accepted");
    CHECK(qgl_subdiv_bilinear(superquad, 0, 2, &m) < 0, "stride 0 accepted");
    CHECK(qgl_subdiv_bilinear(NULL, 6, 2, &m) < 0, "NULL quad accepted");
    CHECK(qgl_subdiv_bilinear(superquad, 6, 2, &m) == 0, "good call");
    CHECK(qgl_subdiv_bilinear(superquad, 3, 2, &m) < 0 && m.ntri == 16, "stride change accepted");
    CHECK(qgl_subdiv_adaptive(superquad, 6, 4, -1, -1, NULL, &m) < 0, "pos_off out of range accepted");
    qgl_mesh_free(&m);
    qgl_mesh_free(NULL);
}

/* Oliveira's differences, written out independently. */
static double oliveira_diff(const double *c[4], int off, int dim)
{
    double v12 = 0, v34 = 0, v14 = 0, v23 = 0;
    for (int k = 0; k < dim; k++) {
        double a = c[0][off + k], b = c[1][off + k], cc = c[2][off + k], d = c[3][off + k];
        v12 += (a - b) * (cc - b);
        v34 += (cc - d) * (a - d);
        v14 += (a - b) * (a - d);
        v23 += (cc - b) * (cc - d);
    }
    return fmax(fabs(v12 - v34), fabs(v14 - v23));
}

/* Layout for the adaptive tests: pos (3), uv (2), clip (4). */
enum { STRIDE = 9, POS = 0, TEX = 3, CLIP = 5 };

static void make_quad(const double pos[4][3], const double uv[4][2], double scale_clip, double q[4 * STRIDE])
{
    for (int i = 0; i < 4; i++) {
        for (int k = 0; k < 3; k++)
            q[i * STRIDE + POS + k] = pos[i][k];
        for (int k = 0; k < 2; k++)
            q[i * STRIDE + TEX + k] = uv[i][k];
        /* orthographic: clip = (x, y, z, 1) * scale_clip, NDC = (x, y) */
        q[i * STRIDE + CLIP + 0] = pos[i][0] * scale_clip;
        q[i * STRIDE + CLIP + 1] = pos[i][1] * scale_clip;
        q[i * STRIDE + CLIP + 2] = 0;
        q[i * STRIDE + CLIP + 3] = scale_clip;
    }
}

/* Every leaf is a parallelogram within thresholds, or at max depth, or small on screen;
 * leaves tile the quad (areas add up, all counter-clockwise); every vertex lies on the
 * bilinear patch at the parameters given by its uv (the uv are the unit square). */
static void check_leaves(const qgl_mesh *m, const double q[4 * STRIDE], double area, int check_bilinear_uv,
                         const qgl_adaptive_params *p)
{
    double sum = 0, maxerr = 0;
    int bad = 0;
    for (int t = 0; t + 1 < m->ntri; t += 2) {
        const double *c[4] = {vert(m, t, 0), vert(m, t, 1), vert(m, t, 2), vert(m, t + 1, 2)};
        CHECK(vert(m, t + 1, 0) == c[0] || memcmp(vert(m, t + 1, 0), c[0], STRIDE * sizeof(double)) == 0,
              "leaf triangles do not share corner 0");
        double ar = tri_area_xy(c[0], c[1], c[2]) + tri_area_xy(c[0], c[2], c[3]);
        sum += ar;
        CHECK(tri_area_xy(c[0], c[1], c[2]) > 0 && tri_area_xy(c[0], c[2], c[3]) > 0, "leaf winding");
        double side = sqrt(ar / area); /* depth d leaves have side about 2^-d */
        int at_max = side < 1.5 * ldexp(1, -p->max_depth);
        if (!at_max && !(oliveira_diff(c, POS, 3) < p->threshold_q && oliveira_diff(c, TEX, 2) < p->threshold_t))
            bad++;
        for (int j = 0; j < 4 && check_bilinear_uv; j++)
            for (int k = 0; k < 3; k++)
                maxerr = fmax(maxerr, fabs(c[j][POS + k] - bilinear(q, STRIDE, POS + k, c[j][TEX], c[j][TEX + 1])));
    }
    CHECK(bad == 0, "%d leaves neither parallelograms nor at max depth", bad);
    CHECK(fabs(sum - area) < 1e-12 * area, "leaf areas %.17g, quad %.17g", sum, area);
    CHECK(maxerr < 1e-12, "vertex off the bilinear patch by %g", maxerr);
}

static void check_adaptive(void)
{
    const double sq_uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const double para[4][3] = {{0, 0, 0}, {4, 1, 0}, {5, 4, 0}, {1, 3, 0}};
    const double para_uv[4][2] = {{0, 0}, {0.5, 0}, {0.75, 0.5}, {0.25, 0.5}};
    const double trap[4][3] = {{0, 0, 0}, {4, 0, 0}, {3, 1, 0}, {1, 1, 0}};
    qgl_adaptive_params p = {0};
    p.viewport[0] = p.viewport[1] = 1000;
    double q[4 * STRIDE];
    qgl_mesh m = {0};

    make_quad(para, para_uv, 1, q);
    CHECK(qgl_subdiv_adaptive(q, STRIDE, POS, TEX, CLIP, &p, &m) == 0 && m.ntri == 2,
          "parallelogram with affine uv subdivided: %d triangles", m.ntri);
    CHECK(memcmp(vert(&m, 0, 0), q, STRIDE * sizeof(double)) == 0 &&
              memcmp(vert(&m, 0, 1), q + STRIDE, STRIDE * sizeof(double)) == 0 &&
              memcmp(vert(&m, 1, 2), q + 3 * STRIDE, STRIDE * sizeof(double)) == 0,
          "leaf corners are not the quad's");
    m.ntri = 0;

    make_quad(para, sq_uv, 1, q); /* object parallelogram, texture square: still affine */
    CHECK(qgl_subdiv_adaptive(q, STRIDE, POS, TEX, CLIP, &p, &m) == 0 && m.ntri == 2, "para+square subdivided");
    m.ntri = 0;

    /* trapezoid: refined, leaves pass the test or are at max depth */
    make_quad(trap, sq_uv, 1, q);
    qgl_adaptive_params pd = {1e-3, 1e-4, 200, 8, {0, 0}}; /* no viewport: no area criterion */
    CHECK(qgl_subdiv_adaptive(q, STRIDE, POS, TEX, -1, &pd, &m) == 0, "trapezoid failed");
    printf("trapezoid 4x1: %d triangles\n", m.ntri);
    CHECK(m.ntri > 2 && m.ntri <= 2 * 65536, "trapezoid: %d triangles", m.ntri);
    check_leaves(&m, q, 3.0, 1, &pd);
    m.ntri = 0;

    /* max depth caps the refinement */
    qgl_adaptive_params p3 = {1e-3, 1e-4, 200, 3, {0, 0}};
    CHECK(qgl_subdiv_adaptive(q, STRIDE, POS, TEX, -1, &p3, &m) == 0 && m.ntri <= 2 * 64 && m.ntri > 2,
          "max depth 3: %d triangles", m.ntri);
    check_leaves(&m, q, 3.0, 1, &p3);
    m.ntri = 0;

    /* the screen criterion: the same trapezoid shrinking on screen needs fewer triangles,
     * down to 2 below 200 pixels (fig. 13) */
    int last = 1 << 30;
    for (double px = 400; px >= 2; px /= 2) {
        qgl_adaptive_params pa = {0, 0, 0, 0, {px, px}};
        /* NDC extent of the trapezoid: x in [0,4] -> 4/2 * px/2 ... area = 3 * (px/2)^2 */
        make_quad(trap, sq_uv, 1, q);
        CHECK(qgl_subdiv_adaptive(q, STRIDE, POS, TEX, CLIP, &pa, &m) == 0, "area run");
        double area_px = 3 * (px / 2) * (px / 2);
        CHECK(m.ntri <= last, "viewport %g: %d triangles, more than at a larger size (%d)", px, m.ntri, last);
        if (area_px < 200)
            CHECK(m.ntri == 2, "area %g px: %d triangles", area_px, m.ntri);
        else
            CHECK(m.ntri > 2, "area %g px: not refined", area_px);
        last = m.ntri;
        m.ntri = 0;
    }
    /* a corner behind the eye: no area can be measured, the shape criteria still apply */
    make_quad(trap, sq_uv, 1, q);
    q[2 * STRIDE + CLIP + 3] = -1;
    CHECK(qgl_subdiv_adaptive(q, STRIDE, POS, TEX, CLIP, &p, &m) == 0 && m.ntri > 2, "w < 0 corner");
    m.ntri = 0;
    double nanq[4 * STRIDE];
    memcpy(nanq, q, sizeof nanq);
    nanq[5] = NAN;
    CHECK(qgl_subdiv_adaptive(nanq, STRIDE, POS, TEX, CLIP, &p, &m) < 0 && m.ntri == 0, "NaN accepted");
    qgl_mesh_free(&m);
}

int main(void)
{
    check_bilinear();
    check_shared_edge();
    check_rotation();
    check_bad_args();
    check_adaptive();
    printf("%d failures\n", failures);
    return failures ? 1 : 0;
}
