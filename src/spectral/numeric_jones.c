/* The closed-form Jones matrices (slab.c, biref_slab_jones_at) for a block of wavelengths at
 * once: the numeric methods' inner loop, laid out across wavelengths.
 *
 * Per wavelength the legs' phase factors are computed once and shared by transmission and
 * reflection, as are the round trip D and the entry amplitudes t01 (I - D)^{-1}. The complex
 * algebra is written out in real arithmetic with the operations and their order of the scalar
 * path under the library's complex model (-fcx-limited-range, no contraction), one loop per
 * block that the compiler vectorises across wavelengths; a propagating leg's phase factor is
 * cexp's own result (cexp(i y) = cos y + i sin y, one sincos). So the Jones matrices equal the
 * scalar path's to the bit (test_numeric_block). */
#define _GNU_SOURCE /* sincos */
#include <complex.h>
#include <math.h>

#include "spectral/numeric_jones.h"

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define BIREF_NUMERIC_HAVE_AVX2 1
#else
#define BIREF_NUMERIC_HAVE_AVX2 0
#endif

/* a * b, as the compiler expands a complex product without range checks. */
#define CMUL(ar, ai, br, bi, rr, ri)                                                                     \
    do {                                                                                                 \
        double ar_ = (ar), ai_ = (ai), br_ = (br), bi_ = (bi);                                           \
        (rr) = ar_ * br_ - ai_ * bi_;                                                                    \
        (ri) = ar_ * bi_ + ai_ * br_;                                                                    \
    } while (0)

/* a / b, likewise (Smith's scaling is not used under -fcx-limited-range). */
#define CDIV(ar, ai, br, bi, rr, ri)                                                                     \
    do {                                                                                                 \
        double ar_ = (ar), ai_ = (ai), br_ = (br), bi_ = (bi);                                           \
        double t_ = br_ * br_ + bi_ * bi_;                                                               \
        (rr) = (ar_ * br_ + ai_ * bi_) / t_;                                                             \
        (ri) = (ai_ * br_ - ar_ * bi_) / t_;                                                             \
    } while (0)

/* c = a b for 2 x 2 complex matrices in real and imaginary parts (cmat2_mul's order). A macro,
 * not a function: the loop that uses it must keep its arrays in registers to be vectorised. */
#define MAT_MUL(ar, ai, br, bi, cr, ci)                                                                  \
    do {                                                                                                 \
        for (int a_ = 0; a_ < 2; a_++)                                                                   \
            for (int b_ = 0; b_ < 2; b_++) {                                                             \
                double xr_, xi_, yr_, yi_;                                                               \
                CMUL((ar)[a_][0], (ai)[a_][0], (br)[0][b_], (bi)[0][b_], xr_, xi_);                      \
                CMUL((ar)[a_][1], (ai)[a_][1], (br)[1][b_], (bi)[1][b_], yr_, yi_);                      \
                (cr)[a_][b_] = xr_ + yr_;                                                                \
                (ci)[a_][b_] = xi_ + yi_;                                                                \
            }                                                                                            \
    } while (0)

/* The phase factor e^{i k opl} of one leg for each wavelength of the block. */
static void leg_phase(double complex opl, const double *k, int n, double *re, double *im)
{
#ifdef __GLIBC__
    if (cimag(opl) == 0.0) {
        /* cexp(i k opl) for a real path: glibc's cexp is exp(0) = 1 times sincos of k opl, so
         * this is its result bit for bit, without its classification and exp. */
        const double a = creal(opl);
        for (int l = 0; l < n; l++) sincos(k[l] * a, &im[l], &re[l]);
        return;
    }
#endif
    for (int l = 0; l < n; l++) {
        double complex z = cexp(I * k[l] * opl);
        re[l] = creal(z);
        im[l] = cimag(z);
    }
}

/* The interface coefficients of a state, [row][col], real and imaginary parts. */
typedef struct {
    double t01r[2][2], t01i[2][2], r10r[2][2], r10i[2][2], r12r[2][2], r12i[2][2];
    double t12r[2][2], t12i[2][2], t10r[2][2], t10i[2][2], r01r[2][2], r01i[2][2];
} coefficients;

/* The legs' phase factors of a block. */
typedef struct {
    const double *pd0r, *pd0i, *pd1r, *pd1i, *pu0r, *pu0i, *pu1r, *pu1i;
} phases;

/* One loop over the block without branches (the sides are compile-time constants in each
 * call below), which the compiler vectorises across wavelengths. */
static inline __attribute__((always_inline)) void block_loop(const coefficients *c, const phases *ph, int n,
                                                              biref_jones_block *T, biref_jones_block *R,
                                                              const int want_t, const int want_r)
{
#pragma omp simd
    for (int l = 0; l < n; l++) {
        const double pdr[2] = {ph->pd0r[l], ph->pd1r[l]}, pdi[2] = {ph->pd0i[l], ph->pd1i[l]};
        const double pur[2] = {ph->pu0r[l], ph->pu1r[l]}, pui[2] = {ph->pu0i[l], ph->pu1i[l]};
        /* down_r12 = diag(P_down) r12, up_r10 = diag(P_up) r10 (slab.c). */
        double dr[2][2], di[2][2], ur[2][2], ui[2][2];
        for (int a = 0; a < 2; a++)
            for (int b = 0; b < 2; b++) {
                CMUL(c->r12r[a][b], c->r12i[a][b], pdr[a], pdi[a], dr[a][b], di[a][b]);
                CMUL(c->r10r[a][b], c->r10i[a][b], pur[a], pui[a], ur[a][b], ui[a][b]);
            }
        /* D = down_r12 up_r10, then (I - D)^{-1} by the adjugate. */
        double Dr[2][2], Di[2][2];
        MAT_MUL(dr, di, ur, ui, Dr, Di);
        const double pr = 1.0 - Dr[0][0], pi = -Di[0][0], qr = -Dr[0][1], qi = -Di[0][1];
        const double rr = -Dr[1][0], ri = -Di[1][0], sr = 1.0 - Dr[1][1], si = -Di[1][1];
        double ar, ai, br, bi;
        CMUL(pr, pi, sr, si, ar, ai);
        CMUL(qr, qi, rr, ri, br, bi);
        const double detr = ar - br, deti = ai - bi;
        double invr[2][2], invi[2][2];
        CDIV(sr, si, detr, deti, invr[0][0], invi[0][0]);
        CDIV(-qr, -qi, detr, deti, invr[0][1], invi[0][1]);
        CDIV(-rr, -ri, detr, deti, invr[1][0], invi[1][0]);
        CDIV(pr, pi, detr, deti, invr[1][1], invi[1][1]);
        /* entry = t01 (I - D)^{-1}: amplitudes going down at the top face. */
        double er[2][2], ei[2][2];
        MAT_MUL(c->t01r, c->t01i, invr, invi, er, ei);
        if (want_t) {
            /* T = entry diag(P_down) t12 (eq. 17). */
            double xr2[2][2], xi2[2][2];
            for (int a = 0; a < 2; a++)
                for (int b = 0; b < 2; b++) CMUL(c->t12r[a][b], c->t12i[a][b], pdr[a], pdi[a], xr2[a][b], xi2[a][b]);
            double jr[2][2], ji[2][2];
            MAT_MUL(er, ei, xr2, xi2, jr, ji);
            for (int a = 0; a < 2; a++)
                for (int b = 0; b < 2; b++) {
                    T->re[a][b][l] = jr[a][b];
                    T->im[a][b][l] = ji[a][b];
                }
        }
        if (want_r) {
            /* R = r01 + entry down_r12 diag(P_up) t10. */
            double ur2[2][2], ui2[2][2], bkr[2][2], bki[2][2];
            for (int a = 0; a < 2; a++)
                for (int b = 0; b < 2; b++) CMUL(c->t10r[a][b], c->t10i[a][b], pur[a], pui[a], ur2[a][b], ui2[a][b]);
            MAT_MUL(dr, di, ur2, ui2, bkr, bki);
            double jr[2][2], ji[2][2];
            MAT_MUL(er, ei, bkr, bki, jr, ji);
            for (int a = 0; a < 2; a++)
                for (int b = 0; b < 2; b++) {
                    R->re[a][b][l] = c->r01r[a][b] + jr[a][b];
                    R->im[a][b][l] = c->r01i[a][b] + ji[a][b];
                }
        }
    }
}

/* The block loop for the sides asked for. */
static inline __attribute__((always_inline)) void block_sides(const coefficients *c, const phases *ph, int n,
                                                               biref_jones_block *T, biref_jones_block *R)
{
    if (T && R)
        block_loop(c, ph, n, T, R, 1, 1);
    else if (T)
        block_loop(c, ph, n, T, NULL, 1, 0);
    else if (R)
        block_loop(c, ph, n, NULL, R, 0, 1);
}

/* The same code for the portable baseline and, where the processor has it, AVX2 (four lanes
 * instead of two). No FMA: the library is compiled without contraction, so both give the same
 * bits. */
static void block_baseline(const coefficients *c, const phases *ph, int n, biref_jones_block *T, biref_jones_block *R)
{
    block_sides(c, ph, n, T, R);
}

#if BIREF_NUMERIC_HAVE_AVX2
__attribute__((target("avx2"))) static void block_avx2(const coefficients *c, const phases *ph, int n,
                                                        biref_jones_block *T, biref_jones_block *R)
{
    block_sides(c, ph, n, T, R);
}
#endif

int biref_numeric_avx2_available(void)
{
#if BIREF_NUMERIC_HAVE_AVX2
    return __builtin_cpu_supports("avx2");
#else
    return 0;
#endif
}

void biref_numeric_jones_block(const biref_slab_state *st, const double *k, int n, biref_jones_block *T,
                               biref_jones_block *R)
{
    biref_numeric_jones_block_isa(st, k, n, T, R, biref_numeric_avx2_available());
}

void biref_numeric_jones_block_isa(const biref_slab_state *st, const double *k, int n, biref_jones_block *T,
                                   biref_jones_block *R, int avx2)
{
    double pd0r[BIREF_NUMERIC_BLOCK], pd0i[BIREF_NUMERIC_BLOCK], pd1r[BIREF_NUMERIC_BLOCK], pd1i[BIREF_NUMERIC_BLOCK];
    double pu0r_[BIREF_NUMERIC_BLOCK], pu0i_[BIREF_NUMERIC_BLOCK], pu1r[BIREF_NUMERIC_BLOCK], pu1i[BIREF_NUMERIC_BLOCK];
    leg_phase(st->opl_down[0], k, n, pd0r, pd0i);
    leg_phase(st->opl_down[1], k, n, pd1r, pd1i);
    /* The ordinary mode's up and down legs have the same optical path (q_o+ = -q_o-). */
    const int o_same = st->opl_up[0] == st->opl_down[0];
    const double *pu0r = o_same ? pd0r : pu0r_, *pu0i = o_same ? pd0i : pu0i_;
    if (!o_same) leg_phase(st->opl_up[0], k, n, pu0r_, pu0i_);
    leg_phase(st->opl_up[1], k, n, pu1r, pu1i);

    coefficients c;
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            c.t01r[a][b] = creal(st->top.t_down[a][b]), c.t01i[a][b] = cimag(st->top.t_down[a][b]);
            c.r10r[a][b] = creal(st->top.r_up[a][b]), c.r10i[a][b] = cimag(st->top.r_up[a][b]);
            c.r12r[a][b] = creal(st->bottom.r_down[a][b]), c.r12i[a][b] = cimag(st->bottom.r_down[a][b]);
            c.t12r[a][b] = creal(st->bottom.t_down[a][b]), c.t12i[a][b] = cimag(st->bottom.t_down[a][b]);
            c.t10r[a][b] = creal(st->top.t_up[a][b]), c.t10i[a][b] = cimag(st->top.t_up[a][b]);
            c.r01r[a][b] = creal(st->top.r_down[a][b]), c.r01i[a][b] = cimag(st->top.r_down[a][b]);
        }
    const phases ph = {pd0r, pd0i, pd1r, pd1i, pu0r, pu0i, pu1r, pu1i};
#if BIREF_NUMERIC_HAVE_AVX2
    if (avx2) {
        block_avx2(&c, &ph, n, T, R);
        return;
    }
#endif
    (void)avx2;
    block_baseline(&c, &ph, n, T, R);
}
