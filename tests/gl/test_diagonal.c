/* test_diagonal: which diagonal the driver splits a quad along, and what the real-program
 * photographs (tools/apps-photo.sh) may rely on.
 *
 * Random quads of every shape (mostly concave and bow-ties, whose two splits cover different
 * pixels) are drawn by the driver as GL_QUADS and as GL_QUAD_STRIP, in immediate mode and from
 * a display list, under both provoking-vertex conventions, inside the window and reaching far
 * out of it (so the driver clips), and compared with the driver's own triangles of each split:
 * 0-1-3 with 1-2-3 (diagonal 1-3) and 0-1-2 with 0-2-3 (diagonal 0-2; a strip's quad is
 * v0 v1 v3 v2). The table shows, per case, how many quads covered exactly the pixels of one
 * split or the other. No single diagonal is the driver's everywhere (on llvmpipe it depends on
 * the primitive, the convention and whether the draw clipped), so the photographs' mask holds
 * the footprint of both splits of every smooth quad. What must hold, and is checked: each
 * quad's pixels are one split's exactly. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"

#define W 96
#define H 96
#define NQUADS 200

static int covered(const th_ctx *t, unsigned char *mask)
{
    glFinish();
    int n = 0;
    for (int i = 0; i < W * H; i++)
        n += mask[i] = t->buf[4 * i] != 0;
    return n;
}

/* The quad q through the driver: as GL_QUADS or GL_QUAD_STRIP, immediately or from a list. */
static void driver_quad(const float q[4][2], int strip, int list)
{
    static const int order[4] = {0, 1, 3, 2};
    glClear(GL_COLOR_BUFFER_BIT);
    if (list)
        glNewList(1, GL_COMPILE);
    glBegin(strip ? GL_QUAD_STRIP : GL_QUADS);
    for (int i = 0; i < 4; i++)
        glVertex2fv(q[strip ? order[i] : i]);
    glEnd();
    if (list) {
        glEndList();
        glCallList(1);
    }
}

/* The driver's triangles of the split along diagonal a-(a+2). */
static void split(const float q[4][2], int a)
{
    glClear(GL_COLOR_BUFFER_BIT);
    glBegin(GL_TRIANGLES);
    for (int k = 0; k < 6; k++)
        glVertex2fv(q[(a + (const int[6]){0, 1, 2, 0, 2, 3}[k]) & 3]);
    glEnd();
}

static float rnd(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (float)(*s >> 8) / 16777216.0f;
}

int main(void)
{
    th_ctx t;
    int rc = th_init(&t, W, H, NULL);
    if (rc)
        return rc;
    glClearColor(0, 0, 0, 1);
    glColor4f(1, 1, 1, 1);
    static unsigned char drv[W * H], d13[W * H], d02[W * H];
    static const char *const prim[2] = {"GL_QUADS", "GL_QUAD_STRIP"}, *const where[2] = {"inside", "clipped"};
    printf("%-14s %-9s %-6s %-7s  diagonal 1-3  diagonal 0-2  (of %d quads; one whose splits cover the same "
           "pixels counts twice)\n",
           "primitive", "mode", "first", "window", NQUADS);
    for (int c = 0; c < 16; c++) {
        int strip = c & 1, list = (c >> 1) & 1, first = (c >> 2) & 1, clipped = (c >> 3) & 1;
        unsigned seed = 7u + (unsigned)c;
        int n13 = 0, n02 = 0, neither = 0;
        glProvokingVertex(first ? GL_FIRST_VERTEX_CONVENTION : GL_LAST_VERTEX_CONVENTION);
        for (int k = 0; k < NQUADS; k++) {
            float q[4][2];
            for (int i = 0; i < 4; i++)
                for (int j = 0; j < 2; j++)
                    q[i][j] = (2 * rnd(&seed) - 1) * (clipped ? 3.0f : 0.95f);
            driver_quad(q, strip, list);
            covered(&t, drv);
            /* a strip's quad is v0 v1 v3 v2: its diagonals are those of that quad */
            split(q, 1);
            covered(&t, d13);
            split(q, 0);
            covered(&t, d02);
            int is13 = memcmp(drv, d13, sizeof drv) == 0, is02 = memcmp(drv, d02, sizeof drv) == 0;
            n13 += is13, n02 += is02, neither += !is13 && !is02;
        }
        printf("%-14s %-9s %-6s %-7s  %12d  %12d%s\n", prim[strip], list ? "list" : "immediate", first ? "first" : "last",
               where[clipped], n13, n02, neither ? "  SOME QUADS NEITHER" : "");
        th_check(neither == 0, "%s, %s: %d quads covered the pixels of neither split", prim[strip],
                 list ? "list" : "immediate", neither);
    }
    glProvokingVertex(GL_LAST_VERTEX_CONVENTION);
    th_free(&t);
    return th_failures ? 1 : 0;
}
