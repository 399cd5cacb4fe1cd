/* test_demo_preload: the same quadgl-demo binary, natively and under `quadgl run`.
 *
 * The demo's "native" method is plain glBegin(GL_QUADS). Run in a window under Xvfb on
 * Bailey's R-B-G-R quad, it must match the headless picture of the driver's split; run again
 * through the launcher (libquadgl-preload.so preloaded) it must match the headless picture of
 * the GL helper's mvc method instead (p99 <= 2 levels, RMS <= 1) and differ from the native
 * one (RMS > 5): the cure without recompiling. Skips (77) without an X display. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "demo_test.h"

static int failures;

static int window_shot(char *const argv[], const char *log, const char *shot, dt_image *img)
{
    int rc = dt_run(argv, log);
    if (rc != 0 || dt_image_read(shot, img)) {
        char *t = dt_slurp(log);
        printf("FAIL: window run exited with %d:\n%s\n", rc, t ? t : "");
        free(t);
        return 1;
    }
    return 0;
}

static void expect_match(const char *what, const dt_image *shot, const char *png)
{
    dt_image ref;
    dt_diff d;
    if (dt_image_read(png, &ref)) {
        printf("FAIL: cannot read %s\n", png);
        failures++;
        return;
    }
    dt_compare(shot, &ref, 0, 0, &d);
    printf("%-28s RMS %.2f, p99 %.1f, max %d\n", what, d.rms, d.p99, d.max);
    DT_CHECK(d.p99 <= 2 && d.rms <= 1, "%s does not match %s", what, png);
    dt_image_free(&ref);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        printf("usage: test_demo_preload PATH/quadgl-demo PATH/quadgl (under xvfb-run)\n");
        return 1;
    }
    if (!getenv("DISPLAY")) {
        printf("SKIP: no X display (run under xvfb-run -a)\n");
        return 77;
    }
    const char *dir = dt_tmpdir("demo-preload");
    char out[600], log[600], shot_n[600], shot_q[600], png_n[700], png_q[700];
    snprintf(out, sizeof out, "%s/headless", dir);
    snprintf(log, sizeof log, "%s/log.txt", dir);
    snprintf(shot_n, sizeof shot_n, "%s/native.png", dir);
    snprintf(shot_q, sizeof shot_q, "%s/preloaded.png", dir);
    snprintf(png_n, sizeof png_n, "%s/bailey_rbgr__native.png", out);
    snprintf(png_q, sizeof png_q, "%s/bailey_rbgr__mvc.png", out);
    char *headless[] = {argv[1], "--headless", "--out", out, "--scene", "bailey_rbgr", "--size", "256x256",
                        "--method", "native,mvc", "--quiet", NULL};
    if (dt_run(headless, log) != 0) {
        printf("FAIL: headless run failed (log %s)\n", log);
        return 1;
    }
#define WINDOW_ARGS "--view", "single", "--method", "native", "--scene", "bailey_rbgr", "--size", "256x256", \
                    "--frames", "3", "--no-text", "--screenshot"
    char *native[] = {argv[1], WINDOW_ARGS, shot_n, NULL};
    char *preloaded[] = {"/bin/sh", argv[2], "run", "--method", "auto", "--", argv[1], WINDOW_ARGS, shot_q, NULL};
    dt_image n, q;
    if (window_shot(native, log, shot_n, &n) || window_shot(preloaded, log, shot_q, &q))
        return 1;
    expect_match("native window vs split", &n, png_n);
    expect_match("preloaded window vs mvc", &q, png_q);
    dt_diff d;
    dt_compare(&n, &q, 0, 0, &d);
    printf("%-28s RMS %.2f\n", "native vs preloaded", d.rms);
    DT_CHECK(d.rms > 5, "the preloaded window looks like the native one (RMS %.2f)", d.rms);
    dt_image_free(&n);
    dt_image_free(&q);
    printf("%s (%d failures)\n", failures ? "FAIL" : "PASS", failures);
    if (!failures)
        dt_rmtree(dir);
    return failures ? 1 : 0;
}
