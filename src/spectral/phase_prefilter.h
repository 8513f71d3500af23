/* Spatial anti-aliasing of the phase integrals: S(cos kD) and S(sin kD) averaged over the range
 * of path differences D that one pixel covers (docs/PHYSICS.md, "Spatial anti-aliasing"). */
#ifndef BIREF_PHASE_PREFILTER_H
#define BIREF_PHASE_PREFILTER_H

#include "biref/integrator.h"
#include "biref/spectral.h"

/* Table of the antiderivative of S(e^{ikD}) over D; immutable after creation, shareable. */
typedef struct biref_phase_prefilter biref_phase_prefilter;

biref_status biref_phase_prefilter_create(const biref_spectral *sp, biref_phase_prefilter **out);
void biref_phase_prefilter_destroy(biref_phase_prefilter *pf);

/* The antiderivative table in the packet kernel's layout (biref_table_packet_layout, the
 * carriers of the point table inside), for its prefiltered look-ups (analytic_packet_kernel.inc). */
const double *biref_phase_prefilter_packet_table(const biref_phase_prefilter *pf);

/* Below this width the box average and the point value differ by < (2 pi w / 380 nm)^2 / 24 < 1e-8:
 * the point look-up is used (one table evaluation instead of two, and no cancellation). */
#define BIREF_PREFILTER_POINT_WIDTH_NM 1e-3

/* Box averages over [opd - width/2, opd + width/2] of S(cos kD) and S(sin kD) per band; width <= a
 * tiny threshold gives the point values of biref_spectral_phase_integrals. */
void biref_phase_integrals_box(const biref_phase_prefilter *pf, double opd_nm, double width_nm, double c[3],
                               double s[3]);

/* Leg types of a prepared slab state, in the order of the gradients below. */
enum { BIREF_LEG_DOWN_O = 0, BIREF_LEG_DOWN_E = 1, BIREF_LEG_UP_O = 2, BIREF_LEG_UP_E = 3 };

/* A pixel's footprint in optical path: grad[leg][k] is how much Re(opl) of that leg type changes
 * across the pixel along image axis k (x, y). Every path difference is an integer combination
 * sum_l n_l opl_l, so its change across the pixel is sum_l n_l grad[l]; the pixel averages its
 * phase integrals over a box of the same variance as that (linear) change over the square pixel. */
struct biref_leg_dispersion;
typedef struct {
    const biref_phase_prefilter *pf;
    double grad[4][2];
    /* A dispersive material's leg phases (spectral/subband.h), or NULL: every phase integral is
     * then the sum over sub-bands of the lag's tangents (docs/PHYSICS.md §7), and pf is not used. */
    struct biref_leg_dispersion *disp; /* (sampled and cached as the look-ups go) */
} biref_opl_footprint;

/* The same footprint for the state lit from the other face (biref_slab_state_flip swaps legs). */
void biref_opl_footprint_flip(const biref_opl_footprint *in, biref_opl_footprint *out);

/* Phase integrals of the path difference opd = sum_l n[l] opl_l, averaged over the footprint
 * (fp NULL: point values). */
void biref_phase_integrals_footprint(const biref_spectral *sp, const biref_opl_footprint *fp, double opd_nm,
                                     const int n[4], double c[3], double s[3]);

/* The analytic method's terms (biref_analytic_terms) and the expansion's detected intensity
 * (biref_spectrum_expansion_polarized) with every phase integral averaged over the footprint fp
 * (NULL: identical to the unfiltered functions). */
void biref_analytic_terms_footprint(const biref_spectral *sp, const biref_slab_state *st,
                                    const biref_opl_footprint *fp, int which, int pairs, double E[2][2][3],
                                    double H[2][2][3]);
biref_status biref_expansion_polarized_footprint(const biref_spectral *sp, const biref_slab_state *st,
                                                 const biref_opl_footprint *fp, int which, const double complex C[2][2],
                                                 const double complex P[2][2], const biref_expansion_opts *opts,
                                                 double xyz[3], int *order_used);

/* The four pairs of both directions (biref_spectrum_analytic, biref_spectrum_expansion) with the
 * phase integrals through the footprint fp (NULL: identical to the plain functions). */
void biref_spectrum_analytic_footprint(const biref_spectral *sp, const biref_slab_state *st,
                                       const biref_opl_footprint *fp, int pairs, biref_spectrum *out);
biref_status biref_spectrum_expansion_footprint(const biref_spectral *sp, const biref_slab_state *st,
                                                const biref_opl_footprint *fp, const biref_expansion_opts *opts,
                                                biref_spectrum *out);

/* biref_integrate with the phase integrals averaged over the footprint fp (the numeric methods,
 * which have no phase table, ignore it; NULL: identical to biref_integrate). */
biref_status biref_integrate_footprint(const biref_integrator *it, const biref_slab_state *st,
                                       const biref_opl_footprint *fp, biref_sides sides, const biref_light *light,
                                       biref_integration *out);

#endif
