// qgl_image.cpp: the C++ shim between OpenImageIO and the C code (see qgl_image.h).
//
// Reading converts any pixel type to float and flips the rows so that row 0 is the bottom
// (GL texture order); writing lets OIIO quantize floats to 8 bits. Errors are OIIO's own
// messages, copied into the caller's buffer; nothing throws across the C boundary.
#include "qgl_image.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

static int set_error(char *err, size_t errlen, const std::string &msg)
{
    if (err && errlen)
        std::snprintf(err, errlen, "%s", msg.empty() ? "unknown image error" : msg.c_str());
    return -1;
}

extern "C" int qgl_image_load_texture(void *, const char *path, qgl_sw_texture *tex, char *err, size_t errlen)
{
    try {
        auto in = OIIO::ImageInput::open(path);
        if (!in)
            return set_error(err, errlen, OIIO::geterror());
        const OIIO::ImageSpec &spec = in->spec();
        int w = spec.width, h = spec.height, ch = spec.nchannels < 4 ? spec.nchannels : 4;
        if (w <= 0 || h <= 0 || ch <= 0)
            return set_error(err, errlen, "image has no pixels");
        std::vector<float> rows((size_t)w * h * ch);
        if (!in->read_image(0, 0, 0, ch, OIIO::TypeDesc::FLOAT, rows.data()))
            return set_error(err, errlen, in->geterror());
        float *texels = static_cast<float *>(std::malloc(rows.size() * sizeof(float)));
        if (!texels)
            return set_error(err, errlen, "out of memory");
        size_t row = (size_t)w * ch;
        for (int y = 0; y < h; y++)
            std::memcpy(texels + (size_t)(h - 1 - y) * row, rows.data() + (size_t)y * row, row * sizeof(float));
        tex->width = w;
        tex->height = h;
        tex->channels = ch;
        tex->texels = texels;
        return 0;
    } catch (const std::exception &e) {
        return set_error(err, errlen, e.what());
    }
}

extern "C" int qgl_image_write(const char *path, int width, int height, int channels, const float *pixels,
                               char *err, size_t errlen)
{
    try {
        auto out = OIIO::ImageOutput::create(path);
        if (!out)
            return set_error(err, errlen, OIIO::geterror());
        OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
        if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, pixels) || !out->close())
            return set_error(err, errlen, out->geterror());
        return 0;
    } catch (const std::exception &e) {
        return set_error(err, errlen, e.what());
    }
}

extern "C" int qgl_image_write_labeled(const char *path, int width, int height, int channels, const float *pixels,
                                       int nlabels, const int *xy, const char *const *text, int fontsize,
                                       char *err, size_t errlen)
{
    try {
        OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
        OIIO::ImageBuf buf(spec);
        buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, pixels);
        int missing_font = 0;
        std::vector<float> white(channels, 1.0f);
        // OIIO looks for its own fonts first; Debian's DejaVu is the usual fallback.
        const char *font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
        std::FILE *probe = std::fopen(font, "rb");
        if (probe)
            std::fclose(probe);
        for (int i = 0; i < nlabels; i++)
            if (!OIIO::ImageBufAlgo::render_text(buf, xy[2 * i], xy[2 * i + 1], text[i], fontsize, probe ? font : "",
                                                 white))
                missing_font = 1;
        buf.set_write_format(OIIO::TypeDesc::UINT8);
        if (!buf.write(path))
            return set_error(err, errlen, buf.geterror());
        return missing_font;
    } catch (const std::exception &e) {
        return set_error(err, errlen, e.what());
    }
}
