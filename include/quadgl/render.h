/* quadgl: the software quad renderer (qgl_sw_*), included by quadgl/quadgl.h.
 *
 * Quads come as 4 clip-space corners (x, y, z, w) in GL order, each with nattr floats of
 * attributes, and are drawn by a method chosen by name into a float framebuffer (colour,
 * depth, and optionally facing and a per-pixel fragment count). Every method shares one
 * coverage rule where it can: pixel centres at +0.5, homogeneous edge functions (Olano &
 * Greer) so that corners behind the eye need no clipper, and a tie rule for centres exactly
 * on an edge (the pixel belongs to the primitive whose inside lies towards +x, or towards
 * +y for an edge parallel to x), so quads sharing an edge never double-cover or miss a pixel.
 * Rows count from the bottom (GL window convention). Description structs follow sokol: a
 * zero field means its documented default. */
#ifndef QUADGL_RENDER_H
#define QUADGL_RENDER_H
#include <quadgl/quadgl.h>
#ifdef __cplusplus
extern "C" {
#endif

/* ---- errors: one X-macro list yields the codes and their messages ------------------------ */

#define QGL_SW_ERRORS(X)                                                           \
    X(QGL_SW_OK, 0, "ok")                                                          \
    X(QGL_SW_EINVAL, -1, "invalid argument")                                       \
    X(QGL_SW_ENOMEM, -2, "out of memory")                                          \
    X(QGL_SW_EMETHOD, -3, "unknown method name or bad method parameter")           \
    X(QGL_SW_EFORMAT, -4, "framebuffer has fewer channels than the shader writes") \
    X(QGL_SW_ESUBDIV, -5, "subdivision failed")

enum {
#define QGL__SW_ENUM(name, value, msg) name = value,
    QGL_SW_ERRORS(QGL__SW_ENUM)
#undef QGL__SW_ENUM
};
QGL_API const char *qgl_sw_error_string(int code);

/* ---- methods ------------------------------------------------------------------------------ */

typedef enum qgl_sw_method {
    QGL_SW_MVC = 0,      /* default: H&T mean value coordinates, float, eq. 12 coverage,
                            A / D / r^2 carried by finite differences along each span */
    QGL_SW_MVC64,        /* the same weights in double, per pixel through qgl_weights */
    QGL_SW_SPLIT02,      /* triangles 012 + 023, perspective-correct (what GL does) */
    QGL_SW_SPLIT13,      /* triangles 123 + 130 */
    QGL_SW_BILINEAR,     /* Bailey's SuperQuad: n x n bilinear subdivision, then triangles */
    QGL_SW_ADAPTIVE,     /* Oliveira's adaptive subdivision, then triangles */
    QGL_SW_INVBILINEAR,  /* Quilez: inverse bilinear of the screen quad per pixel (no
                            perspective correction, as in the original shader) */
    QGL_SW_PROJECTIVE,   /* the homography from the screen quad to the unit square, then
                            bilinear attributes (Heckbert; exact for planar parallelograms) */
    QGL_SW_EXACT,        /* reference: each pixel's ray against the bilinear patch of the
                            corners, double precision, nearest visible hit */
    QGL_SW_MVCPLANE,     /* view-invariant: mean value weights of the fragment's position in
                            the quad's own plane (float, as the GL path), the quad's in-plane
                            cover rasterized as triangles; a non-planar quad's best-fit plane,
                            with the split along the shorter diagonal as its surface; needs
                            desc.object for view invariance */
    QGL_SW_MVCPATCH,     /* view-invariant for non-planar quads too: the exact reference's hit
                            on the bilinear patch, weighed with mean value weights in the
                            best-fit plane (double), the patch's depth */
    QGL_SW_INVBILINEARPLANE, /* the inverse bilinear map of the in-plane quad (Quilez's stable
                            quadratic): for a planar convex quad, the exact reference */
    QGL_SW_MVCGRID,      /* the mean value grid (qgl_mvcgrid) of n x n cells, exact weights at
                            its vertices, triangles between (n not tabulated: the next finer
                            grid); quads not strictly convex or behind the eye per pixel as
                            mvc */
    QGL_SW_METHOD_COUNT
} qgl_sw_method;

typedef struct qgl_sw_method_desc {
    qgl_sw_method method;
    int n;                         /* bilinear: subdivisions per side, default 8; mvcgrid:
                                      cells per side, default 4 */
    qgl_adaptive_params adaptive;  /* adaptive: thresholds, zero fields = Oliveira's */
} qgl_sw_method_desc;

/* Parse "mvc", "split02", "bilinear:16", "adaptive", "adaptive:q=1e-3,t=1e-4,area=200,depth=8".
 * Returns 0, or QGL_SW_EMETHOD (out then zeroed). */
QGL_API int qgl_sw_method_parse(const char *text, qgl_sw_method_desc *out);
/* The canonical name ("bilinear:16"); returns the length snprintf would write. */
QGL_API int qgl_sw_method_format(const qgl_sw_method_desc *m, char *buf, size_t size);
QGL_API const char *qgl_sw_method_name(qgl_sw_method m);

/* ---- framebuffer --------------------------------------------------------------------------- */

typedef struct qgl_sw_fb_desc {
    int width, height;   /* required, pixels */
    int channels;        /* floats per colour pixel, default 4 */
    int no_depth;        /* 1: no depth buffer (every fragment passes) */
    int with_facing;     /* 1: keep the facing (+1 / -1) of the last fragment per pixel */
    int with_count;      /* 1: count fragments per pixel (coverage tests) */
} qgl_sw_fb_desc;

typedef struct qgl_sw_fb {
    int width, height, channels;
    float *color;        /* width * height * channels, row 0 at the bottom */
    float *depth;        /* width * height window depths in [0, 1], or NULL */
    signed char *facing; /* or NULL; 0 where nothing was drawn */
    unsigned *count;     /* or NULL */
} qgl_sw_fb;

QGL_API qgl_sw_fb *qgl_sw_fb_create(const qgl_sw_fb_desc *desc);
QGL_API void qgl_sw_fb_destroy(qgl_sw_fb *fb);
/* Colour to color[0..channels) (NULL: zeros), depth to depth, facing and count to 0. */
QGL_API void qgl_sw_fb_clear(qgl_sw_fb *fb, const float *color, float depth);

/* ---- drawing -------------------------------------------------------------------------------- */

typedef enum { QGL_SW_CULL_NONE = 0, QGL_SW_CULL_BACK, QGL_SW_CULL_FRONT } qgl_sw_cull;
typedef enum { QGL_SW_DEPTH_LESS = 0, QGL_SW_DEPTH_LEQUAL, QGL_SW_DEPTH_ALWAYS } qgl_sw_depth;
typedef enum { QGL_SW_BLEND_REPLACE = 0, QGL_SW_BLEND_ADD } qgl_sw_blend;

/* A fragment shader: attr holds the nattr interpolated attributes, facing is +1 (front,
 * counter-clockwise on screen) or -1; write fb->channels floats to out. Return 0 to discard. */
typedef int (*qgl_sw_shade_fn)(void *user, const float *attr, int nattr, int facing, float *out);

typedef struct qgl_sw_draw_desc {
    qgl_sw_method_desc method;
    int nquads;
    int nattr;            /* floats per corner in attr (0..QGL_SW_MAX_ATTR) */
    const float *clip;    /* nquads * 4 corners * (x, y, z, w) */
    const float *attr;    /* nquads * 4 * nattr, may be NULL when nattr == 0 */
    const float *object;  /* optional nquads * 4 * 3 object positions (adaptive's object test);
                             NULL: clip x, y, z divided by w */
    int uv_attr1;         /* adaptive's texture test: 1 + index of the (u, v) pair; 0: none */
    qgl_sw_cull cull;
    qgl_sw_depth depth;
    qgl_sw_blend blend;
    qgl_sw_shade_fn shade; /* NULL: the attributes themselves are the colour (zero padded) */
    void *user;
} qgl_sw_draw_desc;

#define QGL_SW_MAX_ATTR 16

typedef struct qgl_sw_stats {
    long long fragments;  /* fragments that reached the framebuffer */
    long long triangles;  /* triangles rasterized (splits and subdivisions) */
} qgl_sw_stats;

/* Draw; stats (may be NULL) is added to. Returns QGL_SW_OK or a negative QGL_SW_* code. */
QGL_API int qgl_sw_draw(qgl_sw_fb *fb, const qgl_sw_draw_desc *desc, qgl_sw_stats *stats);

/* ---- textures -------------------------------------------------------------------------------- */

typedef enum { QGL_SW_FILTER_NEAREST = 0, QGL_SW_FILTER_BILINEAR } qgl_sw_filter;

typedef struct qgl_sw_texture {
    int width, height, channels;  /* channels 1..4 */
    float *texels;                /* row 0 at the bottom (t = 0), owned */
} qgl_sw_texture;

/* A checkerboard of checks x checks squares over size x size texels, grey levels lo and hi. */
QGL_API int qgl_sw_texture_checker(qgl_sw_texture *tex, int size, int checks, float lo, float hi);
QGL_API void qgl_sw_texture_free(qgl_sw_texture *tex);
/* Sample at (s, t) with repeat wrapping; out gets 4 floats (missing channels: 0, alpha 1). */
QGL_API void qgl_sw_texture_sample(const qgl_sw_texture *tex, qgl_sw_filter filter, float s, float t,
                                   float out[4]);

/* ---- scenes ------------------------------------------------------------------------------------ */

/* How a scene is shaded and what its attributes mean (the error unit of the benchmark). */
typedef enum { QGL_SW_SHADE_TEXTURE = 0, QGL_SW_SHADE_COLOR, QGL_SW_SHADE_PHONG } qgl_sw_shading;

typedef struct qgl_sw_scene {
    char name[64];
    char path[512];          /* the file it came from */
    int width, height;       /* render size, default 256 x 256 */
    double mvp[16];          /* projection * view, column-major (as GL) */
    int nattr;               /* 2 uv, 3 color or 3 normal */
    char attr_kind[16];      /* "uv", "color", "normal" */
    char unit[16];           /* error unit name: "texels", "levels" */
    double unit_scale;       /* attribute difference * unit_scale = error in units */
    qgl_sw_shading shading;
    qgl_sw_filter filter;
    qgl_sw_texture texture;  /* for SHADE_TEXTURE */
    double light[3];         /* for SHADE_PHONG: direction towards the light, object space */
    double eye_dir[3];       /* for SHADE_PHONG: direction towards the viewer, object space */
    int nverts, nquads;
    double *pos;             /* nverts * 3 object positions */
    float *attr;             /* nverts * nattr */
    int *quad;               /* nquads * 4 vertex indices */
    int cull_back;           /* 1: draw with back-face culling */
} qgl_sw_scene;

/* Reads an image file into tex (row 0 at the bottom); 0 on success, else writes a message. */
typedef int (*qgl_sw_image_loader)(void *user, const char *path, qgl_sw_texture *tex, char *err,
                                   size_t errlen);

typedef struct qgl_sw_scene_load_desc {
    qgl_sw_image_loader load_image; /* NULL: "texture image" lines are an error */
    void *user;
} qgl_sw_scene_load_desc;

/* Load a scene file (grammar in data/scenes/README.md). On failure returns a negative code and
 * err holds "FILE:LINE: message". */
QGL_API int qgl_sw_scene_load(const char *path, const qgl_sw_scene_load_desc *desc, qgl_sw_scene **out,
                              char *err, size_t errlen);
/* The same from text in memory; name stands for the file in messages and resolves relative
 * image paths. */
QGL_API int qgl_sw_scene_parse(const char *text, const char *name, const qgl_sw_scene_load_desc *desc,
                               qgl_sw_scene **out, char *err, size_t errlen);
QGL_API void qgl_sw_scene_free(qgl_sw_scene *scene);

/* The scene's quads as draw arrays (malloc'd, free with free()): clip (nquads*16), attr
 * (nquads*4*nattr), object (nquads*12). rotate moves every quad's corner order by that many
 * places (corner i gets old corner i + rotate), the change the rotation measure makes. */
QGL_API int qgl_sw_scene_arrays(const qgl_sw_scene *scene, int rotate, float **clip, float **attr,
                                float **object);
/* A shader for the scene's shading (texture lookup, colour, Phong on interpolated normals);
 * user must be the scene. Writes 4 channels. */
QGL_API int qgl_sw_scene_shade(void *user, const float *attr, int nattr, int facing, float *out);

#ifdef __cplusplus
}
#endif
#endif
