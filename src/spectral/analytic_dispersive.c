/* The analytic method and the path-group expansion for a dispersive material (material.h),
 * closed-form (docs/PHYSICS.md §7). Per colour-matching band j the modes and Fresnel coefficients
 * are those at the band's two Gauss nodes (band_nodes.c): the unchanged methods integrate the
 * slab state at each node, their phase integrals under the node's linear weight, and band j of the
 * result is the two runs' band j added by the weights' masses (the amplitudes interpolated
 * linearly in k across the band; the paper takes them at one representative permittivity). Every
 * phase integral is of a lag Φ(k) = Σ_l n_l k opl_l(k), no longer linear in k; it is taken as a
 * sum over sub-bands of Φ's tangents (subband.h, leg_dispersion.c): one tangent for the whole band
 * where that stays within the phase tolerance, else the coarsest split of the band into sub-bands
 * (up to 32, narrower in the blue) whose tangents do. The lags' integrals do not depend on the
 * run, so they are computed once per slab (biref_lag_cache). Slabs in the coherent regime (thin,
 * or evanescent coupling), and the few whose birefringent lags still curve beyond BREAK_RAD on the
 * finest split, are integrated exactly with n(λ) at every sample instead; constant indices run
 * once per band at its centroid, the plain methods' numbers. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/material.h"
#include "optics/slab_internal.h"
#include "spectral/analytic_terms.h"
#include "spectral/integrator_internal.h"
#include "spectral/spectral_internal.h"
#include "spectral/subband.h"

/* Where the tangents break: a birefringent lag whose finest tangents still miss its phase by
 * more than this at a sub-band edge (radians). docs/PHYSICS.md §7 says which plates reach it. */
#define BREAK_RAD 0.25

static biref_status prepared_at(const biref_material *m, const biref_slab *geometry, double theta, double lambda,
                                biref_slab_state *st)
{
    biref_slab s;
    biref_status r = biref_material_slab_at(m, geometry, lambda, &s);
    return r != BIREF_OK ? r : biref_slab_prepare_trusted(&s, theta, st);
}

/* The largest residual phase of the birefringent lags e − o (down, up, both) at the level the
 * look-up chooses. */
static double birefringent_residual(const biref_spectral *sp, biref_leg_dispersion *ld)
{
    static const int lags[3][4] = {{-1, 1, 0, 0}, {0, 0, -1, 1}, {-1, 1, -1, 1}};
    double worst = 0.0;
    for (int i = 0; i < 3; i++) {
        double c[3], s[3], res;
        int level;
        biref_lag_integrals(sp, ld, 0.0, lags[i], c, s, &level, &res);
        worst = fmax(worst, res);
    }
    return worst;
}

/* One run of a closed-form method: the slab state whose band `band` is kept, the node whose
 * weight its lags integrate under (-1: none, the whole band) and the share of the band it stands
 * for. */
typedef struct {
    biref_slab_state st;
    int band, node;
    double share;
} band_run;

/* What a dispersive slab's integration does: the exact integration by `coherent` (non-NULL), or
 * the closed-form runs, looking up the lags through ld (its cache heap-allocated, may be NULL). */
typedef struct {
    const biref_numeric_plan *coherent;
    biref_leg_dispersion ld;
    band_run run[3 * BIREF_BAND_NODES];
    int runs;
} dispersive_plan;

static void consider(const biref_spectral *sp, const biref_slab_state *st, const biref_numeric_plan **coherent)
{
    const biref_numeric_plan *p = biref_coherent_plan(sp, st);
    if (p && (!*coherent || biref_numeric_plan_samples(p) > biref_numeric_plan_samples(*coherent))) *coherent = p;
}

/* The runs: with constant indices one per band at its centroid (the plain methods' numbers, bit
 * for bit); with dispersion one per node of each band, on the slab at the node's wavenumber
 * (biref_band_nodes). The exact integration instead when a band's or a node's state is in the
 * coherent regime (the densest of their plans) or the tangents break (the plan that resolves
 * the band-0 state). pl->ld.cache is to be freed whatever the status. */
static biref_status plan(const biref_spectral *sp, const biref_material *m, const biref_slab *geometry, double theta,
                         dispersive_plan *pl)
{
    pl->coherent = NULL;
    pl->runs = 0;
    pl->ld.cache = NULL;
    biref_slab probe;
    if (biref_material_slab_at(m, geometry, 550.0, &probe) != BIREF_OK || biref_slab_check(&probe, NULL, 0) != BIREF_OK ||
        biref_theta_check(theta, NULL, 0) != BIREF_OK)
        return BIREF_ERR_INVALID;
    biref_slab_state st[3];
    for (int j = 0; j < 3; j++) {
        biref_status s = prepared_at(m, geometry, theta, 2.0 * M_PI / sp->k_centroid[j], &st[j]);
        if (s != BIREF_OK) return s;
        consider(sp, &st[j], &pl->coherent);
    }
    if (pl->coherent) return BIREF_OK;
    biref_leg_dispersion *ld = &pl->ld;
    biref_status s = biref_leg_dispersion_init(sp, m, geometry, theta, ld);
    if (s != BIREF_OK) return s;
    if (ld->flat) {
        for (int j = 0; j < 3; j++) pl->run[pl->runs++] = (band_run){st[j], j, -1, 1.0};
        return BIREF_OK;
    }
    ld->cache = biref_lag_cache_create(); /* the residual's look-ups are among the methods' own */
    if (birefringent_residual(sp, ld) > BREAK_RAD) {
        pl->coherent = biref_resolving_plan(sp, &st[0]);
        return BIREF_OK;
    }
    const biref_band_nodes *bn = biref_subband_nodes(ld->sb);
    for (int j = 0; j < 3; j++) {
        const double total = bn->mass[j][0] + bn->mass[j][1];
        for (int i = 0; i < BIREF_BAND_NODES; i++) {
            if (!(bn->mass[j][i] > 0.0)) continue;
            band_run *r = &pl->run[pl->runs++];
            s = prepared_at(m, geometry, theta, 2.0 * M_PI / bn->k[j][i], &r->st);
            if (s != BIREF_OK) return s;
            r->band = j, r->node = i, r->share = bn->mass[j][i] / total;
            consider(sp, &r->st, &pl->coherent);
        }
    }
    return BIREF_OK;
}

/* One run of the method the integrator holds, on run r: the four pairs of both directions (C
 * NULL) or one direction under a general light (into x->T[0][0]). The expansion records its
 * orders in pl->ld.order_seen, from pl->ld.order_floor up. */
static biref_status run_method(const biref_integrator *it, dispersive_plan *pl, int r, int which,
                               const double complex (*C)[2], const double complex (*P)[2], biref_spectrum *x,
                               int *order)
{
    const biref_spectral *sp = biref_integrator_spectral(it);
    biref_opl_footprint fp;
    memset(&fp, 0, sizeof fp);
    fp.disp = &pl->ld;
    pl->ld.node = pl->run[r].node;
    memset(pl->ld.order_seen, 0, sizeof pl->ld.order_seen);
    const biref_slab_state *st = &pl->run[r].st;
    if (biref_integrator_method(it) != BIREF_METHOD_EXPANSION) {
        const int pairs = biref_integrator_method(it) == BIREF_METHOD_ANALYTIC_PAIRS;
        if (C)
            biref_analytic_general(sp, st, &fp, which, pairs, C, P, x->T[0][0]);
        else
            biref_spectrum_analytic_footprint(sp, st, &fp, pairs, x);
        return BIREF_OK;
    }
    const biref_expansion_opts *o = biref_integrator_expansion_opts(it);
    return C ? biref_expansion_polarized_footprint(sp, st, &fp, which, C, P, o, x->T[0][0], order)
             : biref_spectrum_expansion_footprint(sp, st, &fp, o, x);
}

/* Every run, then, for the expansion, again the runs whose orders fell below the other run's of
 * their band (the band's results are added, so its runs share their orders); x[r] the results. */
static biref_status all_runs(const biref_integrator *it, dispersive_plan *pl, int which,
                             const double complex (*C)[2], const double complex (*P)[2], biref_spectrum *x,
                             int *order_used)
{
    int seen[3 * BIREF_BAND_NODES][2][2], order = -1;
    for (int r = 0; r < pl->runs; r++) {
        memset(pl->ld.order_floor, 0, sizeof pl->ld.order_floor);
        biref_status s = run_method(it, pl, r, which, C, P, &x[r], &order);
        if (s != BIREF_OK) return s;
        memcpy(seen[r], pl->ld.order_seen, sizeof seen[r]);
        if (order > *order_used) *order_used = order;
    }
    if (biref_integrator_method(it) != BIREF_METHOD_EXPANSION) return pl->ld.failed;
    for (int r = 0; r < pl->runs; r++) {
        int floor[2][2] = {{0, 0}, {0, 0}}, below = 0;
        for (int q = 0; q < pl->runs; q++)
            for (int d = 0; pl->run[q].band == pl->run[r].band && d < 2; d++)
                for (int e = 0; e < 2; e++) floor[d][e] = seen[q][d][e] > floor[d][e] ? seen[q][d][e] : floor[d][e];
        for (int d = 0; d < 2; d++)
            for (int e = 0; e < 2; e++) below |= seen[r][d][e] < floor[d][e];
        if (!below) continue;
        memcpy(pl->ld.order_floor, floor, sizeof floor);
        biref_status s = run_method(it, pl, r, which, C, P, &x[r], &order);
        if (s != BIREF_OK) return s;
        if (order > *order_used) *order_used = order;
    }
    return pl->ld.failed; /* a sample point where the material is unphysical */
}

/* out_j = share x_j for the first run of band j, += for its next ones. */
static void add_share(const dispersive_plan *pl, int r, const double x[3], double out[3])
{
    const int j = pl->run[r].band;
    const double v = pl->run[r].share * x[j];
    out[j] = r == 0 || pl->run[r - 1].band != j ? v : out[j] + v;
}

biref_status biref_integrate_material_closed_form(const biref_integrator *it, const biref_material *m,
                                                  const biref_slab *geometry, double theta, biref_spectrum *out)
{
    dispersive_plan pl;
    biref_spectrum x[3 * BIREF_BAND_NODES];
    int order = -1;
    biref_status s = plan(biref_integrator_spectral(it), m, geometry, theta, &pl);
    if (s == BIREF_OK && pl.coherent)
        s = biref_spectrum_numeric_dispersive(pl.coherent, m, geometry, theta, out);
    else if (s == BIREF_OK && (s = all_runs(it, &pl, 0, NULL, NULL, x, &order)) == BIREF_OK)
        for (int r = 0; r < pl.runs; r++)
            for (int i = 0; i < 2; i++)
                for (int o = 0; o < 2; o++) {
                    add_share(&pl, r, x[r].T[i][o], out->T[i][o]);
                    add_share(&pl, r, x[r].R[i][o], out->R[i][o]);
                }
    free(pl.ld.cache);
    return s;
}

biref_status biref_integrate_material_closed_form_polarized(const biref_integrator *it, const biref_material *m,
                                                            const biref_slab *geometry, double theta, int which,
                                                            const double complex C[2][2],
                                                            const double complex P[2][2], double xyz[3],
                                                            int *order_used)
{
    dispersive_plan pl;
    biref_spectrum x[3 * BIREF_BAND_NODES];
    biref_status s = plan(biref_integrator_spectral(it), m, geometry, theta, &pl);
    *order_used = -1;
    if (s == BIREF_OK && pl.coherent) {
        *order_used = 0;
        s = biref_spectrum_numeric_dispersive_polarized(pl.coherent, m, geometry, theta, which, C, P, xyz);
    } else if (s == BIREF_OK && (s = all_runs(it, &pl, which, C, P, x, order_used)) == BIREF_OK)
        for (int r = 0; r < pl.runs; r++) add_share(&pl, r, x[r].T[0][0], xyz);
    free(pl.ld.cache);
    return s;
}
