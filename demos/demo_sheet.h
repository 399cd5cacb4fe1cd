/* demo_sheet.h: the headless contact sheet (scenes as rows, methods and heat maps as columns). */
#ifndef DEMO_SHEET_H
#define DEMO_SHEET_H

#include "demo_app.h"

typedef struct demo_sheet {
    int rows, cols, cell;  /* cell: side of a square cell, pixels */
    int w, h;
    unsigned char *rgba;   /* w * h * 4, row 0 at the bottom */
} demo_sheet;

/* A blank sheet with one header name per column. Returns 0, or -1 when out of memory. */
int demo_sheet_init(demo_sheet *sh, int rows, int ncols, int cell, const char *const *col_names);
void demo_sheet_free(demo_sheet *sh);
void demo_sheet_row_label(demo_sheet *sh, int row, const char *label);
/* Put a picture (w x h RGBA, row 0 at the bottom) into cell (row, col), shrunk to fit, with
 * an optional caption underneath. */
void demo_sheet_cell(demo_sheet *sh, int row, int col, const unsigned char *rgba, int w, int h,
                     const char *caption);
/* The same shrunk by each channel's peak under a cell pixel (a sparse heat map). */
void demo_sheet_cell_peak(demo_sheet *sh, int row, int col, const unsigned char *rgba, int w, int h,
                          const char *caption);
/* A heat map's colour scale along the bottom, line 0 or 1, with what it shows. */
void demo_sheet_legend(demo_sheet *sh, int line, int full_scale, const char *what);

#endif
