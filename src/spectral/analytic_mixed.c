/* The analytic method (analytic.c, eqs. 19-26, m = 1) for one side under the paper's s/p light,
 * with the light and filter weights folded into the sums before the band integrals.
 *
 * The renderer needs X = sum_{i,o} w_i m_o (E[i][o] + 2 H[i][o]) (biref_spectrum_mix), not the
 * four pairs. Every term of E and H is linear in the pair's coefficient, and every term of H
 * that shares an optical path difference shares its table look-up, so the weighted sum over
 * (i, o) can be taken on the complex coefficients first: one S(Re(c e^{ikD})) per distinct path
 * difference instead of one per pair, and one (I - Dbar)^-1 row per band instead of one per
 * input. Look-ups beyond the table's far limit are exactly 0 (docs/PHYSICS.md §4): their
 * coefficients are not computed at all. Same mathematics as analytic.c, summed in another
 * order: tests/test_analytic_mixed.c checks the two against each other on random slabs,
 * total reflection included. */
#include <complex.h>
#include <math.h>

#include "spectral/spectral_internal.h"

typedef struct {
    double c[3], s[3]; /* S(cos kD), S(sin kD) per band */
    double att[3];     /* e^{-k_j Im D} */
    int zero;          /* beyond the far limit: the integrals are 0 */
} phase_term;

static inline double abs2(double complex z) { return creal(z) * creal(z) + cimag(z) * cimag(z); }

static void phase_at(const biref_spectral *sp, double complex opd, phase_term *p)
{
    double re = creal(opd);
    p->zero = fabs(re) > sp->d_far;
    if (p->zero) return;
    biref_spectral_phase_integrals(sp, re, p->c, p->s);
    double im = cimag(opd);
    for (int j = 0; j < 3; j++) p->att[j] = im != 0.0 ? exp(-sp->k_centroid[j] * im) : 1.0;
}

/* out_j += weight_j * S(Re(coef e^{ikD})); weight NULL means 1. */
static inline void add_term(double out[3], const double *weight, double complex coef, const phase_term *p)
{
    double a = creal(coef), b = cimag(coef);
    for (int j = 0; j < 3; j++) out[j] += (weight ? weight[j] : 1.0) * p->att[j] * (a * p->c[j] - b * p->s[j]);
}

static inline void leg_energy(const biref_spectral *sp, double complex opl, double e[3])
{
    double im = cimag(opl);
    for (int j = 0; j < 3; j++) e[j] = im != 0.0 ? exp(-2.0 * sp->k_centroid[j] * im) : 1.0;
}

/* out[m][j] = (w0 (I - Dbar_j)^{-1})[m] with Dbar as in analytic.c's path_energies. */
static void mixed_path_energies(const double w0[2][3], const double complex (*Rin)[2], const double e_mid[2][3],
                                const double complex (*Rout)[2], const double e_end[2][3], double out[2][3])
{
    double ai[2][2], ao[2][2];
    for (int m = 0; m < 2; m++)
        for (int n = 0; n < 2; n++) ai[m][n] = abs2(Rin[m][n]), ao[m][n] = abs2(Rout[m][n]);
    for (int j = 0; j < 3; j++) {
        double D[2][2];
        for (int m = 0; m < 2; m++)
            for (int m2 = 0; m2 < 2; m2++)
                D[m][m2] = (ai[m][0] * e_mid[0][j] * ao[0][m2] + ai[m][1] * e_mid[1][j] * ao[1][m2]) * e_end[m2][j];
        double a = 1.0 - D[0][0], b = -D[0][1], c = -D[1][0], d = 1.0 - D[1][1];
        double det = a * d - b * c;
        out[0][j] = (w0[0][j] * d - w0[1][j] * c) / det;
        out[1][j] = (-w0[0][j] * b + w0[1][j] * a) / det;
    }
}

static void transmission(const biref_spectral *sp, const biref_slab_state *st, const double w[2], const double m[2],
                         double X[3])
{
    const double complex(*t01)[2] = st->top.t_down, (*r10)[2] = st->top.r_up;
    const double complex(*r12)[2] = st->bottom.r_down, (*t12)[2] = st->bottom.t_down;
    const double complex *od = st->opl_down, *ou = st->opl_up;

    phase_term h0, trip[2][2];
    phase_at(sp, od[1] - conj(od[0]), &h0);
    for (int y = 0; y < 2; y++)
        for (int x2 = 0; x2 < 2; x2++) phase_at(sp, ou[y] + od[x2], &trip[y][x2]);

    double ed[2][3], eu[2][3], w0[2][3], Wx[2][3];
    for (int k = 0; k < 2; k++) leg_energy(sp, od[k], ed[k]), leg_energy(sp, ou[k], eu[k]);
    for (int x = 0; x < 2; x++) {
        double a = w[0] * abs2(t01[0][x]) + w[1] * abs2(t01[1][x]);
        for (int j = 0; j < 3; j++) w0[x][j] = a * ed[x][j];
    }
    /* Wx[x] = sum_i w_i W[i][x]: the light's energy arriving at the bottom in mode x. */
    mixed_path_energies(w0, r12, eu, r10, ed, Wx);

    double h[3] = {0.0, 0.0, 0.0};
    for (int x = 0; x < 2; x++) {
        double tx = m[0] * abs2(t12[x][0]) + m[1] * abs2(t12[x][1]);
        for (int j = 0; j < 3; j++) X[j] += Wx[x][j] * tx;
    }
    if (!h0.zero) {
        double complex c = 0.0;
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++) c += w[i] * m[o] * conj(t01[i][0] * t12[0][o]) * t01[i][1] * t12[1][o];
        add_term(h, NULL, c, &h0);
    }
    for (int y = 0; y < 2; y++)
        for (int x2 = 0; x2 < 2; x2++) {
            if (trip[y][x2].zero) continue;
            double complex tail = m[0] * r10[y][x2] * t12[x2][0], tail1 = m[1] * r10[y][x2] * t12[x2][1];
            for (int x = 0; x < 2; x++) {
                /* sum_o m_o desc_o (eq. 23, m = 1), weighted by the energy in mode x. */
                double complex c = (conj(t12[x][0]) * tail + conj(t12[x][1]) * tail1) * r12[x][y];
                add_term(h, Wx[x], c, &trip[y][x2]);
            }
        }
    for (int j = 0; j < 3; j++) X[j] += 2.0 * h[j]; /* eqs. 25-26 */
}

static void reflection(const biref_spectral *sp, const biref_slab_state *st, const double w[2], const double m[2],
                       double X[3])
{
    const double complex(*r01)[2] = st->top.r_down, (*t01)[2] = st->top.t_down;
    const double complex(*r10)[2] = st->top.r_up, (*t10)[2] = st->top.t_up;
    const double complex(*r12)[2] = st->bottom.r_down;
    const double complex *od = st->opl_down, *ou = st->opl_up;

    double complex opl1[4];
    phase_term p1[4], pair[4][4];
    for (int a = 0; a < 4; a++) {
        opl1[a] = od[a >> 1] + ou[a & 1];
        phase_at(sp, opl1[a], &p1[a]);
    }
    /* As in analytic.c: pairs (2,3) and (1,3) share the table values of (0,1) and (0,2). */
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

    double ed[2][3], eu[2][3], u0[2][3], Uy[2][3];
    for (int k = 0; k < 2; k++) leg_energy(sp, od[k], ed[k]), leg_energy(sp, ou[k], eu[k]);
    double win[2]; /* the light's energy entering in mode x */
    for (int x = 0; x < 2; x++) win[x] = w[0] * abs2(t01[0][x]) + w[1] * abs2(t01[1][x]);
    for (int y = 0; y < 2; y++)
        for (int j = 0; j < 3; j++)
            u0[y][j] = (win[0] * ed[0][j] * abs2(r12[0][y]) + win[1] * ed[1][j] * abs2(r12[1][y])) * eu[y][j];
    /* Uy[y] = sum_i w_i U[i][y]: the light's energy arriving at the top (inside) in up mode y. */
    mixed_path_energies(u0, r10, ed, r12, eu, Uy);

    for (int i = 0; i < 2; i++) {
        double e = w[i] * (m[0] * abs2(r01[i][0]) + m[1] * abs2(r01[i][1]));
        for (int j = 0; j < 3; j++) X[j] += e;
    }
    for (int y = 0; y < 2; y++) {
        double ty = m[0] * abs2(t10[y][0]) + m[1] * abs2(t10[y][1]);
        for (int j = 0; j < 3; j++) X[j] += Uy[y][j] * ty;
    }

    int any_p1 = !p1[0].zero || !p1[1].zero || !p1[2].zero || !p1[3].zero;
    int any_pair = 0;
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++) any_pair |= !pair[a][b].zero;
    double h[3] = {0.0, 0.0, 0.0};
    if (any_p1 || any_pair) {
        /* Order-1 amplitudes without their phase, a1[i][o][a], and the weighted sums over (i, o). */
        double complex a1[2][2][4], c1[4] = {0}, cp[4][4] = {{0}};
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++)
                for (int a = 0; a < 4; a++) a1[i][o][a] = t01[i][a >> 1] * r12[a >> 1][a & 1] * t10[a & 1][o];
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++) {
                double wm = w[i] * m[o];
                if (wm == 0.0) continue;
                for (int a = 0; a < 4; a++) {
                    if (!p1[a].zero) c1[a] += wm * conj(r01[i][o]) * a1[i][o][a];
                    for (int b = a + 1; b < 4; b++)
                        if (!pair[a][b].zero) cp[a][b] += wm * conj(a1[i][o][a]) * a1[i][o][b];
                }
            }
        for (int a = 0; a < 4; a++) {
            if (!p1[a].zero) add_term(h, NULL, c1[a], &p1[a]);
            for (int b = a + 1; b < 4; b++)
                if (!pair[a][b].zero) add_term(h, NULL, cp[a][b], &pair[a][b]);
        }
    }
    if (any_p1)
        for (int y = 0; y < 2; y++)
            for (int a = 0; a < 4; a++) {
                if (p1[a].zero) continue;
                /* sum_o m_o desc_o[y][a] (one more round trip before exiting). */
                double complex c = (m[0] * conj(t10[y][0]) * t10[a & 1][0] + m[1] * conj(t10[y][1]) * t10[a & 1][1]) *
                                   r10[y][a >> 1] * r12[a >> 1][a & 1];
                add_term(h, Uy[y], c, &p1[a]);
            }
    for (int j = 0; j < 3; j++) X[j] += 2.0 * h[j]; /* eqs. 25-26 */
}

void biref_analytic_mixed(const biref_spectral *sp, const biref_slab_state *st, int which, const double w_in[2],
                          const double out_mask[2], double xyz[3])
{
    xyz[0] = xyz[1] = xyz[2] = 0.0;
    if (which == BIREF_REFLECTION)
        reflection(sp, st, w_in, out_mask, xyz);
    else
        transmission(sp, st, w_in, out_mask, xyz);
}
