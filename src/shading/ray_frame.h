/* The paper's frames of a view ray at a slab hit (docs/SCENES.md "Frames") as one branch-free inline
 * body: biref_shading_frames (one hit) and the renderer's tiles (a loop across hits that the
 * compiler vectorises) both call it, so a hit has the same frame on either path. */
#ifndef BIREF_SHADING_RAY_FRAME_H
#define BIREF_SHADING_RAY_FRAME_H

#include <math.h>

/* The frame of the unit ray d at a slab with unit normal n, unit tangent g and unit world optic axis
 * A: dn = d.n; the transmission frame's axes (y = the normal pointing away from the viewer, z = the
 * ray's tangential direction, or the tangent at normal incidence, x = y cross z); the optic axis in
 * that frame; the mirror direction; and c = |dn| clamped to [c_min, 1] (c_min = cos of the largest
 * angle of incidence, biref_slab_prepare needs theta < pi/2). */
typedef struct {
    double dn, x[3], y[3], z[3], axis[3], mirror[3], c;
} biref_ray_frame;

static inline void biref_ray_frame_of(const double n[3], const double g[3], const double A[3], const double d[3],
                                      double c_min, biref_ray_frame *f)
{
    const double dn = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    const double sign = dn < 0 ? -1.0 : 1.0;
    const double y0 = n[0] * sign, y1 = n[1] * sign, y2 = n[2] * sign;
    double z0 = d[0] + -dn * n[0], z1 = d[1] + -dn * n[1], z2 = d[2] + -dn * n[2];
    const double l = sqrt(z0 * z0 + z1 * z1 + z2 * z2), inv = 1.0 / l;
    const int along = l < 1e-9; /* a ray along the normal: z is the tangent */
    z0 = along ? g[0] : z0 * inv;
    z1 = along ? g[1] : z1 * inv;
    z2 = along ? g[2] : z2 * inv;
    const double x0 = y1 * z2 - y2 * z1, x1 = y2 * z0 - y0 * z2, x2 = y0 * z1 - y1 * z0;
    f->dn = dn;
    f->x[0] = x0, f->x[1] = x1, f->x[2] = x2;
    f->y[0] = y0, f->y[1] = y1, f->y[2] = y2;
    f->z[0] = z0, f->z[1] = z1, f->z[2] = z2;
    f->axis[0] = A[0] * x0 + A[1] * x1 + A[2] * x2;
    f->axis[1] = A[0] * y0 + A[1] * y1 + A[2] * y2;
    f->axis[2] = A[0] * z0 + A[1] * z1 + A[2] * z2;
    f->mirror[0] = d[0] + -2.0 * dn * n[0];
    f->mirror[1] = d[1] + -2.0 * dn * n[1];
    f->mirror[2] = d[2] + -2.0 * dn * n[2];
    double c = fabs(dn);
    c = c < 1.0 ? c : 1.0;
    f->c = c > c_min ? c : c_min;
}

#endif
