/* The closed-form Jones matrices for a block of wavelengths (numeric_jones.c). */
#ifndef BIREF_SPECTRAL_NUMERIC_JONES_H
#define BIREF_SPECTRAL_NUMERIC_JONES_H

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

#endif
