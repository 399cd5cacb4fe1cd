/* demo_app.h: what the parts of quadgl-demo share (scenes, views, methods, pictures, text).
 *
 * quadgl-demo draws the software renderer's scene files as a plain legacy-GL program
 * (glBegin(GL_QUADS) and friends). Each picture is one scene seen through one view (the
 * scene's own camera turned by an orbit and a zoom, and a rotation of every quad's vertex
 * order) and drawn by one method: "native" (plain gl* calls, so the driver's diagonal split,
 * or quadgl's smooth quads when the program runs under `quadgl run`), the GL helper's "mvc",
 * "auto" and "subdiv" (the same drawing code compiled against the qgl* immediate API), and
 * "reference" (the software renderer's exact ray/patch reference, drawn as pixels). The
 * window (GLFW, quadgl-demo.c) and the headless renderer (OSMesa, quadgl-demo-headless.c)
 * share everything in this header; pictures travel as 8-bit RGBA with row 0 at the bottom,
 * as glReadPixels returns them. */
#ifndef DEMO_APP_H
#define DEMO_APP_H

#include <stddef.h>
#include <quadgl/quadgl.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- methods ------------------------------------------------------------------------------ */

typedef enum demo_method {
    DEMO_NATIVE = 0,  /* plain gl* calls: what the driver (or the preload library) makes of them */
    DEMO_MVC,         /* GL helper, shader path forced */
    DEMO_AUTO,        /* GL helper, planner */
    DEMO_SUBDIV,      /* GL helper, CPU subdivision fallback */
    DEMO_REFERENCE,   /* software renderer, exact reference */
    DEMO_NMETHODS
} demo_method;

const char *demo_method_name(demo_method m);
/* Parse a method name; -1 when unknown. */
int demo_method_parse(const char *name);
/* 1 when this build can draw with m (the GL helper methods need libquadgl's GL layer). */
int demo_method_available(demo_method m);

/* ---- scenes and views --------------------------------------------------------------------- */

typedef struct demo_scene {
    qgl_sw_scene *sw;   /* as loaded from the scene file */
    int animate_order;  /* 1: the vertex order turns by one every second (the "rotating" scene) */
    char label[80];     /* name shown on screen and in file names */
    double centre[3];   /* centroid of the vertices: the orbit's pivot */
} demo_scene;

typedef struct demo_scene_list {
    demo_scene *items;
    int count;
} demo_scene_list;

/* Load every *.scene file of dir (sorted by name), then add the rotating-order scene (a copy
 * of the first colour scene with animate_order set). Returns 0, or -1 with err filled. */
int demo_scenes_load(const char *dir, demo_scene_list *out, char *err, size_t errlen);
void demo_scenes_free(demo_scene_list *list);
/* Index of the scene whose label equals name, or failing that contains it; -1 when none. */
int demo_scenes_find(const demo_scene_list *list, const char *name);

/* How a scene is looked at. Zero orbit and zoom 1 give the scene file's own camera. */
typedef struct demo_view {
    double yaw, pitch;  /* orbit about the scene's centroid, radians */
    double zoom;        /* scale of NDC x and y about the centre of the picture */
    int order;          /* vertex order rotation 0..3 (corner i gets old corner i + order) */
    int shading;        /* 1: the scene's shading (texture, colour, Phong); 0: attributes as colour */
    int wireframe;      /* 1: quad outlines on top (and the split diagonal for "native") */
} demo_view;

void demo_view_reset(demo_view *v);
/* The view's projection * view matrix, column-major, for the picture aspect w / h. */
void demo_view_mvp(const demo_scene *s, const demo_view *v, int w, int h, double mvp[16]);

/* ---- software reference ------------------------------------------------------------------- */

extern const float demo_background[4];

/* Render the scene with the software renderer (method by name, e.g. "exact") into rgba
 * (w * h * 4 bytes, row 0 at the bottom). Returns 0, or a negative qgl_sw code. */
int demo_sw_render(const demo_scene *s, const demo_view *v, const char *method, int w, int h,
                   unsigned char *rgba);
/* The colour a fragment gets: the scene's shading or its attributes as colour (the rule the
 * GL drawing code and the software reference share). out gets 4 floats in [0, 1]. */
void demo_shade(const demo_scene *s, int shading, const float *attr, int facing, float out[4]);

/* ---- comparing pictures ------------------------------------------------------------------- */

typedef struct demo_error {
    double rms;      /* over every pixel and the RGB channels, in 8-bit levels */
    int max;         /* largest channel difference, levels */
    double p99;      /* 99th percentile of the per-pixel largest channel difference */
    double frac_over; /* fraction of pixels whose largest channel difference exceeds 8 levels */
} demo_error;

void demo_compare(const unsigned char *a, const unsigned char *b, int w, int h, demo_error *out);
/* Heat map of the per-pixel largest channel difference: black 0, then blue, red, yellow,
 * white at full_scale levels and above. */
void demo_heatmap(const unsigned char *a, const unsigned char *b, int w, int h, int full_scale,
                  unsigned char *rgba);

/* ---- text (a 5 x 7 bitmap font of our own) ------------------------------------------------ */

#define DEMO_GLYPH_W 6   /* advance, pixels */
#define DEMO_GLYPH_H 9   /* line height, pixels */
/* The 7 rows of a character, top row first, bit 4 = leftmost column; blank for unknown. */
const unsigned char *demo_glyph(int c);
/* Draw text into an RGBA picture (row 0 at the bottom), top-left corner of the first glyph at
 * (x, y_top) counted from the top, scaled by scale. */
void demo_text_rgba(unsigned char *rgba, int w, int h, int x, int y_top, int scale,
                    const unsigned char colour[3], const char *text);

/* ---- image files (OpenImageIO, demo_image.cpp) -------------------------------------------- */

/* Write an 8-bit RGBA picture, row 0 at the bottom, as PNG (or any format OIIO knows by the
 * extension); the alpha channel is dropped. 0 on success, else err holds a message. */
int demo_image_write(const char *path, int w, int h, const unsigned char *rgba, char *err,
                     size_t errlen);
/* Read a picture into malloc'd 8-bit RGBA, row 0 at the bottom. */
int demo_image_read(const char *path, int *w, int *h, unsigned char **rgba, char *err, size_t errlen);
/* qgl_sw_image_loader for scene files' "texture image" lines. */
int demo_image_load_texture(void *user, const char *path, qgl_sw_texture *tex, char *err,
                            size_t errlen);

#ifdef __cplusplus
}
#endif
#endif
