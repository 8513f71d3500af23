/* A pixel's footprint in optical path for the prefiltered phase integrals: how the optical path of
 * each leg type changes between neighbouring rays (docs/PHYSICS.md, "Spatial anti-aliasing"). The
 * slab is homogeneous, so a leg's optical path depends on the ray's direction only. */
#include <math.h>

#include "optics/modes_internal.h"
#include "render/render_internal.h"
#include "render/vec3.h"

/* Re(opl) of the four leg types (biref_opl_footprint order) for a ray along dir, in the
 * transmission frame of that ray (the same frame as render_shade_pixel's). Returns 0 if the ray is
 * edge-on to the slab. */
static int leg_opls(const render_slab *sl, const double dir[3], double opl[4])
{
    double dn = v3_dot(dir, sl->normal);
    if (fabs(dn) < 1e-12) return 0;
    double theta = acos(fmin(1.0, fabs(dn)));
    if (theta > RENDER_THETA_MAX) theta = RENDER_THETA_MAX;
    double y[3], z[3], x[3], A[3];
    v3_scale(sl->normal, dn < 0 ? -1.0 : 1.0, y);
    v3_axpy(dir, -dn, sl->normal, z);
    if (v3_normalize(z, z) < 1e-9) v3_set(z, sl->tangent[0], sl->tangent[1], sl->tangent[2]);
    v3_cross(y, z, x);
    v3_set(A, v3_dot(sl->axis_world, x), v3_dot(sl->axis_world, y), v3_dot(sl->axis_world, z));
    double complex q[4];
    biref_uniaxial_normal_components(sl->base.eta_o, sl->base.eta_e, A, sl->base.eta_i * sin(theta), q);
    const double d = sl->base.thickness_nm;
    opl[BIREF_LEG_DOWN_O] = -creal(q[BIREF_MODE_O_DOWN]) * d;
    opl[BIREF_LEG_DOWN_E] = -creal(q[BIREF_MODE_E_DOWN]) * d;
    opl[BIREF_LEG_UP_O] = creal(q[BIREF_MODE_O_UP]) * d;
    opl[BIREF_LEG_UP_E] = creal(q[BIREF_MODE_E_UP]) * d;
    return 1;
}

void render_footprint(const biref_renderer *r, const render_slab *sl, const double dir[3], const double dx[3],
                      const double dy[3], biref_opl_footprint *fp)
{
    fp->pf = r->prefilter;
    double o0[4], o1[4];
    const double *step[2] = {dx, dy};
    int ok0 = leg_opls(sl, dir, o0);
    for (int k = 0; k < 2; k++) {
        double d[3];
        v3_axpy(dir, 1.0, step[k], d);
        v3_normalize(d, d);
        /* A neighbour edge-on to the slab (or a non-finite path) leaves that axis unfiltered. */
        int ok = ok0 && leg_opls(sl, d, o1);
        for (int l = 0; l < 4; l++) {
            double g = ok ? o1[l] - o0[l] : 0.0;
            fp->grad[l][k] = isfinite(g) ? g : 0.0;
        }
    }
}
