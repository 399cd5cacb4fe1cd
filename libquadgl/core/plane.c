/* plane.c: view-invariant weights: mean value coordinates in the quad's own plane.
 *
 * Screen-space mean value weights (weights.c) are not projectively invariant: from every
 * viewpoint they pick a different set of weights for the same surface point, so textures
 * swim as the camera moves. A quad's plane has a 2D frame fixed to the quad; the position of
 * a surface point in it does not depend on the view, and a rasterizer hands it over exactly
 * as a perspective-correct varying (it is affine on the surface). Weights computed there are
 * view-invariant, keep linear precision (a planar quad's affine attributes are reproduced
 * exactly, as by the split), are linear on every edge (so neighbours drawn by any path meet
 * without a seam) and need no case for corners behind the eye.
 *
 * The frame: origin at the corners' centroid; normal the longest of the diagonals' cross
 * product (Newell's normal, the best-fit direction of a non-planar quad) and the four corner
 * normals (for a planar quad every one of them is the plane's normal, and the longest is the
 * best conditioned: a bow-tie's diagonals' product may vanish, a concave quad's corner
 * opposite the reflex one is longer); first axis along the longer diagonal, made orthogonal
 * to the normal; second axis normal x first. A non-planar quad is projected onto that plane
 * (the heights say how far its corners are from it), and its surface is taken as the split
 * along the preferred diagonal, the shorter one in object space (chosen from positions
 * alone, so rotating the corner order does not change it). The corners are translated and
 * scaled by a power of two before any product, so the frame is as accurate for small quads
 * far from the origin as for unit ones. The weights themselves are the core's robust ones
 * (weights.c with every w = 1), so corners, edges and collapsed edges get their limits. */
#include <math.h>
#include <float.h>
#include <string.h>
#include <quadgl/quadgl.h>

#define R double
#define PLANE qgl_plane
#define FN(name) plane_##name##_d
#define EPS (DBL_EPSILON / 2)
#define BIG (DBL_MAX / 64)
#define SQRT sqrt
#define FABS fabs
#define FREXP frexp
#define LDEXP ldexp
#define RMIN DBL_MIN
#define ISFINITE isfinite
#include "plane_impl.h"
#undef R
#undef PLANE
#undef FN
#undef EPS
#undef BIG
#undef SQRT
#undef FABS
#undef FREXP
#undef LDEXP
#undef RMIN

#define R float
#define PLANE qgl_planef
#define FN(name) plane_##name##_f
#define EPS (FLT_EPSILON / 2)
#define BIG (FLT_MAX / 64)
#define SQRT sqrtf
#define FABS fabsf
#define FREXP frexpf
#define LDEXP ldexpf
#define RMIN FLT_MIN
#include "plane_impl.h"

QGL_API int qgl_plane_frame(const double pos[4][3], qgl_plane *out)
{
    return plane_frame_d(pos, out);
}

QGL_API int qgl_plane_framef(const float pos[4][3], qgl_planef *out)
{
    return plane_frame_f(pos, out);
}

QGL_API void qgl_plane_coords(const qgl_plane *pl, const double p[3], double xy[2])
{
    plane_coords_d(pl, p, xy);
}

QGL_API void qgl_plane_coordsf(const qgl_planef *pl, const float p[3], float xy[2])
{
    plane_coords_f(pl, p, xy);
}

QGL_API int qgl_weights_inplane(const qgl_plane *pl, double x, double y, double lambda[4])
{
    return qgl_weights2d(pl->corner, x, y, lambda);
}

QGL_API int qgl_weights_inplanef(const qgl_planef *pl, float x, float y, float lambda[4])
{
    float clip[4][4];
    for (int i = 0; i < 4; i++) {
        clip[i][0] = pl->corner[i][0];
        clip[i][1] = pl->corner[i][1];
        clip[i][2] = 0;
        clip[i][3] = 1;
    }
    return qgl_weightsf(clip, x, y, lambda, NULL);
}

QGL_API int qgl_weights_plane(const double pos[4][3], const double p[3], double lambda[4])
{
    qgl_plane pl;
    double xy[2], spos[4][3], sp[3];
    plane_scale_all_d(pos, p, spos, sp);
    int r = qgl_plane_frame((const double(*)[3])spos, &pl);
    plane_coords_d(&pl, sp, xy);
    int w = qgl_weights_inplane(&pl, isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]) ? xy[0] : NAN, xy[1], lambda);
    return r < 0 && w != QGL_NONFINITE ? r : w;
}

QGL_API int qgl_weights_planef(const float pos[4][3], const float p[3], float lambda[4])
{
    qgl_planef pl;
    float xy[2], spos[4][3], sp[3];
    plane_scale_all_f(pos, p, spos, sp);
    int r = qgl_plane_framef((const float(*)[3])spos, &pl);
    plane_coords_f(&pl, sp, xy);
    int w = qgl_weights_inplanef(&pl, isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]) ? xy[0] : NAN, xy[1], lambda);
    return r < 0 && w != QGL_NONFINITE ? r : w;
}

QGL_API int qgl_plane_cover(const qgl_plane *pl, qgl_cover *out)
{
    int kind = qgl_classify(pl->corner, out);
    if (out && kind == QGL_QUAD_CONVEX && out->ntri == 2 && pl->diagonal) {
        static const unsigned char along13[2][3] = {{1, 2, 3}, {1, 3, 0}};
        memcpy(out->tri, along13, sizeof along13);
    }
    return kind;
}
