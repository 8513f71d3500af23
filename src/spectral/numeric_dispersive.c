/* Numeric spectral integration of a dispersive slab (material.h): the slab is prepared anew at
 * every sample wavelength with the material's indices there, so modes, Fresnel coefficients and
 * optical paths all follow n(λ) exactly. The sums run over the plan's wavelengths in ascending
 * order with the plan's weights, as biref_spectrum_numeric's do: with constant indices every
 * sample's state is the same and the results are the same bits. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "biref/material.h"
#include "optics/slab_internal.h"
#include "spectral/integrator_internal.h"
#include "spectral/numeric_jones.h"
#include "spectral/spectral_internal.h"

/* The state at sample i. The geometry was checked by the caller; the material's indices at a
 * sample are finite and > 1 (else BIREF_ERR_INVALID), so the trusted set-up applies. */
static biref_status state_at(const biref_numeric_plan *plan, int i, const biref_material *m, const biref_slab *geometry,
                             double theta, biref_slab_state *st)
{
    biref_slab slab;
    biref_status s = biref_material_slab_at(m, geometry, plan->lambda[i], &slab);
    if (s != BIREF_OK) return s;
    return biref_slab_prepare_trusted(&slab, theta, st);
}

static biref_status check_geometry(const biref_numeric_plan *plan, const biref_material *m, const biref_slab *geometry,
                                   double theta)
{
    biref_slab slab;
    if (biref_material_slab_at(m, geometry, plan->lambda[0], &slab) != BIREF_OK) return BIREF_ERR_INVALID;
    if (biref_slab_check(&slab, NULL, 0) != BIREF_OK || biref_theta_check(theta, NULL, 0) != BIREF_OK)
        return BIREF_ERR_INVALID;
    return BIREF_OK;
}

biref_status biref_spectrum_numeric_dispersive(const biref_numeric_plan *plan, const biref_material *m,
                                               const biref_slab *geometry, double theta, biref_spectrum *out)
{
    memset(out, 0, sizeof *out);
    biref_status s = check_geometry(plan, m, geometry, theta);
    if (s != BIREF_OK) return s;
    biref_jones_block T, R;
    for (int n = 0; n < plan->samples; n++) {
        biref_slab_state st;
        s = state_at(plan, n, m, geometry, theta, &st);
        if (s != BIREF_OK) return s;
        biref_numeric_jones_block(&st, plan->k + n, 1, &T, &R);
        const double *w = plan->weight[n];
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++) {
                const double PT = T.re[i][o][0] * T.re[i][o][0] + T.im[i][o][0] * T.im[i][o][0];
                const double PR = R.re[i][o][0] * R.re[i][o][0] + R.im[i][o][0] * R.im[i][o][0];
                for (int j = 0; j < 3; j++) {
                    out->T[i][o][j] += w[j] * PT;
                    out->R[i][o][j] += w[j] * PR;
                }
            }
    }
    return BIREF_OK;
}

biref_status biref_spectrum_numeric_dispersive_polarized(const biref_numeric_plan *plan, const biref_material *m,
                                                         const biref_slab *geometry, double theta, int which,
                                                         const double complex C[2][2], const double complex P[2][2],
                                                         double xyz[3])
{
    xyz[0] = xyz[1] = xyz[2] = 0.0;
    biref_status s = check_geometry(plan, m, geometry, theta);
    if (s != BIREF_OK) return s;
    biref_jones_block B;
    for (int n = 0; n < plan->samples; n++) {
        biref_slab_state st;
        s = state_at(plan, n, m, geometry, theta, &st);
        if (s != BIREF_OK) return s;
        if (which == BIREF_REFLECTION)
            biref_numeric_jones_block(&st, plan->k + n, 1, NULL, &B);
        else
            biref_numeric_jones_block(&st, plan->k + n, 1, &B, NULL);
        const double I_det = biref_numeric_block_detected(&B, 0, C, P);
        for (int b = 0; b < 3; b++) xyz[b] += plan->weight[n][b] * I_det;
    }
    return BIREF_OK;
}

static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

/* The four pairs of both directions by the integrator's method: the numeric methods sample n(λ),
 * the closed-form ones linearise each band's phases (analytic_dispersive.c). */
static biref_status material_spectrum(const biref_integrator *it, const biref_material *m, const biref_slab *geometry,
                                      double theta, biref_spectrum *out)
{
    const biref_numeric_plan *plan = biref_integrator_plan(it);
    return plan ? biref_spectrum_numeric_dispersive(plan, m, geometry, theta, out)
                : biref_integrate_material_closed_form(it, m, geometry, theta, out);
}

biref_status biref_integrate_material_spectrum(const biref_integrator *it, const biref_material *m,
                                               const biref_slab *geometry, double theta, biref_spectrum *out)
{
    biref_status s = material_spectrum(it, m, geometry, theta, out);
    if (s != BIREF_OK) return s;
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++)
            if (!finite3(out->T[i][o]) || !finite3(out->R[i][o])) return BIREF_ERR_ILLCOND;
    return BIREF_OK;
}

biref_status biref_integrate_material(const biref_integrator *it, const biref_material *m, const biref_slab *geometry,
                                      double theta, biref_sides sides, const biref_light *light,
                                      biref_integration *out)
{
    out->order_used[0] = out->order_used[1] = -1;
    if (!(sides & BIREF_SIDE_BOTH) || (sides & ~BIREF_SIDE_BOTH)) return BIREF_ERR_INVALID;
    const biref_numeric_plan *plan = biref_integrator_plan(it);
    if (light->sp_model) {
        /* The paper's light mixes from the four pairs. */
        biref_spectrum x;
        biref_status s = material_spectrum(it, m, geometry, theta, &x);
        if (s != BIREF_OK) return s;
        if (sides & BIREF_SIDE_TRANSMISSION) biref_spectrum_mix(x.T, light->w_in, light->mask, out->T);
        if (sides & BIREF_SIDE_REFLECTION) biref_spectrum_mix(x.R, light->w_in, light->mask, out->R);
    } else {
        const double complex(*C)[2] = (const double complex(*)[2])light->C;
        const double complex(*P)[2] = light->has_analyzer ? (const double complex(*)[2])light->P : NULL;
        for (int w = 0; w < 2; w++) {
            if (!(sides & (w ? BIREF_SIDE_REFLECTION : BIREF_SIDE_TRANSMISSION))) continue;
            const int which = w ? BIREF_REFLECTION : BIREF_TRANSMISSION;
            double *xyz = w ? out->R : out->T;
            biref_status s = plan ? biref_spectrum_numeric_dispersive_polarized(plan, m, geometry, theta, which, C, P, xyz)
                                  : biref_integrate_material_closed_form_polarized(it, m, geometry, theta, which, C, P,
                                                                                   xyz, &out->order_used[w]);
            if (s != BIREF_OK) return s;
        }
    }
    if ((sides & BIREF_SIDE_TRANSMISSION) && !finite3(out->T)) return BIREF_ERR_ILLCOND;
    if ((sides & BIREF_SIDE_REFLECTION) && !finite3(out->R)) return BIREF_ERR_ILLCOND;
    return BIREF_OK;
}
