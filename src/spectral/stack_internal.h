/* Internal pieces of the stacks' band integrals (src/spectral/stack_*.c), shared with the tests. */
#ifndef BIREF_SPECTRAL_STACK_INTERNAL_H
#define BIREF_SPECTRAL_STACK_INTERNAL_H

#include <complex.h>

#include "biref/experimental.h"
#include "biref/stack.h"
#include "spectral/subband.h"

/* The adaptive numeric integration doubles its samples from FIRST up to MAX. */
#define BIREF_STACK_ADAPTIVE_FIRST 256
#define BIREF_STACK_ADAPTIVE_MAX 65536

/* Midpoint integration with a plan's samples: the four pairs and the light's XYZ (may be NULL). */
void biref_stack_spectrum_numeric(const biref_numeric_plan *plan, const biref_stack_state *st,
                                  const biref_light *light, biref_spectrum *out, double mixed_T[3], double mixed_R[3]);

/* sum_{i,j,o} C_ij (J P)_io conj((J P)_jo): the intensity a light detects through Jones matrix J. */
double biref_stack_detected(const biref_light *light, const double complex J[2][2]);

/* Numeric integration with 256, 512, ... samples until two successive runs agree to tolerance
 * (every pair and the light's XYZ, mixed[T/R][band]); *converged = 0 when MAX samples were reached
 * first (the last run is returned). BIREF_ERR_NOMEM. */
biref_status biref_stack_numeric_adaptive(const biref_spectral *sp, const biref_stack_state *st,
                                          const biref_light *light, double tolerance, biref_spectrum *out,
                                          double mixed[2][3], int *samples, int *converged);

/* A path group: paths of one optical path phi (nm, real: no evanescent layer) leaving through one
 * face; M[in][out] their summed amplitude. Dispersive stack: phi is the group path at the band's
 * wavelength, the phases are apart (id: the paths' leg counts, biref_stack_legs), else id 0. */
typedef struct {
    double phi;
    int id;
    double complex M[2][2];
} biref_stack_group;

/* The legs of a stack with dispersive layers across the band (stack_legs.c): every leg's phase
 * k Re opl(k) and group path at the sub-band tables' sample points (subband.h), legs of equal
 * phase one class, and the paths' count vectors of crossings per class, interned (id 0: none). */
typedef struct biref_stack_legs biref_stack_legs;

/* Samples the legs of a prepared dispersive state. BIREF_ERR_NOMEM; the codes of
 * biref_material_indices. Free with biref_stack_legs_destroy. */
biref_status biref_stack_legs_create(const biref_spectral *sp, const biref_stack_state *st, biref_stack_legs **out);
void biref_stack_legs_destroy(biref_stack_legs *legs);

/* Every leg's group path at λ, [layer][BIREF_MODE_*] (nm). The codes of biref_material_indices. */
biref_status biref_stack_legs_group_paths(const biref_stack_state *st, double lambda, double grp[][4]);

/* The id of counts `id` plus one crossing of (layer, BIREF_MODE_*); -1 when out of memory. */
int biref_stack_legs_child(biref_stack_legs *legs, int id, int layer, int mode);

/* S(cos Φ), S(sin Φ) per band of the phase difference Φ(k) of the paths with counts h and a
 * (Φ_h − Φ_a), by the slab's sub-band tangents (biref_lag_integrals): over the whole band
 * (node < 0) or under node `node`'s weight (biref_band_nodes, divided by its mass). A whole band's
 * pair that differs only by legs of constant index is looked up by delta (their paths'
 * difference) as a constant stack's. *residual, the error estimate of the integrals: where even
 * the finest sub-bands leave a tangent more than BIREF_SUBBAND_PHASE_TOL from Φ, that distance
 * (radians); where the group path crosses the end of the sub-band tables inside the band, the
 * estimate of stack_legs.c's crossing_error; else 0. Remembers the pairs
 * (the nodes' integrals of a band's runs and of the three bands are taken together). */
void biref_stack_legs_lag(biref_stack_legs *legs, int a, int h, double delta, int node, double c[3], double s[3],
                          double *residual);

/* 1 when no leg's path depends on the wavelength (layers of constant materials). */
int biref_stack_legs_flat(const biref_stack_legs *legs);

/* The bands' two Gauss nodes at which a dispersive stack takes its amplitudes. */
const biref_band_nodes *biref_stack_legs_nodes(const biref_stack_legs *legs);

typedef struct {
    biref_stack_group *g[2]; /* [0] bottom (transmission), [1] top (reflection), sorted by phi */
    int n[2];
    int legs;           /* generations followed (the longest path kept, in legs) */
    double bound;       /* 2A + 3A^2, A = sum of sqrt(power) of the dropped and unfinished paths */
    const char *reason; /* non-NULL: no expansion (fall back), and why */
} biref_stack_groups;

/* Follows the paths (o/e legs, reflections at every interface), merging equal optical paths,
 * until bound <= tolerance. reason set (status OK) when a layer is evanescent, when more than
 * max_groups groups leave one face, or when the bound is not met within the leg limit.
 * Dispersive (legs non-NULL): grp gives each leg's group path [layer][BIREF_MODE_*], summed into
 * the groups' phi, and the groups carry the ids of their leg counts (paths of different counts
 * are not merged); NULL, NULL: the state's optical paths. BIREF_ERR_NOMEM. Free with
 * biref_stack_groups_free. */
biref_status biref_stack_path_groups(const biref_stack_state *st, const double (*grp)[4], biref_stack_legs *legs,
                                     double tolerance, int max_groups, biref_stack_groups *out);

/* What the pair sums compute: the faces (BIREF_SIDE_TRANSMISSION | BIREF_SIDE_REFLECTION), the
 * four s/p pairs (pairs != 0) or only the light's intensity, all three bands (band < 0) or band j
 * = band alone; legs non-NULL: a dispersive stack's band, the pairs' phases by their leg counts,
 * over the whole band (node < 0) or under a node's weight (biref_stack_legs_lag). */
typedef struct {
    int faces, pairs, band;
    biref_stack_legs *legs;
    int node;
} biref_stack_sums;

/* The pair sums of the groups (stack_spectrum.c): out's pairs and the light's XYZ per face
 * (light may be NULL), as `what` asks (the rest left 0). With legs, *err receives the error
 * estimate of the pairs' phase integrals: their estimates (biref_stack_legs_lag) times their
 * amplitudes. BIREF_ERR_NOMEM. */
biref_status biref_stack_face_sums(const biref_spectral *sp, const biref_stack_groups *g, const biref_light *light,
                                   const biref_stack_sums *what, biref_spectrum *out, double mixed[2][3], double *err);

/* One face's detected XYZ of a prepared stack under a light by the default options of
 * biref_stack_spectrum (expansion, its fallbacks), computing that face alone and no s/p pairs:
 * the shader's stack hits. which: BIREF_SIDE_TRANSMISSION or BIREF_SIDE_REFLECTION. The codes of
 * biref_stack_spectrum. */
biref_status biref_stack_light_face(const biref_spectral *sp, const biref_stack_state *st, const biref_light *light,
                                    int which, double xyz[3]);

/* The expansion of a stack with dispersive layers, per band the amplitudes at the band's centroid
 * and the phases by sub-band tangents (stack_dispersive.c); its fallback to adaptive numeric integration is reported in
 * info as for constant layers. BIREF_ERR_NOMEM, BIREF_ERR_INVALID (a material unphysical at a
 * band's wavelength). */
biref_status biref_stack_expansion_dispersive(const biref_spectral *sp, const biref_stack_state *st,
                                              const biref_stack_spectrum_opts *o, const biref_light *light,
                                              biref_spectrum *out, double mixed[2][3],
                                              biref_stack_spectrum_info *info);
void biref_stack_groups_free(biref_stack_groups *g);

#endif
