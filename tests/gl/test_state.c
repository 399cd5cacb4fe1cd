/* test_state: state hygiene and glGetError parity.
 *
 * The application's program, vertex array object, buffer bindings, active and client-active
 * texture, client arrays, polygon mode and matrices are queried before and after quads drawn
 * on every path (shader, split, fallback, pass-through, batch) and must be unchanged; the
 * current colour, normal and texture coordinates must equal the last values given inside
 * qglBegin/qglEnd (and be untouched by the batch call). Misuse must leave the same error the
 * native driver leaves for the same sequence. */
#include <stdio.h>
#include <string.h>

#include "scenes.h"

typedef struct snap {
    GLint program, vao, abuf, ebuf, active, client, poly[2], varr, carr, tarr, vsize, mode;
    float mv[16], col[4], nrm[4], tex[4];
    void *vptr;
} snap;

static void take(snap *s)
{
    memset(s, 0, sizeof *s);
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &s->abuf);
    glGetIntegerv(GL_ELEMENT_ARRAY_BUFFER_BINDING, &s->ebuf);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &s->active);
    glGetIntegerv(GL_CLIENT_ACTIVE_TEXTURE, &s->client);
    glGetIntegerv(GL_POLYGON_MODE, s->poly);
    glGetIntegerv(GL_MATRIX_MODE, &s->mode);
    s->varr = glIsEnabled(GL_VERTEX_ARRAY);
    s->carr = glIsEnabled(GL_COLOR_ARRAY);
    s->tarr = glIsEnabled(GL_TEXTURE_COORD_ARRAY);
    glGetIntegerv(GL_VERTEX_ARRAY_SIZE, &s->vsize);
    glGetPointerv(GL_VERTEX_ARRAY_POINTER, &s->vptr);
    glGetFloatv(GL_MODELVIEW_MATRIX, s->mv);
    glGetFloatv(GL_CURRENT_COLOR, s->col);
    glGetFloatv(GL_CURRENT_NORMAL, s->nrm);
    glGetFloatv(GL_CURRENT_TEXTURE_COORDS, s->tex);
}

static int same_binding_state(const snap *a, const snap *b)
{
    return a->program == b->program && a->vao == b->vao && a->abuf == b->abuf && a->ebuf == b->ebuf &&
           a->active == b->active && a->client == b->client && a->poly[0] == b->poly[0] &&
           a->poly[1] == b->poly[1] && a->varr == b->varr && a->carr == b->carr && a->tarr == b->tarr &&
           a->vsize == b->vsize && a->vptr == b->vptr && a->mode == b->mode && !memcmp(a->mv, b->mv, sizeof a->mv);
}

static const float last_col[4] = {0.25f, 0.5f, 0.75f, 1}, last_nrm[3] = {0, 0.6f, 0.8f}, last_tex[2] = {0.125f, 0.375f};

/* One non-affine quad through qgl, ending on known last attribute values. */
static void draw_quad(void)
{
    static const float p[4][3] = {{-0.8f, -0.8f, 0}, {0.8f, -0.7f, 0}, {0.7f, 0.8f, 0.3f}, {-0.75f, 0.6f, 0}};
    qglBegin(GL_QUADS);
    for (int i = 0; i < 4; i++) {
        qglColor4f(i & 1 ? 1.0f : 0.0f, i & 2 ? 1.0f : 0.0f, 0.5f, 1);
        qglNormal3f(0, 0, 1);
        qglTexCoord2f((float)(i & 1), (float)(i >> 1));
        if (i == 3) {
            qglColor4fv(last_col);
            qglNormal3fv(last_nrm);
            qglTexCoord2fv(last_tex);
        }
        qglVertex3fv(p[i]);
    }
    qglEnd();
}

static void draw_batch(void)
{
    static const float pos[8] = {-0.5f, -0.5f, 0.5f, -0.4f, 0.4f, 0.5f, -0.4f, 0.3f};
    static const unsigned char col[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
    qgl_quad_batch b = {.topology = QGL_QUADS, .count = 4};
    b.position = (qgl_attrib){pos, 2, GL_FLOAT, 0};
    b.color = (qgl_attrib){col, 4, GL_UNSIGNED_BYTE, 0};
    th_check(qgl_draw_quads(qgl_gl_current(), &b) == 1, "batch draw failed");
}

static void check_path(const char *name, void (*setup)(void), void (*undo)(void), qgl_method method, int batch)
{
    static float app_array[12];
    GLuint vao, buf[2];
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(2, buf);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buf[1]);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(3, GL_FLOAT, 0, app_array);
    glBindBuffer(GL_ARRAY_BUFFER, buf[0]);
    glActiveTexture(GL_TEXTURE2);
    glClientActiveTexture(GL_TEXTURE1);
    glMatrixMode(GL_PROJECTION);
    glColor4f(0.9f, 0.8f, 0.7f, 0.6f);
    if (setup)
        setup();
    qgl_gl_set_method(qgl_gl_current(), method);
    snap before, after;
    take(&before);
    while (glGetError() != GL_NO_ERROR)
        ;
    if (batch)
        draw_batch();
    else
        draw_quad();
    GLenum err = glGetError();
    take(&after);
    th_check(same_binding_state(&before, &after), "%s: bindings or client state changed", name);
    th_check(err == GL_NO_ERROR, "%s: the draw raised GL error %#x", name, err);
    if (batch) {
        th_check(!memcmp(before.col, after.col, sizeof before.col), "%s: batch changed the current colour", name);
    } else {
        th_check(!memcmp(after.col, last_col, sizeof last_col), "%s: current colour is not the last given", name);
        th_check(!memcmp(after.nrm, last_nrm, sizeof last_nrm), "%s: current normal is not the last given", name);
        /* the current texture coordinates of unit 2 (active) are not ours: check unit 0 */
        float tex0[4];
        glActiveTexture(GL_TEXTURE0);
        glGetFloatv(GL_CURRENT_TEXTURE_COORDS, tex0);
        glActiveTexture(GL_TEXTURE2);
        th_check(tex0[0] == last_tex[0] && tex0[1] == last_tex[1], "%s: current texcoord is not the last given", name);
    }
    printf("%-22s state %s, error %#x\n", name, same_binding_state(&before, &after) ? "kept" : "CHANGED", err);
    if (undo)
        undo();
    glDisableClientState(GL_VERTEX_ARRAY);
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(2, buf);
    glActiveTexture(GL_TEXTURE0);
    glClientActiveTexture(GL_TEXTURE0);
    glMatrixMode(GL_MODELVIEW);
}

static GLuint app_program;
static void use_app_program(void) { glUseProgram(app_program); }
static void unuse_app_program(void) { glUseProgram(0); }
static void line_mode(void) { glPolygonMode(GL_FRONT_AND_BACK, GL_LINE); }
static void fill_mode(void) { glPolygonMode(GL_FRONT_AND_BACK, GL_FILL); }
static void lighting(void) { glEnable(GL_LIGHTING); }
static void no_lighting(void) { glDisable(GL_LIGHTING); }

static GLuint make_program(void)
{
    static const char *vs = "#version 120\nvoid main() { gl_Position = ftransform(); gl_FrontColor = gl_Color; }\n";
    static const char *fs = "#version 120\nvoid main() { gl_FragColor = gl_Color.bgra; }\n";
    GLuint p = glCreateProgram(), v = glCreateShader(GL_VERTEX_SHADER), f = glCreateShader(GL_FRAGMENT_SHADER);
    glShaderSource(v, 1, &vs, NULL);
    glShaderSource(f, 1, &fs, NULL);
    glCompileShader(v);
    glCompileShader(f);
    glAttachShader(p, v);
    glAttachShader(p, f);
    glLinkProgram(p);
    return p;
}

/* ---- error parity --------------------------------------------------------------------------- */

typedef struct ops {
    void (*begin)(GLenum);
    void (*end)(void);
    void (*vertex)(GLfloat, GLfloat);
} ops;

static void native_begin(GLenum m) { glBegin(m); }
static void native_end(void) { glEnd(); }
static void native_vertex(GLfloat x, GLfloat y) { glVertex2f(x, y); }
static void qgl_begin(GLenum m) { qglBegin(m); }
static void qgl_end(void) { qglEnd(); }
static void qgl_vertex(GLfloat x, GLfloat y) { qglVertex2f(x, y); }

/* Run misuse sequence k with o; return the errors read after each step, packed. */
static unsigned long long sequence(const ops *o, int k)
{
    unsigned long long errs = 0;
    while (glGetError() != GL_NO_ERROR)
        ;
#define STEP(code) do { code; errs = errs * 0x10000 + (glGetError() & 0xffff); } while (0)
    switch (k) {
    case 0: /* glBegin inside glBegin (glGetError itself is misuse inside a primitive) */
        STEP((o->begin(GL_QUADS), o->begin(GL_QUADS), o->vertex(0, 0), o->vertex(1, 0), o->vertex(1, 1),
              o->vertex(0, 1), o->end()));
        STEP(o->end());
        break;
    case 1: /* glEnd without glBegin */
        STEP(o->end());
        STEP(o->end());
        break;
    case 2: /* bad mode, then its vertices and end */
        STEP(o->begin(0x1234));
        STEP(o->vertex(0, 0));
        STEP(o->end());
        break;
    case 3: /* a quad inside a triangle primitive */
        STEP((o->begin(GL_TRIANGLES), o->begin(GL_QUAD_STRIP), o->end()));
        STEP(o->end());
        break;
    case 4: /* a valid quad, strip and an incomplete quad */
        STEP((o->begin(GL_QUADS), o->vertex(0, 0), o->vertex(1, 0), o->vertex(1, 1), o->vertex(0, 1),
              o->vertex(0.5f, 0.5f), o->end()));
        STEP((o->begin(GL_QUAD_STRIP), o->vertex(0, 0), o->vertex(1, 0), o->vertex(1, 1), o->end()));
        break;
    }
#undef STEP
    return errs;
}

int main(void)
{
    th_ctx t;
    int rc = th_init(&t, 64, 64, NULL);
    if (rc)
        return rc;
    app_program = make_program();
    check_path("mvc", NULL, NULL, QGL_METHOD_MVC, 0);
    check_path("split", NULL, NULL, QGL_METHOD_SPLIT, 0);
    check_path("subdiv", NULL, NULL, QGL_METHOD_SUBDIV, 0);
    check_path("auto", NULL, NULL, QGL_METHOD_AUTO, 0);
    check_path("lighting (fallback)", lighting, no_lighting, QGL_METHOD_MVC, 0);
    check_path("app program", use_app_program, unuse_app_program, QGL_METHOD_MVC, 0);
    check_path("polygon line", line_mode, fill_mode, QGL_METHOD_MVC, 0);
    check_path("batch mvc", NULL, NULL, QGL_METHOD_MVC, 1);
    check_path("batch subdiv", NULL, NULL, QGL_METHOD_SUBDIV, 1);

    static const ops native = {native_begin, native_end, native_vertex}, ours = {qgl_begin, qgl_end, qgl_vertex};
    for (int k = 0; k < 5; k++) {
        unsigned long long a = sequence(&native, k), b = sequence(&ours, k);
        printf("error sequence %d: native %016llx, qgl %016llx\n", k, a, b);
        th_check(a == b, "error sequence %d differs", k);
    }
    th_free(&t);
    return th_failures ? 1 : 0;
}
