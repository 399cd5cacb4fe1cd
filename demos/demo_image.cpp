// demo_image.cpp: quadgl-demo's picture files through OpenImageIO's C++ API, behind a C face.
//
// The demo keeps pictures as 8-bit RGBA with row 0 at the bottom (GL's convention) while
// image files store the top row first, so every transfer walks the rows backwards with a
// negative y stride instead of copying. Reading converts any file to 4 channels (grey is
// replicated, a missing alpha is opaque); textures for the software renderer keep the file's
// own channel count as floats.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "demo_app.h"

using namespace OIIO;

static int fail(char *err, size_t errlen, const std::string &msg)
{
    if (err && errlen)
        std::snprintf(err, errlen, "%s", msg.c_str());
    return -1;
}

int demo_image_write(const char *path, int w, int h, const unsigned char *rgba, char *err, size_t errlen)
{
    auto out = ImageOutput::create(path);
    if (!out)
        return fail(err, errlen, std::string(path) + ": " + OIIO::geterror());
    ImageSpec spec(w, h, 3, TypeDesc::UINT8);
    if (!out->open(path, spec))
        return fail(err, errlen, std::string(path) + ": " + out->geterror());
    const stride_t xs = 4, ys = -(stride_t)w * 4;
    const unsigned char *top = rgba + (size_t)(h - 1) * (size_t)w * 4;
    bool ok = out->write_image(TypeDesc::UINT8, top, xs, ys);
    ok = out->close() && ok;
    return ok ? 0 : fail(err, errlen, std::string(path) + ": " + out->geterror());
}

int demo_image_read(const char *path, int *w, int *h, unsigned char **rgba, char *err, size_t errlen)
{
    auto in = ImageInput::open(path);
    if (!in)
        return fail(err, errlen, std::string(path) + ": " + OIIO::geterror());
    const ImageSpec &spec = in->spec();
    int W = spec.width, H = spec.height, C = spec.nchannels;
    std::vector<unsigned char> file((size_t)W * H * C);
    if (!in->read_image(0, 0, 0, C, TypeDesc::UINT8, file.data()))
        return fail(err, errlen, std::string(path) + ": " + in->geterror());
    unsigned char *px = (unsigned char *)std::malloc((size_t)W * H * 4);
    if (!px)
        return fail(err, errlen, "out of memory");
    for (int y = 0; y < H; y++) {
        const unsigned char *src = file.data() + (size_t)(H - 1 - y) * W * C;
        unsigned char *dst = px + (size_t)y * W * 4;
        for (int x = 0; x < W; x++, src += C, dst += 4) {
            for (int k = 0; k < 3; k++)
                dst[k] = src[C >= 3 ? k : 0];
            dst[3] = C == 2 ? src[1] : C >= 4 ? src[3] : 255;
        }
    }
    *w = W;
    *h = H;
    *rgba = px;
    return 0;
}

int demo_image_load_texture(void *user, const char *path, qgl_sw_texture *tex, char *err, size_t errlen)
{
    (void)user;
    auto in = ImageInput::open(path);
    if (!in)
        return fail(err, errlen, std::string(path) + ": " + OIIO::geterror());
    const ImageSpec &spec = in->spec();
    int W = spec.width, H = spec.height, C = spec.nchannels < 4 ? spec.nchannels : 4;
    float *texels = (float *)std::malloc((size_t)W * H * C * sizeof(float));
    if (!texels)
        return fail(err, errlen, "out of memory");
    const stride_t xs = (stride_t)C * sizeof(float), ys = -(stride_t)W * C * sizeof(float);
    float *top = texels + (size_t)(H - 1) * W * C;
    if (!in->read_image(0, 0, 0, C, TypeDesc::FLOAT, top, xs, ys)) {
        std::free(texels);
        return fail(err, errlen, std::string(path) + ": " + in->geterror());
    }
    tex->width = W;
    tex->height = H;
    tex->channels = C;
    tex->texels = texels;
    return 0;
}
