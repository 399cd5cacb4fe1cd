/* test_leaks.c: a preloaded program for valgrind: everything the library allocates is freed.
 *
 * Immediate quads and strips (in several chunks), array draws from client memory and buffer
 * objects, display lists nested, redefined and deleted, an evaluator mesh, then the context
 * destroyed; before that, a second context that drew quads destroyed while not current. Run under valgrind --leak-check=full with libquadgl-preload.so preloaded; the
 * suppression file leaves out what the driver itself keeps. No child processes (valgrind
 * would not follow them), no pixels checked: test_scenes does that. */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <stdlib.h>

static const float quad[4][2] = {{-0.8f, -0.9f}, {0.7f, -0.6f}, {0.5f, 0.8f}, {-0.9f, 0.5f}};

static void immediate(GLenum mode, int n)
{
    glBegin(mode);
    for (int i = 0; i < n; i++) {
        glColor3ub((GLubyte)i, (GLubyte)(i * 3), 200);
        glVertex2fv(quad[i % 4]);
    }
    glEnd();
}

static void mesh(void)
{
    static const float pts[2][2][3] = {{{-1, -1, 0}, {-1, 1, 0}}, {{1, -1, 0}, {1, 1, 0}}};
    glMap2f(GL_MAP2_VERTEX_3, 0, 1, 6, 2, 0, 1, 3, 2, &pts[0][0][0]);
    glEnable(GL_MAP2_VERTEX_3);
    glMapGrid2f(4, 0.0f, 1.0f, 4, 0.0f, 1.0f);
    glEvalMesh2(GL_FILL, 0, 4, 0, 4);
    glDisable(GL_MAP2_VERTEX_3);
}

int main(void)
{
    unsigned char *buf = malloc(32 * 32 * 4);
    OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 16, 0, 0, NULL);
    OSMesaContext other = OSMesaCreateContextExt(OSMESA_RGBA, 16, 0, 0, NULL);
    GLuint base, vbo;
    if (!buf || !ctx || !other || !OSMesaMakeCurrent(other, buf, GL_UNSIGNED_BYTE, 32, 32))
        return 77;
    immediate(GL_QUADS, 8);
    if (!OSMesaMakeCurrent(ctx, buf, GL_UNSIGNED_BYTE, 32, 32))
        return 77;
    OSMesaDestroyContext(other);
    immediate(GL_QUADS, 70000 * 4); /* more than one chunk */
    immediate(GL_QUAD_STRIP, 10);
    glEnableClientState(GL_VERTEX_ARRAY);
    glVertexPointer(2, GL_FLOAT, 0, quad);
    glDrawArrays(GL_QUADS, 0, 4);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STATIC_DRAW);
    glVertexPointer(2, GL_FLOAT, 0, (void *)0);
    glDrawArrays(GL_QUADS, 0, 4);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glDeleteBuffers(1, &vbo);
    base = glGenLists(3);
    glNewList(base, GL_COMPILE);
    immediate(GL_QUADS, 8);
    glEndList();
    glNewList(base + 1, GL_COMPILE_AND_EXECUTE);
    glCallList(base);
    glVertexPointer(2, GL_FLOAT, 0, quad);
    glDrawArrays(GL_QUADS, 0, 4);
    glEndList();
    glNewList(base, GL_COMPILE); /* redefined: the old recording goes */
    immediate(GL_QUAD_STRIP, 6);
    glEndList();
    glCallList(base + 1);
    glNewList(base + 2, GL_COMPILE); /* left for the context's destruction to free */
    immediate(GL_QUADS, 4);
    glEndList();
    glDeleteLists(base, 2);
    glDisableClientState(GL_VERTEX_ARRAY);
    mesh();
    glFinish();
    OSMesaDestroyContext(ctx);
    free(buf);
    return 0;
}
