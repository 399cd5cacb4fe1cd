/* attribs.c: the vertex attributes' table and the two calls that differ per attribute.
 *
 * QGL__ATTRIBS (gl_internal.h) lists the attributes once; this file turns it into the table
 * the rest of the layer walks, and holds the only places where an attribute needs its own GL
 * entry point: setting the driver's current value and pointing a client array at it. */
#include "gl_internal.h"

#define QGL__AT_ROW(name, floats, current, array, normalized) \
    {floats, current, array, normalized, QGL__AT_##name >= QGL__AT_TEX0 ? QGL__AT_##name - QGL__AT_TEX0 : -1},
const qgl__attrib_info qgl__attribs[QGL__NATTR] = {QGL__ATTRIBS(QGL__AT_ROW)};
#undef QGL__AT_ROW

void qgl__set_current(struct qgl__gl *gl, int a, const float *v)
{
    switch (a) {
    case QGL__AT_COLOR: gl->Color4fv(v); break;
    case QGL__AT_NORMAL: gl->Normal3fv(v); break;
    case QGL__AT_COLOR2: gl->SecondaryColor3fv(v); break;
    case QGL__AT_FOG: gl->FogCoordf(v[0]); break;
    default: gl->MultiTexCoord4fv(GL_TEXTURE0 + (GLenum)qgl__attribs[a].unit, v); break;
    }
}

/* Attribute a's array enabled from ptr, or disabled; *enabled is what the VAO holds, so that
 * an array disabled already costs no call (its pointer is never read): a program's list
 * calls point the arrays again for each list, and most of the eight attribute arrays stay off. */
static void attrib_array(struct qgl__gl *gl, unsigned *enabled, int a, int on, const void *ptr)
{
    int floats = qgl__attribs[a].floats;
    unsigned bit = 1u << a;
    if (!on && !(*enabled & bit))
        return;
    if (qgl__attribs[a].unit >= 0)
        gl->ClientActiveTexture(GL_TEXTURE0 + (GLenum)qgl__attribs[a].unit);
    if (!on) {
        gl->DisableClientState(qgl__attribs[a].array);
        *enabled &= ~bit;
        return;
    }
    switch (a) {
    case QGL__AT_COLOR: gl->ColorPointer(floats, GL_FLOAT, 0, ptr); break;
    case QGL__AT_NORMAL: gl->NormalPointer(GL_FLOAT, 0, ptr); break;
    case QGL__AT_COLOR2: gl->SecondaryColorPointer(floats, GL_FLOAT, 0, ptr); break;
    case QGL__AT_FOG: gl->FogCoordPointer(GL_FLOAT, 0, ptr); break;
    default: gl->TexCoordPointer(floats, GL_FLOAT, 0, ptr);
    }
    if (!(*enabled & bit))
        gl->EnableClientState(qgl__attribs[a].array);
    *enabled |= bit;
}

void qgl__point_arrays(qgl_context *ctx, unsigned mask, size_t pos, const size_t off[QGL__NATTR], size_t edge)
{
    struct qgl__gl *gl = &ctx->gl;
    gl->VertexPointer(4, GL_FLOAT, 0, (const void *)(uintptr_t)pos);
    gl->EnableClientState(GL_VERTEX_ARRAY);
    for (int a = 0; a < QGL__NATTR; a++)
        attrib_array(gl, &ctx->vao_arrays, a, (mask >> a) & 1, (const void *)(uintptr_t)off[a]);
    if (mask & QGL__A_EDGE) {
        gl->EdgeFlagPointer(0, (const void *)(uintptr_t)edge);
        if (!(ctx->vao_arrays & QGL__A_EDGE))
            gl->EnableClientState(GL_EDGE_FLAG_ARRAY);
    } else if (ctx->vao_arrays & QGL__A_EDGE) {
        gl->DisableClientState(GL_EDGE_FLAG_ARRAY);
    }
    ctx->vao_arrays = (ctx->vao_arrays & ~(unsigned)QGL__A_EDGE) | (mask & QGL__A_EDGE);
}
