/* The analytic method (eqs. 19-26, m = 1) for any light: an incident coherency matrix C and an
 * analyzer P instead of the paper's s/p fractions and mask. The formulas are the GLSL shader's
 * (shaders/biref_analytic.glsl, transmission_terms and reflection_terms; docs/GPU.md,
 * "Polarisation: one formula for both light models"), in double precision and with complex C and
 * P (circular light and analyzers).
 *
 * Every pair of paths (a, b) contributes sum_ij C_ij (A_b P)_io conj((A_a P)_jo) e^{ik(Phi_b -
 * conj Phi_a)}. All paths of a direction start with the same entry (t01) and, but for the direct
 * reflection, end with the same exit (t12 or t10), so each pair coefficient is a product of
 *     Ein[x][x'] = sum_ij C_ij t01[i][x'] conj(t01[j][x])          (entry, modes x, x')
 *     Xout[y][y'] = sum_o (t P)[y'][o] conj((t P)[y][o])           (exit, modes y, y')
 * and the reflections in between; the E term's geometric series (eqs. 20-21) takes Ein's diagonal
 * as its entry energies and Xout's diagonal as its exit weights. For C = diag(w_in) and
 * P = diag(sqrt(mask)) every term is the paper's mixed by biref_spectrum_mix.
 *
 * Keeping the result physical: eq. 26 can leave [0, inf) where internal reflections are strong.
 * A negative result is moved towards the incoherent path energy E (X = E + t (X - E), one t for
 * the three bands), as the expansion does for a general light and the shader does; the energy
 * balance of biref_physical_limit needs the four s/p pairs and is only applied to the paper's
 * model. */
#include <complex.h>
#include <math.h>

#include "spectral/analytic_terms.h"

static const double ONE[3] = {1.0, 1.0, 1.0};

/* Ein[a][b] = sum_ij C_ij t[i][b] conj(t[j][a]). */
static void entry_matrix(const double complex C[2][2], const double complex (*t)[2], double complex Ein[2][2])
{
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            double complex s = 0.0;
            for (int i = 0; i < 2; i++)
                for (int j = 0; j < 2; j++) s += C[i][j] * t[i][b] * conj(t[j][a]);
            Ein[a][b] = s;
        }
}

/* TP = t P (P NULL: no analyzer); Xout[a][b] = sum_o TP[b][o] conj(TP[a][o]). */
static void exit_matrix(const double complex (*t)[2], const double complex (*P)[2], double complex TP[2][2],
                        double complex Xout[2][2])
{
    for (int y = 0; y < 2; y++)
        for (int o = 0; o < 2; o++) TP[y][o] = P ? t[y][0] * P[0][o] + t[y][1] * P[1][o] : t[y][o];
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) Xout[a][b] = TP[b][0] * conj(TP[a][0]) + TP[b][1] * conj(TP[a][1]);
}

static void transmission(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                         const double complex C[2][2], const double complex (*P)[2], double E[3], double H[3])
{
    const double complex(*r10)[2] = st->top.r_up, (*r12)[2] = st->bottom.r_down;
    biref_phase_int h0, trip[2][2], pair[4][4], ep[4][4];
    biref_transmission_phases(sp, st, fp, &h0, trip);
    biref_order1_pairs(sp, st, fp, pair);
    biref_entry_pairs(sp, st, fp, ep);

    double complex Ein[2][2], TP[2][2], Xout[2][2];
    entry_matrix(C, st->top.t_down, Ein);
    exit_matrix(st->bottom.t_down, P, TP, Xout);
    double ed[2][3], eu[2][3], w0[1][2][3], W[1][2][3];
    for (int m = 0; m < 2; m++) {
        biref_leg_energy(sp, st->opl_down[m], ed[m]);
        biref_leg_energy(sp, st->opl_up[m], eu[m]);
        for (int j = 0; j < 3; j++) w0[0][m][j] = creal(Ein[m][m]) * ed[m][j];
    }
    /* W[x]: energy of all paths arriving at the bottom in mode x (eq. 21's left part). */
    biref_path_energies((const double(*)[2][3])w0, 1, r12, eu, r10, ed, W);
    for (int j = 0; j < 3; j++) {
        E[j] = W[0][0][j] * creal(Xout[0][0]) + W[0][1][j] * creal(Xout[1][1]);
        H[j] = 0.0;
    }
    /* H0 (eq. 24): the ordinary and the extraordinary order-0 path. */
    biref_add_re_integral(H, ONE, Ein[0][1] * Xout[0][1], &h0);
    /* Descendants (eq. 23, m = 1): one more round trip (bottom into y, top into x'). */
    for (int y = 0; y < 2; y++)
        for (int x2 = 0; x2 < 2; x2++)
            for (int x = 0; x < 2; x++)
                biref_add_re_integral(H, W[0][x], r12[x][y] * r10[y][x2] * Xout[x][x2], &trip[y][x2]);
    /* Siblings (analytic.c): from the bottom in mode x, two last round trips a < b, a = (down x2,
     * up y), with the lags of reflection's order-1 pairs. */
    for (int x = 0; x < 2; x++)
        for (int a = 0; a < 4; a++)
            for (int b = a + 1; b < 4; b++) {
                int ya = a & 1, xa = a >> 1, yb = b & 1, xb = b >> 1;
                double complex c = conj(r12[x][ya] * r10[ya][xa]) * r12[x][yb] * r10[yb][xb] * Xout[xa][xb];
                biref_add_re_integral(H, W[0][x], c, &pair[a][b]);
            }
    /* The order-1 paths whose entry legs differ, (o, a) and (e, b). */
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) {
            int ya = a & 1, xa = a >> 1, yb = b & 1, xb = b >> 1;
            double complex c = Ein[0][1] * conj(r12[0][ya] * r10[ya][xa]) * r12[1][yb] * r10[yb][xb] * Xout[xa][xb];
            biref_add_re_integral(H, ONE, c, &ep[a][b]);
        }
}

static void reflection(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                       const double complex C[2][2], const double complex (*P)[2], double E[3], double H[3])
{
    const double complex(*t01)[2] = st->top.t_down, (*r10)[2] = st->top.r_up, (*r12)[2] = st->bottom.r_down;
    biref_phase_int p1[4], pair[4][4];
    biref_reflection_phases(sp, st, fp, p1, pair);

    double complex Ein[2][2], UP[2][2], Xout[2][2], RP[2][2], unused[2][2];
    entry_matrix(C, t01, Ein);
    exit_matrix(st->top.t_up, P, UP, Xout);
    exit_matrix(st->top.r_down, P, RP, unused);
    double ed[2][3], eu[2][3], u0[1][2][3], U[1][2][3];
    for (int m = 0; m < 2; m++) biref_leg_energy(sp, st->opl_down[m], ed[m]), biref_leg_energy(sp, st->opl_up[m], eu[m]);
    for (int y = 0; y < 2; y++)
        for (int j = 0; j < 3; j++)
            u0[0][y][j] = (creal(Ein[0][0]) * ed[0][j] * biref_abs2(r12[0][y]) +
                           creal(Ein[1][1]) * ed[1][j] * biref_abs2(r12[1][y])) * eu[y][j];
    /* U[y]: energy of all paths arriving at the top (inside) in up mode y. */
    biref_path_energies((const double(*)[2][3])u0, 1, r10, ed, r12, eu, U);
    /* The direct reflection's energy sum_ij C_ij sum_o RP[i][o] conj(RP[j][o]), and
     * Q[j][y] = sum_o UP[y][o] conj(RP[j][o]) for its pairs with the order-1 paths. */
    double e0 = 0.0;
    double complex Q[2][2];
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) e0 += creal(C[i][j] * (RP[i][0] * conj(RP[j][0]) + RP[i][1] * conj(RP[j][1])));
    for (int j = 0; j < 2; j++)
        for (int y = 0; y < 2; y++) Q[j][y] = UP[y][0] * conj(RP[j][0]) + UP[y][1] * conj(RP[j][1]);
    for (int j = 0; j < 3; j++) {
        E[j] = e0 + U[0][0][j] * creal(Xout[0][0]) + U[0][1][j] * creal(Xout[1][1]);
        H[j] = 0.0;
    }
    for (int a = 0; a < 4; a++) {
        int x = a >> 1, y = a & 1;
        /* direct x order-1 path a: sum_ij C_ij t01[i][x] r12[x][y] Q[j][y] */
        double complex c = 0.0;
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) c += C[i][j] * t01[i][x] * Q[j][y];
        biref_add_re_integral(H, ONE, r12[x][y] * c, &p1[a]);
    }
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++) {
            int xa = a >> 1, ya = a & 1, xb = b >> 1, yb = b & 1;
            double complex c = conj(r12[xa][ya]) * r12[xb][yb] * Ein[xa][xb] * Xout[ya][yb];
            biref_add_re_integral(H, ONE, c, &pair[a][b]);
        }
    /* Descendants: a path arriving at the top in up mode y, one more round trip (x', y'). */
    for (int y = 0; y < 2; y++)
        for (int a = 0; a < 4; a++)
            biref_add_re_integral(H, U[0][y], r10[y][a >> 1] * r12[a >> 1][a & 1] * Xout[y][a & 1], &p1[a]);
}

void biref_analytic_general_terms(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                                  int which, const double complex C[2][2], const double complex P[2][2], double E[3],
                                  double H[3])
{
    if (which == BIREF_REFLECTION)
        reflection(sp, st, fp, C, P, E, H);
    else
        transmission(sp, st, fp, C, P, E, H);
}

void biref_analytic_general(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                            int which, const double complex C[2][2], const double complex P[2][2], double xyz[3])
{
    const biref_numeric_plan *coherent = biref_coherent_plan(sp, st);
    if (coherent) {
        /* Thin slab or evanescent coupling: the exact integral, as for the paper's light. */
        biref_spectrum_numeric_polarized(coherent, st, which, C, P, xyz);
        return;
    }
    double E[3], H[3];
    biref_analytic_general_terms(sp, st, fp, which, C, P, E, H);
    double t = 1.0;
    for (int j = 0; j < 3; j++) {
        xyz[j] = E[j] + 2.0 * H[j]; /* eqs. 25-26 */
        if (xyz[j] < 0.0) t = fmin(t, E[j] > 0.0 ? E[j] / (E[j] - xyz[j]) : 0.0);
    }
    if (t < 1.0)
        for (int j = 0; j < 3; j++) xyz[j] = E[j] + t * (xyz[j] - E[j]);
}
