/* Vector primitives of the portable baseline: 4 lanes of double (two SSE2 registers on x86-64,
 * generic code elsewhere). The shape of every instruction set's header: PACKET_W, then vany and
 * v_sqrt in the set's instructions, the rest shared (simd/vector.h). */
#ifndef BIREF_SIMD_BASELINE_H
#define BIREF_SIMD_BASELINE_H

#define PACKET_W 4
#include "spectral/simd/vector.h"
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

static inline int vany(vm m) { return v_any_generic(m); }

static inline vd v_sqrt(vd x)
{
#if defined(__SSE2__)
    __m128d lo = _mm_sqrt_pd((__m128d){x[0], x[1]}), hi = _mm_sqrt_pd((__m128d){x[2], x[3]});
    return (vd){lo[0], lo[1], hi[0], hi[1]};
#else
    return v_sqrt_generic(x);
#endif
}

static inline vd v_fma(vd a, vd b, vd c) { return v_fma_generic(a, b, c); }

#endif
