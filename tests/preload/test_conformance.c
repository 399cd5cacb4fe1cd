/* test_conformance.c: the gaps piglit found between the preload library and the driver, one
 * scene each (see pt.h; every scene must give the native pixels and errors).
 *
 * Each scene replays, in small, what a piglit test does that once went wrong preloaded: edge
 * flags in polygon mode line (gl-1.0-edgeflag-quads), display lists called inside glBegin/glEnd
 * and lists that begin or end a primitive, with the errors the driver raises for what a list
 * holds that is illegal there (gl-1.0-dlist-beginend), calls legal inside glBegin/glEnd that
 * the capture does not represent (gl-1.0-beginend-coverage), colour sum left on after the
 * library's first draw (draw-batch), generic attributes given inside
 * glBegin/glEnd and in lists with a GLSL program bound (attribs), and quads drawn with an ARB
 * vertex and fragment program enabled (pos-array), which must reach the driver as they are
 * and never the CPU fallback's fixed function. Values recorded: glGetError after each step,
 * and the pixel at the centre after each part, so that a part drawing nothing is seen even
 * when a later one covers it. */
#include <stdio.h>
#include <string.h>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

#include "pt.h"

static const float green[4] = {0, 1, 0, 1}, red[4] = {1, 0, 0, 1};

/* A parallelogram with affine colours (c3 = c0 + c2 - c1): every method draws the driver's
 * pixels. */
static const float P[4][2] = {{-0.8f, -0.7f}, {0.5f, -0.8f}, {0.8f, 0.6f}, {-0.5f, 0.7f}};
static const float PC[4][4] = {{0.2f, 0.3f, 0.4f, 1}, {0.6f, 0.3f, 0.2f, 1}, {0.7f, 0.6f, 0.3f, 1}, {0.3f, 0.6f, 0.5f, 1}};

/* A non-affine quad (no plane fits its corner colours): smoothing it would show. */
static const float QV[4][2] = {{-0.8f, -0.8f}, {0.7f, -0.9f}, {0.8f, 0.8f}, {-0.7f, 0.6f}};
static const float QC[4][4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};

static void value_error(pt_run *r)
{
    pt_value(r, glGetError());
}

/* The centre pixel, packed, then the window cleared. */
static void value_centre(pt_run *r)
{
    unsigned char p[4];
    glReadPixels(PT_W / 2, PT_H / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, p);
    pt_value(r, (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3]);
    glClear(GL_COLOR_BUFFER_BIT);
}

static void full_quad_vertices(void)
{
    glVertex2f(-1, -1);
    glVertex2f(1, -1);
    glVertex2f(1, 1);
    glVertex2f(-1, 1);
}

static GLuint list_of_vertices(const float *colour)
{
    GLuint l = glGenLists(1);
    glNewList(l, GL_COMPILE);
    glColor4fv(colour);
    full_quad_vertices();
    glEndList();
    return l;
}

/* ---- edge flags in polygon mode line ---------------------------------------------------------- */

/* Quads with some edges flagged off, from glEdgeFlag calls, an edge-flag array and a list. */
static void scene_edgeflag_line(pt_run *r)
{
    static const float v[8][2] = {{-0.9f, -0.9f}, {-0.1f, -0.9f}, {-0.1f, -0.1f}, {-0.9f, -0.1f},
                                  {0.1f, 0.1f},   {0.9f, 0.1f},   {0.9f, 0.9f},   {0.1f, 0.9f}};
    static const GLboolean flags[8] = {GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE, GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE};
    GLuint l = glGenLists(1);
    pt_begin_frame();
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glColor4fv(green);
    glBegin(GL_QUADS);
    for (int i = 0; i < 8; i++) {
        glEdgeFlag(flags[i]);
        glVertex2fv(v[i]);
    }
    glEnd();
    glEdgeFlag(GL_TRUE);
    value_error(r);
    glColor4fv(red);
    glPushMatrix();
    glTranslatef(0.05f, -0.95f, 0);
    glVertexPointer(2, GL_FLOAT, 0, v);
    glEdgeFlagPointer(0, flags);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_EDGE_FLAG_ARRAY);
    glDrawArrays(GL_QUADS, 0, 8);
    glDisableClientState(GL_EDGE_FLAG_ARRAY);
    glDisableClientState(GL_VERTEX_ARRAY);
    glPopMatrix();
    glNewList(l, GL_COMPILE);
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glEdgeFlag(!flags[i]);
        glVertex2f(v[i][0] - 0.05f, v[i][1] + 1.0f);
    }
    glEnd();
    glEndList();
    glColor4fv(green);
    glCallList(l);
    glDeleteLists(l, 1);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    value_error(r);
    r->native_equal = 1;
    r->min_quads = 5;
}

/* ---- display lists and glBegin/glEnd ---------------------------------------------------------- */

/* The cases of piglit's gl-1.0-dlist-beginend, in its order. */
static void scene_dlist_beginend(pt_run *r)
{
    static const float verts[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    GLuint l, inner, outer, begin, end;
    pt_begin_frame();

    l = list_of_vertices(green); /* glCallList inside glBegin/glEnd */
    glBegin(GL_QUADS);
    glCallList(l);
    glEnd();
    value_error(r);
    value_centre(r);
    glDeleteLists(l, 1);

    inner = list_of_vertices(green); /* the same, compiled and executed inside another list */
    outer = glGenLists(1);
    glNewList(outer, GL_COMPILE_AND_EXECUTE);
    glBegin(GL_QUADS);
    glCallList(inner);
    glEnd();
    glEndList();
    value_error(r);
    value_centre(r);
    glCallList(outer);
    value_centre(r);
    glDeleteLists(inner, 1);
    glDeleteLists(outer, 1);

    l = glGenLists(1); /* glRect in a list called inside glBegin/glEnd: an error, not drawn */
    glNewList(l, GL_COMPILE);
    glColor4fv(green);
    full_quad_vertices();
    glColor4fv(red);
    glRectf(-1, -1, 1, 1);
    glEndList();
    glBegin(GL_QUADS);
    glCallList(l);
    glEnd();
    value_error(r);
    value_centre(r);
    glDeleteLists(l, 1);

    glVertexPointer(2, GL_FLOAT, 0, verts); /* glDrawArrays there: the same */
    glEnableClientState(GL_VERTEX_ARRAY);
    l = glGenLists(1);
    glNewList(l, GL_COMPILE);
    glColor4fv(green);
    full_quad_vertices();
    glColor4fv(red);
    glDrawArrays(GL_QUADS, 0, 4);
    glEndList();
    glBegin(GL_QUADS);
    glCallList(l);
    glEnd();
    value_error(r);
    value_centre(r);
    glDeleteLists(l, 1);
    glDisableClientState(GL_VERTEX_ARRAY);

    l = glGenLists(1); /* ... with no array enabled */
    glNewList(l, GL_COMPILE);
    glDrawArrays(GL_QUADS, 0, 4);
    glEndList();
    glColor4fv(red);
    glBegin(GL_QUADS);
    glCallList(l);
    glEnd();
    value_error(r);
    value_centre(r);
    glDeleteLists(l, 1);

    begin = glGenLists(1); /* one list begins the primitive, another ends it */
    glNewList(begin, GL_COMPILE);
    glBegin(GL_QUADS);
    glEndList();
    l = list_of_vertices(green);
    end = glGenLists(1);
    glNewList(end, GL_COMPILE);
    glEnd();
    glEndList();
    glBegin(GL_QUADS);
    glCallList(begin); /* a glBegin inside glBegin: the error */
    glCallList(l);
    glCallList(end);
    value_error(r);
    value_centre(r);
    glCallList(begin); /* outside: the lists make a primitive of their own */
    glCallList(l);
    glCallList(end);
    value_error(r);
    value_centre(r);
    glDeleteLists(begin, 1);
    glDeleteLists(l, 1);
    glDeleteLists(end, 1);

    l = glGenLists(1); /* a bad mode recorded in a list */
    glNewList(l, GL_COMPILE_AND_EXECUTE);
    glBegin(10000);
    glColor4fv(green);
    full_quad_vertices();
    glEnd();
    glEndList();
    value_error(r);
    glCallList(l);
    value_error(r);
    value_centre(r);
    glDeleteLists(l, 1);

    /* Last, quads that a list ends and that follow it: the library still takes quads. */
    end = glGenLists(1);
    glNewList(end, GL_COMPILE);
    glColor4fv(PC[3]);
    glVertex2fv(P[3]);
    glEnd();
    glEndList();
    glBegin(GL_QUADS);
    for (int i = 0; i < 3; i++) {
        glColor4fv(PC[i]);
        glVertex2fv(P[i]);
    }
    glCallList(end);
    value_error(r);
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glColor4fv(PC[i]);
        glVertex2f(P[i][0] * 0.5f, P[i][1] * 0.5f);
    }
    glEnd();
    value_error(r);
    glDeleteLists(end, 1);
    r->native_equal = 1;
    r->min_quads = 1;
}

/* Calls GL allows inside glBegin/glEnd that the capture does not represent (a packed colour,
 * a colour index, an integer attribute), the scalar glMaterial forms there, glCallLists inside
 * a primitive with a list base, and
 * inside a primitive compiled into a list a query (legal: nothing runs yet) and a list command
 * (an error at once, not compiled) (piglit's gl-1.0-beginend-coverage). */
static void scene_beginend_calls(pt_run *r)
{
    static const GLubyte one = 1;
    GLuint l = glGenLists(2);
    GLint index = -1;
    float shininess = 0;
    pt_begin_frame();
    glNewList(l, GL_COMPILE);
    glColor4fv(green);
    glEndList();
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glColor4fv(QC[i]);
        if (i == 0) { /* the scalar forms give one value (the driver reads past it for ambient) */
            glMateriali(GL_FRONT, GL_SHININESS, 20);
            glMaterialf(GL_BACK, GL_AMBIENT, 0.5f);
        }
        if (i == 1) {
            glIndexf(1.0f);
            glVertexAttribI4i(3, 1, 2, 3, 4);
            glColorP3ui(GL_UNSIGNED_INT_2_10_10_10_REV, 0x3ffu << 10); /* green */
        }
        glVertex2f(QV[i][0] * 0.5f - 0.45f, QV[i][1] * 0.5f - 0.45f);
    }
    glEnd();
    value_error(r);
    glGetMaterialfv(GL_FRONT, GL_SHININESS, &shininess);
    pt_value(r, (uint32_t)shininess);
    glListBase(l - 1);
    glBegin(GL_QUADS);
    glCallLists(1, GL_UNSIGNED_BYTE, &one); /* list l: green */
    for (int i = 0; i < 4; i++)
        glVertex2f(QV[i][0] * 0.4f + 0.5f, QV[i][1] * 0.4f + 0.5f);
    glEnd();
    glListBase(0);
    value_error(r);
    glNewList(l + 1, GL_COMPILE);
    glBegin(GL_QUADS);
    glGetIntegerv(GL_LIST_INDEX, &index);
    glNewList(l, GL_COMPILE); /* a list is being compiled: GL_INVALID_OPERATION */
    for (int i = 0; i < 4; i++) {
        glColor4fv(PC[i]);
        glVertex2f(P[i][0] * 0.4f + 0.5f, P[i][1] * 0.4f - 0.5f);
    }
    glEnd();
    glEndList();
    pt_value(r, (uint32_t)index == l + 1);
    value_error(r);
    glCallList(l + 1);
    value_error(r);
    glDeleteLists(l, 2);
    r->native_equal = 1;
    r->min_quads = 1; /* the list's quad: the others go to the driver when it takes them over */
}

/* ---- state the GL path must leave as it found it ----------------------------------------------- */

/* Colour sum on at the first quad the library draws (which makes its GL path, and measures
 * what drawing costs): the secondary colour must still be added afterwards, in quads drawn
 * at once and in a list's triangles and quads (piglit's draw-batch). */
static void scene_color_sum(pt_run *r)
{
    static const float magenta[4] = {1, 0, 1, 1}, grey[3] = {0.2f, 0.2f, 0.2f};
    GLuint l = glGenLists(1);
    pt_begin_frame();
    glEnable(GL_COLOR_SUM);
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glColor4fv(magenta);
        glSecondaryColor3fv(grey);
        glVertex2f(P[i][0] * 0.4f - 0.5f, P[i][1] * 0.4f - 0.5f);
    }
    glEnd();
    glNewList(l, GL_COMPILE);
    glBegin(GL_TRIANGLES);
    for (int i = 0; i < 3; i++) {
        glColor4fv(magenta);
        glSecondaryColor3fv(grey);
        glVertex2f(P[i][0] * 0.4f + 0.5f, P[i][1] * 0.4f - 0.5f);
    }
    glEnd();
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glColor4fv(PC[i]);
        glSecondaryColor3fv(grey);
        glVertex2f(P[i][0] * 0.4f, P[i][1] * 0.4f + 0.5f);
    }
    glEnd();
    glEndList();
    glCallList(l);
    pt_value(r, glIsEnabled(GL_COLOR_SUM));
    glDisable(GL_COLOR_SUM);
    glDeleteLists(l, 1);
    value_error(r);
    r->native_equal = 1;
    r->min_quads = 2;
}

/* ---- the application's own programs ------------------------------------------------------------ */

/* A GLSL program whose colour is generic attribute 1, given per vertex inside glBegin/glEnd,
 * from an array, and in a list (whose call is preceded by other values, as piglit's attribs
 * does to see that compiling ran nothing). */
static void scene_glsl_attribs(pt_run *r)
{
    static const char *vs = "#version 120\n"
                            "attribute vec4 attr;\n"
                            "void main() { gl_Position = gl_Vertex; gl_FrontColor = attr; }\n";
    static const float grey[4] = {0.1f, 0.1f, 0.1f, 0.1f};
    GLuint prog = glCreateProgram(), sh = glCreateShader(GL_VERTEX_SHADER), l = glGenLists(1);
    GLint ok = 0;
    pt_begin_frame();
    glShaderSource(sh, 1, &vs, NULL);
    glCompileShader(sh);
    glAttachShader(prog, sh);
    glBindAttribLocation(prog, 1, "attr");
    glLinkProgram(prog);
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    pt_value(r, (uint32_t)ok);
    glUseProgram(prog);
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glVertexAttrib4fv(1, QC[i]);
        glVertex2f(QV[i][0] * 0.5f - 0.45f, QV[i][1] * 0.5f - 0.45f);
    }
    glEnd();
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, 0, QC);
    glEnableVertexAttribArray(1);
    glVertexPointer(2, GL_FLOAT, 0, QV);
    glEnableClientState(GL_VERTEX_ARRAY);
    glDrawArrays(GL_QUADS, 0, 4);
    glDisableClientState(GL_VERTEX_ARRAY);
    glDisableVertexAttribArray(1);
    glNewList(l, GL_COMPILE);
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glVertexAttrib4Nub(1, (GLubyte)(QC[i][0] * 255), (GLubyte)(QC[i][1] * 255), (GLubyte)(QC[i][2] * 255), 255);
        glVertex2f(QV[i][0] * 0.4f + 0.5f, QV[i][1] * 0.4f + 0.5f);
    }
    glEnd();
    glEndList();
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glVertexAttrib4fv(1, grey);
        glVertex2f(QV[i][0] * 0.4f + 0.5f, QV[i][1] * 0.4f + 0.5f);
    }
    glEnd();
    glCallList(l);
    glUseProgram(0);
    glDeleteLists(l, 1);
    glDeleteProgram(prog);
    glDeleteShader(sh);
    value_error(r);
    r->native_equal = 1;
    r->min_quads = 4;
}

/* ARB vertex and fragment programs, positions from generic attribute 6 (piglit's pos-array)
 * and colours from generic attribute 7, drawn from a buffer object, inside glBegin/glEnd and
 * from a list: the driver's own pipeline, so the driver's own pixels. */
static void scene_arb_programs(pt_run *r)
{
    static const char *vp = "!!ARBvp1.0\n"
                            "PARAM mvp[4] = { state.matrix.mvp };\n"
                            "DP4 result.position.x, mvp[0], vertex.attrib[6];\n"
                            "DP4 result.position.y, mvp[1], vertex.attrib[6];\n"
                            "DP4 result.position.z, mvp[2], vertex.attrib[6];\n"
                            "DP4 result.position.w, mvp[3], vertex.attrib[6];\n"
                            "MOV result.color, vertex.attrib[7];\n"
                            "END\n";
    static const char *fp = "!!ARBfp1.0\nMOV result.color, fragment.color;\nEND\n";
    GLuint prog[2], buf, l = glGenLists(1);
    float data[4 * 2 + 4 * 4];
    pt_begin_frame();
    if (!strstr((const char *)glGetString(GL_EXTENSIONS), "GL_ARB_vertex_program")) {
        pt_value(r, 0x77);
        return;
    }
    glGenProgramsARB(2, prog);
    glBindProgramARB(GL_VERTEX_PROGRAM_ARB, prog[0]);
    glProgramStringARB(GL_VERTEX_PROGRAM_ARB, GL_PROGRAM_FORMAT_ASCII_ARB, (GLsizei)strlen(vp), vp);
    glBindProgramARB(GL_FRAGMENT_PROGRAM_ARB, prog[1]);
    glProgramStringARB(GL_FRAGMENT_PROGRAM_ARB, GL_PROGRAM_FORMAT_ASCII_ARB, (GLsizei)strlen(fp), fp);
    value_error(r);
    glEnable(GL_VERTEX_PROGRAM_ARB);
    glEnable(GL_FRAGMENT_PROGRAM_ARB);
    for (int i = 0; i < 4; i++) {
        data[2 * i] = QV[i][0] * 0.5f - 0.45f;
        data[2 * i + 1] = QV[i][1] * 0.5f - 0.45f;
        memcpy(data + 8 + 4 * i, QC[i], sizeof QC[i]);
    }
    glGenBuffers(1, &buf);
    glBindBuffer(GL_ARRAY_BUFFER, buf);
    glBufferData(GL_ARRAY_BUFFER, sizeof data, data, GL_STATIC_DRAW);
    glVertexAttribPointerARB(6, 2, GL_FLOAT, GL_FALSE, 0, (void *)0);
    glVertexAttribPointerARB(7, 4, GL_FLOAT, GL_FALSE, 0, (void *)(8 * sizeof(float)));
    glEnableVertexAttribArrayARB(6);
    glEnableVertexAttribArrayARB(7);
    glDrawArrays(GL_QUADS, 0, 4);
    glDisableVertexAttribArrayARB(6);
    glDisableVertexAttribArrayARB(7);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    value_centre(r);
    glBegin(GL_QUADS); /* the same inside glBegin/glEnd, and (moved) from a list */
    for (int i = 0; i < 4; i++) {
        glVertexAttrib4fvARB(7, QC[i]);
        glVertexAttrib2fARB(6, data[2 * i], data[2 * i + 1]);
        glVertex2f(data[2 * i], data[2 * i + 1]);
    }
    glEnd();
    glNewList(l, GL_COMPILE);
    glBegin(GL_QUAD_STRIP);
    for (int i = 0; i < 4; i++) {
        static const int strip[4] = {0, 1, 3, 2};
        int k = strip[i];
        glColor4fv(QC[k]);
        glVertexAttrib4fvARB(7, QC[k]);
        glVertexAttrib2fARB(6, QV[k][0] * 0.4f + 0.5f, QV[k][1] * 0.4f + 0.5f);
        glVertex2f(QV[k][0] * 0.4f + 0.5f, QV[k][1] * 0.4f + 0.5f);
    }
    glEnd();
    glEndList();
    glCallList(l);
    glDisable(GL_VERTEX_PROGRAM_ARB);
    glDisable(GL_FRAGMENT_PROGRAM_ARB);
    glDeleteProgramsARB(2, prog);
    glDeleteBuffers(1, &buf);
    glDeleteLists(l, 1);
    value_error(r);
    r->native_equal = 1;
    r->min_quads = 2;
}

static const pt_scene scenes[] = {
    {"edgeflag_line", scene_edgeflag_line},
    {"dlist_beginend", scene_dlist_beginend},
    {"beginend_calls", scene_beginend_calls},
    {"color_sum", scene_color_sum},
    {"glsl_attribs", scene_glsl_attribs},
    {"arb_programs", scene_arb_programs},
};

int main(int argc, char **argv)
{
    return pt_main(argc, argv, scenes, (int)(sizeof scenes / sizeof scenes[0]));
}
