/* qgl_image.h: image files through OpenImageIO, for the benchmark, the tests and scenes.
 *
 * A small C API over a C++ shim (qgl_image.cpp), built as the optional static library
 * quadgl_image when OpenImageIO and a C++ compiler are found (meson: image_dep, which also
 * defines QGL_HAVE_IMAGES). Not part of libquadgl: the library itself stays pure C. */
#ifndef QGL_IMAGE_H
#define QGL_IMAGE_H

#include <stddef.h>
#include <quadgl/quadgl.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A qgl_sw_image_loader: reads any format OIIO knows into float texels, row 0 at the bottom.
 * Returns 0, or -1 with a message in err. */
int qgl_image_load_texture(void *user, const char *path, qgl_sw_texture *tex, char *err, size_t errlen);

/* Writes 8-bit pixels (format from the file name, e.g. .png) from floats in [0, 1], channels
 * per pixel, the first row in memory at the top of the image. Returns 0, or -1 with err. */
int qgl_image_write(const char *path, int width, int height, int channels, const float *pixels, char *err,
                    size_t errlen);

/* The same with text labels drawn on top (white, fontsize pixels, label i's baseline-left
 * corner at xy[2i], xy[2i+1], top-left origin). If no font can be found the image is
 * written without labels and 1 is returned. */
int qgl_image_write_labeled(const char *path, int width, int height, int channels, const float *pixels,
                            int nlabels, const int *xy, const char *const *text, int fontsize, char *err,
                            size_t errlen);

#ifdef __cplusplus
}
#endif
#endif
