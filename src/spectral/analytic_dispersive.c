/* The analytic method and the path-group expansion for a dispersive material (material.h),
 * closed-form: per colour-matching band j, the phase of every leg is linearised in the
 * wavenumber around the band's centroid k_j (docs/PHYSICS.md, "Dispersion in the closed-form
 * methods"):
 *
 *   k opl(k) ≈ k opl_g + ψ,   opl_g = opl − λ d opl/dλ (the group optical path),
 *                              ψ = k_j (opl − opl_g) = 2π d opl/dλ, all at λ_j = 2π/k_j,
 *
 * with the modes and Fresnel coefficients at λ_j (the paper's representative permittivity per
 * band). A path's phase is the sum of its legs', so every path keeps the form amplitude ×
 * e^{ik·(group path)} with the legs' offsets e^{iψ} as constant factors: they are folded into the
 * interface coefficient that ends each leg, and the band-j state is an ordinary slab state that the
 * unchanged methods integrate (the offsets turn S(cos kD) into cos ψ S(cos kD) − sin ψ S(sin kD)).
 * Band j of the result is taken from the band-j state. Slabs in the coherent regime (thin, or
 * evanescent coupling), and slabs whose lag phases curve too much across a band for a line
 * (QUADRATIC_PHASE_MAX_RAD), are integrated exactly with n(λ) at every sample instead. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "biref/material.h"
#include "optics/slab_internal.h"
#include "spectral/analytic_terms.h"
#include "spectral/integrator_internal.h"
#include "spectral/spectral_internal.h"

/* Half the step of the central difference of the optical paths in λ (nm): its truncation error,
 * ~h²/6 · d³opl/dλ³, is far below the table's for every catalogue material. */
#define DISPERSION_DIFF_NM 0.1
/* Half the step of the second difference of the phases in λ (nm): long enough that rounding in
 * k·opl (~1e4 rad for a mm slab) stays below 1e-4 rad in the curvature. */
#define CURVATURE_DIFF_NM 5.0
/* Where the linearisation breaks: the quadratic phase ½ |φ''| Δk² of a birefringent lag across a
 * band (Δk: twice the band's RMS width in k) times the largest band integral its group delay
 * reaches, above this; such slabs are integrated exactly instead. Chosen by measurement
 * (docs/ACCURACY.md, "Dispersive materials"): at 0.1 calcite and sapphire views linearised with
 * this product below it still reach ΔE00 1.7 and 1.0 against the ground truth; at 0.02 every
 * linearised view of the five test plates is within 0.2. */
#define QUADRATIC_PHASE_MAX_RAD 0.02

static biref_status prepared_at(const biref_material *m, const biref_slab *geometry, double theta, double lambda,
                                biref_slab_state *st)
{
    biref_slab s;
    biref_status r = biref_material_slab_at(m, geometry, lambda, &s);
    return r != BIREF_OK ? r : biref_slab_prepare_trusted(&s, theta, st);
}

static void scale_row(double complex M[2][2], int row, double complex f)
{
    M[row][0] *= f;
    M[row][1] *= f;
}

/* The birefringent lags' phases k·(e − o) (down, up, and both) at λ, for their curvature in k. */
static void lag_phases(const biref_slab_state *st, double lambda, double out[3])
{
    const double k = 2.0 * M_PI / lambda;
    out[0] = k * creal(st->opl_down[1] - st->opl_down[0]);
    out[1] = k * creal(st->opl_up[1] - st->opl_up[0]);
    out[2] = out[0] + out[1];
}

/* The largest effect of the quadratic phase ½ |d²φ/dk²| Δk² of a birefringent lag across band j:
 * that phase (radians) times the largest band integral |S_j| the lag's group delay reaches across
 * the band, d(kD)/dk = D_g ± |d²φ/dk²| Δk (a lag whose band integral is small carries little
 * colour, and a curved phase there changes little). mid: the band's state before linearisation. */
static biref_status band_curvature(const biref_spectral *sp, const biref_material *m, const biref_slab *geometry,
                                   double theta, int j, const biref_slab_state *mid, const double group[3],
                                   double *quad)
{
    const double lambda = 2.0 * M_PI / sp->k_centroid[j], H = CURVATURE_DIFF_NM;
    biref_slab_state a, b;
    biref_status s = prepared_at(m, geometry, theta, lambda - H, &a);
    if (s == BIREF_OK) s = prepared_at(m, geometry, theta, lambda + H, &b);
    if (s != BIREF_OK) return s;
    double pa[3], pm[3], pb[3];
    lag_phases(&a, lambda - H, pa);
    lag_phases(mid, lambda, pm);
    lag_phases(&b, lambda + H, pb);
    const double ka = 2.0 * M_PI / (lambda - H), km = 2.0 * M_PI / lambda, kb = 2.0 * M_PI / (lambda + H);
    const double dk = biref_spectral_band_k_width(sp, j);
    *quad = 0.0;
    for (int l = 0; l < 3; l++) {
        /* second derivative through three unevenly spaced points (kb < km < ka) */
        const double d2 = 2.0 * ((pa[l] - pm[l]) / (ka - km) - (pm[l] - pb[l]) / (km - kb)) / (ka - kb);
        double smax = 0.0;
        for (int e = -1; e <= 1; e++) {
            double c[3], si[3];
            biref_spectral_phase_integrals(sp, group[l] + e * fabs(d2) * dk, c, si);
            smax = fmax(smax, hypot(c[j], si[j]));
        }
        *quad = fmax(*quad, 0.5 * fabs(d2) * dk * dk * smax);
    }
    return BIREF_OK;
}

/* The linearised state of band j (see the top of the file); *quad its largest quadratic phase. */
static biref_status band_state(const biref_spectral *sp, const biref_material *m, const biref_slab *geometry,
                               double theta, int j, biref_slab_state *st, double *quad)
{
    const double lambda = 2.0 * M_PI / sp->k_centroid[j], h = DISPERSION_DIFF_NM;
    biref_slab_state lo, hi;
    biref_status s = prepared_at(m, geometry, theta, lambda, st);
    if (s == BIREF_OK) s = prepared_at(m, geometry, theta, lambda - h, &lo);
    if (s == BIREF_OK) s = prepared_at(m, geometry, theta, lambda + h, &hi);
    if (s != BIREF_OK) return s;
    const biref_slab_state unlinearised = *st;
    for (int up = 0; up < 2; up++)
        for (int x = 0; x < 2; x++) {
            double complex *opl = up ? &st->opl_up[x] : &st->opl_down[x];
            const double dopl = creal((up ? hi.opl_up[x] : hi.opl_down[x]) - (up ? lo.opl_up[x] : lo.opl_down[x])) /
                                (2.0 * h);
            const double psi = 2.0 * M_PI * dopl; /* k_j (opl − opl_g) with opl_g = opl − λ dopl/dλ */
            *opl = (creal(*opl) - lambda * dopl) + I * cimag(*opl); /* the decay stays at λ_j */
            /* The offset of a leg rides on the coefficients of the interface that ends it. */
            const double complex f = cexp(I * psi);
            if (up) {
                scale_row(st->top.r_up, x, f);
                scale_row(st->top.t_up, x, f);
            } else {
                scale_row(st->bottom.r_down, x, f);
                scale_row(st->bottom.t_down, x, f);
            }
        }
    const double group[3] = {creal(st->opl_down[1] - st->opl_down[0]), creal(st->opl_up[1] - st->opl_up[0]),
                             creal(st->opl_down[1] - st->opl_down[0] + st->opl_up[1] - st->opl_up[0])};
    return band_curvature(sp, m, geometry, theta, j, &unlinearised, group, quad);
}

/* The three band states, or the plan of the exact integration (*coherent) when a band is in the
 * coherent regime (the densest of the bands' plans) or its phases are too curved to linearise
 * (the plan that resolves the band-0 state). */
static biref_status band_states(const biref_spectral *sp, const biref_material *m, const biref_slab *geometry,
                                double theta, biref_slab_state st[3], const biref_numeric_plan **coherent)
{
    biref_slab probe;
    if (biref_material_slab_at(m, geometry, 550.0, &probe) != BIREF_OK || biref_slab_check(&probe, NULL, 0) != BIREF_OK ||
        biref_theta_check(theta, NULL, 0) != BIREF_OK)
        return BIREF_ERR_INVALID;
    *coherent = NULL;
    double quad = 0.0;
    for (int j = 0; j < 3; j++) {
        double q;
        biref_status s = band_state(sp, m, geometry, theta, j, &st[j], &q);
        if (s != BIREF_OK) return s;
        quad = fmax(quad, q);
        const biref_numeric_plan *p = biref_coherent_plan(sp, &st[j]);
        if (p && (!*coherent || biref_numeric_plan_samples(p) > biref_numeric_plan_samples(*coherent))) *coherent = p;
    }
    if (!*coherent && quad > QUADRATIC_PHASE_MAX_RAD) *coherent = biref_resolving_plan(sp, &st[0]);
    return BIREF_OK;
}

biref_status biref_integrate_material_closed_form(const biref_integrator *it, const biref_material *m,
                                                  const biref_slab *geometry, double theta, biref_spectrum *out)
{
    const biref_spectral *sp = biref_integrator_spectral(it);
    biref_slab_state st[3];
    const biref_numeric_plan *coherent;
    biref_status s = band_states(sp, m, geometry, theta, st, &coherent);
    if (s != BIREF_OK) return s;
    if (coherent) return biref_spectrum_numeric_dispersive(coherent, m, geometry, theta, out);
    for (int j = 0; j < 3; j++) {
        biref_spectrum x;
        if (biref_integrator_method(it) == BIREF_METHOD_EXPANSION)
            s = biref_spectrum_expansion(sp, &st[j], biref_integrator_expansion_opts(it), &x);
        else
            biref_spectrum_analytic(sp, &st[j], &x);
        if (s != BIREF_OK) return s;
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++) {
                out->T[i][o][j] = x.T[i][o][j];
                out->R[i][o][j] = x.R[i][o][j];
            }
    }
    return BIREF_OK;
}

biref_status biref_integrate_material_closed_form_polarized(const biref_integrator *it, const biref_material *m,
                                                            const biref_slab *geometry, double theta, int which,
                                                            const double complex C[2][2],
                                                            const double complex P[2][2], double xyz[3],
                                                            int *order_used)
{
    const biref_spectral *sp = biref_integrator_spectral(it);
    biref_slab_state st[3];
    const biref_numeric_plan *coherent;
    biref_status s = band_states(sp, m, geometry, theta, st, &coherent);
    if (s != BIREF_OK) return s;
    *order_used = -1;
    if (coherent) {
        *order_used = 0;
        return biref_spectrum_numeric_dispersive_polarized(coherent, m, geometry, theta, which, C, P, xyz);
    }
    for (int j = 0; j < 3; j++) {
        double x[3];
        int order = -1;
        if (biref_integrator_method(it) == BIREF_METHOD_EXPANSION)
            s = biref_spectrum_expansion_polarized(sp, &st[j], which, C, P, biref_integrator_expansion_opts(it), x, &order);
        else
            biref_analytic_general(sp, &st[j], NULL, which, C, P, x);
        if (s != BIREF_OK) return s;
        xyz[j] = x[j];
        if (order > *order_used) *order_used = order;
    }
    return BIREF_OK;
}
