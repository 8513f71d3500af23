/* Sub-band phase tables and per-leg dispersion: the closed forms with a dispersive material
 * (docs/PHYSICS.md §7). Every band j of the spectral context is split in wavenumber into nested
 * sub-bands (a binary tree of levels, uniform in k^2 so that they are narrower in the blue, where
 * the dispersion formulas curve most); sub-band b of level L has the table
 *
 *   T_{L,b,j}(D) = S(1_{L,b}(k) e^{ikD}, Λ_j),   sum_b T_{L,b,j} = the band's own table,
 *
 * and a lag whose phase Φ(k) = Σ_l n_l k opl_l(k) curves across the band is integrated as
 * Σ_b e^{i(Φ(k_b) − k_b Φ'(k_b))} T_{L,b}(Φ'(k_b)): the tangent of Φ at each sub-band's midpoint
 * k_b, on the coarsest level whose tangents stay within a phase tolerance of Φ. */
#ifndef BIREF_SPECTRAL_SUBBAND_H
#define BIREF_SPECTRAL_SUBBAND_H

#include "biref/material.h"
#include "spectral/spectral_internal.h"

/* Levels 1..SUBBAND_LEVELS (level L has 2^L sub-bands); level 0 is the band's own table. */
#define BIREF_SUBBAND_LEVELS 5
#define BIREF_SUBBAND_FINEST (1 << BIREF_SUBBAND_LEVELS)
/* The sample points of the legs' phases: the finest level's edges and midpoints, k_p^2 uniform. */
#define BIREF_SUBBAND_POINTS (2 * BIREF_SUBBAND_FINEST + 1)

/* The tables of one spectral context, built on first use (biref_spectral_subbands) and then
 * read-only. */
typedef struct biref_subbands biref_subbands;

/* The context's sub-band tables, built once on the first call (thread-safe); NULL when out of
 * memory. Freed with the context. */
const biref_subbands *biref_spectral_subbands(const biref_spectral *sp);
void biref_subbands_destroy(biref_subbands *sb);

/* The wavenumbers of the sample points (1/nm), ascending. */
const double *biref_subband_points(const biref_subbands *sb);

/* The demodulated table of level L (1..BIREF_SUBBAND_LEVELS), sub-band b: [node][12] in the
 * point table's layout (per band re, im, dre/dD, dim/dD), the point table's carrier. */
const double *biref_subband_table(const biref_subbands *sb, int level, int b);

/* T_{L,b,j}(D) for the three bands, any real D with |D| <= the table's d_max. */
void biref_subband_eval(const biref_subbands *sb, int level, int b, double d, double complex v[3]);

/* Phase integrals already taken for one slab, by lag (the three band runs look up the same lags):
 * an open-addressing table on the lag's leg counts; when it is full, lags are computed anew. */
#define BIREF_LAG_CACHE 256
typedef struct {
    int count;
    unsigned char used[BIREF_LAG_CACHE];
    signed char n[BIREF_LAG_CACHE][4];
    double c[BIREF_LAG_CACHE][3], s[BIREF_LAG_CACHE][3];
} biref_lag_cache;

/* The legs' phases of one slab of a dispersive material at one angle: per leg type (in
 * biref_opl_footprint order) the phase φ_l = k Re(opl_l) and the group path φ_l' = dφ_l/dk at the
 * sample points, sampled when a look-up first needs them (have[p]; the ends and the middle at
 * once). flat: no leg's path depends on the wavelength (a material of constant indices), every
 * look-up is then the plain one. failed: the status of a sample point where the material is
 * unphysical (its phases are then NaN). cache: filled by the look-ups (may be NULL). */
typedef struct biref_leg_dispersion {
    const biref_subbands *sb;
    const biref_material *m;
    double axis[3], K, d;
    int flat;
    biref_status failed;
    unsigned char have[BIREF_SUBBAND_POINTS];
    double phi[4][BIREF_SUBBAND_POINTS], grp[4][BIREF_SUBBAND_POINTS];
    biref_lag_cache *cache;
} biref_leg_dispersion;

/* The codes of biref_material_indices at the points sampled at once; BIREF_ERR_NOMEM when the
 * tables cannot be made. */
biref_status biref_leg_dispersion_init(const biref_spectral *sp, const biref_material *m, const biref_slab *geometry,
                                       double theta, biref_leg_dispersion *ld);

/* The phase tolerance of the tangents (radians, at the sub-band edges). */
#define BIREF_SUBBAND_PHASE_TOL 0.005

/* S(cos Φ), S(sin Φ) per band of the lag Σ_l n_l (leg l), opd_nm its plain path difference (used
 * as it is when the material is flat). Level 0 is the tangent at the middle sample point through
 * the band's own table (also for lags beyond the sub-band tables, where the band integral has all
 * but vanished); *level_out (may be NULL): the level used, -1 for the plain look-up;
 * *residual_out (may be NULL): the largest phase error of the tangents there (radians). */
void biref_lag_integrals(const biref_spectral *sp, biref_leg_dispersion *ld, double opd_nm, const int n[4],
                         double c[3], double s[3], int *level_out, double *residual_out);

#endif
