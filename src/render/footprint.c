/* A pixel's footprint in optical path for the prefiltered phase integrals: how the optical path of
 * each leg type changes between neighbouring rays (docs/PHYSICS.md, "Spatial anti-aliasing"). The
 * slab is homogeneous, so a leg's optical path depends on the ray's direction only. */
#include <math.h>

#include "optics/modes_internal.h"
#include "render/render_internal.h"
#include "render/vec3.h"

/* Re(opl) of the four leg types (biref_opl_footprint order) for a ray along dir, in the
 * transmission frame of that ray (biref_render_hit_frames, as the shading uses). Returns 0 if the
 * ray is edge-on to the slab. */
static int leg_opls(const render_slab *sl, const double dir[3], double opl[4])
{
    if (fabs(v3_dot(dir, sl->normal)) < 1e-12) return 0;
    biref_hit_frames f;
    biref_render_hit_frames(sl->normal, sl->tangent, sl->axis_world, &sl->base, dir, &f);
    double complex q[4];
    biref_uniaxial_normal_components(f.slab.eta_o, f.slab.eta_e, f.slab.axis, f.slab.eta_i * sin(f.theta), q);
    const double d = f.slab.thickness_nm;
    opl[BIREF_LEG_DOWN_O] = -creal(q[BIREF_MODE_O_DOWN]) * d;
    opl[BIREF_LEG_DOWN_E] = -creal(q[BIREF_MODE_E_DOWN]) * d;
    opl[BIREF_LEG_UP_O] = creal(q[BIREF_MODE_O_UP]) * d;
    opl[BIREF_LEG_UP_E] = creal(q[BIREF_MODE_E_UP]) * d;
    return 1;
}

void biref_render_footprint(const biref_renderer *r, const render_slab *sl, const double dir[3], const double dx[3],
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

void biref_render_sample_footprint(const biref_renderer *r, const render_slab *sl, double fx, double fy, double h,
                                   const double dir[3], biref_opl_footprint *fp)
{
    double d1[3], dx[3], dy[3];
    biref_render_camera_ray_at(&r->cam, fx + h, fy, d1);
    v3_sub(d1, dir, dx);
    biref_render_camera_ray_at(&r->cam, fx, fy + h, d1);
    v3_sub(d1, dir, dy);
    biref_render_footprint(r, sl, dir, dx, dy, fp);
}
