/* biref — the EXPERIMENTAL interface: research and test entry points. NOT STABLE.
 *
 * Everything here may change or go away in any release, without a deprecation period, and is
 * not covered by the library's compatibility promise. It is visible only to a program that
 * defines BIREF_EXPERIMENTAL_API before it includes a biref header:
 *
 *     #define BIREF_EXPERIMENTAL_API
 *     #include <biref/biref.h>
 *
 * The stable way to the same results is the integrator (integrator.h): one object per method,
 * created once, that integrates a prepared slab under any light. What is here exposes the
 * methods one by one (for reproducing the paper's figures, comparing methods and checking the
 * formulas) and test doors. The functions are exported from the shared library like the rest.
 * (docs/ARCHITECTURE.md, "Public and internal headers".) */
#ifndef BIREF_EXPERIMENTAL_H
#define BIREF_EXPERIMENTAL_H

#include "biref/common.h"
#include "biref/integrator.h"
#include "biref/material.h"
#include "biref/optics.h"
#include "biref/polarization.h"
#include "biref/render.h"
#include "biref/spectral.h"

#endif /* BIREF_EXPERIMENTAL_H */

/* A guard of its own (as zstd's static section): a translation unit that included a biref header
 * before defining BIREF_EXPERIMENTAL_API still gets these declarations on a later include. */
#if defined(BIREF_EXPERIMENTAL_API) && !defined(BIREF_EXPERIMENTAL_H_API)
#define BIREF_EXPERIMENTAL_H_API

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------- */
/* Spectral methods one by one (spectral.h has the context they share)         */
/* ------------------------------------------------------------------------- */

/* S(cos(2 pi D / lambda), Λ_j) and S(sin(...)) by direct quadrature, without the look-up table
 * (slow; for tests and for checking biref_spectral_phase_integrals). */
BIREF_API void biref_spectral_phase_integrals_direct(const biref_spectral *sp, double opd_nm, double cos_int[3],
                                                     double sin_int[3]);

/* Numeric integration plan: sample wavelengths and per-band weights for N midpoint samples,
 * normalised so that a flat spectrum gives exactly (1, 1, 1). Immutable, shareable. (The
 * integrator makes its own for BIREF_METHOD_NUMERIC and BIREF_METHOD_GROUND_TRUTH.) */
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
/* The same by the analytic-pairs method (BIREF_METHOD_ANALYTIC_PAIRS): eq. 26 plus transmission's
 * sibling and entry pairs (docs/PHYSICS.md, "Siblings"). */
BIREF_API void biref_spectrum_analytic_pairs(const biref_spectral *sp, const biref_slab_state *st,
                                             biref_spectrum *out);

/* General polarisation for numeric integration: incident coherency matrix C (s/p basis of the
 * incident wave, C[i][j] = <e_i conj(e_j)>, trace = incident intensity) and analyzer Jones
 * matrix P ([in][out] in the s/p basis of the outgoing wave; NULL = no analyzer). Detected
 * intensity per wavelength = sum_{i,j,k} C[i][j] (J P)[i][k] conj((J P)[j][k]), integrated
 * with the plan's weights. which = BIREF_TRANSMISSION or BIREF_REFLECTION. */
BIREF_API void biref_spectrum_numeric_polarized(const biref_numeric_plan *plan, const biref_slab_state *st, int which,
                                                const biref_complex C[2][2], const biref_complex P[2][2], double xyz[3]);

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

/* The four input/output pairs of transmission and reflection (like biref_spectrum_analytic). */
BIREF_API biref_status biref_spectrum_expansion(const biref_spectral *sp, const biref_slab_state *st,
                                                const biref_expansion_opts *opts, biref_spectrum *out);

/* Band-normalised energy, detected for coherency C and analyzer P (NULL = none), of all paths
 * of order > `order` added incoherently: the closed-form tail of the path-group expansion
 * (order -1: all paths). which = BIREF_TRANSMISSION or BIREF_REFLECTION. For
 * judging a truncation (bench_spectral --truncation); no allocation. */
BIREF_API void biref_expansion_tail(const biref_spectral *sp, const biref_slab_state *st, int which,
                                    const biref_complex C[2][2], const biref_complex P[2][2], int order, double out[3]);

/* ------------------------------------------------------------------------- */
/* Integrator test doors                                                       */
/* ------------------------------------------------------------------------- */

/* biref_integrate for n slab states: one light for all (light_stride 0) or one per state (1).
 * out[i] and, when not NULL, status[i] per state; returns BIREF_OK or the first failure's
 * status (BIREF_ERR_INVALID for a light_stride above 1). Each state is integrated as
 * biref_integrate integrates it. */
BIREF_API biref_status biref_integrate_batch(const biref_integrator *it, const biref_slab_state *states, size_t n,
                                             biref_sides sides, const biref_light *lights, size_t light_stride,
                                             biref_integration *out, biref_status *status);

/* ------------------------------------------------------------------------- */
/* The light model's per-ray resolution (polarization.h; a shader does this per hit) */
/* ------------------------------------------------------------------------- */

/* The light as one wave pair sees it: world-fixed parts resolved in the basis (s, p_in) of the
 * incident wave and (s, p_out) of the outgoing wave (s shared, all unit world vectors, p = k x s).
 * A light without world-fixed parts is copied unchanged. */
BIREF_API void biref_light_at(const biref_light *l, const double s[3], const double p_in[3], const double p_out[3],
                              biref_light *out);

/* The intensity a light passes through its analyzer with no slab in between (a light without
 * world-fixed parts, or one resolved by biref_light_at): sum C[i][j] P[i][k] conj(P[j][k]). */
BIREF_API double biref_light_passthrough(const biref_light *l);

/* ------------------------------------------------------------------------- */
/* Dispersive materials (material.h) through a numeric plan                    */
/* ------------------------------------------------------------------------- */

/* The dispersive counterparts of biref_spectrum_numeric and biref_spectrum_numeric_polarized:
 * the slab (geometry's axis, thickness, eta_i; the material's indices) prepared anew at every
 * sample wavelength of the plan; with constant indices the same sums in the same order.
 * BIREF_ERR_INVALID for a geometry or angle failing their checks or a sample where the material
 * is unphysical; BIREF_ERR_SINGULAR from a sample's interface solve. */
BIREF_API biref_status biref_spectrum_numeric_dispersive(const biref_numeric_plan *plan, const biref_material *m,
                                                         const biref_slab *geometry, double theta_rad,
                                                         biref_spectrum *out);
BIREF_API biref_status biref_spectrum_numeric_dispersive_polarized(const biref_numeric_plan *plan,
                                                                   const biref_material *m, const biref_slab *geometry,
                                                                   double theta_rad, int which,
                                                                   const biref_complex C[2][2],
                                                                   const biref_complex P[2][2], double xyz[3]);

/* ------------------------------------------------------------------------- */
/* Rendering part of a frame (render.h)                                        */
/* ------------------------------------------------------------------------- */

/* Renders the rectangle of pixels x .. x + width - 1, y .. y + height - 1 into a caller buffer:
 * pixel (x + i, y + j) at xyz[j * row_stride + 3 i .. + 2] (row_stride in floats, >= 3 width);
 * nothing else is written. Every pixel is bit for bit the one biref_renderer_render gives (for a
 * frame split into pieces rendered apart, e.g. by several processes), on the renderer's threads
 * (rows in parallel). stats count the rectangle's pixels. Codes as biref_renderer_render's;
 * BIREF_ERR_INVALID also for a rectangle that is empty or not inside the image. */
BIREF_API biref_status biref_renderer_render_rect(const biref_renderer *r, int x, int y, int width, int height,
                                                  float *xyz, size_t row_stride, biref_render_stats *stats);

#ifdef __cplusplus
}
#endif

#endif /* BIREF_EXPERIMENTAL_API */
