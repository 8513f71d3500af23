/* The legs' phases of a dispersive slab across the band, and the phase integrals of a lag from
 * the sub-band tables (subband.h, docs/PHYSICS.md §7). */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "optics/modes_internal.h"
#include "optics/slab_internal.h"
#include "spectral/phase_prefilter.h"
#include "spectral/subband.h"

/* Half the step of the central difference of the paths (in λ, nm, through the group index): its
 * truncation error ~h²/6 d³opl/dλ³ is far below the tables' for every catalogue material. */
#define DIFF_NM 0.1

/* Re(opl) of the four legs (biref_opl_footprint order) for indices n[o, e]: the normal
 * components of the modes (eq. 2) times the thickness, as biref_slab_prepare. */
static void leg_paths(const double n[2], const double axis[3], double K, double d, double opl[4])
{
    double complex q[4];
    biref_uniaxial_normal_components(n[0], n[1], axis, K, q);
    opl[BIREF_LEG_DOWN_O] = -creal(q[BIREF_MODE_O_DOWN]) * d;
    opl[BIREF_LEG_DOWN_E] = -creal(q[BIREF_MODE_E_DOWN]) * d;
    opl[BIREF_LEG_UP_O] = creal(q[BIREF_MODE_O_UP]) * d;
    opl[BIREF_LEG_UP_E] = creal(q[BIREF_MODE_E_UP]) * d;
}

/* The legs' paths at λ and their derivatives dopl/dλ: a central difference ±DIFF_NM in λ taken
 * through the indices' slopes dn/dλ = (n − n_g)/λ (one evaluation of the material). */
biref_status biref_leg_paths_and_slopes(const biref_material *m, const double axis[3], double K, double d,
                                        double lambda, double opl[4], double dopl[4])
{
    double n[2], ng[2];
    biref_status s = biref_material_indices(m, lambda, n, ng);
    if (s != BIREF_OK) return s;
    leg_paths(n, axis, K, d, opl);
    const double slope[2] = {(n[0] - ng[0]) / lambda, (n[1] - ng[1]) / lambda};
    if (slope[0] == 0.0 && slope[1] == 0.0) {
        for (int l = 0; l < 4; l++) dopl[l] = 0.0;
        return BIREF_OK;
    }
    double lo[4], hi[4];
    leg_paths((const double[2]){n[0] - DIFF_NM * slope[0], n[1] - DIFF_NM * slope[1]}, axis, K, d, lo);
    leg_paths((const double[2]){n[0] + DIFF_NM * slope[0], n[1] + DIFF_NM * slope[1]}, axis, K, d, hi);
    for (int l = 0; l < 4; l++) dopl[l] = (hi[l] - lo[l]) / (2.0 * DIFF_NM);
    return BIREF_OK;
}

/* Samples point p: the legs' phases and group paths. */
static void sample(biref_leg_dispersion *ld, int p)
{
    const double k = biref_subband_points(ld->sb)[p], lambda = 2.0 * M_PI / k;
    double opl[4], dopl[4];
    biref_status s = biref_leg_paths_and_slopes(ld->m, ld->axis, ld->K, ld->d, lambda, opl, dopl);
    if (s != BIREF_OK && ld->failed == BIREF_OK) ld->failed = s;
    for (int l = 0; l < 4; l++) {
        /* φ = k opl, φ' = d(k opl)/dk = opl − λ dopl/dλ: the group path */
        ld->phi[l][p] = s == BIREF_OK ? k * opl[l] : NAN;
        ld->grp[l][p] = s == BIREF_OK ? opl[l] - lambda * dopl[l] : NAN;
        if (s == BIREF_OK && dopl[l] != 0.0) ld->flat = 0;
    }
    ld->have[p] = 1;
}

biref_status biref_leg_dispersion_init(const biref_spectral *sp, const biref_material *m, const biref_slab *geometry,
                                       double theta, biref_leg_dispersion *ld)
{
    ld->sb = biref_spectral_subbands(sp);
    if (!ld->sb) return BIREF_ERR_NOMEM;
    ld->m = m;
    biref_axis_unit_unchecked(geometry->axis, ld->axis);
    ld->K = geometry->eta_i * sin(theta);
    ld->d = geometry->thickness_nm;
    ld->flat = 1;
    ld->failed = BIREF_OK;
    ld->cache = NULL;
    ld->node = -1;
    memset(ld->order_floor, 0, sizeof ld->order_floor);
    memset(ld->order_seen, 0, sizeof ld->order_seen);
    memset(ld->have, 0, sizeof ld->have);
    const int last = BIREF_SUBBAND_POINTS - 1;
    sample(ld, 0);
    sample(ld, last / 2);
    sample(ld, last);
    /* Flat only if no point at all depends on λ (a table may be flat in places). */
    for (int p = 1; ld->flat && ld->failed == BIREF_OK && p < last; p++)
        if (!ld->have[p]) sample(ld, p);
    return ld->failed;
}

/* The largest distance of the lag's phase Phi from the tangent at each sub-band's midpoint, at the
 * sub-band's two edges (level L: 2^L sub-bands over the sample points). */
double biref_subband_level_residual(const double *Phi, const double *G, const double *k, int level)
{
    const int span = (BIREF_SUBBAND_POINTS - 1) >> level;
    double worst = 0.0;
    for (int a = 0; a + span < BIREF_SUBBAND_POINTS; a += span) {
        const int mid = a + span / 2, e = a + span;
        worst = fmax(worst, fabs(Phi[a] - Phi[mid] - G[mid] * (k[a] - k[mid])));
        worst = fmax(worst, fabs(Phi[e] - Phi[mid] - G[mid] * (k[e] - k[mid])));
    }
    return worst;
}

/* The lag's phase and group path at sample point p. */
static void lag_at(biref_leg_dispersion *ld, const int n[4], int p, double *Phi, double *G)
{
    if (!ld->have[p]) sample(ld, p);
    Phi[p] = G[p] = 0.0;
    for (int l = 0; l < 4; l++) {
        Phi[p] += n[l] * ld->phi[l][p];
        G[p] += n[l] * ld->grp[l][p];
    }
}

/* lag_at as biref_subband_level samples the points it needs. */
typedef struct {
    biref_leg_dispersion *ld;
    const int *n;
    double *Phi, *G;
} lag_sampler;

static void sample_lag(void *ctx, int p)
{
    const lag_sampler *at = ctx;
    lag_at(at->ld, at->n, p, at->Phi, at->G);
}

int biref_subband_level(const biref_spectral *sp, const double *Phi, const double *G, const double *k, int from,
                        int to, void (*sample_point)(void *ctx, int p), void *ctx, double *residual)
{
    const int mid = (BIREF_SUBBAND_POINTS - 1) / 2;
    int level = 0;
    double res = biref_subband_level_residual(Phi, G, k, 0);
    /* Level 0 needs the ends and the middle; the finer levels every point, each tangent's group
     * path within the tables (the middle's first: where a look-up most often leaves them). */
    int inside = res > BIREF_SUBBAND_PHASE_TOL && fabs(G[mid]) <= sp->d_max;
    for (int p = from; inside && p <= to; p++) {
        if (sample_point && p != mid) sample_point(ctx, p);
        inside = fabs(G[p]) <= sp->d_max;
    }
    if (inside)
        while (res > BIREF_SUBBAND_PHASE_TOL && level < BIREF_SUBBAND_LEVELS)
            res = biref_subband_level_residual(Phi, G, k, ++level);
    *residual = res;
    return level;
}

/* The tangent of sub-band b of `level` (level 0: the whole range) at its midpoint: the offset
 * e^{i(Φ(k_b) − k_b G_b)} and the group path G_b. */
void biref_subband_tangent(const double *Phi, const double *G, const double *k, int level, int b,
                           double complex *rot, double *g)
{
    const int span = (BIREF_SUBBAND_POINTS - 1) >> level, mid = b * span + span / 2;
    *g = G[mid];
    *rot = cycles_exp((Phi[mid] - k[mid] * G[mid]) / (2.0 * M_PI));
}

/* The sums over the 2^level sub-bands of their tangents' integrals: m0 = S(e^{iΦ}, Λ_j) and
 * m1 = S(k e^{iΦ}, Λ_j). */
void biref_subband_sum(const biref_subbands *sb, const double *Phi, const double *G, const double *k, int level,
                       double complex m0[3], double complex m1[3])
{
    for (int j = 0; j < 3; j++) m0[j] = m1[j] = 0.0;
    for (int b = 0; b < (1 << level); b++) {
        double complex rot, t[3], tk[3];
        double g;
        biref_subband_tangent(Phi, G, k, level, b, &rot, &g);
        biref_subband_eval_moment(sb, level, b, g, t, tk);
        for (int j = 0; j < 3; j++) m0[j] += rot * t[j];
        for (int j = 0; j < 3; j++) m1[j] += rot * tk[j];
    }
}

/* The cache slot of lag n: where it is stored, or the free slot where it would go; -1 when the
 * table is full and n is not in it. */
static int slot(const biref_lag_cache *lc, const int n[4])
{
    unsigned h = (unsigned)(n[0] * 73856093) ^ (unsigned)(n[1] * 19349663) ^ (unsigned)(n[2] * 83492791) ^
                 (unsigned)(n[3] * 2654435761u);
    for (int probe = 0; probe < BIREF_LAG_CACHE; probe++) {
        const int i = (int)((h + (unsigned)probe) % BIREF_LAG_CACHE);
        if (!lc->used[i]) return i;
        if (lc->n[i][0] == n[0] && lc->n[i][1] == n[1] && lc->n[i][2] == n[2] && lc->n[i][3] == n[3]) return i;
    }
    return -1;
}

biref_lag_cache *biref_lag_cache_create(void)
{
    biref_lag_cache *lc = malloc(sizeof *lc);
    if (!lc) return NULL;
    lc->count = 0;
    memset(lc->used, 0, sizeof lc->used);
    return lc;
}

static int cached(const biref_lag_cache *lc, const int n[4], int node, double c[3], double s[3])
{
    const int i = lc && node >= 0 ? slot(lc, n) : -1;
    if (i < 0 || !lc->used[i]) return 0;
    for (int j = 0; j < 3; j++) c[j] = lc->c[i][node][j], s[j] = lc->s[i][node][j];
    return 1;
}

/* The integrals under each node's weight. */
static void remember(biref_lag_cache *lc, const int n[4], const double complex (*node)[3])
{
    /* Leg counts beyond a signed char (orders past 127) are not cached. */
    for (int l = 0; l < 4; l++)
        if (n[l] < -127 || n[l] > 127) return;
    const int i = lc && lc->count < BIREF_LAG_CACHE / 2 ? slot(lc, n) : -1;
    if (i < 0 || lc->used[i]) return;
    lc->used[i] = 1;
    lc->count++;
    for (int l = 0; l < 4; l++) lc->n[i][l] = (signed char)n[l];
    for (int e = 0; e < BIREF_BAND_NODES; e++)
        for (int j = 0; j < 3; j++) lc->c[i][e][j] = creal(node[e][j]), lc->s[i][e][j] = cimag(node[e][j]);
}

void biref_subband_moments(const biref_spectral *sp, const biref_subbands *sb, const double *Phi, const double *G,
                           int level, int far, double complex m0[3], double complex m1[3])
{
    const double *k = biref_subband_points(sb);
    if (level > 0) {
        biref_subband_sum(sb, Phi, G, k, level, m0, m1);
        return;
    }
    double complex rot;
    double g, c0[3], s0[3];
    biref_subband_tangent(Phi, G, k, 0, 0, &rot, &g);
    biref_spectral_phase_integrals(sp, g, c0, s0);
    const double cp = creal(rot), sn = cimag(rot);
    for (int j = 0; j < 3; j++) m0[j] = (cp * c0[j] - sn * s0[j]) + I * (sn * c0[j] + cp * s0[j]);
    if (far) return;
    double complex t[3], tk[3];
    spectral_table_eval_moment(sp, sp->table, fabs(g), t, tk);
    for (int j = 0; j < 3; j++) m1[j] = rot * (g < 0.0 ? conj(tk[j]) : tk[j]);
}

void biref_lag_integrals(const biref_spectral *sp, biref_leg_dispersion *ld, double opd, const int n[4],
                         double c[3], double s[3], int *level_out, double *residual_out)
{
    if (level_out) *level_out = -1;
    if (residual_out) *residual_out = 0.0;
    if (ld->flat) {
        biref_spectral_phase_integrals(sp, opd, c, s);
        return;
    }
    if (!level_out && !residual_out && cached(ld->cache, n, ld->node, c, s)) return;
    const double *k = biref_subband_points(ld->sb);
    double Phi[BIREF_SUBBAND_POINTS], G[BIREF_SUBBAND_POINTS];
    /* Level 0 needs the ends and the middle; the finer levels every point. */
    const int last = BIREF_SUBBAND_POINTS - 1;
    lag_at(ld, n, 0, Phi, G);
    lag_at(ld, n, last / 2, Phi, G);
    lag_at(ld, n, last, Phi, G);
    lag_sampler at = {ld, n, Phi, G};
    double res;
    const int level = biref_subband_level(sp, Phi, G, k, 1, last - 1, sample_lag, &at, &res);
    /* m0 the whole band's integral, m1 its first moment in k, which the nodes' weights need. */
    double complex m0[3], m1[3], node[BIREF_BAND_NODES][3];
    const int far = level == 0 && !(fabs(G[last / 2]) <= sp->d_max);
    biref_subband_moments(sp, ld->sb, Phi, G, level, far, m0, m1);
    biref_lag_node_integrals(biref_subband_nodes(ld->sb), m0, m1, far, node);
    remember(ld->cache, n, (const double complex(*)[3])node);
    const double complex *out = ld->node >= 0 ? node[ld->node] : m0;
    for (int j = 0; j < 3; j++) c[j] = creal(out[j]), s[j] = cimag(out[j]);
    if (level_out) *level_out = level;
    if (residual_out) *residual_out = res;
}
