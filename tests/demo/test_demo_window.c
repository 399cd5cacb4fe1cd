/* test_demo_window: quadgl-demo's window under Xvfb, against its own headless pictures.
 *
 * Two window runs, each a few frames long and ending with a screenshot of its last frame:
 *   1. the 2 x 2 layout of native, mvc, subdiv and reference on the facade at 512 x 512
 *      without text: each 256 x 256 panel must not be empty (over 10% of it drawn), must
 *      match the headless picture of the same scene and method at 256 x 256 (p99 <= 2
 *      levels, RMS <= 1: the same Mesa rasterizer through GLX and OSMesa) and the native
 *      panel must differ from the mvc one (RMS > 5), so the panels really differ by method;
 *   2. the same with the on-screen text: the top-left corner, where the text goes, must
 *      differ from run 1 while the bottom half (no text) must not.
 * Skips (77) when there is no X display (the suite runs it under xvfb-run -a). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "demo_test.h"

static int failures;

#define PANEL 256

static const char *const methods[4] = {"native", "mvc", "subdiv", "reference"};

static int run_demo(const char *demo, const char *dir, const char *shot, int text)
{
    char log[600];
    snprintf(log, sizeof log, "%s/window-log.txt", dir);
    char *argv[20] = {(char *)demo, "--view", "quad", "--method", "native,mvc,subdiv,reference", "--scene",
                      "facade", "--size", "512x512", "--frames", "3", "--screenshot", (char *)shot, NULL};
    if (!text) {
        argv[13] = "--no-text";
        argv[14] = NULL;
    }
    int rc = dt_run(argv, log);
    if (rc != 0) {
        char *t = dt_slurp(log);
        printf("FAIL: window run exited with %d:\n%s\n", rc, t ? t : "");
        free(t);
    }
    return rc;
}

/* Panel i of the 2 x 2 layout: 0 top-left, 1 top-right, 2 bottom-left, 3 bottom-right; the
 * picture's rows count from the bottom. */
static void panel_origin(int i, int *x, int *y)
{
    *x = (i % 2) * PANEL;
    *y = (i < 2) ? PANEL : 0;
}

static void crop(const dt_image *src, int x0, int y0, int w, int h, dt_image *out)
{
    out->w = w;
    out->h = h;
    out->rgba = malloc((size_t)w * (size_t)h * 4);
    for (int y = 0; y < h; y++)
        memcpy(out->rgba + (size_t)y * (size_t)w * 4, src->rgba + ((size_t)(y + y0) * (size_t)src->w + (size_t)x0) * 4,
               (size_t)w * 4);
}

static void check_panels(const char *dir, const dt_image *shot)
{
    dt_image panels[4];
    for (int i = 0; i < 4; i++) {
        char path[700];
        int x, y;
        panel_origin(i, &x, &y);
        crop(shot, x, y, PANEL, PANEL, &panels[i]);
        double cov = dt_coverage(&panels[i]);
        DT_CHECK(cov > 0.10, "%s panel is empty (%.3f drawn)", methods[i], cov);
        snprintf(path, sizeof path, "%s/headless/facade__%s.png", dir, methods[i]);
        dt_image head;
        if (dt_image_read(path, &head)) {
            DT_CHECK(0, "no headless picture %s", path);
            continue;
        }
        dt_diff d;
        dt_compare(&panels[i], &head, 0, 0, &d);
        printf("  panel %-9s drawn %.3f, against headless: rms %.3f p99 %.0f max %d\n", methods[i], cov, d.rms,
               d.p99, d.max);
        DT_CHECK(d.p99 <= 2 && d.rms <= 1.0, "%s panel differs from the headless picture", methods[i]);
        dt_image_free(&head);
    }
    dt_diff d;
    dt_compare(&panels[0], &panels[1], 0, 0, &d);
    printf("  native panel against mvc panel: rms %.2f\n", d.rms);
    DT_CHECK(d.rms > 5, "native and mvc panels should differ (rms %.2f)", d.rms);
    for (int i = 0; i < 4; i++)
        dt_image_free(&panels[i]);
}

static void check_text(const dt_image *plain, const dt_image *text)
{
    dt_image a, b;
    dt_diff d;
    crop(plain, 0, plain->h - 60, 200, 60, &a);
    crop(text, 0, text->h - 60, 200, 60, &b);
    dt_compare(&a, &b, 0, 0, &d);
    printf("  text corner: rms %.2f against the run without text\n", d.rms);
    DT_CHECK(d.rms > 5, "no text drawn in the top-left corner");
    dt_image_free(&a);
    dt_image_free(&b);
    crop(plain, 0, 0, plain->w, 150, &a);
    crop(text, 0, 0, text->w, 150, &b);
    dt_compare(&a, &b, 0, 0, &d);
    printf("  bottom rows: rms %.3f against the run without text\n", d.rms);
    DT_CHECK(d.rms < 0.5, "text changed the bottom panels' pictures away from the labels");
    dt_image_free(&a);
    dt_image_free(&b);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        printf("usage: test_demo_window PATH/quadgl-demo (under xvfb-run)\n");
        return 1;
    }
    if (!getenv("DISPLAY")) {
        printf("SKIP: no X display (run under xvfb-run -a)\n");
        return 77;
    }
    const char *dir = dt_tmpdir("demo-window");
    char shot[600], shot_text[600], out[600], log[600];
    snprintf(shot, sizeof shot, "%s/window.png", dir);
    snprintf(shot_text, sizeof shot_text, "%s/window-text.png", dir);
    snprintf(out, sizeof out, "%s/headless", dir);
    snprintf(log, sizeof log, "%s/headless-log.txt", dir);
    char *headless[] = {argv[1], "--headless", "--out", out, "--scene", "facade", "--size", "256x256",
                        "--method", "native,mvc,subdiv,reference", "--quiet", NULL};
    if (dt_run(headless, log) != 0) {
        printf("FAIL: headless run failed (log %s)\n", log);
        return 1;
    }
    dt_image plain, text;
    if (run_demo(argv[1], dir, shot, 0) || run_demo(argv[1], dir, shot_text, 1))
        return 1;
    if (dt_image_read(shot, &plain) || dt_image_read(shot_text, &text))
        return 1;
    printf("screenshots %dx%d in %s\n", plain.w, plain.h, dir);
    DT_CHECK(plain.w == 2 * PANEL && plain.h == 2 * PANEL, "window is %dx%d, not 512x512", plain.w, plain.h);
    if (!failures) {
        check_panels(dir, &plain);
        check_text(&plain, &text);
    }
    dt_image_free(&plain);
    dt_image_free(&text);
    printf("%s (%d failures)\n", failures ? "FAIL" : "PASS", failures);
    if (!failures)
        dt_rmtree(dir);
    return failures ? 1 : 0;
}
