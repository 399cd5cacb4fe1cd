/* pow2_impl.h: exact scaling by a power of two, for the typed implementation headers
 * (weights_impl.h, plane_impl.h), with their R, FN, LDEXP and RMIN (the type's smallest
 * normal number). */

#include "core_util.h"

/* a[i] = LDEXP(a[i], -e) for n values, by one multiplication each where 2^-e is a normal
 * number (the product is then the same correctly rounded value): a library call per value
 * costs more than the arithmetic it guards. */
static void FN(scale_pow2)(R *a, int n, int e)
{
    R s = (R)qgl__pow2(-e); /* out of R's range: inf or 0, which the test below refuses */
    if (s >= RMIN && s <= 1 / RMIN) {
        for (int i = 0; i < n; i++)
            a[i] *= s;
    } else {
        for (int i = 0; i < n; i++)
            a[i] = LDEXP(a[i], -e);
    }
}

/* LDEXP(x, k) by one multiplication where 2^k is a normal number (the same correctly rounded
 * value, overflow and gradual underflow included). */
static inline R FN(ldexp)(R x, int k)
{
    R s = (R)qgl__pow2(k);
    return s >= RMIN && s <= 1 / RMIN ? x * s : LDEXP(x, k);
}
