/* The analytic method and the path-group expansion for a dispersive material (material.h),
 * closed-form (docs/PHYSICS.md §7). Per colour-matching band j the modes and Fresnel coefficients
 * are those at the band's centroid λ_j = 2π/k_j (the paper's representative permittivity per
 * band): the unchanged methods integrate that band's slab state, and only their phase integrals
 * change. Every phase integral is of a lag Φ(k) = Σ_l n_l k opl_l(k), no longer linear in k; it
 * is taken as a sum over sub-bands of Φ's tangents (subband.h, leg_dispersion.c): one tangent
 * for the whole band where that stays within the phase tolerance, else the coarsest split of the
 * band into sub-bands (up to 32, narrower in the blue) whose tangents do. The lags' integrals do
 * not depend on the band run, so they are computed once per slab (biref_lag_cache). Band j of the
 * result is taken from the band-j run. Slabs in the coherent regime (thin, or evanescent coupling), and the few whose
 * birefringent lags still curve beyond BREAK_RAD on the finest split, are integrated exactly
 * with n(λ) at every sample instead. */
#include <complex.h>
#include <math.h>
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

/* The three band states and the legs' dispersion, or the plan of the exact integration
 * (*coherent) when a band is in the coherent regime (the densest of the bands' plans) or the
 * tangents break (the plan that resolves the band-0 state). */
static biref_status band_states(const biref_spectral *sp, const biref_material *m, const biref_slab *geometry,
                                double theta, biref_slab_state st[3], biref_leg_dispersion *ld,
                                biref_lag_cache *cache, const biref_numeric_plan **coherent)
{
    biref_slab probe;
    if (biref_material_slab_at(m, geometry, 550.0, &probe) != BIREF_OK || biref_slab_check(&probe, NULL, 0) != BIREF_OK ||
        biref_theta_check(theta, NULL, 0) != BIREF_OK)
        return BIREF_ERR_INVALID;
    *coherent = NULL;
    for (int j = 0; j < 3; j++) {
        biref_status s = prepared_at(m, geometry, theta, 2.0 * M_PI / sp->k_centroid[j], &st[j]);
        if (s != BIREF_OK) return s;
        const biref_numeric_plan *p = biref_coherent_plan(sp, &st[j]);
        if (p && (!*coherent || biref_numeric_plan_samples(p) > biref_numeric_plan_samples(*coherent))) *coherent = p;
    }
    if (*coherent) return BIREF_OK;
    biref_status s = biref_leg_dispersion_init(sp, m, geometry, theta, ld);
    if (s != BIREF_OK) return s;
    ld->cache = cache; /* the residual's look-ups are among the methods' own */
    if (!ld->flat && birefringent_residual(sp, ld) > BREAK_RAD) *coherent = biref_resolving_plan(sp, &st[0]);
    return BIREF_OK;
}

/* One run of a closed-form method: the slab state whose band `band` is kept, the node whose
 * weight its lags integrate under (-1: none, the whole band) and the share of the band it stands
 * for. */
typedef struct {
    biref_slab_state st;
    int band, node;
    double share;
} band_run;

/* The runs: with constant indices one per band at its centroid (the plain methods' numbers, bit
 * for bit); with dispersion one per node of each band, on the slab at the node's wavenumber
 * (biref_band_nodes), or the plan of the exact integration when a node's state is in the
 * coherent regime. Returns the number of runs. */
static int band_runs(const biref_spectral *sp, const biref_material *m, const biref_slab *geometry, double theta,
                     const biref_slab_state st[3], const biref_leg_dispersion *ld, band_run run[3 * BIREF_BAND_NODES],
                     const biref_numeric_plan **coherent, biref_status *status)
{
    int n = 0;
    *status = BIREF_OK;
    if (ld->flat) {
        for (int j = 0; j < 3; j++) run[n++] = (band_run){st[j], j, -1, 1.0};
        return n;
    }
    const biref_band_nodes *bn = biref_subband_nodes(ld->sb);
    for (int j = 0; j < 3; j++) {
        const double total = bn->mass[j][0] + bn->mass[j][1];
        for (int i = 0; i < BIREF_BAND_NODES; i++) {
            if (!(bn->mass[j][i] > 0.0)) continue;
            band_run *r = &run[n++];
            *status = prepared_at(m, geometry, theta, 2.0 * M_PI / bn->k[j][i], &r->st);
            if (*status != BIREF_OK) return 0;
            r->band = j, r->node = i, r->share = bn->mass[j][i] / total;
            const biref_numeric_plan *c = biref_coherent_plan(sp, &r->st);
            if (c && (!*coherent || biref_numeric_plan_samples(c) > biref_numeric_plan_samples(*coherent))) *coherent = c;
        }
    }
    return n;
}

/* out_j = share x_j for the first run of band j, += for the next ones. */
static void add_share(double out[3], const double x[3], const band_run *r, int first)
{
    const int j = r->band;
    out[j] = first ? r->share * x[j] : out[j] + r->share * x[j];
}

static biref_opl_footprint dispersive_footprint(biref_leg_dispersion *ld)
{
    biref_opl_footprint fp;
    memset(&fp, 0, sizeof fp);
    fp.disp = ld;
    return fp;
}

biref_status biref_integrate_material_closed_form(const biref_integrator *it, const biref_material *m,
                                                  const biref_slab *geometry, double theta, biref_spectrum *out)
{
    const biref_spectral *sp = biref_integrator_spectral(it);
    biref_slab_state st[3];
    biref_leg_dispersion ld;
    const biref_numeric_plan *coherent;
    biref_lag_cache cache = {.count = 0};
    biref_status s = band_states(sp, m, geometry, theta, st, &ld, &cache, &coherent);
    if (s != BIREF_OK) return s;
    band_run run[3 * BIREF_BAND_NODES];
    const int runs = coherent ? 0 : band_runs(sp, m, geometry, theta, st, &ld, run, &coherent, &s);
    if (s != BIREF_OK) return s;
    if (coherent) return biref_spectrum_numeric_dispersive(coherent, m, geometry, theta, out);
    const biref_opl_footprint fp = dispersive_footprint(&ld);
    for (int r = 0; r < runs; r++) {
        biref_spectrum x;
        ld.node = run[r].node;
        if (biref_integrator_method(it) == BIREF_METHOD_EXPANSION)
            s = biref_spectrum_expansion_footprint(sp, &run[r].st, &fp, biref_integrator_expansion_opts(it), &x);
        else
            biref_spectrum_analytic_footprint(sp, &run[r].st, &fp, &x);
        if (s != BIREF_OK) return s;
        const int first = r == 0 || run[r - 1].band != run[r].band;
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++) {
                add_share(out->T[i][o], x.T[i][o], &run[r], first);
                add_share(out->R[i][o], x.R[i][o], &run[r], first);
            }
    }
    return ld.failed; /* a sample point where the material is unphysical */
}

biref_status biref_integrate_material_closed_form_polarized(const biref_integrator *it, const biref_material *m,
                                                            const biref_slab *geometry, double theta, int which,
                                                            const double complex C[2][2],
                                                            const double complex P[2][2], double xyz[3],
                                                            int *order_used)
{
    const biref_spectral *sp = biref_integrator_spectral(it);
    biref_slab_state st[3];
    biref_leg_dispersion ld;
    const biref_numeric_plan *coherent;
    biref_lag_cache cache = {.count = 0};
    biref_status s = band_states(sp, m, geometry, theta, st, &ld, &cache, &coherent);
    if (s != BIREF_OK) return s;
    band_run run[3 * BIREF_BAND_NODES];
    const int runs = coherent ? 0 : band_runs(sp, m, geometry, theta, st, &ld, run, &coherent, &s);
    if (s != BIREF_OK) return s;
    *order_used = -1;
    if (coherent) {
        *order_used = 0;
        return biref_spectrum_numeric_dispersive_polarized(coherent, m, geometry, theta, which, C, P, xyz);
    }
    const biref_opl_footprint fp = dispersive_footprint(&ld);
    for (int r = 0; r < runs; r++) {
        double x[3];
        int order = -1;
        ld.node = run[r].node;
        if (biref_integrator_method(it) == BIREF_METHOD_EXPANSION)
            s = biref_expansion_polarized_footprint(sp, &run[r].st, &fp, which, C, P, biref_integrator_expansion_opts(it),
                                                    x, &order);
        else
            biref_analytic_general(sp, &run[r].st, &fp, which, C, P, x);
        if (s != BIREF_OK) return s;
        add_share(xyz, x, &run[r], r == 0 || run[r - 1].band != run[r].band);
        if (order > *order_used) *order_used = order;
    }
    return ld.failed; /* a sample point where the material is unphysical */
}
