/* demo_gl.h: the demo's legacy-GL drawing, shared by the window and the headless renderer.
 *
 * Everything here is plain OpenGL 1.x-3.x compatibility calls made on the current context
 * (GLX under GLFW, or OSMesa); the quads themselves go through glBegin(GL_QUADS) or, for the
 * GL helper's methods, through the same code compiled against qglBegin & co (demo_emit.c). */
#ifndef DEMO_GL_H
#define DEMO_GL_H

#include "demo_app.h"

typedef struct demo_gl {
    int nscenes;
    unsigned *tex;        /* per scene: texture name (2D or cube map), 0 until first needed */
    unsigned *tex_target; /* its target */
    qgl_context *qgl;     /* the GL helper's context; NULL when unavailable */
    char qgl_error[160];  /* why qgl is NULL */
} demo_gl;

/* Set up for nscenes scenes in the current context. get_proc resolves GL entry points for the
 * GL helper (glfwGetProcAddress, OSMesaGetProcAddress). Never fails: without the GL helper
 * only "native" and "reference" draw. */
void demo_gl_init(demo_gl *g, int nscenes, void *(*get_proc)(const char *name));
void demo_gl_fini(demo_gl *g);

/* Clear the rectangle (window pixels, origin bottom-left) and make it the viewport. */
void demo_gl_panel(int x, int y, int w, int h);
/* Draw scene index si of list with method m into the current panel of size w x h (the view's
 * wireframe flag is the caller's: demo_gl_wire). The reference method is the caller's too
 * (demo_gl_draw_rgba). Returns 0, or -1 when m cannot draw here. */
int demo_gl_draw(demo_gl *g, const demo_scene_list *list, int si, const demo_view *v, demo_method m,
                 int w, int h);
/* The same with the GL helper's method MVC_PLANE: the weights AUTO's smooth path uses (in the
 * quad's plane, a non-planar quad's on its bilinear patch) per fragment on every quad, with
 * no split or grid: what AUTO's picture would be if the planner chose nothing else. */
int demo_gl_draw_plane(demo_gl *g, const demo_scene_list *list, int si, const demo_view *v, int w, int h);
/* The quad outlines of the same view on top of the panel (and the native split's diagonal,
 * dotted, when m is native). */
void demo_gl_wire(const demo_scene_list *list, int si, const demo_view *v, demo_method m, int w, int h);
/* Pixels at window position (x, y), row 0 at the bottom. */
void demo_gl_draw_rgba(int x, int y, int w, int h, const unsigned char *rgba);
/* Text with a dark shadow, first line's top at window row y_top counted from the bottom. */
void demo_gl_text(int x, int y_top, const char *text, const unsigned char rgb[3]);
/* glReadPixels of the rectangle into rgba (w * h * 4), from the current read buffer. */
void demo_gl_read(int x, int y, int w, int h, unsigned char *rgba);

/* demo_emit.c, compiled twice: the quads as glBegin(GL_QUADS) / qglBegin(GL_QUADS). */
typedef enum { DEMO_EMIT_TEX2, DEMO_EMIT_TEX3, DEMO_EMIT_COLOR } demo_emit_mode;
void demo_emit_native(const demo_scene *s, const demo_view *v, demo_emit_mode mode);
void demo_emit_qgl(const demo_scene *s, const demo_view *v, demo_emit_mode mode);

#endif
