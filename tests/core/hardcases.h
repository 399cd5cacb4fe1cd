/* hardcases.h: the numerical hard-case suite for the weights, and an exact reference.
 *
 * The suite is a list of (quad, point) pairs built from a fixed seed: interior points,
 * points 1e-7..1e-3 (relative) from edges and corners and exactly on them, edge
 * extensions, collapsed edges, collinear corners, zero-area quads, the bow-tie crossing,
 * w -> 0 from both sides, w < 0, quads crossing the eye plane, large coordinates with tiny
 * quads, tiny quads at the origin, and non-finite input. The reference evaluates the same
 * homogeneous formula in __float128 (inputs converted exactly, products of doubles exact)
 * with limits taken only at exact zeros. */
#ifndef HARDCASES_H
#define HARDCASES_H

typedef struct hc_case {
    double clip[4][4];
    double p[2];
    const char *group; /* a short name of the category, for messages and the table */
    double dist;       /* relative distance to the edge or corner the case targets (0 = on it, -1 = none) */
} hc_case;

/* The suite (malloc'd; free it). Returns the count. */
int hc_build(hc_case **out);

/* The exact reference. Returns QGL_INSIDE / QGL_OUTSIDE / QGL_DEGENERATE / QGL_NONFINITE
 * as qgl_weights does; weights in double (rounded once from __float128). */
int hc_reference(const double clip[4][4], double x, double y, double persp[4], double screen[4]);

/* Round a case's inputs to float (the float functions' view of the case). */
void hc_to_float(const hc_case *c, float clip[4][4], float p[2]);

#endif
