/* A reference for the renderer's tiles, one sample at a time with branches where the tiles select
 * (the test's own restatement of the pixel path: camera ray, nearest slab, radiance, background
 * through the analyzer, the shader's frames and evaluation of a hit, colour). The tiles must give
 * its image to the bit when the shader takes every hit one by one (BIREF_SIMD=scalar), and to a
 * few float roundings with the packet kernel. */
#ifndef BIREF_TEST_RENDER_REFERENCE_H
#define BIREF_TEST_RENDER_REFERENCE_H

#include <math.h>
#include <string.h>

#include "render/render_internal.h"
#include "shading/vec3.h"

static void ref_camera_ray(const render_camera *c, double fx, double fy, double dir[3])
{
    double sx = (2.0 * fx / c->width - 1.0) * c->tan_half_h;
    double sy = (1.0 - 2.0 * fy / c->height) * c->tan_half_v;
    double d[3];
    for (int i = 0; i < 3; i++) d[i] = c->forward[i] + sx * c->right[i] + sy * c->up[i];
    v3_normalize(d, dir);
}

static void ref_mix3(const double a[3], const double b[3], double t, double o[3])
{
    for (int i = 0; i < 3; i++) o[i] = a[i] + (b[i] - a[i]) * t;
}

/* The comparisons below are fmin's results for every input, NaN included (fmin returns the
 * other argument, and `x < 1.0` is false for NaN), without fmin's call into libm. */
static void ref_env_radiance(const render_env *e, const double d[3], double xyz[3])
{
    double el = v3_dot(d, e->up);
    if (el >= 0.0) {
        /* sqrt keeps the sky pale near the horizon and saturated overhead. */
        ref_mix3(e->horizon, e->zenith, sqrt(el < 1.0 ? el : 1.0), xyz);
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
    ref_mix3(e->horizon, ground, g, xyz);
}

/* The distance along the ray from `from` in direction dir to the rectangle (centre, unit normal,
 * tangent and bitangent, half sizes) if it is hit nearer than best and beyond the surface the ray
 * leaves, else -1. Edge-on rectangles are not hit. */
static double ref_rect_hit(const double center[3], const double normal[3], const double tangent[3],
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

static void ref_radiance(const biref_renderer *r, const double from[3], const double dir[3], double xyz[3])
{
    double best = INFINITY;
    const render_panel *hit = NULL;
    for (int i = 0; i < r->n_panels; i++) {
        const render_panel *p = &r->panels[i];
        const double t = ref_rect_hit(p->center, p->normal, p->tangent, p->bitangent, p->half_w, p->half_h, from,
                                         dir, best);
        if (t > 0.0) {
            best = t;
            hit = p;
        }
    }
    if (hit)
        memcpy(xyz, hit->radiance_xyz, 3 * sizeof(double));
    else
        ref_env_radiance(&r->env, dir, xyz);
}

/* One sample's colour through the image point (fx, fy); 1 if it hit a slab, *fallback when the
 * slab's evaluation failed. With the prefilter the footprint spans the step h to the next
 * sample's ray right and below. */
static int ref_sample(const biref_renderer *r, double fx, double fy, double h, double xyz[3], int *fallback)
{
    *fallback = 0;
    double dir[3];
    ref_camera_ray(&r->cam, fx, fy, dir);
    double best = INFINITY;
    const render_slab *hit = NULL;
    for (int i = 0; i < r->n_slabs; i++) {
        const render_slab *sl = &r->slabs[i];
        const double t = ref_rect_hit(sl->center, sl->normal, sl->tangent, sl->bitangent, sl->half_w, sl->half_h,
                                      r->cam.origin, dir, best);
        if (t > 0.0) best = t, hit = sl;
    }
    double Lb[3], Lf[3];
    if (!hit) {
        double k_view[3];
        v3_scale(dir, -1.0, k_view);
        ref_radiance(r, r->cam.origin, dir, Lb);
        v3_scale(Lb, biref_shader_background(r->shader, k_view, r->slabs[0].normal, r->slabs[0].tangent), xyz);
        return 0;
    }
    double hp[3];
    v3_axpy(r->cam.origin, best, dir, hp);
    biref_hit_frames fr;
    biref_shading_frames(hit->normal, hit->tangent, hit->axis_world, &hit->base, dir, &fr);
    biref_opl_footprint fp = {0};
    if (r->prefilter) {
        double dx[3], dy[3];
        ref_camera_ray(&r->cam, fx + h, fy, dx);
        ref_camera_ray(&r->cam, fx, fy + h, dy);
        biref_render_footprint_rays(r, hit, dir, dx, dy, &fp);
    }
    double T[3], R[3];
    if (biref_shader_eval(r->shader, &fr, r->prefilter ? &fp : NULL, T, R) != BIREF_OK) {
        *fallback = 1;
        biref_shader_failed_hit(r->shader, &fr, T, R);
    }
    ref_radiance(r, hp, dir, Lb);
    ref_radiance(r, hp, fr.mirror, Lf);
    for (int i = 0; i < 3; i++) xyz[i] = T[i] * Lb[i] + R[i] * Lf[i];
    return 1;
}

#endif
