/* The general-path shading of one prepared point of a plate, shared by the public photoelastic
 * entry points and the pictures: white light through a spectral integrator, monochromatic light
 * by the path expansion. */
#ifndef BIREF_PHOTOELASTIC_SHADE_INTERNAL_H
#define BIREF_PHOTOELASTIC_SHADE_INTERNAL_H

#include "biref/integrator.h"
#include "biref/photoelastic.h"

/* Detected XYZ of the prepared plate st seen through s: white light by biref_integrate (it is
 * required), monochromatic light at s->lambda_nm by the transmission paths to order 2, coherent
 * within an order and orders added in intensity (it unused). */
biref_status biref_pe_shade_state(const biref_pe_setup *s, const biref_integrator *it, const biref_slab_state *st,
                                  double xyz[3]);

/* The setup of a monochromatic picture with C taken at its wavelength (no dispersion left to
 * apply): the general paths build one slab for all of it. Other setups are returned as they are. */
static inline biref_pe_setup biref_pe_setup_at_lambda(const biref_pe_setup *s)
{
    biref_pe_setup c = *s;
    if (s->light == BIREF_PE_MONO && s->material.dispersion_alpha != 0.0) {
        c.material.C_per_Pa = biref_pe_C_at(&s->material, s->lambda_nm);
        c.material.dispersion_alpha = 0.0;
    }
    return c;
}

/* The expansion integrator the general path uses for white light (default options). */
biref_status biref_pe_expansion_integrator(const biref_spectral *sp, biref_integrator **out);

#endif
