/* The two demodulated phase tables of a band (paper §5.2): the point table of
 * F_j(D) = e^{-2 pi i nu_c D} S(e^{2 pi i D / lambda}, Λ_j) (spectral_context.c) and the
 * prefilter's table of its antiderivative (phase_prefilter.c), both by the midpoint rule over
 * the wavelengths. The build-time generator (tools/phase_tables/) runs the same functions for
 * the default band and writes them into the library, so a process with the default
 * configuration copies its tables instead of building them (docs/PERFORMANCE.md, "Serial ends"). */
#ifndef BIREF_SPECTRAL_PHASE_TABLES_H
#define BIREF_SPECTRAL_PHASE_TABLES_H

#include "biref/color.h"
#include "biref/common.h"
#include "biref/spectral.h"

/* Table resolution. Hermite interpolation of the demodulated F has error ~ (2 pi B h)^4 / 384
 * with B = half the band width in 1/lambda (6e-4 / nm for 380-700 nm, at most 8e-4 / nm for the
 * widest band allowed, 360-830 nm): 3e-6 and 1e-5 at h = 50 nm. Beyond D_MAX the endpoint
 * asymptotics are accurate to ~1e-5 (docs/PHYSICS.md). */
#define BIREF_TABLE_STEP_NM 50.0
#define BIREF_TABLE_D_MAX_NM 1.0e5
/* Quadrature step for building both tables: midpoint rule, whose error for e^{i phi} is the
 * multiplicative factor 1 + (phi' h)^2 / 24; at D_MAX, phi' h <= 0.22 rad. */
#define BIREF_TABLE_BUILD_DLAMBDA_NM 0.05
/* Doubles per node of both tables: [band][re, im, dre/dD, dim/dD]. */
#define BIREF_TABLE_ROW 12

/* The nodes D = m * step, m = 0..nodes-1, of a band [lambda_min, lambda_max] demodulated by nu_c. */
typedef struct {
    const biref_cmf_band *band;
    double lambda_min_nm, lambda_max_nm;
    double nu_c, step;
    int nodes;
} biref_phase_grid;

/* The grid of a band: nu_c the band-centre frequency, the step and node count above. */
void biref_phase_grid_init(biref_phase_grid *g, const biref_cmf_band *band, double lambda_min_nm, double lambda_max_nm);

/* Adds the table of F (point) or of q(D) = e^{-2 pi i nu_c D} Q(D), Q the antiderivative of S
 * (prefilter), to `table` (nodes * BIREF_TABLE_ROW doubles, zeroed by the caller). The same bits
 * for any number of threads. BIREF_ERR_NOMEM if the per-wavelength scratch cannot be allocated. */
biref_status biref_phase_table_point(const biref_phase_grid *g, double *table);
biref_status biref_phase_table_prefilter(const biref_phase_grid *g, double *table);

/* The tables written at build time for one band (phase_tables_generated.c in the build tree). */
typedef struct {
    biref_cmf_kind cmf;
    double lambda_min_nm, lambda_max_nm;
    int nodes; /* 0: none were generated (the library then builds every table at run time) */
    const double *point, *prefilter;
} biref_phase_tables_builtin;

extern const biref_phase_tables_builtin biref_phase_tables_generated;

/* The generated tables if they are those of this configuration and node count, else NULL
 * (spectral_context.c; not part of the generator). */
const biref_phase_tables_builtin *biref_phase_tables_builtin_for(const biref_spectral_config *cfg, int nodes);

#endif
