/* bench_report.c: quadgl-bench's outputs: Markdown table, CSV, the gnuplot plot, the sheet.
 *
 * The plot is written as gnuplot data and script files next to the PNG (FILE.png.d/) and
 * rendered by running gnuplot (pngcairo): time against RMS error, log-log, one panel per
 * scene, one series per method family (bilinear:N and adaptive variants become lines through
 * their parameters). The sheet is one float RGB canvas: a row per scene, a column per
 * method, each cell the shaded image and its error heat map side by side, labelled through
 * OpenImageIO's text renderer when a font is available. */
#include "bench.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#ifdef QGL_HAVE_IMAGES
#include "qgl_image.h"
#endif

static const char *unit_of(const bench_scene *scenes, int nscenes, const char *name)
{
    for (int i = 0; i < nscenes; i++)
        if (!strcmp(scenes[i].scene->name, name))
            return scenes[i].scene->unit;
    return "";
}

void bench_table(const bench_result *r, int n, const bench_scene *scenes, int nscenes)
{
    printf("| scene | method | ms | Mpix/s | RMS | max | crease | rotation | drift | unit |\n");
    printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (int i = 0; i < n; i++)
        printf("| %s | %s | %.3f | %.1f | %.4g | %.4g | %.4g | %.4g | %.4g | %s |\n", r[i].scene, r[i].method,
               r[i].ms, r[i].mpix_s, r[i].rms, r[i].max, r[i].crease, r[i].rotation, r[i].drift,
               unit_of(scenes, nscenes, r[i].scene));
}

int bench_csv(const char *path, const bench_result *r, int n)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "quadgl-bench: %s: %s\n", path, strerror(errno));
        return -1;
    }
    fprintf(f, "scene,method,param,ms,mpix_s,rms,max,crease,rotation,drift\n");
    for (int i = 0; i < n; i++) {
        const char *colon = strchr(r[i].method, ':');
        int len = colon ? (int)(colon - r[i].method) : (int)strlen(r[i].method);
        fprintf(f, "%s,%.*s,\"%s\",%.6f,%.4f,%.6g,%.6g,%.6g,%.6g,%.6g\n", r[i].scene, len, r[i].method,
                colon ? colon + 1 : "", r[i].ms, r[i].mpix_s, r[i].rms, r[i].max, r[i].crease, r[i].rotation,
                r[i].drift);
    }
    return fclose(f) ? -1 : 0;
}

/* The family of a method name: "bilinear:8" -> "bilinear". */
static void family(const char *method, char *out, size_t n)
{
    const char *colon = strchr(method, ':');
    snprintf(out, n, "%.*s", colon ? (int)(colon - method) : (int)strlen(method), method);
}

static int write_plot_data(const char *dir, const bench_result *r, int n, const char *scene, char fams[][32],
                           int *nfam)
{
    *nfam = 0;
    for (int i = 0; i < n; i++) {
        char fam[32];
        family(r[i].method, fam, sizeof fam);
        if (strcmp(r[i].scene, scene) || !strcmp(fam, "exact"))
            continue;
        int known = 0;
        for (int k = 0; k < *nfam; k++)
            known |= !strcmp(fams[k], fam);
        if (!known && *nfam < 16)
            snprintf(fams[(*nfam)++], 32, "%s", fam);
    }
    for (int k = 0; k < *nfam; k++) {
        char path[2048];
        snprintf(path, sizeof path, "%s/%s_%s.dat", dir, scene, fams[k]);
        FILE *f = fopen(path, "w");
        if (!f)
            return -1;
        for (int i = 0; i < n; i++) {
            char fam[32];
            family(r[i].method, fam, sizeof fam);
            if (!strcmp(r[i].scene, scene) && !strcmp(fam, fams[k]))
                fprintf(f, "%.6g %.6g %s\n", r[i].ms > 1e-4 ? r[i].ms : 1e-4, r[i].rms > 1e-6 ? r[i].rms : 1e-6,
                        r[i].method);
        }
        fclose(f);
    }
    return 0;
}

int bench_plot(const char *path, const bench_result *r, int n, const bench_scene *scenes, int nscenes)
{
    char dir[1100], script[1200];
    snprintf(dir, sizeof dir, "%s.d", path);
    mkdir(dir, 0777);
    snprintf(script, sizeof script, "%s/plot.gp", dir);
    FILE *g = fopen(script, "w");
    if (!g) {
        fprintf(stderr, "quadgl-bench: %s: %s\n", script, strerror(errno));
        return -1;
    }
    int cols = nscenes < 4 ? nscenes : 4, rows = (nscenes + cols - 1) / cols;
    fprintf(g, "set terminal pngcairo noenhanced size %d,%d font 'DejaVu Sans,9'\nset output '%s'\n", 420 * cols, 340 * rows,
            path);
    fprintf(g, "set multiplot layout %d,%d title 'quadgl-bench: time per frame vs RMS error against exact "
               "(log-log; lower left is better)'\n",
            rows, cols);
    fprintf(g, "set logscale xy\nset grid\nset key top right font ',7'\nset xlabel 'ms per frame'\n");
    for (int s = 0; s < nscenes; s++) {
        char fams[16][32];
        int nfam;
        const qgl_sw_scene *sc = scenes[s].scene;
        if (write_plot_data(dir, r, n, sc->name, fams, &nfam))
            return -1;
        fprintf(g, "set title '%s'\nset ylabel 'RMS error (%s)'\nplot ", sc->name, sc->unit);
        for (int k = 0; k < nfam; k++)
            fprintf(g, "%s'%s/%s_%s.dat' using 1:2 with linespoints pt %d title '%s'", k ? ", " : "", dir, sc->name,
                    fams[k], k + 1, fams[k]);
        fprintf(g, "\n");
    }
    fprintf(g, "unset multiplot\n");
    fclose(g);
    char cmd[1400];
    snprintf(cmd, sizeof cmd, "gnuplot '%s'", script);
    int rc = system(cmd);
    if (rc != 0) {
        fprintf(stderr, "quadgl-bench: gnuplot failed (%d) on %s\n", rc, script);
        return -1;
    }
    return 0;
}

/* Nearest-neighbour copy of a w x h RGB image into the canvas at (x0, y0), scaled to t x t. */
static void blit(float *canvas, int cw, const float *img, int w, int h, int x0, int y0, int t)
{
    for (int y = 0; y < t; y++)
        for (int x = 0; x < t; x++) {
            int sx = x * w / t, sy = y * h / t;
            for (int k = 0; k < 3; k++)
                canvas[((size_t)(y0 + y) * (size_t)cw + (size_t)(x0 + x)) * 3 + (size_t)k] =
                    img[((size_t)sy * (size_t)w + (size_t)sx) * 3 + (size_t)k];
        }
}

static const bench_result *find(const bench_result *r, int n, const char *scene, const char *method)
{
    for (int i = 0; i < n; i++)
        if (!strcmp(r[i].scene, scene) && !strcmp(r[i].method, method))
            return &r[i];
    return NULL;
}

int bench_sheet(const char *path, const bench_result *r, int n, const bench_scene *scenes, int nscenes,
                const char *const *columns, int ncolumns, int t)
{
    const int left = 150, top = 40, gap = 10;
    int cell = 2 * t + gap, w = left + ncolumns * cell, h = top + nscenes * (t + gap);
    float *canvas = malloc((size_t)w * (size_t)h * 3 * sizeof(float));
    int nlab = 0, maxlab = 2 * (nscenes + ncolumns) + 4;
    int *xy = malloc((size_t)maxlab * 2 * sizeof(int));
    char **text = calloc((size_t)maxlab, sizeof(char *));
    if (!canvas || !xy || !text) {
        free(canvas);
        free(xy);
        free(text);
        return -1;
    }
    for (size_t i = 0; i < (size_t)w * (size_t)h * 3; i++)
        canvas[i] = 0.05f;
    for (int c = 0; c < ncolumns; c++) {
        xy[2 * nlab] = left + c * cell;
        xy[2 * nlab + 1] = 16;
        text[nlab++] = strdup(columns[c]);
        xy[2 * nlab] = left + c * cell;
        xy[2 * nlab + 1] = 32;
        text[nlab++] = strdup("image | error");
    }
    for (int s = 0; s < nscenes; s++) {
        int y0 = top + s * (t + gap);
        const qgl_sw_scene *sc = scenes[s].scene;
        char label[96];
        snprintf(label, sizeof label, "%s", sc->name);
        xy[2 * nlab] = 4;
        xy[2 * nlab + 1] = y0 + t / 2;
        text[nlab++] = strdup(label);
        for (int c = 0; c < ncolumns; c++) {
            const bench_result *res = find(r, n, sc->name, columns[c]);
            int x0 = left + c * cell;
            if (res && res->shaded)
                blit(canvas, w, res->shaded, scenes[s].width, scenes[s].height, x0, y0, t);
            if (res && res->heat)
                blit(canvas, w, res->heat, scenes[s].width, scenes[s].height, x0 + t, y0, t);
        }
    }
    int rc = -1;
#ifdef QGL_HAVE_IMAGES
    char err[512];
    rc = qgl_image_write_labeled(path, w, h, 3, canvas, nlab, xy, (const char *const *)text, 13, err, sizeof err);
    if (rc < 0)
        fprintf(stderr, "quadgl-bench: %s: %s\n", path, err);
    else if (rc > 0)
        fprintf(stderr, "quadgl-bench: %s: no font for labels, written without them\n", path);
    rc = rc < 0 ? -1 : 0;
#else
    fprintf(stderr, "quadgl-bench: --sheet needs OpenImageIO (built without it)\n");
#endif
    for (int i = 0; i < nlab; i++)
        free(text[i]);
    free(text);
    free(xy);
    free(canvas);
    return rc;
}
