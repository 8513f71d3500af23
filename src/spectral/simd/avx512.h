/* Vector primitives of AVX-512F: 8 lanes of double, one register. The object that includes this
 * is compiled with -mavx512f -mavx2 -mfma (CMakeLists.txt, biref_isa_object) and only called
 * where the CPU has them (analytic_packet.c); on a host without the instructions it compiles to
 * the generic forms and is never called. */
#ifndef BIREF_SIMD_AVX512_H
#define BIREF_SIMD_AVX512_H

#define PACKET_W 8
#include "spectral/simd/vector.h"
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

static inline int vany(vm m)
{
#if defined(__AVX512F__)
    return _mm512_test_epi64_mask((__m512i)m, (__m512i)m) != 0;
#else
    return v_any_generic(m);
#endif
}

static inline vd v_sqrt(vd x)
{
#if defined(__AVX512F__)
    return (vd)_mm512_sqrt_pd((__m512d)x);
#else
    return v_sqrt_generic(x);
#endif
}

/* a b + c with one rounding. */
static inline vd v_fma(vd a, vd b, vd c)
{
#if defined(__AVX512F__) && defined(__FMA__)
    return (vd)_mm512_fmadd_pd((__m512d)a, (__m512d)b, (__m512d)c);
#else
    return v_fma_generic(a, b, c);
#endif
}

#endif
