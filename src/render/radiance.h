/* Radiance arriving along a ray: the nearest panel in front of its origin, else the environment.
 * Inline because it runs two or three times per pixel, in the scalar path (shade.c) and in the
 * tile's lanes (render_tile.c), which must give the same bits. */
#ifndef BIREF_RENDER_RADIANCE_H
#define BIREF_RENDER_RADIANCE_H

#include <math.h>
#include <string.h>

#include "render/render_internal.h"
#include "shading/vec3.h"

static inline void render_mix3(const double a[3], const double b[3], double t, double o[3])
{
    for (int i = 0; i < 3; i++) o[i] = a[i] + (b[i] - a[i]) * t;
}

/* The comparisons below are fmin's results for every input, NaN included (fmin returns the
 * other argument, and `x < 1.0` is false for NaN), without fmin's call into libm. */
static inline void render_env_radiance(const render_env *e, const double d[3], double xyz[3])
{
    double el = v3_dot(d, e->up);
    if (el >= 0.0) {
        /* sqrt keeps the sky pale near the horizon and saturated overhead. */
        render_mix3(e->horizon, e->zenith, sqrt(el < 1.0 ? el : 1.0), xyz);
        return;
    }
    /* Below the horizon the ground fades in over the first ~7 degrees; the haze also hides
     * the checker's aliasing where its tiles shrink below a pixel. */
    const double g8 = -el * 8.0, g = g8 < 1.0 ? g8 : 1.0;
    const double *ground = e->ground;
    if (e->type == BIREF_ENV_CHECKER && g > 1e-3) {
        /* The ground is a plane one unit below the eye; tiles are check_size units wide. */
        double s = 1.0 / (-el * e->check_size);
        double u = floor(v3_dot(d, e->e1) * s), w = floor(v3_dot(d, e->e2) * s);
        ground = fabs(fmod(u + w, 2.0)) >= 1.0 ? e->check_b : e->check_a;
    }
    render_mix3(e->horizon, ground, g, xyz);
}

/* The distance along the ray from `from` in direction dir to the rectangle (centre, unit normal,
 * tangent and bitangent, half sizes) if it is hit nearer than best and beyond the surface the ray
 * leaves, else -1. Edge-on rectangles are not hit. */
static inline double render_rect_hit(const double center[3], const double normal[3], const double tangent[3],
                                     const double bitangent[3], double half_w, double half_h, const double from[3],
                                     const double dir[3], double best)
{
    double dn = v3_dot(dir, normal);
    if (fabs(dn) < 1e-12) return -1.0;
    double rel[3];
    v3_sub(center, from, rel);
    double t = v3_dot(rel, normal) / dn;
    if (!(t > BIREF_RENDER_RAY_EPS) || t >= best) return -1.0;
    double q[3];
    v3_axpy(from, t, dir, q);
    v3_sub(q, center, q);
    return fabs(v3_dot(q, tangent)) <= half_w && fabs(v3_dot(q, bitangent)) <= half_h ? t : -1.0;
}

static inline void render_radiance(const biref_renderer *r, const double from[3], const double dir[3], double xyz[3])
{
    double best = INFINITY;
    const render_panel *hit = NULL;
    for (int i = 0; i < r->n_panels; i++) {
        const render_panel *p = &r->panels[i];
        const double t = render_rect_hit(p->center, p->normal, p->tangent, p->bitangent, p->half_w, p->half_h, from,
                                         dir, best);
        if (t > 0.0) {
            best = t;
            hit = p;
        }
    }
    if (hit)
        memcpy(xyz, hit->radiance_xyz, 3 * sizeof(double));
    else
        render_env_radiance(&r->env, dir, xyz);
}

#endif
