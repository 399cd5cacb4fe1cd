/* quadgl-demo: the diagonal split and quadgl side by side, in a GLFW window.
 *
 * The window holds one, two or four panels, each drawing the current scene and view with one
 * method (native glBegin(GL_QUADS), the GL helper's mvc / auto / subdiv, or the software
 * reference). Each frame every panel is drawn, timed with glFinish, read back and compared
 * with the software reference of the same view and size; the reference is recomputed only
 * when the scene, the view or the panel size changed, and not while the mouse is orbiting
 * (the error figure then says so), so interaction stays smooth. Text (method, frame time,
 * error) is drawn after the read-back so it never counts as error. --frames and --screenshot
 * make a run that ends by itself and leaves a PNG of its last frame: that is how the test
 * suite sees the window. --headless hands the whole command line to quadgl-demo-headless,
 * the OSMesa sibling built next to this program. */
#include <GLFW/glfw3.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "demo_gl.h"
#include "demo_options.h"

#define MAX_PANELS 4

typedef struct panel_state {
    demo_method method;
    unsigned char *ref, *pixels; /* reference and read-back, w * h * 4 */
    int w, h;
    double key[8];               /* what the reference was computed for */
    int ref_valid;
    demo_error err;
    int err_valid;
    double ms;
} panel_state;

typedef struct app {
    demo_options opt;
    demo_scene_list scenes;
    int scene;
    demo_view view;
    int base_order;        /* the order key O sets; the animation adds seconds to it */
    int animate;           /* A key; the rotating scene animates regardless */
    demo_layout layout;
    demo_method methods[3][MAX_PANELS]; /* per layout */
    int selected;
    int show_text;
    GLFWwindow *win;
    demo_gl gl;
    panel_state panels[MAX_PANELS];
    int dragging;
    double last_x, last_y;
    double t0;
    int frame, shots;
    int shot_requested; /* S pressed: save the next frame */
    int quit;
} app;

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

static int panel_count(demo_layout l)
{
    return l == DEMO_VIEW_SINGLE ? 1 : l == DEMO_VIEW_SPLIT ? 2 : 4;
}

/* Panel p's rectangle in a window of fw x fh pixels (origin bottom-left). */
static void panel_rect(demo_layout l, int p, int fw, int fh, int r[4])
{
    int cols = l == DEMO_VIEW_SINGLE ? 1 : 2, rows = l == DEMO_VIEW_QUAD ? 2 : 1;
    int col = p % cols, row = p / cols;
    r[2] = fw / cols;
    r[3] = fh / rows;
    r[0] = col * r[2];
    r[1] = fh - (row + 1) * r[3];
}

/* ---- methods per panel -------------------------------------------------------------------- */

static demo_method next_available(demo_method m, int step)
{
    for (int k = 0; k < DEMO_NMETHODS; k++) {
        m = (demo_method)(((int)m + step + DEMO_NMETHODS) % DEMO_NMETHODS);
        if (demo_method_available(m))
            return m;
    }
    return DEMO_NATIVE;
}

static void default_methods(app *a)
{
    demo_method smooth = demo_method_available(DEMO_MVC) ? DEMO_MVC : DEMO_REFERENCE;
    demo_method third = demo_method_available(DEMO_SUBDIV) ? DEMO_SUBDIV : DEMO_NATIVE;
    a->methods[DEMO_VIEW_SINGLE][0] = smooth;
    a->methods[DEMO_VIEW_SPLIT][0] = DEMO_NATIVE;
    a->methods[DEMO_VIEW_SPLIT][1] = smooth;
    a->methods[DEMO_VIEW_QUAD][0] = DEMO_NATIVE;
    a->methods[DEMO_VIEW_QUAD][1] = smooth;
    a->methods[DEMO_VIEW_QUAD][2] = third;
    a->methods[DEMO_VIEW_QUAD][3] = DEMO_REFERENCE;
    for (int i = 0; i < a->opt.nmethods && i < MAX_PANELS; i++)
        a->methods[a->layout][i] = a->opt.methods[i];
}

/* ---- reference and error ------------------------------------------------------------------ */

static int effective_order(const app *a)
{
    int turning = a->animate || a->scenes.items[a->scene].animate_order;
    return turning ? (a->base_order + (int)floor(now_s() - a->t0)) % 4 : a->base_order;
}

static void view_key(const app *a, int w, int h, double key[8])
{
    const demo_view *v = &a->view;
    double k[8] = {a->scene, v->yaw, v->pitch, v->zoom, v->order, v->shading, w, h};
    memcpy(key, k, sizeof k);
}

static int panel_buffers(panel_state *p, int w, int h)
{
    if (p->w == w && p->h == h && p->ref)
        return 0;
    free(p->ref);
    free(p->pixels);
    p->ref = malloc((size_t)w * (size_t)h * 4);
    p->pixels = malloc((size_t)w * (size_t)h * 4);
    p->w = w;
    p->h = h;
    p->ref_valid = 0;
    return p->ref && p->pixels ? 0 : -1;
}

/* Bring the panel's reference up to date unless the user is dragging. */
static void update_reference(app *a, panel_state *p, int w, int h)
{
    double key[8];
    view_key(a, w, h, key);
    if (p->ref_valid && memcmp(key, p->key, sizeof key) == 0)
        return;
    p->ref_valid = 0;
    if (a->dragging || panel_buffers(p, w, h))
        return;
    if (demo_sw_render(&a->scenes.items[a->scene], &a->view, "exact", w, h, p->ref) == 0) {
        memcpy(p->key, key, sizeof key);
        p->ref_valid = 1;
    }
}

/* ---- drawing ------------------------------------------------------------------------------ */

static void draw_panel(app *a, int i, const int r[4])
{
    panel_state *p = &a->panels[i];
    p->method = a->methods[a->layout][i];
    update_reference(a, p, r[2], r[3]);
    double t0 = now_s();
    demo_gl_panel(r[0], r[1], r[2], r[3]);
    if (p->method == DEMO_REFERENCE) {
        if (p->ref_valid)
            demo_gl_draw_rgba(r[0], r[1], r[2], r[3], p->ref);
    } else if (demo_gl_draw(&a->gl, &a->scenes, a->scene, &a->view, p->method, r[2], r[3])) {
        p->method = DEMO_REFERENCE;
    }
    glFinish();
    p->ms = (now_s() - t0) * 1e3;
    p->err_valid = 0;
    if (p->ref_valid && !panel_buffers(p, r[2], r[3])) {
        demo_gl_read(r[0], r[1], r[2], r[3], p->pixels);
        demo_compare(p->pixels, p->ref, r[2], r[3], &p->err);
        p->err_valid = 1;
    }
    if (a->view.wireframe)
        demo_gl_wire(&a->scenes, a->scene, &a->view, p->method, r[2], r[3]);
}

static void panel_text(app *a, int i, const int r[4])
{
    static const unsigned char white[3] = {240, 240, 240}, yellow[3] = {255, 220, 90};
    const panel_state *p = &a->panels[i];
    char text[256], err[96];
    if (p->err_valid)
        snprintf(err, sizeof err, "error rms %.2f p99 %.0f max %d", p->err.rms, p->err.p99, p->err.max);
    else
        snprintf(err, sizeof err, "error: %s", a->dragging ? "after the drag" : "no reference");
    snprintf(text, sizeof text, "%s%s\n%.1f ms\n%s", demo_method_name(p->method),
             p->method == DEMO_NATIVE ? " (driver split)" : "", p->ms, err);
    int sel = i == a->selected && panel_count(a->layout) > 1;
    demo_gl_text(r[0] + 8, r[1] + r[3] - 8 - (i == 0 ? 22 : 0), text, sel ? yellow : white);
}

static void header_text(app *a, int fh)
{
    static const unsigned char grey[3] = {200, 200, 200};
    char text[256];
    snprintf(text, sizeof text, "%d/%d %s  order %d%s%s   H: keys", a->scene + 1, a->scenes.count,
             a->scenes.items[a->scene].label, a->view.order,
             a->animate || a->scenes.items[a->scene].animate_order ? " (turning)" : "",
             a->view.shading ? "" : "  attributes as colour");
    demo_gl_text(8, fh - 6, text, grey);
}

static void draw_frame(app *a)
{
    int fw, fh, r[4];
    glfwGetFramebufferSize(a->win, &fw, &fh);
    a->view.order = effective_order(a);
    demo_gl_panel(0, 0, fw, fh);
    for (int i = 0; i < panel_count(a->layout); i++) {
        panel_rect(a->layout, i, fw, fh, r);
        draw_panel(a, i, r);
    }
    glViewport(0, 0, fw, fh);
    glScissor(0, 0, fw, fh);
    if (a->show_text) {
        for (int i = 0; i < panel_count(a->layout); i++) {
            panel_rect(a->layout, i, fw, fh, r);
            panel_text(a, i, r);
        }
        header_text(a, fh);
    }
}

/* The frame just drawn, read from the back buffer right before it is swapped to the screen
 * (Mesa's software GLX under Xvfb returns black for GL_FRONT reads, so the front buffer is
 * no witness there), as PNG. */
static int screenshot(app *a, const char *path)
{
    int fw, fh;
    char err[512];
    glfwGetFramebufferSize(a->win, &fw, &fh);
    unsigned char *px = malloc((size_t)fw * (size_t)fh * 4);
    if (!px)
        return -1;
    glReadBuffer(GL_BACK);
    glDisable(GL_SCISSOR_TEST);
    demo_gl_read(0, 0, fw, fh, px);
    int rc = demo_image_write(path, fw, fh, px, err, sizeof err);
    if (rc)
        fprintf(stderr, "quadgl-demo: %s\n", err);
    else
        printf("quadgl-demo: wrote %s\n", path);
    free(px);
    return rc;
}

/* ---- input -------------------------------------------------------------------------------- */

static void set_scene(app *a, int s)
{
    a->scene = (s + a->scenes.count) % a->scenes.count;
}

static int key_action(app *a, int key, int mods)
{
    int np = panel_count(a->layout);
    demo_method *m = &a->methods[a->layout][a->selected % np];
    switch (key) {
    case GLFW_KEY_RIGHT: case GLFW_KEY_N: set_scene(a, a->scene + 1); break;
    case GLFW_KEY_LEFT: case GLFW_KEY_P: set_scene(a, a->scene - 1); break;
    case GLFW_KEY_M: *m = next_available(*m, mods & GLFW_MOD_SHIFT ? -1 : 1); break;
    case GLFW_KEY_TAB: a->selected = (a->selected + 1) % np; break;
    case GLFW_KEY_V: a->layout = (demo_layout)((a->layout + 1) % 3); a->selected = 0; break;
    case GLFW_KEY_W: a->view.wireframe = !a->view.wireframe; break;
    case GLFW_KEY_T: a->view.shading = !a->view.shading; break;
    case GLFW_KEY_O: a->base_order = (a->base_order + 1) % 4; break;
    case GLFW_KEY_A: a->animate = !a->animate; a->t0 = now_s(); break;
    case GLFW_KEY_R: a->view.yaw = a->view.pitch = 0; a->view.zoom = 1; break;
    case GLFW_KEY_S: a->shot_requested = 1; break;
    case GLFW_KEY_H: demo_options_help(stdout); break;
    case GLFW_KEY_ESCAPE: case GLFW_KEY_Q: a->quit = 1; break;
    default:
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9 && key - GLFW_KEY_1 < a->scenes.count)
            set_scene(a, key - GLFW_KEY_1);
        else
            return 0;
    }
    return 1;
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    if (action != GLFW_RELEASE)
        key_action(glfwGetWindowUserPointer(w), key, mods);
}

static void on_button(GLFWwindow *w, int button, int action, int mods)
{
    app *a = glfwGetWindowUserPointer(w);
    (void)mods;
    if (button != GLFW_MOUSE_BUTTON_LEFT)
        return;
    a->dragging = action == GLFW_PRESS;
    glfwGetCursorPos(w, &a->last_x, &a->last_y);
}

static void on_cursor(GLFWwindow *w, double x, double y)
{
    app *a = glfwGetWindowUserPointer(w);
    if (!a->dragging)
        return;
    a->view.yaw += (x - a->last_x) * 0.01;
    a->view.pitch += (y - a->last_y) * 0.01;
    a->view.pitch = fmax(-1.5, fmin(1.5, a->view.pitch));
    a->last_x = x;
    a->last_y = y;
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    app *a = glfwGetWindowUserPointer(w);
    (void)dx;
    a->view.zoom = fmax(0.05, fmin(50.0, a->view.zoom * pow(1.1, dy)));
}

static void on_glfw_error(int code, const char *msg)
{
    fprintf(stderr, "quadgl-demo: GLFW error %d: %s\n", code, msg);
}

/* ---- set-up ------------------------------------------------------------------------------- */

static void *get_proc(const char *name)
{
    return (void *)glfwGetProcAddress(name);
}

static int open_window(app *a)
{
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        fprintf(stderr, "quadgl-demo: cannot open a window (no display?); try --headless --out DIR\n");
        return -1;
    }
    int w = a->opt.width ? a->opt.width : a->layout == DEMO_VIEW_SPLIT ? 1200 : 900;
    int h = a->opt.height ? a->opt.height : a->layout == DEMO_VIEW_SPLIT ? 600 : 900;
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    a->win = glfwCreateWindow(w, h, "quadgl-demo", NULL, NULL);
    if (!a->win) {
        fprintf(stderr, "quadgl-demo: cannot create a GL window\n");
        return -1;
    }
    glfwMakeContextCurrent(a->win);
    glfwSwapInterval(1);
    glfwSetWindowUserPointer(a->win, a);
    glfwSetKeyCallback(a->win, on_key);
    glfwSetMouseButtonCallback(a->win, on_button);
    glfwSetCursorPosCallback(a->win, on_cursor);
    glfwSetScrollCallback(a->win, on_scroll);
    demo_gl_init(&a->gl, a->scenes.count, get_proc);
    if (!a->gl.qgl)
        fprintf(stderr, "quadgl-demo: GL helper unavailable (%s): native and reference only\n", a->gl.qgl_error);
    return 0;
}

static int run_window(app *a)
{
    if (open_window(a))
        return 1;
    int rc = 0;
    a->t0 = now_s();
    while (!a->quit && !glfwWindowShouldClose(a->win)) {
        draw_frame(a);
        int last = a->opt.frames && a->frame + 1 >= a->opt.frames;
        if (last && a->opt.screenshot)
            rc = screenshot(a, a->opt.screenshot) ? 1 : 0;
        if (a->shot_requested) {
            char path[64];
            snprintf(path, sizeof path, "quadgl-demo-%03d.png", a->shots++);
            screenshot(a, path);
            a->shot_requested = 0;
        }
        glfwSwapBuffers(a->win);
        if (++a->frame, last)
            break;
        glfwWaitEventsTimeout(a->opt.frames ? 0.0 : 0.1);
    }
    demo_gl_fini(&a->gl);
    glfwDestroyWindow(a->win);
    glfwTerminate();
    return rc;
}

/* --headless: the OSMesa sibling next to this executable takes the same arguments. */
static int run_headless(char **argv)
{
    char self[PATH_MAX], path[PATH_MAX + 32];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n <= 0)
        return (fprintf(stderr, "quadgl-demo: cannot find my own executable\n"), 1);
    self[n] = 0;
    char *slash = strrchr(self, '/');
    if (slash)
        *slash = 0;
    snprintf(path, sizeof path, "%s/quadgl-demo-headless", self);
    argv[0] = path;
    execv(path, argv);
    perror(path);
    return 1;
}

int main(int argc, char **argv)
{
    static app a;
    char err[1024];
    if (demo_options_parse(argc, argv, &a.opt))
        return 2;
    if (a.opt.help) {
        demo_options_help(stdout);
        return 0;
    }
    if (a.opt.headless || a.opt.list)
        return run_headless(argv);
    if (demo_scenes_load(a.opt.scene_dir, &a.scenes, err, sizeof err)) {
        fprintf(stderr, "quadgl-demo: %s\n", err);
        return 1;
    }
    a.layout = a.opt.layout;
    a.scene = a.opt.scene ? demo_scenes_find(&a.scenes, a.opt.scene) : 0;
    int rc = 2;
    if (a.scene < 0)
        fprintf(stderr, "quadgl-demo: no scene matches '%s' (try --list)\n", a.opt.scene);
    for (int i = 0; a.scene >= 0 && i < a.opt.nmethods; i++)
        if (!demo_method_available(a.opt.methods[i]))
            a.scene = (fprintf(stderr, "quadgl-demo: method '%s' is not in this build\n",
                               demo_method_name(a.opt.methods[i])), -1);
    if (a.opt.nmethods > panel_count(a.layout) && a.scene >= 0)
        a.scene = (fprintf(stderr, "quadgl-demo: %d methods for %d panels\n", a.opt.nmethods,
                           panel_count(a.layout)), -1);
    if (a.scene >= 0) {
        demo_view_reset(&a.view);
        a.base_order = a.opt.order;
        a.view.wireframe = a.opt.wireframe;
        a.view.shading = a.opt.shading;
        a.show_text = !a.opt.no_text;
        default_methods(&a);
        rc = run_window(&a);
    }
    for (int i = 0; i < MAX_PANELS; i++) {
        free(a.panels[i].ref);
        free(a.panels[i].pixels);
    }
    demo_scenes_free(&a.scenes);
    return rc;
}
