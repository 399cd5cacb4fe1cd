/* test_array_element: qglArrayElement inside captured quads equals the same quads given call by call.
 *
 * A jittered, non-planar grid of quads with random colours and texture coordinates (a
 * texture on, MODULATE; depth test on) is drawn twice through the shader path: once with
 * qglColor4ub / qglTexCoord2f / qglVertex3f per vertex (the reference), once with
 * qglArrayElement reading the application's enabled client arrays. Both captures hold the
 * same floats (an unsigned byte colour converts as c / 255 either way), so the pictures must
 * be identical (tolerance 0) and both must have taken the shader path for every quad. The
 * arrays come three ways: client memory with tight packing (RGBA colours), one interleaved
 * buffer object with a stride and offsets (BGRA colours, which GL swizzles), and client
 * memory again with a texture coordinate array on unit 1 that only the current value after
 * qglEnd can reveal. GL_QUADS and GL_QUAD_STRIP both. Afterwards the application's client
 * state is as it was (arrays enabled, pointers, buffer binding, client active unit) and the
 * current colour and texture coordinates are those of the last element fed. Outside a
 * captured primitive the call goes to the driver: inside a forwarded GL_TRIANGLES it draws
 * exactly what the native glArrayElement draws, and outside glBegin/glEnd, with only the
 * colour array enabled, it sets the current colour as the native call does. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"

enum { N = 8 };

/* One vertex as the buffer object holds it: 24 bytes, colour in BGRA order. */
typedef struct packed {
    float pos[3];
    unsigned char bgra[4];
    float uv[2];
} packed;

typedef struct arrays {
    int n;
    float pos[SC_MAX][3], uv[SC_MAX][2], uv1[SC_MAX][2];
    unsigned char rgba[SC_MAX][4];
    packed inter[SC_MAX];
} arrays;

static void fill(arrays *a, const sc_mesh *m)
{
    a->n = m->nverts;
    for (int i = 0; i < m->nverts; i++) {
        memcpy(a->pos[i], m->pos[i], sizeof a->pos[i]);
        a->uv[i][0] = 2.5f * m->pos[i][0] + 0.3f * m->col[i][0];
        a->uv[i][1] = 1.5f * m->pos[i][1] - 0.4f * m->col[i][1];
        a->uv1[i][0] = (float)i, a->uv1[i][1] = -(float)i;
        for (int k = 0; k < 4; k++)
            a->rgba[i][k] = (unsigned char)(m->col[i][k] * 255.0f + 0.5f);
        memcpy(a->inter[i].pos, a->pos[i], sizeof a->pos[i]);
        memcpy(a->inter[i].uv, a->uv[i], sizeof a->uv[i]);
        a->inter[i].bgra[0] = a->rgba[i][2], a->inter[i].bgra[1] = a->rgba[i][1];
        a->inter[i].bgra[2] = a->rgba[i][0], a->inter[i].bgra[3] = a->rgba[i][3];
    }
}

/* The primitives of m (one GL_QUADS, or one GL_QUAD_STRIP per row), vertex i by feed(i). */
static void draw_mesh(const sc_mesh *m, void (*feed)(const arrays *, int), const arrays *a)
{
    int rows = m->strip_rows ? m->strip_rows : 1, per = m->strip_rows ? m->nverts / rows : m->nverts;
    for (int r = 0; r < rows; r++) {
        qglBegin(m->strip_rows ? GL_QUAD_STRIP : GL_QUADS);
        for (int i = 0; i < per; i++)
            feed(a, r * per + i);
        qglEnd();
    }
}

static void feed_calls(const arrays *a, int i)
{
    qglColor4ub(a->rgba[i][0], a->rgba[i][1], a->rgba[i][2], a->rgba[i][3]);
    qglTexCoord2f(a->uv[i][0], a->uv[i][1]);
    qglVertex3f(a->pos[i][0], a->pos[i][1], a->pos[i][2]);
}

static void feed_element(const arrays *a, int i)
{
    (void)a;
    qglArrayElement(i);
}

/* ---- the three ways of giving arrays ------------------------------------------------------- */

enum { CLIENT, BUFFER, UNIT1, NKINDS };
static const char *const kind_names[NKINDS] = {"client", "buffer", "unit1"};

static GLuint set_arrays(const arrays *a, int kind)
{
    GLuint vbo = 0;
    glEnableClientState(GL_VERTEX_ARRAY);
    glEnableClientState(GL_COLOR_ARRAY);
    glEnableClientState(GL_TEXTURE_COORD_ARRAY);
    if (kind == BUFFER) {
        glGenBuffers(1, &vbo);
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(packed) * (size_t)a->n), a->inter, GL_STATIC_DRAW);
        glVertexPointer(3, GL_FLOAT, sizeof(packed), (const void *)offsetof(packed, pos));
        glColorPointer(GL_BGRA, GL_UNSIGNED_BYTE, sizeof(packed), (const void *)offsetof(packed, bgra));
        glTexCoordPointer(2, GL_FLOAT, sizeof(packed), (const void *)offsetof(packed, uv));
        return vbo;
    }
    glVertexPointer(3, GL_FLOAT, 0, a->pos);
    glColorPointer(4, GL_UNSIGNED_BYTE, 0, a->rgba);
    glTexCoordPointer(2, GL_FLOAT, 0, a->uv);
    if (kind == UNIT1) {
        glClientActiveTexture(GL_TEXTURE1);
        glEnableClientState(GL_TEXTURE_COORD_ARRAY);
        glTexCoordPointer(2, GL_FLOAT, 0, a->uv1);
        glClientActiveTexture(GL_TEXTURE0);
    }
    return 0;
}

static void unset_arrays(GLuint vbo)
{
    glClientActiveTexture(GL_TEXTURE1);
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glClientActiveTexture(GL_TEXTURE0);
    glDisableClientState(GL_VERTEX_ARRAY);
    glDisableClientState(GL_COLOR_ARRAY);
    glDisableClientState(GL_TEXTURE_COORD_ARRAY);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    if (vbo)
        glDeleteBuffers(1, &vbo);
}

typedef struct client_snap {
    GLint abuf, client, vsize, csize;
    GLboolean varr, carr, tarr;
    void *vptr, *cptr;
} client_snap;

static void take(client_snap *s)
{
    memset(s, 0, sizeof *s);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &s->abuf);
    glGetIntegerv(GL_CLIENT_ACTIVE_TEXTURE, &s->client);
    glGetIntegerv(GL_VERTEX_ARRAY_SIZE, &s->vsize);
    glGetIntegerv(GL_COLOR_ARRAY_SIZE, &s->csize);
    s->varr = glIsEnabled(GL_VERTEX_ARRAY);
    s->carr = glIsEnabled(GL_COLOR_ARRAY);
    s->tarr = glIsEnabled(GL_TEXTURE_COORD_ARRAY);
    glGetPointerv(GL_VERTEX_ARRAY_POINTER, &s->vptr);
    glGetPointerv(GL_COLOR_ARRAY_POINTER, &s->cptr);
}

static int close_to(const float *a, const float *b, int n)
{
    for (int k = 0; k < n; k++)
        if (!(a[k] - b[k] < 1e-6f && b[k] - a[k] < 1e-6f))
            return 0;
    return 1;
}

/* The current colour and unit 0 / unit 1 texture coordinates are the last element's. */
static int current_is_last(const arrays *a, int kind)
{
    int l = a->n - 1;
    float col[4], t0[4], t1[4];
    float want_col[4] = {a->rgba[l][0] / 255.0f, a->rgba[l][1] / 255.0f, a->rgba[l][2] / 255.0f,
                         a->rgba[l][3] / 255.0f};
    float want_t0[4] = {a->uv[l][0], a->uv[l][1], 0, 1}, want_t1[4] = {a->uv1[l][0], a->uv1[l][1], 0, 1};
    glGetFloatv(GL_CURRENT_COLOR, col);
    glGetFloatv(GL_CURRENT_TEXTURE_COORDS, t0);
    glActiveTexture(GL_TEXTURE1);
    glGetFloatv(GL_CURRENT_TEXTURE_COORDS, t1);
    glActiveTexture(GL_TEXTURE0);
    return close_to(col, want_col, 4) && close_to(t0, want_t0, 4) && (kind != UNIT1 || close_to(t1, want_t1, 4));
}

static unsigned char *render(th_ctx *t, const sc_mesh *m, const arrays *a, int by_elements, qgl_gl_stats_t *st)
{
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    qgl_gl_reset_stats(t->qgl);
    draw_mesh(m, by_elements ? feed_element : feed_calls, a);
    qgl_gl_stats(t->qgl, st);
    return th_snapshot(t);
}

static void against_calls(th_ctx *t, const sc_mesh *m, const arrays *a, int kind)
{
    const char *topo = m->strip_rows ? "strip" : "quads";
    glMultiTexCoord2f(GL_TEXTURE1, 7, 7);
    qgl_gl_stats_t sr, se;
    unsigned char *ref = render(t, m, a, 0, &sr);
    GLuint vbo = set_arrays(a, kind);
    client_snap before, after;
    take(&before);
    unsigned char *img = render(t, m, a, 1, &se);
    take(&after);
    int current_ok = current_is_last(a, kind);
    GLenum err = glGetError();
    unset_arrays(vbo);
    int over, covered = 0, worst = sc_diff(t, ref, img, 0, &over);
    for (int i = 0; i < t->w * t->h; i++)
        covered += img[4 * i + 3] != 0;
    int kept = !memcmp(&before, &after, sizeof before);
    printf("%-6s %-5s covered %5d, worst %d/255, %d pixels differ; mvc %llu of %llu (calls: %llu of %llu); "
           "client state %s, current %s, error %#x\n",
           kind_names[kind], topo, covered, worst, over, (unsigned long long)se.mvc, (unsigned long long)se.quads,
           (unsigned long long)sr.mvc, (unsigned long long)sr.quads, kept ? "kept" : "CHANGED",
           current_ok ? "last element" : "WRONG", err);
    char name[64];
    snprintf(name, sizeof name, "array_element_%s_%s", kind_names[kind], topo);
    th_write(t, img, name);
    th_check(covered > 10000, "%s %s: too little drawn", kind_names[kind], topo);
    th_check(over == 0, "%s %s: qglArrayElement differs from the calls", kind_names[kind], topo);
    th_check(se.quads == N * N && se.mvc == se.quads && sr.mvc == sr.quads, "%s %s: not all on the shader path",
             kind_names[kind], topo);
    th_check(kept && current_ok && err == GL_NO_ERROR, "%s %s: state after the draw", kind_names[kind], topo);
    free(ref);
    free(img);
}

/* ---- outside a captured primitive ------------------------------------------------------------ */

static void forwarded_triangles(th_ctx *t, const arrays *a)
{
    GLuint vbo = set_arrays(a, CLIENT);
    unsigned char *img[2];
    qgl_gl_reset_stats(t->qgl);
    for (int k = 0; k < 2; k++) {
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        k ? qglBegin(GL_TRIANGLES) : glBegin(GL_TRIANGLES);
        for (int i = 0; i < 3 * (a->n / 3); i++)
            k ? qglArrayElement(i) : glArrayElement(i);
        k ? qglEnd() : glEnd();
        img[k] = th_snapshot(t);
    }
    unset_arrays(vbo);
    qgl_gl_stats_t st;
    qgl_gl_stats(t->qgl, &st);
    int over, covered = 0, worst = sc_diff(t, img[0], img[1], 0, &over);
    for (int i = 0; i < t->w * t->h; i++)
        covered += img[1][4 * i + 3] != 0;
    printf("forwarded triangles: covered %d, worst %d/255, %d pixels differ from native, quads seen %llu\n", covered,
           worst, over, (unsigned long long)st.quads);
    th_check(covered > 1000 && over == 0 && st.quads == 0, "triangles: not forwarded as the native call");
    free(img[0]);
    free(img[1]);
}

static void outside_begin_end(const arrays *a)
{
    float native[4], ours[4];
    glEnableClientState(GL_COLOR_ARRAY);
    glColorPointer(4, GL_UNSIGNED_BYTE, 0, a->rgba);
    glColor4f(0, 0, 0, 0);
    glArrayElement(5);
    glGetFloatv(GL_CURRENT_COLOR, native);
    glColor4f(0, 0, 0, 0);
    qglArrayElement(5);
    glGetFloatv(GL_CURRENT_COLOR, ours);
    glDisableClientState(GL_COLOR_ARRAY);
    GLenum err = glGetError();
    printf("outside glBegin/glEnd: native colour %.3f %.3f %.3f %.3f, ours %.3f %.3f %.3f %.3f, error %#x\n",
           native[0], native[1], native[2], native[3], ours[0], ours[1], ours[2], ours[3], err);
    th_check(!memcmp(native, ours, sizeof ours) && native[3] > 0 && err == GL_NO_ERROR,
             "outside glBegin/glEnd: not forwarded");
}

int main(void)
{
    th_ctx t;
    qgl_gl_desc d = {.method = QGL_METHOD_MVC};
    int rc = th_init(&t, 256, 256, &d);
    if (rc)
        return rc;
    if (qgl_gl_shader_level(t.qgl) == 0) {
        fprintf(stderr, "no shader path on this context\n");
        return 77;
    }
    sc_mesh *m = malloc(sizeof *m);
    arrays *a = malloc(sizeof *a);
    sc_texture(1);
    glEnable(GL_TEXTURE_2D);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    glEnable(GL_DEPTH_TEST);
    glClearColor(0, 0, 0, 0);
    for (int strips = 0; strips < 2; strips++) {
        sc_jitter_grid(m, N, 0.4f, 0.15f, 11u + (unsigned)strips, strips);
        fill(a, m);
        sc_camera(-35, 15);
        for (int kind = 0; kind < NKINDS; kind++)
            against_calls(&t, m, a, kind);
    }
    glDisable(GL_TEXTURE_2D);
    forwarded_triangles(&t, a);
    outside_begin_end(a);
    free(m);
    free(a);
    th_free(&t);
    return th_failures ? 1 : 0;
}
