/* Internal layout of the spectral context and numeric plans. */
#ifndef BIREF_SPECTRAL_INTERNAL_H
#define BIREF_SPECTRAL_INTERNAL_H

#include <complex.h>
#include <math.h>
#include <stdatomic.h>

#include "biref/experimental.h" /* the library is built with BIREF_EXPERIMENTAL_API */
#include "biref/spectral.h"

#define BIREF_COHERENT_PLANS 9
/* Round trips shorter than this (nm of optical path) put a slab in the coherent regime
 * (coherent.c, where the value is explained). */
#define BIREF_COHERENT_ROUND_TRIP_NM 10000.0

struct biref_spectral {
    biref_spectral_config cfg;
    biref_cmf_band band;
    /* Look-up table of F_j(D) = e^{-2 pi i D nu_c} S(e^{2 pi i D / lambda}, Λ_j) on D = m * step,
     * m = 0..nodes-1, stored as [m][band][re, im, dre/dD, dim/dD] for cubic Hermite
     * interpolation. Demodulating by the band-centre frequency nu_c leaves a function that
     * varies on the scale 1 / (half the band's width in 1/lambda), so a coarse step suffices. */
    double nu_c;
    double step, inv_step; /* inv_step = 1 / step, for the float lanes' node positions */
    int nodes;
    double d_max;
    double *table;
    double *carrier; /* e^{2 pi i nu_c m step} per node, [m][re, im] */
    /* The same table re-laid out for the packet kernel (biref_table_packet_layout): 16 doubles
     * per node, 64-byte aligned, so that one lane's look-up reads 32 contiguous doubles. */
    double *packet_table;
    /* The same rounded to float for the float lanes' look-ups (biref_table_packet_layout_f32):
     * 32 floats per node, 64-byte aligned. */
    float *packet_table_f32;
    /* Endpoint terms of the asymptotic expansion used beyond d_max (integration by parts):
     * S(e^{ikD}) ~ i/(2 pi D) [Λ λ^2 e^{2 pi i D/λ}]_{λmin}^{λmax}. */
    double edge_lo[3], edge_hi[3];
    /* Beyond d_far the endpoint terms are below FAR_FIELD_BOUND in every band and the integrals
     * are returned as 0 (no libm-free sine evaluations on the per-sample path). */
    double d_far;
    /* Band centroids of the wavenumber, S(2 pi / lambda, Λ_j): evanescent legs are attenuated
     * with e^{-k_j Im(opl)} per band (dispersion of the decay ignored within a band). */
    double k_centroid[3];
    /* Midpoint plans for the coherent regime (src/spectral/coherent.c), 48 * 2^i samples. */
    int n_coherent;
    biref_numeric_plan *coherent[BIREF_COHERENT_PLANS];
    /* Sub-band tables for dispersive materials (subband.h), made on first use. */
    struct biref_subbands *_Atomic subbands;
};

/* Twice the RMS width of colour-matching band j in wavenumber, S((k − k_j)², Λ_j)^½ (1/nm):
 * the span over which a dispersive phase is linearised around the band's centroid k_j. */
double biref_spectral_band_k_width(const biref_spectral *sp, int j);

/* cos and sin of a small angle (|a| <= 0.7 rad) by Taylor series to a^13: error < 1e-13.
 * Saves a libm call per look-up on the per-sample path. */
static inline void small_angle_cos_sin(double a, double *c, double *s)
{
    double a2 = a * a;
    *c = 1 + a2 * (-1.0 / 2 + a2 * (1.0 / 24 + a2 * (-1.0 / 720 + a2 * (1.0 / 40320 + a2 * (-1.0 / 3628800 + a2 * (1.0 / 479001600))))));
    *s = a * (1 + a2 * (-1.0 / 6 + a2 * (1.0 / 120 + a2 * (-1.0 / 5040 + a2 * (1.0 / 362880 + a2 * (-1.0 / 39916800 + a2 * (1.0 / 6227020800)))))));
}

/* e^{2 pi i x} for large x without libm: reduce to the nearest cycle (|f| <= 1/2), take the
 * Taylor series at f/8 (|angle| <= pi/8) and square three times (relative error ~1e-15). */
static inline double complex cycles_exp(double x)
{
    double f = x - floor(x + 0.5), c, s;
    small_angle_cos_sin(2.0 * M_PI * f / 8.0, &c, &s);
    double complex z = c + I * s;
    z *= z;
    z *= z;
    z *= z;
    return z;
}

/* A demodulated table on the context's nodes (12 doubles per node: per band the value's real and
 * imaginary parts and their derivatives in D) at 0 <= D <= d_max: cubic Hermite between nodes,
 * re-modulated by the band-centre carrier e^{2 pi i nu_c D} (node carrier times a small rotation,
 * nu_c * step < 0.11 cycles). The phase look-up table and the prefilter's antiderivative table
 * share these nodes. */
static inline void spectral_table_eval(const struct biref_spectral *sp, const double *table, double d,
                                       double complex v[3])
{
    double x = d / sp->step;
    int m = (int)x;
    if (m >= sp->nodes - 1) m = sp->nodes - 2;
    double t = x - m, t2 = t * t, t3 = t2 * t;
    double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
    const double *a = table + (size_t)m * 12, *b = a + 12;
    double cr, ci;
    small_angle_cos_sin(2.0 * M_PI * sp->nu_c * (d - m * sp->step), &cr, &ci);
    double complex carrier = (sp->carrier[2 * m] + I * sp->carrier[2 * m + 1]) * (cr + I * ci);
    for (int j = 0; j < 3; j++) {
        double re = h00 * a[4 * j] + h10 * sp->step * a[4 * j + 2] + h01 * b[4 * j] + h11 * sp->step * b[4 * j + 2];
        double im = h00 * a[4 * j + 1] + h10 * sp->step * a[4 * j + 3] + h01 * b[4 * j + 1] +
                    h11 * sp->step * b[4 * j + 3];
        v[j] = carrier * (re + I * im);
    }
}

/* spectral_table_eval and, from the same rows, the table's first moment in k: vk[j] =
 * S(k e^{ikD}, Λ_j) = -i d/dD S(e^{ikD}, Λ_j), which is the carrier times (2 pi nu_c F - i F')
 * with F the demodulated value (its derivative that of the Hermite cubic). The closed forms with
 * dispersion weigh their amplitudes linearly in k across a band (docs/PHYSICS.md §7). */
static inline void spectral_table_eval_moment(const struct biref_spectral *sp, const double *table, double d,
                                              double complex v[3], double complex vk[3])
{
    double x = d / sp->step;
    int m = (int)x;
    if (m >= sp->nodes - 1) m = sp->nodes - 2;
    double t = x - m, t2 = t * t, t3 = t2 * t;
    double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
    /* d/dt of the basis, divided by the step: d/dD */
    double g00 = (6 * t2 - 6 * t) / sp->step, g10 = 3 * t2 - 4 * t + 1, g01 = -g00, g11 = 3 * t2 - 2 * t;
    const double *a = table + (size_t)m * 12, *b = a + 12;
    double cr, ci;
    small_angle_cos_sin(2.0 * M_PI * sp->nu_c * (d - m * sp->step), &cr, &ci);
    double complex carrier = (sp->carrier[2 * m] + I * sp->carrier[2 * m + 1]) * (cr + I * ci);
    const double kc = 2.0 * M_PI * sp->nu_c;
    for (int j = 0; j < 3; j++) {
        double re = h00 * a[4 * j] + h10 * sp->step * a[4 * j + 2] + h01 * b[4 * j] + h11 * sp->step * b[4 * j + 2];
        double im = h00 * a[4 * j + 1] + h10 * sp->step * a[4 * j + 3] + h01 * b[4 * j + 1] +
                    h11 * sp->step * b[4 * j + 3];
        double dre = g00 * a[4 * j] + g10 * a[4 * j + 2] + g01 * b[4 * j] + g11 * b[4 * j + 2];
        double dim = g00 * a[4 * j + 1] + g10 * a[4 * j + 3] + g01 * b[4 * j + 1] + g11 * b[4 * j + 3];
        v[j] = carrier * (re + I * im);
        vk[j] = carrier * ((kc * re + dim) + I * (kc * im - dre));
    }
}

struct biref_numeric_plan {
    int samples;
    double *lambda;
    double *k;           /* 2 pi / lambda */
    double (*weight)[3]; /* sum over samples = 1 per band */
    /* The lanes path (numeric_lanes.h): k padded to a multiple of BIREF_NUMERIC_LANES_PAD with
     * its last value, the weights per band padded with 0; the instruction set (a biref_simd_isa,
     * BIREF_SIMD_SCALAR: the per-wavelength blocks of numeric_jones.c), the largest k. */
    int padded;
    double *wband[3];
    int isa;
    double k_max;
};

/* One hit by numeric integration: transmission of st and reflection of its flip
 * (biref_slab_state_flip) under the coherency C and analyzer P (NULL: none), band-normalised
 * XYZ; in one pass over the wavelengths where the lanes take the state (numeric_lanes.h). */
void biref_numeric_hit(const biref_numeric_plan *plan, const biref_slab_state *st, const double complex C[2][2],
                       const double complex P[2][2], double T[3], double R[3]);

/* The two terms of the analytic approximation, S(|J|^2) ~ E + 2 H (eqs. 19, 25), for
 * which = BIREF_TRANSMISSION or BIREF_REFLECTION, indexed [in][out][band]; pairs 0: the paper's
 * eq. 26 (BIREF_METHOD_ANALYTIC), 1: plus transmission's sibling and entry pairs
 * (BIREF_METHOD_ANALYTIC_PAIRS), here and in every analytic function taking it. In the coherent
 * regime (biref_coherent_plan) E is the exact integral and H is 0. */
void biref_analytic_terms(const biref_spectral *sp, const biref_slab_state *st, int which, int pairs,
                          double E[2][2][3], double H[2][2][3]);

/* sum_{i,o} w_in[i] out_mask[o] (E + 2 H)[i][o] of biref_analytic_terms, the same quantity with
 * the weights folded in before the band integrals (src/spectral/analytic_mixed.c). */
void biref_analytic_mixed(const biref_spectral *sp, const biref_slab_state *st, int which, int pairs, const double w_in[2],
                          const double out_mask[2], double xyz[3]);

/* Makes a result X [direction T/R][in][out][band] physical given the incoherent path energies E
 * (src/spectral/analytic.c): every entry >= 0 (X moved towards E where needed) and the sum over
 * outputs and directions exactly 1 per input and band (energy balance of a lossless slab). */
void biref_physical_limit(const double E[2][2][2][3], double X[2][2][2][3]);

/* E of biref_analytic_paper_terms alone: the incoherent energy of every path (eqs. 20-21), the
 * energy balance's reference (biref_physical_limit), without the look-ups of H. */
void biref_analytic_paper_energy(const biref_spectral *sp, const biref_slab_state *st, int which, double E[2][2][3]);

/* The paper's terms as printed (eqs. 20-26, m = 1; pairs 1: with the siblings), in every regime
 * (tests of the formulas). */
void biref_analytic_paper_terms(const biref_spectral *sp, const biref_slab_state *st, int which, int pairs,
                                double E[2][2][3], double H[2][2][3]);

/* The path-group series of biref_spectrum_expansion(_polarized) in every regime, without the
 * switch to the exact integral in the coherent regime (tests of the series). */
biref_status biref_expansion_series(const biref_spectral *sp, const biref_slab_state *st,
                                    const biref_expansion_opts *opts, biref_spectrum *out);
biref_status biref_expansion_series_polarized(const biref_spectral *sp, const biref_slab_state *st, int which,
                                              const double complex C[2][2], const double complex P[2][2],
                                              const biref_expansion_opts *opts, double xyz[3], int *order_used);

/* The plan that integrates this slab exactly when the fast methods' path picture does not hold
 * (thin slabs, evanescent legs coupling the faces; src/spectral/coherent.c), or NULL when it
 * does. */
const biref_numeric_plan *biref_coherent_plan(const biref_spectral *sp, const biref_slab_state *st);
/* The plan that resolves the state's closed form (eq. 17) in any regime: the numeric samples
 * biref_coherent_plan picks once it has decided the regime is coherent. */
const biref_numeric_plan *biref_resolving_plan(const biref_spectral *sp, const biref_slab_state *st);
/* For a state whose optical paths are all real: non-zero exactly when biref_coherent_plan
 * returns a plan (the slab is in the coherent regime), without computing the plan. */
int biref_coherent_real_paths(const biref_slab_state *st);

#endif
