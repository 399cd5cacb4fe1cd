/* demo_emit_qgl.c: demo_emit.c compiled against the GL helper's qgl* immediate API.
 *
 * The whole file is the redirection switch and the shared source: the point of the demo is
 * that a legacy program gets smooth quads by renaming its calls, nothing else. */
#define DEMO_EMIT_QGL 1
#include "demo_emit.c"
