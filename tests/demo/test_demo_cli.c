/* test_demo_cli: quadgl-demo's command line: bad arguments give the usage and a non-zero exit,
 * --help lists the options and the keys, --list names the scenes, and a window run without a
 * display fails cleanly instead of crashing.
 *
 * Each case runs the demo with one command line and checks its exit status and that its
 * output contains the expected phrases (the message naming the bad argument, "usage:"). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "demo_test.h"

static int failures;

typedef struct cli_case {
    const char *args[8];
    int status;            /* expected exit status */
    const char *says[4];   /* phrases the output must contain (NULL-terminated) */
} cli_case;

static void run_case(const char *demo, const char *dir, int index, const cli_case *c)
{
    char log[600];
    char *argv[12] = {(char *)demo};
    int n = 1;
    for (int i = 0; c->args[i]; i++)
        argv[n++] = (char *)c->args[i];
    argv[n] = NULL;
    snprintf(log, sizeof log, "%s/case%02d.txt", dir, index);
    int status = dt_run(argv, log);
    char *text = dt_slurp(log);
    char line[256] = "";
    for (int i = 1; i < n; i++)
        snprintf(line + strlen(line), sizeof line - strlen(line), " %s", argv[i]);
    int ok = status == c->status;
    for (int i = 0; ok && c->says[i]; i++)
        ok = text && strstr(text, c->says[i]) != NULL;
    printf("%s quadgl-demo%s -> exit %d\n", ok ? "ok  " : "FAIL", line, status);
    if (!ok) {
        printf("  expected exit %d and output containing:", c->status);
        for (int i = 0; c->says[i]; i++)
            printf(" \"%s\"", c->says[i]);
        printf("\n  output:\n%s\n", text ? text : "(none)");
        failures++;
    }
    free(text);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        printf("usage: test_demo_cli PATH/quadgl-demo\n");
        return 1;
    }
    const char *dir = dt_tmpdir("demo-cli");
    char out[600], forbidden[600];
    snprintf(out, sizeof out, "%s/out", dir);
    snprintf(forbidden, sizeof forbidden, "%s/file/sub", dir);
    char blocker[600];
    snprintf(blocker, sizeof blocker, "%s/file", dir);
    FILE *f = fopen(blocker, "w");
    if (f)
        fclose(f);
    const cli_case cases[] = {
        {{"--bogus"}, 2, {"unknown option '--bogus'", "usage:"}},
        {{"stray"}, 2, {"unexpected argument 'stray'", "usage:"}},
        {{"--headless"}, 2, {"--headless needs --out DIR", "usage:"}},
        {{"--out", out}, 2, {"--out is for --headless runs", "usage:"}},
        {{"--method", "nope"}, 2, {"unknown method 'nope'", "usage:"}},
        {{"--method", ","}, 2, {"empty method list ','", "usage:"}},
        {{"--size", "12x"}, 2, {"bad size '12x'", "usage:"}},
        {{"--size", "10x10"}, 2, {"bad size '10x10'", "usage:"}},
        {{"--frames", "abc"}, 2, {"bad frame count 'abc'", "usage:"}},
        {{"--order", "7"}, 2, {"bad vertex order '7'", "usage:"}},
        {{"--view", "diagonal"}, 2, {"unknown view 'diagonal'", "usage:"}},
        {{"--scene"}, 2, {"option '--scene' needs a value", "usage:"}},
        {{"--headless", "--out", out, "--scene", "no_such_scene"}, 2, {"no scene matches 'no_such_scene'"}},
        {{"--headless", "--out", forbidden, "--scene", "bailey_rbgr"}, 1, {"cannot create"}},
        {{"--scenes", "/nonexistent/scenes", "--headless", "--out", out}, 1, {"/nonexistent/scenes"}},
        {{"--help"}, 0, {"usage:", "Keys (window):", "drag with the left button to orbit"}},
        {{"-h"}, 0, {"--headless", "--screenshot FILE", "wireframe"}},
        {{"--list"}, 0, {"bailey_rbgr", "bailey_rbgr-rotating", "ht_fig11_phong"}},
        {{"--frames", "1"}, 1, {"cannot open a window"}},
    };
    /* the last case: a window run with no display to open it on */
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        run_case(argv[1], dir, (int)i, &cases[i]);
    printf("%s (%d failures)\n", failures ? "FAIL" : "PASS", failures);
    if (!failures)
        dt_rmtree(dir);
    return failures ? 1 : 0;
}
