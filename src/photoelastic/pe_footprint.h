/* Spatial anti-aliasing of photoelastic pictures (docs/ANTIALIASING.md, "Photoelastic pictures"):
 * the fringes are averaged over the range of retardation one picture sample covers. */
#ifndef BIREF_PE_FOOTPRINT_H
#define BIREF_PE_FOOTPRINT_H

#include "biref/photoelastic.h"
#include "spectral/phase_prefilter.h"

/* biref_pe_shade with every phase term averaged over a box of width (2m + 1) width_nm around its
 * path difference (2m + 1) delta: white light through the pre-integrated table pf, monochromatic
 * light in closed form (each term of the Airy series times sinc(k (2m + 1) width / 2)). pf may be
 * NULL for monochromatic light; width_nm 0 (or pf NULL for white light) gives biref_pe_shade. */
void biref_pe_shade_footprint(const biref_pe_setup *s, const biref_spectral *sp, const biref_phase_prefilter *pf,
                              double width_nm, const biref_pe_principal *p, double xyz[3]);

/* The retardation footprint of the sample at (x, y) whose neighbours are (x + hx, y) and
 * (x, y - hy): the box width with the variance of the retardation's (linear) change over the
 * hx x hy sample, sqrt(gx^2 + gy^2) with gx, gy the change to the next sample along each axis
 * (towards the previous one where the next lies outside the material). delta_nm: the
 * retardation at (x, y). */
double biref_pe_retardation_footprint(const biref_pe_setup *s, const biref_pe_field *f, double x, double y, double hx,
                                      double hy, double delta_nm);

#endif
