/* demo_sheet.c: the headless contact sheet: scenes as rows, methods as columns.
 *
 * Every cell is a picture shrunk to the cell by area averaging (each target pixel is the
 * mean of the source pixels its footprint covers, weighted by overlap, so thin creases stay
 * visible instead of aliasing away); a method's cell is followed by its error heat map
 * against the reference, with the error figures printed underneath. Auto's also gets its
 * difference from the per-fragment picture of its own weights on a finer scale, shrunk by the
 * peak under each cell pixel instead (it is zero but where the planner split, and a mean would
 * wash out a line of single pixels); the legend has a line per scale. Text uses the demo's
 * own bitmap font. The sheet is built in memory and written once. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "demo_sheet.h"

#define MARGIN 8
#define LABEL_W 132
#define HEADER_H 22
#define CAPTION_H 12
#define LEGEND_LINE 16
#define LEGEND_H (2 * LEGEND_LINE + 14)

static const unsigned char ink_white[3] = {235, 235, 235};
static const unsigned char ink_grey[3] = {170, 170, 170};

int demo_sheet_init(demo_sheet *sh, int rows, int ncols, int cell, const char *const *col_names)
{
    memset(sh, 0, sizeof *sh);
    sh->rows = rows;
    sh->cols = ncols;
    sh->cell = cell;
    sh->w = LABEL_W + ncols * (cell + MARGIN) + MARGIN;
    sh->h = HEADER_H + rows * (cell + CAPTION_H + MARGIN) + LEGEND_H;
    sh->rgba = malloc((size_t)sh->w * (size_t)sh->h * 4);
    if (!sh->rgba)
        return -1;
    for (size_t i = 0; i < (size_t)sh->w * (size_t)sh->h; i++) {
        unsigned char *p = sh->rgba + i * 4;
        p[0] = p[1] = p[2] = 40;
        p[3] = 255;
    }
    for (int c = 0; c < ncols; c++)
        demo_text_rgba(sh->rgba, sh->w, sh->h, LABEL_W + c * (cell + MARGIN), 6, 1, ink_white, col_names[c]);
    return 0;
}

void demo_sheet_free(demo_sheet *sh)
{
    free(sh->rgba);
    memset(sh, 0, sizeof *sh);
}

/* Top-left pixel (from the top) of cell (row, col). */
static void cell_origin(const demo_sheet *sh, int row, int col, int *x, int *y_top)
{
    *x = LABEL_W + col * (sh->cell + MARGIN);
    *y_top = HEADER_H + row * (sh->cell + CAPTION_H + MARGIN);
}

void demo_sheet_row_label(demo_sheet *sh, int row, const char *label)
{
    int x, y;
    cell_origin(sh, row, 0, &x, &y);
    char buf[96];
    snprintf(buf, sizeof buf, "%s", label);
    /* wrap at the label column's width, breaking after '-' or '_' where possible */
    int per_line = (LABEL_W - MARGIN * 2) / DEMO_GLYPH_W, line = 0;
    for (char *p = buf; *p && line < 6; line++) {
        char piece[32];
        int n = (int)strlen(p) < per_line ? (int)strlen(p) : per_line;
        for (int k = n; k > per_line / 2 && n == per_line; k--)
            if (p[k - 1] == '-' || p[k - 1] == '_') {
                n = k;
                break;
            }
        snprintf(piece, sizeof piece, "%.*s", n, p);
        demo_text_rgba(sh->rgba, sh->w, sh->h, MARGIN, y + line * DEMO_GLYPH_H, 1, ink_white, piece);
        p += n;
    }
}

/* Area-averaging resample of src (sw x sh_, RGBA) into the cell, keeping the aspect and
 * centring it; peak: each channel's largest value under the footprint instead, so that a
 * sparse heat map's single pixels stay visible. */
static void blit_scaled(demo_sheet *sh, int x0, int y_top, const unsigned char *src, int sw, int sh_, int peak)
{
    double scale = fmax((double)sw / sh->cell, (double)sh_ / sh->cell);
    int dw = (int)floor(sw / scale), dh = (int)floor(sh_ / scale);
    int ox = x0 + (sh->cell - dw) / 2, oy_top = y_top + (sh->cell - dh) / 2;
    for (int ty = 0; ty < dh; ty++)
        for (int tx = 0; tx < dw; tx++) {
            double sx0 = tx * scale, sx1 = (tx + 1) * scale, sy0 = ty * scale, sy1 = (ty + 1) * scale;
            double acc[3] = {0, 0, 0}, wsum = 0;
            for (int y = (int)sy0; y < (int)ceil(sy1) && y < sh_; y++)
                for (int x = (int)sx0; x < (int)ceil(sx1) && x < sw; x++) {
                    double wx = fmin(sx1, x + 1) - fmax(sx0, x), wy = fmin(sy1, y + 1) - fmax(sy0, y);
                    double wgt = wx * wy;
                    /* picture rows count from the bottom, the target row ty from the top */
                    const unsigned char *p = src + ((size_t)(sh_ - 1 - y) * (size_t)sw + (size_t)x) * 4;
                    for (int k = 0; k < 3; k++)
                        acc[k] = peak ? fmax(acc[k], wgt > 0 ? p[k] : 0) : acc[k] + wgt * p[k];
                    wsum += wgt;
                }
            int row = sh->h - 1 - (oy_top + ty);
            unsigned char *d = sh->rgba + ((size_t)row * (size_t)sh->w + (size_t)(ox + tx)) * 4;
            for (int k = 0; k < 3; k++)
                d[k] = (unsigned char)lrint(peak ? acc[k] : wsum > 0 ? acc[k] / wsum : 0);
        }
}

static void cell(demo_sheet *sh, int row, int col, const unsigned char *rgba, int w, int h, const char *caption,
                 int peak)
{
    int x, y;
    cell_origin(sh, row, col, &x, &y);
    blit_scaled(sh, x, y, rgba, w, h, peak);
    if (caption)
        demo_text_rgba(sh->rgba, sh->w, sh->h, x, y + sh->cell + 3, 1, ink_grey, caption);
}

void demo_sheet_cell(demo_sheet *sh, int row, int col, const unsigned char *rgba, int w, int h,
                     const char *caption)
{
    cell(sh, row, col, rgba, w, h, caption, 0);
}

void demo_sheet_cell_peak(demo_sheet *sh, int row, int col, const unsigned char *rgba, int w, int h,
                          const char *caption)
{
    cell(sh, row, col, rgba, w, h, caption, 1);
}

void demo_sheet_legend(demo_sheet *sh, int line, int full_scale, const char *what)
{
    int y_top = sh->h - LEGEND_H + 6 + line * LEGEND_LINE, x = LABEL_W, bar_w = 256, bar_h = 10;
    unsigned char *a = calloc((size_t)bar_w * bar_h * 4, 1), *b = calloc((size_t)bar_w * bar_h * 4, 1);
    unsigned char *heat = malloc((size_t)bar_w * bar_h * 4);
    if (a && b && heat) {
        for (int j = 0; j < bar_h; j++)
            for (int i = 0; i < bar_w; i++)
                b[((size_t)j * bar_w + (size_t)i) * 4] = (unsigned char)lrint((double)i * full_scale / (bar_w - 1));
        demo_heatmap(a, b, bar_w, bar_h, full_scale, heat);
        for (int j = 0; j < bar_h; j++) {
            int row = sh->h - 1 - (y_top + j);
            memcpy(sh->rgba + ((size_t)row * (size_t)sh->w + (size_t)x) * 4, heat + (size_t)j * bar_w * 4,
                   (size_t)bar_w * 4);
        }
        char text[160];
        snprintf(text, sizeof text, "0 .. %d levels: %s", full_scale, what);
        demo_text_rgba(sh->rgba, sh->w, sh->h, x + bar_w + 8, y_top + 2, 1, ink_grey, text);
    }
    free(a);
    free(b);
    free(heat);
}
