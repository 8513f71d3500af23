/* The inner loop shared by the two demodulated tables (spectral_context.c, phase_prefilter.c):
 * one wavelength sample's contribution to a run of nodes. */
#ifndef BIREF_SPECTRAL_TABLE_BUILD_H
#define BIREF_SPECTRAL_TABLE_BUILD_H

#include <complex.h>

/* rows[m] (12 doubles: [band][re, im, dre/dD, dim/dD]) += w[band] * (z, dz z) for m = 0..count-1,
 * z advancing by one rotation per node; returns z after the last node. The four values of a
 * band are one vector of two pairs, each element a product and a sum as in scalar code (the
 * library is compiled without contraction), so the table is the same to the bit as element by
 * element, and about half the instructions. */
static inline double complex biref_table_accumulate(double *rows, int count, const double w[3], double complex z,
                                                    double complex rot, double complex dz)
{
    typedef double pair __attribute__((vector_size(16)));
    const pair w2[3] = {{w[0], w[0]}, {w[1], w[1]}, {w[2], w[2]}};
    for (int m = 0; m < count; m++) {
        double *row = rows + (size_t)m * 12;
        const double complex zd = dz * z;
        const pair v = {creal(z), cimag(z)}, vd = {creal(zd), cimag(zd)};
        for (int j = 0; j < 3; j++) {
            pair a, b;
            __builtin_memcpy(&a, row + 4 * j, sizeof a);
            __builtin_memcpy(&b, row + 4 * j + 2, sizeof b);
            a += w2[j] * v;
            b += w2[j] * vd;
            __builtin_memcpy(row + 4 * j, &a, sizeof a);
            __builtin_memcpy(row + 4 * j + 2, &b, sizeof b);
        }
        z *= rot;
    }
    return z;
}

#endif
