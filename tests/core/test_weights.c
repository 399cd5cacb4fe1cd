/* test_weights.c: qgl_weights / qgl_weightsf against the __float128 reference on the hard-case suite.
 *
 * Checked on every case: no NaN/inf output for finite input; the documented codes and
 * weights for bad input; accuracy against the reference (double 1e-12, float 1e-5, every
 * weight, wherever the reference's weights are bounded); inside/outside agreement away
 * from the boundary; weights summing to 1 and nonnegative inside; the Lagrange property at
 * corners; linear precision (sum persp_i * (x_i - p w_i) = 0); invariance under rotating
 * the corner order. `--table` prints the accuracy table of the paper's formula,
 * Bloomenthal's guarded formula and ours (float and double), as in the README. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <quadgl/quadgl.h>
#include "hardcases.h"

static int failures;

#define CHECK(cond, c, ...)                                                                    \
    do {                                                                                       \
        if (!(cond)) {                                                                         \
            if (failures++ < 25) {                                                             \
                fprintf(stderr, "FAIL %s:%d [%s p=(%.17g, %.17g)] ", __FILE__, __LINE__,       \
                        (c)->group, (c)->p[0], (c)->p[1]);                                     \
                fprintf(stderr, __VA_ARGS__);                                                  \
                fputc('\n', stderr);                                                           \
            }                                                                                  \
        }                                                                                      \
    } while (0)

static int all_finite(const double *a, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(a[i]))
            return 0;
    return 1;
}

static double max_diff(const double *a, const double *b, int n)
{
    double m = 0;
    for (int i = 0; i < n; i++)
        m = fmax(m, fabs(a[i] - b[i]));
    return isnan(m) ? INFINITY : m;
}

static double abs_sum(const double *a)
{
    return fabs(a[0]) + fabs(a[1]) + fabs(a[2]) + fabs(a[3]);
}

/* The reference's weights are bounded (accuracy is measured there; far outside points
 * where sum(nu) ~ 0 have unbounded weights and only need to be finite). */
static int measurable(int code, const double *persp, const double *screen)
{
    return (code == QGL_INSIDE || code == QGL_OUTSIDE) && abs_sum(persp) <= 8 && abs_sum(screen) <= 8;
}

static void check_bad_input(const hc_case *c, int code, const double *persp, const double *screen)
{
    CHECK(code == QGL_NONFINITE, c, "code %d, want QGL_NONFINITE", code);
    for (int i = 0; i < 4; i++)
        CHECK(persp[i] == 0.25 && screen[i] == 0.25, c, "weight %d = %g, want 1/4", i, persp[i]);
}

/* Properties of the double version that do not need the reference. */
static void check_invariants(const hc_case *c, int code, const double *persp)
{
    if (code != QGL_INSIDE)
        return;
    double sum = 0, lx = 0, ly = 0, mag = 0; /* mag: the quad's extent around p */
    for (int i = 0; i < 4; i++) {
        sum += persp[i];
        CHECK(persp[i] >= -1e-12, c, "negative weight %d inside: %g", i, persp[i]);
        double sx = fma(-c->p[0], c->clip[i][3], c->clip[i][0]), sy = fma(-c->p[1], c->clip[i][3], c->clip[i][1]);
        lx += persp[i] * sx;
        ly += persp[i] * sy;
        mag = fmax(mag, hypot(sx, sy));
    }
    CHECK(fabs(sum - 1) <= 1e-12, c, "weights sum to 1%+g", sum - 1);
    CHECK(hypot(lx, ly) <= 1e-14 * mag, c, "linear precision: residual %g of %g", hypot(lx, ly), mag);
    for (int i = 0; i < 4; i++) {
        double vx = c->clip[i][0] / c->clip[i][3], vy = c->clip[i][1] / c->clip[i][3];
        if (vx == c->p[0] && vy == c->p[1] && c->clip[i][3] == 1) {
            int coincident = 0;
            for (int j = 0; j < 4; j++)
                coincident += c->clip[j][0] == c->clip[i][0] && c->clip[j][1] == c->clip[i][1];
            CHECK(fabs(persp[i] - 1.0 / coincident) <= 1e-15, c, "Lagrange: weight %d = %.17g", i, persp[i]);
        }
    }
}

static void check_rotation(const hc_case *c, const double *persp)
{
    double clip[4][4], rp[4], rs[4];
    for (int i = 0; i < 4; i++)
        memcpy(clip[i], c->clip[(i + 1) & 3], sizeof clip[i]);
    int code = qgl_weights(clip, c->p[0], c->p[1], rp, rs);
    if (code != QGL_INSIDE)
        return;
    for (int i = 0; i < 4; i++)
        CHECK(fabs(rp[i] - persp[(i + 1) & 3]) <= 1e-12, c, "rotation changes weight %d by %g", i,
              rp[i] - persp[(i + 1) & 3]);
}

typedef struct stats {
    double max_err;
    int nonfinite, over;
} stats;

static void account(stats *s, double err, int finite)
{
    if (!finite || !isfinite(err))
        s->nonfinite++;
    else
        s->max_err = fmax(s->max_err, err);
    if (!(err <= 1e-5))
        s->over++;
}

int main(int argc, char **argv)
{
    int table = argc > 1 && strcmp(argv[1], "--table") == 0;
    hc_case *cases;
    int n = hc_build(&cases), measured = 0;
    stats st[4] = {{0}};

    for (int k = 0; k < n; k++) {
        const hc_case *c = &cases[k];
        double pd[4], sd[4], rp[4], rs[4], rfp[4], rfs[4], fclip_d[4][4];
        float fclip[4][4], fp[2], pf[4], sf[4], paper[4], bloom[4];
        int finite_in = isfinite(c->p[0]) && isfinite(c->p[1]);
        for (int i = 0; i < 16; i++)
            finite_in = finite_in && isfinite(c->clip[i / 4][i % 4]);

        int code = qgl_weights(c->clip, c->p[0], c->p[1], pd, sd);
        int ref = hc_reference(c->clip, c->p[0], c->p[1], rp, rs);
        hc_to_float(c, fclip, fp);
        for (int i = 0; i < 16; i++)
            fclip_d[i / 4][i % 4] = fclip[i / 4][i % 4];
        int fcode = qgl_weightsf(fclip, fp[0], fp[1], pf, sf);
        int fref = hc_reference(fclip_d, fp[0], fp[1], rfp, rfs);
        qgl_weights_paper(fclip, fp[0], fp[1], paper);
        qgl_weights_bloomenthal(fclip, fp[0], fp[1], bloom);
        double pfd[8], paperd[4], bloomd[4];
        for (int i = 0; i < 4; i++) {
            pfd[i] = pf[i];
            pfd[4 + i] = sf[i];
            paperd[i] = paper[i];
            bloomd[i] = bloom[i];
        }

        if (!finite_in) {
            check_bad_input(c, code, pd, sd);
            double f4[4] = {pf[0], pf[1], pf[2], pf[3]}, s4[4] = {sf[0], sf[1], sf[2], sf[3]};
            check_bad_input(c, fcode, f4, s4);
            continue;
        }
        CHECK(all_finite(pd, 4) && all_finite(sd, 4), c, "double output not finite");
        CHECK(all_finite(pfd, 8), c, "float output not finite");
        if (strcmp(c->group, "zero-area") == 0) {
            CHECK(code == QGL_DEGENERATE, c, "zero-area quad: code %d", code);
            CHECK(fcode == QGL_DEGENERATE, c, "zero-area quad (float): code %d", fcode);
            continue;
        }
        CHECK(code == QGL_INSIDE || code == QGL_OUTSIDE, c, "code %d for a quad with interior", code);
        if (c->dist < 0 || c->dist >= 1e-5)
            CHECK(code == ref, c, "double says %d, reference %d", code, ref);
        if (c->dist < 0 || c->dist >= 1e-3)
            CHECK(fcode == fref || fref == QGL_DEGENERATE, c, "float says %d, reference %d", fcode, fref);
        if (c->dist == 0 && ref == QGL_INSIDE)
            CHECK(code == QGL_INSIDE, c, "point on the boundary reported outside");
        check_invariants(c, code, pd);
        if (c->clip[0][3] == 1 && c->clip[1][3] == 1 && c->clip[2][3] == 1 && c->clip[3][3] == 1) {
            double v[4][2], l2[4];
            for (int i = 0; i < 4; i++)
                v[i][0] = c->clip[i][0], v[i][1] = c->clip[i][1];
            int code2 = qgl_weights2d(v, c->p[0], c->p[1], l2);
            CHECK(code2 == code && max_diff(l2, pd, 4) == 0, c, "qgl_weights2d differs from qgl_weights (w = 1)");
        }
        check_rotation(c, pd);

        if (measurable(ref, rp, rs)) {
            double err = fmax(max_diff(pd, rp, 4), max_diff(sd, rs, 4));
            CHECK(err <= 1e-12, c, "double error %g (persp %g %g %g %g, ref %g %g %g %g)", err, pd[0], pd[1],
                  pd[2], pd[3], rp[0], rp[1], rp[2], rp[3]);
            account(&st[3], err, 1);
            measured++;
        }
        /* Within float resolution of a bow-tie's crossing point the weights jump with the
         * direction of approach (a 0/0 point): any convex combination there is the limit. */
        int fjump = strncmp(c->group, "bow-tie", 7) == 0 && hypot(c->p[0], c->p[1]) < 1e-5;
        if (measurable(fref, rfp, rfs) && !fjump) {
            double errf = fmax(max_diff(pfd, rfp, 4), max_diff(pfd + 4, rfs, 4));
            CHECK(errf <= 1e-5, c, "float error %g (persp %g %g %g %g, ref %g %g %g %g)", errf, pf[0], pf[1],
                  pf[2], pf[3], rfp[0], rfp[1], rfp[2], rfp[3]);
            if (fcode == QGL_INSIDE) {
                double sum = pf[0] + pf[1] + pf[2] + pf[3];
                CHECK(fabs(sum - 1) <= 1e-5, c, "float weights sum to 1%+g", sum - 1);
            }
            account(&st[2], errf, 1);
            account(&st[0], max_diff(paperd, rfp, 4), all_finite(paperd, 4));
            account(&st[1], max_diff(bloomd, rfp, 4), all_finite(bloomd, 4));
        }
    }

    const char *names[4] = {"H&T pseudo-code as printed (float)", "Bloomenthal, t = 0 where abs(A) < 1e-6 (float)",
                            "quadgl qgl_weightsf (float)", "quadgl qgl_weights (double)"};
    FILE *out = table ? stdout : stderr;
    fprintf(out, "Weights on the hard-case suite: %d cases, %d with bounded reference weights\n\n", n, measured);
    fprintf(out, "| formula | max abs error (finite outputs) | NaN/inf outputs | cases over 1e-5 |\n");
    fprintf(out, "|---|---|---|---|\n");
    for (int m = 0; m < 4; m++)
        fprintf(out, "| %s | %.2e | %d | %d |\n", names[m], st[m].max_err, st[m].nonfinite, st[m].over);
    free(cases);
    if (failures)
        fprintf(stderr, "%d check(s) failed\n", failures);
    return failures ? 1 : 0;
}
