/* A pixel's footprint in optical path for the prefiltered phase integrals: how the optical path of
 * each leg type changes between neighbouring rays (docs/PHYSICS.md, "Spatial anti-aliasing"). The
 * slab is homogeneous, so a leg's optical path depends on the ray's direction only. */
#include <math.h>

#include "render/render_internal.h"
#include "render/vec3.h"

/* The slab's constants of leg_opls, once per footprint. */
typedef struct {
    double eo, ee, de, an, eta_i2, eta_i, aq, inv_aq, be_de, d;
} leg_consts;

static void leg_consts_of(const render_slab *sl, leg_consts *c)
{
    const biref_slab *b = &sl->base;
    c->eo = b->eta_o * b->eta_o;
    c->ee = b->eta_e * b->eta_e;
    c->de = c->ee - c->eo;
    c->an = v3_dot(sl->axis_world, sl->normal);
    c->eta_i = b->eta_i;
    c->eta_i2 = b->eta_i * b->eta_i;
    c->aq = c->eo + c->an * c->an * c->de; /* eps_o + be^2 de: be^2 = (a.n)^2 on either face */
    c->inv_aq = 1.0 / c->aq;
    c->be_de = c->an * c->de;
    c->d = b->thickness_nm;
}

/* Re(opl) of the four leg types (biref_opl_footprint order) for a unit ray along dir: the normal
 * components of biref_uniaxial_normal_components (modes.c) times the thickness, without the hit
 * frame. In the ray's transmission frame (biref_render_hit_frames: y the normal away from the
 * viewer, z the ray's tangential direction) the dispersion relation of the e wave needs only
 * K^2 = eta_i^2 sin^2(theta) = eta_i^2 (1 - dn^2), be = a.y = sign(dn) a.n, ga K = eta_i a.(dir -
 * dn n) and al^2 K^2 = K^2 (1 - be^2) - (ga K)^2 (a unit), which are dot products with the ray: no
 * acos, sin or frame per neighbouring ray. Evanescent legs (complex q) have Re(opl) = 0, as there.
 * Returns 0 if the ray is edge-on to the slab. */
static int leg_opls(const render_slab *sl, const leg_consts *k, const double dir[3], double opl[4])
{
    const double dn = v3_dot(dir, sl->normal);
    if (fabs(dn) < 1e-12) return 0;
    const double c = fabs(dn), s = dn < 0 ? -1.0 : 1.0;
    const double K2 = k->eta_i2 * ((1.0 - c) * (1.0 + c));
    const double gaK = k->eta_i * (v3_dot(sl->axis_world, dir) - dn * k->an);
    const double al2K2 = K2 * (1.0 - k->an * k->an) - gaK * gaK;
    const double so = k->eo - K2, disc = k->ee * k->aq + (al2K2 * k->de - k->ee * K2);
    const double qo = so > 0.0 ? sqrt(so) : 0.0, root = disc > 0.0 ? sqrt(k->eo * disc) : 0.0;
    const double mid = s * k->be_de * gaK; /* be ga K de */
    opl[BIREF_LEG_DOWN_O] = qo * k->d;
    opl[BIREF_LEG_DOWN_E] = (root - mid) * k->inv_aq * k->d;
    opl[BIREF_LEG_UP_O] = qo * k->d;
    opl[BIREF_LEG_UP_E] = (mid + root) * k->inv_aq * k->d;
    return 1;
}

void biref_render_footprint_rays(const biref_renderer *r, const render_slab *sl, const double dir[3],
                                 const double dir_x[3], const double dir_y[3], biref_opl_footprint *fp)
{
    fp->pf = r->prefilter;
    leg_consts k;
    leg_consts_of(sl, &k);
    double o0[4], o1[4];
    const double *nb[2] = {dir_x, dir_y};
    int ok0 = leg_opls(sl, &k, dir, o0);
    for (int a = 0; a < 2; a++) {
        /* A neighbour edge-on to the slab (or a non-finite path) leaves that axis unfiltered. */
        int ok = ok0 && leg_opls(sl, &k, nb[a], o1);
        for (int l = 0; l < 4; l++) {
            double g = ok ? o1[l] - o0[l] : 0.0;
            fp->grad[l][a] = isfinite(g) ? g : 0.0;
        }
    }
}

void biref_render_footprint(const biref_renderer *r, const render_slab *sl, const double dir[3], const double dx[3],
                            const double dy[3], biref_opl_footprint *fp)
{
    double d[2][3];
    v3_axpy(dir, 1.0, dx, d[0]);
    v3_normalize(d[0], d[0]);
    v3_axpy(dir, 1.0, dy, d[1]);
    v3_normalize(d[1], d[1]);
    biref_render_footprint_rays(r, sl, dir, d[0], d[1], fp);
}

void biref_render_sample_footprint(const biref_renderer *r, const render_slab *sl, double fx, double fy, double h,
                                   const double dir[3], biref_opl_footprint *fp)
{
    double d[2][3];
    biref_render_camera_ray_at(&r->cam, fx + h, fy, d[0]);
    biref_render_camera_ray_at(&r->cam, fx, fy + h, d[1]);
    biref_render_footprint_rays(r, sl, dir, d[0], d[1], fp);
}
