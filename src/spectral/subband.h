/* Sub-band phase tables and per-leg dispersion: the closed forms with a dispersive material
 * (docs/PHYSICS.md §7). Every band j of the spectral context is split in wavenumber into nested
 * sub-bands (a binary tree of levels, uniform in k^2 so that they are narrower in the blue, where
 * the dispersion formulas curve most); sub-band b of level L has the table
 *
 *   T_{L,b,j}(D) = S(1_{L,b}(k) e^{ikD}, Λ_j),   sum_b T_{L,b,j} = the band's own table,
 *
 * and a lag whose phase Φ(k) = Σ_l n_l k opl_l(k) curves across the band is integrated as
 * Σ_b e^{i(Φ(k_b) − k_b Φ'(k_b))} T_{L,b}(Φ'(k_b)): the tangent of Φ at each sub-band's midpoint
 * k_b, on the coarsest level whose tangents stay within a phase tolerance of Φ. */
#ifndef BIREF_SPECTRAL_SUBBAND_H
#define BIREF_SPECTRAL_SUBBAND_H

#include "biref/material.h"
#include "spectral/spectral_internal.h"

/* Levels 1..SUBBAND_LEVELS (level L has 2^L sub-bands); level 0 is the band's own table. */
#define BIREF_SUBBAND_LEVELS 5
#define BIREF_SUBBAND_FINEST (1 << BIREF_SUBBAND_LEVELS)
/* The sample points of the legs' phases: the finest level's edges and midpoints, k_p^2 uniform. */
#define BIREF_SUBBAND_POINTS (2 * BIREF_SUBBAND_FINEST + 1)

/* The tables of one spectral context, built on first use (biref_spectral_subbands) and then
 * read-only. */
typedef struct biref_subbands biref_subbands;

/* The context's sub-band tables, built once on the first call (thread-safe); NULL when out of
 * memory. Freed with the context. */
const biref_subbands *biref_spectral_subbands(const biref_spectral *sp);
void biref_subbands_destroy(biref_subbands *sb);

/* The wavenumbers of the sample points (1/nm), ascending. */
const double *biref_subband_points(const biref_subbands *sb);

/* The demodulated table of level L (1..BIREF_SUBBAND_LEVELS), sub-band b: [node][12] in the
 * point table's layout (per band re, im, dre/dD, dim/dD), the point table's carrier. */
const double *biref_subband_table(const biref_subbands *sb, int level, int b);

/* T_{L,b,j}(D) for the three bands, any real D with |D| <= the table's d_max. */
void biref_subband_eval(const biref_subbands *sb, int level, int b, double d, double complex v[3]);

/* T_{L,b,j}(D) and its first moment in k, S(k 1_{L,b}(k) e^{ikD}, Λ_j), from the same rows. */
void biref_subband_eval_moment(const biref_subbands *sb, int level, int b, double d, double complex v[3],
                               double complex vk[3]);

/* The wavenumbers at which the closed forms with dispersion take their amplitudes
 * (docs/PHYSICS.md §7): per band j the two Gauss nodes k[j][i] of the weight Λ_j(k) dk, and
 * mass[j][i] = S(ℓ_i, Λ_j), ℓ_i(k) the linear function of k that is 1 at node i and 0 at the
 * other. A result F(k) (a method run on the slab at k) taken as Σ_i ℓ_i(k) F(k_i) across the
 * band integrates exactly when F is a cubic in k where the band is not oscillating, and is the
 * linear interpolation of F between the nodes under every phase. Read-only, made with the
 * tables. */
#define BIREF_BAND_NODES 2
typedef struct {
    double k[3][BIREF_BAND_NODES], mass[3][BIREF_BAND_NODES];
} biref_band_nodes;

const biref_band_nodes *biref_subband_nodes(const biref_subbands *sb);

/* The nodes from the moments S((k - kref_j)^n, Λ_j), n = 0..3 (band_nodes.c); a band too narrow for two
 * nodes (a degenerate range) gets one, at its centroid, with the whole mass. */
void biref_band_nodes_choose(const double moment[3][4], const double kref[3], biref_band_nodes *bn);

/* A lag's integrals under the nodes' weights, S(ℓ_i e^{iΦ}, Λ_j) / S(ℓ_i, Λ_j) (band_nodes.c),
 * from its integrals m0 = S(e^{iΦ}, Λ_j) and m1 = S(k e^{iΦ}, Λ_j); far (m1 unknown: the lag is
 * beyond the sub-band tables, where every integral is the band's endpoint term, below 1e-3):
 * each node's is the band's. */
void biref_lag_node_integrals(const biref_band_nodes *bn, const double complex m0[3], const double complex m1[3],
                              int far, double complex node[BIREF_BAND_NODES][3]);

/* Phase integrals already taken for one slab, by lag (the six band runs look up the same lags):
 * an open-addressing table on the lag's leg counts, each entry the integrals under both nodes'
 * weights; filled to half, beyond which lags are computed anew (a thick plate's expansion asks
 * for ~500 distinct lags). Heap-allocated per call (~100 kB; biref_lag_cache_create). */
#define BIREF_LAG_CACHE 1024
typedef struct {
    int count;
    unsigned char used[BIREF_LAG_CACHE];
    signed char n[BIREF_LAG_CACHE][4];
    double c[BIREF_LAG_CACHE][BIREF_BAND_NODES][3], s[BIREF_LAG_CACHE][BIREF_BAND_NODES][3];
} biref_lag_cache;

/* An empty cache, or NULL when out of memory (the look-ups then compute every lag anew: the same
 * numbers). Freed with free(). */
biref_lag_cache *biref_lag_cache_create(void);

/* The legs' phases of one slab of a dispersive material at one angle: per leg type (in
 * biref_opl_footprint order) the phase φ_l = k Re(opl_l) and the group path φ_l' = dφ_l/dk at the
 * sample points, sampled when a look-up first needs them (have[p]; the ends and the middle at
 * once). flat: no leg's path depends on the wavelength (a material of constant indices), every
 * look-up is then the plain one. failed: the status of a sample point where the material is
 * unphysical (its phases are then NaN). cache: filled by the look-ups (may be NULL). node: -1,
 * the look-ups integrate over the whole band; i, under node i's weight ℓ_i (biref_band_nodes),
 * divided by its mass: a weighted mean over the band, as the whole band's are means. */
typedef struct biref_leg_dispersion {
    const biref_subbands *sb;
    const biref_material *m;
    double axis[3], K, d;
    int flat;
    biref_status failed;
    unsigned char have[BIREF_SUBBAND_POINTS];
    double phi[4][BIREF_SUBBAND_POINTS], grp[4][BIREF_SUBBAND_POINTS];
    biref_lag_cache *cache;
    int node;
    /* The expansion's adaptive orders ([T, R][pairs, groups]): it chooses at least order_floor
     * and records its choice in order_seen (largest since reset), so that a band's two runs can
     * be made to share their orders (analytic_dispersive.c). Zero: its own choice. */
    int order_floor[2][2], order_seen[2][2];
} biref_leg_dispersion;

/* The codes of biref_material_indices at the points sampled at once; BIREF_ERR_NOMEM when the
 * tables cannot be made. */
biref_status biref_leg_dispersion_init(const biref_spectral *sp, const biref_material *m, const biref_slab *geometry,
                                       double theta, biref_leg_dispersion *ld);

/* The phase tolerance of the tangents (radians, at the sub-band edges). */
#define BIREF_SUBBAND_PHASE_TOL 0.005

/* S(cos Φ), S(sin Φ) per band of the lag Σ_l n_l (leg l), opd_nm its plain path difference (used
 * as it is when the material is flat), over the whole band or under a node's weight (ld->node). Level 0 is the tangent at the middle sample point through
 * the band's own table (also for lags beyond the sub-band tables, where the band integral has all
 * but vanished); *level_out (may be NULL): the level used, -1 for the plain look-up;
 * *residual_out (may be NULL): the largest phase error of the tangents there (radians). */
void biref_lag_integrals(const biref_spectral *sp, biref_leg_dispersion *ld, double opd_nm, const int n[4],
                         double c[3], double s[3], int *level_out, double *residual_out);

/* Shared with the stacks' dispersive expansion (stack_legs.c), which samples its lags' phases
 * itself. Re(opl) of the four legs of a layer of material m (biref_opl_footprint order) at λ and
 * their slopes dopl/dλ (the codes of biref_material_indices). */
biref_status biref_leg_paths_and_slopes(const biref_material *m, const double axis[3], double K, double d,
                                        double lambda, double opl[4], double dopl[4]);
/* The largest distance of a phase Phi (group path G, both at every sample point k) from its
 * tangents at the midpoints of level `level`'s sub-bands, at their edges (radians). */
double biref_subband_level_residual(const double *Phi, const double *G, const double *k, int level);
/* The level of sub-bands a phase Phi (group path G, both at the sample points k) is integrated
 * on: the coarsest whose tangents stay within BIREF_SUBBAND_PHASE_TOL of Phi, level 0 (the band's
 * own table at the middle tangent) when that is within it or when a group path at the middle or
 * at points from..to lies beyond the sub-band tables (|G| > d_max), else at most
 * BIREF_SUBBAND_LEVELS; *residual: that level's (radians). Level 0 reads the ends and the middle
 * of Phi and G, a finer level every point: sample_point(ctx, p) (may be NULL: every point is
 * there) fills point p first, called only once the ends and the middle are not enough. The slab's
 * lags (biref_lag_integrals) and the stacks' pair phases (stack_legs.c) choose by it. */
int biref_subband_level(const biref_spectral *sp, const double *Phi, const double *G, const double *k, int from,
                        int to, void (*sample_point)(void *ctx, int p), void *ctx, double *residual);
/* The tangent of sub-band b of `level` (level 0: the whole range) at its midpoint: the offset
 * e^{i(Φ(k_b) − k_b G_b)} and the group path G_b. */
void biref_subband_tangent(const double *Phi, const double *G, const double *k, int level, int b,
                           double complex *rot, double *g);
/* The sums over the 2^level sub-bands of their tangents' integrals: m0 = S(e^{iΦ}, Λ_j) and
 * m1 = S(k e^{iΦ}, Λ_j). */
void biref_subband_sum(const biref_subbands *sb, const double *Phi, const double *G, const double *k, int level,
                       double complex m0[3], double complex m1[3]);
/* m0 = S(e^{iΦ}, Λ_j) and m1 = S(k e^{iΦ}, Λ_j) of a phase once its level is chosen: the sums of
 * level's sub-bands (level > 0), else the band's own table at the middle tangent, which also
 * covers the lags beyond the sub-band tables; far: beyond them, where the integral has all but
 * vanished and m1 is neither needed nor set. At level 0 only the ends and the middle of Phi and G
 * are read. */
void biref_subband_moments(const biref_spectral *sp, const biref_subbands *sb, const double *Phi, const double *G,
                           int level, int far, double complex m0[3], double complex m1[3]);

#endif
