/* protos.c: preprocessed by the build to give gen_entries.py the system's GL prototypes. */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
