/* test_lit_inputs: smoothly lit quads split exactly where their lighting inputs group.
 *
 * Under smooth lighting that reads no position (a directional light, an infinite viewer) a
 * corner's colour is a function of its normal, colour and material alone, and the texture
 * coordinates pass through affine maps. The split is then exact when the corners with equal
 * lighting inputs form groups whose indicators are affine over the quad and the texture
 * coordinates are affine: a billboard (one normal, one colour, a texture spread over it, as
 * particle systems draw) or a cylinder's side with a texture. With the invisible-split rule
 * turned off (split_error < 0), so that only exactness can split a quad, each case below must
 * take the path its geometry calls for, through qgl_draw_quads and through a retained batch
 * (the cached facts) alike:
 * - split: an exact parallelogram (judged by values alone), a parallelogram rotated in floats
 *   (planar only to rounding: judged through the corners' affine dependency), a general convex
 *   planar quad with texture coordinates affine in the position, a trapezoid whose parallel
 *   sides carry one normal each; and a trapezoid with a square's texture coordinates when
 *   texturing is off (the coordinates then reach nothing);
 * - smooth path: the same trapezoid textured (its coordinates are not affine), the general
 *   quad with a normal per corner, the trapezoid with its groups across the parallel sides,
 *   and the billboard under a positional light.
 * Each split picture must match the driver's own quad within 2/255 and the forced smooth path
 * (MVC_PLANE, the mean value interpolation) within 3/255 except at most 1% of the pixels
 * (the edges' coverage); each is also checked to draw something, and written as
 * lit_inputs_N.ppm. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scenes.h"

#define W 96

typedef struct lit_case {
    const char *name;
    float pos[4][3], nrm[4][3], uv[4][2];
    int textured, positional;
    int split; /* the path expected: 1 split, 0 smooth */
} lit_case;

static lit_case cases[9];
static int ncases;

static void add(const char *name, const float p[4][3], const float n[4][3], const float uv[4][2], int textured,
                int positional, int split)
{
    lit_case *c = &cases[ncases++];
    c->name = name;
    for (int i = 0; i < 4; i++) {
        for (int k = 0; k < 3; k++)
            c->pos[i][k] = p[i][k], c->nrm[i][k] = n[i][k];
        c->uv[i][0] = uv[i][0], c->uv[i][1] = uv[i][1];
    }
    c->textured = textured, c->positional = positional, c->split = split;
}

static void make_cases(void)
{
    static const float one_n[4][3] = {{0.2f, 0.3f, 1}, {0.2f, 0.3f, 1}, {0.2f, 0.3f, 1}, {0.2f, 0.3f, 1}};
    static const float square_uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    /* exact in floats: p0 + p2 == p1 + p3 */
    static const float par[4][3] = {{-0.75f, -0.625f, 0}, {0.5f, -0.375f, 0.25f}, {0.75f, 0.75f, 0.5f},
                                    {-0.5f, 0.5f, 0.25f}};
    float rot[4][3], gen[4][3], gen_uv[4][2], trap[4][3], trap_uv[4][2];
    /* centre +- ex +- ey with ex, ey turned by 0.3 rad, as a billboard's corners are computed */
    float c = cosf(0.3f), s = sinf(0.3f), cx = 0.1f, cy = -0.05f;
    float ex[3] = {0.8f * c, 0.8f * s, 0.1f}, ey[3] = {-0.7f * s, 0.7f * c, 0.2f};
    const float sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
    for (int i = 0; i < 4; i++) {
        rot[i][0] = cx + sx[i] * ex[0] + sy[i] * ey[0];
        rot[i][1] = cy + sx[i] * ex[1] + sy[i] * ey[1];
        rot[i][2] = sx[i] * ex[2] + sy[i] * ey[2];
    }
    /* a convex quad in the plane z = 0.2 x + 0.1 y, no two sides parallel */
    static const float gxy[4][2] = {{-0.8f, -0.7f}, {0.7f, -0.9f}, {0.9f, 0.6f}, {-0.6f, 0.8f}};
    for (int i = 0; i < 4; i++) {
        gen[i][0] = gxy[i][0], gen[i][1] = gxy[i][1], gen[i][2] = 0.2f * gxy[i][0] + 0.1f * gxy[i][1];
        gen_uv[i][0] = 0.7f * gxy[i][0] + 0.2f * gxy[i][1] + 0.5f, gen_uv[i][1] = -0.3f * gxy[i][0] + 0.9f * gxy[i][1];
    }
    /* a trapezoid: side 0-1 (y = -0.8) parallel to side 3-2 (y = 0.8), half as long */
    static const float txy[4][2] = {{-0.9f, -0.8f}, {0.9f, -0.8f}, {0.45f, 0.8f}, {-0.45f, 0.8f}};
    for (int i = 0; i < 4; i++) {
        trap[i][0] = txy[i][0], trap[i][1] = txy[i][1], trap[i][2] = 0.1f * txy[i][1];
        trap_uv[i][0] = 0.5f * txy[i][0] + 0.5f, trap_uv[i][1] = 0.5f * txy[i][1] + 0.5f;
    }
    static const float corner_n[4][3] = {{-0.6f, -0.5f, 1}, {0.7f, -0.4f, 1}, {0.5f, 0.6f, 1}, {-0.3f, 0.7f, 1}};
    static const float rows_n[4][3] = {{0, -0.6f, 1}, {0, -0.6f, 1}, {0, 0.6f, 1}, {0, 0.6f, 1}};
    static const float cols_n[4][3] = {{-0.6f, 0, 1}, {0.6f, 0, 1}, {0.6f, 0, 1}, {-0.6f, 0, 1}};
    add("parallelogram", par, one_n, square_uv, 1, 0, 1);
    add("rotated billboard", rot, one_n, square_uv, 1, 0, 1);
    add("general quad", gen, one_n, gen_uv, 1, 0, 1);
    add("trapezoid, normals by side", trap, rows_n, trap_uv, 1, 0, 1);
    add("trapezoid, untextured", trap, one_n, square_uv, 0, 0, 1);
    add("trapezoid, square uv", trap, one_n, square_uv, 1, 0, 0);
    add("general quad, corner normals", gen, corner_n, gen_uv, 1, 0, 0);
    add("trapezoid, normals across", trap, cols_n, trap_uv, 1, 0, 0);
    add("billboard, positional light", par, one_n, square_uv, 1, 1, 0);
}

static const float colour[4] = {0.8f, 0.6f, 0.4f, 1};

static void set_state(const lit_case *c, unsigned tex)
{
    static const float dir[4] = {0.3f, 0.4f, 1, 0}, point[4] = {0.2f, 0.1f, 0.9f, 1};
    static const float spec[4] = {0.6f, 0.6f, 0.6f, 1};
    glShadeModel(GL_SMOOTH);
    glEnable(GL_LIGHTING);
    glEnable(GL_LIGHT0);
    glEnable(GL_COLOR_MATERIAL);
    glEnable(GL_NORMALIZE);
    glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, spec);
    glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 12);
    glMatrixMode(GL_MODELVIEW);
    glPushMatrix();
    glLoadIdentity(); /* the light in eye space */
    glLightfv(GL_LIGHT0, GL_POSITION, c->positional ? point : dir);
    glPopMatrix();
    glBindTexture(GL_TEXTURE_2D, tex);
    if (c->textured)
        glEnable(GL_TEXTURE_2D);
    else
        glDisable(GL_TEXTURE_2D);
}

static qgl_quad_batch batch(const lit_case *c)
{
    static float col[4][4];
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++)
            col[i][k] = colour[k];
    qgl_quad_batch b = {.topology = QGL_QUADS, .count = 4};
    b.position = (qgl_attrib){c->pos, 3, GL_FLOAT, 0};
    b.normal = (qgl_attrib){c->nrm, 3, GL_FLOAT, 0};
    b.color = (qgl_attrib){col, 4, GL_FLOAT, 0};
    b.texcoord[0] = (qgl_attrib){c->uv, 2, GL_FLOAT, 0};
    return b;
}

static void draw_native(const lit_case *c)
{
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glColor4fv(colour);
        glNormal3fv(c->nrm[i]);
        glTexCoord2fv(c->uv[i]);
        glVertex3fv(c->pos[i]);
    }
    glEnd();
}

/* Draws c through qgl (retained r, or qgl_draw_quads) under method m; the picture and the
 * counters' change. */
static unsigned char *draw_ours(th_ctx *t, const lit_case *c, qgl_retained *r, qgl_method m, qgl_gl_stats_t *d)
{
    qgl_gl_stats_t s0, s1;
    qgl_gl_set_method(t->qgl, m);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    qgl_gl_stats(t->qgl, &s0);
    if (r) {
        th_check(qgl_gl_draw_retained(t->qgl, r) == 1, "%s: the retained batch draws one quad", c->name);
    } else {
        qgl_quad_batch b = batch(c);
        qgl_draw_quads(t->qgl, &b);
    }
    qgl_gl_stats(t->qgl, &s1);
    d->split = s1.split - s0.split;
    d->mvc = s1.mvc - s0.mvc + s1.fallback - s0.fallback + s1.subdiv - s0.subdiv;
    qgl_gl_set_method(t->qgl, QGL_METHOD_AUTO);
    return th_snapshot(t);
}

static void check(th_ctx *t, const lit_case *c, unsigned tex)
{
    set_state(c, tex);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw_native(c);
    unsigned char *native = th_snapshot(t);
    qgl_quad_batch b = batch(c);
    qgl_retained *r = qgl_gl_retain(&b, NULL);
    th_check(r != NULL, "%s: qgl_gl_retain succeeds", c->name);
    for (int retained = 0; retained < 2 && r; retained++) {
        const char *via = retained ? "retained" : "qgl_draw_quads";
        qgl_gl_stats_t d, dm;
        unsigned char *ours = draw_ours(t, c, retained ? r : NULL, QGL_METHOD_AUTO, &d);
        th_check(d.split == (uint64_t)c->split && d.mvc == (uint64_t)!c->split,
                 "%s (%s): split %llu, smooth %llu; expected the %s", c->name, via, (unsigned long long)d.split,
                 (unsigned long long)d.mvc, c->split ? "split" : "smooth path");
        if (c->split) {
            unsigned char *mvc = draw_ours(t, c, retained ? r : NULL, QGL_METHOD_MVC_PLANE, &dm);
            int over_n, over_m, dn = sc_diff(t, native, ours, 2, &over_n), dmv = sc_diff(t, mvc, ours, 3, &over_m);
            th_check(over_n == 0, "%s (%s): %d pixels differ from the driver's quad by more than 2 (max %d)", c->name,
                     via, over_n, dn);
            th_check(over_m <= W * W / 100, "%s (%s): %d pixels differ from the smooth path by more than 3 (max %d)",
                     c->name, via, over_m, dmv);
            free(mvc);
        }
        size_t lit = 0;
        for (int i = 0; i < W * W; i++)
            lit += ours[4 * i] + ours[4 * i + 1] + ours[4 * i + 2] > 60;
        th_check(lit > (size_t)W * W / 8, "%s (%s): the quad is drawn (%zu pixels)", c->name, via, lit);
        if (!retained) {
            char name[32];
            snprintf(name, sizeof name, "lit_inputs_%d", (int)(c - cases));
            th_write(t, ours, name);
            printf("%-30s split %llu smooth %llu\n", c->name, (unsigned long long)d.split, (unsigned long long)d.mvc);
        }
        free(ours);
    }
    qgl_gl_release(r);
    free(native);
}

int main(void)
{
    th_ctx t;
    int rc = th_init(&t, W, W, NULL);
    if (rc)
        return rc;
    if ((rc = th_need_geometry_shaders(&t)) != 0)
        return rc;
    qgl_gl_set_split_error(t.qgl, -1); /* only an exact split may split */
    unsigned tex = sc_texture(0);
    sc_camera(-35, 20);
    make_cases();
    for (int i = 0; i < ncases; i++)
        check(&t, &cases[i], tex);
    glDeleteTextures(1, &tex);
    th_free(&t);
    printf("%s\n", th_failures ? "FAIL" : "ok");
    return th_failures ? 1 : 0;
}
