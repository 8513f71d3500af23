/* The paper's analytic approximation of the spectral integral (§5, eqs. 19–26, m = 1), for
 * all four input/output polarisation pairs, in transmission and in reflection.
 *
 * S(|J|^2) = E + 2H (eq. 19). E, the incoherent sum of all path energies, is summed in closed
 * form as a geometric series of the component-wise |.|^2 of the round-trip operator (eqs.
 * 20–21; the right-hand vector of eq. 21 is the exit coefficients, docs/PAPER-ERRATA.md). H keeps
 * only the pairs (path, path + one more round trip) ("descendants", eqs. 22–23 with m = 1)
 * plus the interference of the lowest-order paths among themselves (H0, eq. 24). Transmission
 * also keeps the siblings (ours, beyond the paper): the pairs of paths of one order that coincide
 * up to their last round trip, weighted like the descendants by the energy W of all paths
 * reaching the bottom, and the order-1 pairs whose entry legs differ. Their lags are the
 * birefringent ones (multiples of e − o down and up), as short as H0's, so they interfere as
 * strongly; without them eq. 26 misses up to ΔE00 7–12 of grazing light through strongly
 * reflecting plates (docs/ACCURACY-DISPERSION.md). Complex
 * coefficients (total reflection) need S(sin(k D)) next to S(cos(k D)):
 * S(Re(c e^{ikD})) = Re(c) S(cos kD) - Im(c) S(sin kD).
 *
 * Reflection is derived the same way (the paper's supplement is not available): the lowest
 * orders are the direct reflection and the four order-1 paths (down x, up y), whose ten
 * mutual pairs form H0_R; descendants add one round trip (down x', up y') before exiting. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "spectral/analytic_terms.h"

static const double ONE[3] = {1.0, 1.0, 1.0};

void biref_transmission_phases(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                               biref_phase_int *h0, biref_phase_int trip[2][2])
{
    const double complex *od = st->opl_down, *ou = st->opl_up;
    /* Distinct optical path differences: the order-0 pair (eq. 24) and the four round trips
     * (bottom reflection into y, up, top reflection into x', down): five table look-ups. */
    biref_phase_eval(sp, fp, od[1] - conj(od[0]), (const int[4]){-1, 1, 0, 0}, h0);
    for (int y = 0; y < 2; y++)
        for (int x2 = 0; x2 < 2; x2++) {
            int n[4] = {0, 0, 0, 0};
            n[BIREF_LEG_DOWN_O + x2]++, n[BIREF_LEG_UP_O + y]++;
            biref_phase_eval(sp, fp, ou[y] + od[x2], n, &trip[y][x2]);
        }
}

void biref_order1_pairs(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                        biref_phase_int pair[4][4])
{
    const double complex *od = st->opl_down, *ou = st->opl_up;
    double complex opl1[4];
    int legs1[4][4] = {{0}}; /* leg counts of the order-1 paths */
    for (int a = 0; a < 4; a++) {
        opl1[a] = od[a >> 1] + ou[a & 1];
        legs1[a][BIREF_LEG_DOWN_O + (a >> 1)]++, legs1[a][BIREF_LEG_UP_O + (a & 1)]++;
    }
    /* Pairs (0,1) and (2,3) differ by the same up-leg difference, (0,2) and (1,3) by the same
     * down-leg difference: their table values coincide, only the decay of evanescent legs can
     * differ. Six pairs, four look-ups. */
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++) {
            double complex d = opl1[b] - conj(opl1[a]);
            if ((a == 2 && b == 3) || (a == 1 && b == 3)) {
                const biref_phase_int *twin = a == 2 ? &pair[0][1] : &pair[0][2];
                pair[a][b] = *twin;
                for (int j = 0; j < 3; j++)
                    pair[a][b].att[j] = cimag(d) != 0.0 ? exp(-sp->k_centroid[j] * cimag(d)) : 1.0;
            } else {
                int n[4];
                for (int l = 0; l < 4; l++) n[l] = legs1[b][l] - legs1[a][l];
                biref_phase_eval(sp, fp, d, n, &pair[a][b]);
            }
        }
}

void biref_reflection_phases(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                             biref_phase_int p1[4], biref_phase_int pair[4][4])
{
    const double complex *od = st->opl_down, *ou = st->opl_up;
    /* Order-1 paths a = (down x, up y) = (a >> 1, a & 1); the same four sums serve as the extra
     * round trip of the descendants. */
    for (int a = 0; a < 4; a++) {
        int legs[4] = {0, 0, 0, 0};
        legs[BIREF_LEG_DOWN_O + (a >> 1)]++, legs[BIREF_LEG_UP_O + (a & 1)]++;
        biref_phase_eval(sp, fp, od[a >> 1] + ou[a & 1], legs, &p1[a]);
    }
    biref_order1_pairs(sp, st, fp, pair);
}

void biref_entry_pairs(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                       biref_phase_int ep[4][4])
{
    const double complex *od = st->opl_down, *ou = st->opl_up;
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) {
            /* (down o, down a >> 1, up a & 1) and (down e, down b >> 1, up b & 1) */
            int n[4] = {0, 0, 0, 0};
            n[BIREF_LEG_DOWN_E]++, n[BIREF_LEG_DOWN_O + (b >> 1)]++, n[BIREF_LEG_UP_O + (b & 1)]++;
            n[BIREF_LEG_DOWN_O]--, n[BIREF_LEG_DOWN_O + (a >> 1)]--, n[BIREF_LEG_UP_O + (a & 1)]--;
            double complex la = od[0] + od[a >> 1] + ou[a & 1], lb = od[1] + od[b >> 1] + ou[b & 1];
            biref_phase_eval(sp, fp, lb - conj(la), n, &ep[a][b]);
        }
}

/* E of transmission (eqs. 20-21): W[i][x], the energy of all paths arriving at the bottom in mode
 * x (eq. 21's left part), and the incoherent energy E[i][o] leaving through it. */
static void transmission_energy(const biref_spectral *sp, const biref_slab_state *st, double W[2][2][3],
                                double E[2][2][3])
{
    const double complex(*t01)[2] = st->top.t_down, (*r10)[2] = st->top.r_up;
    const double complex(*r12)[2] = st->bottom.r_down, (*t12)[2] = st->bottom.t_down;
    const double complex *od = st->opl_down, *ou = st->opl_up;
    double ed[2][3], eu[2][3], w0[2][2][3];
    for (int m = 0; m < 2; m++) biref_leg_energy(sp, od[m], ed[m]), biref_leg_energy(sp, ou[m], eu[m]);
    for (int i = 0; i < 2; i++)
        for (int x = 0; x < 2; x++)
            for (int j = 0; j < 3; j++) w0[i][x][j] = biref_abs2(t01[i][x]) * ed[x][j];
    biref_path_energies((const double(*)[2][3])w0, 2, r12, eu, r10, ed, W);
    for (int o = 0; o < 2; o++)
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 3; j++) E[i][o][j] = W[i][0][j] * biref_abs2(t12[0][o]) + W[i][1][j] * biref_abs2(t12[1][o]);
}

/* E of reflection: U[i][y], the energy of all paths arriving at the top (inside) in up mode y,
 * and the incoherent energy E[i][o] of the direct reflection and all paths leaving there. */
static void reflection_energy(const biref_spectral *sp, const biref_slab_state *st, double U[2][2][3],
                              double E[2][2][3])
{
    const double complex(*r01)[2] = st->top.r_down, (*t01)[2] = st->top.t_down;
    const double complex(*r10)[2] = st->top.r_up, (*t10)[2] = st->top.t_up;
    const double complex(*r12)[2] = st->bottom.r_down;
    const double complex *od = st->opl_down, *ou = st->opl_up;
    double ed[2][3], eu[2][3], u0[2][2][3];
    for (int m = 0; m < 2; m++) biref_leg_energy(sp, od[m], ed[m]), biref_leg_energy(sp, ou[m], eu[m]);
    for (int i = 0; i < 2; i++)
        for (int y = 0; y < 2; y++)
            for (int j = 0; j < 3; j++)
                u0[i][y][j] = (biref_abs2(t01[i][0]) * ed[0][j] * biref_abs2(r12[0][y]) + biref_abs2(t01[i][1]) * ed[1][j] * biref_abs2(r12[1][y])) *
                              eu[y][j];
    biref_path_energies((const double(*)[2][3])u0, 2, r10, ed, r12, eu, U);
    for (int o = 0; o < 2; o++)
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 3; j++)
                E[i][o][j] = biref_abs2(r01[i][o]) + U[i][0][j] * biref_abs2(t10[0][o]) + U[i][1][j] * biref_abs2(t10[1][o]);
}

void biref_analytic_paper_energy(const biref_spectral *sp, const biref_slab_state *st, int which, double E[2][2][3])
{
    double V[2][2][3];
    if (which == BIREF_REFLECTION)
        reflection_energy(sp, st, V, E);
    else
        transmission_energy(sp, st, V, E);
}

static void transmission(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                         double E[2][2][3], double H[2][2][3])
{
    const double complex(*t01)[2] = st->top.t_down, (*r10)[2] = st->top.r_up;
    const double complex(*r12)[2] = st->bottom.r_down, (*t12)[2] = st->bottom.t_down;

    biref_phase_int h0, trip[2][2], pair[4][4], ep[4][4];
    biref_transmission_phases(sp, st, fp, &h0, trip);
    biref_order1_pairs(sp, st, fp, pair);
    biref_entry_pairs(sp, st, fp, ep);
    double W[2][2][3];
    transmission_energy(sp, st, W, E);

    for (int o = 0; o < 2; o++) {
        /* Descendant coefficients (eq. 23, m = 1) do not depend on the input; nor do the last
         * round trips a = (down x2, up y) of the siblings, from the bottom in mode x. */
        double complex desc[2][2][2], last[2][4];
        for (int x = 0; x < 2; x++)
            for (int y = 0; y < 2; y++)
                for (int x2 = 0; x2 < 2; x2++) desc[x][y][x2] = conj(t12[x][o]) * r12[x][y] * r10[y][x2] * t12[x2][o];
        for (int x = 0; x < 2; x++)
            for (int a = 0; a < 4; a++) last[x][a] = r12[x][a & 1] * r10[a & 1][a >> 1] * t12[a >> 1][o];
        for (int i = 0; i < 2; i++) {
            double *h = H[i][o];
            h[0] = h[1] = h[2] = 0.0;
            /* H0 (eq. 24): the ordinary and the extraordinary order-0 path. */
            biref_add_re_integral(h, ONE, conj(t01[i][0] * t12[0][o]) * t01[i][1] * t12[1][o], &h0);
            for (int x = 0; x < 2; x++)
                for (int y = 0; y < 2; y++)
                    for (int x2 = 0; x2 < 2; x2++) biref_add_re_integral(h, W[i][x], desc[x][y][x2], &trip[y][x2]);
            /* Siblings (ours): every path arriving at the bottom in mode x, then two different
             * last round trips a < b (lags: reflection's order-1 pairs); and the order-1 paths
             * whose entry legs differ, (o, a) and (e, b). */
            for (int x = 0; x < 2; x++)
                for (int a = 0; a < 4; a++)
                    for (int b = a + 1; b < 4; b++)
                        biref_add_re_integral(h, W[i][x], conj(last[x][a]) * last[x][b], &pair[a][b]);
            const double complex ent = conj(t01[i][0]) * t01[i][1];
            for (int a = 0; a < 4; a++)
                for (int b = 0; b < 4; b++) biref_add_re_integral(h, ONE, ent * conj(last[0][a]) * last[1][b], &ep[a][b]);
        }
    }
}

static void reflection(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                       double E[2][2][3], double H[2][2][3])
{
    const double complex(*r01)[2] = st->top.r_down, (*t01)[2] = st->top.t_down;
    const double complex(*r10)[2] = st->top.r_up, (*t10)[2] = st->top.t_up;
    const double complex(*r12)[2] = st->bottom.r_down;

    biref_phase_int p1[4], pair[4][4];
    biref_reflection_phases(sp, st, fp, p1, pair);
    double U[2][2][3];
    reflection_energy(sp, st, U, E);

    for (int o = 0; o < 2; o++) {
        double complex desc[2][4];
        for (int y = 0; y < 2; y++)
            for (int a = 0; a < 4; a++) desc[y][a] = conj(t10[y][o]) * r10[y][a >> 1] * r12[a >> 1][a & 1] * t10[a & 1][o];
        for (int i = 0; i < 2; i++) {
            double *h = H[i][o];
            h[0] = h[1] = h[2] = 0.0;
            double complex a1[4]; /* order-1 amplitudes without their phase */
            for (int a = 0; a < 4; a++) a1[a] = t01[i][a >> 1] * r12[a >> 1][a & 1] * t10[a & 1][o];
            for (int a = 0; a < 4; a++) {
                biref_add_re_integral(h, ONE, conj(r01[i][o]) * a1[a], &p1[a]);
                for (int b = a + 1; b < 4; b++) biref_add_re_integral(h, ONE, conj(a1[a]) * a1[b], &pair[a][b]);
            }
            for (int y = 0; y < 2; y++)
                for (int a = 0; a < 4; a++) biref_add_re_integral(h, U[i][y], desc[y][a], &p1[a]);
        }
    }
}

/* Eq. 26 (and the truncated expansion) can leave [0, 1] where internal reflections are strong:
 * they keep some interference pairs and drop others, so their interference terms can be more
 * negative than the light there is, and they carry net energy, which the exact ones never do:
 * for a lossless slab sum_out (T + R) = 1 for each input at every wavelength, hence per band.
 * E, the incoherent sum of all path energies, is physical by itself: every path's |a|^2 is its
 * power fraction and an incoherent ray tree conserves power, so sum_out (E_T + E_R) = 1 exactly
 * and E >= 0. Two steps, per input:
 *
 * 1. Each direction on its own: X - E scaled towards E (X = E + s (X - E), a convex combination
 *    of two results, one s in [0, 1] for all bands and outputs), the largest s that makes every
 *    entry >= 0; nothing changes where X >= 0 already. */
static void limit_positive(const double E[2][2][3], double X[2][2][3])
{
    for (int i = 0; i < 2; i++) {
        double s = 1.0;
        for (int o = 0; o < 2; o++)
            for (int j = 0; j < 3; j++)
                if (X[i][o][j] < 0.0) s = fmin(s, E[i][o][j] > 0.0 ? E[i][o][j] / (E[i][o][j] - X[i][o][j]) : 0.0);
        if (s >= 1.0) continue;
        for (int o = 0; o < 2; o++)
            for (int j = 0; j < 3; j++) X[i][o][j] = E[i][o][j] + s * (X[i][o][j] - E[i][o][j]);
    }
}

/* 2. Both directions, per band: divided by sum_out (X_T + X_R), which restores the energy balance
 *    of the exact result (dark outputs, e.g. crossed polarizers, stay dark: the correction is
 *    relative). On the fig. 9 materials this also brings the analytic method closer to the
 *    reference (docs/ACCURACY.md). */
static void normalize_energy(double X[2][2][2][3])
{
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 3; j++) {
            double sum = X[0][i][0][j] + X[0][i][1][j] + X[1][i][0][j] + X[1][i][1][j];
            if (!(sum > 0.0)) continue;
            for (int d = 0; d < 2; d++)
                for (int o = 0; o < 2; o++) X[d][i][o][j] /= sum;
        }
}

void biref_physical_limit(const double E[2][2][2][3], double X[2][2][2][3])
{
    for (int d = 0; d < 2; d++) limit_positive(E[d], X[d]);
    normalize_energy(X);
}

/* E + 2H of the paper's terms with step 1 applied. */
static void paper_terms(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                        int which, double E[2][2][3], double H[2][2][3])
{
    if (which == BIREF_REFLECTION)
        reflection(sp, st, fp, E, H);
    else
        transmission(sp, st, fp, E, H);
}

static void paper_result(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                         int which, double E[2][2][3], double X[2][2][3])
{
    double H[2][2][3];
    paper_terms(sp, st, fp, which, E, H);
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++)
            for (int j = 0; j < 3; j++) X[i][o][j] = E[i][o][j] + 2.0 * H[i][o][j];
    limit_positive(E, X);
}

void biref_analytic_paper_terms(const biref_spectral *sp, const biref_slab_state *st, int which, double E[2][2][3],
                                double H[2][2][3])
{
    paper_terms(sp, st, NULL, which, E, H);
}

void biref_analytic_paper_terms_footprint(const biref_spectral *sp, const biref_slab_state *st,
                                          const biref_opl_footprint *fp, int which, double E[2][2][3], double H[2][2][3])
{
    paper_terms(sp, st, fp, which, E, H);
}

void biref_analytic_terms(const biref_spectral *sp, const biref_slab_state *st, int which, double E[2][2][3],
                          double H[2][2][3])
{
    biref_analytic_terms_footprint(sp, st, NULL, which, E, H);
}

void biref_analytic_terms_footprint(const biref_spectral *sp, const biref_slab_state *st,
                                    const biref_opl_footprint *fp, int which, double E[2][2][3], double H[2][2][3])
{
    const biref_numeric_plan *coherent = biref_coherent_plan(sp, st);
    if (coherent) {
        /* Thin slab or evanescent coupling: eq. 26 does not hold; the exact integral of eq. 17
         * (src/spectral/coherent.c) is returned as E with no interference term. */
        biref_spectrum x;
        biref_spectrum_numeric(coherent, st, &x);
        memcpy(E, which == BIREF_REFLECTION ? x.R : x.T, sizeof x.T);
        memset(H, 0, sizeof x.T);
        return;
    }
    /* Eq. 26 drops interference pairs (siblings, orders two apart) and can leave [0, 1] where
     * internal reflections are strong: the result is kept physical (biref_physical_limit), which
     * needs both directions. H is adjusted so that E + 2H stays the result. */
    double Ed[2][2][2][3], X[2][2][2][3];
    for (int d = 0; d < 2; d++) paper_result(sp, st, fp, d, Ed[d], X[d]);
    normalize_energy(X);
    memcpy(E, Ed[which], sizeof Ed[which]);
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++)
            for (int j = 0; j < 3; j++) H[i][o][j] = 0.5 * (X[which][i][o][j] - E[i][o][j]);
}

void biref_spectrum_analytic(const biref_spectral *sp, const biref_slab_state *st, biref_spectrum *out)
{
    biref_spectrum_analytic_footprint(sp, st, NULL, out);
}

void biref_spectrum_analytic_footprint(const biref_spectral *sp, const biref_slab_state *st,
                                       const biref_opl_footprint *fp, biref_spectrum *out)
{
    const biref_numeric_plan *coherent = biref_coherent_plan(sp, st);
    if (coherent) {
        biref_spectrum_numeric(coherent, st, out);
        return;
    }
    double E[2][2][2][3], X[2][2][2][3];
    for (int d = 0; d < 2; d++) paper_result(sp, st, fp, d, E[d], X[d]); /* eqs. 25-26 */
    normalize_energy(X);
    memcpy(out->T, X[BIREF_TRANSMISSION], sizeof out->T);
    memcpy(out->R, X[BIREF_REFLECTION], sizeof out->R);
}
