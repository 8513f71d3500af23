/*
 * biref — birefringence-induced iridescence of uniaxial slabs.
 *
 * The one public header. No global state: every function is re-entrant and
 * thread-safe; objects created by biref_*_create are immutable afterwards and
 * may be shared between threads.
 *
 * Frame and conventions: docs/CONVENTIONS.md. In short: slab top surface is
 * y = 0, slab occupies -d <= y <= 0, light arrives from y > 0 in the YZ plane,
 * phase e^{i(qy - Kz - wt)}, s = x, (s, p, k) right handed, wavelengths in nm,
 * angles in radians, thickness in nm.
 */
#ifndef BIREF_BIREF_H
#define BIREF_BIREF_H

#include "biref/common.h"
#include "biref/optics.h"
#include "biref/color.h"
#include "biref/polarization.h"
#include "biref/spectral.h"
#include "biref/stack.h"
#include "biref/integrator.h"
#include "biref/render.h"
#include "biref/photoelastic.h"
#include "biref/shading.h"
#include "biref/gpu.h"
#include "biref/material.h"
#include "biref/experimental.h" /* empty unless BIREF_EXPERIMENTAL_API is defined first */

#endif /* BIREF_BIREF_H */
