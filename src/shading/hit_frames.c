/* The paper's frames of a view ray at a slab hit (docs/SCENES.md "Frames"), from the one inline
 * body the renderer's tiles share (ray_frame.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "shading/ray_frame.h"
#include "shading/shader_internal.h"
#include "shading/vec3.h"

#define THETA_MAX BIREF_SHADING_THETA_MAX

void biref_shading_frames(const double normal[3], const double tangent[3], const double axis_world[3],
                          const biref_slab *base, const double dir[3], biref_hit_frames *f)
{
    /* Transmission: y = normal pointing away from the viewer (towards the light behind), z = the
     * view ray's tangential part, x = y x z. The reflection frame has y towards the viewer and the
     * same z, hence x_R = -x_T: the same slab lit from its other face. */
    biref_ray_frame rf;
    biref_ray_frame_of(normal, tangent, axis_world, dir, cos(THETA_MAX), &rf);
    f->theta = acos(rf.c);
    memcpy(f->x_T, rf.x, sizeof f->x_T);
    memcpy(f->y_T, rf.y, sizeof f->y_T);
    memcpy(f->z, rf.z, sizeof f->z);
    memcpy(f->mirror, rf.mirror, sizeof f->mirror);
    v3_scale(f->x_T, -1.0, f->x_R);
    v3_scale(f->y_T, -1.0, f->y_R);
    v3_scale(dir, -1.0, f->k_view); /* light reaching the eye travels against the view ray */
    f->slab = *base;
    memcpy(f->slab.axis, rf.axis, sizeof f->slab.axis);
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
