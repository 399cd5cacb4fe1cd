/* appdiff.c: compares two photographs of a program and draws the difference as a heat map.
 *
 *   appdiff A.ppm B.ppm [MASK.ppm|-] [HEAT.ppm]
 *
 * prints one line: "over2 max differ outside": pixels whose largest channel difference is
 * over 2 levels, the largest difference, pixels that differ at all, and pixels over 2 levels
 * outside the mask (a pixel is inside when any channel of MASK is nonzero; without a mask
 * every pixel is outside). The heat map shows A's luminance dimmed to a quarter as the
 * background, tinted green inside the mask, and each differing pixel coloured by the log of
 * its difference: blue at 1 level through yellow to white at 128 and more. Pictures of
 * different sizes are an error (exit 2), so a program that changed its window is noticed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct image {
    int w, h;
    unsigned char *px;
} image;

static int read_ppm(const char *path, image *im)
{
    FILE *f = fopen(path, "rb");
    int maxv = 0;
    size_t n;
    im->px = NULL;
    if (!f)
        return 0;
    if (fscanf(f, "P6 %d %d %d", &im->w, &im->h, &maxv) == 3 && fgetc(f) != EOF && im->w > 0 && im->h > 0 &&
        maxv == 255) {
        n = (size_t)im->w * (size_t)im->h * 3;
        im->px = malloc(n);
        if (im->px && fread(im->px, 1, n, f) != n) {
            free(im->px);
            im->px = NULL;
        }
    }
    fclose(f);
    return im->px != NULL;
}

static int max_diff(const unsigned char *a, const unsigned char *b)
{
    int d = 0;
    for (int c = 0; c < 3; c++) {
        int e = abs((int)a[c] - (int)b[c]);
        d = e > d ? e : d;
    }
    return d;
}

/* Blue (1 level) through cyan, green and yellow to white (128 and more), by log2. */
static void heat_colour(int d, unsigned char out[3])
{
    static const unsigned char ramp[5][3] = {{40, 80, 255}, {0, 220, 255}, {60, 255, 60}, {255, 230, 0}, {255, 255, 255}};
    double t = fmin(log2((double)d) / 7.0, 1.0) * 4.0;
    int i = (int)t < 4 ? (int)t : 3;
    double f = t - i;
    for (int c = 0; c < 3; c++)
        out[c] = (unsigned char)(ramp[i][c] + f * (ramp[i + 1][c] - ramp[i][c]) + 0.5);
}

static void background(const unsigned char *a, int inside, unsigned char out[3])
{
    int y = (77 * a[0] + 150 * a[1] + 29 * a[2]) >> 10;
    out[0] = (unsigned char)y;
    out[1] = (unsigned char)(inside ? y + 70 : y);
    out[2] = (unsigned char)y;
}

int main(int argc, char **argv)
{
    image a, b, m = {0, 0, NULL};
    long over2 = 0, differ = 0, outside = 0;
    int worst = 0;
    FILE *heat = NULL;
    if (argc < 3 || argc > 5) {
        fprintf(stderr, "usage: %s A.ppm B.ppm [MASK.ppm|-] [HEAT.ppm]\n", argv[0]);
        return 2;
    }
    if (!read_ppm(argv[1], &a) || !read_ppm(argv[2], &b) ||
        (argc > 3 && argv[3][0] != '-' && !read_ppm(argv[3], &m))) {
        fprintf(stderr, "appdiff: cannot read the pictures\n");
        return 2;
    }
    if (a.w != b.w || a.h != b.h || (m.px && (m.w != a.w || m.h != a.h))) {
        fprintf(stderr, "appdiff: sizes differ (%dx%d, %dx%d)\n", a.w, a.h, b.w, b.h);
        return 2;
    }
    if (argc > 4 && !(heat = fopen(argv[4], "wb")))
        return 2;
    if (heat)
        fprintf(heat, "P6\n%d %d\n255\n", a.w, a.h);
    for (size_t i = 0; i < (size_t)a.w * (size_t)a.h; i++) {
        const unsigned char *pa = a.px + 3 * i, *pb = b.px + 3 * i;
        int d = max_diff(pa, pb), inside = m.px && (m.px[3 * i] | m.px[3 * i + 1] | m.px[3 * i + 2]);
        unsigned char out[3];
        differ += d > 0;
        over2 += d > 2;
        outside += d > 2 && !inside;
        worst = d > worst ? d : worst;
        if (heat) {
            if (d > 0)
                heat_colour(d, out);
            else
                background(pa, inside, out);
            fwrite(out, 1, 3, heat);
        }
    }
    if (heat && fclose(heat) != 0)
        return 2;
    printf("%ld %d %ld %ld\n", over2, worst, differ, outside);
    free(a.px);
    free(b.px);
    free(m.px);
    return 0;
}
