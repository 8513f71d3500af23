/* Internal pieces of the stacks' band integrals (src/spectral/stack_*.c), shared with the tests. */
#ifndef BIREF_SPECTRAL_STACK_INTERNAL_H
#define BIREF_SPECTRAL_STACK_INTERNAL_H

#include <complex.h>

#include "biref/experimental.h"
#include "biref/stack.h"

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
 * face; M[in][out] their summed amplitude. curv: for a dispersive stack's band, the curvature
 * d²(k phi)/dk² of the group's phase (nm², that of its first path: merged paths have crossed the
 * same legs in another order), else 0. */
typedef struct {
    double phi;
    double curv;
    double complex M[2][2];
} biref_stack_group;

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
 * curv (NULL: none) gives each leg's phase curvature, [layer][BIREF_MODE_*] in nm², summed into
 * the groups' curv. BIREF_ERR_NOMEM. Free with biref_stack_groups_free. */
biref_status biref_stack_path_groups(const biref_stack_state *st, const double (*curv)[4], double tolerance,
                                     int max_groups, biref_stack_groups *out);

/* What the pair sums compute: the faces (BIREF_SIDE_TRANSMISSION | BIREF_SIDE_REFLECTION), the
 * four s/p pairs (pairs != 0) or only the light's intensity, all three bands (band < 0) or band j
 * = band alone with the estimate of its linearisation error (dk: the band's width in k). */
typedef struct {
    int faces, pairs, band;
    double dk;
} biref_stack_sums;

/* The pair sums of the groups (stack_spectrum.c): out's pairs and the light's XYZ per face
 * (light may be NULL), as `what` asks (the rest left 0). With a band, *err receives the
 * estimated error of the linearised phases in it (pairs' curvature differences over the band's
 * width, each weighted by its amplitudes and band integral). BIREF_ERR_NOMEM. */
biref_status biref_stack_face_sums(const biref_spectral *sp, const biref_stack_groups *g, const biref_light *light,
                                   const biref_stack_sums *what, biref_spectrum *out, double mixed[2][3], double *err);

/* One face's detected XYZ of a prepared stack under a light by the default options of
 * biref_stack_spectrum (expansion, its fallbacks), computing that face alone and no s/p pairs:
 * the shader's stack hits. which: BIREF_SIDE_TRANSMISSION or BIREF_SIDE_REFLECTION. The codes of
 * biref_stack_spectrum. */
biref_status biref_stack_light_face(const biref_spectral *sp, const biref_stack_state *st, const biref_light *light,
                                    int which, double xyz[3]);

/* The expansion of a stack with dispersive layers, per band linearised around the band's
 * centroid (stack_dispersive.c); its fallback to adaptive numeric integration is reported in
 * info as for constant layers. BIREF_ERR_NOMEM, BIREF_ERR_INVALID (a material unphysical at a
 * band's wavelength). */
biref_status biref_stack_expansion_dispersive(const biref_spectral *sp, const biref_stack_state *st,
                                              const biref_stack_spectrum_opts *o, const biref_light *light,
                                              biref_spectrum *out, double mixed[2][3],
                                              biref_stack_spectrum_info *info);
void biref_stack_groups_free(biref_stack_groups *g);

#endif
