/* The path expansion of a stack with layers of a dispersive material (docs/STACKS.md, "Layers of a
 * dispersive material"). Per colour-matching band j the stack is prepared at the band's centroid
 * wavelength λ_j and every leg's phase is linearised in the wavenumber there, as the slab's is
 * (analytic_dispersive.c, docs/PHYSICS.md §7):
 *
 *   k opl(k) ≈ k opl_g + ψ,   opl_g = opl − λ d opl/dλ (the group optical path),  ψ = 2π d opl/dλ,
 *
 * the offset e^{iψ} riding on the coefficients of the interface that ends the leg. A path's phase
 * is the sum of its legs', so the band's groups are again amplitude × e^{ik·(group path)}, and the
 * pair sums of the constant expansion integrate them exactly; band j of the result comes from the
 * band-j groups. What the line leaves out is each leg's curvature d²(k opl)/dk²: the groups carry
 * the sum of theirs, and the pair sums estimate the error of the quadratic phases across the band
 * (stack_spectrum.c). Where that estimate passes the tolerance, or the expansion does not apply
 * (evanescent layers, too many groups, the bound not met), the adaptive numeric integration with
 * the stack prepared anew at every sample wavelength, reported in info. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "biref/stack.h"
#include "spectral/spectral_internal.h"
#include "spectral/stack_internal.h"

/* Half the step of the central difference of the optical paths in λ (nm), and of the second
 * difference of the phases (nm): the slab's choices (analytic_dispersive.c). */
#define DISPERSION_DIFF_NM 0.1
#define CURVATURE_DIFF_NM 5.0

static void scale_row(biref_complex M[2][2], int row, double complex f)
{
    M[row][0] *= f;
    M[row][1] *= f;
}

/* Re opl of every leg of a state, [layer][BIREF_MODE_*]. */
static void leg_paths(const biref_stack_state *st, double out[][4])
{
    for (int l = 0; l < st->n_layers; l++)
        for (int x = 0; x < 2; x++) {
            out[l][BIREF_MODE_O_DOWN + x] = creal(st->opl_down[l][x]);
            out[l][BIREF_MODE_O_UP + x] = creal(st->opl_up[l][x]);
        }
}

/* The linearised state of band j and each leg's phase curvature d²(k opl)/dk² (nm²). */
static biref_status band_state(const biref_spectral *sp, const biref_stack_state *st, int j, biref_stack_state *b,
                               double curv[][4])
{
    const double lambda = 2.0 * M_PI / sp->k_centroid[j], h = DISPERSION_DIFF_NM, H = CURVATURE_DIFF_NM;
    static const double offset[4] = {-DISPERSION_DIFF_NM, DISPERSION_DIFF_NM, -CURVATURE_DIFF_NM, CURVATURE_DIFF_NM};
    double p[4][BIREF_STACK_MAX_LAYERS][4], mid[BIREF_STACK_MAX_LAYERS][4];
    biref_status s = biref_stack_prepare_at(&st->stack, st->theta, lambda, b);
    for (int i = 0; i < 4 && s == BIREF_OK; i++) {
        biref_stack_state at;
        s = biref_stack_prepare_at(&st->stack, st->theta, lambda + offset[i], &at);
        if (s == BIREF_OK) leg_paths(&at, p[i]);
    }
    if (s != BIREF_OK) return s;
    leg_paths(b, mid);
    const double ka = 2.0 * M_PI / (lambda - H), km = 2.0 * M_PI / lambda, kb = 2.0 * M_PI / (lambda + H);
    for (int l = 0; l < b->n_layers; l++)
        for (int mode = 0; mode < 4; mode++) {
            const int up = mode >= BIREF_MODE_O_UP, x = mode & 1;
            const double dopl = (p[1][l][mode] - p[0][l][mode]) / (2.0 * h);
            /* second derivative of k opl through three unevenly spaced points (kb < km < ka) */
            const double pa = ka * p[2][l][mode], pm = km * mid[l][mode], pb = kb * p[3][l][mode];
            curv[l][mode] = 2.0 * ((pa - pm) / (ka - km) - (pm - pb) / (km - kb)) / (ka - kb);
            biref_complex *opl = up ? &b->opl_up[l][x] : &b->opl_down[l][x];
            *opl = (creal(*opl) - lambda * dopl) + I * cimag(*opl); /* the decay stays at λ_j */
            const double complex f = cexp(I * 2.0 * M_PI * dopl);  /* ψ = k_j (opl − opl_g) */
            biref_interface *end = &b->iface[up ? l : l + 1];
            if (up) {
                scale_row(end->r_up, x, f);
                scale_row(end->t_up, x, f);
            } else {
                scale_row(end->r_down, x, f);
                scale_row(end->t_down, x, f);
            }
        }
    b->dispersive = 0; /* the band's linearised constants, not n(λ) */
    return BIREF_OK;
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
    memset(out, 0, sizeof *out);
    info->bound = 0.0;
    for (int j = 0; j < 3; j++) {
        biref_stack_state b;
        double curv[BIREF_STACK_MAX_LAYERS][4];
        biref_status s = band_state(sp, st, j, &b, curv);
        if (s != BIREF_OK) return s;
        biref_stack_groups g;
        s = biref_stack_path_groups(&b, (const double(*)[4])curv, o->tolerance, o->max_groups, &g);
        if (s != BIREF_OK) return s;
        if (g.reason) return fall_back(sp, st, o, light, out, mixed, info, g.reason);
        biref_spectrum x;
        double m[2][3], err = 0.0;
        const biref_stack_sums band = {BIREF_SIDE_BOTH, 1, j, biref_spectral_band_k_width(sp, j)};
        s = biref_stack_face_sums(sp, &g, light, &band, &x, m, &err);
        for (int f = 0; f < 2; f++) info->groups[f] = g.n[f] > info->groups[f] ? g.n[f] : info->groups[f];
        info->legs = g.legs > info->legs ? g.legs : info->legs;
        info->bound = fmax(info->bound, g.bound);
        biref_stack_groups_free(&g);
        if (s != BIREF_OK) return s;
        if (err > o->tolerance)
            return fall_back(sp, st, o, light, out, mixed, info,
                             "dispersion: the phases curve too much across a band to be linearised");
        for (int i = 0; i < 2; i++)
            for (int k = 0; k < 2; k++) {
                out->T[i][k][j] = x.T[i][k][j];
                out->R[i][k][j] = x.R[i][k][j];
            }
        mixed[0][j] = m[0][j];
        mixed[1][j] = m[1][j];
    }
    return BIREF_OK;
}
