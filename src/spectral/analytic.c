/* The paper's analytic approximation of the spectral integral (§5, eqs. 19–26, m = 1), for
 * all four input/output polarisation pairs, in transmission and in reflection.
 *
 * S(|J|^2) = E + 2H (eq. 19). E, the incoherent sum of all path energies, is summed in closed
 * form as a geometric series of the component-wise |.|^2 of the round-trip operator (eqs.
 * 20–21; the right-hand vector of eq. 21 is the exit coefficients, READING-NOTES 3). H keeps
 * only the pairs (path, path + one more round trip) ("descendants", eqs. 22–23 with m = 1)
 * plus the interference of the lowest-order paths among themselves (H0, eq. 24). Complex
 * coefficients (total reflection) need S(sin(k D)) next to S(cos(k D)):
 * S(Re(c e^{ikD})) = Re(c) S(cos kD) - Im(c) S(sin kD).
 *
 * Reflection is derived the same way (the paper's supplement is not available): the lowest
 * orders are the direct reflection and the four order-1 paths (down x, up y), whose ten
 * mutual pairs form H0_R; descendants add one round trip (down x', up y') before exiting. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "spectral/spectral_internal.h"

typedef struct {
    double c[3], s[3]; /* S(cos kD), S(sin kD) per band */
    double att[3];     /* e^{-k_j Im D}: decay of evanescent legs at the band's centroid */
} phase_int;

static void phase_eval(const biref_spectral *sp, double complex opd, phase_int *p)
{
    biref_spectral_phase_integrals(sp, creal(opd), p->c, p->s);
    double im = cimag(opd);
    for (int j = 0; j < 3; j++) p->att[j] = im != 0.0 ? exp(-sp->k_centroid[j] * im) : 1.0;
}

/* out_j += weight * S(Re(coef e^{ikD}), Λ_j). */
static inline void add_re_integral(double out[3], double weight, double complex coef, const phase_int *p)
{
    double a = creal(coef), b = cimag(coef);
    for (int j = 0; j < 3; j++) out[j] += weight * p->att[j] * (a * p->c[j] - b * p->s[j]);
}

static inline double abs2(double complex z) { return creal(z) * creal(z) + cimag(z) * cimag(z); }

/* |e^{ik opl}|^2 at the band's centroid: 1 for propagating legs. */
static inline double leg_energy(const biref_spectral *sp, double complex opl, int band)
{
    double im = cimag(opl);
    return im != 0.0 ? exp(-2.0 * sp->k_centroid[band] * im) : 1.0;
}

/* w (1x2) (I - M)^{-1}. */
static void row_times_inv_one_minus(const double w[2], const double M[2][2], double out[2])
{
    double a = 1.0 - M[0][0], b = -M[0][1], c = -M[1][0], d = 1.0 - M[1][1];
    double det = a * d - b * c;
    out[0] = (w[0] * d - w[1] * c) / det;
    out[1] = (-w[0] * b + w[1] * a) / det;
}

static void transmission(const biref_spectral *sp, const biref_slab_state *st, double out[2][2][3])
{
    const double complex(*t01)[2] = st->top.t_down, (*r10)[2] = st->top.r_up;
    const double complex(*r12)[2] = st->bottom.r_down, (*t12)[2] = st->bottom.t_down;
    const double complex *od = st->opl_down, *ou = st->opl_up;

    /* Distinct optical path differences: the order-0 pair (eq. 24) and the four round trips
     * (bottom reflection into y, up, top reflection into x', down): five table look-ups. */
    phase_int h0, trip[2][2];
    phase_eval(sp, od[1] - conj(od[0]), &h0);
    for (int y = 0; y < 2; y++)
        for (int x2 = 0; x2 < 2; x2++) phase_eval(sp, ou[y] + od[x2], &trip[y][x2]);

    for (int j = 0; j < 3; j++) {
        /* Energy of a round trip from the bottom in mode x back to the bottom in mode x' (eq. 20). */
        double Dbar[2][2];
        for (int x = 0; x < 2; x++)
            for (int x2 = 0; x2 < 2; x2++) {
                double e = 0.0;
                for (int y = 0; y < 2; y++)
                    e += abs2(r12[x][y]) * leg_energy(sp, ou[y], j) * abs2(r10[y][x2]) * leg_energy(sp, od[x2], j);
                Dbar[x][x2] = e;
            }
        for (int i = 0; i < 2; i++) {
            /* W[x]: energy of all paths arriving at the bottom in mode x (eq. 21's left part). */
            double w0[2] = {abs2(t01[i][0]) * leg_energy(sp, od[0], j), abs2(t01[i][1]) * leg_energy(sp, od[1], j)};
            double W[2];
            row_times_inv_one_minus(w0, Dbar, W);
            for (int o = 0; o < 2; o++) {
                double E = W[0] * abs2(t12[0][o]) + W[1] * abs2(t12[1][o]); /* eq. 21 */
                double H[3] = {0, 0, 0};
                /* H0 (eq. 24): the ordinary and extraordinary order-0 paths. */
                add_re_integral(H, 1.0, conj(t01[i][0] * t12[0][o]) * t01[i][1] * t12[1][o], &h0);
                /* Descendants (eq. 23, m = 1). */
                for (int x = 0; x < 2; x++)
                    for (int y = 0; y < 2; y++)
                        for (int x2 = 0; x2 < 2; x2++)
                            add_re_integral(H, W[x], conj(t12[x][o]) * r12[x][y] * r10[y][x2] * t12[x2][o], &trip[y][x2]);
                out[i][o][j] = E + 2.0 * H[j];
            }
        }
    }
}

static void reflection(const biref_spectral *sp, const biref_slab_state *st, double out[2][2][3])
{
    const double complex(*r01)[2] = st->top.r_down, (*t01)[2] = st->top.t_down;
    const double complex(*r10)[2] = st->top.r_up, (*t10)[2] = st->top.t_up;
    const double complex(*r12)[2] = st->bottom.r_down;
    const double complex *od = st->opl_down, *ou = st->opl_up;

    /* Order-1 paths (down x, up y): optical paths and pairwise differences; the same four
     * sums serve as the extra round trip (down x', up y') of the descendants. */
    double complex opl1[4];
    phase_int p1[4], pair[4][4];
    for (int a = 0; a < 4; a++) {
        opl1[a] = od[a >> 1] + ou[a & 1];
        phase_eval(sp, opl1[a], &p1[a]);
    }
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++) phase_eval(sp, opl1[b] - conj(opl1[a]), &pair[a][b]);

    for (int j = 0; j < 3; j++) {
        /* Round trip from the top (inside, up mode y) back to the top in mode y'. */
        double Dbar[2][2];
        for (int y = 0; y < 2; y++)
            for (int y2 = 0; y2 < 2; y2++) {
                double e = 0.0;
                for (int x = 0; x < 2; x++)
                    e += abs2(r10[y][x]) * leg_energy(sp, od[x], j) * abs2(r12[x][y2]) * leg_energy(sp, ou[y2], j);
                Dbar[y][y2] = e;
            }
        for (int i = 0; i < 2; i++) {
            double u0[2] = {0, 0};
            for (int y = 0; y < 2; y++)
                for (int x = 0; x < 2; x++)
                    u0[y] += abs2(t01[i][x]) * leg_energy(sp, od[x], j) * abs2(r12[x][y]) * leg_energy(sp, ou[y], j);
            double U[2];
            row_times_inv_one_minus(u0, Dbar, U);
            for (int o = 0; o < 2; o++) {
                double E = abs2(r01[i][o]) + U[0] * abs2(t10[0][o]) + U[1] * abs2(t10[1][o]);
                double complex a1[4]; /* amplitudes of the order-1 paths without phase */
                for (int a = 0; a < 4; a++) a1[a] = t01[i][a >> 1] * r12[a >> 1][a & 1] * t10[a & 1][o];
                double H[3] = {0, 0, 0};
                for (int a = 0; a < 4; a++) {
                    add_re_integral(H, 1.0, conj(r01[i][o]) * a1[a], &p1[a]);
                    for (int b = a + 1; b < 4; b++) add_re_integral(H, 1.0, conj(a1[a]) * a1[b], &pair[a][b]);
                }
                for (int y = 0; y < 2; y++)
                    for (int a = 0; a < 4; a++) {
                        int x2 = a >> 1, y2 = a & 1;
                        add_re_integral(H, U[y], conj(t10[y][o]) * r10[y][x2] * r12[x2][y2] * t10[y2][o], &p1[a]);
                    }
                out[i][o][j] = E + 2.0 * H[j];
            }
        }
    }
}

void biref_spectrum_analytic(const biref_spectral *sp, const biref_slab_state *st, biref_spectrum *out)
{
    transmission(sp, st, out->T);
    reflection(sp, st, out->R);
}
