/* test_demo_headless: quadgl-demo --headless pictures against the software renderer.
 *
 * The demo renders every scene and method through OSMesa at 128 x 128; this test loads the
 * same scene files itself and draws them with the software renderer's public API (not the
 * demo's code). Properties checked, per scene:
 *   - the reference PNG is the software exact renderer's picture (max difference 1 level:
 *     the PNG round trip is lossless, 1 allows a rounding difference of the float->8 bit step);
 *   - the native picture (plain glBegin(GL_QUADS) on Mesa) is one of the software renderer's
 *     two diagonal splits within the tolerance p99 <= 4 levels and RMS <= 2 (edge pixels and
 *     texture filtering of two rasterizers may differ; a wrong diagonal, camera or shading
 *     gives RMS in the tens, see the table printed);
 *   - the mvc picture (the GL helper) is the software mvc picture within the same tolerance;
 *   - where the split is wrong by more than 2 levels RMS against the exact reference, mvc's
 *     RMS is at most 0.85 of native's: the demo shows the cure. (Not 0 error: H&T's
 *     interpolant is not the bilinear patch the reference intersects, and on checkerboards
 *     a small shift of a check edge costs full-contrast pixels.)
 * And for the rotating-order scene: turning the vertex order by one changes the native
 * picture (RMS > 10) and leaves mvc's unchanged (RMS < 1). The contact sheet must exist,
 * hold one row per scene, and not be blank.
 * Auto against its per-fragment twin (SCENE__auto__mvcplane.png: the GL helper's MVC_PLANE,
 * the weights auto uses, with no split or grid): the two are the same program wherever the
 * planner kept the shader path, and where it chose the split or the mean value grid by its
 * budget they may differ by what the budget allows. Colours: half an 8-bit level before
 * rounding, so 1 level between the two rounded pictures. Texture coordinates: 1/32 texel per
 * coordinate; bilinear filtering changes by at most D per texel along each axis, D the largest
 * difference between neighbouring texels, so 1 + D / 16 levels (the checker's D is 204: 13
 * levels; a cube map's D is taken as 255). Quads the planner splits because their bounding
 * box is under 4 px^2 (its invisible-area rule, which claims no error bound: a sphere's pole
 * quads span many texels in two pixels) are masked out with a pixel's margin. At 128 x 128
 * the planner splits little, so the finest sphere is also rendered at its own 512 x 512, where
 * it splits the equator's bands by its budget. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <dirent.h>

#include "demo_app.h"
#include "demo_test.h"

#define SIZE 128
#define SPLIT_P99 4
#define SPLIT_RMS 2.0
#define INVISIBLE_AREA 4.0 /* px^2: the planner's default invisible_area_px */

static int failures;

static int load_picture(const char *dir, const char *scene, const char *method, dt_image *img)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s__%s.png", dir, scene, method);
    return dt_image_read(path, img);
}

static void check_close(const char *what, const char *scene, const dt_image *gl, const dt_image *sw, dt_diff *d)
{
    dt_compare(gl, sw, 0, 0, d);
    printf("  %-22s %-28s rms %6.2f p99 %4.0f max %3d over8 %.4f\n", scene, what, d->rms, d->p99, d->max,
           d->frac_over8);
    DT_CHECK(d->p99 <= SPLIT_P99 && d->rms <= SPLIT_RMS, "%s: %s differs (rms %.2f, p99 %.0f)", scene, what,
             d->rms, d->p99);
}

static void check_scene(const char *out, const qgl_sw_scene *s, int have_mvc)
{
    dt_image ref, native, mvc, sw_exact, sw_split, sw_mvc;
    dt_diff d, native_err, mvc_err;
    if (load_picture(out, s->name, "reference", &ref) || load_picture(out, s->name, "native", &native)) {
        DT_CHECK(0, "%s: pictures missing", s->name);
        return;
    }
    DT_CHECK(ref.w == SIZE && ref.h == SIZE && native.w == SIZE, "%s: size %dx%d", s->name, ref.w, ref.h);
    DT_CHECK(dt_sw_picture(s, "exact", 0, SIZE, SIZE, &sw_exact) == 0, "%s: sw exact", s->name);
    dt_compare(&ref, &sw_exact, 0, 0, &d);
    DT_CHECK(d.max <= 1, "%s: reference PNG differs from the software exact picture by %d", s->name, d.max);
    DT_CHECK(dt_coverage(&ref) > 0.01, "%s: reference picture is empty", s->name);
    /* Mesa splits along 0-2, except a quad the clipper cuts (a corner behind the eye), which
     * it splits along 1-3: the native picture must be one of the two software splits */
    dt_diff d13;
    DT_CHECK(dt_sw_picture(s, "split13", 0, SIZE, SIZE, &sw_split) == 0, "%s: sw split13", s->name);
    dt_compare(&native, &sw_split, 0, 0, &d13);
    dt_image_free(&sw_split);
    DT_CHECK(dt_sw_picture(s, "split02", 0, SIZE, SIZE, &sw_split) == 0, "%s: sw split02", s->name);
    dt_compare(&native, &sw_split, 0, 0, &d);
    if (d13.rms < d.rms) {
        dt_image_free(&sw_split);
        DT_CHECK(dt_sw_picture(s, "split13", 0, SIZE, SIZE, &sw_split) == 0, "%s: sw split13", s->name);
        check_close("native vs sw split13", s->name, &native, &sw_split, &d);
    } else {
        check_close("native vs sw split02", s->name, &native, &sw_split, &d);
    }
    dt_compare(&native, &sw_exact, 0, 0, &native_err);
    if (have_mvc && load_picture(out, s->name, "mvc", &mvc) == 0) {
        DT_CHECK(dt_sw_picture(s, "mvc", 0, SIZE, SIZE, &sw_mvc) == 0, "%s: sw mvc", s->name);
        check_close("mvc vs sw mvc", s->name, &mvc, &sw_mvc, &d);
        dt_compare(&mvc, &sw_exact, 0, 0, &mvc_err);
        printf("  %-22s against exact: native rms %.2f, mvc rms %.2f\n", s->name, native_err.rms, mvc_err.rms);
        if (native_err.rms > 2)
            DT_CHECK(mvc_err.rms < 0.85 * native_err.rms, "%s: mvc (%.2f) not closer to exact than native (%.2f)",
                     s->name, mvc_err.rms, native_err.rms);
        dt_image_free(&mvc);
        dt_image_free(&sw_mvc);
    }
    dt_image_free(&ref);
    dt_image_free(&native);
    dt_image_free(&sw_exact);
    dt_image_free(&sw_split);
}

/* The levels auto may differ from its twin by where the planner's budget chose the split or
 * the grid (see the top). */
static double twin_tolerance(const qgl_sw_scene *s)
{
    if (s->shading == QGL_SW_SHADE_COLOR)
        return 1;
    if (s->shading != QGL_SW_SHADE_TEXTURE || !s->texture.texels)
        return 1 + 255.0 / 16;
    const qgl_sw_texture *t = &s->texture;
    double d = 0;
    for (int y = 0; y < t->height; y++)
        for (int x = 0; x < t->width; x++)
            for (int c = 0; c < t->channels; c++) {
                const float *p = t->texels + ((size_t)y * t->width + x) * t->channels + c;
                float right = t->texels[((size_t)y * t->width + (x + 1) % t->width) * t->channels + c];
                float up = t->texels[((size_t)((y + 1) % t->height) * t->width + x) * t->channels + c];
                d = fmax(d, fmax(fabs(*p - right), fabs(*p - up)));
            }
    return 1 + ceil(d * 255) / 16;
}

/* Pixels of quads the invisible-area rule splits, with a pixel's margin. */
static unsigned char *invisible_mask(const qgl_sw_scene *s, int w, int h)
{
    float *clip = NULL, *attr = NULL, *object = NULL;
    unsigned char *mask = calloc((size_t)w * h, 1);
    if (!mask || qgl_sw_scene_arrays(s, 0, &clip, &attr, &object) < 0) {
        free(mask);
        return NULL;
    }
    for (int q = 0; q < s->nquads; q++) {
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
        int front = 1;
        for (int i = 0; i < 4; i++) {
            const float *c = clip + 16 * q + 4 * i;
            front &= c[3] > 0;
            for (int k = 0; k < 2; k++) {
                double px = (c[k] / c[3] + 1) * 0.5 * (k ? h : w);
                lo[k] = fmin(lo[k], px), hi[k] = fmax(hi[k], px);
            }
        }
        if (!front || (hi[0] - lo[0]) * (hi[1] - lo[1]) >= INVISIBLE_AREA)
            continue;
        for (int y = (int)fmax(0, floor(lo[1]) - 1); y <= (int)fmin(h - 1, ceil(hi[1]) + 1); y++)
            for (int x = (int)fmax(0, floor(lo[0]) - 1); x <= (int)fmin(w - 1, ceil(hi[0]) + 1); x++)
                mask[(size_t)y * w + x] = 1;
    }
    free(clip);
    free(attr);
    free(object);
    return mask;
}

static void check_twin(const char *out, const qgl_sw_scene *s)
{
    dt_image a, b;
    if (load_picture(out, s->name, "auto", &a) || load_picture(out, s->name, "auto__mvcplane", &b)) {
        DT_CHECK(0, "%s: auto's twin picture missing", s->name);
        return;
    }
    unsigned char *mask = invisible_mask(s, a.w, a.h);
    double tol = twin_tolerance(s);
    int worst = 0, differ = 0, masked = 0, over = 0;
    for (size_t i = 0; mask && i < (size_t)a.w * a.h; i++) {
        int d = 0;
        for (int k = 0; k < 3; k++)
            d = abs(a.rgba[4 * i + k] - b.rgba[4 * i + k]) > d ? abs(a.rgba[4 * i + k] - b.rgba[4 * i + k]) : d;
        if (mask[i]) {
            masked += d > 0;
            continue;
        }
        differ += d > 0;
        over += d > tol;
        worst = d > worst ? d : worst;
    }
    printf("  %-22s auto vs mvcplane: %d pixels differ (worst %d, tolerance %.1f levels), %d more under the "
           "invisible-area rule\n",
           s->name, differ, worst, tol, masked);
    DT_CHECK(mask && over == 0, "%s: auto differs from its per-fragment twin by %d levels (tolerance %.1f)", s->name,
             worst, tol);
    free(mask);
    dt_image_free(&a);
    dt_image_free(&b);
}

/* The finest sphere at its own size, auto only, against its twin. */
static void check_sphere_at_size(const char *demo, const char *out, const char *log)
{
    char dir[600], path[1024], err[512];
    snprintf(dir, sizeof dir, "%s/sphere", out);
    char *cmd[] = {(char *)demo, "--headless", "--out", dir, "--scene", "sphere_100x40", "--method", "auto",
                   "--quiet", NULL};
    DT_CHECK(dt_run(cmd, log) == 0, "quadgl-demo --scene sphere_100x40 failed");
    snprintf(path, sizeof path, "%s/sphere_100x40.scene", DEMO_SCENE_DIR);
    qgl_sw_scene *s = NULL;
    qgl_sw_scene_load_desc desc = {demo_image_load_texture, NULL};
    if (qgl_sw_scene_load(path, &desc, &s, err, sizeof err) == 0)
        check_twin(dir, s);
    else
        DT_CHECK(0, "%s", err);
    qgl_sw_scene_free(s);
}

/* The rotating-order scene's pictures are at order 1; the plain scene's at order 0. */
static void check_rotation(const char *out, const qgl_sw_scene *s, int have_mvc)
{
    char label[128];
    snprintf(label, sizeof label, "%s-rotating", s->name);
    dt_image a, b, sw_split;
    dt_diff d;
    if (load_picture(out, label, "native", &b) || load_picture(out, s->name, "native", &a)) {
        DT_CHECK(0, "%s: rotating-order pictures missing", label);
        return;
    }
    DT_CHECK(dt_sw_picture(s, "split02", 1, SIZE, SIZE, &sw_split) == 0, "sw split02 turned");
    check_close("native turned vs sw split02 turned", label, &b, &sw_split, &d);
    dt_compare(&a, &b, 0, 0, &d);
    printf("  %-22s native, order 0 vs 1: rms %.2f\n", label, d.rms);
    DT_CHECK(d.rms > 10, "%s: turning the order should change the native split (rms %.2f)", label, d.rms);
    dt_image_free(&a);
    dt_image_free(&b);
    dt_image_free(&sw_split);
    if (!have_mvc || load_picture(out, label, "mvc", &b) || load_picture(out, s->name, "mvc", &a))
        return;
    dt_compare(&a, &b, 0, 0, &d);
    printf("  %-22s mvc, order 0 vs 1: rms %.2f\n", label, d.rms);
    DT_CHECK(d.rms < 1, "%s: turning the order should not change mvc (rms %.2f)", label, d.rms);
    dt_image_free(&a);
    dt_image_free(&b);
}

static int scene_filter(const struct dirent *e)
{
    size_t n = strlen(e->d_name);
    return n > 6 && !strcmp(e->d_name + n - 6, ".scene");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        printf("usage: test_demo_headless PATH/quadgl-demo\n");
        return 1;
    }
    const char *out = dt_tmpdir("demo-headless");
    char log[600], size[32];
    snprintf(log, sizeof log, "%s/log.txt", out);
    snprintf(size, sizeof size, "%dx%d", SIZE, SIZE);
    char *cmd[] = {argv[1], "--headless", "--out", (char *)out, "--size", size, "--quiet", NULL};
    int rc = dt_run(cmd, log);
    if (rc != 0) {
        char *text = dt_slurp(log);
        printf("FAIL: quadgl-demo --headless exited with %d:\n%s\n", rc, text ? text : "");
        free(text);
        return 1;
    }
    struct dirent **names;
    int n = scandir(DEMO_SCENE_DIR, &names, scene_filter, alphasort);
    DT_CHECK(n > 0, "no scenes in %s", DEMO_SCENE_DIR);
    char probe[1024];
    snprintf(probe, sizeof probe, "%s/%s", out, "bailey_rbgr__mvc.png");
    FILE *f = fopen(probe, "rb");
    int have_mvc = f != NULL;
    if (f)
        fclose(f);
    printf("output in %s; GL helper pictures: %s\n", out, have_mvc ? "yes" : "no");
    int rows = 0;
    for (int i = 0; i < n; i++) {
        char path[1024], err[512];
        snprintf(path, sizeof path, "%s/%s", DEMO_SCENE_DIR, names[i]->d_name);
        qgl_sw_scene *s = NULL;
        qgl_sw_scene_load_desc desc = {demo_image_load_texture, NULL};
        if (qgl_sw_scene_load(path, &desc, &s, err, sizeof err)) {
            DT_CHECK(0, "%s", err);
        } else {
            check_scene(out, s, have_mvc);
            if (have_mvc)
                check_twin(out, s);
            if (!strcmp(s->name, "bailey_rbgr"))
                check_rotation(out, s, have_mvc);
            rows++;
        }
        qgl_sw_scene_free(s);
        free(names[i]);
    }
    free(names);
    if (have_mvc)
        check_sphere_at_size(argv[1], out, log);
    dt_image sheet;
    snprintf(probe, sizeof probe, "%s/contact_sheet.png", out);
    if (dt_image_read(probe, &sheet) == 0) {
        printf("contact sheet %dx%d for %d scenes (+1 rotating)\n", sheet.w, sheet.h, rows);
        DT_CHECK(sheet.h >= (rows + 1) * 160, "contact sheet too short for %d rows", rows + 1);
        DT_CHECK(dt_coverage(&sheet) > 0.2, "contact sheet mostly blank");
        dt_image_free(&sheet);
    } else {
        DT_CHECK(0, "no contact sheet");
    }
    printf("%s (%d failures)\n", failures ? "FAIL" : "PASS", failures);
    if (!failures)
        dt_rmtree(out);
    return failures ? 1 : 0;
}
