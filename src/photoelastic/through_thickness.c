/* A plate whose plane stress varies through its thickness (docs/STACKS.md §3): equal layers, each
 * the uniaxial slab of its own stress (biref_pe_slab_at), as a stack. */
#include <math.h>
#include <string.h>

#include "biref/photoelastic.h"
#include "biref/stack.h"
#include "error.h"

biref_status biref_pe_stack(const biref_pe_material *m, double thickness_m, double eta_i, int n_layers,
                            const biref_pe_stress *stress, biref_stack *out, char *msg, size_t msg_len)
{
    const double ref = m && m->lambda_ref_nm > 0.0 ? m->lambda_ref_nm : BIREF_PE_LAMBDA_REF_NM;
    return biref_pe_stack_at(m, thickness_m, eta_i, n_layers, stress, ref, out, msg, msg_len);
}

biref_status biref_pe_stack_at(const biref_pe_material *dispersive, double thickness_m, double eta_i, int n_layers,
                               const biref_pe_stress *stress, double lambda_nm, biref_stack *out, char *msg,
                               size_t msg_len)
{
    biref_status s = biref_pe_material_check(dispersive, msg, msg_len);
    if (s != BIREF_OK) return s;
    if (!(lambda_nm > 0.0) || !isfinite(lambda_nm))
        return biref_fail(msg, msg_len, "wavelength must be a positive finite length (got %g nm)", lambda_nm);
    /* Every layer's slab with C at this wavelength (exactly C when alpha is 0). */
    biref_pe_material at = *dispersive;
    at.C_per_Pa = biref_pe_C_at(dispersive, lambda_nm);
    at.dispersion_alpha = 0.0;
    const biref_pe_material *m = &at;
    if (s != BIREF_OK) return s;
    if (n_layers < 1 || n_layers > BIREF_STACK_MAX_LAYERS)
        return biref_fail(msg, msg_len, "a plate through its thickness has 1 to %d layers (got %d)",
                          BIREF_STACK_MAX_LAYERS, n_layers);
    if (!(thickness_m > 0.0) || !isfinite(thickness_m))
        return biref_fail(msg, msg_len, "thickness must be a positive finite length (got %g m)", thickness_m);
    memset(out, 0, sizeof *out);
    out->eta_i = eta_i;
    out->n_layers = n_layers;
    for (int k = 0; k < n_layers; k++) {
        const biref_pe_stress *t = &stress[k];
        if (!isfinite(t->sxx) || !isfinite(t->syy) || !isfinite(t->txy))
            return biref_fail(msg, msg_len, "stress of layer %d is not finite", k);
        biref_pe_principal p;
        biref_pe_principal_of(t, &p);
        biref_slab sl = biref_pe_slab_at(m, thickness_m / n_layers, eta_i, &p);
        biref_layer *l = &out->layers[k];
        l->eta_o = sl.eta_o;
        l->eta_e = sl.eta_e;
        memcpy(l->axis, sl.axis, sizeof l->axis);
        l->thickness_nm = sl.thickness_nm;
    }
    return biref_stack_check(out, msg, msg_len);
}
