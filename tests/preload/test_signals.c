/* test_signals: what QUADGL_STATS prints when a program is ended by a signal, and what it must
 * not change.
 *
 * Run with libquadgl-preload.so preloaded and QUADGL_STATS=1. Each case forks a child (which
 * keeps the library) that draws a few quads in an OSMesa context and then is ended: by SIGINT
 * and by SIGTERM with no handler of its own (the statistics line must reach stderr, counting
 * the quads, and the child must still die of the signal), and by SIGINT with a handler it
 * installed itself (the program's handler runs and decides the exit status; the library's
 * never displaces it). The child's stderr comes back through a pipe. */
#include <GL/gl.h>
#include <GL/osmesa.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static int failures;

static void check(int ok, const char *what)
{
    if (!ok) {
        fprintf(stderr, "FAIL: %s\n", what);
        failures++;
    }
}

static void draw_quads(int frames)
{
    static unsigned char buf[32 * 32 * 4];
    OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 16, 0, 0, NULL);
    if (!ctx || !OSMesaMakeCurrent(ctx, buf, GL_UNSIGNED_BYTE, 32, 32))
        _exit(77);
    for (int f = 0; f < frames; f++) {
        glClear(GL_COLOR_BUFFER_BIT);
        glBegin(GL_QUADS);
        for (int q = 0; q < 3; q++) {
            glColor3f(1, 0, 0), glVertex2f(-0.9f + 0.6f * (float)q, -0.5f);
            glColor3f(0, 1, 0), glVertex2f(-0.4f + 0.6f * (float)q, -0.5f);
            glColor3f(0, 0, 1), glVertex2f(-0.4f + 0.6f * (float)q, 0.5f);
            glColor3f(1, 1, 1), glVertex2f(-0.9f + 0.6f * (float)q, 0.4f);
        }
        glEnd();
        glFinish();
    }
}

static void own_handler(int sig)
{
    static const char msg[] = "program's own handler\n";
    (void)sig;
    if (write(2, msg, sizeof msg - 1) < 0)
        _exit(4);
    _exit(3);
}

/* Runs child() in a fork; its stderr into out (size n), its wait status returned. */
static int run(void (*child)(void), char *out, size_t n)
{
    int fds[2], status = 0;
    if (pipe(fds) != 0)
        return -1;
    pid_t pid = fork();
    if (pid == 0) {
        dup2(fds[1], 2);
        close(fds[0]);
        child();
        _exit(0);
    }
    close(fds[1]);
    size_t got = 0;
    ssize_t k;
    while (got + 1 < n && (k = read(fds[0], out + got, n - 1 - got)) > 0)
        got += (size_t)k;
    out[got] = 0;
    close(fds[0]);
    waitpid(pid, &status, 0);
    return status;
}

static void by_sigint(void)
{
    draw_quads(2);
    raise(SIGINT);
}

static void by_sigterm(void)
{
    draw_quads(2);
    raise(SIGTERM);
}

static void with_own_handler(void)
{
    signal(SIGINT, own_handler);
    draw_quads(2);
    raise(SIGINT);
}

int main(void)
{
    static char out[8192];
    if (!getenv("QUADGL_STATS")) {
        fprintf(stderr, "run with QUADGL_STATS=1 and the library preloaded\n");
        return 1;
    }
    int st = run(by_sigint, out, sizeof out);
    if (WIFEXITED(st) && WEXITSTATUS(st) == 77)
        return 77;
    printf("SIGINT: %s", out);
    check(WIFSIGNALED(st) && WTERMSIG(st) == SIGINT, "the program did not die of SIGINT");
    check(strstr(out, "quadgl: 6 quads:") != NULL, "no statistics line (6 quads) on SIGINT");

    st = run(by_sigterm, out, sizeof out);
    printf("SIGTERM: %s", out);
    check(WIFSIGNALED(st) && WTERMSIG(st) == SIGTERM, "the program did not die of SIGTERM");
    check(strstr(out, "quadgl: 6 quads:") != NULL, "no statistics line (6 quads) on SIGTERM");

    st = run(with_own_handler, out, sizeof out);
    printf("own handler: %s", out);
    check(WIFEXITED(st) && WEXITSTATUS(st) == 3 && strstr(out, "program's own handler"),
          "the program's own SIGINT handler did not run or did not decide the exit");

    printf("%s\n", failures ? "FAILED" : "ok");
    return failures ? 1 : 0;
}
