/* demo_test.c: helpers of the demo suite: process runs, picture files, software pictures.
 *
 * Children are started with posix_spawn and their output appended to a log file that the
 * tests print when something fails, so a failure shows what the demo said. Software
 * pictures are drawn here with the renderer's public API and the scene's own camera, not
 * through the demo's code, so they are an independent reference for the demo's output. */
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <ftw.h>
#include <unistd.h>

#include "demo_app.h"
#include "demo_test.h"

extern char **environ;

const float dt_background[4] = {0.1f, 0.1f, 0.12f, 1.0f};

int dt_run(char *const argv[], const char *log)
{
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, log, O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    pid_t pid;
    int rc = posix_spawn(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc)
        return -1;
    int status;
    if (waitpid(pid, &status, 0) < 0)
        return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

char *dt_slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 1 << 16, len = 0;
    char *buf = malloc(cap);
    for (size_t got; buf && (got = fread(buf + len, 1, cap - len - 1, f)) > 0;) {
        len += got;
        if (len + 1 == cap) {
            char *b = realloc(buf, cap *= 2);
            if (!b)
                free(buf);
            buf = b;
        }
    }
    fclose(f);
    if (buf)
        buf[len] = 0;
    return buf;
}

const char *dt_tmpdir(const char *tag)
{
    static char path[512];
    const char *base = getenv("TMPDIR");
    snprintf(path, sizeof path, "%s/quadgl-%s-XXXXXX", base && *base ? base : "/tmp", tag);
    return mkdtemp(path);
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    return remove(path);
}

void dt_rmtree(const char *dir)
{
    nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

int dt_image_read(const char *path, dt_image *img)
{
    char err[512];
    memset(img, 0, sizeof *img);
    if (demo_image_read(path, &img->w, &img->h, &img->rgba, err, sizeof err)) {
        printf("cannot read %s: %s\n", path, err);
        return -1;
    }
    return 0;
}

void dt_image_free(dt_image *img)
{
    free(img->rgba);
    memset(img, 0, sizeof *img);
}

static int pixel_diff(const unsigned char *a, const unsigned char *b)
{
    int d = 0;
    for (int k = 0; k < 3; k++) {
        int e = abs((int)a[k] - (int)b[k]);
        d = e > d ? e : d;
    }
    return d;
}

void dt_compare(const dt_image *a, const dt_image *b, int bx, int by, dt_diff *out)
{
    long hist[256] = {0};
    double sum2 = 0;
    size_t n = (size_t)a->w * (size_t)a->h;
    out->max = 0;
    for (int y = 0; y < a->h; y++)
        for (int x = 0; x < a->w; x++) {
            const unsigned char *p = a->rgba + ((size_t)y * (size_t)a->w + (size_t)x) * 4;
            const unsigned char *q = b->rgba + ((size_t)(y + by) * (size_t)b->w + (size_t)(x + bx)) * 4;
            for (int k = 0; k < 3; k++)
                sum2 += (double)(p[k] - q[k]) * (double)(p[k] - q[k]);
            int d = pixel_diff(p, q);
            hist[d]++;
            out->max = d > out->max ? d : out->max;
        }
    out->rms = sqrt(sum2 / (3.0 * (double)n));
    long seen = 0, over = 0;
    out->p99 = -1;
    for (int d = 0; d < 256; d++) {
        seen += hist[d];
        over += d > 8 ? hist[d] : 0;
        if (out->p99 < 0 && (double)seen >= 0.99 * (double)n)
            out->p99 = d;
    }
    out->frac_over8 = (double)over / (double)n;
}

int dt_sw_picture(const qgl_sw_scene *scene, const char *method, int rotate, int w, int h, dt_image *out)
{
    qgl_sw_method_desc m;
    float *clip = NULL, *attr = NULL, *object = NULL;
    memset(out, 0, sizeof *out);
    int rc = qgl_sw_method_parse(method, &m);
    if (rc == 0)
        rc = qgl_sw_scene_arrays(scene, rotate, &clip, &attr, &object);
    qgl_sw_fb_desc fd = {.width = w, .height = h, .channels = 4};
    qgl_sw_fb *fb = rc == 0 ? qgl_sw_fb_create(&fd) : NULL;
    out->rgba = fb ? malloc((size_t)w * (size_t)h * 4) : NULL;
    if (rc == 0 && !out->rgba)
        rc = QGL_SW_ENOMEM;
    if (rc == 0) {
        qgl_sw_draw_desc d = {.method = m, .nquads = scene->nquads, .nattr = scene->nattr, .clip = clip,
                              .attr = attr, .object = object,
                              .cull = scene->cull_back ? QGL_SW_CULL_BACK : QGL_SW_CULL_NONE,
                              .shade = qgl_sw_scene_shade, .user = (void *)scene};
        qgl_sw_fb_clear(fb, dt_background, 1.0f);
        rc = qgl_sw_draw(fb, &d, NULL);
        out->w = w;
        out->h = h;
        for (size_t i = 0; i < (size_t)w * (size_t)h * 4; i++) {
            float v = fb->color[i] < 0 ? 0 : fb->color[i] > 1 ? 1 : fb->color[i];
            out->rgba[i] = (unsigned char)lrintf(v * 255.0f);
        }
    }
    qgl_sw_fb_destroy(fb);
    free(clip);
    free(attr);
    free(object);
    return rc;
}

double dt_coverage(const dt_image *img)
{
    unsigned char bg[4];
    for (int k = 0; k < 4; k++)
        bg[k] = (unsigned char)lrintf(dt_background[k] * 255.0f);
    size_t n = (size_t)img->w * (size_t)img->h, drawn = 0;
    for (size_t i = 0; i < n; i++)
        drawn += pixel_diff(img->rgba + i * 4, bg) > 8;
    return n ? (double)drawn / (double)n : 0;
}
