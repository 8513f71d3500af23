/* The paper's frames of a view ray at a slab hit (docs/SCENES.md "Frames"). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "shading/shader_internal.h"
#include "shading/vec3.h"

#define THETA_MAX BIREF_SHADING_THETA_MAX

void biref_shading_frames(const double normal[3], const double tangent[3], const double axis_world[3],
                          const biref_slab *base, const double dir[3], biref_hit_frames *f)
{
    double dn = v3_dot(dir, normal);
    f->theta = acos(fmin(1.0, fabs(dn)));
    if (f->theta > THETA_MAX) f->theta = THETA_MAX;
    /* Transmission: y = normal pointing away from the viewer (towards the light behind), z = the
     * view ray's tangential part, x = y x z. The reflection frame has y towards the viewer and the
     * same z, hence x_R = -x_T: the same slab lit from its other face. */
    v3_scale(normal, dn < 0 ? -1.0 : 1.0, f->y_T);
    v3_axpy(dir, -dn, normal, f->z);
    if (v3_normalize(f->z, f->z) < 1e-9) memcpy(f->z, tangent, sizeof f->z);
    v3_cross(f->y_T, f->z, f->x_T);
    v3_scale(f->x_T, -1.0, f->x_R);
    v3_scale(f->y_T, -1.0, f->y_R);
    v3_scale(dir, -1.0, f->k_view); /* light reaching the eye travels against the view ray */
    v3_axpy(dir, -2.0 * dn, normal, f->mirror);
    f->slab = *base;
    f->slab.axis[0] = v3_dot(axis_world, f->x_T);
    f->slab.axis[1] = v3_dot(axis_world, f->y_T);
    f->slab.axis[2] = v3_dot(axis_world, f->z);
}

static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

biref_status biref_hit_frames_make(const biref_surface *s, const double view_dir[3], biref_hit_frames *out)
{
    if (!s || !view_dir || !out) return BIREF_ERR_INVALID;
    if (!finite3(s->normal) || !finite3(s->tangent) || !finite3(s->axis) || !finite3(view_dir))
        return BIREF_ERR_INVALID;
    double n[3], t[3], b[3], v[3], a[3];
    if (!(v3_normalize(s->normal, n) > 0.0) || !(v3_normalize(view_dir, v) > 0.0)) return BIREF_ERR_INVALID;
    if (v3_orthonormalize(s->tangent, n, t)) return BIREF_ERR_INVALID;
    if (fabs(v3_dot(v, n)) < 1e-12) return BIREF_ERR_INVALID;
    v3_cross(t, n, b); /* local z = x cross y */
    for (int k = 0; k < 3; k++) a[k] = s->axis[0] * t[k] + s->axis[1] * n[k] + s->axis[2] * b[k];
    if (!(v3_normalize(a, a) > 0.0)) return BIREF_ERR_INVALID;
    biref_slab base = {s->eta_o, s->eta_e, {0, 0, 0}, s->thickness_nm, s->eta_i};
    biref_shading_frames(n, t, a, &base, v, out);
    return BIREF_OK;
}
