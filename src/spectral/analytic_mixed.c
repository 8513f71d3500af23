/* The analytic method (analytic.c, eqs. 19-26, m = 1, kept physical by biref_physical_limit)
 * for one side under the paper's s/p light: the integrator's and the renderer's worker.
 *
 * The result of one side needs both directions of the same state (the energy balance divides by
 * sum_out (X_T + X_R)), so both are computed here in one pass that shares what they share:
 * transmission's four round trips (up y, down x') are reflection's four order-1 paths (down x,
 * up y): one table look-up each instead of two. Look-ups beyond the table's far limit are
 * exactly 0 (docs/PHYSICS.md §4) and their terms, coefficients included, are skipped (adding 0
 * changes nothing). The remaining terms are analytic.c's, in its order and association, so the
 * result is the same bit for bit (tests/test_analytic_mixed.c, test_integrator); slabs in the
 * coherent regime (coherent.c) go to biref_analytic_terms. */
#include <complex.h>
#include <math.h>

#include "spectral/analytic_terms.h"

typedef struct {
    double c[3], s[3]; /* S(cos kD), S(sin kD) per band */
    double att[3];     /* e^{-k_j Im D} */
    int zero;          /* beyond the far limit: the integrals are 0 */
} phase_term;

static void phase_at(const biref_spectral *sp, double complex opd, phase_term *p)
{
    double re = creal(opd);
    p->zero = fabs(re) > sp->d_far;
    if (p->zero) return;
    biref_spectral_phase_integrals(sp, re, p->c, p->s);
    double im = cimag(opd);
    for (int j = 0; j < 3; j++) p->att[j] = im != 0.0 ? exp(-sp->k_centroid[j] * im) : 1.0;
}

/* out_j += weight_j * S(Re(coef e^{ikD})). */
static inline void add_w(double out[3], const double weight[3], double complex coef, const phase_term *p)
{
    double a = creal(coef), b = cimag(coef);
    for (int j = 0; j < 3; j++) out[j] += weight[j] * p->att[j] * (a * p->c[j] - b * p->s[j]);
}

/* out_j += S(Re(coef e^{ikD})). */
static inline void add_1(double out[3], double complex coef, const phase_term *p)
{
    double a = creal(coef), b = cimag(coef);
    for (int j = 0; j < 3; j++) out[j] += p->att[j] * (a * p->c[j] - b * p->s[j]);
}

/* The analytic-pairs method's terms of transmission (analytic.c): the siblings, two last round
 * trips a < b from the bottom in mode x (lags: reflection's order-1 pairs), and the order-1 pairs
 * whose entry legs differ; ent = conj(t01[i][o]) t01[i][e]. */
static void add_pairs(double h[3], const double W[2][3], const double complex last[2][4], double complex ent,
                      const phase_term pair[4][4], const phase_term ep[4][4])
{
    for (int x = 0; x < 2; x++)
        for (int a = 0; a < 4; a++)
            for (int b = a + 1; b < 4; b++)
                if (!pair[a][b].zero) add_w(h, W[x], conj(last[x][a]) * last[x][b], &pair[a][b]);
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++)
            if (!ep[a][b].zero) add_1(h, ent * conj(last[0][a]) * last[1][b], &ep[a][b]);
}

/* E and X = E + 2H (eqs. 19-26) of both directions, [direction][in][out][band]. */
static void paper_both(const biref_spectral *sp, const biref_slab_state *st, int pairs, double E[2][2][2][3],
                       double X[2][2][2][3])
{
    const double complex(*t01)[2] = st->top.t_down, (*r10)[2] = st->top.r_up;
    const double complex(*r01)[2] = st->top.r_down, (*t10)[2] = st->top.t_up;
    const double complex(*r12)[2] = st->bottom.r_down, (*t12)[2] = st->bottom.t_down;
    const double complex *od = st->opl_down, *ou = st->opl_up;

    /* Look-ups: p1[a] (a = (x, y), down x then up y) is reflection's order-1 path and
     * transmission's round trip (up y, down x); h0 the order-0 pair of transmission; pair[a][b]
     * the order-1 pairs of reflection, (2,3) and (1,3) sharing the values of (0,1) and (0,2). */
    double complex opl1[4];
    phase_term p1[4], h0, pair[4][4];
    for (int a = 0; a < 4; a++) {
        opl1[a] = od[a >> 1] + ou[a & 1];
        phase_at(sp, opl1[a], &p1[a]);
    }
    phase_at(sp, od[1] - conj(od[0]), &h0);
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++) {
            double complex d = opl1[b] - conj(opl1[a]);
            if ((a == 2 && b == 3) || (a == 1 && b == 3)) {
                pair[a][b] = a == 2 ? pair[0][1] : pair[0][2];
                if (!pair[a][b].zero)
                    for (int j = 0; j < 3; j++)
                        pair[a][b].att[j] = cimag(d) != 0.0 ? exp(-sp->k_centroid[j] * cimag(d)) : 1.0;
            } else {
                phase_at(sp, d, &pair[a][b]);
            }
        }
    int any_p1 = !p1[0].zero || !p1[1].zero || !p1[2].zero || !p1[3].zero;
    /* Transmission's order-1 pairs whose entry legs differ (biref_entry_pairs). */
    phase_term ep[4][4];
    if (pairs)
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                phase_at(sp, (od[1] + od[b >> 1] + ou[b & 1]) - conj(od[0] + od[a >> 1] + ou[a & 1]), &ep[a][b]);

    double ed[2][3], eu[2][3];
    for (int k = 0; k < 2; k++) biref_leg_energy(sp, od[k], ed[k]), biref_leg_energy(sp, ou[k], eu[k]);

    /* Transmission (analytic.c's transmission()). */
    {
        double w0[2][2][3], W[2][2][3];
        for (int i = 0; i < 2; i++)
            for (int x = 0; x < 2; x++)
                for (int j = 0; j < 3; j++) w0[i][x][j] = biref_abs2(t01[i][x]) * ed[x][j];
        biref_path_energies((const double(*)[2][3])w0, 2, r12, eu, r10, ed, W);
        for (int o = 0; o < 2; o++) {
            double complex desc[2][2][2], last[2][4];
            if (any_p1)
                for (int x = 0; x < 2; x++)
                    for (int y = 0; y < 2; y++)
                        for (int x2 = 0; x2 < 2; x2++)
                            desc[x][y][x2] = conj(t12[x][o]) * r12[x][y] * r10[y][x2] * t12[x2][o];
            if (pairs)
                for (int x = 0; x < 2; x++)
                    for (int a = 0; a < 4; a++) last[x][a] = r12[x][a & 1] * r10[a & 1][a >> 1] * t12[a >> 1][o];
            for (int i = 0; i < 2; i++) {
                double h[3] = {0.0, 0.0, 0.0};
                if (!h0.zero) add_1(h, conj(t01[i][0] * t12[0][o]) * t01[i][1] * t12[1][o], &h0);
                if (any_p1)
                    for (int x = 0; x < 2; x++)
                        for (int y = 0; y < 2; y++)
                            for (int x2 = 0; x2 < 2; x2++) {
                                const phase_term *p = &p1[(x2 << 1) | y]; /* down x2 + up y */
                                if (!p->zero) add_w(h, W[i][x], desc[x][y][x2], p);
                            }
                if (pairs) add_pairs(h, (const double(*)[3])W[i], (const double complex(*)[4])last,
                                     conj(t01[i][0]) * t01[i][1], (const phase_term(*)[4])pair,
                                     (const phase_term(*)[4])ep);
                for (int j = 0; j < 3; j++) {
                    double e = W[i][0][j] * biref_abs2(t12[0][o]) + W[i][1][j] * biref_abs2(t12[1][o]);
                    E[BIREF_TRANSMISSION][i][o][j] = e;
                    X[BIREF_TRANSMISSION][i][o][j] = e + 2.0 * h[j]; /* eqs. 25-26 */
                }
            }
        }
    }

    /* Reflection (analytic.c's reflection()). */
    {
        double u0[2][2][3], U[2][2][3];
        for (int i = 0; i < 2; i++)
            for (int y = 0; y < 2; y++)
                for (int j = 0; j < 3; j++)
                    u0[i][y][j] =
                        (biref_abs2(t01[i][0]) * ed[0][j] * biref_abs2(r12[0][y]) + biref_abs2(t01[i][1]) * ed[1][j] * biref_abs2(r12[1][y])) *
                        eu[y][j];
        biref_path_energies((const double(*)[2][3])u0, 2, r10, ed, r12, eu, U);
        for (int o = 0; o < 2; o++) {
            double complex desc[2][4];
            if (any_p1)
                for (int y = 0; y < 2; y++)
                    for (int a = 0; a < 4; a++)
                        desc[y][a] = conj(t10[y][o]) * r10[y][a >> 1] * r12[a >> 1][a & 1] * t10[a & 1][o];
            for (int i = 0; i < 2; i++) {
                double h[3] = {0.0, 0.0, 0.0};
                double complex a1[4]; /* order-1 amplitudes without their phase */
                for (int a = 0; a < 4; a++) a1[a] = t01[i][a >> 1] * r12[a >> 1][a & 1] * t10[a & 1][o];
                for (int a = 0; a < 4; a++) {
                    if (!p1[a].zero) add_1(h, conj(r01[i][o]) * a1[a], &p1[a]);
                    for (int b = a + 1; b < 4; b++)
                        if (!pair[a][b].zero) add_1(h, conj(a1[a]) * a1[b], &pair[a][b]);
                }
                if (any_p1)
                    for (int y = 0; y < 2; y++)
                        for (int a = 0; a < 4; a++)
                            if (!p1[a].zero) add_w(h, U[i][y], desc[y][a], &p1[a]);
                for (int j = 0; j < 3; j++) {
                    double e = biref_abs2(r01[i][o]) + U[i][0][j] * biref_abs2(t10[0][o]) + U[i][1][j] * biref_abs2(t10[1][o]);
                    E[BIREF_REFLECTION][i][o][j] = e;
                    X[BIREF_REFLECTION][i][o][j] = e + 2.0 * h[j];
                }
            }
        }
    }
}

void biref_analytic_mixed(const biref_spectral *sp, const biref_slab_state *st, int which, int pairs, const double w_in[2],
                          const double out_mask[2], double xyz[3])
{
    double E[2][2][2][3], X[2][2][2][3];
    if (biref_coherent_plan(sp, st)) {
        /* Thin slab or evanescent coupling: the exact integral, as analytic.c does. */
        double H[2][2][3];
        biref_analytic_terms(sp, st, which, pairs, E[which], H);
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++)
                for (int j = 0; j < 3; j++) X[which][i][o][j] = E[which][i][o][j] + 2.0 * H[i][o][j];
    } else {
        paper_both(sp, st, pairs, E, X);
        biref_physical_limit(E, X);
    }
    biref_spectrum_mix(X[which], w_in, out_mask, xyz);
}
