/* Unchecked slab set-up for hot paths whose caller has already validated the slab. */
#ifndef BIREF_OPTICS_SLAB_INTERNAL_H
#define BIREF_OPTICS_SLAB_INTERNAL_H

#include "biref/optics.h"

/* biref_axis_normalize without the checks (axis finite and non-zero): the same unit vector. */
void biref_axis_unit_unchecked(const double axis[3], double unit[3]);

/* biref_slab_prepare for a slab that biref_slab_check accepted (the axis may differ, as long as
 * it is finite and non-zero) and theta in [0, pi/2): no checks, and the modes' Poynting
 * directions and effective indices are left 0 (no spectral method reads them). Every other
 * field equals biref_slab_prepare's, bit for bit. */
biref_status biref_slab_prepare_trusted(const biref_slab *slab, double theta, biref_slab_state *st);

#endif
