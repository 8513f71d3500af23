/* The integrator's entry points for the library's own renderer. */
#ifndef BIREF_INTEGRATOR_INTERNAL_H
#define BIREF_INTEGRATOR_INTERNAL_H

#include <complex.h>

#include "biref/experimental.h" /* the library is built with BIREF_EXPERIMENTAL_API */
#include "biref/integrator.h"
#include "biref/stack.h"
#include "spectral/analytic_packet.h"
#include "spectral/phase_prefilter.h"

/* A renderer's slab hit: a slab that biref_slab_check accepted (the axis finite and non-zero, not
 * necessarily unit) seen at theta in [0, pi/2). */
typedef struct {
    biref_slab slab;
    double theta;
} biref_slab_hit;

/* The packet kernel on hits already in its form (K = eta_i sin theta computed by the caller):
 * T[k] the transmission of hit k's state and R[k] the reflection of the same slab lit from its
 * other face (biref_slab_state_flip), both under one light, for the hits whose scalar[k] is 0.
 * scalar[k] = 1 marks a hit to shade with biref_integrate_hit (the kernel declined it, or the
 * integrator has no hit kernel, or the light is not the paper's s/p model: then every hit).
 * fp NULL: point look-ups; else every phase integral is averaged over the hit's footprint (the
 * prefilter, docs/PHYSICS.md §6): transmission over fp[k], reflection over its flip, as
 * biref_integrate_footprint gives them. The kernel takes the hits when all footprints are of one
 * prefilter (else every scalar[k] = 1). */
void biref_integrate_packet_hits(const biref_integrator *it, const biref_packet_hits *hits,
                                 const biref_opl_footprint *fp, size_t n, const biref_light *light, double (*T)[3],
                                 double (*R)[3], unsigned char *scalar);

/* The same door for a light outside the paper's model, one per hit (world-fixed polarizers: the
 * renderer resolves its light in each hit's two frames, biref_light_at, and hands the coherency
 * and analyzer over as lights[k].T for the transmission and lights[k].R for the reflection of the
 * flipped state). T[k], R[k] equal biref_integrate_hit's under those lights
 * (biref_light_coherency + biref_light_set_analyzer of the same matrices) to rounding, for the
 * hits whose scalar[k] is 0; scalar[k] = 1 as above (every hit when the integrator is not the
 * analytic method's or the footprints are not of one prefilter). A light with complex entries
 * (circular polarisation) takes point look-ups only: with footprints its packets are marked for
 * the scalar way. */
void biref_integrate_packet_hits_lit(const biref_integrator *it, const biref_packet_hits *hits,
                                     const biref_opl_footprint *fp, size_t n, const biref_packet_hit_light *lights,
                                     double (*T)[3], double (*R)[3], unsigned char *scalar);

/* One hit the scalar way (biref_slab_prepare_trusted, then T and R as above, over the footprint
 * fp unless it is NULL); the outputs are undefined unless it returns BIREF_OK. */
biref_status biref_integrate_hit(const biref_integrator *it, const biref_slab_hit *hit, const biref_opl_footprint *fp,
                                 const biref_light *light, double T[3], double R[3]);

/* A stack of layers at a hit (docs/STACKS.md §5): T the transmission of stT under lT, R the
 * reflection of stR (the same stack lit from the viewer's face, its own frame) under lR. The analytic
 * and expansion methods integrate a stack by its path expansion (adaptive numeric integration where
 * that does not apply), the numeric methods with their plan. Outputs undefined unless BIREF_OK;
 * BIREF_ERR_ILLCOND for a non-finite result, BIREF_ERR_NOMEM. */
biref_status biref_integrate_stack_hit(const biref_integrator *it, const biref_stack_state *stT,
                                       const biref_stack_state *stR, const biref_light *lT, const biref_light *lR,
                                       double T[3], double R[3]);

/* The numeric methods' plan (NULL for the analytic and expansion methods): the dispersive
 * integration (numeric_dispersive.c) samples at its wavelengths. */
const biref_numeric_plan *biref_integrator_plan(const biref_integrator *it);
/* The spectral context and the expansion's options (analytic_dispersive.c). */
const biref_spectral *biref_integrator_spectral(const biref_integrator *it);
const biref_expansion_opts *biref_integrator_expansion_opts(const biref_integrator *it);

/* A dispersive material by the analytic method or the expansion (the integrator's), each band's
 * amplitudes at its two Gauss nodes and its phases on sub-band tangents (analytic_dispersive.c):
 * the four pairs of both
 * directions, and one direction under a general light (*order_used: the expansion's largest pair
 * order over the bands, 0 in the coherent regime, -1 for the analytic method). The codes of
 * biref_integrate_material. */
biref_status biref_integrate_material_closed_form(const biref_integrator *it, const biref_material *m,
                                                  const biref_slab *geometry, double theta, biref_spectrum *out);
biref_status biref_integrate_material_closed_form_polarized(const biref_integrator *it, const biref_material *m,
                                                            const biref_slab *geometry, double theta, int which,
                                                            const double complex C[2][2],
                                                            const double complex P[2][2], double xyz[3],
                                                            int *order_used);

/* The instruction set of the integrator's packet kernel (BIREF_SIMD_SCALAR: none). */
biref_simd_isa biref_integrator_simd(const biref_integrator *it);

#endif
