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

#include "spectral/analytic_packet.h"
#include "spectral/numeric_block.h"

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

void biref_numeric_block_baseline(const coefficients *c, const phases *ph, int n, biref_jones_block *T,
                                  biref_jones_block *R)
{
    block_sides(c, ph, n, T, R);
}

/* The AVX2 object is compiled with -mavx2 -mfma (biref_isa_object): run it where the packet
 * kernel's AVX2 set runs. */
int biref_numeric_avx2_available(void) { return biref_simd_isa_supported(BIREF_SIMD_AVX2); }

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
    if (avx2)
        biref_numeric_block_avx2(&c, &ph, n, T, R);
    else
        biref_numeric_block_baseline(&c, &ph, n, T, R);
}
