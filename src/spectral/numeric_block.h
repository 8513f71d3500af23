/* The numeric methods' block loop (numeric_jones.c), shared by the objects of each instruction
 * set: the portable baseline in numeric_jones.c and AVX2 in numeric_jones_avx2.c (compiled with
 * the set's flags, CMakeLists.txt biref_isa_object). The complex algebra in real arithmetic with
 * the scalar path's operations and order; no contraction in either object, so both give the same
 * bits. */
#ifndef BIREF_SPECTRAL_NUMERIC_BLOCK_H
#define BIREF_SPECTRAL_NUMERIC_BLOCK_H

#include "spectral/numeric_jones.h"

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

/* The block loop for the sides asked for, on the instruction set of the object it is compiled
 * into: numeric_jones.c (baseline) and numeric_jones_avx2.c. */
void biref_numeric_block_baseline(const coefficients *c, const phases *ph, int n, biref_jones_block *T,
                                  biref_jones_block *R);
void biref_numeric_block_avx2(const coefficients *c, const phases *ph, int n, biref_jones_block *T,
                              biref_jones_block *R);

#endif
