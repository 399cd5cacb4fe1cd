/* quadgl: the gl layer's public API (included by quadgl/quadgl.h). */
#ifndef QUADGL_GL_H
#define QUADGL_GL_H
#include <quadgl/quadgl.h>
#ifdef __cplusplus
extern "C" {
#endif

#ifdef __cplusplus
}
#endif
#endif
