/* quadgl: the render layer's public API (included by quadgl/quadgl.h). */
#ifndef QUADGL_RENDER_H
#define QUADGL_RENDER_H
#include <quadgl/quadgl.h>
#ifdef __cplusplus
extern "C" {
#endif

#ifdef __cplusplus
}
#endif
#endif
