/* Per-pixel shading: environment and panels, the nearest slab and its shader's evaluation in the
 * paper's frames of each ray. Frames and semantics: docs/SCENES.md. */
#include <math.h>
#include <string.h>

#include "render/radiance.h"
#include "render/render_internal.h"
#include "shading/vec3.h"

void biref_render_env_init(render_env *e, const biref_environment *env)
{
    e->type = env->type;
    memcpy(e->up, env->up, sizeof e->up);
    double a[3] = {1, 0, 0};
    if (fabs(e->up[0]) > 0.9) v3_set(a, 0, 0, 1);
    v3_orthonormalize(a, e->up, e->e1);
    v3_cross(e->up, e->e1, e->e2);
    biref_linear_srgb_to_xyz(env->zenith, e->zenith);
    biref_linear_srgb_to_xyz(env->horizon, e->horizon);
    biref_linear_srgb_to_xyz(env->ground, e->ground);
    biref_linear_srgb_to_xyz(env->check_a, e->check_a);
    biref_linear_srgb_to_xyz(env->check_b, e->check_b);
    e->check_size = env->check_size;
}

void biref_render_radiance(const biref_renderer *r, const double from[3], const double dir[3], double xyz[3])
{
    render_radiance(r, from, dir, xyz);
}

const render_slab *biref_render_nearest_slab(const biref_renderer *r, const double dir[3], double *t_hit)
{
    double best = INFINITY;
    const render_slab *hit = NULL;
    for (int i = 0; i < r->n_slabs; i++) {
        const render_slab *sl = &r->slabs[i];
        const double t = render_rect_hit(sl->center, sl->normal, sl->tangent, sl->bitangent, sl->half_w, sl->half_h,
                                         r->cam.origin, dir, best);
        if (t > 0.0) {
            best = t;
            hit = sl;
        }
    }
    *t_hit = best;
    return hit;
}

void biref_render_background(const biref_renderer *r, const double dir[3], double xyz[3])
{
    double k_view[3], L[3]; /* light reaching the eye travels against the view ray */
    v3_scale(dir, -1.0, k_view);
    biref_render_radiance(r, r->cam.origin, dir, L);
    /* World-fixed polarizers are resolved in the basis of the first slab's plane of incidence. */
    double f = biref_shader_background(r->shader, k_view, r->slabs[0].normal, r->slabs[0].tangent);
    v3_scale(L, f, xyz);
}

void biref_render_hit_colour(const biref_renderer *r, const double hp[3], const double dir[3],
                             const biref_hit_frames *fr, const double tT[3], const double tR[3], double xyz[3])
{
    double Lb[3], Lf[3];
    biref_render_radiance(r, hp, dir, Lb);
    biref_render_radiance(r, hp, fr->mirror, Lf);
    /* Band-wise products: exact for grey light, an approximation for coloured light. */
    for (int i = 0; i < 3; i++) xyz[i] = tT[i] * Lb[i] + tR[i] * Lf[i];
}

biref_status biref_render_eval(const biref_renderer *r, const render_slab *sl, const biref_hit_frames *fr,
                               const biref_opl_footprint *fp, double T[3], double R[3])
{
    if (sl->is_stack) return biref_shader_eval_stack(r->shader, fr, sl->normal, sl->tangent, &sl->stack, T, R);
    return biref_shader_eval(r->shader, fr, fp, T, R);
}

int biref_render_shade_pixel(const biref_renderer *r, const double dir[3], const double dx[3], const double dy[3],
                             double xyz[3], int *fallback)
{
    *fallback = 0;
    double best;
    const render_slab *hit = biref_render_nearest_slab(r, dir, &best);
    if (!hit) {
        biref_render_background(r, dir, xyz);
        return 0;
    }
    double hp[3];
    v3_axpy(r->cam.origin, best, dir, hp);
    biref_hit_frames fr;
    biref_shading_frames(hit->normal, hit->tangent, hit->axis_world, &hit->base, dir, &fr);
    double tT[3], tR[3];
    biref_opl_footprint fp;
    if (r->prefilter && dx && dy) biref_render_footprint(r, hit, dir, dx, dy, &fp);
    if (biref_render_eval(r, hit, &fr, r->prefilter && dx && dy ? &fp : NULL, tT, tR) != BIREF_OK) {
        *fallback = 1;
        biref_shader_failed_hit(r->shader, &fr, tT, tR);
    }
    biref_render_hit_colour(r, hp, dir, &fr, tT, tR, xyz);
    return 1;
}
