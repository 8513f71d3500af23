/* Dispersive materials (material.h): construction, indices and group indices at a wavelength,
 * the physical-range check of a band, and the slab of a material at one wavelength. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "optics/material_internal.h"
#include "optics/validate.h"

static biref_material *material_new(const char *name, const char *fallback)
{
    biref_material *m = calloc(1, sizeof *m);
    if (!m) return NULL;
    snprintf(m->name_buf, sizeof m->name_buf, "%s", name && *name ? name : fallback);
    m->name = m->name_buf;
    m->owned = 1;
    return m;
}

biref_status biref_material_from_formulas(const char *name, const biref_index_formula *o,
                                          const biref_index_formula *e, const double range_nm[2],
                                          biref_material **out, char *msg, size_t msg_len)
{
    if (!out) return biref_fail(msg, msg_len, "no output");
    *out = NULL;
    if (!o) return biref_fail(msg, msg_len, "no formula for the ordinary index");
    biref_status s = biref_formula_check(o, e ? "ordinary index" : "index", msg, msg_len);
    if (s == BIREF_OK && e) s = biref_formula_check(e, "extraordinary index", msg, msg_len);
    if (s != BIREF_OK) return s;
    if (range_nm && !(isfinite(range_nm[0]) && isfinite(range_nm[1]) && range_nm[0] > 0.0 && range_nm[1] > range_nm[0]))
        return biref_fail(msg, msg_len, "valid range %g-%g nm: expected 0 < min < max", range_nm[0], range_nm[1]);
    biref_material *m = material_new(name, "user");
    if (!m) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    m->description = "user-defined dispersion formula";
    m->source = "user";
    m->kind = MATERIAL_FORMULA;
    m->isotropic = e == NULL;
    m->formula[0] = *o;
    m->formula[1] = e ? *e : *o;
    if (range_nm) {
        m->has_range = 1;
        m->range_nm[0] = range_nm[0];
        m->range_nm[1] = range_nm[1];
    }
    *out = m;
    return BIREF_OK;
}

biref_status biref_material_constant(double eta_o, double eta_e, biref_material **out, char *msg, size_t msg_len)
{
    if (!out) return biref_fail(msg, msg_len, "no output");
    *out = NULL;
    if (!(isfinite(eta_o) && eta_o > 1.0) || !(isfinite(eta_e) && eta_e > 1.0))
        return biref_fail(msg, msg_len, "constant indices must be finite and > 1 (got %g, %g)", eta_o, eta_e);
    biref_index_formula fo = {.kind = BIREF_FORMULA_CAUCHY, .a = eta_o}, fe = {.kind = BIREF_FORMULA_CAUCHY, .a = eta_e};
    biref_status s = biref_material_from_formulas("constant", &fo, &fe, NULL, out, msg, msg_len);
    if (s == BIREF_OK) {
        (*out)->description = "constant indices (no dispersion)";
        (*out)->source = "constant";
    }
    return s;
}

void biref_material_destroy(biref_material *m)
{
    if (!m || !m->owned) return;
    free(m->lambda_nm);
    for (int c = 0; c < 2; c++) {
        free(m->column[c].n);
        free(m->column[c].slope);
    }
    free(m);
}

void biref_material_get_info(const biref_material *m, biref_material_info *out)
{
    out->name = m->name;
    out->description = m->description;
    out->source = m->source;
    out->range_nm[0] = m->has_range ? m->range_nm[0] : 0.0;
    out->range_nm[1] = m->has_range ? m->range_nm[1] : INFINITY;
    out->isotropic = m->isotropic;
}

/* n and dn/dλ (per nm) of index c (0 = o, 1 = e); 0 where unphysical. */
static int index_at(const biref_material *m, int c, double lambda_nm, double *n, double *dn_dl)
{
    if (m->isotropic) c = 0;
    if (m->kind == MATERIAL_TABLE) {
        biref_table_eval(m, c, lambda_nm, n, dn_dl);
        return isfinite(*n) && isfinite(*dn_dl) && *n > 1.0;
    }
    double dn_dx;
    if (!biref_formula_eval(&m->formula[c], lambda_nm * 1e-3, n, &dn_dx)) return 0;
    *dn_dl = dn_dx * 1e-3;
    return 1;
}

biref_status biref_material_indices(const biref_material *m, double lambda_nm, double n[2], double n_group[2])
{
    if (!(isfinite(lambda_nm) && lambda_nm > 0.0)) return BIREF_ERR_INVALID;
    for (int c = 0; c < 2; c++) {
        double v, d;
        if (!index_at(m, c, lambda_nm, &v, &d)) return BIREF_ERR_INVALID;
        n[c] = v;
        if (n_group) n_group[c] = v - lambda_nm * d; /* n_g = n − λ dn/dλ */
    }
    return BIREF_OK;
}

biref_status biref_material_check_band(const biref_material *m, double lo, double hi, char *msg, size_t msg_len)
{
    if (!(isfinite(lo) && isfinite(hi) && lo > 0.0 && hi >= lo))
        return biref_fail(msg, msg_len, "band %g-%g nm: expected 0 < min <= max", lo, hi);
    static const char *const NAMES[2] = {"n_o", "n_e"};
    for (int c = 0; c < (m->isotropic ? 1 : 2); c++) {
        const char *which = m->isotropic ? "n" : NAMES[c];
        if (m->kind == MATERIAL_FORMULA) {
            const double pole = biref_formula_pole_in(&m->formula[c], lo, hi);
            if (pole > 0.0)
                return biref_fail(msg, msg_len, "material %s: %s has a pole at %.4g nm, inside %g-%g nm", m->name,
                                  which, pole, lo, hi);
        }
        /* Every nanometre and both ends: n² <= 1 is unphysical for a lossless dielectric. */
        const int steps = (int)ceil(hi - lo) + 1;
        for (int i = 0; i <= steps; i++) {
            const double l = i == steps ? hi : lo + i < hi ? lo + i : hi;
            double v, d;
            if (!index_at(m, c, l, &v, &d))
                return biref_fail(msg, msg_len, "material %s: %s is unphysical at %g nm (n^2 <= 1 or not finite)",
                                  m->name, which, l);
        }
    }
    return BIREF_OK;
}

int biref_material_extrapolated(const biref_material *m, double lo, double hi, double out[2][2])
{
    if (!m->has_range) return 0;
    int k = 0;
    if (lo < m->range_nm[0]) {
        out[k][0] = lo;
        out[k][1] = hi < m->range_nm[0] ? hi : m->range_nm[0];
        k++;
    }
    if (hi > m->range_nm[1]) {
        out[k][0] = lo > m->range_nm[1] ? lo : m->range_nm[1];
        out[k][1] = hi;
        k++;
    }
    return k;
}

biref_status biref_material_slab_at(const biref_material *m, const biref_slab *geometry, double lambda_nm,
                                    biref_slab *out)
{
    double n[2];
    biref_status s = biref_material_indices(m, lambda_nm, n, NULL);
    if (s != BIREF_OK) return s;
    *out = *geometry;
    out->eta_o = n[0];
    out->eta_e = n[1];
    return BIREF_OK;
}
