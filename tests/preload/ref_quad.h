/* ref_quad.h: the quad the windowed preload tests draw, and its mean value reference.
 *
 * One non-affine quad (corner colours no plane fits) in normalized device coordinates under
 * identity matrices, in a REF_SIZE x REF_SIZE viewport on black. ref_check compares a
 * picture (RGB, rows from the bottom) with the reference: inside the quad, more than 1.5
 * pixels from its outline, each channel within 3/255 of the corners' colours interpolated
 * with qgl_weights at the pixel centre; outside, black. It returns the number of bad pixels
 * and prints the first few. Programs that only draw include it without REF_CHECK. */
#ifndef REF_QUAD_H
#define REF_QUAD_H

#define REF_SIZE 64

static const float ref_v[4][2] = {{-0.8f, -0.9f}, {0.7f, -0.6f}, {0.5f, 0.8f}, {-0.9f, 0.5f}};
static const float ref_c[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};

#ifdef REF_CHECK
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <quadgl/quadgl.h>

static double ref_outline_dist(double px, double py)
{
    double best = 1e30;
    for (int i = 0; i < 4; i++) {
        double ax = (ref_v[i][0] + 1) * REF_SIZE / 2, ay = (ref_v[i][1] + 1) * REF_SIZE / 2;
        double bx = (ref_v[(i + 1) % 4][0] + 1) * REF_SIZE / 2, by = (ref_v[(i + 1) % 4][1] + 1) * REF_SIZE / 2;
        double dx = bx - ax, dy = by - ay, t = ((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy);
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        best = fmin(best, hypot(px - ax - t * dx, py - ay - t * dy));
    }
    return best;
}

static int ref_check(const unsigned char *rgb, const char *who)
{
    double clip[4][4], v2[4][2];
    int bad = 0, inside = 0;
    for (int i = 0; i < 4; i++) {
        clip[i][0] = v2[i][0] = ref_v[i][0];
        clip[i][1] = v2[i][1] = ref_v[i][1];
        clip[i][2] = 0;
        clip[i][3] = 1;
    }
    for (int y = 0; y < REF_SIZE; y++)
        for (int x = 0; x < REF_SIZE; x++) {
            double nx = (x + 0.5) * 2.0 / REF_SIZE - 1, ny = (y + 0.5) * 2.0 / REF_SIZE - 1, w[4];
            const unsigned char *p = rgb + 3 * (y * REF_SIZE + x);
            int in, worst = 0;
            if (ref_outline_dist(x + 0.5, y + 0.5) < 1.5)
                continue;
            in = qgl_inside(v2, nx, ny) != 0;
            qgl_weights(clip, nx, ny, w, NULL);
            for (int c = 0; c < 3; c++) {
                double e = 0;
                int d;
                for (int i = 0; in && i < 4; i++)
                    e += w[i] * ref_c[i][c];
                d = abs((int)p[c] - (int)lround(e * 255.0));
                worst = d > worst ? d : worst;
            }
            inside += in;
            if (worst > 3) {
                if (bad < 5)
                    fprintf(stderr, "%s: pixel (%d,%d) = %d %d %d, off the mean value reference by %d\n", who, x, y,
                            p[0], p[1], p[2], worst);
                bad++;
            }
        }
    fprintf(stderr, "%s: %d of %d pixels inside the quad, %d off the reference\n", who, inside,
            REF_SIZE * REF_SIZE, bad);
    return bad + (inside < 100);
}
#endif
#endif
