/* pt.c: the preload tests' harness (see pt.h): OSMesa context, native child, comparisons.
 *
 * The native side is this executable run again through /proc/self/exe with LD_PRELOAD
 * removed from its environment; it writes one pt_run to a pipe. The reference inside a
 * declared quad is the mean value interpolation of its corner colours at the pixel centre
 * (qgl_weights with w = 1), compared with a tolerance of 3/255 per channel (8-bit rounding
 * plus the shader's float arithmetic); pixels within 1.5 pixels of a quad's outline are left
 * out, as the rasterizers may legitimately decide them differently. PT_VERBOSE=1 lists every
 * pixel off, not only the first five. */
#include "pt.h"

#include <GL/osmesa.h>
#include <dlfcn.h>
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <quadgl/quadgl.h>

extern char **environ;

void pt_value(pt_run *r, uint32_t v)
{
    if (r->nvalues < PT_MAX_VALUES)
        r->values[r->nvalues++] = v;
}

void pt_expect(pt_run *r, const float v[4][2], const float c[4][4], int flat)
{
    pt_quad *q;
    if (r->nquads >= PT_MAX_QUADS)
        return;
    q = &r->quads[r->nquads++];
    memcpy(q->v, v, sizeof q->v);
    memcpy(q->c, c, sizeof q->c);
    q->flat = flat;
}

void pt_begin_frame(void)
{
    glViewport(0, 0, PT_W, PT_H);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

/* Draws the scene in a fresh OSMesa context; 0 or -1 when no context could be made. */
static int pt_render(const pt_scene *s, pt_run *r)
{
    OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, NULL);
    if (!ctx || !OSMesaMakeCurrent(ctx, r->pixels, GL_UNSIGNED_BYTE, PT_W, PT_H)) {
        if (ctx)
            OSMesaDestroyContext(ctx);
        return -1;
    }
    s->draw(r);
    glFinish();
    OSMesaDestroyContext(ctx);
    return 0;
}

static int pt_write_all(int fd, const void *buf, size_t n)
{
    const char *p = buf;
    while (n) {
        ssize_t k = write(fd, p, n);
        if (k <= 0)
            return -1;
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

static int pt_read_all(int fd, void *buf, size_t n)
{
    char *p = buf;
    while (n) {
        ssize_t k = read(fd, p, n);
        if (k <= 0)
            return -1;
        p += k;
        n -= (size_t)k;
    }
    return 0;
}

/* The environment without LD_PRELOAD. */
static char **pt_native_env(void)
{
    size_t n = 0, k = 0;
    char **env;
    while (environ[n])
        n++;
    env = calloc(n + 1, sizeof *env);
    for (size_t i = 0; env && i < n; i++)
        if (strncmp(environ[i], "LD_PRELOAD=", 11) != 0)
            env[k++] = environ[i];
    return env;
}

static int pt_render_native(const char *name, pt_run *r)
{
    int fds[2], status = 0, rc;
    pid_t pid;
    char *args[] = {"pt-native", "--native", (char *)name, NULL};
    char **env = pt_native_env();
    posix_spawn_file_actions_t fa;
    if (!env || pipe(fds) != 0) {
        free(env);
        return -1;
    }
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
    posix_spawn_file_actions_addclose(&fa, fds[0]);
    rc = posix_spawn(&pid, "/proc/self/exe", &fa, NULL, args, env);
    posix_spawn_file_actions_destroy(&fa);
    free(env);
    close(fds[1]);
    if (rc != 0) {
        close(fds[0]);
        return -1;
    }
    rc = pt_read_all(fds[0], r, sizeof *r);
    close(fds[0]);
    waitpid(pid, &status, 0);
    return (rc == 0 && WIFEXITED(status) && WEXITSTATUS(status) == 0) ? 0 : -1;
}

int pt_preloaded(void)
{
    Dl_info info;
    void *fn = dlsym(RTLD_DEFAULT, "glBegin");
    return fn && dladdr(fn, &info) && info.dli_fname && strstr(info.dli_fname, "quadgl-preload");
}

static void pt_stats(uint64_t out[PT_NCOUNTERS])
{
    void (*get)(uint64_t *) = (void (*)(uint64_t *))dlsym(RTLD_DEFAULT, "qgl_preload_stats");
    memset(out, 0, PT_NCOUNTERS * sizeof *out);
    if (get)
        get(out);
}

int pt_counters(uint64_t out[PT_NCOUNTERS])
{
    const char *method = getenv("QUADGL_METHOD");
    pt_stats(out);
    if (!pt_preloaded() || (method && (!strcmp(method, "off") || !strcmp(method, "replay"))))
        return -1;
    return 0;
}

/* ---- comparisons ---------------------------------------------------------------------------- */

static int pt_channel_diff(const unsigned char *a, const unsigned char *b)
{
    int d = 0;
    for (int k = 0; k < 3; k++) {
        int e = abs((int)a[k] - (int)b[k]);
        d = e > d ? e : d;
    }
    return d;
}

static double pt_seg_dist(const float a[2], const float b[2], double x, double y)
{
    double dx = b[0] - a[0], dy = b[1] - a[1], t;
    double l2 = dx * dx + dy * dy;
    t = l2 > 0 ? ((x - a[0]) * dx + (y - a[1]) * dy) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(x - (a[0] + t * dx), y - (a[1] + t * dy));
}

/* Pixel distance from (px, py) (pixel units) to the quad's outline. */
static double pt_outline_dist(const pt_quad *q, double px, double py)
{
    double best = 1e30;
    for (int i = 0; i < 4; i++) {
        float a[2] = {(q->v[i][0] + 1) * PT_W / 2, (q->v[i][1] + 1) * PT_H / 2};
        float b[2] = {(q->v[(i + 1) % 4][0] + 1) * PT_W / 2, (q->v[(i + 1) % 4][1] + 1) * PT_H / 2};
        double d = pt_seg_dist(a, b, px, py);
        best = d < best ? d : best;
    }
    return best;
}

/* 1 inside (reference colour to ref), 0 outside, -1 near the outline. */
static int pt_reference(const pt_run *r, int x, int y, unsigned char ref[3])
{
    double nx = (x + 0.5) * 2.0 / PT_W - 1, ny = (y + 0.5) * 2.0 / PT_H - 1;
    int result = 0;
    for (int k = 0; k < r->nquads; k++) {
        const pt_quad *q = &r->quads[k];
        double clip[4][4], w[4], v2[4][2];
        for (int i = 0; i < 4; i++) {
            clip[i][0] = v2[i][0] = q->v[i][0];
            clip[i][1] = v2[i][1] = q->v[i][1];
            clip[i][2] = 0;
            clip[i][3] = 1;
        }
        if (pt_outline_dist(q, x + 0.5, y + 0.5) < 1.5)
            return -1;
        if (!qgl_inside(v2, nx, ny))
            continue;
        qgl_weights(clip, nx, ny, w, NULL);
        for (int c = 0; c < 3; c++) {
            double v = 0;
            for (int i = 0; i < 4; i++)
                v += (q->flat ? (i == q->flat - 1) : w[i]) * q->c[i][c];
            v = v < 0 ? 0 : v > 1 ? 1 : v;
            ref[c] = (unsigned char)lround(v * 255.0);
        }
        result = 1; /* later quads are drawn over earlier ones */
    }
    return result;
}

static int pt_compare(const char *name, const pt_run *ours, const pt_run *native, int exact)
{
    int bad = 0, worst = 0, inside = 0, smoothed = 0, errors = 0, any_smooth = 0;
    for (int k = 0; k < ours->nquads; k++)
        any_smooth |= !ours->quads[k].flat;
    if (ours->nvalues != native->nvalues ||
        memcmp(ours->values, native->values, sizeof(uint32_t) * (size_t)ours->nvalues)) {
        fprintf(stderr, "%s: recorded values differ from native:", name);
        for (int i = 0; i < ours->nvalues || i < native->nvalues; i++)
            fprintf(stderr, " [%d] %#x/%#x", i, i < ours->nvalues ? ours->values[i] : 0,
                    i < native->nvalues ? native->values[i] : 0);
        fputc('\n', stderr);
        errors++;
    }
    for (int y = 0; y < PT_H; y++)
        for (int x = 0; x < PT_W; x++) {
            const unsigned char *a = ours->pixels + 4 * (y * PT_W + x), *b = native->pixels + 4 * (y * PT_W + x);
            unsigned char ref[3];
            int d = pt_channel_diff(a, b), role = -2, tol = 0;
            if (exact) {
                tol = 0;
            } else if (ours->native_equal) {
                tol = 2;
            } else if (ours->checks_reference && (role = pt_reference(ours, x, y, ref)) == 1) {
                inside++;
                smoothed += d > 8;
                d = pt_channel_diff(a, ref);
                tol = 3;
            } else if (role == -1) {
                continue;
            }
            worst = d > worst ? d : worst;
            if (d > tol) {
                if (bad < 5 || getenv("PT_VERBOSE"))
                    fprintf(stderr, "%s: pixel (%d,%d) ours %d %d %d native %d %d %d%s (tolerance %d)\n", name, x, y,
                            a[0], a[1], a[2], b[0], b[1], b[2], role == 1 ? " vs reference" : "", tol);
                bad++;
            }
        }
    if (!exact && ours->checks_reference && !ours->native_equal && any_smooth && smoothed == 0) {
        fprintf(stderr, "%s: no pixel differs from the native split: the quads were not smoothed\n", name);
        errors++;
    }
    printf("%s: %s, %d pixels off, worst %d/255, %d inside declared quads, %d visibly smoothed\n", name,
           exact ? "exact" : ours->native_equal ? "native" : "reference", bad, worst, inside, smoothed);
    return bad == 0 && errors == 0 ? 0 : 1;
}

/* ---- main ---------------------------------------------------------------------------------- */

static const pt_scene *pt_find(const pt_scene *scenes, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (strcmp(scenes[i].name, name) == 0)
            return &scenes[i];
    return NULL;
}

int pt_main(int argc, char **argv, const pt_scene *scenes, int nscenes)
{
    static pt_run ours, native;
    const char *method = getenv("QUADGL_METHOD");
    const pt_scene *s;
    uint64_t st[PT_NCOUNTERS];
    int exact, off, rc;
    if (argc == 3 && strcmp(argv[1], "--native") == 0) {
        if (!(s = pt_find(scenes, nscenes, argv[2])) || pt_render(s, &native) != 0)
            return 1;
        return pt_write_all(1, &native, sizeof native) == 0 ? 0 : 1;
    }
    if (argc != 2 || !(s = pt_find(scenes, nscenes, argv[1]))) {
        fprintf(stderr, "usage: %s SCENE\n", argv[0]);
        return 1;
    }
    if (!pt_preloaded()) {
        fprintf(stderr, "%s: libquadgl-preload.so is not preloaded\n", s->name);
        return 1;
    }
    if (pt_render(s, &ours) != 0) {
        fprintf(stderr, "%s: no OSMesa context\n", s->name);
        return 77;
    }
    if (pt_render_native(s->name, &native) != 0) {
        fprintf(stderr, "%s: the native run failed\n", s->name);
        return 1;
    }
    off = method && strcmp(method, "off") == 0;
    /* the split draws what the driver draws, to the last bit (depth too: passes drawn by
     * the driver over ours must meet them exactly) */
    exact = off || (method && (strcmp(method, "replay") == 0 || strcmp(method, "split") == 0));
    rc = pt_compare(s->name, &ours, &native, exact);
    if (ours.failure[0]) {
        fprintf(stderr, "%s: %s\n", s->name, ours.failure);
        rc = 1;
    }
    pt_stats(st);
    printf("%s: quadgl saw %llu quads: mvc=%llu split=%llu subdiv=%llu passthrough=%llu\n", s->name,
           (unsigned long long)st[0], (unsigned long long)st[1], (unsigned long long)st[2],
           (unsigned long long)st[3], (unsigned long long)st[4]);
    if (off ? st[0] != 0 : st[0] < (uint64_t)ours.min_quads) {
        fprintf(stderr, "%s: expected %s %d quads captured, saw %llu\n", s->name, off ? "none of the" : "at least",
                ours.min_quads, (unsigned long long)st[0]);
        rc = 1;
    }
    return rc;
}
