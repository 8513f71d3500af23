/* Vector primitives of AVX2 + FMA: 4 lanes of double, one register. The object that includes
 * this is compiled with -mavx2 -mfma (CMakeLists.txt, biref_isa_object) and only called where the
 * CPU has both (analytic_packet.c); on a host without the instructions it compiles to the generic
 * forms and is never called. */
#ifndef BIREF_SIMD_AVX2_H
#define BIREF_SIMD_AVX2_H

#define PACKET_W 4
#include "spectral/simd/vector.h"
#if defined(__AVX2__)
#include <immintrin.h>
#endif

static inline int vany(vm m)
{
#if defined(__AVX2__)
    return _mm256_movemask_pd((__m256d)m) != 0;
#else
    return v_any_generic(m);
#endif
}

static inline vd v_sqrt(vd x)
{
#if defined(__AVX2__)
    return (vd)_mm256_sqrt_pd((__m256d)x);
#else
    return v_sqrt_generic(x);
#endif
}

/* a b + c with one rounding. */
static inline vd v_fma(vd a, vd b, vd c)
{
#if defined(__AVX2__) && defined(__FMA__)
    return (vd)_mm256_fmadd_pd((__m256d)a, (__m256d)b, (__m256d)c);
#else
    return v_fma_generic(a, b, c);
#endif
}

#endif
