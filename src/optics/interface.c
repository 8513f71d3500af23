/* Fresnel coefficients of a plane interface between two homogeneous media (paper appendix A).
 *
 * Instead of the extracted closed forms (which carry OCR damage, see docs/PHYSICS.md) we solve
 * the boundary conditions directly: the tangential components E_x, E_z, H_x, H_z are continuous
 * across y = 0. For one incident mode this is a 4x4 linear system in the two reflected and the
 * two transmitted amplitudes; the same matrix serves incidence from above and from below, and
 * the same code covers isotropic/anisotropic media on either side. */
#include <complex.h>
#include <math.h>

#include "biref/optics.h"
#include "optics/modes_internal.h"

/* Tangential field vector (E_x, E_z, H_x, H_z) of mode idx. */
static void tangential(const biref_modes *m, int idx, double complex f[4])
{
    f[0] = m->E[idx][0];
    f[1] = m->E[idx][2];
    f[2] = m->H[idx][0];
    f[3] = m->H[idx][2];
}

/* |re| + |im|: a pivot magnitude without the square root of cabs (within a factor sqrt 2). */
static inline double l1(double complex z) { return fabs(creal(z)) + fabs(cimag(z)); }

/* 1 / z without the overflow-guarded library division (pivots here are O(1) field values). */
static inline double complex recip(double complex z)
{
    double a = creal(z), b = cimag(z), n = 1.0 / (a * a + b * b);
    return a * n - I * (b * n);
}

/* Solves A X = B in place for 4 right-hand sides by Gaussian elimination with partial
 * pivoting (a fixed 4x4 system on the per-sample hot path: no allocation, no library call). */
static biref_status solve4(double complex A[4][4], double complex B[4][4])
{
    double scale = 0.0;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double v = l1(A[i][j]);
            scale = v > scale ? v : scale; /* fmax without the libm call: entries are finite */
        }
    double complex inv_diag[4];
    for (int c = 0; c < 4; c++) {
        int p = c;
        double best = l1(A[c][c]);
        for (int r = c + 1; r < 4; r++)
            if (l1(A[r][c]) > best) best = l1(A[r][c]), p = r;
        if (!(best > 1e-13 * scale)) return BIREF_ERR_SINGULAR;
        if (p != c)
            for (int j = 0; j < 4; j++) {
                double complex t = A[c][j];
                A[c][j] = A[p][j];
                A[p][j] = t;
                t = B[c][j];
                B[c][j] = B[p][j];
                B[p][j] = t;
            }
        double complex inv = recip(A[c][c]);
        inv_diag[c] = inv;
        for (int r = c + 1; r < 4; r++) {
            double complex f = A[r][c] * inv;
            if (f == 0.0) continue;
            for (int j = c; j < 4; j++) A[r][j] -= f * A[c][j];
            for (int j = 0; j < 4; j++) B[r][j] -= f * B[c][j];
        }
    }
    for (int c = 3; c >= 0; c--)
        for (int j = 0; j < 4; j++) {
            double complex s = B[c][j];
            for (int k = c + 1; k < 4; k++) s -= A[c][k] * B[k][j];
            B[c][j] = s * inv_diag[c];
        }
    return BIREF_OK;
}

/* solve4 in real arithmetic, for real systems. The same pivots, the same reciprocal formula and
 * the same order of operations: a complex product or difference whose imaginary parts are all 0
 * is exactly the real one, so the result equals solve4's bit for bit at a quarter of the work. */
static biref_status solve4_real(double A[4][4], double B[4][4])
{
    double scale = 0.0;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double v = fabs(A[i][j]);
            scale = v > scale ? v : scale;
        }
    double inv_diag[4];
    for (int c = 0; c < 4; c++) {
        int p = c;
        double best = fabs(A[c][c]);
        for (int r = c + 1; r < 4; r++)
            if (fabs(A[r][c]) > best) best = fabs(A[r][c]), p = r;
        if (!(best > 1e-13 * scale)) return BIREF_ERR_SINGULAR;
        if (p != c)
            for (int j = 0; j < 4; j++) {
                double t = A[c][j];
                A[c][j] = A[p][j];
                A[p][j] = t;
                t = B[c][j];
                B[c][j] = B[p][j];
                B[p][j] = t;
            }
        double a = A[c][c], inv = a * (1.0 / (a * a)); /* recip() of a real number */
        inv_diag[c] = inv;
        for (int r = c + 1; r < 4; r++) {
            double f = A[r][c] * inv;
            if (f == 0.0) continue;
            for (int j = c; j < 4; j++) A[r][j] -= f * A[c][j];
            for (int j = 0; j < 4; j++) B[r][j] -= f * B[c][j];
        }
    }
    for (int c = 3; c >= 0; c--)
        for (int j = 0; j < 4; j++) {
            double t = B[c][j];
            for (int k = c + 1; k < 4; k++) t -= A[c][k] * B[k][j];
            B[c][j] = t * inv_diag[c];
        }
    return BIREF_OK;
}

/* Imaginary parts all exactly 0? */
static int all_real(const double complex *v, int n)
{
    int real = 1;
    for (int i = 0; i < n; i++) real &= cimag(v[i]) == 0.0;
    return real;
}

biref_status biref_interface_from_modes(const biref_modes *up, const biref_modes *lo, biref_interface *out)
{
    return biref_interface_from_modes_as(up, lo, 1, out);
}

biref_status biref_interface_from_modes_as(const biref_modes *up, const biref_modes *lo, int allow_real,
                                           biref_interface *out)
{
    /* Unknowns x = (a0, a1, b0, b1): a = amplitudes of the upper medium's up-going modes,
     * b = the lower medium's down-going modes. Continuity: sum a F_up + incident_above =
     * sum b F_lo_down + incident_below, i.e. [F_up | -F_lo_down] x = rhs. */
    double complex A[4][4], B[4][4], f[4];
    for (int j = 0; j < 2; j++) {
        tangential(up, BIREF_MODE_O_UP + j, f);
        for (int r = 0; r < 4; r++) A[r][j] = f[r];
        tangential(lo, BIREF_MODE_O_DOWN + j, f);
        for (int r = 0; r < 4; r++) A[r][2 + j] = -f[r];
    }
    for (int i = 0; i < 2; i++) {
        tangential(up, BIREF_MODE_O_DOWN + i, f); /* incident from above */
        for (int r = 0; r < 4; r++) B[r][i] = -f[r];
        tangential(lo, BIREF_MODE_O_UP + i, f); /* incident from below */
        for (int r = 0; r < 4; r++) B[r][2 + i] = f[r];
    }
    /* No evanescent mode on either side (the common case of a slab in air): the mode fields are
     * real (eqs. 2-3 with real q), and so is the system. */
    if (allow_real && all_real(&A[0][0], 16) && all_real(&B[0][0], 16)) {
        double Ar[4][4], Br[4][4];
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++) Ar[r][c] = creal(A[r][c]), Br[r][c] = creal(B[r][c]);
        biref_status s = solve4_real(Ar, Br);
        if (s != BIREF_OK) return s;
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++) B[r][c] = Br[r][c];
    } else {
        biref_status s = solve4(A, B);
        if (s != BIREF_OK) return s;
    }
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            out->r_down[i][j] = B[j][i];
            out->t_down[i][j] = B[2 + j][i];
            out->t_up[i][j] = B[j][2 + i];
            out->r_up[i][j] = B[2 + j][2 + i];
        }
    return BIREF_OK;
}

biref_status biref_interface_solve(const biref_medium *upper, const biref_medium *lower, double K,
                                   biref_interface *out)
{
    biref_modes mu, ml;
    biref_status s = biref_medium_modes(upper, K, &mu); /* validates the medium and K */
    if (s == BIREF_OK) s = biref_medium_modes(lower, K, &ml);
    if (s != BIREF_OK) return s;
    return biref_interface_from_modes(&mu, &ml, out);
}
