/* A stack of layers at a hit (docs/STACKS.md §5): the stack in each side's paper frame, its band
 * integrals by the shader's integrator under the light resolved in that frame. */
#include <math.h>
#include <string.h>

#include "biref/stack.h"
#include "shading/shader_internal.h"
#include "shading/vec3.h"

/* The stack as the light of one side meets it: in the frame (x, y, z) light arrives from y > 0,
 * so it enters the +normal face (the first layer listed) when y points along the normal, else the
 * last layer first; every axis from the local frame (tangent, normal, tangent x normal) into the
 * side's frame. */
static void stack_in_frame(const biref_stack *local, const double t[3], const double n[3], const double x[3],
                           const double y[3], const double z[3], biref_stack *out)
{
    double b[3];
    v3_cross(t, n, b);
    const int reversed = v3_dot(y, n) < 0.0;
    out->eta_i = local->eta_i;
    out->n_layers = local->n_layers;
    for (int i = 0; i < local->n_layers; i++) {
        const biref_layer *in = &local->layers[reversed ? local->n_layers - 1 - i : i];
        biref_layer *o = &out->layers[i];
        *o = *in;
        double a[3];
        for (int k = 0; k < 3; k++) a[k] = in->axis[0] * t[k] + in->axis[1] * n[k] + in->axis[2] * b[k];
        v3_set(o->axis, v3_dot(a, x), v3_dot(a, y), v3_dot(a, z));
    }
}

biref_status biref_shader_eval_stack(const biref_shader *sh, const biref_hit_frames *f, const double normal[3],
                                     const double tangent[3], const biref_stack *local, double T[3], double R[3])
{
    biref_stack sT, sR;
    stack_in_frame(local, tangent, normal, f->x_T, f->y_T, f->z, &sT);
    stack_in_frame(local, tangent, normal, f->x_R, f->y_R, f->z, &sR);
    biref_stack_state stT, stR;
    biref_status s = biref_stack_prepare(&sT, f->theta, &stT);
    if (!s) s = biref_stack_prepare(&sR, f->theta, &stR);
    if (s) return s;
    double k_refl_in[3];
    v3_scale(f->mirror, -1.0, k_refl_in);
    biref_light lT, lR;
    biref_shader_side_light(sh, f->x_T, f->k_view, f->k_view, &lT);
    biref_shader_side_light(sh, f->x_R, k_refl_in, f->k_view, &lR);
    return biref_integrate_stack_hit(sh->it, &stT, &stR, &lT, &lR, T, R);
}

biref_status biref_shade_stack_hit(const biref_shader *sh, const biref_stack_surface *s, const double view_dir[3],
                                   double T_xyz[3], double R_xyz[3], biref_hit_frames *frames)
{
    if (!sh || !s || !s->stack || !T_xyz || !R_xyz) return BIREF_ERR_INVALID;
    if (biref_stack_check(s->stack, NULL, 0)) return BIREF_ERR_INVALID;
    /* The frames of the ray, from a surface of the same orientation (its slab is layer 0's). */
    const biref_layer *l0 = &s->stack->layers[0];
    biref_surface surf = {{s->normal[0], s->normal[1], s->normal[2]},
                          {s->tangent[0], s->tangent[1], s->tangent[2]},
                          {0, 1, 0},
                          l0->eta_o,
                          l0->eta_e,
                          l0->thickness_nm,
                          s->stack->eta_i};
    biref_hit_frames local;
    biref_hit_frames *f = frames ? frames : &local;
    biref_status st = biref_hit_frames_make(&surf, view_dir, f);
    if (st) return st;
    double n[3] = {0, 1, 0}, t[3] = {1, 0, 0};
    v3_normalize(s->normal, n);
    v3_orthonormalize(s->tangent, n, t);
    st = biref_shader_eval_stack(sh, f, n, t, s->stack, T_xyz, R_xyz);
    if (st == BIREF_ERR_NOMEM) return st;
    return st == BIREF_OK ? BIREF_OK : BIREF_ERR_ILLCOND;
}
