/* Tiny 3-vector helpers for the shader and the renderer (inline: they sit in the per-pixel loop). */
#ifndef BIREF_SHADING_VEC3_H
#define BIREF_SHADING_VEC3_H

#include <math.h>

static inline void v3_set(double o[3], double x, double y, double z)
{
    o[0] = x;
    o[1] = y;
    o[2] = z;
}
static inline double v3_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline double v3_len(const double a[3]) { return sqrt(v3_dot(a, a)); }
static inline void v3_sub(const double a[3], const double b[3], double o[3])
{
    o[0] = a[0] - b[0];
    o[1] = a[1] - b[1];
    o[2] = a[2] - b[2];
}
static inline void v3_scale(const double a[3], double s, double o[3])
{
    o[0] = a[0] * s;
    o[1] = a[1] * s;
    o[2] = a[2] * s;
}
/* o = a + s b */
static inline void v3_axpy(const double a[3], double s, const double b[3], double o[3])
{
    o[0] = a[0] + s * b[0];
    o[1] = a[1] + s * b[1];
    o[2] = a[2] + s * b[2];
}
/* o = a x b (o may alias neither input). */
static inline void v3_cross(const double a[3], const double b[3], double o[3])
{
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    o[0] = x;
    o[1] = y;
    o[2] = z;
}
/* Normalises a into o; returns the length (0 leaves o untouched). */
static inline double v3_normalize(const double a[3], double o[3])
{
    double l = v3_len(a);
    if (l > 0) v3_scale(a, 1.0 / l, o);
    return l;
}
/* o = normalised component of a orthogonal to unit n. Returns non-zero (and leaves o
 * untouched) when a is (nearly) parallel to n. */
static inline int v3_orthonormalize(const double a[3], const double n[3], double o[3])
{
    double t[3];
    v3_axpy(a, -v3_dot(a, n), n, t);
    double l = v3_len(t);
    if (!(l > 1e-6 * v3_len(a))) return 1;
    v3_scale(t, 1.0 / l, o);
    return 0;
}

/* A slab's optic axis, given in its local frame (x = tangent, y = normal, z = tangent x normal,
 * docs/SCENES.md), as a unit vector in the world. */
static inline void v3_slab_axis_world(const double axis[3], const double tangent[3], const double normal[3],
                                      double o[3])
{
    double b[3];
    v3_cross(tangent, normal, b);
    for (int k = 0; k < 3; k++) o[k] = axis[0] * tangent[k] + axis[1] * normal[k] + axis[2] * b[k];
    v3_normalize(o, o);
}

#endif
