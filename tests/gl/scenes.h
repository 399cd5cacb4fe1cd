/* scenes.h: small quad meshes shared by the GL tests (native and qgl drawing). */
#ifndef QGL_TEST_SCENES_H
#define QGL_TEST_SCENES_H
#include "harness.h"

#define SC_MAX 1024

/* A quad list: 4 corners each (GL_QUADS order) or a strip grid; position, colour, uv. */
typedef struct sc_mesh {
    int nverts;
    float pos[SC_MAX][3], col[SC_MAX][4], uv[SC_MAX][2];
    int strip_rows, strip_cols; /* strip grid: rows of (cols+1)*2 vertices */
} sc_mesh;

/* n x n planar parallelogram grid with colour and uv affine in position. */
void sc_affine_grid(sc_mesh *m, int n, int strips);
/* n x n grid jittered by jit (0..0.5 of a cell), z jitter zj, random colours (seeded). */
void sc_jitter_grid(sc_mesh *m, int n, float jit, float zj, unsigned seed, int strips);

/* The corner colours red, green, blue, white, and one quad with them drawn through qgl*. */
extern const float sc_corner_colors[4][4];
void sc_draw_quad(const float p[4][3]);

/* Draw through the driver (native = 1) or through qgl*. */
void sc_draw(const sc_mesh *m, int native, int use_color, int use_uv);
/* A smooth RGBA texture (gradients and a low-frequency pattern), bound to unit 0, linear. */
unsigned sc_texture(int with_alpha);
/* Set a perspective camera looking at the unit square from an angle. */
void sc_camera(float angle_x, float angle_z);

/* Watertightness by additive blending: mesh m drawn natively and through qgl* (the current
 * context), every quad adding 0.25 to red. twice counts pixels ours hit more than once,
 * differ those whose coverage differs from native, inside native's covered pixels; st holds
 * the qgl draw's counters. The two snapshots are returned (free them). Leaves blending on. */
typedef struct sc_coverage {
    int twice, differ, inside;
    qgl_gl_stats_t st;
    unsigned char *native, *ours;
} sc_coverage;
void sc_coverage_run(th_ctx *t, const sc_mesh *m, sc_coverage *out);

/* Largest channel difference between two snapshots, and the count of pixels above tol. */
int sc_diff(const th_ctx *t, const unsigned char *a, const unsigned char *b, int tol, int *over);
#endif
