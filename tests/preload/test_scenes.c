/* test_scenes.c: legacy GL scenes drawn through the preload library and natively (see pt.h).
 *
 * Each scene exercises one way a program hands quads to GL: glBegin/glEnd with every kind of
 * attribute call, client arrays, buffer objects, display lists (nested, defined after their
 * caller, compile-and-execute, glCallLists with a base, deleted and redefined), flat shading
 * (with and without lighting), polygon mode line, lighting, texturing, evaluators, misuse, and
 * a primitive of ten million vertices. The quads are in normalized device coordinates under
 * identity matrices, so the reference of a declared quad is its corners' colours
 * interpolated by mean value weights. */
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>
#include <sys/resource.h>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/osmesa.h>
#include <GL/glext.h>

#include "pt.h"

/* A two-quad strip (with pt.h's three non-affine quads Q, C). */
static const float S[6][2] = {{0.1f, 0.1f}, {0.1f, 0.9f}, {0.5f, 0.15f}, {0.45f, 0.85f}, {0.9f, 0.1f}, {0.85f, 0.9f}};
static const float SC[6][4] = {{1, 0, 0, 1}, {0, 0, 1, 1}, {0, 1, 0, 1}, {1, 1, 1, 1}, {1, 0, 1, 1}, {0, 0, 0, 1}};

static void expect_quads(pt_run *r, int flat)
{
    for (int q = 0; q < 3; q++)
        pt_expect(r, Q[q], C[q], flat ? 4 : 0);
}

/* Strip quad k is v2k, v2k+1, v2k+3, v2k+2; its provoking vertex 2k+3 is corner 2. */
static void expect_strip(pt_run *r, int flat)
{
    static const int order[4] = {0, 1, 3, 2};
    for (int k = 0; k < 2; k++) {
        float v[4][2], c[4][4];
        for (int i = 0; i < 4; i++) {
            memcpy(v[i], S[2 * k + order[i]], sizeof v[i]);
            memcpy(c[i], SC[2 * k + order[i]], sizeof c[i]);
        }
        pt_expect(r, v, c, flat ? 3 : 0);
    }
}

static void strip_immediate(void)
{
    glBegin(GL_QUAD_STRIP);
    for (int i = 0; i < 6; i++) {
        glColor4fv(SC[i]);
        glVertex2fv(S[i]);
    }
    glEnd();
}

static void quad_immediate(int q, float dx, float dy)
{
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glColor4fv(C[q][i]);
        glVertex2f(Q[q][i][0] + dx, Q[q][i][1] + dy);
    }
    glEnd();
}

/* ---- immediate mode ---------------------------------------------------------------------- */

static void scene_immediate(pt_run *r)
{
    pt_begin_frame();
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) { /* float colour, float vertex */
        glColor4f(C[0][i][0], C[0][i][1], C[0][i][2], C[0][i][3]);
        glVertex2f(Q[0][i][0], Q[0][i][1]);
    }
    for (int i = 0; i < 4; i++) { /* double colour, double vertex with z and w */
        glColor3d(C[1][i][0], C[1][i][1], C[1][i][2]);
        glVertex4d(Q[1][i][0], Q[1][i][1], 0.0, 1.0);
    }
    for (int i = 0; i < 4; i++) { /* vector forms */
        double v[3] = {Q[2][i][0], Q[2][i][1], 0.0};
        glColor3fv(C[2][i]);
        glVertex3dv(v);
    }
    glVertex2f(0.5f, 0.5f); /* an incomplete trailing quad is dropped */
    glVertex2f(0.6f, 0.5f);
    glEnd();
    strip_immediate();
    expect_quads(r, 0);
    expect_strip(r, 0);
    r->checks_reference = 1;
    r->min_quads = 5;
}

/* Colour given from the second vertex on: vertex 0 takes the colour current at glBegin; after
 * glEnd the current colour is the last one given (the triangle below shows it). */
static void scene_partial(pt_run *r)
{
    float c[4][4];
    memcpy(c, C[0], sizeof c);
    c[0][0] = 0.25f, c[0][1] = 0.5f, c[0][2] = 0.75f;
    pt_begin_frame();
    glColor3f(0.25f, 0.5f, 0.75f);
    glBegin(GL_QUADS);
    glVertex2fv(Q[0][0]);
    for (int i = 1; i < 4; i++) {
        glColor4ub((GLubyte)(C[0][i][0] * 255), (GLubyte)(C[0][i][1] * 255), (GLubyte)(C[0][i][2] * 255), 255);
        glVertex2fv(Q[0][i]);
    }
    glEnd();
    glBegin(GL_TRIANGLES);
    glVertex2f(0.2f, 0.2f);
    glVertex2f(0.9f, 0.2f);
    glVertex2f(0.5f, 0.9f);
    glEnd();
    pt_expect(r, Q[0], c, 0);
    r->checks_reference = 1;
    r->min_quads = 1;
}

/* ---- vertex arrays --------------------------------------------------------------------------- */

static void scene_arrays(pt_run *r)
{
    GLubyte col[4][4];
    GLuint idx[4] = {0, 1, 2, 3};
    float inter[4][6], cur[4];
    GLint first[1] = {0};
    GLsizei count[1] = {6};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++)
            col[i][k] = (GLubyte)(C[0][i][k] * 255.0f + 0.5f);
    pt_begin_frame();
    glColor3f(0.125f, 0.25f, 0.5f);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(2, GL_FLOAT, 0, Q[0]);
    glColorPointer(4, GL_UNSIGNED_BYTE, 0, col);
    glDrawArrays(GL_QUADS, 0, 4);
    glVertexPointer(2, GL_FLOAT, 0, Q[1]);
    glColorPointer(4, GL_FLOAT, 0, C[1]);
    glDrawElements(GL_QUADS, 4, GL_UNSIGNED_INT, idx);
    for (int i = 0; i < 4; i++) {
        memcpy(inter[i], C[2][i], 3 * sizeof(float));
        inter[i][3] = Q[2][i][0], inter[i][4] = Q[2][i][1], inter[i][5] = 0;
    }
    glInterleavedArrays(GL_C3F_V3F, 0, inter);
    glDrawArrays(GL_QUADS, 0, 4);
    glVertexPointer(2, GL_FLOAT, 0, S);
    glColorPointer(4, GL_FLOAT, 0, SC);
    glMultiDrawArrays(GL_QUAD_STRIP, first, count, 1);
    glDisableClientState(GL_VERTEX_ARRAY);
    glDisableClientState(GL_COLOR_ARRAY);
    /* The current colour after array draws is what the driver leaves (the one from before). */
    glGetFloatv(GL_CURRENT_COLOR, cur);
    for (int i = 0; i < 4; i++)
        pt_value(r, (uint32_t)(cur[i] * 1000.0f));
    expect_quads(r, 0);
    expect_strip(r, 0);
    r->checks_reference = 1;
    r->min_quads = 5;
}

/* Interleaved position + colour in a buffer object, 32-bit indices in an element buffer. */
static void scene_buffers(pt_run *r)
{
    float data[10][6];
    GLuint idx[8] = {9, 8, 7, 6, 0, 1, 2, 3}, vbo, ebo;
    for (int i = 0; i < 4; i++) {
        data[i][0] = Q[0][i][0], data[i][1] = Q[0][i][1];
        memcpy(&data[i][2], C[0][i], 4 * sizeof(float));
        /* Q[1] stored backwards at 6..9 so its indices are 9 8 7 6 -> corners 0 1 2 3 */
        data[9 - i][0] = Q[1][i][0], data[9 - i][1] = Q[1][i][1];
        memcpy(&data[9 - i][2], C[1][i], 4 * sizeof(float));
    }
    memset(data[4], 0, 2 * sizeof data[4]);
    pt_begin_frame();
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof data, data, GL_STATIC_DRAW);
    glGenBuffers(1, &ebo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, sizeof idx, idx, GL_STATIC_DRAW);
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glVertexPointer(2, GL_FLOAT, 6 * sizeof(float), (void *)0);
    glColorPointer(4, GL_FLOAT, 6 * sizeof(float), (void *)(2 * sizeof(float)));
    glLockArraysEXT(0, 10);
    glDrawRangeElements(GL_QUADS, 0, 9, 8, GL_UNSIGNED_INT, (void *)0);
    glUnlockArraysEXT();
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glVertexPointer(2, GL_FLOAT, 0, Q[2]);
    glColorPointer(4, GL_FLOAT, 0, C[2]);
    glDrawArrays(GL_QUADS, 0, 4);
    glDisableClientState(GL_VERTEX_ARRAY);
    glDisableClientState(GL_COLOR_ARRAY);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
    glDeleteBuffers(1, &vbo);
    glDeleteBuffers(1, &ebo);
    expect_quads(r, 0);
    r->checks_reference = 1;
    r->min_quads = 3;
}

/* ---- display lists ---------------------------------------------------------------------------- */

/* explicit_first: vertex 0 of the compile-and-execute quad gets its own colour. Mesa compiles
 * a quad whose first vertex takes a colour set earlier in the same list with another
 * triangulation than the same calls made immediately or split over two lists, so the exact
 * comparison of the replay mode uses this variant. */
static void draw_lists(pt_run *r, int explicit_first)
{
    GLuint base = glGenLists(8);
    GLubyte calls[2] = {0, 1};
    float moved[4][2], c1[4][4];
    pt_begin_frame();
    /* base+1 calls base+0 under a translation before base+0 exists: resolved when it runs. */
    glNewList(base + 1, GL_COMPILE);
    glPushMatrix();
    glTranslatef(0.0f, 1.0f, 0.0f);
    glCallList(base + 0);
    glPopMatrix();
    glEndList();
    glNewList(base + 0, GL_COMPILE);
    quad_immediate(1, 0, 0);
    glEndList();
    glCallList(base + 1);
    /* Compile-and-execute, with a colour set inside the list that vertex 0 then takes. */
    glNewList(base + 2, GL_COMPILE_AND_EXECUTE);
    glColor3f(0.5f, 0.0f, 0.25f);
    glBegin(GL_QUADS);
    if (explicit_first)
        glColor3f(0.5f, 0.0f, 0.25f);
    glVertex2fv(Q[0][0]);
    for (int i = 1; i < 4; i++) {
        glColor4fv(C[0][i]);
        glVertex2fv(Q[0][i]);
    }
    glEnd();
    glEndList();
    glColor3f(0, 1, 0); /* overridden by the list's own colour when it runs again */
    glCallList(base + 2);
    /* glCallLists through the list base: base+3 is a quad, base+4 the strip. */
    glNewList(base + 3, GL_COMPILE);
    quad_immediate(2, 0, 0);
    glEndList();
    glNewList(base + 4, GL_COMPILE);
    strip_immediate();
    glEndList();
    glListBase(base + 3);
    glCallLists(2, GL_UNSIGNED_BYTE, calls);
    glListBase(0);
    /* A deleted list draws nothing; a list redefined without quads draws its new content. */
    glNewList(base + 5, GL_COMPILE);
    quad_immediate(1, 0, 0);
    glEndList();
    glDeleteLists(base + 5, 1);
    glCallList(base + 5);
    pt_value(r, glIsList(base + 5));
    pt_value(r, glIsList(base + 1));
    glNewList(base + 6, GL_COMPILE);
    quad_immediate(1, 0, 0);
    glEndList();
    glNewList(base + 6, GL_COMPILE);
    glEndList();
    glCallList(base + 6);
    pt_value(r, glGetError());
    glDeleteLists(base, 8);
    for (int i = 0; i < 4; i++)
        moved[i][0] = Q[1][i][0], moved[i][1] = Q[1][i][1] + 1.0f;
    memcpy(c1, C[0], sizeof c1);
    c1[0][0] = 0.5f, c1[0][1] = 0.0f, c1[0][2] = 0.25f;
    pt_expect(r, moved, C[1], 0);
    pt_expect(r, Q[0], c1, 0);
    pt_expect(r, Q[2], C[2], 0);
    expect_strip(r, 0);
    r->checks_reference = 1;
    r->min_quads = 6;
}

static void scene_lists(pt_run *r)
{
    draw_lists(r, 0);
}

static void scene_lists_explicit(pt_run *r)
{
    draw_lists(r, 1);
}

/* One list drawn under several states (its retained copy must follow each: smooth, then flat
 * shaded one unit up, where the driver's own compilation draws it), then redefined with
 * another quad and drawn again, then deleted (drawing nothing). */
static void scene_lists_states(pt_run *r)
{
    GLuint l = glGenLists(1);
    float up[4][2];
    pt_begin_frame();
    glNewList(l, GL_COMPILE);
    quad_immediate(0, 0, 0);
    glEndList();
    glCallList(l);
    glShadeModel(GL_FLAT);
    glPushMatrix();
    glTranslatef(0.0f, 1.0f, 0.0f);
    glCallList(l);
    glPopMatrix();
    glShadeModel(GL_SMOOTH);
    glNewList(l, GL_COMPILE);
    quad_immediate(1, 0, 0);
    glEndList();
    glCallList(l);
    glDeleteLists(l, 1);
    glCallList(l);
    pt_value(r, glIsList(l));
    for (int i = 0; i < 4; i++)
        up[i][0] = Q[0][i][0], up[i][1] = Q[0][i][1] + 1.0f;
    pt_expect(r, Q[0], C[0], 0);
    pt_expect(r, up, C[0], 4);
    pt_expect(r, Q[1], C[1], 0);
    r->checks_reference = 1;
    r->min_quads = 3;
}

/* A bound 2D texture of w x h RGBA texels with filter for both minification and magnification. */
static GLuint texture_2d(int w, int h, const void *rgba, GLint filter)
{
    GLuint name;
    glGenTextures(1, &name);
    glBindTexture(GL_TEXTURE_2D, name);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    return name;
}

/* ---- batches: many small primitives with changes between them ------------------------------ */

/* Cell k of a 5 x 5 grid of small non-affine quads (corners pulled by varying amounts), all
 * inside the view volume. */
static void cell_quad(int k, float v[4][2])
{
    static const float pull[4][2] = {{0.02f, 0.01f}, {-0.03f, 0.02f}, {-0.01f, -0.03f}, {0.03f, -0.02f}};
    float x0 = -0.9f + 0.36f * (float)(k % 5), y0 = -0.9f + 0.36f * (float)(k / 5), d = 0.3f;
    float corner[4][2] = {{x0, y0}, {x0 + d, y0}, {x0 + d, y0 + d}, {x0, y0 + d}};
    for (int i = 0; i < 4; i++)
        for (int a = 0; a < 2; a++)
            v[i][a] = corner[i][a] + pull[(i + k) % 4][a] * (float)(1 + k % 3);
}

static void cell_colours(int k, float c[4][4])
{
    for (int i = 0; i < 4; i++) {
        c[i][0] = (float)((k * 7 + i * 3) % 5) / 4.0f;
        c[i][1] = (float)((k * 5 + i * 2) % 4) / 3.0f;
        c[i][2] = (float)((k + i * 5) % 6) / 5.0f;
        c[i][3] = 1;
    }
}

/* Each cell its own glBegin/glEnd, with what programs do between such primitives: colours set
 * outside (an attribute some primitives give and others do not), colours given from a later
 * vertex on, matrix changes, flat shading, a display list, an array draw, a glGet of the
 * current colour. Every cell must come out as if drawn alone (the batch is invisible). */
static void scene_batches(pt_run *r)
{
    float v[4][2], c[4][4], cur[4];
    GLuint list = glGenLists(1);
    pt_begin_frame();
    for (int k = 0; k < 25; k++) {
        int way = k % 8, flat = 0;
        cell_quad(k, v);
        cell_colours(k, c);
        if (way == 1 || way == 5) { /* one colour from outside the primitive */
            glColor4fv(c[k % 4]);
            for (int i = 0; i < 4; i++)
                memcpy(c[i], c[k % 4], sizeof c[i]);
            if (way == 1) { /* what waits is drawn now: the colour just set must survive that */
                glPushMatrix();
                glPopMatrix();
                glPushMatrix();
            }
        } else if (way == 2) { /* the first two vertices take the current colour */
            glColor4fv(c[0]);
            memcpy(c[1], c[0], sizeof c[1]);
        } else if (way == 4) {
            glShadeModel(GL_FLAT);
            flat = 4;
        }
        if (way == 3) { /* drawn one cell to the left, moved back by the matrix */
            glPushMatrix();
            glTranslatef(0.36f, 0.0f, 0.0f);
        }
        if (way == 6) { /* from client arrays, between immediate primitives */
            float moved[4][2];
            memcpy(moved, v, sizeof moved);
            glEnableClientState(GL_VERTEX_ARRAY);
            glEnableClientState(GL_COLOR_ARRAY);
            glVertexPointer(2, GL_FLOAT, 0, moved);
            glColorPointer(4, GL_FLOAT, 0, c);
            glDrawArrays(GL_QUADS, 0, 4);
            glDisableClientState(GL_VERTEX_ARRAY);
            glDisableClientState(GL_COLOR_ARRAY);
        } else if (way == 7) {
            glNewList(list, GL_COMPILE);
            glBegin(GL_QUADS);
            for (int i = 0; i < 4; i++) {
                glColor4fv(c[i]);
                glVertex2fv(v[i]);
            }
            glEnd();
            glEndList();
            glCallList(list);
        } else {
            glBegin(GL_QUADS);
            for (int i = 0; i < 4; i++) {
                if (way != 1 && way != 5 && (way != 2 || i >= 2))
                    glColor4fv(c[i]);
                glVertex2f(v[i][0] - (way == 3 ? 0.36f : 0.0f), v[i][1]);
            }
            glEnd();
        }
        if (way == 3 || way == 1) /* way 1: drawn now, with the colour set before the last flush */
            glPopMatrix();
        if (way == 4)
            glShadeModel(GL_SMOOTH);
        if (k == 12) { /* the current colour after glEnd is the primitive's last */
            glGetFloatv(GL_CURRENT_COLOR, cur);
            for (int i = 0; i < 4; i++)
                pt_value(r, (uint32_t)(cur[i] * 1000.0f + 0.5f));
        }
        pt_expect(r, v, c, flat);
    }
    glDeleteLists(list, 1);
    r->checks_reference = 1;
    r->min_quads = 25;
}

static void quad_from(const float v[4][2], const float c[4][4], float dy)
{
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glColor4fv(c[i]);
        glVertex2f(v[i][0], v[i][1] + dy);
    }
    glEnd();
}

/* Draws since the counters were read into before (0 when nothing is counted). */
static uint64_t draws_since(const uint64_t before[PT_NCOUNTERS])
{
    uint64_t now[PT_NCOUNTERS];
    glFinish();
    return pt_counters(now) == 0 ? now[PT_DRAWS] - before[PT_DRAWS] : 0;
}

/* Eighteen single-quad primitives in a row must cost the library a draw or two, not one each;
 * 600 more (cell 0 again, drawn over itself) fill the batch more than once, and a primitive
 * that finds it full begins the next batch instead of being drawn alone: three draws; a
 * display list of seven such primitives, called three times under different matrices,
 * uploads its vertices once and takes a draw or two a call. */
static void scene_batch_draws(pt_run *r)
{
    uint64_t before[PT_NCOUNTERS], uploads = 0;
    float v[4][2], c[4][4];
    GLuint list = glGenLists(1);
    pt_begin_frame();
    pt_counters(before);
    for (int k = 0; k < 18; k++) {
        cell_quad(k, v);
        cell_colours(k, c);
        quad_from(v, c, 0);
        pt_expect(r, v, c, 0);
    }
    uint64_t d = draws_since(before);
    if (d > 2)
        snprintf(r->failure, sizeof r->failure, "18 primitives in a row took %llu draws", (unsigned long long)d);
    pt_counters(before);
    cell_quad(0, v);
    cell_colours(0, c);
    for (int k = 0; k < 600; k++)
        quad_from(v, c, 0);
    d = draws_since(before);
    if (d > 3 && !r->failure[0])
        snprintf(r->failure, sizeof r->failure, "600 primitives in a row took %llu draws", (unsigned long long)d);
    glNewList(list, GL_COMPILE);
    for (int k = 18; k < 25; k++) {
        cell_quad(k, v);
        cell_colours(k, c);
        quad_from(v, c, 0);
    }
    glEndList();
    for (int call = 0; call < 3; call++) {
        float dy = -0.54f * (float)call;
        pt_counters(before);
        glPushMatrix();
        glTranslatef(0.0f, dy, 0.0f);
        glCallList(list);
        glPopMatrix();
        d = draws_since(before);
        if (d > 2 && !r->failure[0])
            snprintf(r->failure, sizeof r->failure, "a list of 7 primitives took %llu draws", (unsigned long long)d);
        if (call > 0 && before[PT_UPLOADS] != uploads && !r->failure[0])
            snprintf(r->failure, sizeof r->failure, "the list was uploaded again at call %d", call);
        pt_counters(before);
        uploads = before[PT_UPLOADS];
        for (int k = 18; k < 25; k++) {
            cell_quad(k, v);
            cell_colours(k, c);
            for (int i = 0; i < 4; i++)
                v[i][1] += dy;
            pt_expect(r, v, c, 0);
        }
    }
    glDeleteLists(list, 1);
    r->checks_reference = 1;
    r->min_quads = 18 + 3 * 7;
}

/* Single-quad primitives captured straight into the pending batch, each with what sends a
 * primitive back to arrays of its own or changes the batch under it: no colour of its own
 * after a colour set outside, a colour given only from its third vertex (the batch so far
 * carries none), an edge flag from its second vertex and a vertex left over, a generic
 * attribute from its third vertex, a list called inside (the driver takes the primitive
 * over), and one primitive of 16 400 vertices (the same quad again and again) that fills the
 * batch in the middle. Every cell must come out as if drawn alone, and the current colour
 * after each primitive must be GL's: asked for, and (the last cell) drawn by the driver in a
 * triangle after a quad of no area and a call that may change current values unseen. */
static void scene_batch_direct(pt_run *r)
{
    float v[4][2], c[4][4], cur[4] = {1, 1, 1, 1}, got[4];
    GLuint list = glGenLists(1);
    pt_begin_frame();
    for (int k = 0; k < 24; k++) {
        int way = k % 6, reps = k == 4 ? 4100 : 1, declared = 1;
        cell_quad(k, v);
        cell_colours(k, c);
        if (way == 5) { /* compiled between primitives, called inside the next one */
            glNewList(list, GL_COMPILE);
            glColor4fv(c[2]);
            glEndList();
        }
        if (way == 0) {
            glColor4fv(c[1]);
            memcpy(cur, c[1], sizeof cur);
        }
        glBegin(GL_QUADS);
        for (int n = 0; n < reps; n++)
            for (int i = 0; i < 4; i++) {
                if (way == 1 && i < 2) {
                    memcpy(c[i], cur, sizeof c[i]);
                } else if (way == 0) {
                    memcpy(c[i], cur, sizeof c[i]);
                } else if (way == 5 && i == 2) {
                    glCallList(list);
                    declared = 0; /* the driver's own quad: its pixels must be the driver's */
                } else {
                    glColor4fv(c[i]);
                }
                if (way == 2 && i == 1)
                    glEdgeFlag(GL_FALSE);
                if (way == 3 && i == 2)
                    glVertexAttrib4f(1, 0.5f, 0.25f, 0.125f, 1.0f);
                glVertex2fv(v[i]);
            }
        if (way == 2)
            glVertex2f(0.0f, 0.0f); /* a fifth vertex: no quad */
        glEnd();
        if (way == 2)
            glEdgeFlag(GL_TRUE);
        if (way != 0)
            memcpy(cur, c[3], sizeof cur);
        if (declared)
            pt_expect(r, v, c, 0);
        if (k % 4 == 1) {
            glGetFloatv(GL_CURRENT_COLOR, got);
            for (int i = 0; i < 4; i++)
                pt_value(r, (uint32_t)(got[i] * 1000.0f + 0.5f));
        }
    }
    cell_quad(24, v);
    cell_colours(24, c);
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glColor4fv(c[i]);
        glVertex2fv(v[0]);
    }
    glEnd();
    glIndexi(1);
    glBegin(GL_TRIANGLES);
    glVertex2f(v[0][0] - 0.01f, v[0][1] - 0.01f);
    glVertex2f(v[0][0] + 0.3f, v[0][1]);
    glVertex2f(v[0][0], v[0][1] + 0.3f);
    glEnd();
    glDeleteLists(list, 1);
    r->checks_reference = 1;
    r->min_quads = 24;
}

/* Strip k of three: two non-affine quads in a column of the 64 x 64 window, its vertex i
 * coloured SC[(i + k + shift) % 6]. */
static void column_strip(int k, float out[6][2])
{
    for (int i = 0; i < 6; i++) {
        out[i][0] = -0.9f + 0.6f * (float)k + (i & 1 ? 0.45f : 0.0f) + (i == 2 ? 0.1f : 0.0f);
        out[i][1] = -0.9f + 0.4f * (float)(i / 2) + (i == 3 ? 0.15f : 0.0f);
    }
}

static void draw_column_strip(int k, int shift)
{
    float st[6][2];
    column_strip(k, st);
    glBegin(GL_QUAD_STRIP);
    for (int i = 0; i < 6; i++) {
        glColor4fv(SC[(i + k + shift) % 6]);
        glVertex2fv(st[i]);
    }
    glEnd();
}

/* The quads of the three strips, dy higher, smooth or flat (the provoking vertex 2k+3). */
static void expect_column_strips(pt_run *r, int shift, float dy, int flat)
{
    static const int order[4] = {0, 1, 3, 2};
    float st[6][2], v[4][2], c[4][4];
    for (int k = 0; k < 3; k++) {
        column_strip(k, st);
        for (int q = 0; q < 2; q++) {
            for (int i = 0; i < 4; i++) {
                int j = 2 * q + order[i];
                v[i][0] = st[j][0], v[i][1] = st[j][1] + dy;
                memcpy(c[i], SC[(j + k + shift) % 6], sizeof c[i]);
            }
            pt_expect(r, v, c, flat ? 3 : 0);
        }
    }
}

/* Three strips, through a display list and then in immediate mode, drawn smooth and then flat
 * (the strips' quads are planned together, unrolled: their colours must still be the strip's,
 * and under flat shading the provoking vertex's), in a draw or two each time. */
static void scene_list_strips(pt_run *r)
{
    uint64_t before[PT_NCOUNTERS];
    GLuint list = glGenLists(1);
    const char *method = getenv("QUADGL_METHOD");
    pt_begin_frame();
    glNewList(list, GL_COMPILE);
    for (int k = 0; k < 3; k++)
        draw_column_strip(k, 0);
    glEndList();
    for (int pass = 0; pass < 4; pass++) {
        int flat = pass & 1, immediate = pass >= 2;
        glShadeModel(flat ? GL_FLAT : GL_SMOOTH);
        glPushMatrix();
        glTranslatef(0.0f, flat ? 1.05f : 0.0f, 0.0f);
        pt_counters(before);
        if (immediate)
            for (int k = 0; k < 3; k++)
                draw_column_strip(k, 1);
        else
            glCallList(list);
        glPopMatrix();
        uint64_t d = draws_since(before);
        int replayed = immediate && method && !strcmp(method, "split"); /* the driver's own strips */
        if (d > 2 && !replayed && !r->failure[0])
            snprintf(r->failure, sizeof r->failure, "3 strips (%s) took %llu draws", immediate ? "immediate" : "a list",
                     (unsigned long long)d);
        expect_column_strips(r, immediate, flat ? 1.05f : 0.0f, flat);
    }
    glShadeModel(GL_SMOOTH);
    glDeleteLists(list, 1);
    r->checks_reference = 1;
    r->min_quads = 24;
}

/* A display list of a 12 x 12 grid of GL_QUADS (each inner corner given four times, as a
 * sphere's or a terrain's quads give them) with colours affine in the position, so that every
 * method draws it as the driver does, and a quad strip after it; drawn filled, then outlined.
 * The driver's own lists merge the equal corners, so its vertex stage runs about once per
 * distinct vertex: where the library draws the list, the vertex shader must not run once
 * per quad corner instead (ARB_pipeline_statistics_query counts it). */
static void grid_corner(int i, int j)
{
    float x = (float)i / 12.0f, y = (float)j / 12.0f;
    glColor4f(0.2f + 0.5f * x, 0.3f + 0.4f * y, 0.7f - 0.3f * x, 1);
    glVertex2f(-0.9f + 1.2f * x, -0.9f + 1.2f * y);
}

static void scene_list_grid(pt_run *r)
{
    enum { N = 12 };
    GLuint list = glGenLists(1), query = 0;
    const char *method = getenv("QUADGL_METHOD");
    int count = method && (!strcmp(method, "split") || !strcmp(method, "auto"));
    pt_begin_frame();
    glNewList(list, GL_COMPILE);
    glBegin(GL_QUADS);
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            grid_corner(i, j), grid_corner(i + 1, j);
            grid_corner(i + 1, j + 1), grid_corner(i, j + 1);
        }
    glEnd();
    glBegin(GL_QUAD_STRIP);
    for (int k = 0; k <= 4; k++) {
        glColor4f(0.9f, 0.2f * (float)k, 0.1f, 1);
        glVertex2f(0.45f, -0.9f + 0.3f * (float)k);
        glVertex2f(0.85f, -0.9f + 0.3f * (float)k);
    }
    glEnd();
    glEndList();
    if (strstr((const char *)glGetString(GL_EXTENSIONS), "GL_ARB_pipeline_statistics_query"))
        glGenQueries(1, &query);
    if (query)
        glBeginQuery(GL_VERTEX_SHADER_INVOCATIONS_ARB, query);
    glCallList(list);
    if (query) {
        GLuint runs = 0;
        glEndQuery(GL_VERTEX_SHADER_INVOCATIONS_ARB);
        glGetQueryObjectuiv(query, GL_QUERY_RESULT, &runs);
        glDeleteQueries(1, &query);
        /* 169 distinct corners and 10 strip vertices; 586 where every corner runs */
        if (pt_preloaded())
            printf("list_grid: the vertex stage ran %u times\n", runs);
        if (count && pt_preloaded() && runs > 2 * (N + 1) * (N + 1) + 10)
            snprintf(r->failure, sizeof r->failure, "the vertex stage ran %u times for %d distinct vertices", runs,
                     (N + 1) * (N + 1) + 10);
    }
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glPushMatrix();
    glTranslatef(0.95f, 0.95f, 0);
    glScalef(0.5f, 0.5f, 1);
    glCallList(list);
    glPopMatrix();
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDeleteLists(list, 1);
    r->native_equal = 1;
    r->min_quads = 2 * (N * N + 4);
}

/* Thin quad strips of a spiral, one glBegin/glEnd each, added up by blending (a hypnosis
 * wheel): where the driver's triangles leave a shared edge's pixel to both or to neither, the
 * sum shows it, so the strips must reach the rasterizer as the driver's own strips do. Each
 * strip has one colour: every method's picture is the driver's. */
static void scene_strip_blend(pt_run *r)
{
    pt_begin_frame();
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    for (int arm = 0; arm < 48; arm++) {
        float a0 = 6.2831853f * (float)arm / 48.0f;
        glBegin(GL_QUAD_STRIP);
        for (int k = 0; k <= 40; k++) {
            float t = (float)k / 40.0f, rad = 0.02f + 1.3f * t, a = a0 + 3.1f * t * t;
            for (int side = 0; side < 2; side++) {
                float w = a + (side ? 0.3f : 0.0f);
                glColor4f(0.05f + 0.1f * (float)(arm % 3), 0.1f, 0.15f - 0.05f * (float)(arm % 3), 1);
                glVertex2f(rad * cosf(w), rad * sinf(w));
            }
        }
        glEnd();
    }
    glDisable(GL_BLEND);
    r->native_equal = 1;
    r->min_quads = 48 * 40;
}

/* A display list alternating primitives the driver draws as they are (triangles, a fan, affine
 * quads) with strips and quads that need smoothing, drawn with the depth test on, where the
 * order of primitives cannot show: the library may draw it by kind, a draw per mode and one
 * for the smooth quads, and the picture must not change (the driver's pixels outside the
 * smooth quads, the reference inside). */
static void scene_list_depth(pt_run *r)
{
    static const float affine[4][4] = {{0.1f, 0.2f, 0.3f, 1}, {0.5f, 0.2f, 0.3f, 1}, {0.5f, 0.6f, 0.3f, 1},
                                       {0.1f, 0.6f, 0.3f, 1}};
    uint64_t before[PT_NCOUNTERS];
    float st[6][2];
    GLuint list = glGenLists(1);
    pt_begin_frame();
    glEnable(GL_DEPTH_TEST);
    glNewList(list, GL_COMPILE);
    for (int k = 0; k < 3; k++) {
        column_strip(k, st);
        draw_column_strip(k, 0);
        glBegin(k == 1 ? GL_TRIANGLE_FAN : GL_TRIANGLES); /* above the strip, in its column */
        glColor3f(0.2f * (float)k, 0.5f, 0.9f);
        glVertex2f(st[4][0], 0.3f);
        glVertex2f(st[5][0], 0.3f);
        glColor3f(0.9f, 0.3f * (float)k, 0.1f);
        glVertex2f(st[5][0], 0.6f);
        glEnd();
        const float a[4][2] = {{st[4][0], 0.7f}, {st[5][0], 0.7f}, {st[5][0], 0.95f}, {st[4][0], 0.95f}};
        quad_from(a, affine, 0); /* affine colours: the driver's split is exact */
        pt_expect(r, a, affine, 0);
    }
    glEndList();
    pt_counters(before);
    glCallList(list);
    uint64_t d = draws_since(before);
    if (d > 4)
        snprintf(r->failure, sizeof r->failure, "a depth-tested list of 9 primitives took %llu draws",
                 (unsigned long long)d);
    glDisable(GL_DEPTH_TEST);
    glDeleteLists(list, 1);
    expect_column_strips(r, 0, 0, 0);
    r->checks_reference = 1;
    r->min_quads = 9;
}

/* Small planar quads with affine colours (the split is exact, so every method must give the
 * driver's pixels) and state changes between them that a batch must not cross: blending,
 * polygon mode, texturing, depth test, line width, the clear colour and a clear. */
static void scene_batch_states(pt_run *r)
{
    static const GLubyte tex[2][2][4] = {{{255, 0, 0, 255}, {0, 255, 0, 255}}, {{0, 0, 255, 255}, {255, 255, 0, 255}}};
    GLuint name;
    float v[4][2];
    pt_begin_frame();
    name = texture_2d(2, 2, tex, GL_NEAREST);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    for (int k = 0; k < 25; k++) {
        int way = k % 6;
        float x0 = -0.96f + 0.38f * (float)(k % 5), y0 = -0.96f + 0.38f * (float)(k / 5), d = 0.3f;
        v[0][0] = v[3][0] = x0, v[1][0] = v[2][0] = x0 + d + 0.04f * (float)(k % 3);
        v[0][1] = v[1][1] = y0, v[2][1] = v[3][1] = y0 + d;
        if (way == 1)
            glEnable(GL_BLEND);
        else if (way == 2)
            glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        else if (way == 3)
            glEnable(GL_TEXTURE_2D);
        else if (way == 4)
            glLineWidth(3.0f);
        glBegin(GL_QUADS);
        for (int i = 0; i < 4; i++) {
            glColor4f(0.2f + 0.7f * (float)(i == 1 || i == 2), 0.3f + 0.5f * (float)(i >= 2), 0.6f, 0.5f);
            glTexCoord2f((float)(i == 1 || i == 2), (float)(i >= 2));
            glVertex2fv(v[i]);
        }
        glEnd();
        glDisable(GL_BLEND);
        glDisable(GL_TEXTURE_2D);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        glLineWidth(1.0f);
        if (k == 20) { /* a clear between batches wipes what came before it */
            glEnable(GL_SCISSOR_TEST);
            glScissor(0, 0, 32, 32);
            glClearColor(0.1f, 0.2f, 0.3f, 1);
            glClear(GL_COLOR_BUFFER_BIT);
            glDisable(GL_SCISSOR_TEST);
        }
    }
    glDeleteTextures(1, &name);
    r->native_equal = 1;
    r->min_quads = 25;
}

/* ---- fixed-function states ------------------------------------------------------------------------ */

static void scene_flat(pt_run *r)
{
    pt_begin_frame();
    glShadeModel(GL_FLAT);
    for (int q = 0; q < 3; q++)
        quad_immediate(q, 0, 0);
    strip_immediate();
    glShadeModel(GL_SMOOTH);
    expect_quads(r, 1);
    expect_strip(r, 1);
    r->checks_reference = 1;
    r->min_quads = 5;
}

/* Flat shading with lighting and a normal per vertex (glxgears' teeth): every quad takes the
 * lit colour of its provoking vertex, as the driver draws it. */
static void scene_flat_lit(pt_run *r)
{
    static const float dir[4] = {5.0f, 5.0f, 10.0f, 0.0f}, red[4] = {0.8f, 0.1f, 0.0f, 1.0f};
    pt_begin_frame();
    glShadeModel(GL_FLAT);
    glEnable(GL_LIGHTING);
    glEnable(GL_LIGHT0);
    glLightfv(GL_LIGHT0, GL_POSITION, dir);
    glMaterialfv(GL_FRONT, GL_AMBIENT_AND_DIFFUSE, red);
    glBegin(GL_QUAD_STRIP);
    for (int i = 0; i < 6; i++) {
        glNormal3f(0.3f * (float)(i % 3) - 0.3f, 0.2f * (float)(i % 2), 1.0f);
        glVertex2fv(S[i]);
    }
    glEnd();
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glNormal3f(0.4f * (float)i - 0.6f, 0.1f, 1.0f);
        glVertex2fv(Q[0][i]);
    }
    glEnd();
    glDisable(GL_LIGHTING);
    glShadeModel(GL_SMOOTH);
    r->native_equal = 1;
    r->min_quads = 3;
}

/* glMaterial per vertex inside glBegin/glEnd (as programs colour a lit surface without colour
 * material): fixed function lights each vertex with the material given before it, so the
 * picture is the mean value interpolation of the corners' lit colours, whatever path draws
 * each quad. A directional light along the normal lights a vertex with 0.2 (the scene's
 * ambient) + 1 (the light's diffuse) times its material. */
static void scene_materials(pt_run *r)
{
    static const float dir[4] = {0, 0, 1, 0};
    float lit[4][4];
    pt_begin_frame();
    glEnable(GL_LIGHTING);
    glEnable(GL_LIGHT0);
    glLightfv(GL_LIGHT0, GL_POSITION, dir);
    glNormal3f(0, 0, 1);
    for (int q = 0; q < 3; q++) {
        glBegin(GL_QUADS);
        for (int i = 0; i < 4; i++) {
            float m[4] = {0.75f * C[q][i][0], 0.75f * C[q][i][1], 0.75f * C[q][i][2], 1};
            glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, m);
            glVertex2fv(Q[q][i]);
            for (int k = 0; k < 3; k++)
                lit[i][k] = 1.2f * m[k];
            lit[i][3] = 1;
        }
        glEnd();
        pt_expect(r, Q[q], lit, 0);
    }
    glDisable(GL_LIGHTING);
    r->checks_reference = 1;
    r->min_quads = 3;
}

/* A lit quad's corner colours change with a glMaterial given between primitives, and the
 * planner, which lights corners on the CPU to judge whether the split would show, must see
 * the change. Light and viewer along z: a corner's colour is d nz + s nz^h. With the first
 * material (d 0.004, no specular) the quads are within half a level of affine: their split is
 * invisible. Then the specular turns on: the corner facing the light is 100 levels brighter
 * than the others, which the split shows as a crease; judged with the old material, the quad
 * would be split and differ from the reference. */
/* Light 0 white along z (as the viewer), with no ambient light anywhere. */
static void light_along_z(void)
{
    static const float dir[4] = {0, 0, 1, 0}, white[4] = {1, 1, 1, 1}, none[4] = {0, 0, 0, 1};
    glEnable(GL_LIGHTING);
    glEnable(GL_LIGHT0);
    glLightfv(GL_LIGHT0, GL_POSITION, dir);
    glLightfv(GL_LIGHT0, GL_AMBIENT, none);
    glLightfv(GL_LIGHT0, GL_DIFFUSE, white);
    glLightfv(GL_LIGHT0, GL_SPECULAR, white);
    glLightModelfv(GL_LIGHT_MODEL_AMBIENT, none);
}

/* Corner i's unit normal, tilted off z to n_z = tilt_nz[i], towards x or y by turns. */
static const float tilt_nz[4] = {0.6f, 0.6f, 1.0f, 0.6f};

static void tilted_normal(int i)
{
    float sxy = sqrtf(1 - tilt_nz[i] * tilt_nz[i]);
    glNormal3f(i & 1 ? sxy : 0, i & 1 ? 0 : sxy, tilt_nz[i]);
}

static void scene_material_change(pt_run *r)
{
    static const float none[4] = {0, 0, 0, 1};
    static const float dim[4] = {0.004f, 0.004f, 0.004f, 1}, shiny[4] = {1, 1, 1, 1};
    const float *nz = tilt_nz;
    pt_begin_frame();
    light_along_z();
    glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, none);
    glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, dim);
    glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, none);
    glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 1);
    for (int q = 0; q < 2; q++) {
        if (q == 1)
            glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, shiny);
        float lit[4][4];
        glBegin(GL_QUADS);
        for (int i = 0; i < 4; i++) {
            tilted_normal(i);
            glVertex2fv(Q[q][i]);
            float c = dim[0] * nz[i] + (q == 1 ? nz[i] : 0);
            lit[i][0] = lit[i][1] = lit[i][2] = c > 1 ? 1 : c;
            lit[i][3] = 1;
        }
        glEnd();
        pt_expect(r, Q[q], lit, 0);
    }
    glDisable(GL_LIGHTING);
    r->checks_reference = 1;
    r->min_quads = 2;
}

/* glMaterial once per quad inside one glBegin(GL_QUADS), before its first vertex (as programs
 * colour the faces of a lit model): each quad has one material at its four corners, which
 * the GL layer then keeps at the quad's first corner alone and copies to the others only for
 * a draw that uploads them. The corners' normals tilt, so the lit colours are far from affine
 * and the shader path draws the quads: each must show its own material, interpolated by the
 * mean value weights. A directional light along z with no ambient lights a corner with its
 * material times n_z. */
static void scene_quad_materials(pt_run *r)
{
    static const float mat[3][4] = {{0.9f, 0.3f, 0.2f, 1}, {0.2f, 0.8f, 0.3f, 1}, {0.3f, 0.4f, 0.9f, 1}};
    float lit[3][4][4];
    pt_begin_frame();
    light_along_z(); /* the material's specular is GL's default, black */
    glBegin(GL_QUADS);
    for (int q = 0; q < 3; q++) {
        glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, mat[q]);
        for (int i = 0; i < 4; i++) {
            tilted_normal(i);
            glVertex2fv(Q[q][i]);
            for (int k = 0; k < 3; k++)
                lit[q][i][k] = mat[q][k] * tilt_nz[i];
            lit[q][i][3] = 1;
        }
    }
    glEnd();
    for (int q = 0; q < 3; q++)
        pt_expect(r, Q[q], lit[q], 0);
    glDisable(GL_LIGHTING);
    r->checks_reference = 1;
    r->min_quads = 3;
}

/* The material state as values to compare with the driver's (bit patterns of the floats). */
static void material_values(pt_run *r)
{
    static const GLenum pnames[] = {GL_AMBIENT, GL_DIFFUSE, GL_SPECULAR, GL_EMISSION};
    for (int f = 0; f < 2; f++)
        for (int k = 0; k < 4; k++) {
            float m[4];
            glGetMaterialfv(f ? GL_BACK : GL_FRONT, pnames[k], m);
            for (int i = 0; i < 4; i++) {
                uint32_t bits;
                memcpy(&bits, &m[i], sizeof bits);
                pt_value(r, bits);
            }
        }
}

/* Unlit primitives that set a material per quad (as programs that share code between lit and
 * unlit passes do): batched like any other, the materials still reach the driver in their order
 * (also against glColor under colour material), and a lit quad drawn afterwards has the last. */
static void scene_unlit_materials(pt_run *r)
{
    static const float dir[4] = {0, 0, 1, 0};
    uint64_t before[PT_NCOUNTERS];
    float v[4][2], c[4][4], m[4] = {0, 0, 0, 1}, lit[4][4];
    pt_begin_frame();
    glEnable(GL_COLOR_MATERIAL); /* lighting off: glColor still sets the tracked material */
    glColorMaterial(GL_FRONT, GL_DIFFUSE);
    cell_quad(0, v);
    cell_colours(0, c);
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glColor4fv(c[i]);
        if (i == 1) {
            const float spec[4] = {0.1f, 0.2f, 0.3f, 1};
            glMaterialfv(GL_FRONT, GL_DIFFUSE, spec); /* the next glColor overrides it */
            glMaterialfv(GL_BACK, GL_SPECULAR, spec);
        }
        glVertex2fv(v[i]);
    }
    glEnd();
    pt_expect(r, v, c, 0);
    glDisable(GL_COLOR_MATERIAL);
    material_values(r);
    pt_counters(before);
    for (int k = 1; k < 20; k++) {
        cell_quad(k, v);
        cell_colours(k, c);
        for (int i = 0; k % 2 == 0 && i < 4; i++) /* even cells in one colour */
            memcpy(c[i], c[0], sizeof c[i]);
        for (int i = 0; i < 3; i++)
            m[i] = 0.75f * c[0][i];
        glBegin(GL_QUADS);
        glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, m);
        for (int i = 0; i < 4; i++) {
            glColor4fv(c[i]);
            if (i == 2 && k % 3 == 0)
                glMaterialf(GL_FRONT, GL_SHININESS, (float)k);
            glVertex2fv(v[i]);
        }
        glEnd();
        pt_expect(r, v, c, 0);
        if (k % 5 == 0)
            glMaterialfv(GL_BACK, GL_EMISSION, m); /* outside, between primitives */
    }
    uint64_t d = draws_since(before);
    if (d > 2)
        snprintf(r->failure, sizeof r->failure, "19 unlit primitives with materials took %llu draws",
                 (unsigned long long)d);
    material_values(r);
    glEnable(GL_LIGHTING);
    glEnable(GL_LIGHT0);
    glLightfv(GL_LIGHT0, GL_POSITION, dir);
    glNormal3f(0, 0, 1);
    cell_quad(22, v);
    for (int i = 0; i < 4; i++) {
        for (int k = 0; k < 3; k++)
            lit[i][k] = 1.2f * m[k];
        lit[i][3] = 1;
    }
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++)
        glVertex2fv(v[i]);
    glEnd();
    pt_expect(r, v, lit, 0);
    glDisable(GL_LIGHT0);
    glDisable(GL_LIGHTING);
    r->checks_reference = 1;
    r->min_quads = 21;
}

static void scene_polygon_line(pt_run *r)
{
    pt_begin_frame();
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    for (int q = 0; q < 3; q++)
        quad_immediate(q, 0, 0);
    strip_immediate();
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    r->native_equal = 1;
    r->min_quads = 5;
}

/* A parallelogram with affine colours (c3 = c0 + c2 - c1): the driver's split is exact. */
static const float P[4][2] = {{-0.8f, -0.7f}, {0.5f, -0.8f}, {0.8f, 0.6f}, {-0.5f, 0.7f}};
static const float PC[4][4] = {{0.2f, 0.3f, 0.4f, 1}, {0.6f, 0.3f, 0.2f, 1}, {0.7f, 0.6f, 0.3f, 1}, {0.3f, 0.6f, 0.5f, 1}};

static void scene_lighting(pt_run *r)
{
    static const float dir[4] = {0.3f, 0.4f, 1.0f, 0.0f}, white[4] = {0.8f, 0.8f, 0.8f, 1};
    pt_begin_frame();
    glEnable(GL_LIGHTING);
    glEnable(GL_LIGHT0);
    glLightfv(GL_LIGHT0, GL_POSITION, dir);
    glLightfv(GL_LIGHT0, GL_DIFFUSE, white);
    glEnable(GL_COLOR_MATERIAL);
    glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
    glBegin(GL_QUADS);
    glNormal3f(0, 0, 1);
    for (int i = 0; i < 4; i++) {
        glColor4fv(PC[i]);
        glVertex2fv(P[i]);
    }
    glEnd();
    glDisable(GL_COLOR_MATERIAL);
    glDisable(GL_LIGHTING);
    r->native_equal = 1;
    r->min_quads = 1;
}

static void scene_texture(pt_run *r)
{
    GLubyte tex[8][8][4];
    GLuint name;
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++) {
            GLubyte v = ((x ^ y) & 1) ? 230 : 40;
            tex[y][x][0] = v, tex[y][x][1] = (GLubyte)(255 - v), tex[y][x][2] = 128, tex[y][x][3] = 255;
        }
    pt_begin_frame();
    name = texture_2d(8, 8, tex, GL_LINEAR);
    glEnable(GL_TEXTURE_2D);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    glBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        glColor4fv(PC[i]);
        glTexCoord2f(i == 1 || i == 2 ? 2.0f : 0.0f, i >= 2 ? 2.0f : 0.0f);
        glVertex2fv(P[i]);
    }
    glEnd();
    glDisable(GL_TEXTURE_2D);
    glDeleteTextures(1, &name);
    r->native_equal = 1;
    r->min_quads = 1;
}

/* Flat-shaded, lit, textured parallelograms with a glMaterial before each quad's first vertex
 * (rubik's facelets, textured): one colour and one material per quad, so the split can differ
 * only by the texture coordinates, here a 1/128 texel off affine at one corner, within the
 * invisible split's 1/32. auto splits every quad by that bound, and the pixels are the
 * driver's own. */
static void scene_flat_materials(pt_run *r)
{
    static const float dir[4] = {0, 0, 1, 0};
    static const float ambient[4] = {0.2f, 0.2f, 0.2f, 1}, diffuse[4] = {0.8f, 0.8f, 0.8f, 1};
    GLubyte tex[8][8][4];
    uint64_t before[PT_NCOUNTERS], after[PT_NCOUNTERS];
    float v[4][2];
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++) {
            GLubyte c = (GLubyte)(40 + 25 * x);
            tex[y][x][0] = c, tex[y][x][1] = (GLubyte)(220 - 20 * y), tex[y][x][2] = 128, tex[y][x][3] = 255;
        }
    pt_begin_frame();
    GLuint name = texture_2d(8, 8, tex, GL_LINEAR);
    glEnable(GL_TEXTURE_2D);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    glShadeModel(GL_FLAT);
    glEnable(GL_LIGHTING);
    glEnable(GL_LIGHT0);
    glLightfv(GL_LIGHT0, GL_POSITION, dir);
    glNormal3f(0, 0, 1);
    pt_counters(before);
    glBegin(GL_QUADS);
    for (int k = 0; k < 9; k++) {
        const float m[4] = {0.3f + 0.07f * (float)k, 0.8f - 0.05f * (float)k, 0.4f, 1};
        float x0 = -0.875f + 0.625f * (float)(k % 3), y0 = -0.875f + 0.625f * (float)(k / 3);
        v[0][0] = x0, v[0][1] = y0, v[1][0] = x0 + 0.5f, v[1][1] = y0 + 0.0625f; /* exact in floats */
        v[2][0] = x0 + 0.5625f, v[2][1] = y0 + 0.5f, v[3][0] = x0 + 0.0625f, v[3][1] = y0 + 0.4375f;
        glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, m);
        for (int i = 0; i < 4; i++) {
            float s = i == 1 || i == 2 ? 1.0f : 0.0f, t = i >= 2 ? 1.0f : 0.0f;
            glTexCoord2f(s + (i == 2 ? 1.0f / (128 * 8) : 0.0f), t);
            glVertex2fv(v[i]);
        }
    }
    glEnd();
    glFinish();
    if (pt_counters(after) == 0 && (after[PT_SPLIT] - before[PT_SPLIT] != 9 || after[PT_MVC] != before[PT_MVC]))
        snprintf(r->failure, sizeof r->failure, "9 flat lit quads with one material each: %llu split, %llu smooth",
                 (unsigned long long)(after[PT_SPLIT] - before[PT_SPLIT]),
                 (unsigned long long)(after[PT_MVC] - before[PT_MVC]));
    glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT, ambient);
    glMaterialfv(GL_FRONT_AND_BACK, GL_DIFFUSE, diffuse);
    glDisable(GL_LIGHTING);
    glShadeModel(GL_SMOOTH);
    glDisable(GL_TEXTURE_2D);
    glDeleteTextures(1, &name);
    r->native_equal = 1;
    r->min_quads = 9;
}

/* Under GL_REPLACE an alpha texture keeps the primary colour and an RGB one replaces it: a
 * key built for a texture of the other format shows. */
static const GLubyte tex_alpha[4] = {200, 200, 200, 200};
static const GLubyte tex_green[4][3] = {{30, 200, 90}, {30, 200, 90}, {30, 200, 90}, {30, 200, 90}};
static const GLubyte tex_red[4][3] = {{220, 20, 40}, {220, 20, 40}, {220, 20, 40}, {220, 20, 40}};

/* A 2 x 2 image (GL_ALPHA or GL_RGB) for the bound texture, filtered nearest. */
static void tex_image(GLenum format, const void *texels)
{
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)format, 2, 2, 0, format, GL_UNSIGNED_BYTE, texels);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
}

/* Texturing under GL_REPLACE with a colour the alpha texture keeps. */
static void tex_replace_on(void)
{
    glEnable(GL_TEXTURE_2D);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    glColor4f(0.3f, 0.4f, 0.9f, 1);
}

/* An axis-aligned rectangle (x0, y0) to (x1, y1) with the whole texture on it. */
static void tex_rect(float x0, float y0, float x1, float y1)
{
    glBegin(GL_QUADS);
    glTexCoord2f(0, 0), glVertex2f(x0, y0);
    glTexCoord2f(1, 0), glVertex2f(x1, y0);
    glTexCoord2f(1, 1), glVertex2f(x1, y1);
    glTexCoord2f(0, 1), glVertex2f(x0, y1);
    glEnd();
}

/* Textures of different formats swapped by glBindTexture alone, then one re-specified by
 * glTexImage2D under the same name. */
static void scene_texture_formats(pt_run *r)
{
    GLuint names[2];
    pt_begin_frame();
    glGenTextures(2, names);
    glBindTexture(GL_TEXTURE_2D, names[0]);
    tex_image(GL_ALPHA, tex_alpha);
    glBindTexture(GL_TEXTURE_2D, names[1]);
    tex_image(GL_RGB, tex_green);
    tex_replace_on();
    for (int q = 0; q < 4; q++) {
        glBindTexture(GL_TEXTURE_2D, names[q & 1]);
        if (q == 2) /* the alpha texture's name gets an RGB image */
            tex_image(GL_RGB, tex_red);
        tex_rect(q & 1 ? 0.1f : -0.9f, q & 2 ? 0.1f : -0.9f, q & 1 ? 0.9f : -0.1f, q & 2 ? 0.9f : -0.1f);
    }
    glDisable(GL_TEXTURE_2D);
    glDeleteTextures(2, names);
    r->native_equal = 1;
    r->min_quads = 4;
}

/* Texture objects are shared: a second context of the same share group gives the texture
 * this context drew with an image of another format, and this context's next quad must show
 * it (what the library keeps of a texture is per context). */
static void scene_texture_shared(pt_run *r)
{
    static unsigned char other_buffer[4 * 4 * 4];
    OSMesaContext own = OSMesaGetCurrentContext(), other;
    GLint w = 0, h = 0, format = 0;
    void *buffer = NULL;
    GLuint name;
    if (!own || !OSMesaGetColorBuffer(own, &w, &h, &format, &buffer)) {
        snprintf(r->failure, sizeof r->failure, "no current OSMesa context to share with");
        return;
    }
    pt_begin_frame();
    glGenTextures(1, &name);
    glBindTexture(GL_TEXTURE_2D, name);
    tex_image(GL_ALPHA, tex_alpha);
    tex_replace_on();
    tex_rect(-0.9f, -0.9f, 0.9f, -0.1f);
    other = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, own);
    if (!other || !OSMesaMakeCurrent(other, other_buffer, GL_UNSIGNED_BYTE, 4, 4)) {
        snprintf(r->failure, sizeof r->failure, "no second OSMesa context");
        return;
    }
    glBindTexture(GL_TEXTURE_2D, name);
    tex_image(GL_RGB, tex_red);
    glFinish();
    OSMesaMakeCurrent(own, buffer, GL_UNSIGNED_BYTE, w, h);
    OSMesaDestroyContext(other);
    tex_rect(-0.9f, 0.1f, 0.9f, 0.9f);
    glDisable(GL_TEXTURE_2D);
    glDeleteTextures(1, &name);
    r->native_equal = 1;
    r->min_quads = 2;
}

/* glEvalMesh2(GL_FILL) of a bilinear patch (order 2 x 2) with a colour map: its quads are
 * the grid cells, each non-affine in colour, so they come out smooth. */
static void scene_eval(pt_run *r)
{
    static const float pts[2][2][3] = {{{-0.8f, -0.8f, 0}, {-0.7f, 0.8f, 0}}, {{0.8f, -0.6f, 0}, {0.6f, 0.7f, 0}}};
    static const float cols[2][2][4] = {{{1, 0, 0, 1}, {0, 0, 1, 1}}, {{0, 1, 0, 1}, {1, 1, 1, 1}}};
    float cur[4];
    pt_begin_frame();
    glMap2f(GL_MAP2_VERTEX_3, 0, 1, 6, 2, 0, 1, 3, 2, &pts[0][0][0]);
    glMap2f(GL_MAP2_COLOR_4, 0, 1, 8, 2, 0, 1, 4, 2, &cols[0][0][0]);
    glEnable(GL_MAP2_VERTEX_3);
    glEnable(GL_MAP2_COLOR_4);
    glMapGrid2f(2, 0.0f, 1.0f, 2, 0.0f, 1.0f);
    glColor3f(0.5f, 0.25f, 0.125f);
    glEvalMesh2(GL_FILL, 0, 2, 0, 2);
    glDisable(GL_MAP2_VERTEX_3);
    glDisable(GL_MAP2_COLOR_4);
    /* Evaluators leave the current colour alone (its red, green and blue here: Mesa 22 leaves
     * the current alpha at 0 after glEvalMesh2, which the specification does not allow). */
    glGetFloatv(GL_CURRENT_COLOR, cur);
    for (int i = 0; i < 3; i++)
        pt_value(r, (uint32_t)(cur[i] * 1000.0f));
    /* Cell (i, j) has corners (u_i, v_j), (u_i, v_j+1), (u_i+1, v_j+1), (u_i+1, v_j): quad k
     * of row j's strip. Position and colour are bilinear in (u, v) on the patch. */
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            static const int du[4] = {0, 0, 1, 1}, dv[4] = {0, 1, 1, 0};
            float v[4][2], c[4][4];
            for (int k = 0; k < 4; k++) {
                float u = 0.5f * (float)(i + du[k]), w = 0.5f * (float)(j + dv[k]);
                float b[2][2] = {{(1 - u) * (1 - w), (1 - u) * w}, {u * (1 - w), u * w}};
                memset(v[k], 0, sizeof v[k]);
                memset(c[k], 0, sizeof c[k]);
                for (int a = 0; a < 2; a++)
                    for (int e = 0; e < 2; e++) {
                        for (int m = 0; m < 2; m++)
                            v[k][m] += b[a][e] * pts[a][e][m];
                        for (int m = 0; m < 4; m++)
                            c[k][m] += b[a][e] * cols[a][e][m];
                    }
            }
            pt_expect(r, v, c, 0);
        }
    r->checks_reference = 1;
    r->min_quads = 4;
}

/* ---- misuse: the driver's own errors ----------------------------------------------------------- */

static void scene_errors(pt_run *r)
{
    float cur[4];
    pt_begin_frame();
    glBegin(GL_QUADS);
    glBegin(GL_QUADS); /* nested: GL_INVALID_OPERATION */
    glVertex2fv(Q[0][0]);
    glVertex2fv(Q[0][1]);
    glVertex2fv(Q[0][2]);
    glVertex2fv(Q[0][3]);
    glEnd();
    pt_value(r, glGetError());
    pt_value(r, glGetError());
    glEnd(); /* no glBegin: GL_INVALID_OPERATION */
    pt_value(r, glGetError());
    glVertex2f(0, 0); /* outside: no error */
    pt_value(r, glGetError());
    glBegin(GL_QUADS); /* 5 vertices: the last is dropped silently */
    for (int i = 0; i < 5; i++)
        glVertex2fv(Q[1][i % 4]);
    glEnd();
    pt_value(r, glGetError());
    glBegin(GL_QUAD_STRIP); /* 3 vertices: nothing */
    glVertex2fv(S[0]);
    glVertex2fv(S[1]);
    glVertex2fv(S[2]);
    glEnd();
    pt_value(r, glGetError());
    glBegin(0x7777); /* GL_INVALID_ENUM */
    pt_value(r, glGetError());
    glBegin(GL_QUADS);
    glEndList(); /* a list command inside glBegin/glEnd: GL_INVALID_OPERATION */
    glEnd();
    pt_value(r, glGetError());
    glCallLists(1, 0x1234, "x"); /* GL_INVALID_ENUM */
    pt_value(r, glGetError());
    glBegin(GL_QUADS);
    glColor3f(0.25f, 0.5f, 1.0f);
    glEnd();
    glGetFloatv(GL_CURRENT_COLOR, cur);
    for (int i = 0; i < 4; i++)
        pt_value(r, (uint32_t)(cur[i] * 1000.0f));
    pt_value(r, glGetError());
    r->native_equal = 1;
    r->min_quads = 2;
}

/* ---- ten million vertices in one glBegin/glEnd ------------------------------------------------------- */

static long max_rss_kb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

static void scene_big(pt_run *r)
{
    const int n = 2500000; /* quads: 10 million vertices */
    long before;
    pt_begin_frame();
    before = max_rss_kb();
    glBegin(GL_QUADS);
    for (int k = 0; k < n; k++) {
        int cell = k % (PT_W * PT_H / 4);
        float x = (float)(cell % (PT_W / 2)) / (PT_W / 4) - 1.0f, y = (float)(cell / (PT_W / 2)) / (PT_H / 4) - 1.0f;
        float d = 2.0f / (PT_W / 2);
        glColor3ub((GLubyte)(k * 7), (GLubyte)(k * 13), (GLubyte)(k * 3));
        glVertex2f(x, y);
        glVertex2f(x + d, y);
        glVertex2f(x + d, y + d);
        glVertex2f(x, y + d);
    }
    glEnd();
    /* Held as captured vertices the primitive would need 1.3 GB; bounded chunks, a few MB.
     * (Only ours is judged: the driver's own growth depends on how far behind its
     * rasterizer threads are.) */
    long grown = max_rss_kb() - before;
    if (pt_preloaded() && grown >= 200 * 1024)
        snprintf(r->failure, sizeof r->failure, "10M vertices in one primitive grew the process by %ld MB",
                 grown / 1024);
    r->native_equal = 1;
    r->min_quads = n;
}

static const pt_scene scenes[] = {
    {"immediate", scene_immediate},
    {"partial", scene_partial},
    {"arrays", scene_arrays},
    {"buffers", scene_buffers},
    {"lists", scene_lists},
    {"lists_explicit", scene_lists_explicit},
    {"lists_states", scene_lists_states},
    {"flat", scene_flat},
    {"flat_lit", scene_flat_lit},
    {"polygon_line", scene_polygon_line},
    {"lighting", scene_lighting},
    {"texture", scene_texture},
    {"texture_formats", scene_texture_formats},
    {"texture_shared", scene_texture_shared},
    {"eval", scene_eval},
    {"errors", scene_errors},
    {"big", scene_big},
    {"batches", scene_batches},
    {"batch_states", scene_batch_states},
    {"batch_draws", scene_batch_draws},
    {"batch_direct", scene_batch_direct},
    {"materials", scene_materials},
    {"material_change", scene_material_change},
    {"quad_materials", scene_quad_materials},
    {"flat_materials", scene_flat_materials},
    {"unlit_materials", scene_unlit_materials},
    {"list_strips", scene_list_strips},
    {"list_grid", scene_list_grid},
    {"strip_blend", scene_strip_blend},
    {"list_depth", scene_list_depth},
};

int main(int argc, char **argv)
{
    return pt_main(argc, argv, scenes, (int)(sizeof scenes / sizeof scenes[0]));
}
