/* Exact spectral integration of the path-group expansion, for any polarizer and analyzer
 * (beyond the paper).
 *
 * Ignoring dispersion within a band, J(k) = sum_g M_g e^{ik Phi_g}: a group g collects the
 * paths with the same numbers of o/e legs down and up, hence the same optical path Phi_g. For an
 * incident coherency matrix C and an analyzer P the detected intensity is
 *     I(k) = sum_{g,h} c_gh e^{ik(Phi_g - conj Phi_h)},   c_gh = sum C_ij (M_g P)_io conj((M_h P)_jo),
 * so its band integral is exact given S(cos kD) and S(sin kD) at the pairwise differences. The
 * paper's eq. 26 keeps only some pairs (order 0 and "descendants"); here every pair up to the
 * pair order interferes, groups of up to two more orders add their own intensity (the paths of a
 * group are coherent with each other), and the paths beyond add their energy incoherently, summed
 * in closed form (the geometric series of eq. 20-21); see choose_orders and docs/PHYSICS.md §5. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "spectral/expansion_internal.h"

void biref_expansion_opts_default(biref_expansion_opts *o)
{
    o->order = -1;
    o->tolerance = 1e-3;
    o->max_order = EXP_MAX_ORDER;
}

/* The pair sums of one direction's groups and its tail, for the four pure pairs (input i fully
 * polarized, analyzer passing output o): one component per form, v_g = M_g[i][o]. */
static void pure_pair_intensities(phase_cache *pc, const biref_slab_state *st, const tail_model *tm,
                                  expansion_orders ord, path_group *g, int G, double out[4][3])
{
    G = biref_xp_merged(st, g, G);
    int Gp = biref_xp_groups_below(g, G, ord.pairs);
    double complex v[EXP_MAX_GROUPS][MAX_COMP];
    for (int a = 0; a < G; a++)
        for (int k = 0; k < 4; k++) v[a][k] = g[a].M[k >> 1][k & 1];
    biref_xp_pair_sums(pc, g, G, Gp, (const double complex(*)[MAX_COMP])v, st->total_reflection, out);
    for (int k = 0; k < 4; k++) {
        double tail[3];
        biref_xp_tail_energy(tm, k, ord.groups, tail);
        for (int j = 0; j < 3; j++) out[k][j] += tail[j];
    }
}

/* The detected intensity of one general form (any coherency matrix and analyzer). */
static int expansion_core(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp, int which,
                          const quad_form *form, const biref_expansion_opts *opts, double out[3])
{
    tail_model tm;
    biref_xp_tail_setup(sp, st, which, form, 1, &tm);
    phase_cache pc;
    cache_init(&pc, sp, st, fp);
    expansion_orders ord = biref_xp_choose_orders(&pc, st, &tm, 1, opts);
    path_group g[EXP_MAX_GROUPS];
    int G;
    if (which == BIREF_TRANSMISSION)
        biref_xp_build_groups(st, ord.groups, g, &G, -1, NULL, NULL);
    else
        biref_xp_build_groups(st, -1, NULL, NULL, ord.groups, g, &G);
    G = biref_xp_merged(st, g, G);
    int Gp = biref_xp_groups_below(g, G, ord.pairs);
    double complex v[EXP_MAX_GROUPS][MAX_COMP];
    biref_xp_form_vectors(g, G, form, v);
    double comp[MAX_COMP][3];
    biref_xp_pair_sums(&pc, g, G, Gp, (const double complex(*)[MAX_COMP])v, st->total_reflection, comp);
    biref_xp_tail_energy(&tm, 0, ord.groups, out);
    for (int c = 0; c < MAX_COMP; c++)
        for (int j = 0; j < 3; j++) out[j] += comp[c][j];
    return ord.pairs;
}

/* The series functions with the phase integrals averaged over the footprint fp (NULL: points). */
static biref_status series_polarized(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                                     int which, const double complex C[2][2], const double complex P[2][2],
                                     const biref_expansion_opts *opts, double xyz[3], int *order_used)
{
    if (!sp || !st || !C || !xyz || (which != BIREF_TRANSMISSION && which != BIREF_REFLECTION)) return BIREF_ERR_INVALID;
    biref_expansion_opts def;
    if (!opts) {
        biref_expansion_opts_default(&def);
        opts = &def;
    }
    if (!(opts->tolerance > 0.0) && opts->order < 0) return BIREF_ERR_INVALID;
    quad_form f = {C, P};
    int order = expansion_core(sp, st, fp, which, &f, opts, xyz);
    if (order_used) *order_used = order;
    return BIREF_OK;
}

biref_status biref_expansion_series_polarized(const biref_spectral *sp, const biref_slab_state *st, int which,
                                              const double complex C[2][2], const double complex P[2][2],
                                              const biref_expansion_opts *opts, double xyz[3], int *order_used)
{
    return series_polarized(sp, st, NULL, which, C, P, opts, xyz, order_used);
}

/* order_used (NULL: not wanted): the pair order of each direction. */
static biref_status series(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                           const biref_expansion_opts *opts, biref_spectrum *out, int order_used[2])
{
    if (!sp || !st || !out) return BIREF_ERR_INVALID;
    biref_expansion_opts def;
    if (!opts) {
        biref_expansion_opts_default(&def);
        opts = &def;
    }
    if (!(opts->tolerance > 0.0) && opts->order < 0) return BIREF_ERR_INVALID;
    /* Forms: input i fully polarized (C = e_i e_i^H), analyzer passing output o only. */
    static const double complex Cin[2][2][2] = {{{1, 0}, {0, 0}}, {{0, 0}, {0, 1}}};
    static const double complex Pout[2][2][2] = {{{1, 0}, {0, 0}}, {{0, 0}, {0, 1}}};
    quad_form f[4];
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) f[2 * i + o] = (quad_form){Cin[i], Pout[o]};
    /* Transmission and reflection share the path differences, hence the band integrals, and
     * the amplitude recursion. */
    phase_cache pc;
    cache_init(&pc, sp, st, fp);
    tail_model tm[2];
    expansion_orders ord[2];
    for (int which = 0; which < 2; which++) {
        biref_xp_tail_setup(sp, st, which, f, 4, &tm[which]);
        ord[which] = biref_xp_choose_orders(&pc, st, &tm[which], 4, opts);
        if (order_used) order_used[which] = ord[which].pairs;
    }
    path_group gT[EXP_MAX_GROUPS], gR[EXP_MAX_GROUPS];
    int G[2];
    biref_xp_build_groups(st, ord[0].groups, gT, &G[0], ord[1].groups, gR, &G[1]);
    for (int which = 0; which < 2; which++) {
        double res[4][3];
        pure_pair_intensities(&pc, st, &tm[which], ord[which], which ? gR : gT, G[which], res);
        double(*X)[2][3] = which == BIREF_REFLECTION ? out->R : out->T;
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++) memcpy(X[i][o], res[2 * i + o], sizeof res[0]);
    }
    return BIREF_OK;
}

biref_status biref_expansion_series(const biref_spectral *sp, const biref_slab_state *st,
                                    const biref_expansion_opts *opts, biref_spectrum *out)
{
    return series(sp, st, NULL, opts, out, NULL);
}

static biref_status expansion_pairs(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                                    const biref_expansion_opts *opts, biref_spectrum *out, int order_used[2]);

static int is_diagonal(const double complex M[2][2]) { return M[0][1] == 0.0 && M[1][0] == 0.0; }

/* Thin slabs and evanescent legs that couple the faces: the path series converges too slowly
 * (or, with amplifying evanescent reflections, not at all) and its incoherent tail is wrong;
 * the exact integral of eq. 17 instead (src/spectral/coherent.c). *order_used is 0 then.
 * Elsewhere the truncated series can leave [0, 1] slightly where internal reflections are strong
 * (up to ~1e-2 at grazing incidence and high indices): for the paper's light model (C and P
 * diagonal) the result is that of biref_spectrum_expansion, kept physical with both directions
 * (biref_physical_limit); for other polarizers it is kept >= 0 by moving it towards the
 * incoherent energy of the paths. */
static biref_status expansion_polarized(const biref_spectral *sp, const biref_slab_state *st,
                                       const biref_opl_footprint *fp, int which, const double complex C[2][2],
                                       const double complex P[2][2], const biref_expansion_opts *opts, double xyz[3],
                                       int *order_used)
{
    if (!sp || !st || !C || !xyz || (which != BIREF_TRANSMISSION && which != BIREF_REFLECTION)) return BIREF_ERR_INVALID;
    const biref_numeric_plan *coherent = biref_coherent_plan(sp, st);
    if (coherent) {
        if (opts && !(opts->tolerance > 0.0) && opts->order < 0) return BIREF_ERR_INVALID;
        biref_spectrum_numeric_polarized(coherent, st, which, C, P, xyz);
        if (order_used) *order_used = 0;
        return BIREF_OK;
    }
    if (is_diagonal(C) && (!P || is_diagonal(P))) {
        /* The order reported is the one the result comes from: that of the four s/p pairs. */
        biref_spectrum x;
        int ord[2];
        biref_status s = expansion_pairs(sp, st, fp, opts, &x, ord);
        if (s != BIREF_OK) return s;
        if (order_used) *order_used = ord[which];
        const double(*X)[2][3] = which == BIREF_REFLECTION ? x.R : x.T;
        for (int j = 0; j < 3; j++) {
            xyz[j] = 0.0;
            for (int i = 0; i < 2; i++)
                for (int o = 0; o < 2; o++) xyz[j] += creal(C[i][i]) * (P ? cabs(P[o][o]) * cabs(P[o][o]) : 1.0) * X[i][o][j];
        }
        return BIREF_OK;
    }
    biref_status s = series_polarized(sp, st, fp, which, C, P, opts, xyz, order_used);
    if (s != BIREF_OK) return s;
    if (xyz[0] < 0.0 || xyz[1] < 0.0 || xyz[2] < 0.0) {
        quad_form f = {C, P};
        tail_model tm;
        biref_xp_tail_setup(sp, st, which, &f, 1, &tm);
        double e[3];
        biref_xp_tail_energy(&tm, 0, tm.lowest - 1, e); /* every order */
        if (which == BIREF_REFLECTION) {
            /* plus the direct reflection, order 0 */
            const double complex(*r01)[2] = st->top.r_down;
            for (int o = 0; o < 2; o++) {
                double complex v[2];
                for (int i = 0; i < 2; i++) v[i] = P ? r01[i][0] * P[0][o] + r01[i][1] * P[1][o] : r01[i][o];
                double d = 0.0;
                for (int i = 0; i < 2; i++)
                    for (int jj = 0; jj < 2; jj++) d += creal(C[i][jj] * v[i] * conj(v[jj]));
                for (int j = 0; j < 3; j++) e[j] += d;
            }
        }
        double t = 1.0;
        for (int j = 0; j < 3; j++)
            if (xyz[j] < 0.0) t = fmin(t, e[j] > 0.0 ? e[j] / (e[j] - xyz[j]) : 0.0);
        for (int j = 0; j < 3; j++) xyz[j] = e[j] + t * (xyz[j] - e[j]);
    }
    return BIREF_OK;
}

static biref_status expansion_pairs(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                                    const biref_expansion_opts *opts, biref_spectrum *out, int order_used[2])
{
    if (!sp || !st || !out) return BIREF_ERR_INVALID;
    const biref_numeric_plan *coherent = biref_coherent_plan(sp, st);
    if (!coherent) {
        biref_status s = series(sp, st, fp, opts, out, order_used);
        if (s != BIREF_OK) return s;
        /* The truncated series and its incoherent tail can leave [0, 1] by up to ~1e-2 where
         * internal reflections are strong (grazing incidence, high indices). */
        double E[2][2][2][3], X[2][2][2][3];
        for (int which = 0; which < 2; which++) biref_analytic_paper_energy(sp, st, which, E[which]);
        memcpy(X[0], out->T, sizeof out->T);
        memcpy(X[1], out->R, sizeof out->R);
        biref_physical_limit((const double(*)[2][2][3])E, X);
        memcpy(out->T, X[0], sizeof out->T);
        memcpy(out->R, X[1], sizeof out->R);
        return BIREF_OK;
    }
    if (opts && !(opts->tolerance > 0.0) && opts->order < 0) return BIREF_ERR_INVALID;
    biref_spectrum_numeric(coherent, st, out);
    if (order_used) order_used[0] = order_used[1] = 0;
    return BIREF_OK;
}

/* A result that is not finite is an error (BIREF_ERR_ILLCOND), never an output. */
static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

biref_status biref_spectrum_expansion_polarized(const biref_spectral *sp, const biref_slab_state *st, int which,
                                                const double complex C[2][2], const double complex P[2][2],
                                                const biref_expansion_opts *opts, double xyz[3], int *order_used)
{
    return biref_expansion_polarized_footprint(sp, st, NULL, which, C, P, opts, xyz, order_used);
}

biref_status biref_expansion_polarized_footprint(const biref_spectral *sp, const biref_slab_state *st,
                                                 const biref_opl_footprint *fp, int which, const double complex C[2][2],
                                                 const double complex P[2][2], const biref_expansion_opts *opts,
                                                 double xyz[3], int *order_used)
{
    biref_status s = expansion_polarized(sp, st, fp, which, C, P, opts, xyz, order_used);
    return s == BIREF_OK && !finite3(xyz) ? BIREF_ERR_ILLCOND : s;
}

biref_status biref_spectrum_expansion(const biref_spectral *sp, const biref_slab_state *st,
                                      const biref_expansion_opts *opts, biref_spectrum *out)
{
    return biref_spectrum_expansion_footprint(sp, st, NULL, opts, out);
}

biref_status biref_spectrum_expansion_footprint(const biref_spectral *sp, const biref_slab_state *st,
                                                const biref_opl_footprint *fp, const biref_expansion_opts *opts,
                                                biref_spectrum *out)
{
    biref_status s = expansion_pairs(sp, st, fp, opts, out, NULL);
    if (s != BIREF_OK) return s;
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++)
            if (!finite3(out->T[i][o]) || !finite3(out->R[i][o])) return BIREF_ERR_ILLCOND;
    return BIREF_OK;
}
