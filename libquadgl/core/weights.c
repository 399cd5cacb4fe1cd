/* weights.c: robust perspective-correct mean value weights of a point in a quad (H&T 2004).
 *
 * We evaluate H&T's eq. (8)/(10) in homogeneous form. With clip corners (x_i, y_i, w_i) and
 * the point p, let s~_i = (x_i - p.x w_i, y_i - p.y w_i) = w_i s_i. The half-angle tangents
 * are unchanged by the w_i (signs included: the angle between s~_i and s~_{i+1} is the
 * exterior angle exactly when w_i w_{i+1} < 0, which is H&T's rule for corners behind the
 * eye), and mu_i / w_i = (t_{i-1} + t_i) / |s~_i| =: nu_i. So the perspective weights are
 * nu / sum(nu) with no division by w at all: corners at w = 0 (at infinity) and w < 0 need
 * no special case, and inside means "all nu_i share one sign". Screen weights (eq. 7, for
 * depth) are w_i nu_i / sum(w_j nu_j).
 *
 * Robustness: t_i = tan(alpha_i / 2) is (P - D) / A or A / (P + D) (P = |s~_i||s~_{i+1}|,
 * D dot, A cross); we take the form whose denominator does not cancel. A collapsed edge or a
 * point on an edge's outer extension (A = 0, D > 0) gives 0 exactly. The two real 0/0 and
 * inf/inf cases get their limits: a point on a corner (|s~_i| tiny against the sum of all
 * |s~_j|) gets that corner; a point on an edge segment (A tiny against P - D, D < 0) gets the
 * linear interpolation along the edge. All tolerances are a few units of roundoff relative
 * to quantities of the quad, never absolute. s~ is formed with an exact product, so small
 * quads far from the origin keep their precision. The same code serves float and double
 * (weights_impl.h); the float version uses float arithmetic only. */
#include <math.h>
#include <float.h>
#include <quadgl/quadgl.h>

#define R double
#define FN(name) name##_d
#define EPS (DBL_EPSILON / 2)
#define SQRT sqrt
#define FABS fabs
#define FREXP frexp
#define LDEXP ldexp
#define RMIN DBL_MIN
#define ISFINITE isfinite
#define SPLITTER 134217729.0 /* 2^27 + 1 */
#include "weights_impl.h"
#undef R
#undef FN
#undef EPS
#undef SQRT
#undef FABS
#undef FREXP
#undef LDEXP
#undef RMIN
#undef SPLITTER

#define R float
#define FN(name) name##_f
#define EPS (FLT_EPSILON / 2)
#define SQRT sqrtf
#define FABS fabsf
#define FREXP frexpf
#define LDEXP ldexpf
#define RMIN FLT_MIN
#define SPLITTER 4097.0f /* 2^12 + 1 */
#include "weights_impl.h"

QGL_API int qgl_weights(const double clip[4][4], double x, double y, double persp[4], double screen[4])
{
    return weights_d(clip, x, y, persp, screen);
}

QGL_API int qgl_weightsf(const float clip[4][4], float x, float y, float persp[4], float screen[4])
{
    return weights_f(clip, x, y, persp, screen);
}

QGL_API int qgl_weights2d(const double v[4][2], double x, double y, double lambda[4])
{
    double clip[4][4];
    for (int i = 0; i < 4; i++) {
        clip[i][0] = v[i][0];
        clip[i][1] = v[i][1];
        clip[i][2] = 0;
        clip[i][3] = 1;
    }
    return weights_d(clip, x, y, lambda, NULL);
}

/* H&T's pseudo-code (sec. 4.2) exactly as printed, then eq. (10) for perspective. */
QGL_API void qgl_weights_paper(const float clip[4][4], float x, float y, float persp[4])
{
    float s[4][2], r[4], t[4], mu[4], w[4], sum = 0, psum = 0;
    for (int i = 0; i < 4; i++) {
        w[i] = clip[i][3];
        s[i][0] = clip[i][0] / w[i] - x;
        s[i][1] = clip[i][1] / w[i] - y;
        r[i] = sqrtf(s[i][0] * s[i][0] + s[i][1] * s[i][1]) * (w[i] < 0 ? -1.0f : 1.0f);
    }
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        float a = s[i][0] * s[j][1] - s[i][1] * s[j][0];
        float d = s[i][0] * s[j][0] + s[i][1] * s[j][1];
        t[i] = (r[i] * r[j] - d) / a;
    }
    for (int i = 0; i < 4; i++)
        sum += mu[i] = (t[(i + 3) & 3] + t[i]) / r[i];
    for (int i = 0; i < 4; i++)
        psum += persp[i] = mu[i] / sum / w[i];
    for (int i = 0; i < 4; i++)
        persp[i] /= psum;
}

/* Bloomenthal's shader (JCGT 2022, listing 2): the paper's formula with t = 0 whenever
 * |A| < 1e-6, then eq. (10) for perspective. */
QGL_API void qgl_weights_bloomenthal(const float clip[4][4], float x, float y, float persp[4])
{
    float s[4][2], r[4], t[4], u[4], w[4], sum = 0, psum = 0;
    for (int i = 0; i < 4; i++) {
        w[i] = clip[i][3];
        s[i][0] = clip[i][0] / w[i] - x;
        s[i][1] = clip[i][1] / w[i] - y;
        r[i] = sqrtf(s[i][0] * s[i][0] + s[i][1] * s[i][1]) * (w[i] < 0 ? -1.0f : w[i] > 0 ? 1.0f : 0.0f);
    }
    for (int i = 0; i < 4; i++) {
        int j = (i + 1) & 3;
        float a = s[i][0] * s[j][1] - s[i][1] * s[j][0];
        float d = s[i][0] * s[j][0] + s[i][1] * s[j][1];
        t[i] = fabsf(a) < 1e-6f ? 0.0f : (r[i] * r[j] - d) / a;
    }
    for (int i = 0; i < 4; i++)
        sum += u[i] = (t[(i + 3) & 3] + t[i]) / r[i];
    for (int i = 0; i < 4; i++)
        psum += persp[i] = u[i] / sum / w[i];
    for (int i = 0; i < 4; i++)
        persp[i] /= psum;
}
