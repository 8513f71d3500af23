/* Unchecked mode constructors used on hot paths after the public entry point validated input. */
#ifndef BIREF_OPTICS_MODES_INTERNAL_H
#define BIREF_OPTICS_MODES_INTERNAL_H

#include "biref/optics.h"

void biref_isotropic_modes(double eta, double K, biref_modes *m);
/* axis must be a unit vector (biref_axis_normalize). */
void biref_uniaxial_modes(double eta_o, double eta_e, const double axis[3], double K, biref_modes *m);
/* The normal components q[4] (BIREF_MODE_* order) of biref_uniaxial_modes alone, without the
 * fields: for callers that need only the legs' optical paths (the anti-aliasing footprint). */
void biref_uniaxial_normal_components(double eta_o, double eta_e, const double axis[3], double K, double complex q[4]);
/* The same without the Poynting directions and effective indices (left 0): q, E and H only,
 * all that the interface solves and the spectral methods use. */
void biref_uniaxial_mode_fields(double eta_o, double eta_e, const double axis[3], double K, biref_modes *m);
/* Interface coefficients from two precomputed mode sets (upper medium above y = 0). */
biref_status biref_interface_from_modes(const biref_modes *upper, const biref_modes *lower, biref_interface *out);
/* The same; allow_real = 0 forces the complex elimination even for a real system (tests). */
biref_status biref_interface_from_modes_as(const biref_modes *upper, const biref_modes *lower, int allow_real,
                                           biref_interface *out);

#endif
