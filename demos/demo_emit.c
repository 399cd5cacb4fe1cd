/* demo_emit.c: a scene's quads as immediate-mode GL, the way a legacy program draws them.
 *
 * One glBegin(GL_QUADS) .. glEnd() per scene, each corner's attribute given before its
 * vertex: a 2D texture coordinate (textured scenes), the normal as a 3D texture coordinate
 * (Phong scenes, looked up in a cube map that holds the lighting), or a colour. The file is
 * compiled twice: as is, calling the driver's gl* functions, and by demo_emit_qgl.c with the
 * names redirected to the GL helper's qgl* API (which has GL's own signatures), so the
 * native and the smooth pictures come from one and the same drawing code. */
#include <GL/gl.h>

#include "demo_gl.h"

#ifdef DEMO_EMIT_QGL
#define glBegin qglBegin
#define glEnd qglEnd
#define glVertex3d qglVertex3d
#define glTexCoord2f qglTexCoord2f
#define glTexCoord3f qglTexCoord3f
#define glColor4fv qglColor4fv
#define DEMO_EMIT_FN demo_emit_qgl
#else
#define DEMO_EMIT_FN demo_emit_native
#endif

static void emit_corner(const demo_scene *s, int shading, int idx, demo_emit_mode mode)
{
    const qgl_sw_scene *sw = s->sw;
    const float *a = sw->attr + (size_t)idx * (size_t)sw->nattr;
    if (mode == DEMO_EMIT_TEX2) {
        glTexCoord2f(a[0], a[1]);
    } else if (mode == DEMO_EMIT_TEX3) {
        glTexCoord3f(a[0], a[1], a[2]);
    } else {
        float c[4];
        demo_shade(s, shading, a, 1, c);
        glColor4fv(c);
    }
    const double *p = sw->pos + (size_t)idx * 3;
    glVertex3d(p[0], p[1], p[2]);
}

void DEMO_EMIT_FN(const demo_scene *s, const demo_view *v, demo_emit_mode mode)
{
    const qgl_sw_scene *sw = s->sw;
    glBegin(GL_QUADS);
    for (int q = 0; q < sw->nquads; q++)
        for (int k = 0; k < 4; k++)
            emit_corner(s, v->shading, sw->quad[q * 4 + (k + v->order) % 4], mode);
    glEnd();
}
