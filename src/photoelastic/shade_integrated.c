/* Photoelastic shading through the spectral integrator: the polariscope as a biref_light and the
 * plate as a slab, white light by any method (integrator.h). */
#include <math.h>

#include "biref/photoelastic.h"

void biref_pe_light(const biref_pe_polariscope *pol, biref_light *out)
{
    biref_light_coherency((const biref_complex(*)[2])pol->C, out);
    biref_light_set_analyzer(out, (const biref_complex(*)[2])pol->P);
}

biref_status biref_pe_shade_integrated(const biref_pe_setup *s, const biref_integrator *it,
                                       const biref_pe_principal *p, double theta_rad, double xyz[3])
{
    if (!s || !it || !p || !xyz || s->light != BIREF_PE_WHITE) return BIREF_ERR_INVALID;
    biref_status r = biref_theta_check(theta_rad, NULL, 0);
    if (r != BIREF_OK) return r;
    /* Normal incidence: the model of biref_pe_shade_general / _numeric; oblique: the closest
     * uniaxial slab, as biref_pe_shade_oblique. */
    const biref_slab slab = theta_rad == 0.0 ? biref_pe_slab_at(&s->material, s->thickness, s->eta_i, p)
                                             : biref_pe_slab_best(&s->material, s->thickness, s->eta_i, p);
    biref_slab_state st;
    if ((r = biref_slab_prepare(&slab, theta_rad, &st)) != BIREF_OK) return r;
    biref_light light;
    biref_pe_light(&s->pol, &light);
    biref_integration res;
    if ((r = biref_integrate(it, &st, BIREF_SIDE_TRANSMISSION, &light, &res)) != BIREF_OK) return r;
    for (int j = 0; j < 3; j++) xyz[j] = res.T[j];
    return BIREF_OK;
}
