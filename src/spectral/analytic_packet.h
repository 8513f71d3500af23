/* The analytic method's packet kernel: many slab hits shaded at once in SIMD lanes.
 *
 * Without an evanescent mode (a slab in a surround no denser than itself, every slab of the
 * renderer in air) the mode fields, interface coefficients and optical paths of a state are
 * real, every leg's energy factor is exactly 1 and every interference term needs only the
 * cosine integral S(cos kD). analytic_mixed.c's one-pass worker (eqs. 19-26 with the energy
 * balance biref_physical_limit) then becomes branch-free real arithmetic, evaluated here for
 * PACKET lanes (structure of arrays, double precision throughout). States in total reflection,
 * in the coherent regime or with any complex coefficient are not eligible and stay on the
 * scalar path.
 *
 * One source, analytic_packet_kernel.inc (the algorithm by stage in packet_*.inc, the vector
 * primitives of each instruction set in simd/<isa>.h), is compiled once per instruction set (a
 * portable baseline, AVX2 + FMA, AVX-512: analytic_packet_<isa>.c, each with its set's compiler
 * flags, the one per-ISA mechanism of the library, CMakeLists.txt biref_isa_object); the
 * integrator picks one at creation from what the CPU supports, or from the environment variable
 * BIREF_SIMD (baseline, avx2, avx512, scalar; any other value is refused). */
#ifndef BIREF_ANALYTIC_PACKET_H
#define BIREF_ANALYTIC_PACKET_H

#include <stddef.h>

#include "biref/optics.h"
#include "biref/spectral.h"
#include "spectral/phase_prefilter.h"

/* One renderer hit: a checked slab (its axis normalised in the kernel; one far from length 1 is
 * left to the scalar path) seen at incidence parameter K = eta_i sin theta.
 * The kernel prepares it (modes, both interface solves, paths) in lanes as well. */
typedef struct {
    double eta_o, eta_e, axis[3], thickness_nm, eta_i, K;
} biref_packet_hit;

/* The kernel's input: hits as structure of arrays, so that a packet's field is one vector load
 * (no transposition; the renderer's tiles fill the columns in their loops across hits). Field f of
 * hit k is v[f * stride + k], the fields in biref_packet_hit's order (eta_o, eta_e, axis x, y, z,
 * thickness_nm, eta_i, K). */
enum { BIREF_PACKET_HIT_FIELDS = 8 };
typedef struct {
    const double *v;
    size_t stride;
} biref_packet_hits;

/* Hit k of the columns v (stride values each) set from h. */
static inline void biref_packet_hit_put(double *v, size_t stride, size_t k, const biref_packet_hit *h)
{
    const double f[BIREF_PACKET_HIT_FIELDS] = {h->eta_o,        h->eta_e, h->axis[0], h->axis[1],
                                               h->axis[2],      h->thickness_nm, h->eta_i, h->K};
    for (int i = 0; i < BIREF_PACKET_HIT_FIELDS; i++) v[(size_t)i * stride + k] = f[i];
}

/* A hit's light outside the paper's model, in the kernel's form: an incident coherency (Hermitian:
 * C00, C11 and the real part of C01 in C, the imaginary part of C01 in Ci; C10 = conj C01) in the
 * s/p basis of the incident wave and an analyzer (P00, P01, P10, P11, [in][out]: real parts in P,
 * imaginary parts in Pi) in the s/p basis of the outgoing wave, for the hit's transmission (T: its
 * state) and its reflection (R: the flipped state): e.g. a world-fixed linear polarizer and
 * analyzer resolved in the hit's two frames (Ci, Pi 0), or circular light and analyzers. */
typedef struct {
    double C[3], P[4], Ci, Pi[4];
} biref_packet_light;
typedef struct {
    biref_packet_light T, R;
} biref_packet_hit_light;

/* T[k] and R[k] as biref_integrate_hit gives them (transmission of the hit's state, reflection
 * of its flip), up to rounding, for the hits whose scalar[k] is 0; scalar[k] = 1 marks a hit the
 * kernel cannot take (an evanescent mode, the optic-axis degeneracy, a near-singular interface
 * system, the coherent regime): its T and R are undefined and it goes to the scalar path.
 * fp: NULL for point look-ups, else one footprint per hit (all of one prefilter, fp[k].pf the
 * same non-NULL table): every phase integral is then its box average over the hit's footprint,
 * as biref_integrate_footprint gives it (transmission with fp[k], reflection with its flip).
 * lights: NULL for the paper's light (w_in, mask) on every hit, else one light per hit (w_in and
 * mask unused): the general terms (analytic_general.c) with the phase integrals as above; a packet
 * with a complex light (Ci or Pi not 0) needs S(sin kD) too, which only the point look-ups give:
 * with fp, its hits are marked scalar. */
typedef void biref_packet_hits_fn(const biref_spectral *sp, const double w_in[2], const double mask[2],
                                  const biref_packet_hits *hits, size_t n, double (*T)[3], double (*R)[3],
                                  unsigned char *scalar, const biref_opl_footprint *fp,
                                  const biref_packet_hit_light *lights);
typedef biref_packet_hits_fn *biref_packet_hits_kernel;

biref_packet_hits_fn biref_packet_hits_baseline, biref_packet_hits_avx2, biref_packet_hits_avx512;

/* The same with float lanes for the terms (analytic_packet_f32_kernel.inc: set-up and look-ups in
 * double, coefficients and phase integrals then rounded to float): results within ~1e-6 of the
 * double kernels' above, which stay the reference. A light per hit takes the double kernel. */
biref_packet_hits_fn biref_packet_hits_f32_avx2, biref_packet_hits_f32_avx512;

/* The same kernels for the analytic-pairs method (PACKET_PAIRS 1: eq. 26 plus transmission's
 * siblings and entry pairs), compiled from the same sources (analytic_packet_pairs_*.c). */
biref_packet_hits_fn biref_packet_hits_pairs_baseline, biref_packet_hits_pairs_avx2, biref_packet_hits_pairs_avx512;
biref_packet_hits_fn biref_packet_hits_f32_pairs_avx2, biref_packet_hits_f32_pairs_avx512;

/* The instruction sets, fastest last. */
typedef enum {
    BIREF_SIMD_SCALAR = 0, /* no packets: every state through the scalar worker */
    BIREF_SIMD_BASELINE,   /* generic x86-64 (SSE2), 4 lanes */
    BIREF_SIMD_AVX2,       /* AVX2 + FMA, 4 lanes */
    BIREF_SIMD_AVX512,     /* AVX-512F, 8 lanes */
    BIREF_SIMD_COUNT
} biref_simd_isa;

const char *biref_simd_isa_name(biref_simd_isa isa);
/* Can this CPU run the path? */
int biref_simd_isa_supported(biref_simd_isa isa);
/* The path the integrator uses: BIREF_SIMD from the environment when set (and not empty), else
 * the fastest one the CPU supports. BIREF_ERR_INVALID for a name that is not one of scalar,
 * baseline, avx2, avx512 or one this CPU cannot run, with one line in msg naming the accepted
 * values: biref_integrator_create refuses such a value (no silent replacement). */
biref_status biref_simd_isa_pick(biref_simd_isa *out, char *msg, size_t msg_len);
/* biref_simd_isa_pick's choice, or the CPU's fastest where it fails (for the renderer's tiles,
 * whose integrator was created first and so has refused a bad BIREF_SIMD already; they should
 * rather take biref_integrator_simd of their integrator). */
biref_simd_isa biref_simd_isa_choose(void);
/* The hit kernel of a path (NULL for BIREF_SIMD_SCALAR): the integrator's, with float lanes where
 * the set has them (AVX2, AVX-512), else the double one. */
biref_packet_hits_kernel biref_simd_hits_kernel(biref_simd_isa isa);
/* The double kernel of a path (NULL for BIREF_SIMD_SCALAR): the reference the float lanes are
 * checked against. */
biref_packet_hits_kernel biref_simd_hits_kernel_f64(biref_simd_isa isa);
/* The same two for the analytic-pairs method. */
biref_packet_hits_kernel biref_simd_hits_kernel_pairs(biref_simd_isa isa);
biref_packet_hits_kernel biref_simd_hits_kernel_f64_pairs(biref_simd_isa isa);

/* Can the packet kernel take this state? Real coefficients and paths (no evanescent mode) and
 * not in the coherent regime (biref_coherent_plan(sp, st) == NULL). The same for the flipped
 * state. */
int biref_packet_eligible(const biref_spectral *sp, const biref_slab_state *st);

#endif
