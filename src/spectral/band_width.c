/* The width of a colour-matching band in wavenumber, for the linearisation of dispersive phases
 * per band (analytic_dispersive.c, stack_dispersive.c): the quadratic phase a leg or a pair of
 * paths leaves across band j is ½ |d²φ/dk²| Δk² with Δk from here. */
#include <math.h>

#include "spectral/spectral_internal.h"

double biref_spectral_band_k_width(const biref_spectral *sp, int j)
{
    const double lmin = sp->cfg.lambda_min_nm, lmax = sp->cfg.lambda_max_nm;
    const int n = (int)ceil(lmax - lmin);
    const double dl = (lmax - lmin) / n;
    double var = 0.0, w = 0.0;
    for (int i = 0; i < n; i++) {
        const double l = lmin + (i + 0.5) * dl, dk = 2.0 * M_PI / l - sp->k_centroid[j];
        double lam[3];
        biref_cmf_band_eval(&sp->band, l, lam);
        var += lam[j] * dk * dk;
        w += lam[j];
    }
    return w > 0.0 ? 2.0 * sqrt(var / w) : 0.0;
}
