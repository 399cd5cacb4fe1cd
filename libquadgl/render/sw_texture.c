/* sw_texture.c: float textures (procedural checkerboards, or images someone else loaded).
 *
 * Sampling follows GL with GL_REPEAT: texel centres at (i + 0.5) / width, nearest picks the
 * texel containing the point, bilinear blends the four texels around it with weights from
 * the fractional position. Texture row 0 is t = 0 (the bottom), as in GL. */
#include "sw_internal.h"

#include <math.h>
#include <stdlib.h>

int qgl_sw_texture_checker(qgl_sw_texture *tex, int size, int checks, float lo, float hi)
{
    if (!tex || size <= 0 || checks <= 0 || size > 16384)
        return QGL_SW_EINVAL;
    tex->width = tex->height = size;
    tex->channels = 1;
    tex->texels = malloc((size_t)size * (size_t)size * sizeof(float));
    if (!tex->texels)
        return QGL_SW_ENOMEM;
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++) {
            int cx = (int)((long long)x * checks / size), cy = (int)((long long)y * checks / size);
            tex->texels[(size_t)y * (size_t)size + (size_t)x] = ((cx + cy) & 1) ? hi : lo;
        }
    return QGL_SW_OK;
}

void qgl_sw_texture_free(qgl_sw_texture *tex)
{
    if (!tex)
        return;
    free(tex->texels);
    tex->texels = NULL;
    tex->width = tex->height = tex->channels = 0;
}

static int wrap(int i, int n)
{
    int r = i % n;
    return r < 0 ? r + n : r;
}

static void fetch(const qgl_sw_texture *tex, int x, int y, float out[4])
{
    const float *p = tex->texels + ((size_t)wrap(y, tex->height) * (size_t)tex->width + (size_t)wrap(x, tex->width)) *
                                       (size_t)tex->channels;
    if (tex->channels < 3) {
        out[0] = out[1] = out[2] = p[0];
        out[3] = tex->channels == 2 ? p[1] : 1.0f;
        return;
    }
    for (int k = 0; k < 3; k++)
        out[k] = p[k];
    out[3] = tex->channels == 4 ? p[3] : 1.0f;
}

void qgl_sw_texture_sample(const qgl_sw_texture *tex, qgl_sw_filter filter, float s, float t, float out[4])
{
    if (!tex || !tex->texels || !isfinite(s) || !isfinite(t)) {
        out[0] = out[1] = out[2] = 0;
        out[3] = 1;
        return;
    }
    float fx = s * (float)tex->width - 0.5f, fy = t * (float)tex->height - 0.5f;
    if (filter == QGL_SW_FILTER_NEAREST) {
        fetch(tex, (int)floorf(fx + 0.5f), (int)floorf(fy + 0.5f), out);
        return;
    }
    float x0 = floorf(fx), y0 = floorf(fy), ax = fx - x0, ay = fy - y0;
    float c[4][4];
    fetch(tex, (int)x0, (int)y0, c[0]);
    fetch(tex, (int)x0 + 1, (int)y0, c[1]);
    fetch(tex, (int)x0, (int)y0 + 1, c[2]);
    fetch(tex, (int)x0 + 1, (int)y0 + 1, c[3]);
    for (int k = 0; k < 4; k++)
        out[k] = (1 - ay) * ((1 - ax) * c[0][k] + ax * c[1][k]) + ay * ((1 - ax) * c[2][k] + ax * c[3][k]);
}
