/* bench_preload.c: immediate-mode cost per vertex, for tools/quadgl-preload-bench.sh.
 *
 * An ordinary OSMesa program (no quadgl code in it): each frame draws a grid of small quads
 * in immediate mode (glBegin/glEnd around all of them, a colour and a vertex call per
 * vertex) into a 256 x 256 buffer, then glFinish. It prints the median frame time and the
 * time per vertex. The script runs it natively and with libquadgl-preload.so preloaded
 * (each QUADGL_METHOD), so the ratio is the library's cost per vertex: capture, planning
 * and drawing, against the driver's own immediate mode. With a third argument each
 * glBegin/glEnd holds that many quads (1: one quad per glBegin, as many programs draw text and
 * tiles), so the cost per primitive shows too.
 *
 *   quadgl-preload-bench [vertices per frame (default 1000000)] [frames (default 7)]
 *                        [quads per glBegin (default all)] */
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define SIZE 256

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void frame(int quads, int per_begin)
{
    const int grid = 250;
    const float d = 2.0f / (float)grid;
    glClear(GL_COLOR_BUFFER_BIT);
    glBegin(GL_QUADS);
    for (int k = 0; k < quads; k++) {
        if (per_begin && k && k % per_begin == 0) {
            glEnd();
            glBegin(GL_QUADS);
        }
        int cell = k % (grid * grid);
        float x = -1.0f + d * (float)(cell % grid), y = -1.0f + d * (float)(cell / grid);
        glColor3ub((GLubyte)k, (GLubyte)(k >> 3), 128);
        glVertex2f(x, y);
        glColor3ub((GLubyte)(k + 40), (GLubyte)(k >> 3), 128);
        glVertex2f(x + d, y);
        glColor3ub((GLubyte)(k + 80), (GLubyte)(k >> 2), 128);
        glVertex2f(x + d, y + d);
        glColor3ub((GLubyte)(k + 120), (GLubyte)(k >> 2), 128);
        glVertex2f(x, y + d);
    }
    glEnd();
    glFinish();
}

int main(int argc, char **argv)
{
    int vertices = argc > 1 ? atoi(argv[1]) : 1000000, frames = argc > 2 ? atoi(argv[2]) : 7;
    int per_begin = argc > 3 ? atoi(argv[3]) : 0;
    unsigned char *buf = malloc(SIZE * SIZE * 4);
    OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 16, 0, 0, NULL);
    double *t;
    if (vertices < 4 || frames < 1 || per_begin < 0 || !buf || !ctx || !OSMesaMakeCurrent(ctx, buf, GL_UNSIGNED_BYTE, SIZE, SIZE))
        return 1;
    t = malloc((size_t)frames * sizeof *t);
    if (!t)
        return 1;
    frame(vertices / 4, per_begin); /* warm-up: shaders compiled, buffers grown */
    for (int f = 0; f < frames; f++) {
        double t0 = now();
        frame(vertices / 4, per_begin);
        t[f] = now() - t0;
    }
    qsort(t, (size_t)frames, sizeof *t, cmp);
    printf("frame %.2f ms, %.1f ns per vertex (%d vertices, median of %d frames)\n", 1e3 * t[frames / 2],
           1e9 * t[frames / 2] / (double)(vertices / 4 * 4), vertices / 4 * 4, frames);
    OSMesaDestroyContext(ctx);
    free(buf);
    free(t);
    return 0;
}
