/* quadgl: smooth quadrilaterals for OpenGL (Hormann & Tarini 2004 mean value coordinates).
 *
 * Three layers share this header:
 *   - the numeric core (qgl_weights & friends): pure C, no GL, usable anywhere;
 *   - the software renderer (qgl_sw_*): quads drawn by every known method into float buffers;
 *   - the GL helper (qgl_gl_* and the qgl* immediate API): smooth quads inside a live GL context.
 *
 * Conventions: corners come in GL order (0,1,2,3 around the quad). Clip-space corners are
 * (x, y, z, w); screen points are normalized device coordinates. Every function that takes
 * geometry accepts any finite or non-finite input without crashing; bad input returns a
 * documented negative code and leaves outputs finite. */
#ifndef QUADGL_H
#define QUADGL_H

#include <stddef.h>
#include <stdint.h>

#if defined(QGL_BUILDING) && defined(__GNUC__)
#define QGL_API __attribute__((visibility("default")))
#else
#define QGL_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

#define QGL_VERSION_MAJOR 0
#define QGL_VERSION_MINOR 1

/* ---- weights ---------------------------------------------------------------------------- */

/* Return codes of the weight and classification functions. */
enum {
    QGL_OUTSIDE = 0,     /* point outside the quad; weights finite (mixed signs) */
    QGL_INSIDE = 1,      /* point inside or on the boundary; weights >= 0, sum 1 */
    QGL_DEGENERATE = -1, /* quad has no interior on screen (all corners collinear or
                            coincident, or every w == 0); weights finite: on the degenerate
                            outline they interpolate along it, elsewhere unspecified */
    QGL_NONFINITE = -2   /* an input is NaN or infinite; weights = 1/4 each */
};

/* Perspective-correct mean value weights of the point (x, y), in normalized device
 * coordinates, with respect to the quad whose corners are given in clip space
 * (x, y, z, w), in GL order. persp receives lambda'_i (H&T eq. 10): an attribute is
 * sum persp[i] * a_i. screen (may be NULL) receives lambda_i (eq. 7), used for depth.
 * Returns QGL_INSIDE (1) when the point is inside or on the boundary, QGL_OUTSIDE (0)
 * otherwise (weights still finite), or a negative QGL_DEGENERATE code when the quad has
 * no interior on screen or an input is not finite (weights then finite and documented). */
QGL_API int qgl_weights(const double clip[4][4], double x, double y, double persp[4], double screen[4]);
QGL_API int qgl_weightsf(const float clip[4][4], float x, float y, float persp[4], float screen[4]);

/* Screen-space (affine, no perspective) mean value weights of (x, y) with respect to the 2D
 * quad v, with every w taken as +1. Same return codes. */
QGL_API int qgl_weights2d(const double v[4][2], double x, double y, double lambda[4]);

/* The formulas we compare against in the accuracy table (not for production use):
 * H&T's pseudo-code as printed (t = (r r' - D) / A, no limits) and Bloomenthal's shader
 * (abs(A) < 1e-6 ? 0 : ...), both in float. They return the raw perspective weights and
 * may produce NaN or inf; that is what the table measures. */
QGL_API void qgl_weights_paper(const float clip[4][4], float x, float y, float persp[4]);
QGL_API void qgl_weights_bloomenthal(const float clip[4][4], float x, float y, float persp[4]);

/* ---- classification and cover ------------------------------------------------------------ */

typedef enum {
    QGL_QUAD_CONVEX = 0,
    QGL_QUAD_CONCAVE = 1,  /* one reflex corner */
    QGL_QUAD_BOWTIE = 2,   /* self-intersecting: two lobes of opposite facing */
    QGL_QUAD_EXTERNAL = 3, /* corners on both sides of the eye plane (w of mixed sign) */
    QGL_QUAD_DEGENERATE = 4
} qgl_quad_kind;

/* A triangle of the cover: indices 0..3 name the quad's corners, 4 the bow-tie crossing
 * point. Triangles keep the winding of the region they cover (a bow-tie's lobes differ). */
typedef struct qgl_cover {
    qgl_quad_kind kind;
    int orientation;     /* +1 counter-clockwise, -1 clockwise, 0 (bow-tie or degenerate) */
    int reflex;          /* concave: index of the reflex corner, else -1 */
    int cross_edge;      /* bow-tie: 0 when edges 01 and 23 cross, 1 when 12 and 30, else -1 */
    double cross[2];     /* bow-tie: the crossing point */
    double cross_t;      /* bow-tie: crossing as a parameter along edge cross_edge (01 or 12) */
    int ntri;            /* 0, 1 or 2 */
    unsigned char tri[2][3];
} qgl_cover;

/* Classify the screen quad v (NDC or window coordinates; scale-free tolerances) and fill
 * its exact cover: every interior point lies in exactly one triangle. Returns the kind, or
 * QGL_NONFINITE (out then degenerate, ntri == 0). Three collinear corners (a collapsed edge,
 * a straight corner, a spike, a bow-tie touching at a corner) leave a triangle: convex with
 * ntri == 1. A turn below 64 eps of the quad's size counts as collinear. Convex quads split
 * as (0,1,2),(0,2,3); concave ones along the diagonal from the reflex corner r as
 * (r,r+1,r+2),(r,r+2,r+3). out may be NULL. */
QGL_API int qgl_classify(const double v[4][2], qgl_cover *out);
/* The same from clip-space corners (x/w, y/w; all w > 0 or all w < 0). QGL_QUAD_EXTERNAL
 * when the w differ in sign or some (not all) w are 0: the cover is then left to a
 * homogeneous clipper (ntri == 0). Every w == 0: QGL_QUAD_DEGENERATE. */
QGL_API int qgl_classify_clip(const double clip[4][4], qgl_cover *out);

/* Membership test of H&T eq. (12) on the screen quad v: +1 inside and front-facing
 * (counter-clockwise locally), -1 inside and back-facing, 0 outside. Points exactly on an
 * edge count as inside (as front-facing when both apply); for a collinear quad, points on
 * its outline. Non-finite input: 0. */
QGL_API int qgl_inside(const double v[4][2], double x, double y);

/* ---- affinity ---------------------------------------------------------------------------- */

/* Planarity: the distance between the lines of the two diagonals (twice the corners'
 * distance from the plane midway between them), relative to the quad's extent (largest
 * coordinate difference from corner 0), is at most rel_tol. 0 for non-finite input. */
QGL_API int qgl_is_planar(const double p[4][3], double rel_tol);
/* Oliveira's parallelogram test on a quad of dim-vector corners (corner i at q + i*dim):
 * |V1.V2 - V3.V4| < tol and |V1.V4 - V2.V3| < tol (unnormalized, as in the paper). */
QGL_API int qgl_is_parallelogram(const double *q, int dim, double tol);
/* Bloomenthal's affinity test (JCGT 2022, listing 3): the barycentric coordinates of each
 * corner with respect to the other three agree in geometry (dim_g <= 16, e.g. 3) and
 * attribute (dim_a <= 16, e.g. 2 for uv) space within tol (Euclidean norm; the listing's
 * default is 0.01). Barycentrics are taken by least squares, so in 3D a corner off the plane
 * of the others is projected onto it: combine with qgl_is_planar. A degenerate corner
 * triangle in either space fails the test, as in the listing. */
QGL_API int qgl_bloomenthal_affine(const double *geom, int dim_g, const double *attr, int dim_a,
                                   double tol);
/* The diagonal split is exact for this quad: it is planar and every attribute is affine in
 * object space over it (corner 3's attributes are the affine image of corners 0..2's). attr
 * holds nattr floats per corner. Relative tolerance rel_tol. */
QGL_API int qgl_split_is_exact(const double p[4][3], const double *attr, int nattr, double rel_tol);
/* The affine dependency of a planar quad's corners: n with sum n_i p_i = 0 and sum n_i = 0,
 * from where the diagonals' lines cross, p0 + t (p2 - p0) = p1 + u (p3 - p1): n = (1 - t,
 * u - 1, t, -u). It is what the split's weights and any other pair of interpolants exact on
 * affine functions differ by, up to a factor (the attribute f then errs by that factor times
 * n . f), and the same up to scale in any projective image of the quad (clip space). Returns
 * 1 when both t and u lie within (0.01, 0.99), the quad strictly convex; 0 otherwise (n
 * untouched), and for non-finite input. Planarity is the caller's: combine with
 * qgl_is_planar (off the plane, the lines' nearest points are taken). */
QGL_API int qgl_affine_dependency(const double p[4][3], double n[4]);

/* ---- subdivision -------------------------------------------------------------------------- */

/* A triangle soup: ntri triangles, each 3 vertices of stride doubles (the layout is the
 * caller's). Start from a zeroed struct; cap counts triangles. Grown with realloc; appending
 * with a different stride fails. Free with qgl_mesh_free. */
typedef struct qgl_mesh {
    double *v;
    int stride;
    int ntri;
    int cap;
} qgl_mesh;

QGL_API void qgl_mesh_free(qgl_mesh *m);

/* Bailey's SuperQuad: bilinear n x n subdivision of a quad whose corners are stride doubles
 * each (every component interpolated bilinearly, corners in GL order at (s,t) = (0,0),
 * (1,0), (1,1), (0,1)), appended to out as 4 n^2 triangles: cells row by row in t, then in
 * s, each as four triangles (0,1,m),(1,2,m),(2,3,m),(3,0,m) around its centre m (the quad's
 * winding; no diagonal is preferred, so rotating the corner order leaves the triangles the
 * same up to rounding, unlike Bailey's two triangles per cell). Points on an edge depend only on that
 * edge's two corners, bitwise, so neighbouring quads stay watertight. Returns 0, or -1 on
 * bad arguments or allocation failure (out's triangles unchanged). */
QGL_API int qgl_subdiv_bilinear(const double *quad, int stride, int n, qgl_mesh *out);

/* Oliveira's adaptive subdivision. Corners are stride doubles: object position at pos_off
 * (3 doubles), texture coordinates at tex_off (2 doubles, or -1 for none), clip position at
 * clip_off (4 doubles, or -1 to skip the screen criterion); viewport size in pixels for the
 * area (zero: no area criterion). Zero fields of the params take the paper's values. A cell
 * is emitted as (0,1,2),(0,2,3) when its object and texture parallelogram differences are
 * below the thresholds, its projected area (measured on its own clip corners; infinite when
 * a w <= 0) is below min_area_px, or it is at max_depth (capped at 10); otherwise every
 * component is split at the edge midpoints and centre. T-junctions between cells of
 * different depth are not removed. Returns 0, or -1 on bad arguments, non-finite corners or
 * allocation failure (out's triangles unchanged). */
typedef struct qgl_adaptive_params {
    double threshold_q;   /* object space, default 1e-3 */
    double threshold_t;   /* texture space, default 1e-4 */
    double min_area_px;   /* stop below this projected area, default 200 */
    int max_depth;        /* default 8 */
    double viewport[2];   /* pixels, for the area criterion */
} qgl_adaptive_params;

QGL_API int qgl_subdiv_adaptive(const double *quad, int stride, int pos_off, int tex_off, int clip_off,
                                const qgl_adaptive_params *params, qgl_mesh *out);

/* ---- view-invariant weights: mean value coordinates in the quad's own plane ----------------- */

/* The frame of a quad's plane, fixed to the quad: a surface point's in-plane coordinates are
 * axis[k] . (p - origin), whatever the camera. For a non-planar quad, the best-fit plane
 * (Newell's normal) with the split along `diagonal` as its surface. */
typedef struct qgl_plane {
    double origin[3];    /* the corners' centroid */
    double normal[3];    /* unit normal */
    double axis[2][3];   /* orthonormal in-plane axes (axis[0] x axis[1] = normal) */
    double corner[4][2]; /* the corners' in-plane coordinates (object units) */
    double height[4];    /* the corners' signed distances from the plane (0 when planar) */
    int diagonal;        /* the preferred split: 0 along corners 0-2, 1 along 1-3 (the shorter in
                            object space, chosen from positions alone: rotating the corner order
                            keeps it) */
} qgl_plane;

typedef struct qgl_planef {
    float origin[3], normal[3], axis[2][3], corner[4][2], height[4];
    int diagonal;
} qgl_planef;

/* The plane frame of the quad with object corners pos (GL order). Returns 0, QGL_DEGENERATE
 * when the corners span no plane (collinear or coincident; out then holds a frame of their
 * line) or QGL_NONFINITE (out then the identity frame at the origin, corners 0). */
QGL_API int qgl_plane_frame(const double pos[4][3], qgl_plane *out);
QGL_API int qgl_plane_framef(const float pos[4][3], qgl_planef *out);
/* In-plane coordinates of the object point p (its orthogonal projection onto the plane). */
QGL_API void qgl_plane_coords(const qgl_plane *pl, const double p[3], double xy[2]);
QGL_API void qgl_plane_coordsf(const qgl_planef *pl, const float p[3], float xy[2]);
/* View-invariant mean value weights of the in-plane point (x, y): the core's robust weights
 * of the point in the quad of pl->corner (every w = 1). An attribute is sum lambda[i] a_i, with
 * no perspective division: the in-plane position already is the surface point. Return codes
 * as qgl_weights. */
QGL_API int qgl_weights_inplane(const qgl_plane *pl, double x, double y, double lambda[4]);
QGL_API int qgl_weights_inplanef(const qgl_planef *pl, float x, float y, float lambda[4]);
/* The same in one call, in the style of qgl_weights: the weights of the object point p (on
 * or near the quad's surface; projected onto the plane) for the quad with object corners pos.
 * Returns QGL_NONFINITE for any non-finite input, else the frame's code when it is negative
 * (QGL_DEGENERATE), else the weights'. */
QGL_API int qgl_weights_plane(const double pos[4][3], const double p[3], double lambda[4]);
QGL_API int qgl_weights_planef(const float pos[4][3], const float p[3], float lambda[4]);
/* The exact cover of the quad in its plane (qgl_classify of pl->corner), a convex quad split
 * along pl->diagonal: drawn in object space, it covers the screen quad exactly whatever the
 * camera, corners behind the eye included (the clipper cuts its triangles). Returns the kind. */
QGL_API int qgl_plane_cover(const qgl_plane *pl, qgl_cover *out);

/* The mean value grid: a subdivision of a convex screen quad whose vertices carry the exact
 * mean value weights, so that a rasterizer's linear interpolation between them approximates
 * the per-pixel result; corners 0..3 first (uv (0,0), (1,0), (1,1), (0,1)), then the interior
 * points. No vertex lies on the boundary: each edge is one triangle edge between two corners,
 * so neighbours drawn by any path meet it without T-junctions. Triangles keep the quad's
 * winding. bound is a measured bound (with margin) on the Euclidean norm of the difference
 * between the interpolated and the exact screen weights, valid for quads qgl_mvcgrid_fits
 * accepts (libquadgl/core/mvcgrid.c tells how it was measured; the core test re-derives it). */
typedef struct qgl_mvcgrid {
    int k;                 /* k x k cells in (u, v) */
    int nverts, ntris;
    float (*uv)[2];        /* bilinear parameters per vertex */
    uint16_t (*tri)[3];    /* vertex numbers */
    double bound;
} qgl_mvcgrid;

/* The tabulated grids, finest last: qgl_mvcgrid_at(0 .. count - 1), or by k (NULL if absent). */
QGL_API int qgl_mvcgrid_count(void);
QGL_API const qgl_mvcgrid *qgl_mvcgrid_at(int i);
QGL_API const qgl_mvcgrid *qgl_mvcgrid_get(int k);
/* Index of the coarsest grid whose bound is <= limit; -1 when none is. */
QGL_API int qgl_mvcgrid_choose(double limit);
/* The class the bounds hold for: strictly convex, every angle within 45 degrees of a right
 * angle, the shortest edge at least a third of the longest (screen points in an isotropic
 * space, such as pixels). */
QGL_API int qgl_mvcgrid_fits(const double v[4][2]);
/* Screen points of g's vertices in the quad v (bilinear in uv). */
QGL_API void qgl_mvcgrid_points(const qgl_mvcgrid *g, const double v[4][2], double (*out)[2]);
/* The screen points (v) and perspective weights (persp) of g's vertices for clip-space
 * corners (x, y, w used); 0 when some w <= 0 or the screen quad is not strictly convex (the
 * bound needs the class as well: the caller's test). */
QGL_API int qgl_mvcgrid_weights(const qgl_mvcgrid *g, const double clip[4][4], double (*v)[2], double (*persp)[4]);

/* ---- inverse bilinear (Quilez), for comparison ---------------------------------------------- */

/* Parameters (u, v) of the point (x, y) in the bilinear patch of the 2D quad q with corners
 * q0 (0,0), q1 (1,0), q2 (1,1), q3 (0,1). Stable quadratic, no absolute thresholds; returns
 * 1 when a root within 1e-12 of [0,1]^2 exists, 0 when not (uv then the root nearest the
 * square, finite, or (0,0) when there is none), QGL_NONFINITE on non-finite input (uv (0,0)).
 * uv may be NULL. */
QGL_API int qgl_inv_bilinear(const double q[4][2], double x, double y, double uv[2]);

#ifdef __cplusplus
}
#endif

#include <quadgl/render.h> /* the software renderer */
#include <quadgl/gl.h>     /* the GL helper */
#endif
