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
    BIREF_METHOD_EXPANSION = 3,    /* exact integral of the path-group expansion (beyond the paper) */
    BIREF_METHOD_ANALYTIC_PAIRS = 4 /* eq. 26 plus transmission's sibling and entry pairs (beyond the paper) */
} biref_method;

#define BIREF_GROUND_TRUTH_SAMPLES 16384

/* "analytic", "numeric", "ground-truth", "expansion", "analytic-pairs". */
BIREF_API biref_status biref_method_from_name(const char *name, biref_method *out);
BIREF_API const char *biref_method_name(biref_method m);

/* S(cos(2 pi D / lambda), Λ_j) and S(sin(2 pi D / lambda), Λ_j) for an optical path
 * difference D in nm, from the look-up table (negative D allowed: cos even, sin odd). */
BIREF_API void biref_spectral_phase_integrals(const biref_spectral *sp, double opd_nm, double cos_int[3], double sin_int[3]);

/* ------------------------------------------------------------------------- */
/* Polarisation states and the exact path-group expansion (beyond the paper)  */
/* ------------------------------------------------------------------------- */

/* Stokes vectors, coherency matrices and analyzers: polarization.h. The methods one by one
 * (biref_spectrum_analytic, _numeric, _expansion, numeric plans): experimental.h. */

#define BIREF_EXPANSION_MAX_ORDER 8

typedef struct {
    int order;        /* fixed: every pair up to this order interferes, the rest incoherent; -1:
                         adaptive (default; docs/PHYSICS.md section 5) */
    double tolerance; /* adaptive: target relative intensity error of truncation (1e-3) */
    int max_order;    /* adaptive cap (default and maximum 8) */
} biref_expansion_opts;

BIREF_API void biref_expansion_opts_default(biref_expansion_opts *o);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_SPECTRAL_H */
