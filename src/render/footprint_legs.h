/* The leg paths of the prefilter's footprint from two dot products of a unit ray (docs/PHYSICS.md,
 * "Spatial anti-aliasing"), shared by the per-sample footprint (footprint.c) and the tiles'
 * branch-free loop (footprint_lanes.inc), which thus give the same bits for the same rays.
 *
 * Re(opl) of the four leg types (biref_opl_footprint order) are the normal components of
 * biref_uniaxial_normal_components (modes.c) times the thickness. In the ray's transmission frame
 * (ray_frame.h: y the normal away from the viewer, z the ray's tangential direction)
 * the e wave's dispersion relation needs only K^2 = eta_i^2 sin^2(theta) = eta_i^2 (1 - dn^2),
 * be = a.y = sign(dn) a.n, ga K = eta_i a.(dir - dn n) and al^2 K^2 = K^2 (1 - be^2) - (ga K)^2
 * (a unit): dot products with the ray (dn = dir.n, ad = dir.a), no acos, sin or frame per
 * neighbouring ray. Evanescent legs (complex q) have Re(opl) = 0, as there. */
#ifndef BIREF_RENDER_FOOTPRINT_LEGS_H
#define BIREF_RENDER_FOOTPRINT_LEGS_H

#include <math.h>

#include "render/render_internal.h"

/* The slab's constants, once per footprint (or per run of hits on one slab). */
typedef struct {
    double eo, ee, de, an, eta_i, eta_i2, aq, inv_aq, be_de, d, n[3], a[3];
} biref_leg_consts;

static inline void biref_leg_consts_of(const render_slab *sl, biref_leg_consts *c)
{
    const biref_slab *b = &sl->base;
    c->eo = b->eta_o * b->eta_o;
    c->ee = b->eta_e * b->eta_e;
    c->de = c->ee - c->eo;
    for (int i = 0; i < 3; i++) c->n[i] = sl->normal[i], c->a[i] = sl->axis_world[i];
    c->an = c->a[0] * c->n[0] + c->a[1] * c->n[1] + c->a[2] * c->n[2];
    c->eta_i = b->eta_i;
    c->eta_i2 = b->eta_i * b->eta_i;
    c->aq = c->eo + c->an * c->an * c->de; /* eps_o + be^2 de: be^2 = (a.n)^2 on either face */
    c->inv_aq = 1.0 / c->aq;
    c->be_de = c->an * c->de;
    c->d = b->thickness_nm;
}

/* The four leg paths of a unit ray with dn = dir.n and ad = dir.a, branch-free (the caller
 * drops rays edge-on to the slab, |dn| < 1e-12). The e legs: q = (be ga K de -+ sqrt(eps_o
 * disc)) / (eps_o + be^2 de), disc = eps_e (eps_o + be^2 de) + K^2 (al^2 de - eps_e) (paper
 * eq. 2 as corrected in modes.c). */
static inline void biref_leg_opls(const biref_leg_consts *k, double dn, double ad, double opl[4])
{
    const double c = fabs(dn), s = dn < 0 ? -1.0 : 1.0;
    const double K2 = k->eta_i2 * ((1.0 - c) * (1.0 + c));
    const double gaK = k->eta_i * (ad - dn * k->an);
    const double al2K2 = K2 * (1.0 - k->an * k->an) - gaK * gaK;
    const double so = k->eo - K2, disc = k->ee * k->aq + (al2K2 * k->de - k->ee * K2);
    const double qo = sqrt(so > 0.0 ? so : 0.0), root = sqrt(disc > 0.0 ? k->eo * disc : 0.0);
    const double mid = s * k->be_de * gaK; /* be ga K de */
    opl[BIREF_LEG_DOWN_O] = qo * k->d;
    opl[BIREF_LEG_DOWN_E] = (root - mid) * k->inv_aq * k->d;
    opl[BIREF_LEG_UP_O] = qo * k->d;
    opl[BIREF_LEG_UP_E] = (mid + root) * k->inv_aq * k->d;
}

/* A neighbour's change of one leg path: 0 where either ray is edge-on or the difference is not
 * finite (that axis is then not filtered). */
static inline double biref_leg_grad(int ok, double o1, double o0)
{
    const double g = ok ? o1 - o0 : 0.0;
    return fabs(g) <= 1.7976931348623157e308 ? g : 0.0;
}

#endif
