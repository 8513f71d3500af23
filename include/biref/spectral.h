/* biref — spectral integration of slab intensities over colour-matching functions (paper §5).
 *
 * A biref_spectral object holds the band-normalised sensitivity functions and the look-up
 * tables of S(cos(k D), Λ_j) and S(sin(k D), Λ_j); it is immutable after creation and may be
 * shared by any number of threads. Results are band-normalised: a wavelength-independent
 * intensity f integrates to (f, f, f). */
#ifndef BIREF_SPECTRAL_H
#define BIREF_SPECTRAL_H

#include "biref/color.h"
#include "biref/common.h"
#include "biref/optics.h"
#include "biref/polarization.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    biref_cmf_kind cmf;     /* default BIREF_CMF_CIE1931 */
    double lambda_min_nm;   /* default 380 */
    double lambda_max_nm;   /* default 700 */
} biref_spectral_config;

BIREF_API void biref_spectral_config_default(biref_spectral_config *cfg);

typedef struct biref_spectral biref_spectral;

/* BIREF_ERR_INVALID for an unknown cmf, a non-finite or inverted range (min >= max, min <= 0),
 * a range outside the colour-matching data (biref_cmf_domain) or one where a band integrates to
 * zero. */
BIREF_API biref_status biref_spectral_create(const biref_spectral_config *cfg, biref_spectral **out, char *msg,
                                             size_t msg_len);
BIREF_API void biref_spectral_destroy(biref_spectral *sp);
BIREF_API const biref_cmf_band *biref_spectral_band(const biref_spectral *sp);

/* Band-normalised integrals of |J[in][out]|^2 for transmission and reflection,
 * [input s/p][output s/p][band x/y/z]. */
typedef struct {
    double T[2][2][3];
    double R[2][2][3];
} biref_spectrum;

typedef enum {
    BIREF_METHOD_ANALYTIC = 0,     /* the paper's approximation, eq. 26 with m = 1 */
    BIREF_METHOD_NUMERIC = 1,      /* N uniform midpoint samples of eq. 17 */
    BIREF_METHOD_GROUND_TRUTH = 2, /* numeric with N = 16384 (paper §6) */
    BIREF_METHOD_EXPANSION = 3     /* exact integral of the path-group expansion (beyond the paper) */
} biref_method;

#define BIREF_GROUND_TRUTH_SAMPLES 16384

/* "analytic", "numeric", "ground-truth", "expansion". */
BIREF_API biref_status biref_method_from_name(const char *name, biref_method *out);
BIREF_API const char *biref_method_name(biref_method m);

/* Numeric integration plan: sample wavelengths and per-band weights for N midpoint samples,
 * normalised so that a flat spectrum gives exactly (1, 1, 1). Immutable, shareable. */
typedef struct biref_numeric_plan biref_numeric_plan;

/* BIREF_ERR_INVALID for samples outside 1..2^24 (one-line reason in msg). */
BIREF_API biref_status biref_numeric_plan_create(const biref_spectral *sp, int samples, biref_numeric_plan **out,
                                                 char *msg, size_t msg_len);
BIREF_API void biref_numeric_plan_destroy(biref_numeric_plan *plan);
BIREF_API int biref_numeric_plan_samples(const biref_numeric_plan *plan);

/* Numeric integration of the closed-form Jones matrices (no allocation). */
BIREF_API void biref_spectrum_numeric(const biref_numeric_plan *plan, const biref_slab_state *st, biref_spectrum *out);

/* The paper's analytic approximation (eqs. 20–26, m = 1) for all four input/output pairs,
 * transmission and reflection (no allocation). */
BIREF_API void biref_spectrum_analytic(const biref_spectral *sp, const biref_slab_state *st, biref_spectrum *out);

/* S(cos(2 pi D / lambda), Λ_j) and S(sin(2 pi D / lambda), Λ_j) for an optical path
 * difference D in nm, from the look-up table (negative D allowed: cos even, sin odd). */
BIREF_API void biref_spectral_phase_integrals(const biref_spectral *sp, double opd_nm, double cos_int[3], double sin_int[3]);

/* The same integrals by direct quadrature (slow; for tests and for checking the table). */
BIREF_API void biref_spectral_phase_integrals_direct(const biref_spectral *sp, double opd_nm, double cos_int[3],
                                                     double sin_int[3]);

/* General polarisation for numeric integration: incident coherency matrix C (s/p basis of the
 * incident wave, C[i][j] = <e_i conj(e_j)>, trace = incident intensity) and analyzer Jones
 * matrix P ([in][out] in the s/p basis of the outgoing wave; NULL = no analyzer). Detected
 * intensity per wavelength = sum_{i,j,k} C[i][j] (J P)[i][k] conj((J P)[j][k]), integrated
 * with the plan's weights. which = BIREF_TRANSMISSION or BIREF_REFLECTION. */
BIREF_API void biref_spectrum_numeric_polarized(const biref_numeric_plan *plan, const biref_slab_state *st, int which,
                                                const biref_complex C[2][2], const biref_complex P[2][2], double xyz[3]);

/* ------------------------------------------------------------------------- */
/* Polarisation states and the exact path-group expansion (beyond the paper)  */
/* ------------------------------------------------------------------------- */

/* Stokes vectors, coherency matrices and analyzers: polarization.h. */

#define BIREF_EXPANSION_MAX_ORDER 8

typedef struct {
    int order;        /* fixed: every pair up to this order interferes, the rest incoherent; -1:
                         adaptive (default; docs/PHYSICS.md section 5) */
    double tolerance; /* adaptive: target relative intensity error of truncation (1e-3) */
    int max_order;    /* adaptive cap (default and maximum 8) */
} biref_expansion_opts;

BIREF_API void biref_expansion_opts_default(biref_expansion_opts *o);

/* Exact spectral integral of the path-group expansion J(k) = sum_g M_g e^{ik Phi_g} (groups of
 * paths with equal optical path) up to the chosen order, every pair of groups interfering via
 * the S(cos), S(sin) table; adaptive runs add the own intensity of up to two more orders' groups;
 * paths beyond are added incoherently in closed form. Detected intensity for incident coherency
 * C and analyzer P (NULL = none), which = BIREF_TRANSMISSION or BIREF_REFLECTION. *order_used
 * (the pair order) may be NULL. No allocation; about 250 KB of stack per call (threads created
 * with small stacks need at least 512 KB). BIREF_ERR_INVALID for options outside their domain
 * (biref_integrator_create says which), BIREF_ERR_ILLCOND for a non-finite result. */
BIREF_API biref_status biref_spectrum_expansion_polarized(const biref_spectral *sp, const biref_slab_state *st, int which,
                                                          const biref_complex C[2][2], const biref_complex P[2][2],
                                                          const biref_expansion_opts *opts, double xyz[3], int *order_used);

/* Band-normalised energy, detected for coherency C and analyzer P (NULL = none), of all paths
 * of order > `order` added incoherently: the closed-form tail of the path-group expansion
 * (order -1: all paths). which = BIREF_TRANSMISSION or BIREF_REFLECTION. For
 * judging a truncation (bench_spectral --truncation); no allocation. */
BIREF_API void biref_expansion_tail(const biref_spectral *sp, const biref_slab_state *st, int which,
                                    const biref_complex C[2][2], const biref_complex P[2][2], int order, double out[3]);

/* The four input/output pairs of transmission and reflection (like biref_spectrum_analytic). */
BIREF_API biref_status biref_spectrum_expansion(const biref_spectral *sp, const biref_slab_state *st,
                                                const biref_expansion_opts *opts, biref_spectrum *out);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_SPECTRAL_H */
