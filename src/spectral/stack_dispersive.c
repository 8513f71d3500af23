/* The path expansion of a stack with layers of a dispersive material (docs/STACKS.md, "Layers of a
 * dispersive material"): the slab's sub-band machinery (analytic_dispersive.c, docs/PHYSICS.md
 * §7) on the stack's paths. Per colour-matching band j the stack is prepared at each of the
 * band's two Gauss nodes for the amplitudes (the interfaces' coefficients; the two runs added by
 * the nodes' masses, each taking its pairs' integrals under its node's weight); the paths are
 * followed with the group paths of their legs there (which order them and decide which pairs are
 * coherent) and their counts of crossings per leg class (stack_legs.c), so that a pair of groups
 * has its exact phase difference Σ_c Δn_c k Re opl_c(k), integrated by tangents on nested
 * sub-bands within 0.005 rad. Where even the finest sub-bands leave a coherent pair's tangent
 * further from its phase (the estimate, residual × amplitudes, above the tolerance), or the
 * expansion does not apply (evanescent layers, too many groups, the bound not met), the adaptive
 * numeric integration with the stack prepared anew at every sample wavelength, reported in info. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "biref/stack.h"
#include "spectral/spectral_internal.h"
#include "spectral/stack_internal.h"

/* One run of band j: the stack prepared at λ for the amplitudes (the band's centroid, node < 0,
 * or node `node` of the band), the paths followed with their legs' group paths there (which order
 * the groups and decide which pairs are coherent), the pair sums; band j of x and m, and the
 * tangents' error estimate into *err. *reason: the expansion does not apply. */
static biref_status band_run(const biref_spectral *sp, const biref_stack_state *st, const biref_stack_spectrum_opts *o,
                             const biref_light *light, biref_stack_legs *legs, int j, int node, double lambda,
                             biref_spectrum *x, double m[2][3], double *err, biref_stack_spectrum_info *info,
                             const char **reason)
{
    biref_stack_state b;
    double grp[BIREF_STACK_MAX_LAYERS][4];
    biref_status s = biref_stack_prepare_at(&st->stack, st->theta, lambda, &b);
    if (s == BIREF_OK) s = biref_stack_legs_group_paths(&b, lambda, grp);
    biref_stack_groups g = {0};
    if (s == BIREF_OK) s = biref_stack_path_groups(&b, (const double(*)[4])grp, legs, o->tolerance, o->max_groups, &g);
    if (s != BIREF_OK || (*reason = g.reason)) return s;
    const biref_stack_sums band = {BIREF_SIDE_BOTH, 1, j, legs, node};
    s = biref_stack_face_sums(sp, &g, light, &band, x, m, err);
    for (int f = 0; f < 2; f++) info->groups[f] = g.n[f] > info->groups[f] ? g.n[f] : info->groups[f];
    info->legs = g.legs > info->legs ? g.legs : info->legs;
    info->bound = fmax(info->bound, g.bound);
    biref_stack_groups_free(&g);
    return s;
}

/* Gives up on the expansion: adaptive numeric integration with n(λ) per sample, and why. */
static biref_status fall_back(const biref_spectral *sp, const biref_stack_state *st,
                              const biref_stack_spectrum_opts *o, const biref_light *light, biref_spectrum *out,
                              double mixed[2][3], biref_stack_spectrum_info *info, const char *reason)
{
    info->fallback = 1;
    info->reason = reason;
    info->groups[0] = info->groups[1] = 0;
    int converged;
    biref_status s = biref_stack_numeric_adaptive(sp, st, light, o->tolerance, out, mixed, &info->samples, &converged);
    info->bound = converged ? o->tolerance : NAN;
    return s;
}

biref_status biref_stack_expansion_dispersive(const biref_spectral *sp, const biref_stack_state *st,
                                              const biref_stack_spectrum_opts *o, const biref_light *light,
                                              biref_spectrum *out, double mixed[2][3],
                                              biref_stack_spectrum_info *info)
{
    if (st->evanescent)
        return fall_back(sp, st, o, light, out, mixed, info, "a layer has an evanescent mode (total reflection inside)");
    biref_stack_legs *legs;
    biref_status s = biref_stack_legs_create(sp, st, &legs);
    if (s != BIREF_OK) return s;
    memset(out, 0, sizeof *out);
    memset(mixed, 0, sizeof(double[2][3]));
    info->bound = 0.0;
    /* Constant materials only: one run per band at its centroid, the constant stack's numbers. */
    const int nodes = biref_stack_legs_flat(legs) ? 0 : BIREF_BAND_NODES;
    const biref_band_nodes *bn = biref_stack_legs_nodes(legs);
    const char *reason = NULL;
    for (int j = 0; j < 3 && s == BIREF_OK && !reason; j++)
        for (int i = nodes ? 0 : -1; i < nodes && s == BIREF_OK && !reason; i++) {
            const double total = bn->mass[j][0] + bn->mass[j][1];
            const double share = i < 0 ? 1.0 : bn->mass[j][i] / total;
            if (!(share > 0.0)) continue; /* a degenerate band's empty node */
            const double lambda = 2.0 * M_PI / (i < 0 ? sp->k_centroid[j] : bn->k[j][i]);
            biref_spectrum x;
            double m[2][3], err = 0.0;
            s = band_run(sp, st, o, light, legs, j, i, lambda, &x, m, &err, info, &reason);
            if (s == BIREF_OK && !reason && err > o->tolerance)
                reason = "dispersion: the phases curve too much across the finest sub-bands";
            if (s != BIREF_OK || reason) break;
            for (int a = 0; a < 2; a++)
                for (int k = 0; k < 2; k++) {
                    out->T[a][k][j] += share * x.T[a][k][j];
                    out->R[a][k][j] += share * x.R[a][k][j];
                }
            mixed[0][j] += share * m[0][j];
            mixed[1][j] += share * m[1][j];
        }
    biref_stack_legs_destroy(legs);
    if (s == BIREF_OK && reason) return fall_back(sp, st, o, light, out, mixed, info, reason);
    return s;
}
