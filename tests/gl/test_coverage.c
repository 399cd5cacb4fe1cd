/* test_coverage: watertightness, rotation invariance, flat shading, polygon mode line.
 *
 * Watertight: jittered (concave and non-planar) meshes as quads and strips, drawn with
 * additive blending of a constant colour: no pixel may be hit twice, and the covered set must
 * equal the driver's split of the same mesh (whose own counts are no oracle: a concave quad
 * split through the wrong diagonal covers a sliver of its neighbour twice), in 2D and in
 * perspective (small z jitter: the mesh must not fold over itself). Rotation: a quad whose corner list is rotated by 1, 2, 3 places renders the
 * same picture within 1/255. Flat: every pixel of quad k takes vertex 4k+3's colour (strip
 * 2k+3), as the driver does. Polygon mode line: the picture equals the driver's outline and
 * the quad's diagonal is not drawn. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

static void watertight(th_ctx *t, int strips, int persp)
{
    sc_mesh *m = malloc(sizeof *m);
    sc_jitter_grid(m, 12, 0.45f, persp ? 0.08f : 0, 7u + (unsigned)strips, strips);
    if (persp) {
        sc_camera(-30, 15);
    } else {
        glMatrixMode(GL_PROJECTION);
        glLoadIdentity();
        glMatrixMode(GL_MODELVIEW);
        glLoadIdentity();
    }
    glDisable(GL_DEPTH_TEST);
    glClearColor(0, 0, 0, 0);
    sc_coverage cv;
    sc_coverage_run(t, m, &cv);
    unsigned char *native = cv.native, *ours = cv.ours;
    qgl_gl_stats_t st = cv.st;
    int twice = cv.twice, differ = cv.differ, inside = cv.inside;
    char name[64];
    snprintf(name, sizeof name, "watertight_%s%s", strips ? "strip" : "quads", persp ? "_persp" : "");
    printf("%-26s covered %d, hit twice %d, differ from native %d (mvc quads %llu of %llu)\n", name, inside, twice,
           differ, (unsigned long long)st.mvc, (unsigned long long)st.quads);
    th_write(t, ours, name);
    for (int i = 0; i < t->w * t->h; i++) /* the difference image: red missing, green extra */
        ours[4 * i + 1] = ours[4 * i] > native[4 * i] ? 255 : 0, ours[4 * i + 2] = ours[4 * i] < native[4 * i] ? 255 : 0;
    strcat(name, "_diff");
    th_write(t, ours, name);
    th_check(inside > 10000 && twice == 0 && differ == 0, "%s: coverage differs", name);
    th_check(st.mvc == st.quads, "%s: not all on the shader path", name);
    glDisable(GL_BLEND);
    free(native);
    free(ours);
    free(m);
}

static void draw_rotated(const float p[4][3], const float c[4][4], const float uv[4][2], int rot)
{
    qglBegin(GL_QUADS);
    for (int k = 0; k < 4; k++) {
        int i = (k + rot) & 3;
        qglColor4fv(c[i]);
        qglTexCoord2fv(uv[i]);
        qglVertex3fv(p[i]);
    }
    qglEnd();
}

static void rotation(th_ctx *t, const float p[4][3], const char *name)
{
    static const float c[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
    static const float uv[4][2] = {{0, 0}, {1.3f, 0.1f}, {1, 1}, {-0.2f, 0.8f}};
    sc_camera(-35, 10);
    sc_texture(1);
    glEnable(GL_TEXTURE_2D);
    glEnable(GL_DEPTH_TEST);
    unsigned char *first = NULL;
    for (int rot = 0; rot < 4; rot++) {
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        draw_rotated(p, c, uv, rot);
        unsigned char *img = th_snapshot(t);
        if (!first) {
            first = img;
            th_write(t, img, name);
            continue;
        }
        int over, worst = sc_diff(t, first, img, 1, &over);
        printf("%-26s rotation %d: worst %d/255, %d pixels over 1\n", name, rot, worst, over);
        th_check(over == 0, "%s: rotation %d changes the picture", name, rot);
        free(img);
    }
    free(first);
    glDisable(GL_TEXTURE_2D);
}

static void flat(th_ctx *t, int strips)
{
    sc_mesh *m = malloc(sizeof *m);
    sc_jitter_grid(m, 6, 0.3f, 0.2f, 11, strips);
    sc_camera(-30, 5);
    glShadeModel(GL_FLAT);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    sc_draw(m, 1, 1, 0);
    unsigned char *native = th_snapshot(t);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    sc_draw(m, 0, 1, 0);
    unsigned char *ours = th_snapshot(t);
    int over, worst = sc_diff(t, native, ours, 1, &over);
    /* each provoking colour must appear: quad k of a strip row takes vertex 2k+3 */
    int found = 0, quads = 0;
    int per = strips ? 2 * (m->strip_cols + 1) : 4;
    int nq = strips ? m->strip_rows * m->strip_cols : m->nverts / 4;
    for (int q = 0; q < nq; q++, quads++) {
        int v = strips ? (q / m->strip_cols) * per + 2 * (q % m->strip_cols) + 3 : 4 * q + 3;
        unsigned char want[3];
        for (int k = 0; k < 3; k++)
            want[k] = (unsigned char)(m->col[v][k] * 255 + 0.5f);
        for (int i = 0; i < t->w * t->h; i++)
            if (abs(ours[4 * i] - want[0]) <= 1 && abs(ours[4 * i + 1] - want[1]) <= 1 &&
                abs(ours[4 * i + 2] - want[2]) <= 1) {
                found++;
                break;
            }
    }
    printf("flat %-7s worst %d/255 vs native, %d pixels over 1; provoking colours found %d of %d\n",
           strips ? "strip" : "quads", worst, over, found, quads);
    th_write(t, ours, strips ? "flat_strip" : "flat_quads");
    th_check(over == 0 && found == quads, "flat shading (%s) differs", strips ? "strip" : "quads");
    glShadeModel(GL_SMOOTH);
    free(native);
    free(ours);
    free(m);
}

static void polygon_line(th_ctx *t)
{
    static const float p[4][3] = {{-0.8f, -0.8f, 0}, {0.8f, -0.7f, 0}, {0.7f, 0.8f, 0}, {-0.75f, 0.6f, 0}};
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glDisable(GL_DEPTH_TEST);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glColor3f(1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++)
        glVertex3fv(p[i]);
    glEnd();
    unsigned char *native = th_snapshot(t);
    glClear(GL_COLOR_BUFFER_BIT);
    qgl_gl_reset_stats(t->qgl);
    qglBegin(GL_QUADS);
    for (int i = 0; i < 4; i++)
        qglVertex3fv(p[i]);
    qglEnd();
    unsigned char *ours = th_snapshot(t);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    qgl_gl_stats_t st;
    qgl_gl_stats(t->qgl, &st);
    int over, worst = sc_diff(t, native, ours, 0, &over);
    /* pixels along both diagonals, away from the corners, must stay black */
    int lit = 0, outline = 0;
    for (int k = 10; k <= 90; k++) {
        for (int d = 0; d < 2; d++) {
            const float *a = p[d], *b = p[d + 2];
            float x = a[0] + (b[0] - a[0]) * k / 100.0f, y = a[1] + (b[1] - a[1]) * k / 100.0f;
            int px = (int)((x + 1) * 0.5f * t->w), py = (int)((y + 1) * 0.5f * t->h);
            lit += ours[4 * (py * t->w + px)] != 0;
        }
    }
    for (int i = 0; i < t->w * t->h; i++)
        outline += ours[4 * i] != 0;
    printf("polygon line: worst %d vs native, %d differ, diagonal pixels lit %d, outline pixels %d, passthrough %llu\n",
           worst, over, lit, outline, (unsigned long long)st.passthrough);
    th_write(t, ours, "polygon_line");
    th_check(over == 0 && lit == 0 && outline > 400 && st.passthrough == 1, "polygon mode line");
    free(native);
    free(ours);
}

int main(void)
{
    th_ctx t;
    qgl_gl_desc d = {.method = QGL_METHOD_MVC};
    int rc = th_init(&t, 256, 256, &d);
    if (rc)
        return rc;
    for (int persp = 0; persp < 2; persp++)
        for (int strips = 0; strips < 2; strips++)
            watertight(&t, strips, persp);
    static const float saddle[4][3] = {{-1, -1, 0.4f}, {1, -0.8f, -0.4f}, {0.9f, 1, 0.4f}, {-1, 0.9f, -0.4f}};
    static const float dart[4][3] = {{-1, -1, 0}, {1, 0, 0}, {-1, 1, 0}, {-0.2f, 0, 0}};
    static const float bowtie[4][3] = {{-1, -1, 0}, {1, 1, 0.2f}, {1, -1, 0}, {-1, 1, -0.2f}};
    rotation(&t, saddle, "rotation_saddle");
    rotation(&t, dart, "rotation_dart");
    rotation(&t, bowtie, "rotation_bowtie");
    flat(&t, 0);
    flat(&t, 1);
    polygon_line(&t);
    th_free(&t);
    return th_failures ? 1 : 0;
}
