/* test_threads.c: two threads, each with its own OSMesa context, drawing quads at once.
 *
 * Run with libquadgl-preload.so preloaded. Each thread makes its own context current, draws
 * ref_quad.h's quad forty times (immediate mode, then from a display list of its own, the
 * two contexts using the same list name), and checks its last picture against the mean value
 * reference. Per-thread current contexts and per-context capture state and lists must keep
 * the two apart; the library's counters must show exactly the quads drawn. */
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <dlfcn.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#define REF_CHECK
#include "ref_quad.h"

#define ROUNDS 40

static void draw_quad(void)
{
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glColor3fv(ref_c[i]);
        glVertex2fv(ref_v[i]);
    }
    glEnd();
}

static void *worker(void *arg)
{
    static const char *const names[2] = {"thread 0", "thread 1"};
    int id = (int)(intptr_t)arg;
    unsigned char *rgba = calloc(REF_SIZE * REF_SIZE, 4), *rgb = calloc(REF_SIZE * REF_SIZE, 3);
    OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 16, 0, 0, NULL);
    intptr_t bad = 1;
    if (!rgba || !rgb || !ctx || !OSMesaMakeCurrent(ctx, rgba, GL_UNSIGNED_BYTE, REF_SIZE, REF_SIZE))
        goto done;
    glNewList(1, GL_COMPILE);
    draw_quad();
    glEndList();
    for (int r = 0; r < ROUNDS; r++) {
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        if (r % 2)
            glCallList(1);
        else
            draw_quad();
    }
    glFinish();
    for (int i = 0; i < REF_SIZE * REF_SIZE; i++)
        for (int c = 0; c < 3; c++)
            rgb[3 * i + c] = rgba[4 * i + c];
    bad = ref_check(rgb, names[id]);
    glDeleteLists(1, 1);
done:
    if (ctx)
        OSMesaDestroyContext(ctx);
    free(rgba);
    free(rgb);
    return (void *)bad;
}

int main(void)
{
    pthread_t t[2];
    void *res[2];
    uint64_t st[8] = {0};
    void (*stats)(uint64_t *) = (void (*)(uint64_t *))dlsym(RTLD_DEFAULT, "qgl_preload_stats");
    if (!stats) {
        fprintf(stderr, "threads: libquadgl-preload.so is not preloaded\n");
        return 1;
    }
    for (int i = 0; i < 2; i++)
        if (pthread_create(&t[i], NULL, worker, (void *)(intptr_t)i) != 0)
            return 1;
    for (int i = 0; i < 2; i++)
        pthread_join(t[i], &res[i]);
    stats(st);
    printf("threads: %llu quads captured (expected %d)\n", (unsigned long long)st[0], 2 * ROUNDS);
    return res[0] || res[1] || st[0] != 2 * ROUNDS ? 1 : 0;
}
