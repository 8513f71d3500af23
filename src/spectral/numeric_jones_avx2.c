/* The numeric methods' block loop for AVX2 (four lanes of double instead of two): compiled with
 * -mavx2 -mfma and without contraction (CMakeLists.txt, biref_isa_object), called only where the
 * CPU has AVX2 (numeric_jones.c); the same bits as the baseline. */
#include "spectral/numeric_block.h"

void biref_numeric_block_avx2(const coefficients *c, const phases *ph, int n, biref_jones_block *T,
                              biref_jones_block *R)
{
    block_sides(c, ph, n, T, R);
}
