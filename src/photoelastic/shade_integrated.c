/* Photoelastic shading through the spectral integrator: the polariscope as a biref_light and the
 * plate as a slab, white light by any method (integrator.h). */
#include <math.h>

#include "biref/photoelastic.h"
#include "photoelastic/shade_internal.h"

void biref_pe_light(const biref_pe_polariscope *pol, biref_light *out)
{
    biref_light_coherency((const biref_complex(*)[2])pol->C, out);
    biref_light_set_analyzer(out, (const biref_complex(*)[2])pol->P);
}

biref_status biref_pe_expansion_integrator(const biref_spectral *sp, biref_integrator **out)
{
    biref_integrator_options o;
    biref_integrator_options_default(&o);
    o.method = BIREF_METHOD_EXPANSION;
    return biref_integrator_create(sp, &o, out, NULL, 0);
}

biref_status biref_pe_shade_integrated(const biref_pe_setup *s, const biref_integrator *it,
                                       const biref_pe_principal *p, double theta_rad, double xyz[3])
{
    if (!s || !it || !p || !xyz || s->light != BIREF_PE_WHITE) return BIREF_ERR_INVALID;
    if (s->material.dispersion_alpha != 0.0) return BIREF_ERR_INVALID; /* one slab for the band: no dispersion */
    biref_status r = biref_theta_check(theta_rad, NULL, 0);
    if (r != BIREF_OK) return r;
    /* Normal incidence: the model of biref_pe_shade_general; oblique: the closest uniaxial slab,
     * as biref_pe_shade_oblique. */
    const biref_slab slab = theta_rad == 0.0 ? biref_pe_slab_at(&s->material, s->thickness, s->eta_i, p)
                                             : biref_pe_slab_best(&s->material, s->thickness, s->eta_i, p);
    biref_slab_state st;
    if ((r = biref_slab_prepare(&slab, theta_rad, &st)) != BIREF_OK) return r;
    return biref_pe_shade_state(s, it, &st, xyz);
}
