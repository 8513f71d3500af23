/* The integrator's entry points for the library's own renderer. */
#ifndef BIREF_INTEGRATOR_INTERNAL_H
#define BIREF_INTEGRATOR_INTERNAL_H

#include "biref/integrator.h"
#include "spectral/analytic_packet.h"

/* A renderer's slab hits: T[k] the transmission of states[k] and R[k] the reflection of the
 * same slab lit from its other face (biref_slab_state_flip of states[k]), both under one light;
 * status[k] the worse of the two evaluations' statuses (the outputs are then undefined). The
 * analytic method shades the eligible states in packets (analytic_packet.h), the rest one by
 * one as biref_integrate does. */
void biref_integrate_hits(const biref_integrator *it, const biref_slab_state *states, size_t n,
                          const biref_light *light, double (*T)[3], double (*R)[3], biref_status *status);

/* The instruction set of the integrator's packet kernel (BIREF_SIMD_SCALAR: none). */
biref_simd_isa biref_integrator_simd(const biref_integrator *it);

#endif
