/* bench.h: the pieces of quadgl-bench (run, metrics, reports) and what they share.
 *
 * One run renders one scene with one method at one size: a timed attribute render (the
 * median of repeats), the same with the corners rotated by one place, and one shaded render
 * for the comparison sheet. Metrics compare attribute images against the exact reference. */
#ifndef QGL_BENCH_H
#define QGL_BENCH_H

#include <quadgl/quadgl.h>

/* An attribute image (what the renderer interpolated, per pixel) and its coverage. */
typedef struct bench_image {
    int width, height, nattr;
    float *attr;          /* width * height * nattr */
    unsigned char *cover; /* 1 where a fragment landed */
} bench_image;

/* One scene with its draw arrays (as given, and rotated by one corner). */
typedef struct bench_scene {
    qgl_sw_scene *scene;
    float *clip[2], *attr[2], *object[2];
    int width, height;
    bench_image reference;   /* exact, rotation 0 */
    float *ref_shaded;       /* exact, shaded RGB, top row first (sheet) */
} bench_scene;

typedef struct bench_result {
    char scene[64], method[64];
    qgl_sw_method_desc m;
    double ms, mpix_s, rms, max, crease, rotation, drift;
    long long fragments;
    float *shaded;   /* RGB, top row first, for the sheet (NULL when not kept) */
    float *heat;     /* RGB heat map of the error, top row first */
} bench_result;

/* ---- metrics (bench_metrics.c) ---- */
int bench_image_alloc(bench_image *im, int w, int h, int nattr);
void bench_image_free(bench_image *im);
/* Attribute render of the scene's arrays (rotation r); returns ms of the draw, fragments. */
double bench_render(const bench_scene *bs, const qgl_sw_method_desc *m, int rot, bench_image *out,
                    long long *fragments);
/* RMS and max of |a - ref| * unit over pixels both cover. */
void bench_error(const bench_image *a, const bench_image *ref, double unit, double *rms, double *max);
/* The crease measure: the jump of the attribute gradient across each quad's diagonals. */
double bench_crease(const bench_scene *bs, const bench_image *a, double unit);
/* RGB heat map of |a - ref| * unit (log scale 1e-3 .. 10 units), top row first. */
float *bench_heat(const bench_image *a, const bench_image *ref, double unit);
/* The view drift (bench_drift.c): the largest change of the value at fixed surface points of
 * a sample of the scene's quads over an orbit of cameras, head-on to 80 degrees, in units. */
double bench_drift(const bench_scene *bs, const qgl_sw_method_desc *m);
/* The heat map's colour of an error of e units (log scale 1e-3 .. 10). */
void bench_heat_units(double e, float rgb[3]);
/* A picture of the view drift (bench_drift.c): the scene's first quad from four viewpoints
 * (head-on to 80 degrees), each with mvc and mvcplane, shaded and with the change against the
 * head-on value at each pixel's surface point as a heat map; size pixels per image. */
int bench_drift_sheet(const char *path, const bench_scene *bs, int size);
/* Shaded RGB render (top row first) with the scene's shader. */
float *bench_shaded(const bench_scene *bs, const qgl_sw_method_desc *m);

/* ---- reports (bench_report.c) ---- */
void bench_table(const bench_result *r, int n, const bench_scene *scenes, int nscenes);
int bench_csv(const char *path, const bench_result *r, int n);
int bench_plot(const char *path, const bench_result *r, int n, const bench_scene *scenes, int nscenes);
int bench_sheet(const char *path, const bench_result *r, int n, const bench_scene *scenes, int nscenes,
                const char *const *columns, int ncolumns, int thumb);

#endif
