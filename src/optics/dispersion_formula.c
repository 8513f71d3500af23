/* Dispersion formulas of one refractive index (material.h): the Sellmeier family used by the
 * crystal literature, n² = a + Σ b λ²/(λ² − c) + Σ d/(λ² − e) + f λ², and Cauchy's series in
 * 1/λ². Their derivatives give the group index n − λ dn/dλ. */
#include <math.h>

#include "error.h"
#include "optics/material_internal.h"

int biref_formula_eval(const biref_index_formula *f, double x, double *n, double *dn_dx)
{
    double v, dv;
    const double L = x * x;
    if (f->kind == BIREF_FORMULA_CAUCHY) {
        v = f->a;
        dv = 0.0;
        double p = 1.0; /* x^(-2i) */
        for (int i = 0; i < f->n_terms; i++) {
            p /= L;
            v += f->b[i] * p;
            dv += -2.0 * (i + 1) * f->b[i] * p / x;
        }
        *n = v;
        *dn_dx = dv;
        return isfinite(v) && isfinite(dv) && v > 1.0;
    }
    /* n² and d(n²)/dx: d/dx [b L/(L − c)] = −2 b c x/(L − c)², d/dx [d/(L − e)] = −2 d x/(L − e)². */
    double n2 = f->a + f->f * L, dn2 = 2.0 * f->f * x;
    for (int i = 0; i < f->n_terms; i++) {
        const double q = L - f->c[i];
        n2 += f->b[i] * L / q;
        dn2 += -2.0 * f->b[i] * f->c[i] * x / (q * q);
    }
    for (int j = 0; j < f->n_poles; j++) {
        const double q = L - f->e[j];
        n2 += f->d[j] / q;
        dn2 += -2.0 * f->d[j] * x / (q * q);
    }
    if (!(isfinite(n2) && isfinite(dn2) && n2 > 1.0)) return 0;
    *n = sqrt(n2);
    *dn_dx = dn2 / (2.0 * *n);
    return 1;
}

biref_status biref_formula_check(const biref_index_formula *f, const char *which, char *msg, size_t msg_len)
{
    if (f->kind != BIREF_FORMULA_SELLMEIER && f->kind != BIREF_FORMULA_CAUCHY)
        return biref_fail(msg, msg_len, "%s: unknown formula kind %d", which, (int)f->kind);
    if (f->n_terms < 0 || f->n_terms > BIREF_FORMULA_MAX_TERMS)
        return biref_fail(msg, msg_len, "%s: %d terms (expected 0 to %d)", which, f->n_terms, BIREF_FORMULA_MAX_TERMS);
    const int sellmeier = f->kind == BIREF_FORMULA_SELLMEIER;
    if (sellmeier && (f->n_poles < 0 || f->n_poles > 2))
        return biref_fail(msg, msg_len, "%s: %d pole terms (expected 0 to 2)", which, f->n_poles);
    int ok = isfinite(f->a) && isfinite(f->f);
    for (int i = 0; i < f->n_terms; i++) ok = ok && isfinite(f->b[i]) && (!sellmeier || isfinite(f->c[i]));
    for (int j = 0; sellmeier && j < f->n_poles; j++) ok = ok && isfinite(f->d[j]) && isfinite(f->e[j]);
    if (!ok) return biref_fail(msg, msg_len, "%s: coefficients must be finite numbers", which);
    return BIREF_OK;
}

double biref_formula_pole_in(const biref_index_formula *f, double lo_nm, double hi_nm)
{
    if (f->kind != BIREF_FORMULA_SELLMEIER) return 0.0;
    double best = 0.0;
    for (int k = 0; k < f->n_terms + f->n_poles; k++) {
        const double c = k < f->n_terms ? f->c[k] : f->e[k - f->n_terms];
        const double coef = k < f->n_terms ? f->b[k] : f->d[k - f->n_terms];
        if (!(c > 0.0) || coef == 0.0) continue;
        const double pole_nm = 1e3 * sqrt(c);
        if (pole_nm >= lo_nm && pole_nm <= hi_nm && (best == 0.0 || pole_nm < best)) best = pole_nm;
    }
    return best;
}
