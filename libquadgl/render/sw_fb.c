/* sw_fb.c: the software framebuffer: float colour, depth, facing and fragment counts.
 *
 * One allocation per plane; rows count from the bottom as GL's window coordinates do. The
 * optional planes exist only when asked for, so a plain colour + depth target costs nothing
 * extra per fragment beyond a NULL test. */
#include "sw_internal.h"

#include <stdlib.h>
#include <string.h>

qgl_sw_fb *qgl_sw_fb_create(const qgl_sw_fb_desc *desc)
{
    if (!desc || desc->width <= 0 || desc->height <= 0 || desc->channels < 0 || desc->channels > 64)
        return NULL;
    qgl_sw_fb *fb = calloc(1, sizeof *fb);
    if (!fb)
        return NULL;
    size_t n = (size_t)desc->width * (size_t)desc->height;
    fb->width = desc->width;
    fb->height = desc->height;
    fb->channels = desc->channels ? desc->channels : 4;
    fb->color = malloc(n * (size_t)fb->channels * sizeof(float));
    int ok = fb->color != NULL;
    if (ok && !desc->no_depth)
        ok = (fb->depth = malloc(n * sizeof(float))) != NULL;
    if (ok && desc->with_facing)
        ok = (fb->facing = malloc(n)) != NULL;
    if (ok && desc->with_count)
        ok = (fb->count = malloc(n * sizeof(unsigned))) != NULL;
    if (!ok) {
        qgl_sw_fb_destroy(fb);
        return NULL;
    }
    qgl_sw_fb_clear(fb, NULL, 1.0f);
    return fb;
}

void qgl_sw_fb_destroy(qgl_sw_fb *fb)
{
    if (!fb)
        return;
    free(fb->color);
    free(fb->depth);
    free(fb->facing);
    free(fb->count);
    free(fb);
}

void qgl_sw_fb_clear(qgl_sw_fb *fb, const float *color, float depth)
{
    if (!fb)
        return;
    size_t n = (size_t)fb->width * (size_t)fb->height;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < fb->channels; k++)
            fb->color[i * (size_t)fb->channels + (size_t)k] = color ? color[k] : 0.0f;
    if (fb->depth)
        for (size_t i = 0; i < n; i++)
            fb->depth[i] = depth;
    if (fb->facing)
        memset(fb->facing, 0, n);
    if (fb->count)
        memset(fb->count, 0, n * sizeof(unsigned));
}
