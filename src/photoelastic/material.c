/* Photoelastic materials, principal stresses and the per-point uniaxial slab
 * (docs/PHOTOELASTICITY.md, "Model" and "Materials"). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "biref/photoelastic.h"

/* Nominal handbook values; docs/PHOTOELASTICITY.md lists the sources and the spread between
 * grades. C is given in Brewster (1e-12 / Pa); the fringe constant follows as f = lambda / C. */
static const biref_pe_material PRESETS[] = {
    {"polycarbonate", "Dally & Riley, Experimental Stress Analysis (4th ed.), table of photoelastic "
                      "materials: f = 7.0 kN/m at 546.1 nm (PSM-1 type sheet)",
     1.586, 78.0 * BIREF_BREWSTER, BIREF_PE_LAMBDA_REF_NM, 0.0},
    {"epoxy", "Dally & Riley (4th ed.): epoxy (Araldite B type) f = 11.0 kN/m at 546.1 nm", 1.57,
     50.0 * BIREF_BREWSTER, BIREF_PE_LAMBDA_REF_NM, 0.0},
    {"pmma", "Dally & Riley (4th ed.): polymethyl methacrylate f = 130 kN/m at 546.1 nm", 1.491,
     4.2 * BIREF_BREWSTER, BIREF_PE_LAMBDA_REF_NM, 0.0},
    {"glass", "Aben & Guillemet, Photoelasticity of Glass (Springer 1993): soda-lime C = 2.7 Brewster", 1.52,
     2.7 * BIREF_BREWSTER, BIREF_PE_LAMBDA_REF_NM, 0.0},
};

size_t biref_pe_material_count(void) { return sizeof PRESETS / sizeof PRESETS[0]; }

const biref_pe_material *biref_pe_material_at(size_t i)
{
    return i < biref_pe_material_count() ? &PRESETS[i] : NULL;
}

biref_status biref_pe_material_preset(const char *name, biref_pe_material *out)
{
    if (!name || !out) return BIREF_ERR_INVALID;
    for (size_t i = 0; i < biref_pe_material_count(); i++)
        if (!strcmp(name, PRESETS[i].name)) {
            *out = PRESETS[i];
            return BIREF_OK;
        }
    return BIREF_ERR_INVALID;
}

biref_status biref_pe_material_check(const biref_pe_material *m, char *msg, size_t msg_len)
{
    const char *why = NULL;
    if (!m)
        why = "no material";
    else if (!isfinite(m->n0) || m->n0 < 1.0 || m->n0 > 5.0)
        why = "n0 must be between 1 and 5";
    else if (!isfinite(m->C_per_Pa) || m->C_per_Pa <= 0.0 || m->C_per_Pa > 1e-8)
        why = "C must be positive and at most 10000 Brewster";
    else if (!(m->lambda_ref_nm == 0.0 || (m->lambda_ref_nm >= 200.0 && m->lambda_ref_nm <= 2000.0)))
        why = "the reference wavelength of C must be 0 (546.1 nm) or 200 to 2000 nm";
    else if (!isfinite(m->dispersion_alpha) || m->dispersion_alpha < -1.0 || m->dispersion_alpha > 3.0)
        why = "the dispersion exponent alpha of C must be between -1 and 3";
    if (!why) return BIREF_OK;
    if (msg && msg_len) snprintf(msg, msg_len, "%s", why);
    return BIREF_ERR_INVALID;
}

double biref_pe_C_at(const biref_pe_material *m, double lambda_nm)
{
    if (m->dispersion_alpha == 0.0) return m->C_per_Pa;
    const double ref = m->lambda_ref_nm > 0.0 ? m->lambda_ref_nm : BIREF_PE_LAMBDA_REF_NM;
    return m->C_per_Pa * pow(ref / lambda_nm, m->dispersion_alpha);
}

double biref_pe_fringe_constant(const biref_pe_material *m, double lambda_nm)
{
    return lambda_nm * 1e-9 / biref_pe_C_at(m, lambda_nm);
}

void biref_pe_principal_of(const biref_pe_stress *s, biref_pe_principal *out)
{
    /* Mohr's circle: centre (sxx + syy) / 2, radius r = sqrt(((sxx - syy) / 2)^2 + txy^2);
     * direction of s1 from tan 2 phi = 2 txy / (sxx - syy) with cos 2 phi of the sign of
     * sxx - syy (so that s1 = centre + r). hypot avoids overflow for huge stresses. */
    double c = 0.5 * (s->sxx + s->syy), d = 0.5 * (s->sxx - s->syy);
    double r = hypot(d, s->txy);
    out->s1 = c + r;
    out->s2 = c - r;
    if (r > 0.0) {
        out->cos2phi = d / r;
        out->sin2phi = s->txy / r;
        out->phi = 0.5 * atan2(s->txy, d);
        if (out->phi <= -0.5 * M_PI) out->phi += M_PI; /* keep (-pi/2, pi/2] */
    } else {
        out->cos2phi = 1.0;
        out->sin2phi = 0.0;
        out->phi = 0.0;
    }
}

biref_slab biref_pe_slab_at(const biref_pe_material *m, double thickness_m, double eta_i,
                            const biref_pe_principal *p)
{
    /* Axis along principal direction 1 at angle phi from s (= x) towards p (= plate y); at normal
     * incidence p is the slab frame's z (docs/CONVENTIONS.md), so the axis is (cos, 0, sin). */
    biref_slab sl;
    sl.eta_o = m->n0;
    sl.eta_e = m->n0 + m->C_per_Pa * (p->s1 - p->s2);
    sl.axis[0] = cos(p->phi);
    sl.axis[1] = 0.0;
    sl.axis[2] = sin(p->phi);
    sl.thickness_nm = thickness_m * 1e9;
    sl.eta_i = eta_i;
    return sl;
}

biref_slab biref_pe_slab_best(const biref_pe_material *m, double thickness_m, double eta_i,
                              const biref_pe_principal *p)
{
    if (fabs(p->s1) >= fabs(p->s2)) return biref_pe_slab_at(m, thickness_m, eta_i, p);
    /* Axis along direction 2 (phi + 90 deg): eta_e = n2, eta_o = n1 = n3 in the model. Keeping
     * eta_o = n0 shifts both indices by -C (s1 - s2): a common phase only. */
    biref_slab sl;
    sl.eta_o = m->n0;
    sl.eta_e = m->n0 - m->C_per_Pa * (p->s1 - p->s2);
    sl.axis[0] = -sin(p->phi);
    sl.axis[1] = 0.0;
    sl.axis[2] = cos(p->phi);
    sl.thickness_nm = thickness_m * 1e9;
    sl.eta_i = eta_i;
    return sl;
}
