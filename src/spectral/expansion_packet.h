/* The path-group expansion's packet kernel (beyond the paper): slab hits shaded in SIMD lanes, for
 * the paper's s/p light, with or without the prefilter's footprints.
 *
 * For the states the analytic packet kernel takes (no evanescent mode: real coefficients and
 * paths, every leg's energy factor 1, only S(cos kD) needed) the expansion of expansion.c is real
 * arithmetic: the group amplitudes by the same recursion over half round trips, their own
 * intensities and same-order pair sums per lag, the incoherent tail and the energy balance, for
 * a hit's state (transmission) and its flip (reflection), each with both directions, in lanes.
 * Each lane keeps its own orders (masks), so a lane's result is the scalar path's to rounding and
 * never depends on its neighbours. Hits the lanes do not take go the scalar way (scalar[k] = 1):
 * those the analytic kernel declines, degenerate legs (merged groups) and pair or group orders
 * above BIREF_XP_LANE_ORDER. Groups of different orders interfere in slabs whose round trip lies
 * within the look-up table's far limit: those pairs go per lag against the kept lower orders.
 * Lights outside the paper's model (world-fixed
 * polarizers: a real coherency and analyzer per hit) take series_polarized's path: one direction
 * per side, the light's components in place of the four s/p pairs.
 *
 * One source, expansion_packet_kernel.inc, compiled per instruction set like the analytic kernel
 * (expansion_packet_<isa>.c, CMakeLists.txt biref_isa_object), on its primitives (simd/<isa>.h,
 * packet_lookup.inc, packet_setup.inc, packet_limit.inc), with its lag integrals
 * (expansion_packet_lags.inc), coherences (expansion_packet_coherence.inc), tail and order
 * choice (expansion_packet_orders.inc) and lights (expansion_packet_light.inc). */
#ifndef BIREF_EXPANSION_PACKET_H
#define BIREF_EXPANSION_PACKET_H

#include <stddef.h>

#include "spectral/analytic_packet.h"

/* The largest pair and group order in lanes. */
#define BIREF_XP_LANE_ORDER 3

/* T[k], R[k] as biref_integrate_hit gives them with the expansion (options o) under the paper's
 * light (w_in, mask: the detected fraction of each output), for the hits whose scalar[k] is 0; fp
 * as for biref_packet_hits_kernel. lights: NULL for the paper's light, else one real light per
 * hit and side (w_in and mask unused), as biref_packet_hits_kernel takes them; hits whose light is
 * diagonal in both C and P go the scalar way (the scalar expansion treats them as the paper's
 * light, with both directions' energy balance). */
typedef void (*biref_expansion_hits_kernel)(const biref_spectral *sp, const biref_expansion_opts *o,
                                            const double w_in[2], const double mask[2], const biref_packet_hits *hits,
                                            size_t n, double (*T)[3], double (*R)[3], unsigned char *scalar,
                                            const biref_opl_footprint *fp, const biref_packet_hit_light *lights);

void biref_expansion_hits_baseline(const biref_spectral *sp, const biref_expansion_opts *o, const double w_in[2],
                                   const double mask[2], const biref_packet_hits *hits, size_t n, double (*T)[3],
                                   double (*R)[3], unsigned char *scalar, const biref_opl_footprint *fp,
                                   const biref_packet_hit_light *lights);
void biref_expansion_hits_avx2(const biref_spectral *sp, const biref_expansion_opts *o, const double w_in[2],
                               const double mask[2], const biref_packet_hits *hits, size_t n, double (*T)[3],
                               double (*R)[3], unsigned char *scalar, const biref_opl_footprint *fp,
                               const biref_packet_hit_light *lights);
void biref_expansion_hits_avx512(const biref_spectral *sp, const biref_expansion_opts *o, const double w_in[2],
                                 const double mask[2], const biref_packet_hits *hits, size_t n, double (*T)[3],
                                 double (*R)[3], unsigned char *scalar, const biref_opl_footprint *fp,
                                 const biref_packet_hit_light *lights);

/* The kernel of an instruction set (NULL for BIREF_SIMD_SCALAR). */
biref_expansion_hits_kernel biref_simd_expansion_kernel(biref_simd_isa isa);

#endif
