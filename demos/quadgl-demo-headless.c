/* quadgl-demo-headless: quadgl-demo's --headless mode, every scene and method through OSMesa.
 *
 * For each scene: the software reference is rendered once, then every method draws the same
 * view into an OSMesa buffer of the scene's size (the median of a few timed repeats is kept),
 * is read back, written as PNG and compared with the reference; the comparison becomes a heat
 * map PNG, a row of the Markdown table on stdout and a row of the contact sheet. The
 * rotating-order scene is the exception that shows the other half of the problem: there each
 * method's picture at order K+1 is compared with its own picture at order K, so the heat map
 * shows what changes when nothing but the vertex order does. The auto picture gets a second
 * heat map: its difference from the per-fragment picture of the weights auto uses (the GL
 * helper's MVC_PLANE, with no split or grid), saved as SCENE__auto__mvcplane.png, on a finer
 * scale; it is zero wherever the planner kept the shader path, so it shows where the planner
 * chose the split or the mean value grid and what that cost (the planner's budget is half an
 * 8-bit level for colours, 1/32 texel for texture coordinates). This is a separate executable
 * from the window program because it links OSMesa's gl* functions and the window program
 * links libGL's: one process cannot have both answer to glBegin. */
#include <GL/osmesa.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "demo_gl.h"
#include "demo_options.h"
#include "demo_sheet.h"

#define REPEATS 3
#define HEAT_SCALE 32
#define TWIN_SCALE 4 /* levels: auto against its per-fragment twin, within a level or two */
#define SHEET_CELL 160

typedef struct run {
    demo_options opt;
    demo_scene_list scenes;
    int first, last;             /* scene range rendered */
    int methods[DEMO_NMETHODS];
    int nmethods;
    OSMesaContext ctx;
    unsigned char *buffer;       /* OSMesa's colour buffer */
    demo_gl gl;
    demo_sheet sheet;
    int failures;
} run;

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

/* ---- set-up ------------------------------------------------------------------------------- */

static int pick_methods(run *r)
{
    if (r->opt.nmethods) {
        for (int i = 0; i < r->opt.nmethods; i++)
            if (!demo_method_available(r->opt.methods[i])) {
                fprintf(stderr, "quadgl-demo: method '%s' is not available in this build (%s)\n",
                        demo_method_name(r->opt.methods[i]), "built without the GL helper");
                return -1;
            }
        memcpy(r->methods, r->opt.methods, sizeof r->methods);
        r->nmethods = r->opt.nmethods;
        return 0;
    }
    for (int m = 0; m < DEMO_NMETHODS; m++)
        if (demo_method_available(m))
            r->methods[r->nmethods++] = m;
    return 0;
}

static int pick_scenes(run *r)
{
    r->first = 0;
    r->last = r->scenes.count - 1;
    if (!r->opt.scene)
        return 0;
    int i = demo_scenes_find(&r->scenes, r->opt.scene);
    if (i < 0) {
        fprintf(stderr, "quadgl-demo: no scene matches '%s' (try --list)\n", r->opt.scene);
        return -1;
    }
    r->first = r->last = i;
    return 0;
}

static int make_dir(const char *dir)
{
    char path[1024];
    snprintf(path, sizeof path, "%s", dir);
    for (char *p = path + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            mkdir(path, 0777);
            *p = '/';
        }
    if (mkdir(path, 0777) && errno != EEXIST) {
        fprintf(stderr, "quadgl-demo: cannot create '%s': %s\n", dir, strerror(errno));
        return -1;
    }
    return 0;
}

static OSMesaContext create_context(void)
{
    static const int versions[][2] = {{4, 5}, {3, 3}, {2, 1}};
    for (size_t i = 0; i < sizeof versions / sizeof versions[0]; i++) {
        const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
                               OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION,
                               versions[i][0], OSMESA_CONTEXT_MINOR_VERSION, versions[i][1], 0};
        OSMesaContext c = OSMesaCreateContextAttribs(attribs, NULL);
        if (c)
            return c;
    }
    return OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, NULL);
}

static int picture_size(const run *r, const demo_scene *s, int *w, int *h)
{
    *w = r->opt.width ? r->opt.width : s->sw->width;
    *h = r->opt.height ? r->opt.height : s->sw->height;
    return 0;
}

static int make_current(run *r, int w, int h)
{
    free(r->buffer);
    r->buffer = malloc((size_t)w * (size_t)h * 4);
    if (!r->buffer || !OSMesaMakeCurrent(r->ctx, r->buffer, GL_UNSIGNED_BYTE, w, h)) {
        fprintf(stderr, "quadgl-demo: OSMesaMakeCurrent failed (%dx%d)\n", w, h);
        return -1;
    }
    return 0;
}

/* ---- one picture -------------------------------------------------------------------------- */

typedef struct picture {
    unsigned char *rgba;
    double ms;
    char paths[192]; /* the GL helper's counters: which path drew the quads */
} picture;

static void helper_paths(run *r, demo_method m, char *out, size_t n)
{
    out[0] = 0;
#if DEMO_HAVE_QGL
    if (r->gl.qgl && m != DEMO_NATIVE && m != DEMO_REFERENCE) {
        qgl_gl_stats_t st;
        qgl_gl_stats(r->gl.qgl, &st);
        snprintf(out, n, "mvc %llu split %llu grid %llu fallback %llu pass %llu",
                 (unsigned long long)st.mvc / REPEATS, (unsigned long long)st.split / REPEATS,
                 (unsigned long long)st.subdiv / REPEATS, (unsigned long long)st.fallback / REPEATS,
                 (unsigned long long)st.passthrough / REPEATS);
    }
#else
    (void)r;
    (void)m;
    (void)n;
#endif
}

static int draw_gl(run *r, int si, const demo_view *v, demo_method m, int w, int h, picture *p)
{
    double times[REPEATS];
#if DEMO_HAVE_QGL
    if (r->gl.qgl)
        qgl_gl_reset_stats(r->gl.qgl);
#endif
    for (int k = 0; k < REPEATS; k++) {
        double t0 = now_ms();
        demo_gl_panel(0, 0, w, h);
        if (demo_gl_draw(&r->gl, &r->scenes, si, v, m, w, h))
            return -1;
        glFinish();
        times[k] = now_ms() - t0;
    }
    for (int i = 1; i < REPEATS; i++)
        for (int j = i; j > 0 && times[j] < times[j - 1]; j--) {
            double t = times[j];
            times[j] = times[j - 1];
            times[j - 1] = t;
        }
    p->ms = times[REPEATS / 2];
    helper_paths(r, m, p->paths, sizeof p->paths);
    if (v->wireframe)
        demo_gl_wire(&r->scenes, si, v, m, w, h);
    demo_gl_read(0, 0, w, h, p->rgba);
    return glGetError() == GL_NO_ERROR ? 0 : -1;
}

static int draw_picture(run *r, int si, const demo_view *v, demo_method m, int w, int h, picture *p)
{
    p->paths[0] = 0;
    if (m != DEMO_REFERENCE)
        return draw_gl(r, si, v, m, w, h, p);
    double t0 = now_ms();
    int rc = demo_sw_render(&r->scenes.items[si], v, "exact", w, h, p->rgba);
    p->ms = now_ms() - t0;
    return rc;
}

/* ---- one scene ---------------------------------------------------------------------------- */

static int save(run *r, const char *label, const char *method, const char *suffix, int w, int h,
                const unsigned char *rgba)
{
    char path[1200], err[512];
    snprintf(path, sizeof path, "%s/%s__%s%s.png", r->opt.out_dir, label, method, suffix);
    if (demo_image_write(path, w, h, rgba, err, sizeof err)) {
        fprintf(stderr, "quadgl-demo: %s\n", err);
        return -1;
    }
    return 0;
}

/* Whether method m gets the column of its difference from its per-fragment twin. */
static int has_twin(const run *r, demo_method m)
{
    return m == DEMO_AUTO && r->gl.qgl;
}

/* Sheet columns of a method: its picture, then its heat map (but the reference's), then
 * auto's difference from its twin. */
static int sheet_width(const run *r, demo_method m)
{
    return m == DEMO_REFERENCE ? 1 : has_twin(r, m) ? 3 : 2;
}

/* Sheet column of method index i. */
static int sheet_col(const run *r, int i)
{
    int col = 0;
    for (int k = 0; k < i; k++)
        col += sheet_width(r, r->methods[k]);
    return col;
}

static void report(run *r, int row, int i, const demo_scene *s, const picture *p, const demo_error *e,
                   int w, int h, const unsigned char *heat)
{
    demo_method m = r->methods[i];
    char caption[64];
    snprintf(caption, sizeof caption, "%.1f ms", p->ms);
    demo_sheet_cell(&r->sheet, row, sheet_col(r, i), p->rgba, w, h, caption);
    if (heat) {
        snprintf(caption, sizeof caption, "%s %.2f p99 %.0f", s->animate_order ? "turn" : "rms",
                 e->rms, e->p99);
        demo_sheet_cell(&r->sheet, row, sheet_col(r, i) + 1, heat, w, h, caption);
    }
    if (r->opt.quiet)
        return;
    if (heat)
        printf("| %-22s | %-9s | %8.2f | %6.2f | %4.0f | %3d | %s |\n", s->label, demo_method_name(m), p->ms,
               e->rms, e->p99, e->max, p->paths);
    else
        printf("| %-22s | %-9s | %8.2f |      - |    - |   - | reference |\n", s->label,
               demo_method_name(m), p->ms);
}

/* Auto's picture p against its twin (twin: w x h x 4 scratch, heat: the heat map's): the
 * picture, the heat map, the sheet cell and the table row. */
static int report_twin(run *r, int row, int i, int si, const demo_view *v, const picture *p, int w, int h,
                       unsigned char *twin, unsigned char *heat)
{
    const demo_scene *s = &r->scenes.items[si];
    demo_gl_panel(0, 0, w, h);
    if (demo_gl_draw_plane(&r->gl, &r->scenes, si, v, w, h)) {
        fprintf(stderr, "quadgl-demo: scene %s: drawing with mvcplane failed\n", s->label);
        return -1;
    }
    if (v->wireframe)
        demo_gl_wire(&r->scenes, si, v, DEMO_AUTO, w, h);
    glFinish();
    demo_gl_read(0, 0, w, h, twin);
    demo_error e;
    demo_compare(p->rgba, twin, w, h, &e);
    demo_heatmap(p->rgba, twin, w, h, TWIN_SCALE, heat);
    if (save(r, s->label, "auto", "__mvcplane", w, h, twin) ||
        save(r, s->label, "auto", "__vs_mvcplane", w, h, heat))
        return -1;
    char caption[64];
    snprintf(caption, sizeof caption, "rms %.2f max %d", e.rms, e.max);
    demo_sheet_cell_peak(&r->sheet, row, sheet_col(r, i) + 2, heat, w, h, caption);
    if (!r->opt.quiet)
        printf("| %-22s | %-9s | %8s | %6.2f | %4.0f | %3d | against mvcplane; %s |\n", s->label, "auto-pf", "-",
               e.rms, e.p99, e.max, p->paths);
    return 0;
}

static int render_scene(run *r, int si, int row)
{
    const demo_scene *s = &r->scenes.items[si];
    int w, h;
    picture_size(r, s, &w, &h);
    if (make_current(r, w, h))
        return -1;
    size_t bytes = (size_t)w * (size_t)h * 4;
    unsigned char *ref = malloc(bytes), *heat = malloc(bytes), *twin = malloc(bytes);
    picture p = {malloc(bytes), 0, ""};
    demo_view v, turned;
    demo_view_reset(&v);
    v.order = r->opt.order;
    v.wireframe = r->opt.wireframe;
    v.shading = r->opt.shading;
    turned = v;
    turned.order = (v.order + 1) % 4;
    int rc = ref && heat && twin && p.rgba ? demo_sw_render(s, &v, "exact", w, h, ref) : -1;
    demo_sheet_row_label(&r->sheet, row, s->label);
    for (int i = 0; rc == 0 && i < r->nmethods; i++) {
        demo_method m = r->methods[i];
        demo_error e;
        if (s->animate_order) {
            /* the change from order K to K+1 of this method's own picture */
            rc = draw_picture(r, si, &v, m, w, h, &p);
            memcpy(ref, p.rgba, bytes);
            rc = rc ? rc : draw_picture(r, si, &turned, m, w, h, &p);
        } else {
            rc = draw_picture(r, si, &v, m, w, h, &p);
        }
        if (rc) {
            fprintf(stderr, "quadgl-demo: scene %s, method %s: drawing failed\n", s->label, demo_method_name(m));
            break;
        }
        int with_heat = m != DEMO_REFERENCE || s->animate_order;
        demo_compare(p.rgba, ref, w, h, &e);
        demo_heatmap(p.rgba, ref, w, h, HEAT_SCALE, heat);
        rc = save(r, s->label, demo_method_name(m), "", w, h, p.rgba);
        if (rc == 0 && with_heat)
            rc = save(r, s->label, demo_method_name(m), "__err", w, h, heat);
        report(r, row, i, s, &p, &e, w, h, with_heat && m != DEMO_REFERENCE ? heat : NULL);
        if (rc == 0 && has_twin(r, m))
            rc = report_twin(r, row, i, si, s->animate_order ? &turned : &v, &p, w, h, twin, heat);
    }
    free(ref);
    free(heat);
    free(twin);
    free(p.rgba);
    return rc;
}

/* ---- main --------------------------------------------------------------------------------- */

static int sheet_setup(run *r)
{
    const char *names[3 * DEMO_NMETHODS];
    char heat_names[DEMO_NMETHODS][48];
    int n = 0;
    for (int i = 0; i < r->nmethods; i++) {
        names[n++] = demo_method_name(r->methods[i]);
        if (r->methods[i] != DEMO_REFERENCE) {
            snprintf(heat_names[i], sizeof heat_names[i], "%s error", demo_method_name(r->methods[i]));
            names[n++] = heat_names[i];
        }
        if (has_twin(r, r->methods[i]))
            names[n++] = "auto - mvcplane";
    }
    return demo_sheet_init(&r->sheet, r->last - r->first + 1, n, SHEET_CELL, names);
}

static void *get_proc(const char *name)
{
    return (void *)OSMesaGetProcAddress(name);
}

static int render_all(run *r)
{
    if (make_current(r, 64, 64))
        return -1;
    demo_gl_init(&r->gl, r->scenes.count, get_proc);
    if (sheet_setup(r)) { /* after the GL helper: auto's twin column needs it */
        demo_gl_fini(&r->gl);
        fprintf(stderr, "quadgl-demo: out of memory for the contact sheet\n");
        return -1;
    }
    if (!r->opt.quiet) {
        printf("GL: %s, %s; GL helper: %s\n\n", (const char *)glGetString(GL_RENDERER),
               (const char *)glGetString(GL_VERSION), r->gl.qgl ? "yes" : r->gl.qgl_error);
        printf("| %-22s | %-9s | %8s | %6s | %4s | %3s | %s |\n", "scene", "method", "ms", "rms", "p99", "max",
               "paths (GL helper)");
        printf("|%s|%s|%s|%s|%s|%s|%s|\n", "------------------------", "-----------", "----------",
               "--------", "------", "-----", "---");
    }
    for (int i = 0; i <= r->last - r->first && !r->failures; i++)
        if (render_scene(r, r->first + i, i))
            r->failures++;
    demo_gl_fini(&r->gl);
    if (r->failures)
        return -1;
    char path[1200], err[512];
    demo_sheet_legend(&r->sheet, 0, HEAT_SCALE, "largest channel difference from the reference");
    demo_sheet_legend(&r->sheet, 1, TWIN_SCALE,
                      "auto - mvcplane: where the planner split or drew the grid (0: the shader path)");
    snprintf(path, sizeof path, "%s/contact_sheet.png", r->opt.out_dir);
    if (demo_image_write(path, r->sheet.w, r->sheet.h, r->sheet.rgba, err, sizeof err)) {
        fprintf(stderr, "quadgl-demo: %s\n", err);
        return -1;
    }
    if (!r->opt.quiet)
        printf("\nrms, p99, max: 8-bit levels against the exact reference (rotating scene: change from "
               "vertex order %d to %d);\nauto-pf: auto against the per-fragment picture of its own weights "
               "(mvcplane: no split, no grid)\nwrote %s\n",
               r->opt.order, (r->opt.order + 1) % 4, path);
    return 0;
}

static void list_scenes(const demo_scene_list *l)
{
    printf("scenes:\n");
    for (int i = 0; i < l->count; i++)
        printf("  %2d  %-24s %5d quads  %s\n", i + 1, l->items[i].label, l->items[i].sw->nquads,
               l->items[i].sw->path);
    printf("methods:");
    for (int m = 0; m < DEMO_NMETHODS; m++)
        printf(" %s%s", demo_method_name(m), demo_method_available(m) ? "" : " (not in this build)");
    printf("\n");
}

int main(int argc, char **argv)
{
    static run r;
    char err[1024];
    if (demo_options_parse(argc, argv, &r.opt))
        return 2;
    if (r.opt.help) {
        demo_options_help(stdout);
        return 0;
    }
    if (demo_scenes_load(r.opt.scene_dir, &r.scenes, err, sizeof err)) {
        fprintf(stderr, "quadgl-demo: %s\n", err);
        return 1;
    }
    int rc = 0;
    if (r.opt.list)
        list_scenes(&r.scenes);
    else if (!r.opt.headless)
        rc = (fprintf(stderr, "quadgl-demo-headless: needs --headless --out DIR\n"), 2);
    else if (pick_scenes(&r) || pick_methods(&r))
        rc = 2;
    else if (make_dir(r.opt.out_dir) || !(r.ctx = create_context()))
        rc = (fprintf(stderr, "quadgl-demo: cannot set up the headless renderer\n"), 1);
    else if (render_all(&r))
        rc = 1;
    if (r.ctx)
        OSMesaDestroyContext(r.ctx);
    free(r.buffer);
    demo_sheet_free(&r.sheet);
    demo_scenes_free(&r.scenes);
    return rc;
}
