/* Per-pixel shading: environment and panels, the slab's two spectral evaluations in the paper's
 * frame of each ray, and the polarisation bookkeeping. Frames and semantics: docs/SCENES.md. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "optics/slab_internal.h"
#include "render/radiance.h"
#include "render/render_internal.h"
#include "render/vec3.h"

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

/* Coherency matrix of the incident light in the basis (s, p_in) of a wave travelling along
 * k_in. The paper's model (unpolarized, s/p fractions) is diagonal in every ray's own basis;
 * a world-fixed polarizer projects its axis onto the wave's transverse plane, so light along
 * the axis itself is blocked (the amplitude is the projection: Malus at oblique incidence). */
static void light_coherency(const biref_renderer *r, const double s[3], const double p_in[3], double C[2][2])
{
    if (r->pol.type == BIREF_POL_LINEAR) {
        double e[2] = {v3_dot(r->pol.direction, s), v3_dot(r->pol.direction, p_in)};
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) C[i][j] = e[i] * e[j];
    } else {
        C[0][0] = r->w_in[0];
        C[1][1] = r->w_in[1];
        C[0][1] = C[1][0] = 0.0;
    }
}

/* Analyzer Jones matrix [in][out] in the outgoing wave's basis (s, p_out). A world-fixed
 * analyzer with axis a passes the amplitude E . a_t (a_t: the axis' transverse part, |a_t| <= 1
 * acting as a transmission factor) polarized along a_t / |a_t|: P = a_t (a_t / |a_t|)^T. */
static void analyzer(const biref_renderer *r, const double s[3], const double p_out[3], double P[2][2])
{
    if (r->filter.type == BIREF_FILTER_LINEAR) {
        double a[2] = {v3_dot(r->filter.direction, s), v3_dot(r->filter.direction, p_out)};
        double l = sqrt(a[0] * a[0] + a[1] * a[1]);
        double u[2] = {l > 0 ? a[0] / l : 0.0, l > 0 ? a[1] / l : 0.0};
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) P[i][j] = a[i] * u[j];
    } else {
        P[0][0] = r->mask[0];
        P[1][1] = r->mask[1];
        P[0][1] = P[1][0] = 0.0;
    }
}

/* Intensity of the light passed unchanged (no slab) through the analyzer:
 * sum_{i,j,k} C[i][j] P[i][k] P[j][k]. */
static double passthrough(const double C[2][2], const double P[2][2])
{
    double f = 0.0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 2; k++) f += C[i][j] * P[i][k] * P[j][k];
    return f;
}

/* One spectral evaluation of a prepared slab state in a ray's paper frame (x: the frame's x
 * axis in world coordinates, the s direction of every wave), for light arriving along k_in and
 * leaving along k_out. which selects transmission or reflection. Returns 0 on success;
 * non-zero leaves xyz undefined. */
static int eval_slab(const biref_renderer *r, const biref_slab_state *st, const biref_opl_footprint *fp,
                     const double x[3], const double k_in[3], const double k_out[3], int which, double xyz[3])
{
    const biref_light *l = &r->light;
    biref_light ray_light;
    if (r->world_fixed) {
        /* A world-fixed polarizer or analyzer has its own matrices in every ray's basis: s = x
         * for both waves (s is the frame's x), p = k x s. */
        double p_in[3], p_out[3], Cr[2][2], Pr[2][2];
        v3_cross(k_in, x, p_in);
        v3_cross(k_out, x, p_out);
        light_coherency(r, x, p_in, Cr);
        analyzer(r, x, p_out, Pr);
        double complex C[2][2], P[2][2];
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) {
                C[i][j] = Cr[i][j];
                P[i][j] = Pr[i][j];
            }
        biref_light_coherency((const double complex(*)[2])C, &ray_light);
        biref_light_set_analyzer(&ray_light,
                                 r->filter.type == BIREF_FILTER_NONE ? NULL : (const double complex(*)[2])P);
        l = &ray_light;
    }
    const biref_sides side = which == BIREF_REFLECTION ? BIREF_SIDE_REFLECTION : BIREF_SIDE_TRANSMISSION;
    biref_integration res;
    if (biref_integrate_footprint(r->integrator, st, fp, side, l, &res) != BIREF_OK) return 1;
    memcpy(xyz, which == BIREF_REFLECTION ? res.R : res.T, 3 * sizeof(double));
    return 0;
}

/* The pass-through factor for a wave along k (no slab), in the basis whose s is
 * perpendicular to the plane containing k and n (the slab normal), as in the paper's light
 * model; k parallel to n falls back to the slab's tangent. */
static double background_factor(const biref_renderer *r, const double k[3], const render_slab *sl)
{
    double s[3], p[3];
    v3_cross(k, sl->normal, s);
    if (v3_normalize(s, s) < 1e-9 && v3_orthonormalize(sl->tangent, k, s)) {
        /* k is parallel to both the normal and the tangent: impossible for an orthonormal pair. */
        v3_set(s, 1, 0, 0);
    }
    v3_cross(k, s, p);
    double C[2][2], P[2][2];
    light_coherency(r, s, p, C);
    analyzer(r, s, p, P);
    return passthrough(C, P);
}

double biref_render_passthrough_sp(const biref_renderer *r)
{
    /* Without a world-fixed polarizer C and P are diagonal in every wave's own basis, so any
     * basis gives background_factor's value, to the bit. */
    static const double s[3] = {1, 0, 0}, p[3] = {0, 1, 0};
    double C[2][2], P[2][2];
    light_coherency(r, s, p, C);
    analyzer(r, s, p, P);
    return passthrough(C, P);
}

/* The slab's two evaluations, the phase integrals averaged over the footprint fpT (in the
 * transmission frame; NULL: point look-ups). */
static int shade_hit(const biref_renderer *r, const biref_hit_frames *f, const biref_opl_footprint *fpT,
                     double T_xyz[3], double R_xyz[3])
{
    /* One optics set-up per hit: the reflection frame is the transmission frame rotated by 180
     * degrees about z, i.e. the same slab lit from the other face (biref_slab_state_flip). */
    double k_refl_in[3];
    v3_scale(f->mirror, -1.0, k_refl_in);
    biref_slab_state stT, stR;
    /* The slab's constants were checked when the renderer (or biref_shade_hit) accepted them;
     * the axis is a unit world axis seen in an orthonormal frame and theta is clamped below
     * pi/2 (render_hit_frames), so the per-pixel set-up needs no checks. */
    if (biref_slab_prepare_trusted(&f->slab, f->theta, &stT) != BIREF_OK) return 1;
    biref_slab_state_flip(&stT, &stR);
    biref_opl_footprint fpR;
    if (fpT) biref_opl_footprint_flip(fpT, &fpR); /* the flip swaps the down and up legs */
    return eval_slab(r, &stT, fpT, f->x_T, f->k_view, f->k_view, BIREF_TRANSMISSION, T_xyz) ||
           eval_slab(r, &stR, fpT ? &fpR : NULL, f->x_R, k_refl_in, f->k_view, BIREF_REFLECTION, R_xyz);
}

int biref_render_shade_hit(const biref_renderer *r, const biref_hit_frames *f, double T_xyz[3], double R_xyz[3])
{
    return shade_hit(r, f, NULL, T_xyz, R_xyz);
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
    double f = background_factor(r, k_view, &r->slabs[0]);
    v3_scale(L, f, xyz);
}

void biref_render_failed_hit(const biref_renderer *r, const biref_hit_frames *fr, double tT[3], double tR[3])
{
    /* A failed evaluation (grazing-angle breakdown) must not put a NaN in the image: treat the
     * slab as a perfect mirror seen through the filter. */
    const double *xR = fr->x_R;
    double k_refl_in[3], p_in[3], p_out[3], C[2][2], P[2][2];
    v3_scale(fr->mirror, -1.0, k_refl_in);
    v3_cross(k_refl_in, xR, p_in);
    v3_cross(fr->k_view, xR, p_out);
    light_coherency(r, xR, p_in, C);
    analyzer(r, xR, p_out, P);
    double f = passthrough(C, P);
    v3_set(tT, 0, 0, 0);
    v3_set(tR, f, f, f);
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
    biref_render_hit_frames(hit->normal, hit->tangent, hit->axis_world, &hit->base, dir, &fr);
    double tT[3], tR[3];
    biref_opl_footprint fp;
    if (r->prefilter && dx && dy) biref_render_footprint(r, hit, dir, dx, dy, &fp);
    if (shade_hit(r, &fr, r->prefilter && dx && dy ? &fp : NULL, tT, tR)) {
        *fallback = 1;
        biref_render_failed_hit(r, &fr, tT, tR);
    }
    biref_render_hit_colour(r, hp, dir, &fr, tT, tR, xyz);
    return 1;
}
