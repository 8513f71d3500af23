/* Float lanes for the packet kernel's terms (analytic_packet_f32_kernel.inc): FLOAT_W = 2 *
 * PACKET_W lanes of float, one register of the instruction set (8 for AVX2, 16 for AVX-512), made
 * from two packets of double lanes. Included after an instruction set's header (simd/<isa>.h). */
#ifndef BIREF_SIMD_LANES_F32_H
#define BIREF_SIMD_LANES_F32_H

#include "spectral/simd/vector.h"
#if defined(__AVX__) || defined(__AVX512F__)
#include <immintrin.h>
#endif

#define FLOAT_W (2 * PACKET_W)

typedef float vf __attribute__((vector_size(FLOAT_W * sizeof(float))));
typedef int vfm __attribute__((vector_size(FLOAT_W * sizeof(float)))); /* a comparison's lanes: 0 or -1 */
typedef float vfh __attribute__((vector_size(PACKET_W * sizeof(float)))); /* a double packet's lanes in float */
typedef float vf_in __attribute__((vector_size(FLOAT_W * sizeof(float)), may_alias));

/* x in every lane: one broadcast (GCC does not recognise vb's loop for float lanes). */
static inline vf vfb(float x)
{
#if FLOAT_W == 16 && defined(__AVX512F__)
    return (vf)_mm512_set1_ps(x);
#elif FLOAT_W == 8 && defined(__AVX__)
    return (vf)_mm256_set1_ps(x);
#else
    vf v;
    for (int l = 0; l < FLOAT_W; l++) v[l] = x;
    return v;
#endif
}
static inline vf vfsel(vfm m, vf a, vf b) { return (vf)((m & (vfm)a) | (~m & (vfm)b)); }

static inline int vfany(vfm m)
{
#if FLOAT_W == 16 && defined(__AVX512F__)
    return _mm512_test_epi32_mask((__m512i)m, (__m512i)m) != 0;
#elif FLOAT_W == 8 && defined(__AVX2__)
    return _mm256_movemask_ps((__m256)m) != 0;
#else
    int r = 0;
    for (int l = 0; l < FLOAT_W; l++) r |= m[l];
    return r != 0;
#endif
}

/* Two packets of double lanes as one of float lanes (lo: lanes 0 .. PACKET_W - 1), each value
 * rounded once. */
#if PACKET_W == 8
#define VF_CONCAT(a, b) __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15)
#else
#define VF_CONCAT(a, b) __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7)
#endif
static inline vf vf_join(vd lo, vd hi)
{
    vfh a = __builtin_convertvector(lo, vfh), b = __builtin_convertvector(hi, vfh);
    return VF_CONCAT(a, b);
}


/* The same for two packets' comparison masks (64-bit lanes of 0 or -1). */
static inline vfm vfm_join(vm lo, vm hi)
{
    vi a = __builtin_convertvector(lo, vi), b = __builtin_convertvector(hi, vi);
    return VF_CONCAT(a, b);
}

/* Eight floats: one lane's eight values of a table row (analytic_packet_f32_kernel.inc). */
typedef float vf8 __attribute__((vector_size(8 * sizeof(float))));
typedef float vf8_in __attribute__((vector_size(8 * sizeof(float)), may_alias));

typedef int vi8 __attribute__((vector_size(8 * sizeof(int))));
static inline vf8 vf8b(float x)
{
#if defined(__AVX__)
    return (vf8)_mm256_set1_ps(x);
#else
    vf8 v;
    for (int l = 0; l < 8; l++) v[l] = x;
    return v;
#endif
}

/* r[k][l] = r[l][k] for 8 x 8 floats, three rounds of two-vector shuffles as v_transpose. */
#define VF8_LO1(a, c) __builtin_shufflevector(a, c, 0, 8, 2, 10, 4, 12, 6, 14)
#define VF8_HI1(a, c) __builtin_shufflevector(a, c, 1, 9, 3, 11, 5, 13, 7, 15)
#define VF8_LO2(a, c) __builtin_shufflevector(a, c, 0, 1, 8, 9, 4, 5, 12, 13)
#define VF8_HI2(a, c) __builtin_shufflevector(a, c, 2, 3, 10, 11, 6, 7, 14, 15)
#define VF8_LO4(a, c) __builtin_shufflevector(a, c, 0, 1, 2, 3, 8, 9, 10, 11)
#define VF8_HI4(a, c) __builtin_shufflevector(a, c, 4, 5, 6, 7, 12, 13, 14, 15)
#define VF8_ROUND(r, b, LO, HI)                                                                                        \
    for (int i = 0; i < 8; i++)                                                                                        \
        if (!(i & (b))) {                                                                                              \
            vf8 a_ = (r)[i], c_ = (r)[i + (b)];                                                                        \
            (r)[i] = LO(a_, c_);                                                                                       \
            (r)[i + (b)] = HI(a_, c_);                                                                                 \
        }
static inline void vf8_transpose(vf8 r[8])
{
    VF8_ROUND(r, 1, VF8_LO1, VF8_HI1)
    VF8_ROUND(r, 2, VF8_LO2, VF8_HI2)
    VF8_ROUND(r, 4, VF8_LO4, VF8_HI4)
}

/* Lanes 8k .. 8k + 7 of a float packet from g[k] (FLOAT_W / 8 groups of eight lanes). */
static inline vf vf_of8(const vf8 g[FLOAT_W / 8])
{
#if FLOAT_W == 16
    return __builtin_shufflevector(g[0], g[1], 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
#else
    return g[0];
#endif
}

/* 1 / x to ~1e-8 where AVX-512's 14-bit estimates exist (rcp14, rsqrt14, one Newton step each:
 * the error squares to ~4e-9), else exact: for the set-up's scale factors (V_COEF_RECIP of
 * packet_setup.inc) in double lanes and the terms' divisions in float lanes, whose results are
 * rounded to float anyway. Zero gives NaN instead of infinity: only in lanes marked bad. */
#if defined(__AVX512F__) && PACKET_W == 8
static inline vd vd_recip_est(vd x)
{
    vd r = (vd)_mm512_rcp14_pd((__m512d)x);
    return r * (2.0 - x * r);
}
static inline vd vd_rsqrt_est(vd x)
{
    vd y = (vd)_mm512_rsqrt14_pd((__m512d)x);
    return y * (1.5 - (0.5 * x) * (y * y));
}
static inline vf vf_recip(vf x)
{
    vf r = (vf)_mm512_rcp14_ps((__m512)x);
    return r * (2.0f - x * r);
}
#define V_COEF_RECIP(x) vd_recip_est(x)
#define V_COEF_RSQRT(x) vd_rsqrt_est(x)
#define V_COEF_SQRT(x) ((x) * vd_rsqrt_est(x))
#else
static inline vf vf_recip(vf x) { return 1.0f / x; }
#endif

#endif
