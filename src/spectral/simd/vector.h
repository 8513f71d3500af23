/* The packet kernel's lanes in GCC vector extensions (clang has them too), for the width
 * PACKET_W that the instruction set's header (simd/baseline.h, avx2.h, avx512.h) defines before
 * including this: the vector types, what is the same code on every set (broadcast, select,
 * absolute value, transposes by shuffles), and generic forms of what is not (vany, v_sqrt), which
 * each set's header uses or replaces by its instructions. */
#ifndef BIREF_SIMD_VECTOR_H
#define BIREF_SIMD_VECTOR_H

#include <math.h>

#if !defined(PACKET_W) || (PACKET_W != 4 && PACKET_W != 8)
#error "include an instruction set's header (spectral/simd/<isa>.h), which defines PACKET_W 4 or 8"
#endif

/* Vectors wider than the target's registers (4 lanes on the baseline) pass between static
 * functions only, never through an external interface: the ABI note does not apply. */
#pragma GCC diagnostic ignored "-Wpsabi"

typedef double vd __attribute__((vector_size(PACKET_W * sizeof(double))));
typedef long long vm __attribute__((vector_size(PACKET_W * sizeof(double))));
typedef int vi __attribute__((vector_size(PACKET_W * sizeof(int))));
/* A vector read in place from an array of doubles (the packet table, whose rows are aligned). */
typedef double vd_in __attribute__((vector_size(PACKET_W * sizeof(double)), may_alias));
/* The same from memory aligned only as double (the caller's hits). */
typedef double vd_u __attribute__((vector_size(PACKET_W * sizeof(double)), may_alias, aligned(sizeof(double))));

/* x in every lane (a broadcast: (vd){0} + x would cost an addition, which IEEE rules keep).
 * Always inlined: an out-of-line copy would return a vector wider than the baseline set's
 * registers (a -Wpsabi error), which GCC may make when a large kernel exhausts its inline budget. */
static inline __attribute__((always_inline)) vd vb(double x)
{
    vd v;
    for (int l = 0; l < PACKET_W; l++) v[l] = x;
    return v;
}
static inline vd vsel(vm m, vd a, vd b) { return (vd)((m & (vm)a) | (~m & (vm)b)); }
static inline vd vabs(vd x) { return (vd)((vm)x & ((vm){0} + 0x7fffffffffffffffLL)); }
/* Whether any lane of m is set, lane by lane. */
static inline int v_any_generic(vm m)
{
    long long r = 0;
    for (int l = 0; l < PACKET_W; l++) r |= m[l];
    return r != 0;
}

/* Per-lane square root (IEEE, as sqrt), lane by lane. */
static inline vd v_sqrt_generic(vd x)
{
    for (int l = 0; l < PACKET_W; l++) x[l] = sqrt(x[l]);
    return x;
}

/* a b + c with one rounding per lane (libm's fma: slow where the CPU has no fused multiply-add). */
static inline vd v_fma_generic(vd a, vd b, vd c)
{
    for (int l = 0; l < PACKET_W; l++) a[l] = fma(a[l], b[l], c[l]);
    return a;
}

/* r[k][l] = r[l][k]: PACKET_W vectors of PACKET_W lanes transposed in log2(PACKET_W) rounds of
 * two-vector shuffles (pairs of blocks of 1, 2, 4 lanes interleaved). __builtin_shufflevector
 * (constant lane indices) rather than GCC's __builtin_shuffle, which clang does not have: the
 * fuzzing build compiles this file with clang. */
#if PACKET_W == 8
#define V_LO1(a, c) __builtin_shufflevector(a, c, 0, 8, 2, 10, 4, 12, 6, 14)
#define V_HI1(a, c) __builtin_shufflevector(a, c, 1, 9, 3, 11, 5, 13, 7, 15)
#define V_LO2(a, c) __builtin_shufflevector(a, c, 0, 1, 8, 9, 4, 5, 12, 13)
#define V_HI2(a, c) __builtin_shufflevector(a, c, 2, 3, 10, 11, 6, 7, 14, 15)
#define V_LO4(a, c) __builtin_shufflevector(a, c, 0, 1, 2, 3, 8, 9, 10, 11)
#define V_HI4(a, c) __builtin_shufflevector(a, c, 4, 5, 6, 7, 12, 13, 14, 15)
#else
#define V_LO1(a, c) __builtin_shufflevector(a, c, 0, 4, 2, 6)
#define V_HI1(a, c) __builtin_shufflevector(a, c, 1, 5, 3, 7)
#define V_LO2(a, c) __builtin_shufflevector(a, c, 0, 1, 4, 5)
#define V_HI2(a, c) __builtin_shufflevector(a, c, 2, 3, 6, 7)
#endif
#define V_TRANSPOSE_ROUND(r, b, LO, HI)                                                                                \
    for (int i = 0; i < PACKET_W; i++)                                                                                 \
        if (!(i & (b))) {                                                                                              \
            vd a_ = (r)[i], c_ = (r)[i + (b)];                                                                         \
            (r)[i] = LO(a_, c_);                                                                                       \
            (r)[i + (b)] = HI(a_, c_);                                                                                 \
        }

static inline void v_transpose(vd r[PACKET_W])
{
    V_TRANSPOSE_ROUND(r, 1, V_LO1, V_HI1)
    V_TRANSPOSE_ROUND(r, 2, V_LO2, V_HI2)
#if PACKET_W == 8
    V_TRANSPOSE_ROUND(r, 4, V_LO4, V_HI4)
#endif
}

#endif
