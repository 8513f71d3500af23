/*
 * biref — independent reference solver for a uniaxial slab: the 4x4 Berreman
 * transfer-matrix method (D. W. Berreman, "Optics in stratified and
 * anisotropic media: 4x4-matrix formulation", JOSA 62, 502 (1972); P. Yeh,
 * "Electromagnetic propagation in birefringent layered media", JOSA 69, 742
 * (1979)).
 *
 * Why a second method: the closed form of the paper (normal modes q_o, q_e,
 * eq. 2; mode fields, eq. 3; Fresnel coefficients, appendix A; sum of all
 * orders, eq. 17) is reconstructed from an OCR'd text and has several known
 * garbles (docs/PAPER-ERRATA.md). This file uses none of
 * it: inside the slab only Maxwell's equations and a numerical
 * eigen-decomposition (LAPACK zgeev) appear, so agreement between the two is
 * evidence for both.
 *
 * Frame and conventions: docs/CONVENTIONS.md. Surface normal is y; the slab
 * fills -d <= y <= 0; fields vary as exp(i k0 (q y - K z) - i w t) with
 * K = eta_i sin(theta).
 *
 * Derivation of the Berreman matrix (our frame; the textbooks use z as the
 * normal, so the signs below are re-derived, not copied).
 *   Non-magnetic, e^{-iwt}:  curl E = i w mu0 H,  curl H = -i w eps0 eps E.
 *   Rescale H~ = (w mu0 / k0) H = mu0 c H, so that for a plane wave H~ = k x E
 *   with k in units of k0 (the convention of CONVENTIONS.md), and
 *       curl E = i k0 H~,   curl H~ = -i k0 eps E.
 *   With d/dx = 0 and d/dz = -i k0 K the six component equations are
 *       (1) dEz/dy + i k0 K Ey = i k0 Hx      (2) Hy = -K Ex
 *       (3) dEx/dy = -i k0 Hz
 *       (4) dHz/dy + i k0 K Hy = -i k0 (eps E)_x
 *       (5) K Hx = (eps E)_y                  (6) dHx/dy = i k0 (eps E)_z
 *   (2) and (5) are algebraic: they give the normal components
 *       Hy = -K Ex,   Ey = (K Hx - e_yx Ex - e_yz Ez) / e_yy,
 *   and substituting them into (1), (3), (4), (6) leaves, for the tangential
 *   vector psi = (Ex, Hz, Ez, Hx) (all continuous across an interface),
 *       d psi / dy = i k0 Delta psi,
 *
 *   Delta = | 0                          -1   0                           0              |
 *           | K^2 - e_xx + e_xy e_yx/e_yy  0  -e_xz + e_xy e_yz/e_yy      -K e_xy/e_yy    |
 *           | K e_yx/e_yy                  0   K e_yz/e_yy                 1 - K^2/e_yy   |
 *           | e_zx - e_zy e_yx/e_yy        0   e_zz - e_zy e_yz/e_yy       K e_zy/e_yy    |
 *
 *   with eps = eps_o I + (eps_e - eps_o) A A^T, eps = eta^2, A the unit axis.
 *   Check (isotropic, eps = n^2 I): the (Ex, Hz) and (Ez, Hx) blocks decouple
 *   and both give lambda^2 = n^2 - K^2 = q^2, as they must.
 *
 * Transfer matrix. In a homogeneous layer psi(y) = V exp(i k0 y Lambda) c,
 * where Delta V = V Lambda (zgeev). Hence
 *       psi(0) = M psi(-d),   M = V diag(exp(i k0 d lambda_j)) V^-1.
 * Nothing needs to know which eigenvalue is "up" or "down": M is invariant
 * under any choice or ordering of eigenvectors (also inside a degenerate
 * eigenspace, e.g. the isotropic case or k parallel to A), which is what makes
 * this method a robust reference. M is applied to vectors as
 * V (diag(..) (V^-1 psi)) with an LU solve instead of forming V^-1.
 *
 * Boundary problem (Yeh 1979, sec. III, written for our bases). Outside, with
 * n = eta_i, c = cos(theta), s = x and p = k^ x s, the tangential vectors
 * (Ex, Hz, Ez, Hx) of unit-amplitude waves are (H = k x E, k = (0, q, -K)):
 *       incident / transmitted s, k = (0,-nc,-K):   (1,  nc, 0,  0)
 *       incident / transmitted p, p = (0,-sin,c):   (0,  0,  c, -n)
 *       reflected s,              k = (0, nc,-K):   (1, -nc, 0,  0)
 *       reflected p,              p = (0,-sin,-c):  (0,  0, -c, -n)
 *   Incident and reflected amplitudes refer to y = 0, transmitted to y = -d:
 *       psi_inc + r_s psi_rs + r_p psi_rp = M (t_s psi_ts + t_p psi_tp),
 *   four equations in (r_s, r_p, t_s, t_p), solved for both inputs at once.
 *   At normal incidence this basis gives r_p = -r_s for an isotropic
 *   interface (the p vector flips with k^), as CONVENTIONS.md states.
 *
 * Trust. The transfer matrix multiplies evanescent components by
 * exp(k0 d |Im lambda|); when propagating and evanescent modes coexist, the
 * rounding of the large part (~ eps_mach * growth) pollutes the O(1) part, so
 * the answer is refused (BIREF_ERR_ILLCOND) once the growth exceeds
 * TMM_MAX_GROWTH. Near a critical angle two eigenvalues merge into a Jordan
 * block and V becomes singular; an ill-conditioned V is refused too.
 *
 * Re-entrant: no global state, no heap allocation (the LAPACKE *_work entry
 * points with column-major storage do not allocate).
 */
#include <complex.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#include <lapacke.h>

#include "biref/optics.h"
#include "biref/stack.h"

enum { TMM_N = 4, TMM_LWORK = 256 };

/* Largest tolerated amplification exp(k0 d max|Im lambda|) of an evanescent
 * component across the slab. The absolute error of the result grows like
 * 1e-16 * growth (see the header comment), so 1e6 keeps it near 1e-10. */
#define TMM_MAX_GROWTH 1e6
/* Smallest tolerated reciprocal condition number (1-norm) of the eigenvector
 * matrix V: errors scale like 1e-16 / rcond. */
#define TMM_MIN_RCOND 1e-8
/* Largest tolerated phase k0 d |lambda|: beyond it the phase of a crossing is
 * not known to better than ~1e-8 rad. */
#define TMM_MAX_PHASE 1e8

/* Largest double below pi/2 (cos of it is still positive). */
static const double tmm_half_pi = 1.5707963267948966;
static const double tmm_two_pi = 6.283185307179586;

static int tmm_finite_positive(double x) { return isfinite(x) && x > 0.0; }

/* Validates the inputs and returns the unit optic axis in a. */
static biref_status tmm_check(const biref_slab *slab, double theta, double lambda_nm, double a[3])
{
    if (!slab) return BIREF_ERR_INVALID;
    if (!tmm_finite_positive(slab->eta_o) || !tmm_finite_positive(slab->eta_e) ||
        !tmm_finite_positive(slab->eta_i) || !tmm_finite_positive(slab->thickness_nm) ||
        !tmm_finite_positive(lambda_nm))
        return BIREF_ERR_INVALID;
    if (!isfinite(theta) || theta < 0.0 || theta >= tmm_half_pi) return BIREF_ERR_INVALID;
    /* Normalise after scaling by the largest component, so that huge or tiny
     * (but finite, non-zero) axes neither overflow nor underflow. */
    double m = 0.0;
    for (int i = 0; i < 3; i++) {
        if (!isfinite(slab->axis[i])) return BIREF_ERR_INVALID;
        if (fabs(slab->axis[i]) > m) m = fabs(slab->axis[i]);
    }
    if (!(m > 0.0)) return BIREF_ERR_INVALID;
    double s2 = 0.0;
    for (int i = 0; i < 3; i++) {
        a[i] = slab->axis[i] / m;
        s2 += a[i] * a[i];
    }
    double inv = 1.0 / sqrt(s2);
    for (int i = 0; i < 3; i++) a[i] *= inv;
    return BIREF_OK;
}

/* Fills the Berreman matrix (column-major, D[r + 4 c]) for psi = (Ex, Hz, Ez, Hx). */
static void tmm_berreman(const double e[3][3], double K, double complex D[TMM_N * TMM_N])
{
    enum { X = 0, Y = 1, Z = 2 };
    const double eyy = e[Y][Y]; /* > 0: eps is positive definite */
    double R[TMM_N][TMM_N] = {
        {0.0, -1.0, 0.0, 0.0},
        {K * K - e[X][X] + e[X][Y] * e[Y][X] / eyy, 0.0, -e[X][Z] + e[X][Y] * e[Y][Z] / eyy, -K * e[X][Y] / eyy},
        {K * e[Y][X] / eyy, 0.0, K * e[Y][Z] / eyy, 1.0 - K * K / eyy},
        {e[Z][X] - e[Z][Y] * e[Y][X] / eyy, 0.0, e[Z][Z] - e[Z][Y] * e[Y][Z] / eyy, K * e[Z][Y] / eyy},
    };
    for (int r = 0; r < TMM_N; r++)
        for (int c = 0; c < TMM_N; c++) D[r + TMM_N * c] = R[r][c];
}

/* Dielectric tensor eps = eps_o I + (eps_e - eps_o) A A^T of a medium with unit axis a. */
static void tmm_tensor(double eta_o, double eta_e, const double a[3], double e[3][3])
{
    const double eo = eta_o * eta_o, de = eta_e * eta_e - eo;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) e[i][j] = (i == j ? eo : 0.0) + de * a[i] * a[j];
}

/* B <- M B for the two columns of B (tangential vectors psi at the layer's bottom face, giving
 * them at its top face), M = V diag(exp(i k0 d w)) V^-1 of one homogeneous layer. *growth
 * accumulates k0 d max|Im w| over the layers crossed (the evanescent amplification). */
static biref_status tmm_layer_apply(const double e[3][3], double K, double k0d, double *growth,
                                    double complex B[TMM_N * 2])
{
    /* Eigen-decomposition Delta V = V diag(w). */
    double complex D[TMM_N * TMM_N], w[TMM_N], V[TMM_N * TMM_N], vl_dummy[1], work[TMM_LWORK];
    double rwork[2 * TMM_N];
    tmm_berreman(e, K, D);
    lapack_int info = LAPACKE_zgeev_work(LAPACK_COL_MAJOR, 'N', 'V', TMM_N, D, TMM_N, w, vl_dummy, 1, V, TMM_N,
                                         work, TMM_LWORK, rwork);
    if (info != 0) return BIREF_ERR_SINGULAR;

    /* Growth and phase limits (computed on exponents: no overflow). */
    double max_im = 0.0, max_abs = 0.0;
    for (int j = 0; j < TMM_N; j++) {
        if (fabs(cimag(w[j])) > max_im) max_im = fabs(cimag(w[j]));
        if (cabs(w[j]) > max_abs) max_abs = cabs(w[j]);
    }
    *growth += k0d * max_im;
    if (*growth > log(TMM_MAX_GROWTH) || k0d * max_abs > TMM_MAX_PHASE) return BIREF_ERR_ILLCOND;

    /* LU of V, and its conditioning (Jordan block near a critical angle). */
    double complex Vlu[TMM_N * TMM_N];
    lapack_int piv[TMM_N];
    double vnorm = 0.0;
    for (int c = 0; c < TMM_N; c++) {
        double col = 0.0;
        for (int r = 0; r < TMM_N; r++) {
            Vlu[r + TMM_N * c] = V[r + TMM_N * c];
            col += cabs(V[r + TMM_N * c]);
        }
        if (col > vnorm) vnorm = col;
    }
    info = LAPACKE_zgetrf_work(LAPACK_COL_MAJOR, TMM_N, TMM_N, Vlu, TMM_N, piv);
    if (info != 0) return BIREF_ERR_SINGULAR;
    double rcond = 0.0;
    info = LAPACKE_zgecon_work(LAPACK_COL_MAJOR, '1', TMM_N, Vlu, TMM_N, vnorm, &rcond, work, rwork);
    if (info != 0) return BIREF_ERR_SINGULAR;
    if (!(rcond >= TMM_MIN_RCOND)) return BIREF_ERR_ILLCOND;

    /* V diag(exp(i k0 d w)) V^-1 B. */
    info = LAPACKE_zgetrs_work(LAPACK_COL_MAJOR, 'N', TMM_N, 2, Vlu, TMM_N, piv, B, TMM_N);
    if (info != 0) return BIREF_ERR_SINGULAR;
    for (int j = 0; j < TMM_N; j++) {
        double complex ph = cexp(I * k0d * w[j]);
        B[j] *= ph;
        B[j + TMM_N] *= ph;
    }
    double complex out[TMM_N * 2];
    for (int p = 0; p < 2; p++)
        for (int r = 0; r < TMM_N; r++) {
            double complex m = 0.0;
            for (int j = 0; j < TMM_N; j++) m += V[r + TMM_N * j] * B[j + TMM_N * p];
            out[r + TMM_N * p] = m;
        }
    memcpy(B, out, sizeof out);
    return BIREF_OK;
}

/* Ambient waves, tangential vectors (Ex, Hz, Ez, Hx); see the header. W holds M psi_t for the
 * transmitted s and p waves (M: the whole structure). */
static biref_status tmm_boundary(double n, double theta, const double complex W[TMM_N * 2], biref_jones *T,
                                 biref_jones *R)
{
    const double cs = cos(theta), qi = n * cs;
    const double psi_in[2][TMM_N] = {{1.0, qi, 0.0, 0.0}, {0.0, 0.0, cs, -n}};  /* incident = transmitted */
    const double psi_rf[2][TMM_N] = {{1.0, -qi, 0.0, 0.0}, {0.0, 0.0, -cs, -n}}; /* reflected */

    /* Boundary system S x = b: columns (psi_rs, psi_rp, -W_s, -W_p), unknowns
     * (r_s, r_p, t_s, t_p), one right-hand side -psi_inc per input. */
    double complex S[TMM_N * TMM_N], X[TMM_N * 2];
    lapack_int piv[TMM_N];
    for (int r = 0; r < TMM_N; r++) {
        S[r] = psi_rf[0][r];
        S[r + TMM_N] = psi_rf[1][r];
        for (int p = 0; p < 2; p++) {
            S[r + TMM_N * (2 + p)] = -W[r + TMM_N * p];
            X[r + TMM_N * p] = -psi_in[p][r];
        }
    }
    lapack_int info = LAPACKE_zgesv_work(LAPACK_COL_MAJOR, TMM_N, 2, S, TMM_N, piv, X, TMM_N);
    if (info != 0) return BIREF_ERR_SINGULAR;
    for (int k = 0; k < TMM_N * 2; k++)
        if (!isfinite(creal(X[k])) || !isfinite(cimag(X[k]))) return BIREF_ERR_ILLCOND;

    /* Column p of X holds (r_s, r_p, t_s, t_p) for input p: Jones [input][output]. */
    for (int p = 0; p < 2; p++) {
        if (R) {
            R->m[p][BIREF_S] = X[0 + TMM_N * p];
            R->m[p][BIREF_P] = X[1 + TMM_N * p];
        }
        if (T) {
            T->m[p][BIREF_S] = X[2 + TMM_N * p];
            T->m[p][BIREF_P] = X[3 + TMM_N * p];
        }
    }
    return BIREF_OK;
}

/* The transmitted s and p waves' tangential vectors at the bottom plane. */
static void tmm_transmitted(double n, double theta, double complex B[TMM_N * 2])
{
    const double cs = cos(theta);
    const double psi[2][TMM_N] = {{1.0, n * cs, 0.0, 0.0}, {0.0, 0.0, cs, -n}};
    for (int p = 0; p < 2; p++)
        for (int r = 0; r < TMM_N; r++) B[r + TMM_N * p] = psi[p][r];
}

biref_status biref_slab_jones_tmm(const biref_slab *slab, double theta_rad, double lambda_nm, biref_jones *T,
                                  biref_jones *R)
{
    double a[3];
    biref_status st = tmm_check(slab, theta_rad, lambda_nm, a);
    if (st != BIREF_OK) return st;
    const double n = slab->eta_i;
    double e[3][3];
    tmm_tensor(slab->eta_o, slab->eta_e, a, e);
    double complex B[TMM_N * 2];
    tmm_transmitted(n, theta_rad, B);
    double growth = 0.0;
    st = tmm_layer_apply(e, n * sin(theta_rad), tmm_two_pi / lambda_nm * slab->thickness_nm, &growth, B);
    if (st != BIREF_OK) return st;
    return tmm_boundary(n, theta_rad, B, T, R);
}

biref_status biref_stack_jones_tmm(const biref_stack *dispersive, double theta_rad, double lambda_nm, biref_jones *T,
                                   biref_jones *R)
{
    biref_stack at;
    if (biref_stack_check(dispersive, NULL, 0) != BIREF_OK || !tmm_finite_positive(lambda_nm) ||
        !isfinite(theta_rad) || theta_rad < 0.0 || theta_rad >= tmm_half_pi ||
        biref_stack_at(dispersive, lambda_nm, &at) != BIREF_OK)
        return BIREF_ERR_INVALID;
    const biref_stack *stack = &at;
    const double n = stack->eta_i, K = n * sin(theta_rad);
    double complex B[TMM_N * 2];
    tmm_transmitted(n, theta_rad, B);
    double growth = 0.0;
    /* psi(0) = M_1 M_2 ... M_N psi(-D): the last layer acts first. */
    for (int j = stack->n_layers - 1; j >= 0; j--) {
        const biref_layer *l = &stack->layers[j];
        double a[3] = {0.0, 1.0, 0.0}, e[3][3];
        if (!l->isotropic) {
            biref_slab probe = {l->eta_o, l->eta_e, {l->axis[0], l->axis[1], l->axis[2]}, l->thickness_nm, n};
            biref_status st = tmm_check(&probe, theta_rad, lambda_nm, a);
            if (st != BIREF_OK) return st;
        }
        tmm_tensor(l->eta_o, l->isotropic ? l->eta_o : l->eta_e, a, e);
        biref_status st = tmm_layer_apply(e, K, tmm_two_pi / lambda_nm * l->thickness_nm, &growth, B);
        if (st != BIREF_OK) return st;
    }
    return tmm_boundary(n, theta_rad, B, T, R);
}
