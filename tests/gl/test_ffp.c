/* test_ffp: the fixed-function pipeline in the shader path (issue 6).
 *
 * Oracle matrix: a 4 x 4 grid of planar quads whose every attribute (colour, secondary colour,
 * fog coordinate, texture coordinates of two units, per-vertex material) is affine in object
 * space is drawn natively and through the shader path (method MVC forced); on such quads the
 * mean value interpolation equals the driver's split, so every pixel must match within 2/255 (times a combiner scale),
 * for each state of the matrix: lights (directional, several, all eight; positional and spot
 * under flat shading, where the colour is the provoking corner's), two-sided front and back,
 * every colour-material mode and face, separate specular, NORMALIZE / RESCALE_NORMAL, per-vertex
 * glMaterial, every env mode on every base format, COMBINE functions / sources / operands /
 * scales and the crossbar, linear texgen, 1D / 3D / cube / rectangle targets, multitexture on
 * 2 and 4 units, fog LINEAR / EXP / EXP2 from the fog coordinate and from depth, colour sum,
 * clip planes, flat shading. The counters must show every quad of the matrix on the shader path.
 *
 * Reference cases, where per-vertex results are not affine (smooth lighting with positional and
 * spot lights, attenuation and a local viewer on a non-planar quad with differing normals;
 * sphere, reflection and normal map texgen): the driver's own per-corner results are read
 * back through feedback mode, and every interior pixel must equal the core's perspective
 * weights (qgl_weights, double) applied to them, within 3/255 (float weights, 8-bit texels).
 * Two-sided lighting on a bow-tie: each pixel must show the front or back material as the
 * core's membership test (qgl_inside) says its lobe faces. A clip plane across a non-planar
 * quad must cut it where the interpolated eye position crosses the plane.
 *
 * Finally the share of quads that took the CPU fallback over the whole program must stay
 * under 1%. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

enum { TOL = 2, REF_TOL = 3, W = 160, H = 160, N = 4 };

enum { A_COL = 1, A_COL2 = 2, A_FOG = 4, A_NRM = 8, A_TEX0 = 16, A_TEX1 = 32, A_MAT = 64 };

typedef struct vtx {
    float pos[3], col[4], col2[3], fog, nrm[3], tex[2][4], mat[4];
} vtx;

typedef struct grid {
    int nv, strips;
    vtx v[2 * (N + 1) * N + 4 * N * N];
} grid;

static qgl_gl_stats_t total; /* every qgl draw of the program */

/* ---- geometry ------------------------------------------------------------------------------- */

static void affine_vertex(grid *g, float s, float t)
{
    vtx *v = &g->v[g->nv++];
    float x = -1 + 2 * s + 0.3f * t, y = -1 + 2 * t;
    v->pos[0] = x, v->pos[1] = y, v->pos[2] = 0;
    float c[4] = {0.5f + 0.3f * x, 0.5f + 0.3f * y, 0.5f - 0.15f * x + 0.15f * y, 0.75f + 0.1f * x};
    memcpy(v->col, c, sizeof c);
    v->col2[0] = 0.2f + 0.1f * y, v->col2[1] = 0.15f - 0.1f * x, v->col2[2] = 0.2f + 0.05f * x;
    v->fog = 2.5f + 1.2f * x - 0.4f * y;
    v->nrm[0] = 0, v->nrm[1] = 0, v->nrm[2] = 1;
    float t0[4] = {0.7f * x + 0.2f * y, -0.2f * x + 0.9f * y, 0.3f * x - 0.4f * y + 0.5f, 1 + 0.15f * x};
    float t1[4] = {0.4f * y + 0.1f, 0.6f * x - 0.1f * y, 0.5f + 0.2f * y, 1};
    memcpy(v->tex[0], t0, sizeof t0);
    memcpy(v->tex[1], t1, sizeof t1);
    v->mat[0] = 0.5f + 0.25f * x, v->mat[1] = 0.45f - 0.2f * y, v->mat[2] = 0.4f + 0.1f * x + 0.1f * y, v->mat[3] = 0.9f;
}

static void make_grid(grid *g, int strips)
{
    g->nv = 0;
    g->strips = strips;
    for (int j = 0; j < N; j++) {
        if (strips) {
            for (int i = 0; i <= N; i++) { /* counter-clockwise, as the GL_QUADS ones */
                affine_vertex(g, (float)i / N, (float)(j + 1) / N);
                affine_vertex(g, (float)i / N, (float)j / N);
            }
            continue;
        }
        for (int i = 0; i < N; i++) {
            affine_vertex(g, (float)i / N, (float)j / N);
            affine_vertex(g, (float)(i + 1) / N, (float)j / N);
            affine_vertex(g, (float)(i + 1) / N, (float)(j + 1) / N);
            affine_vertex(g, (float)i / N, (float)(j + 1) / N);
        }
    }
}

/* One vertex through the driver (P = gl) or through qgl (P = qgl). */
#define EMIT(P, v, a) \
    do { \
        if ((a) & A_COL) \
            P##Color4fv((v)->col); \
        if ((a) & A_COL2) \
            P##SecondaryColor3fv((v)->col2); \
        if ((a) & A_FOG) \
            P##FogCoordf((v)->fog); \
        if ((a) & A_NRM) \
            P##Normal3fv((v)->nrm); \
        if ((a) & A_TEX0) \
            P##MultiTexCoord4fv(GL_TEXTURE0, (v)->tex[0]); \
        if ((a) & A_TEX1) \
            P##MultiTexCoord4fv(GL_TEXTURE1, (v)->tex[1]); \
        if ((a) & A_MAT) \
            P##Materialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, (v)->mat); \
        P##Vertex3fv((v)->pos); \
    } while (0)

static void draw_range(const vtx *v, int first, int n, GLenum mode, int native, unsigned a)
{
    if (native) {
        glBegin(mode);
        for (int i = first; i < first + n; i++)
            EMIT(gl, &v[i], a);
        glEnd();
    } else {
        qglBegin(mode);
        for (int i = first; i < first + n; i++)
            EMIT(qgl, &v[i], a);
        qglEnd();
    }
}

static void draw_grid(const grid *g, int native, unsigned a)
{
    if (!g->strips) {
        draw_range(g->v, 0, g->nv, GL_QUADS, native, a);
        return;
    }
    int per = 2 * (N + 1);
    for (int r = 0; r < N; r++)
        draw_range(g->v, r * per, per, GL_QUAD_STRIP, native, a);
}

/* ---- textures -------------------------------------------------------------------------------- */

static unsigned char texels[64 * 64 * 4];

static void fill_texels(int n)
{
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) {
            unsigned char *p = texels + 4 * (y * n + x);
            p[0] = (unsigned char)(x * 255 / (n - 1));
            p[1] = (unsigned char)(y * 255 / (n - 1));
            p[2] = (unsigned char)(64 + (x + y) * 127 / (n - 1));
            p[3] = (unsigned char)(255 - x * 160 / (n - 1));
        }
}

static void linear(GLenum target, GLenum wrap)
{
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, wrap);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, wrap);
    glTexParameteri(target, GL_TEXTURE_WRAP_R, wrap);
}

/* A 2D texture on the active unit, enabled. */
static void tex2d(GLenum ifmt)
{
    GLuint id;
    fill_texels(64);
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_2D, id);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)ifmt, 64, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    linear(GL_TEXTURE_2D, GL_REPEAT);
    glEnable(GL_TEXTURE_2D);
}

static void tex1d(void)
{
    GLuint id;
    fill_texels(64);
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_1D, id);
    glTexImage1D(GL_TEXTURE_1D, 0, GL_RGBA8, 64, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels + 4 * 64 * 20);
    linear(GL_TEXTURE_1D, GL_REPEAT);
    glEnable(GL_TEXTURE_1D);
}

static void tex3d(void)
{
    static unsigned char vox[8 * 8 * 8 * 4];
    for (int i = 0; i < 8 * 8 * 8; i++) {
        vox[4 * i] = (unsigned char)((i & 7) * 36), vox[4 * i + 1] = (unsigned char)(((i >> 3) & 7) * 36);
        vox[4 * i + 2] = (unsigned char)((i >> 6) * 36), vox[4 * i + 3] = 255;
    }
    GLuint id;
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_3D, id);
    glTexImage3D(GL_TEXTURE_3D, 0, GL_RGBA8, 8, 8, 8, 0, GL_RGBA, GL_UNSIGNED_BYTE, vox);
    linear(GL_TEXTURE_3D, GL_REPEAT);
    glEnable(GL_TEXTURE_3D);
}

static void texcube(void)
{
    GLuint id;
    fill_texels(16);
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_CUBE_MAP, id);
    for (int f = 0; f < 6; f++)
        glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)f, 0, GL_RGBA8, 16, 16, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                     texels);
    linear(GL_TEXTURE_CUBE_MAP, GL_CLAMP_TO_EDGE);
    glEnable(GL_TEXTURE_CUBE_MAP);
}

static void texrect(void)
{
    GLuint id;
    fill_texels(32);
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_RECTANGLE, id);
    glTexImage2D(GL_TEXTURE_RECTANGLE, 0, GL_RGBA8, 32, 32, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    glTexParameteri(GL_TEXTURE_RECTANGLE, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_RECTANGLE, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_RECTANGLE, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_RECTANGLE, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glEnable(GL_TEXTURE_RECTANGLE);
    glMatrixMode(GL_TEXTURE); /* rectangle coordinates are texels */
    glScalef(12, 12, 1);
    glTranslatef(1.3f, 1.3f, 0);
    glMatrixMode(GL_MODELVIEW);
}

static void env(GLenum mode)
{
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, (GLint)mode);
}

static void env_colour(void)
{
    static const float c[4] = {0.3f, 0.6f, 0.2f, 0.7f};
    glTexEnvfv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_COLOR, c);
}

/* ---- lighting ------------------------------------------------------------------------------- */

static void material(void)
{
    static const float e[4] = {0.05f, 0.05f, 0.05f, 1}, a[4] = {0.2f, 0.25f, 0.2f, 1}, d[4] = {0.5f, 0.4f, 0.3f, 0.8f},
                       s[4] = {0.3f, 0.3f, 0.3f, 1}, be[4] = {0.02f, 0.1f, 0.02f, 1}, bd[4] = {0.2f, 0.3f, 0.55f, 0.6f};
    glMaterialfv(GL_FRONT_AND_BACK, GL_EMISSION, e);
    glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, a);
    glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, d);
    glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, s);
    glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 10);
    glMaterialfv(GL_BACK, GL_EMISSION, be);
    glMaterialfv(GL_BACK, GL_DIFFUSE, bd);
    glMaterialf(GL_BACK, GL_SHININESS, 4);
}

/* Light i as given, with moderate colours (sums stay below 1: the result is affine). */
static void light(int i, float x, float y, float z, float w)
{
    const float s = 1.0f / (1 + i * 0.5f);
    float pos[4] = {x, y, z, w}, a[4] = {0.05f * s, 0.05f * s, 0.05f * s, 1}, d[4] = {0.5f * s, 0.45f * s, 0.4f * s, 1},
          sp[4] = {0.4f * s, 0.4f * s, 0.4f * s, 1};
    GLenum L = GL_LIGHT0 + (GLenum)i;
    glMatrixMode(GL_MODELVIEW);
    glPushMatrix();
    glLoadIdentity(); /* positions in eye coordinates */
    glLightfv(L, GL_POSITION, pos);
    glPopMatrix();
    glLightfv(L, GL_AMBIENT, a);
    glLightfv(L, GL_DIFFUSE, d);
    glLightfv(L, GL_SPECULAR, sp);
    glEnable(L);
}

static void lit(void)
{
    glEnable(GL_LIGHTING);
    material();
    light(0, 0.3f, 0.2f, 1, 0);
}

static void colour_material(GLenum face, GLenum mode)
{
    lit();
    glColorMaterial(face, mode);
    glEnable(GL_COLOR_MATERIAL);
}

/* ---- the oracle matrix ------------------------------------------------------------------------ */

static void s_light_dir(void) { lit(); }
static void s_two_lights(void) { lit(); light(1, -0.5f, 0.4f, 0.8f, 0); }
static void s_eight_lights(void)
{
    lit();
    for (int i = 1; i < 8; i++)
        light(i, 0.2f * (float)(i - 4), 0.1f * (float)i - 0.3f, 1, 0);
    static const float dim[4] = {0.05f, 0.05f, 0.05f, 1};
    for (int i = 0; i < 8; i++)
        glLightfv(GL_LIGHT0 + (GLenum)i, GL_DIFFUSE, dim);
}
static void s_cm_amb_diff(void) { colour_material(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE); }
static void s_cm_ambient(void) { colour_material(GL_FRONT_AND_BACK, GL_AMBIENT); }
static void s_cm_diffuse(void) { colour_material(GL_FRONT, GL_DIFFUSE); }
static void s_cm_specular(void) { colour_material(GL_FRONT_AND_BACK, GL_SPECULAR); }
static void s_cm_emission(void) { colour_material(GL_FRONT_AND_BACK, GL_EMISSION); }
static void s_cm_back_only(void) /* seen from the front: colour material on the back does nothing */
{
    colour_material(GL_BACK, GL_AMBIENT_AND_DIFFUSE);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, 1);
}
static void s_cm_both_two_side(void) /* on back faces the same as s_cm_back_only */
{
    colour_material(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, 1);
}
static void s_two_side_front(void)
{
    colour_material(GL_FRONT, GL_DIFFUSE);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, 1);
}
static void s_separate_spec(void)
{
    colour_material(GL_FRONT_AND_BACK, GL_DIFFUSE);
    glLightModeli(GL_LIGHT_MODEL_COLOR_CONTROL, GL_SEPARATE_SPECULAR_COLOR);
    tex2d(GL_RGBA8);
    env(GL_MODULATE);
}
static void s_normalize(void)
{
    lit();
    glEnable(GL_NORMALIZE);
    glScalef(1.3f, 1.3f, 1.3f);
}
static void s_rescale(void)
{
    lit();
    glEnable(GL_RESCALE_NORMAL);
    glScalef(0.8f, 0.8f, 0.8f);
}
static void s_material_pv(void) { lit(); }
static void s_flat_spot(void) /* glxgears-like: lit, flat; the provoking corner's colour */
{
    lit();
    glDisable(GL_LIGHT0);
    light(1, 0.4f, -0.3f, -1.2f, 1);
    glLightf(GL_LIGHT1, GL_SPOT_CUTOFF, 40);
    glLightf(GL_LIGHT1, GL_SPOT_EXPONENT, 3);
    static const float dir[3] = {-0.2f, 0.3f, -1};
    glLightfv(GL_LIGHT1, GL_SPOT_DIRECTION, dir);
    glLightf(GL_LIGHT1, GL_LINEAR_ATTENUATION, 0.3f);
    glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, 1);
    glShadeModel(GL_FLAT);
}
static void s_flat_positional(void)
{
    colour_material(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
    light(1, -0.5f, 0.5f, -1.5f, 1);
    glShadeModel(GL_FLAT);
}

static void s_modulate(void) { tex2d(GL_RGBA8); env(GL_MODULATE); }
static void s_replace(void) { tex2d(GL_RGBA8); env(GL_REPLACE); }
static void s_decal(void) { tex2d(GL_RGBA8); env(GL_DECAL); }
static void s_blend(void) { tex2d(GL_RGBA8); env(GL_BLEND); env_colour(); }
static void s_add(void) { tex2d(GL_RGBA8); env(GL_ADD); }
static void s_replace_rgb(void) { tex2d(GL_RGB8); env(GL_REPLACE); }
static void s_decal_rgb(void) { tex2d(GL_RGB8); env(GL_DECAL); }
static void s_blend_rgb(void) { tex2d(GL_RGB8); env(GL_BLEND); env_colour(); }
static void s_modulate_alpha(void) { tex2d(GL_ALPHA8); env(GL_MODULATE); }
static void s_replace_alpha(void) { tex2d(GL_ALPHA8); env(GL_REPLACE); }
static void s_add_lum(void) { tex2d(GL_LUMINANCE8); env(GL_ADD); }
static void s_replace_la(void) { tex2d(GL_LUMINANCE8_ALPHA8); env(GL_REPLACE); }
static void s_blend_int(void) { tex2d(GL_INTENSITY8); env(GL_BLEND); env_colour(); }
static void s_add_int(void) { tex2d(GL_INTENSITY8); env(GL_ADD); }

/* COMBINE: func, three sources and operands for RGB and alpha, scales. */
static void combine(GLenum frgb, const GLenum srgb[3], const GLenum orgb[3], GLenum fa, const GLenum sa[3],
                    const GLenum oa[3], int scale_rgb, int scale_a)
{
    env(GL_COMBINE);
    env_colour();
    glTexEnvi(GL_TEXTURE_ENV, GL_COMBINE_RGB, (GLint)frgb);
    glTexEnvi(GL_TEXTURE_ENV, GL_COMBINE_ALPHA, (GLint)fa);
    for (int i = 0; i < 3; i++) {
        glTexEnvi(GL_TEXTURE_ENV, GL_SRC0_RGB + (GLenum)i, (GLint)srgb[i]);
        glTexEnvi(GL_TEXTURE_ENV, GL_OPERAND0_RGB + (GLenum)i, (GLint)orgb[i]);
        glTexEnvi(GL_TEXTURE_ENV, GL_SRC0_ALPHA + (GLenum)i, (GLint)sa[i]);
        glTexEnvi(GL_TEXTURE_ENV, GL_OPERAND0_ALPHA + (GLenum)i, (GLint)oa[i]);
    }
    glTexEnvi(GL_TEXTURE_ENV, GL_RGB_SCALE, scale_rgb);
    glTexEnvi(GL_TEXTURE_ENV, GL_ALPHA_SCALE, scale_a);
}

#define S3(a, b, c) ((const GLenum[3]){a, b, c})
#define SC GL_SRC_COLOR
#define OMSC GL_ONE_MINUS_SRC_COLOR
#define SA GL_SRC_ALPHA
#define OMSA GL_ONE_MINUS_SRC_ALPHA

static void s_c_replace(void)
{
    tex2d(GL_RGBA8);
    combine(GL_REPLACE, S3(GL_TEXTURE, 0, 0), S3(SC, SC, SC), GL_REPLACE, S3(GL_PRIMARY_COLOR, 0, 0), S3(SA, SA, SA), 1, 1);
}
static void s_c_modulate(void)
{
    tex2d(GL_RGBA8);
    combine(GL_MODULATE, S3(GL_TEXTURE, GL_PRIMARY_COLOR, 0), S3(SC, OMSC, SC), GL_MODULATE,
            S3(GL_TEXTURE, GL_CONSTANT, 0), S3(SA, SA, SA), 1, 1);
}
static void s_c_add(void)
{
    tex2d(GL_RGBA8);
    combine(GL_ADD, S3(GL_TEXTURE, GL_CONSTANT, 0), S3(SC, SA, SC), GL_ADD, S3(GL_TEXTURE, GL_PRIMARY_COLOR, 0),
            S3(OMSA, SA, SA), 1, 1);
}
static void s_c_add_signed(void)
{
    tex2d(GL_RGBA8);
    combine(GL_ADD_SIGNED, S3(GL_PREVIOUS, GL_TEXTURE, 0), S3(SC, SC, SC), GL_ADD_SIGNED,
            S3(GL_PREVIOUS, GL_TEXTURE, 0), S3(SA, SA, SA), 2, 1);
}
static void s_c_interpolate(void)
{
    tex2d(GL_RGBA8);
    combine(GL_INTERPOLATE, S3(GL_TEXTURE, GL_CONSTANT, GL_PRIMARY_COLOR), S3(SC, SC, SA), GL_INTERPOLATE,
            S3(GL_CONSTANT, GL_TEXTURE, GL_PRIMARY_COLOR), S3(SA, SA, OMSA), 1, 2);
}
static void s_c_subtract(void)
{
    tex2d(GL_RGBA8);
    combine(GL_SUBTRACT, S3(GL_TEXTURE, GL_PRIMARY_COLOR, 0), S3(SC, OMSA, SC), GL_SUBTRACT,
            S3(GL_TEXTURE, GL_PRIMARY_COLOR, 0), S3(SA, OMSA, SA), 4, 4);
}
static void s_c_dot3_rgb(void)
{
    tex2d(GL_RGBA8);
    combine(GL_DOT3_RGB, S3(GL_TEXTURE, GL_PRIMARY_COLOR, 0), S3(SC, SC, SC), GL_MODULATE,
            S3(GL_TEXTURE, GL_PRIMARY_COLOR, 0), S3(SA, SA, SA), 1, 1);
}
static void s_c_dot3_rgba(void)
{
    tex2d(GL_RGBA8);
    combine(GL_DOT3_RGBA, S3(GL_TEXTURE, GL_CONSTANT, 0), S3(SC, SC, SC), GL_REPLACE, S3(GL_TEXTURE, 0, 0),
            S3(SA, SA, SA), 1, 1);
}
static void s_c_crossbar(void) /* unit 1 reads unit 0's texel (GL_TEXTURE0) */
{
    tex2d(GL_RGBA8);
    env(GL_MODULATE);
    glActiveTexture(GL_TEXTURE1);
    tex2d(GL_RGB8);
    combine(GL_INTERPOLATE, S3(GL_TEXTURE0, GL_TEXTURE, GL_PRIMARY_COLOR), S3(SC, SC, SA), GL_MODULATE,
            S3(GL_TEXTURE0, GL_PREVIOUS, 0), S3(SA, SA, SA), 1, 1);
    glActiveTexture(GL_TEXTURE0);
}

static void texgen_linear(GLenum mode)
{
    static const float ps[4] = {0.6f, 0.25f, 0.1f, 0.2f}, pt[4] = {-0.2f, 0.7f, 0.3f, -0.1f};
    GLenum plane = mode == GL_OBJECT_LINEAR ? GL_OBJECT_PLANE : GL_EYE_PLANE;
    tex2d(GL_RGBA8);
    env(GL_MODULATE);
    glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, (GLint)mode);
    glTexGeni(GL_T, GL_TEXTURE_GEN_MODE, (GLint)mode);
    glTexGenfv(GL_S, plane, ps);
    glTexGenfv(GL_T, plane, pt);
    glEnable(GL_TEXTURE_GEN_S);
    glEnable(GL_TEXTURE_GEN_T);
}
static void s_gen_object(void) { texgen_linear(GL_OBJECT_LINEAR); }
static void s_gen_eye(void) { texgen_linear(GL_EYE_LINEAR); }
static void s_tex1d(void) { tex1d(); env(GL_MODULATE); }
static void s_tex3d(void) { tex3d(); env(GL_MODULATE); }
static void s_texcube(void)
{
    texcube();
    env(GL_REPLACE);
    glMatrixMode(GL_TEXTURE); /* directions through the +Z face */
    glLoadIdentity();
    glTranslatef(0, 0, 1.2f);
    glScalef(0.5f, 0.5f, 0.2f);
    glMatrixMode(GL_MODELVIEW);
}
static void s_texrect(void) { texrect(); env(GL_MODULATE); }
static void s_multi2(void)
{
    tex2d(GL_RGBA8);
    env(GL_MODULATE);
    glActiveTexture(GL_TEXTURE1);
    tex2d(GL_LUMINANCE8);
    env(GL_ADD);
    glMatrixMode(GL_TEXTURE);
    glRotatef(30, 0, 0, 1);
    glMatrixMode(GL_MODELVIEW);
    glActiveTexture(GL_TEXTURE0);
}
static void s_multi4(void)
{
    static const GLenum envs[4] = {GL_MODULATE, GL_DECAL, GL_BLEND, GL_MODULATE};
    static const GLenum fmts[4] = {GL_RGB8, GL_RGBA8, GL_INTENSITY8, GL_LUMINANCE8_ALPHA8};
    for (int u = 0; u < 4; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        tex2d(fmts[u]);
        env(envs[u]);
        env_colour();
        if (u >= 2) { /* units 2, 3 get no coordinates: generated */
            texgen_linear(u == 2 ? GL_OBJECT_LINEAR : GL_EYE_LINEAR);
            env(envs[u]);
        }
    }
    glActiveTexture(GL_TEXTURE0);
}

static void fog(GLenum mode, GLenum src)
{
    static const float c[4] = {0.1f, 0.2f, 0.6f, 1};
    glEnable(GL_FOG);
    glFogi(GL_FOG_MODE, (GLint)mode);
    glFogi(GL_FOG_COORD_SRC, (GLint)src);
    glFogf(GL_FOG_START, 1.0f);
    glFogf(GL_FOG_END, 5.0f);
    glFogf(GL_FOG_DENSITY, 0.35f);
    glFogfv(GL_FOG_COLOR, c);
}
static void s_fog_linear_coord(void) { fog(GL_LINEAR, GL_FOG_COORD); }
static void s_fog_exp_coord(void) { fog(GL_EXP, GL_FOG_COORD); }
static void s_fog_exp2_coord(void) { fog(GL_EXP2, GL_FOG_COORD); }
static void s_fog_linear_depth(void) { fog(GL_LINEAR, GL_FRAGMENT_DEPTH); }
static void s_fog_exp_depth(void) { fog(GL_EXP, GL_FRAGMENT_DEPTH); }
static void s_fog_exp2_depth(void) { fog(GL_EXP2, GL_FRAGMENT_DEPTH); }
static void s_colour_sum(void)
{
    glEnable(GL_COLOR_SUM);
    tex2d(GL_RGBA8);
    env(GL_MODULATE);
}
static void s_clip1(void)
{
    static const double p[4] = {1, 0.5, 0, 0.2};
    glClipPlane(GL_CLIP_PLANE0, p);
    glEnable(GL_CLIP_PLANE0);
}
static void s_clip2(void)
{
    static const double p[4] = {-0.3, 1, 0.2, 0.5};
    s_clip1();
    glClipPlane(GL_CLIP_PLANE3, p);
    glEnable(GL_CLIP_PLANE3);
}
static void s_flat(void) { glShadeModel(GL_FLAT); }
static void s_flat_tex_sum(void)
{
    s_colour_sum();
    fog(GL_EXP, GL_FOG_COORD);
    glShadeModel(GL_FLAT);
}
static void s_everything(void) /* lighting, two units, fog, clip plane together */
{
    s_separate_spec();
    glActiveTexture(GL_TEXTURE1);
    tex2d(GL_LUMINANCE8);
    env(GL_ADD);
    glActiveTexture(GL_TEXTURE0);
    fog(GL_EXP2, GL_FRAGMENT_DEPTH);
    s_clip1();
}

typedef struct ocase {
    const char *name;
    void (*setup)(void); /* the state (of the native drawing, and of ours unless ours is set) */
    unsigned attrs;
    int back;   /* view the back faces */
    int strips; /* 1: also drawn as strips */
    void (*ours)(void); /* a state the spec makes equivalent, for a driver wrong on setup's */
    int scale;  /* the combiner's scale (0: 1): it magnifies differences before it, such as
                   llvmpipe's 8-bit texture filter weights stepping at another coordinate ulp */
} ocase;

#define BASE (A_COL | A_NRM)
#define TEX (A_COL | A_NRM | A_TEX0)

static const ocase ocases[] = {
    {"light_dir", s_light_dir, BASE, 0, 1, NULL, 0},
    {"two_lights", s_two_lights, BASE, 0, 0, NULL, 0},
    {"eight_lights", s_eight_lights, BASE, 0, 0, NULL, 0},
    {"cm_amb_diff", s_cm_amb_diff, BASE, 0, 1, NULL, 0},
    {"cm_ambient", s_cm_ambient, BASE, 0, 0, NULL, 0},
    {"cm_diffuse_front", s_cm_diffuse, BASE, 0, 0, NULL, 0},
    {"cm_specular", s_cm_specular, BASE, 0, 0, NULL, 0},
    {"cm_emission", s_cm_emission, BASE, 0, 0, NULL, 0},
    {"cm_back_only", s_cm_back_only, BASE, 0, 0, NULL, 0},
    {"two_side_front", s_two_side_front, BASE, 0, 0, NULL, 0},
    {"two_side_back", s_two_side_front, BASE, 1, 0, NULL, 0},
    /* Mesa 22 lights back faces wrongly with glColorMaterial(GL_BACK) (a red colour gives
     * white): the native picture is drawn with GL_FRONT_AND_BACK, the same on back faces */
    {"two_side_back_cm", s_cm_both_two_side, BASE, 1, 1, s_cm_back_only, 0},
    {"two_side_back_cm_both", s_cm_both_two_side, BASE, 1, 0, NULL, 0},
    {"separate_spec", s_separate_spec, TEX, 0, 0, NULL, 0},
    {"normalize", s_normalize, BASE, 0, 0, NULL, 0},
    {"rescale_normal", s_rescale, BASE, 0, 0, NULL, 0},
    {"material_per_vertex", s_material_pv, BASE | A_MAT, 0, 1, NULL, 0},
    {"flat_spot_local", s_flat_spot, BASE, 0, 1, NULL, 0},
    {"flat_positional_cm", s_flat_positional, BASE, 0, 1, NULL, 0},
    {"modulate", s_modulate, TEX, 0, 0, NULL, 0},
    {"replace", s_replace, TEX, 0, 0, NULL, 0},
    {"decal", s_decal, TEX, 0, 0, NULL, 0},
    {"blend", s_blend, TEX, 0, 0, NULL, 0},
    {"add", s_add, TEX, 0, 0, NULL, 0},
    {"replace_rgb", s_replace_rgb, TEX, 0, 0, NULL, 0},
    {"decal_rgb", s_decal_rgb, TEX, 0, 0, NULL, 0},
    {"blend_rgb", s_blend_rgb, TEX, 0, 0, NULL, 0},
    {"modulate_alpha", s_modulate_alpha, TEX, 0, 0, NULL, 0},
    {"replace_alpha", s_replace_alpha, TEX, 0, 0, NULL, 0},
    {"add_luminance", s_add_lum, TEX, 0, 0, NULL, 0},
    {"replace_lum_alpha", s_replace_la, TEX, 0, 0, NULL, 0},
    {"blend_intensity", s_blend_int, TEX, 0, 0, NULL, 0},
    {"add_intensity", s_add_int, TEX, 0, 0, NULL, 0},
    {"combine_replace", s_c_replace, TEX, 0, 0, NULL, 0},
    {"combine_modulate", s_c_modulate, TEX, 0, 0, NULL, 0},
    {"combine_add", s_c_add, TEX, 0, 0, NULL, 0},
    {"combine_add_signed_x2", s_c_add_signed, TEX, 0, 0, NULL, 2},
    {"combine_interpolate", s_c_interpolate, TEX, 0, 0, NULL, 0},
    {"combine_subtract_x4", s_c_subtract, TEX, 0, 0, NULL, 4},
    {"combine_dot3_rgb", s_c_dot3_rgb, TEX, 0, 0, NULL, 0},
    {"combine_dot3_rgba", s_c_dot3_rgba, TEX, 0, 0, NULL, 0},
    {"combine_crossbar", s_c_crossbar, TEX | A_TEX1, 0, 0, NULL, 0},
    {"texgen_object", s_gen_object, BASE, 0, 0, NULL, 0},
    {"texgen_eye", s_gen_eye, BASE, 0, 1, NULL, 0},
    {"target_1d", s_tex1d, TEX, 0, 0, NULL, 0},
    {"target_3d", s_tex3d, TEX, 0, 0, NULL, 0},
    {"target_cube", s_texcube, TEX, 0, 0, NULL, 0},
    {"target_rect", s_texrect, TEX, 0, 0, NULL, 0},
    {"multitex_2", s_multi2, TEX | A_TEX1, 0, 1, NULL, 0},
    {"multitex_4", s_multi4, TEX | A_TEX1, 0, 0, NULL, 0},
    {"fog_linear_coord", s_fog_linear_coord, BASE | A_FOG, 0, 0, NULL, 0},
    {"fog_exp_coord", s_fog_exp_coord, BASE | A_FOG, 0, 0, NULL, 0},
    {"fog_exp2_coord", s_fog_exp2_coord, BASE | A_FOG, 0, 0, NULL, 0},
    {"fog_linear_depth", s_fog_linear_depth, BASE, 0, 0, NULL, 0},
    {"fog_exp_depth", s_fog_exp_depth, BASE, 0, 0, NULL, 0},
    {"fog_exp2_depth", s_fog_exp2_depth, BASE, 0, 1, NULL, 0},
    {"colour_sum", s_colour_sum, TEX | A_COL2, 0, 0, NULL, 0},
    {"clip_plane", s_clip1, BASE, 0, 0, NULL, 0},
    {"clip_planes_2", s_clip2, BASE, 0, 1, NULL, 0},
    {"flat", s_flat, BASE, 0, 1, NULL, 0},
    {"flat_tex_sum_fog", s_flat_tex_sum, TEX | A_COL2 | A_FOG, 0, 0, NULL, 0},
    {"everything", s_everything, TEX | A_TEX1, 0, 1, NULL, 0},
};

static void reset_texture_matrices(void)
{
    glMatrixMode(GL_TEXTURE);
    for (int u = 3; u >= 0; u--) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        glLoadIdentity();
    }
    glMatrixMode(GL_MODELVIEW);
}

/* The defaults every case starts from (glPopAttrib does not restore everything on every driver:
 * colour sum stays on after it here). */
static void clean_state(void)
{
    static const GLenum off[] = {GL_LIGHTING, GL_FOG, GL_COLOR_SUM, GL_COLOR_MATERIAL, GL_NORMALIZE, GL_RESCALE_NORMAL};
    for (size_t i = 0; i < sizeof off / sizeof off[0]; i++)
        glDisable(off[i]);
    static const GLenum targets[] = {GL_TEXTURE_1D, GL_TEXTURE_2D, GL_TEXTURE_3D, GL_TEXTURE_CUBE_MAP, GL_TEXTURE_RECTANGLE,
                                     GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T, GL_TEXTURE_GEN_R, GL_TEXTURE_GEN_Q};
    for (int u = 3; u >= 0; u--) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        for (size_t i = 0; i < sizeof targets / sizeof targets[0]; i++)
            glDisable(targets[i]);
    }
    for (int i = 0; i < 8; i++)
        glDisable(GL_CLIP_PLANE0 + (GLenum)i);
    glShadeModel(GL_SMOOTH);
}

/* FFP_ONLY=substring runs only the matching oracle cases (for debugging). */
static int selected(const char *name)
{
    const char *only = getenv("FFP_ONLY");
    return !only || strstr(name, only);
}

static void camera(int back)
{
    sc_camera(back ? -130.0f : -50.0f, 20);
}

/* Draw the case natively then through the shader path; returns the worst difference. */
static void run_oracle(th_ctx *t, const ocase *c, int strips)
{
    grid *g = malloc(sizeof *g);
    make_grid(g, strips);
    glClearColor(0, 0, 0, 0.5f);
    glPushAttrib(GL_ALL_ATTRIB_BITS);
    clean_state();
    camera(c->back);
    c->setup();
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw_grid(g, 1, c->attrs);
    unsigned char *native = th_snapshot(t);
    if (c->ours) {
        glPopAttrib();
        glPushAttrib(GL_ALL_ATTRIB_BITS);
        clean_state();
        camera(c->back);
        c->ours();
    }

    qgl_gl_set_method(t->qgl, QGL_METHOD_MVC);
    qgl_gl_reset_stats(t->qgl);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw_grid(g, 0, c->attrs);
    unsigned char *ours = th_snapshot(t);
    qgl_gl_stats_t st;
    qgl_gl_stats(t->qgl, &st);
    total.quads += st.quads, total.mvc += st.mvc, total.fallback += st.fallback, total.split += st.split;
    glPopAttrib();
    reset_texture_matrices();

    int tol = TOL * (c->scale ? c->scale : 1);
    int over, worst = sc_diff(t, native, ours, tol, &over), lit_px = 0;
    for (int i = 0; i < t->w * t->h; i++)
        lit_px += native[4 * i] | native[4 * i + 1] | native[4 * i + 2] ? 1 : 0;
    char name[80];
    snprintf(name, sizeof name, "ffp_%s%s", c->name, strips ? "_strip" : "");
    printf("%-36s worst %3d/255, %5d px over %d (%5d drawn); mvc %llu/%llu\n", name, worst, over, tol, lit_px,
           (unsigned long long)st.mvc, (unsigned long long)st.quads);
    if (over) {
        th_write(t, native, "ffp_native");
        th_write(t, ours, name);
    }
    th_check(over == 0, "%s: %d pixels differ from the native split", name, over);
    th_check(st.quads == N * N && st.mvc == st.quads, "%s: not every quad took the shader path", name);
    th_check(lit_px > t->w * t->h / 16, "%s: the scene is (nearly) empty", name);
    free(native);
    free(ours);
    free(g);
}

/* ---- reference cases: per-corner results read back from the driver ----------------------------- */

/* Clip corners and the driver's per-corner colour and unit-0 texture coordinates (feedback:
 * each corner drawn as a point with the same attributes and state). */
typedef struct corners {
    double clip[4][4];
    float col[4][4], tex[4][4];
} corners;

static int feedback(const vtx q[4], unsigned a, corners *out)
{
    static GLfloat buf[4 * 16];
    float p[4][3];
    for (int c = 0; c < 4; c++)
        memcpy(p[c], q[c].pos, sizeof p[c]);
    th_clip_of(p, out->clip);
    glFeedbackBuffer(4 * 16, GL_4D_COLOR_TEXTURE, buf);
    glRenderMode(GL_FEEDBACK);
    for (int c = 0; c < 4; c++)
        draw_range(q, c, 1, GL_POINTS, 1, a);
    int n = glRenderMode(GL_RENDER);
    if (n != 4 * 13)
        return 0;
    for (int c = 0; c < 4; c++) {
        const GLfloat *f = buf + 13 * c;
        if (f[0] != GL_POINT_TOKEN)
            return 0;
        memcpy(out->col[c], f + 5, 4 * sizeof(float));
        memcpy(out->tex[c], f + 9, 4 * sizeof(float));
    }
    return 1;
}

/* Interior pixels (3 x 3 neighbourhood inside) compared with f(sum lambda'_i a_i); the worst
 * channel difference in /255, or -1 when fewer than min_px pixels were compared. */
typedef void (*shade_fn)(const float a[4], float out[3]);

static int compare_reference(const th_ctx *t, const unsigned char *img, const double clip[4][4], const float attr[4][4],
                             shade_fn shade, int *compared)
{
    int worst = 0, n = 0;
    for (int y = 1; y < t->h - 1; y++)
        for (int x = 1; x < t->w - 1; x++) {
            int inside = 1;
            float ref[4] = {0};
            for (int dy = -1; dy <= 1 && inside; dy++)
                for (int dx = -1; dx <= 1 && inside; dx++)
                    inside = th_ref_color(t, clip, attr, x + dx, y + dy, ref) == QGL_INSIDE;
            if (!inside)
                continue;
            th_ref_color(t, clip, attr, x, y, ref);
            float rgb[3];
            shade(ref, rgb);
            const unsigned char *px = img + 4 * (y * t->w + x);
            for (int k = 0; k < 3; k++) {
                int d = abs((int)px[k] - (int)lrintf(255 * rgb[k]));
                worst = d > worst ? d : worst;
            }
            n++;
        }
    *compared = n;
    return worst;
}

static void shade_colour(const float a[4], float out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = a[k];
}

/* The 1D ramp texture (2 texels, black and white, clamped) is linear in s on [0.25, 0.75]. */
static void shade_ramp(const float a[4], float out[3])
{
    float s = a[0] / a[3], v = (s - 0.25f) * 2;
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    out[0] = out[1] = out[2] = v;
}

static void ramp_texture(void)
{
    static const unsigned char ramp[2] = {0, 255};
    GLuint id;
    glGenTextures(1, &id);
    glBindTexture(GL_TEXTURE_1D, id);
    glTexImage1D(GL_TEXTURE_1D, 0, GL_LUMINANCE8, 2, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, ramp);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glEnable(GL_TEXTURE_1D);
    env(GL_REPLACE);
}

/* A non-planar quad with differing normals and colours, seen in perspective. */
static void reference_quad(vtx q[4])
{
    static const float p[4][3] = {{-0.9f, -0.8f, 0.2f}, {0.85f, -0.9f, -0.1f}, {0.8f, 0.85f, 0.35f}, {-0.8f, 0.9f, -0.2f}};
    static const float n[4][3] = {{-0.3f, -0.2f, 1}, {0.4f, -0.3f, 0.9f}, {0.2f, 0.5f, 1}, {-0.5f, 0.3f, 0.8f}};
    static const float c[4][4] = {{0.9f, 0.2f, 0.2f, 1}, {0.2f, 0.9f, 0.2f, 1}, {0.2f, 0.2f, 0.9f, 1}, {0.9f, 0.9f, 0.3f, 1}};
    memset(q, 0, 4 * sizeof *q);
    for (int i = 0; i < 4; i++) {
        memcpy(q[i].pos, p[i], sizeof p[i]);
        float l = sqrtf(n[i][0] * n[i][0] + n[i][1] * n[i][1] + n[i][2] * n[i][2]);
        for (int k = 0; k < 3; k++)
            q[i].nrm[k] = n[i][k] / l;
        memcpy(q[i].col, c[i], sizeof c[i]);
    }
}

static void r_spot_local(void)
{
    colour_material(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
    light(1, 0.5f, 0.4f, -1.0f, 1);
    glLightf(GL_LIGHT1, GL_SPOT_CUTOFF, 60);
    glLightf(GL_LIGHT1, GL_SPOT_EXPONENT, 2);
    static const float dir[3] = {-0.4f, -0.3f, -1};
    glLightfv(GL_LIGHT1, GL_SPOT_DIRECTION, dir);
    glLightf(GL_LIGHT1, GL_QUADRATIC_ATTENUATION, 0.2f);
    glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, 1);
}
static void r_positional(void)
{
    lit();
    light(2, -0.6f, 0.2f, -1.5f, 1);
    glLightf(GL_LIGHT2, GL_LINEAR_ATTENUATION, 0.4f);
    glMaterialf(GL_FRONT, GL_SHININESS, 30);
}

/* Texgen mode for s, t, r with the texture matrix sending coordinate k to s' in [0.25, 0.75]. */
static void texgen_ref(GLenum mode, int k)
{
    ramp_texture();
    for (int c = 0; c < (mode == GL_SPHERE_MAP ? 2 : 3); c++) {
        glTexGeni(GL_S + (GLenum)c, GL_TEXTURE_GEN_MODE, (GLint)mode);
        glEnable(GL_TEXTURE_GEN_S + (GLenum)c);
    }
    float m[16] = {0};
    m[4 * k] = 0.2f, m[12] = 0.5f, m[15] = 1; /* s' = 0.2 coord_k + 0.5, q' = q */
    glMatrixMode(GL_TEXTURE);
    glLoadMatrixf(m);
    glMatrixMode(GL_MODELVIEW);
}

static int ref_k;
static GLenum ref_mode;
static void r_texgen(void) { texgen_ref(ref_mode, ref_k); }

static void run_reference(th_ctx *t, const char *name, void (*setup)(void), shade_fn shade, int use_tex)
{
    vtx q[4];
    reference_quad(q);
    glPushAttrib(GL_ALL_ATTRIB_BITS);
    clean_state();
    camera(0);
    setup();
    corners cr;
    int fb = feedback(q, A_COL | A_NRM, &cr);
    qgl_gl_set_method(t->qgl, QGL_METHOD_MVC);
    qgl_gl_reset_stats(t->qgl);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw_range(q, 0, 4, GL_QUADS, 0, A_COL | A_NRM);
    unsigned char *img = th_snapshot(t);
    qgl_gl_stats_t st;
    qgl_gl_stats(t->qgl, &st);
    total.quads += st.quads, total.mvc += st.mvc, total.fallback += st.fallback, total.split += st.split;
    glPopAttrib();
    reset_texture_matrices();
    int n = 0, worst = fb ? compare_reference(t, img, cr.clip, use_tex ? cr.tex : cr.col, shade, &n) : 999;
    printf("%-36s worst %3d/255 over %5d interior px (reference); mvc %llu/%llu\n", name, worst, n,
           (unsigned long long)st.mvc, (unsigned long long)st.quads);
    th_check(fb, "%s: feedback did not return the corners", name);
    th_check(worst <= REF_TOL && n > 2000, "%s: differs from the per-pixel reference", name);
    th_check(st.quads == 1 && st.mvc == 1, "%s: not on the shader path", name);
    if (worst > REF_TOL)
        th_write(t, img, name);
    free(img);
}

/* Two-sided lighting on a bow-tie: each lobe shows the material of the side it shows. */
static void run_bowtie(th_ctx *t)
{
    static const float p[4][3] = {{-0.8f, -0.7f, 0}, {0.8f, 0.7f, 0}, {0.8f, -0.7f, 0}, {-0.8f, 0.7f, 0}};
    static const float red[4] = {1, 0, 0, 1}, blue[4] = {0, 0, 1, 1}, black[4] = {0, 0, 0, 1};
    vtx q[4];
    memset(q, 0, sizeof q);
    for (int i = 0; i < 4; i++) {
        memcpy(q[i].pos, p[i], sizeof p[i]);
        q[i].nrm[2] = 1;
    }
    glPushAttrib(GL_ALL_ATTRIB_BITS);
    clean_state();
    sc_camera(-20, 0);
    glEnable(GL_LIGHTING);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, 1);
    glLightModelfv(GL_LIGHT_MODEL_AMBIENT, black);
    glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, black);
    glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, black);
    glMaterialfv(GL_FRONT, GL_EMISSION, red);
    glMaterialfv(GL_BACK, GL_EMISSION, blue);
    double clip[4][4], v[4][2];
    th_clip_of(p, clip);
    for (int c = 0; c < 4; c++)
        v[c][0] = clip[c][0] / clip[c][3], v[c][1] = clip[c][1] / clip[c][3];
    qgl_gl_set_method(t->qgl, QGL_METHOD_MVC);
    qgl_gl_reset_stats(t->qgl);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw_range(q, 0, 4, GL_QUADS, 0, A_NRM);
    unsigned char *img = th_snapshot(t);
    qgl_gl_stats_t st;
    qgl_gl_stats(t->qgl, &st);
    total.quads += st.quads, total.mvc += st.mvc, total.fallback += st.fallback, total.split += st.split;
    glPopAttrib();
    int counted[2] = {0, 0}, wrong = 0;
    for (int y = 1; y < t->h - 1; y++)
        for (int x = 1; x < t->w - 1; x++) {
            int side = 2, agree = 1;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int s = qgl_inside(v, (x + dx + 0.5) / t->w * 2 - 1, (y + dy + 0.5) / t->h * 2 - 1);
                    agree &= s != 0 && (side == 2 || s == side);
                    side = s;
                }
            if (!agree)
                continue;
            const unsigned char *px = img + 4 * (y * t->w + x);
            int front = side > 0;
            counted[front]++;
            wrong += front ? !(px[0] == 255 && px[2] == 0) : !(px[0] == 0 && px[2] == 255);
        }
    printf("%-36s front %d px, back %d px, %d wrong; mvc %llu/%llu\n", "ffp_two_side_bowtie", counted[1], counted[0],
           wrong, (unsigned long long)st.mvc, (unsigned long long)st.quads);
    th_check(counted[0] > 500 && counted[1] > 500 && wrong == 0, "two-sided bow-tie: facing is not per lobe");
    th_check(st.mvc == 1, "two-sided bow-tie: not on the shader path");
    if (wrong)
        th_write(t, img, "ffp_two_side_bowtie");
    free(img);
}

/* A clip plane across a non-planar quad cuts where the interpolated eye position crosses it. */
static void run_clip_nonplanar(th_ctx *t)
{
    static const double plane[4] = {1, 0.6, 0, 0.3}; /* eye coordinates: set with identity */
    vtx q[4];
    reference_quad(q);
    for (int i = 0; i < 4; i++)
        q[i].col[0] = q[i].col[1] = q[i].col[2] = 1;
    glPushAttrib(GL_ALL_ATTRIB_BITS);
    clean_state();
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glClipPlane(GL_CLIP_PLANE1, plane);
    glEnable(GL_CLIP_PLANE1);
    camera(0);
    double mv[16];
    glGetDoublev(GL_MODELVIEW_MATRIX, mv);
    float p[4][3];
    double clip[4][4], eye[4][4];
    for (int c = 0; c < 4; c++) {
        memcpy(p[c], q[c].pos, sizeof p[c]);
        for (int r = 0; r < 4; r++)
            eye[c][r] = mv[r] * p[c][0] + mv[4 + r] * p[c][1] + mv[8 + r] * p[c][2] + mv[12 + r];
    }
    th_clip_of(p, clip);
    qgl_gl_set_method(t->qgl, QGL_METHOD_MVC);
    qgl_gl_reset_stats(t->qgl);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw_range(q, 0, 4, GL_QUADS, 0, A_COL);
    unsigned char *img = th_snapshot(t);
    qgl_gl_stats_t st;
    qgl_gl_stats(t->qgl, &st);
    total.quads += st.quads, total.mvc += st.mvc, total.fallback += st.fallback, total.split += st.split;
    glPopAttrib();
    int kept = 0, cut = 0, wrong = 0;
    for (int y = 1; y < t->h - 1; y++)
        for (int x = 1; x < t->w - 1; x++) {
            double lam[4], e[4] = {0};
            if (th_weights(t, clip, x, y, lam, NULL) != QGL_INSIDE)
                continue;
            for (int c = 0; c < 4; c++)
                for (int r = 0; r < 4; r++)
                    e[r] += lam[c] * eye[c][r];
            double d = plane[0] * e[0] + plane[1] * e[1] + plane[2] * e[2] + plane[3] * e[3];
            if (fabs(d) < 0.02) /* about a pixel of the eye-space extent */
                continue;
            int on = img[4 * (y * t->w + x)] > 128;
            kept += d > 0, cut += d < 0;
            wrong += on != (d > 0);
        }
    printf("%-36s kept %d px, cut %d px, %d wrong; mvc %llu/%llu\n", "ffp_clip_nonplanar", kept, cut, wrong,
           (unsigned long long)st.mvc, (unsigned long long)st.quads);
    th_check(kept > 1000 && cut > 1000 && wrong == 0, "non-planar clip: wrong side of the plane");
    th_check(st.mvc == 1, "non-planar clip: not on the shader path");
    if (wrong)
        th_write(t, img, "ffp_clip_nonplanar");
    free(img);
}

/* A state whose programs would pass more varyings than the budget (two sides of primary and
 * secondary colour, four units, per-fragment clipping, depth): the CPU fallback draws it, and
 * the counters say so. */
static void run_over_budget(th_ctx *t)
{
    vtx q[4];
    reference_quad(q);
    glPushAttrib(GL_ALL_ATTRIB_BITS);
    clean_state();
    camera(0);
    s_separate_spec();
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, 1);
    for (int u = 1; u < 4; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        texgen_linear(GL_OBJECT_LINEAR);
    }
    glActiveTexture(GL_TEXTURE0);
    s_clip1();
    qgl_gl_set_method(t->qgl, QGL_METHOD_MVC);
    qgl_gl_reset_stats(t->qgl);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw_range(q, 0, 4, GL_QUADS, 0, A_COL | A_NRM);
    glFinish();
    qgl_gl_stats_t st;
    qgl_gl_stats(t->qgl, &st);
    glPopAttrib();
    printf("%-36s mvc %llu subdiv %llu of %llu\n", "ffp_over_budget", (unsigned long long)st.mvc,
           (unsigned long long)st.fallback, (unsigned long long)st.quads);
    th_check(st.quads == 1 && st.fallback == 1, "over the varying budget: expected the counted CPU fallback");
}

int main(void)
{
    th_ctx t;
    int rc = th_init(&t, W, H, NULL);
    if (rc)
        return rc;
    if (qgl_gl_shader_level(t.qgl) < 150) {
        printf("no geometry shader path here: skipped\n");
        th_free(&t);
        return 77;
    }
    glEnable(GL_DEPTH_TEST);
    for (size_t i = 0; i < sizeof ocases / sizeof ocases[0]; i++) {
        if (!selected(ocases[i].name))
            continue;
        run_oracle(&t, &ocases[i], 0);
        if (ocases[i].strips)
            run_oracle(&t, &ocases[i], 1);
    }
    run_reference(&t, "ffp_ref_spot_local_atten", r_spot_local, shade_colour, 0);
    run_reference(&t, "ffp_ref_positional_specular", r_positional, shade_colour, 0);
    static const struct { const char *name; GLenum mode; int ncoords; } gens[] = {
        {"sphere", GL_SPHERE_MAP, 2}, {"reflection", GL_REFLECTION_MAP, 3}, {"normal", GL_NORMAL_MAP, 3}};
    for (int g = 0; g < 3; g++)
        for (int k = 0; k < gens[g].ncoords; k++) {
            char name[64];
            snprintf(name, sizeof name, "ffp_ref_texgen_%s_%c", gens[g].name, "str"[k]);
            ref_mode = gens[g].mode, ref_k = k;
            run_reference(&t, name, r_texgen, shade_ramp, 1);
        }
    run_bowtie(&t);
    run_clip_nonplanar(&t);
    run_over_budget(&t); /* not in the share below: it is meant to fall back */
    double share = total.quads ? 100.0 * (double)total.fallback / (double)total.quads : 0;
    printf("all: %llu quads, %llu shader path, %llu split, %llu CPU fallback (%.2f%%)\n",
           (unsigned long long)total.quads, (unsigned long long)total.mvc, (unsigned long long)total.split,
           (unsigned long long)total.fallback, share);
    th_check(share < 1.0, "%.2f%% of quads took the CPU fallback", share);
    th_free(&t);
    return th_failures ? 1 : 0;
}
