/* test_fidelity.c: scenes from real programs whose pictures a replay (QUADGL_METHOD=replay) must
 * reproduce exactly and the split (QUADGL_METHOD=split) within 2 levels (see pt.h).
 *
 * Each scene is the smallest form of a program's drawing that showed a difference: the quads
 * are non-affine (no plane fits their corners' colours), so a quad split on the other diagonal,
 * or a corner lit with another corner's material, shows. */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include "pt.h"

/* A frame lit by light 0 at pos (directional with w = 0), a display list 1 being compiled. */
static void lit_list(const float pos[4])
{
    pt_begin_frame();
    glEnable(GL_LIGHTING);
    glEnable(GL_LIGHT0);
    glLightfv(GL_LIGHT0, GL_POSITION, pos);
    glNewList(1, GL_COMPILE);
}

/* Ends the list, draws it, and asks for the driver's picture of its three quads. */
static void call_list(pt_run *r)
{
    glEndList();
    glCallList(1);
    glDisable(GL_LIGHTING);
    r->native_equal = 1;
    r->min_quads = 3;
}

/* squirtorus: lit GL_QUADS in a display list, a glColor and a glMaterialfv(GL_FRONT_AND_BACK,
 * GL_AMBIENT_AND_DIFFUSE) before every vertex. The driver's list lights each vertex with its
 * own material and splits each quad 0-1-3, 1-2-3. */
static void scene_list_materials(pt_run *r)
{
    static const float dir[4] = {0.2f, 0.3f, 1, 0};
    lit_list(dir);
    glBegin(GL_QUADS);
    for (int q = 0; q < 3; q++)
        for (int i = 0; i < 4; i++) {
            glColor4fv(C[q][(i + 1) % 4]);
            glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, C[q][i]);
            glNormal3f(0.1f * (float)i, 0.2f * (float)q - 0.2f, 1);
            glVertex2fv(Q[q][i]);
        }
    glEnd();
    call_list(r);
}

/* spheremonics: the same with the front material only, under two-sided lighting and a light
 * at a point, one primitive for the whole surface. */
static void scene_list_front(pt_run *r)
{
    static const float pos[4] = {0.5f, 0.5f, 2, 1};
    glEnable(GL_NORMALIZE);
    glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
    lit_list(pos);
    glBegin(GL_QUADS);
    for (int q = 0; q < 3; q++)
        for (int i = 0; i < 4; i++) {
            glNormal3f(0.3f * (float)i - 0.4f, 0.1f * (float)q, q == 1 ? -1.0f : 1.0f);
            glMaterialfv(GL_FRONT, GL_AMBIENT_AND_DIFFUSE, C[q][i]);
            glColor3fv(C[q][3 - i]);
            glVertex2fv(Q[q][i]);
        }
    glEnd();
    call_list(r);
}

/* gibson: a lit list whose first quad gives a colour and a material inside glBegin/glEnd and whose
 * later strips give neither (they are set between the primitives, with the normal): the
 * driver's list lights those strips with the material as state; a replay through its
 * immediate mode kept the material per vertex and rounded differently. */
static void scene_list_state_attribs(pt_run *r)
{
    static const float pos[4] = {0.3f, 0.6f, 2, 1}, c0[4] = {0.02f, 0.02f, 0.3f, 1}, c1[4] = {0.54f, 0.17f, 0.89f, 1};
    lit_list(pos);
    glBegin(GL_QUADS);
    glColor4fv(c0);
    glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, c0);
    for (int i = 0; i < 4; i++)
        glVertex2fv(Q[0][i]);
    glEnd();
    glColor4fv(c1);
    glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, c1);
    for (int q = 1; q < 3; q++) {
        glPushMatrix();
        glTranslatef(0.01f * (float)q, 0, 0);
        glNormal3f(0.1f * (float)q, 0.2f, 1);
        glBegin(GL_QUAD_STRIP);
        for (int i = 0; i < 4; i++)
            glVertex2fv(Q[q][i ^ (i >> 1)]);
        glEnd();
        glPopMatrix();
    }
    call_list(r);
}

/* A list of GL_QUADS primitives in a row with the normal and the colour set between them, never
 * inside (a cube drawn face by face): the primitives share one run of quads, and each must
 * still be lit with its own values. */
static void scene_list_between(pt_run *r)
{
    static const float dir[4] = {0.3f, 0.5f, 1, 0};
    glEnable(GL_COLOR_MATERIAL);
    lit_list(dir);
    for (int q = 0; q < 3; q++) {
        glNormal3f(0.4f * (float)(q - 1), 0.3f * (float)q, 1);
        glColor4f(0.3f + 0.3f * (float)q, 0.8f - 0.25f * (float)q, 0.5f, 1);
        glBegin(GL_QUADS);
        for (int i = 0; i < 4; i++)
            glVertex2fv(Q[q][i]);
        glEnd();
    }
    call_list(r);
    glDisable(GL_COLOR_MATERIAL);
}

static const pt_scene scenes[] = {
    {"list_between", scene_list_between},
    {"list_state_attribs", scene_list_state_attribs},
    {"list_materials", scene_list_materials},
    {"list_front", scene_list_front},
};

int main(int argc, char **argv)
{
    return pt_main(argc, argv, scenes, (int)(sizeof scenes / sizeof scenes[0]));
}
