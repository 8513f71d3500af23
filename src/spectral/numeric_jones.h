/* The closed-form Jones matrices for a block of wavelengths (numeric_jones.c). */
#ifndef BIREF_SPECTRAL_NUMERIC_JONES_H
#define BIREF_SPECTRAL_NUMERIC_JONES_H

#include <complex.h>
#include <string.h>

#include "biref/optics.h"

/* Wavelengths per block: the per-block arrays stay in the first-level cache. */
#define BIREF_NUMERIC_BLOCK 32

/* Jones matrices [from][to] of up to BIREF_NUMERIC_BLOCK wavelengths, real and imaginary parts. */
typedef struct {
    double re[2][2][BIREF_NUMERIC_BLOCK], im[2][2][BIREF_NUMERIC_BLOCK];
} biref_jones_block;

/* T and/or R (either may be NULL) of a prepared state at the vacuum wavenumbers k[0..n-1]
 * (2 pi / lambda, 1/nm), n <= BIREF_NUMERIC_BLOCK: equal to biref_slab_jones_at at
 * lambda = 2 pi / k to the bit when k was computed as 2.0 * M_PI / lambda. */
void biref_numeric_jones_block(const biref_slab_state *st, const double *k, int n, biref_jones_block *T,
                               biref_jones_block *R);

/* The same on a chosen code path: avx2 = 0 the portable baseline, 1 the AVX2 loop (only where
 * biref_numeric_avx2_available). For tests; both give the same bits. */
void biref_numeric_jones_block_isa(const biref_slab_state *st, const double *k, int n, biref_jones_block *T,
                                   biref_jones_block *R, int avx2);
int biref_numeric_avx2_available(void);

/* The intensity detected from wavelength l of a block under incident coherency C through the
 * analyzer P (NULL: none): <|e J P|^2> over the input ensemble
 * = sum_{i,j} C[i][j] sum_k M[i][k] conj(M[j][k]), M = J P. The amplitudes are rebuilt as
 * re + i im exactly, signed zeros included (C17 6.2.5p13 lays a complex out as double[2]; CMPLX
 * is defined by glibc only for compilers that identify as GCC >= 4.7, not clang). */
static inline double biref_numeric_block_detected(const biref_jones_block *B, int l, const double complex C[2][2],
                                                  const double complex P[2][2])
{
    double complex J[2][2], M[2][2];
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++) {
            const double parts[2] = {B->re[i][k][l], B->im[i][k][l]};
            memcpy(&J[i][k], parts, sizeof J[i][k]);
        }
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++) M[i][k] = P ? J[i][0] * P[0][k] + J[i][1] * P[1][k] : J[i][k];
    double I_det = 0.0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) I_det += creal(C[i][j] * M[i][k] * conj(M[j][k]));
    return I_det;
}

#endif
