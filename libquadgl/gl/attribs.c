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

void qgl__attrib_array(struct qgl__gl *gl, int a, int on, const void *ptr)
{
    int floats = qgl__attribs[a].floats;
    switch (a) {
    case QGL__AT_COLOR: gl->ColorPointer(floats, GL_FLOAT, 0, ptr); break;
    case QGL__AT_NORMAL: gl->NormalPointer(GL_FLOAT, 0, ptr); break;
    case QGL__AT_COLOR2: gl->SecondaryColorPointer(floats, GL_FLOAT, 0, ptr); break;
    case QGL__AT_FOG: gl->FogCoordPointer(GL_FLOAT, 0, ptr); break;
    default:
        gl->ClientActiveTexture(GL_TEXTURE0 + (GLenum)qgl__attribs[a].unit);
        gl->TexCoordPointer(floats, GL_FLOAT, 0, ptr);
    }
    if (on)
        gl->EnableClientState(qgl__attribs[a].array);
    else
        gl->DisableClientState(qgl__attribs[a].array);
}
