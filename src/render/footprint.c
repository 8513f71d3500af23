/* A pixel's footprint in optical path for the prefiltered phase integrals: how the optical path of
 * each leg type changes between neighbouring rays (docs/PHYSICS.md, "Spatial anti-aliasing"). The
 * slab is homogeneous, so a leg's optical path depends on the ray's direction only. */
#include <math.h>

#include "render/footprint_legs.h"
#include "render/render_internal.h"
#include "shading/vec3.h"

/* The leg paths of a unit ray (footprint_legs.h); 0 if the ray is edge-on to the slab. */
static int leg_opls(const biref_leg_consts *k, const double dir[3], double opl[4])
{
    const double dn = dir[0] * k->n[0] + dir[1] * k->n[1] + dir[2] * k->n[2];
    const double ad = dir[0] * k->a[0] + dir[1] * k->a[1] + dir[2] * k->a[2];
    biref_leg_opls(k, dn, ad, opl);
    return !(fabs(dn) < 1e-12);
}

void biref_render_footprint_rays(const biref_renderer *r, const render_slab *sl, const double dir[3],
                                 const double dir_x[3], const double dir_y[3], biref_opl_footprint *fp)
{
    fp->pf = r->prefilter;
    fp->disp = NULL;
    biref_leg_consts k;
    biref_leg_consts_of(sl, &k);
    double o0[4], o1[4];
    const double *nb[2] = {dir_x, dir_y};
    const int ok0 = leg_opls(&k, dir, o0);
    for (int a = 0; a < 2; a++) {
        const int ok = leg_opls(&k, nb[a], o1) && ok0;
        for (int l = 0; l < 4; l++) fp->grad[l][a] = biref_leg_grad(ok, o1[l], o0[l]);
    }
}
