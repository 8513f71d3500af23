/* Inline 2x2 complex matrix algebra for Jones matrices and path operators.
 * Matrices are [from][to]: composition in travel order is the ordinary product A*B. */
#ifndef BIREF_OPTICS_CMAT2_H
#define BIREF_OPTICS_CMAT2_H

#include <complex.h>

typedef struct {
    double complex m[2][2];
} cmat2;

static inline cmat2 cmat2_mul(cmat2 a, cmat2 b)
{
    cmat2 c;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) c.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j];
    return c;
}

static inline cmat2 cmat2_from(const double complex a[2][2])
{
    cmat2 c = {{{a[0][0], a[0][1]}, {a[1][0], a[1][1]}}};
    return c;
}

static inline cmat2 cmat2_diag(double complex a, double complex b)
{
    cmat2 c = {{{a, 0}, {0, b}}};
    return c;
}

/* diag(d) * a: scales row i (paths arriving in mode i) by d[i]. */
static inline cmat2 cmat2_scale_rows(cmat2 a, double complex d0, double complex d1)
{
    a.m[0][0] *= d0;
    a.m[0][1] *= d0;
    a.m[1][0] *= d1;
    a.m[1][1] *= d1;
    return a;
}

/* (I - a)^{-1}: the geometric series of all round trips (paper eq. 17). */
static inline cmat2 cmat2_inv_one_minus(cmat2 a)
{
    double complex p = 1.0 - a.m[0][0], q = -a.m[0][1], r = -a.m[1][0], s = 1.0 - a.m[1][1];
    double complex det = p * s - q * r;
    cmat2 c = {{{s / det, -q / det}, {-r / det, p / det}}};
    return c;
}

static inline cmat2 cmat2_add(cmat2 a, cmat2 b)
{
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) a.m[i][j] += b.m[i][j];
    return a;
}

#endif
