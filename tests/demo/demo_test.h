/* demo_test.h: what the demo suite's tests share: running quadgl-demo, reading its pictures,
 * and the software renderer's own pictures of a scene (the independent reference). */
#ifndef DEMO_TEST_H
#define DEMO_TEST_H

#include <stddef.h>
#include <quadgl/quadgl.h>

/* Run argv (argv[0] a path) with stdout and stderr into the file log (appended); returns the
 * exit status, 128 + signal when killed, or -1 when it could not start. */
int dt_run(char *const argv[], const char *log);
/* The whole file as a NUL-terminated malloc'd string, or NULL. */
char *dt_slurp(const char *path);
/* A fresh temporary directory (mkdtemp) under $TMPDIR or /tmp; the path is static. */
const char *dt_tmpdir(const char *tag);
/* Remove a directory tree made by dt_tmpdir (tests keep theirs when they fail). */
void dt_rmtree(const char *dir);

/* An 8-bit RGBA picture, row 0 at the bottom. */
typedef struct dt_image {
    int w, h;
    unsigned char *rgba;
} dt_image;

int dt_image_read(const char *path, dt_image *img);
void dt_image_free(dt_image *img);

typedef struct dt_diff {
    double rms;       /* RGB channels, 8-bit levels */
    double p99;       /* 99th percentile of the per-pixel largest channel difference */
    int max;
    double frac_over8; /* fraction of pixels whose largest channel difference exceeds 8 */
} dt_diff;

/* Compare a with the w x h sub-rectangle of b starting at (bx, by). */
void dt_compare(const dt_image *a, const dt_image *b, int bx, int by, dt_diff *out);

/* The software renderer's picture of scene (as loaded from its file, camera as in the file)
 * with method and vertex-order rotation, over the background the demo uses, quantized to 8
 * bits. w x h must have the scene's aspect. Returns 0 or a negative qgl_sw code. */
int dt_sw_picture(const qgl_sw_scene *scene, const char *method, int rotate, int w, int h, dt_image *out);

/* The demo's background (0.1, 0.1, 0.12): the colour of every pixel no quad covers. */
extern const float dt_background[4];
/* Fraction of pixels differing from the background by more than 8 levels. */
double dt_coverage(const dt_image *img);

#define DT_CHECK(cond, ...)                                  \
    do {                                                     \
        if (!(cond)) {                                       \
            printf("FAIL %s:%d: ", __FILE__, __LINE__);      \
            printf(__VA_ARGS__);                             \
            printf("\n");                                    \
            failures++;                                      \
        }                                                    \
    } while (0)

#endif
