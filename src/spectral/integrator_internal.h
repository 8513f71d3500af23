/* The integrator's entry points for the library's own renderer. */
#ifndef BIREF_INTEGRATOR_INTERNAL_H
#define BIREF_INTEGRATOR_INTERNAL_H

#include "biref/integrator.h"
#include "spectral/analytic_packet.h"
#include "spectral/phase_prefilter.h"

/* A renderer's slab hit: a slab that biref_slab_check accepted (the axis finite and non-zero, not
 * necessarily unit) seen at theta in [0, pi/2). */
typedef struct {
    biref_slab slab;
    double theta;
} biref_slab_hit;

/* T[k] the transmission of hit k's state (biref_slab_prepare_trusted) and R[k] the reflection
 * of the same slab lit from its other face (biref_slab_state_flip), both under one light;
 * status[k] the worse of the two evaluations' statuses or the set-up's (the outputs are then
 * undefined). The analytic method prepares and shades the hits it can in packets
 * (analytic_packet.h), the rest one by one as biref_integrate does. */
void biref_integrate_hits(const biref_integrator *it, const biref_slab_hit *hits, size_t n, const biref_light *light,
                          double (*T)[3], double (*R)[3], biref_status *status);

/* The packet kernel on hits already in its form (K = eta_i sin theta computed by the caller):
 * T[k], R[k] as biref_integrate_hits gives them for the hits whose scalar[k] is 0. scalar[k] = 1
 * marks a hit to shade with biref_integrate_hit (the kernel declined it, or the integrator has no
 * hit kernel or the light is not the paper's s/p model: then every hit). */
void biref_integrate_packet_hits(const biref_integrator *it, const biref_packet_hit *hits, size_t n,
                                 const biref_light *light, double (*T)[3], double (*R)[3], unsigned char *scalar);

/* One hit the scalar way, as biref_integrate_hits shades a hit its kernel declines. */
biref_status biref_integrate_hit(const biref_integrator *it, const biref_slab_hit *hit, const biref_light *light,
                                 double T[3], double R[3]);

/* The same two with every phase integral averaged over the hit's footprint (the prefilter,
 * docs/PHYSICS.md §6): transmission over fp[k], reflection over its flip, as
 * biref_integrate_footprint gives them. The kernel takes the hits when all footprints are of one
 * prefilter (else every scalar[k] = 1). fp NULL: the point look-ups above. */
void biref_integrate_packet_hits_footprint(const biref_integrator *it, const biref_packet_hit *hits,
                                           const biref_opl_footprint *fp, size_t n, const biref_light *light,
                                           double (*T)[3], double (*R)[3], unsigned char *scalar);
biref_status biref_integrate_hit_footprint(const biref_integrator *it, const biref_slab_hit *hit,
                                           const biref_opl_footprint *fp, const biref_light *light, double T[3],
                                           double R[3]);

/* The instruction set of the integrator's packet kernel (BIREF_SIMD_SCALAR: none). */
biref_simd_isa biref_integrator_simd(const biref_integrator *it);

#endif
