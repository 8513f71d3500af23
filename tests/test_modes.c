/* Normal modes of a uniaxial medium (paper §3, eqs. 2–6): each mode must solve Maxwell's
 * wave equation, carry energy the way its label says, and the corrected formulas must differ
 * from the extracted ones exactly where the extraction was wrong. */
#include <complex.h>
#include <math.h>

#include "biref/biref.h"
#include "test_cases.h"

/* |(k k^T - (k.k) I + eps) E| for k = (0, q, -K): zero iff E is a mode with normal component q. */
static double wave_equation_residual(double eo, double ee, const double A[3], double K, double complex q,
                                     const double complex E[3])
{
    double complex k[3] = {0.0, q, -K};
    double complex kk = k[0] * k[0] + k[1] * k[1] + k[2] * k[2];
    double complex kE = k[0] * E[0] + k[1] * E[1] + k[2] * E[2];
    double complex AE = A[0] * E[0] + A[1] * E[1] + A[2] * E[2];
    double r = 0.0;
    for (int i = 0; i < 3; i++) {
        double complex v = k[i] * kE - kk * E[i] + eo * E[i] + (ee - eo) * A[i] * AE;
        r += creal(v * conj(v));
    }
    return sqrt(r);
}

/* Eq. 2 exactly as the PDF extraction printed it (beta*gamma*K*de inside the square root). */
static double complex q_e_as_extracted(double eo, double ee, const double A[3], double K, int sign)
{
    double de = ee - eo, al = A[0], be = A[1], ga = A[2];
    double complex inner = csqrt(ee * (be * be * de + eo) + K * K * (al * al * de - ee) + be * ga * K * de);
    return sign * sqrt(eo) * inner / (eo + be * be * de);
}

static void random_axis(test_rng *r, double A[3])
{
    test_random_axis(r, A);
    double n = sqrt(A[0] * A[0] + A[1] * A[1] + A[2] * A[2]);
    for (int i = 0; i < 3; i++) A[i] /= n;
}

/* One stream of draws for all cases, in table order. */
static test_rng rng = {0x5eed1234abcdULL};

static void modes_solve_the_wave_equation(void)
{
    int caught_eq2 = 0, generic = 0;
    for (int t = 0; t < 2000; t++) {
        double A[3];
        random_axis(&rng, A);
        double no = test_uniform(&rng, 1.2, 2.2), ne = no + test_uniform(&rng, -0.3, 0.3);
        double K = test_uniform(&rng, 0.0, 2.4);
        biref_medium med = biref_medium_uniaxial(no, ne, A);
        biref_modes m;
        CHECK(biref_medium_modes(&med, K, &m) == BIREF_OK);
        double eo = no * no, ee = ne * ne;
        for (int i = 0; i < 4; i++) {
            double scale = eo + K * K;
            CHECK(wave_equation_residual(eo, ee, A, K, m.q[i], m.E[i]) < 1e-12 * scale);
            /* Unit Hermitian norm. */
            double n2 = 0;
            for (int j = 0; j < 3; j++) n2 += creal(m.E[i][j] * conj(m.E[i][j]));
            CHECK_NEAR(n2, 1.0, 1e-12);
        }
        /* Ordinary field is perpendicular to the axis (eq. 3). */
        for (int i = 0; i < 4; i += 2) {
            double complex AE = A[0] * m.E[i][0] + A[1] * m.E[i][1] + A[2] * m.E[i][2];
            CHECK(cabs(AE) < 1e-12);
        }
        /* Labels follow energy flow (propagating) or decay (evanescent). */
        if (K < m.K_max_o) {
            CHECK(!m.evanescent_o);
            CHECK(m.poynting[BIREF_MODE_O_DOWN][1] < 0 && m.poynting[BIREF_MODE_O_UP][1] > 0);
        } else {
            CHECK(cimag(m.q[BIREF_MODE_O_DOWN]) < 0 && cimag(m.q[BIREF_MODE_O_UP]) > 0);
        }
        if (K < m.K_max_e) {
            CHECK(!m.evanescent_e);
            CHECK(m.poynting[BIREF_MODE_E_DOWN][1] < 0 && m.poynting[BIREF_MODE_E_UP][1] > 0);
            /* Effective index (eq. 5) lies between eta_o and eta_e. */
            CHECK(m.eta_eff[BIREF_MODE_E_DOWN] >= fmin(no, ne) - 1e-12);
            CHECK(m.eta_eff[BIREF_MODE_E_DOWN] <= fmax(no, ne) + 1e-12);
        } else {
            CHECK(m.evanescent_e);
            CHECK(cimag(m.q[BIREF_MODE_E_DOWN]) < 0 && cimag(m.q[BIREF_MODE_E_UP]) > 0);
        }
        /* The extracted eq. 2 fails the wave equation whenever beta*gamma*K*de is not tiny. */
        if (fabs(A[1] * A[2] * K * (ee - eo)) > 1e-2 && K < m.K_max_e) {
            generic++;
            double complex qx = q_e_as_extracted(eo, ee, A, K, -1);
            double complex tmp[3];
            /* Best case for the extracted formula: E_e built with its own q via eq. 3. */
            double complex ak = A[1] * qx - A[2] * K;
            tmp[0] = eo * A[0];
            tmp[1] = eo * A[1] - ak * qx;
            tmp[2] = eo * A[2] + ak * K;
            double nrm = sqrt(creal(tmp[0] * conj(tmp[0]) + tmp[1] * conj(tmp[1]) + tmp[2] * conj(tmp[2])));
            for (int j = 0; j < 3; j++) tmp[j] /= nrm;
            if (wave_equation_residual(eo, ee, A, K, qx, tmp) > 1e-4) caught_eq2++;
        }
    }
    CHECK(generic > 100);
    CHECK(caught_eq2 == generic);
}

/* K_max (eq. 6). Axis along x: an e wave in the YZ plane always sees eta_e, so K_max_e = eta_e;
 * the extracted eq. 6 (gamma^2 in place of alpha^2) gives eta_o here. */
static void k_max_of_axis_in_the_surface_is_eta_e(void)
{
    double A[3] = {1, 0, 0};
    biref_medium med = biref_medium_uniaxial(1.5, 1.7, A);
    biref_modes m;
    CHECK(biref_medium_modes(&med, 0.3, &m) == BIREF_OK);
    CHECK_NEAR(m.K_max_e, 1.7, 1e-12);
    double extracted = 1.7 * sqrt((1.5 * 1.5 + 0.0) / (1.7 * 1.7 - 0.0));
    CHECK(fabs(extracted - m.K_max_e) > 0.1);
    CHECK_NEAR(m.eta_eff[BIREF_MODE_E_DOWN], 1.7, 1e-12);
}

/* Random axes: evanescence switches exactly at K_max_e. */
static void e_mode_turns_evanescent_at_k_max_for_random_axes(void)
{
    for (int t = 0; t < 200; t++) {
        double A[3];
        random_axis(&rng, A);
        double no = test_uniform(&rng, 1.2, 2.0), ne = no + test_uniform(&rng, -0.3, 0.3);
        biref_medium med = biref_medium_uniaxial(no, ne, A);
        biref_modes lo, hi, probe;
        CHECK(biref_medium_modes(&med, 0.0, &probe) == BIREF_OK);
        double km = probe.K_max_e;
        CHECK(biref_medium_modes(&med, km * (1 - 1e-9), &lo) == BIREF_OK);
        CHECK(biref_medium_modes(&med, km * (1 + 1e-9), &hi) == BIREF_OK);
        CHECK(!lo.evanescent_e && hi.evanescent_e);
    }
}

/* Degenerate direction: axis along the normal at normal incidence. Both modes are
 * ordinary-like with index eta_o and the fields stay finite and orthogonal. */
static void ray_along_the_axis_gives_orthogonal_modes_of_index_eta_o(void)
{
    double A[3] = {0, 1, 0};
    biref_medium med = biref_medium_uniaxial(1.5, 1.6, A);
    biref_modes m;
    CHECK(biref_medium_modes(&med, 0.0, &m) == BIREF_OK);
    for (int i = 0; i < 4; i++) {
        CHECK_NEAR(cabs(m.q[i]), 1.5, 1e-12);
        CHECK(wave_equation_residual(1.5 * 1.5, 1.6 * 1.6, A, 0.0, m.q[i], m.E[i]) < 1e-12);
    }
    double complex dot = conj(m.E[0][0]) * m.E[1][0] + conj(m.E[0][1]) * m.E[1][1] + conj(m.E[0][2]) * m.E[1][2];
    CHECK(cabs(dot) < 1e-12);
}

/* Invalid media are rejected. */
static void invalid_media_are_rejected(void)
{
    double A0[3] = {0, 0, 0}, A1[3] = {0, 1, 0};
    biref_medium bad = biref_medium_uniaxial(1.5, 1.6, A0);
    biref_modes m;
    CHECK(biref_medium_modes(&bad, 0.1, &m) == BIREF_ERR_INVALID);
    bad = biref_medium_uniaxial(NAN, 1.6, A1);
    CHECK(biref_medium_modes(&bad, 0.1, &m) == BIREF_ERR_INVALID);
    bad = biref_medium_uniaxial(1.5, -1.6, A1);
    CHECK(biref_medium_modes(&bad, 0.1, &m) == BIREF_ERR_INVALID);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"modes_solve_the_wave_equation", modes_solve_the_wave_equation},
        {"k_max_of_axis_in_the_surface_is_eta_e", k_max_of_axis_in_the_surface_is_eta_e},
        {"e_mode_turns_evanescent_at_k_max_for_random_axes", e_mode_turns_evanescent_at_k_max_for_random_axes},
        {"ray_along_the_axis_gives_orthogonal_modes_of_index_eta_o",
         ray_along_the_axis_gives_orthogonal_modes_of_index_eta_o},
        {"invalid_media_are_rejected", invalid_media_are_rejected},
    };
    return test_run_cases("test_modes", cases, TEST_COUNT(cases), argc, argv);
}
