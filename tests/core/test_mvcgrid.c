/* test_mvcgrid: the mean value grid's structure, its vertex weights, and its tabulated bounds
 * re-derived on random quads.
 *
 * Structure: every triangle is counter-clockwise in (u, v) with positive area, their areas
 * sum to the unit square's, and the only edges used by one triangle are the four corner-to-
 * corner sides (no boundary vertex: no T-junction with any neighbour). Weights:
 * qgl_mvcgrid_weights equals qgl_weights (double) at every vertex within 1e-12, under
 * perspective. Bounds: for random quads of the class (angles within 45 degrees of a right
 * angle, no edge under a third of the longest; another seed than the one the table was measured with), the largest difference
 * between the linearly interpolated and the exact screen weights, sampled on a barycentric
 * lattice of 8 per triangle edge, must stay under bound / 1.25. "--table N" prints the
 * measured maxima over N quads per grid instead (how the table was made). */
#include <math.h>
#include <quadgl/quadgl.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

static double rnd(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return (double)(*s >> 8 & 0xffffff) / 16777216.0;
}

/* A random quad of the class: corners around a circle, angles and radii jittered. */
static void random_quad(unsigned *seed, double v[4][2])
{
    do {
        double a0 = rnd(seed) * 2 * M_PI;
        for (int i = 0; i < 4; i++) {
            double a = a0 + i * M_PI / 2 + (rnd(seed) - 0.5) * M_PI * 0.6, r = 0.3 + rnd(seed);
            v[i][0] = r * cos(a) * 100, v[i][1] = r * sin(a) * 100;
        }
    } while (!qgl_mvcgrid_fits(v));
}

static void screen_weights(const double v[4][2], double x, double y, double out[4])
{
    double clip[4][4], persp[4];
    for (int i = 0; i < 4; i++)
        clip[i][0] = v[i][0], clip[i][1] = v[i][1], clip[i][2] = 0, clip[i][3] = 1;
    qgl_weights(clip, x, y, persp, out);
}

/* Largest |interpolated - exact| (Euclidean over the four weights) over g on quad v. */
static double grid_error(const qgl_mvcgrid *g, const double v[4][2])
{
    enum { S = 8 };
    double (*p)[2] = malloc((size_t)g->nverts * sizeof *p), (*lam)[4] = malloc((size_t)g->nverts * sizeof *lam);
    qgl_mvcgrid_points(g, v, p);
    for (int j = 0; j < g->nverts; j++)
        screen_weights(v, p[j][0], p[j][1], lam[j]);
    double worst = 0;
    for (int t = 0; t < g->ntris; t++) {
        const uint16_t *tr = g->tri[t];
        for (int a = 0; a <= S; a++)
            for (int b = 0; a + b <= S; b++) {
                double ba[3] = {(double)a / S, (double)b / S, (double)(S - a - b) / S}, x = 0, y = 0, lin[4] = {0};
                for (int c = 0; c < 3; c++) {
                    x += ba[c] * p[tr[c]][0], y += ba[c] * p[tr[c]][1];
                    for (int i = 0; i < 4; i++)
                        lin[i] += ba[c] * lam[tr[c]][i];
                }
                double ex[4], e2 = 0;
                screen_weights(v, x, y, ex);
                for (int i = 0; i < 4; i++)
                    e2 += (lin[i] - ex[i]) * (lin[i] - ex[i]);
                worst = e2 > worst ? e2 : worst;
            }
    }
    free(p);
    free(lam);
    return sqrt(worst);
}

static void check_structure(const qgl_mvcgrid *g)
{
    double area = 0;
    int nedge = 0, boundary = 0, bad_boundary = 0;
    int (*edges)[3] = malloc((size_t)g->ntris * 3 * sizeof *edges);
    for (int t = 0; t < g->ntris; t++) {
        const uint16_t *tr = g->tri[t];
        const float *a = g->uv[tr[0]], *b = g->uv[tr[1]], *c = g->uv[tr[2]];
        double o = ((double)b[0] - a[0]) * ((double)c[1] - a[1]) - ((double)b[1] - a[1]) * ((double)c[0] - a[0]);
        CHECK(o > 0, "k=%d triangle %d not counter-clockwise (%g)", g->k, t, o);
        area += o / 2;
        for (int e = 0; e < 3; e++) {
            int i = tr[e], j = tr[(e + 1) % 3], lo = i < j ? i : j, hi = i < j ? j : i, f;
            for (f = 0; f < nedge; f++)
                if (edges[f][0] == lo && edges[f][1] == hi)
                    break;
            if (f == nedge)
                edges[nedge][0] = lo, edges[nedge][1] = hi, edges[nedge++][2] = 0;
            edges[f][2]++;
        }
    }
    for (int f = 0; f < nedge; f++) {
        CHECK(edges[f][2] <= 2, "k=%d edge %d-%d in %d triangles", g->k, edges[f][0], edges[f][1], edges[f][2]);
        if (edges[f][2] == 1) {
            boundary++;
            int lo = edges[f][0], hi = edges[f][1];
            bad_boundary += !(hi < 4 && (hi - lo == 1 || (lo == 0 && hi == 3)));
        }
    }
    CHECK(boundary == 4 && bad_boundary == 0, "k=%d: %d boundary edges, %d not between corners", g->k, boundary,
          bad_boundary);
    CHECK(fabs(area - 1) < 1e-6, "k=%d: triangles cover %g of the unit square", g->k, area);
    free(edges);
}

/* qgl_mvcgrid_weights against qgl_weights at every vertex, corners in perspective. */
static void check_weights(const qgl_mvcgrid *g, unsigned *seed)
{
    double v[4][2], clip[4][4];
    random_quad(seed, v);
    for (int i = 0; i < 4; i++) {
        double w = 0.5 + 3 * rnd(seed);
        clip[i][0] = v[i][0] * w, clip[i][1] = v[i][1] * w, clip[i][2] = 0, clip[i][3] = w;
    }
    double (*p)[2] = malloc((size_t)g->nverts * sizeof *p), (*persp)[4] = malloc((size_t)g->nverts * sizeof *persp);
    CHECK(qgl_mvcgrid_weights(g, clip, p, persp), "k=%d: weights refused a quad of the class", g->k);
    double worst = 0;
    for (int j = 0; j < g->nverts; j++) {
        double ref[4], scr[4];
        qgl_weights(clip, p[j][0], p[j][1], ref, scr);
        for (int i = 0; i < 4; i++)
            worst = fmax(worst, fabs(ref[i] - persp[j][i]));
    }
    CHECK(worst < 1e-12, "k=%d: vertex weights differ from qgl_weights by %g", g->k, worst);
    free(p);
    free(persp);
}

static void check_class(void)
{
    const double square[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, cw[4][2] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    const double concave[4][2] = {{0, 0}, {1, 0}, {0.3, 0.3}, {0, 1}}, bowtie[4][2] = {{0, 0}, {1, 1}, {1, 0}, {0, 1}};
    const double sharp[4][2] = {{0, 0}, {1, 0}, {1.8, 1}, {0.8, 1}}; /* 51 and 129 degrees: in */
    const double thin[4][2] = {{0, 0}, {1, 0}, {1, 0.3}, {0, 0.3}}; /* edges 0.3 of the longest: out */
    const double sharper[4][2] = {{0, 0}, {1, 0}, {2.5, 1}, {1.5, 1}}; /* 34 degrees: out */
    CHECK(qgl_mvcgrid_fits(square) && qgl_mvcgrid_fits(cw) && qgl_mvcgrid_fits(sharp), "class rejects a good quad");
    CHECK(!qgl_mvcgrid_fits(concave) && !qgl_mvcgrid_fits(bowtie) && !qgl_mvcgrid_fits(sharper) && !qgl_mvcgrid_fits(thin),
          "class accepts a concave, bow-tie, sharp or thin quad");
}

int main(int argc, char **argv)
{
    int table = argc > 2 && !strcmp(argv[1], "--table") ? atoi(argv[2]) : 0;
    unsigned seed = table ? 1u : 20240613u;
    check_class();
    for (int r = 0; r < qgl_mvcgrid_count(); r++) {
        const qgl_mvcgrid *g = qgl_mvcgrid_at(r);
        CHECK(g != NULL, "grid %d not built", r);
        if (!g)
            continue;
        check_structure(g);
        check_weights(g, &seed);
        int n = table ? table : g->k <= 8 ? 150 : g->k <= 16 ? 30 : 8;
        double worst = 0;
        for (int q = 0; q < n; q++) {
            double v[4][2];
            random_quad(&seed, v);
            worst = fmax(worst, grid_error(g, v));
        }
        printf("k=%2d: %4d vertices %4d triangles, max |eps| %.4f over %d quads, bound %.4f (margin %.2f)\n", g->k,
               g->nverts, g->ntris, worst, n, g->bound, g->bound / worst);
        if (!table)
            CHECK(worst * 1.25 <= g->bound, "k=%d: measured %.4f leaves less than 1.25 of margin to the bound %.4f",
                  g->k, worst, g->bound);
    }
    CHECK(qgl_mvcgrid_choose(1.0) == 0 && qgl_mvcgrid_choose(0.0) == -1, "choose");
    printf("%s\n", failures ? "FAILED" : "ok");
    return failures ? 1 : 0;
}
