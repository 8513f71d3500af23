/* Slab Jones matrices (paper §4, eq. 17 and its reflection analogue): isotropic limit = Airy,
 * energy conservation on random slabs, the wave-plate limit, the degenerate axis, agreement
 * of the path expansion with the closed form, and the appendix-B phase correction. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>

#include "biref/biref.h"
#include "test_cases.h"
#include "textbook.h"

static void random_slab(test_rng *r, biref_slab *s, double *theta, double *lambda)
{
    double A[3];
    test_random_axis(r, A);
    s->eta_o = test_uniform(r, 1.3, 2.0);
    s->eta_e = s->eta_o + test_uniform(r, -0.3, 0.3);
    for (int i = 0; i < 3; i++) s->axis[i] = A[i];
    s->thickness_nm = exp(test_uniform(r, log(500.0), log(2e6)));
    s->eta_i = test_uniform(r, 0, 1) < 0.5 ? 1.0 : 1.33;
    *theta = test_uniform(r, 0, 89) * M_PI / 180;
    *lambda = test_uniform(r, 380, 700);
}

/* Isotropic limit: eta_o = eta_e reproduces Airy for s and p, complex amplitudes,
 * for several axes (the o/e basis inside must not matter). */
static void isotropic_slab_equals_airy_formula(void)
{
    double axes[3][3] = {{0.3, 0.5, 0.8}, {1, 0, 0}, {0, 1, 0}};
    for (int a = 0; a < 3; a++)
        for (int t = 0; t < 40; t++) {
            biref_slab s = {1.52, 1.52, {axes[a][0], axes[a][1], axes[a][2]}, 200.0 + 5000.0 * t,
                            t % 2 ? 1.33 : 1.0};
            double theta = (2.1 * t) * M_PI / 180, lambda = 400 + 7.0 * t;
            biref_jones T, R;
            CHECK(biref_slab_jones(&s, theta, lambda, &T, &R) == BIREF_OK);
            for (int p = 0; p < 2; p++) {
                double complex ta, ra;
                tb_airy(p, s.eta_i, 1.52, s.thickness_nm, theta, lambda, &ta, &ra);
                CHECK(cabs(T.m[p][p] - ta) < 1e-10);
                CHECK(cabs(R.m[p][p] - ra) < 1e-10);
                CHECK(cabs(T.m[p][1 - p]) < 1e-10 && cabs(R.m[p][1 - p]) < 1e-10);
            }
        }
}

/* Frustrated total reflection: ambient denser than the (isotropic) slab, thin slab. */
static void frustrated_total_reflection_equals_airy_formula(void)
{
    biref_slab s = {1.2, 1.2, {0.2, 0.9, 0.1}, 150.0, 1.5};
    double theta = 60 * M_PI / 180;
    biref_jones T, R;
    CHECK(biref_slab_jones(&s, theta, 500, &T, &R) == BIREF_OK);
    for (int p = 0; p < 2; p++) {
        double complex ta, ra;
        tb_airy(p, 1.5, 1.2, 150.0, theta, 500, &ta, &ra);
        CHECK(cabs(T.m[p][p] - ta) < 1e-10);
        CHECK(cabs(R.m[p][p] - ra) < 1e-10);
    }
}

/* Energy: for every input polarisation sum T + sum R = 1 on random lossless slabs. */
static void lossless_random_slabs_have_t_plus_r_equal_to_one(void)
{
    test_rng rng = {0x1234567ULL};
    for (int t = 0; t < 2000; t++) {
        biref_slab s;
        double theta, lambda;
        random_slab(&rng, &s, &theta, &lambda);
        biref_jones T, R;
        CHECK(biref_slab_jones(&s, theta, lambda, &T, &R) == BIREF_OK);
        double PT[2][2], PR[2][2];
        biref_jones_intensity(&T, PT);
        biref_jones_intensity(&R, PR);
        for (int i = 0; i < 2; i++) CHECK_NEAR(PT[i][0] + PT[i][1] + PR[i][0] + PR[i][1], 1.0, 1e-9);
    }
}

/* Wave plate: normal incidence, axis in the surface plane. The eigenpolarisations are
 * along and across the axis and each is an Airy slab of index eta_e / eta_o. */
static void normal_incidence_is_a_wave_plate_with_airy_eigenmodes(void)
{
    for (int t = 0; t < 20; t++) {
        double phi = 0.3 + 0.13 * t, ne = 1.553, no = 1.544;
        biref_slab s = {no, ne, {cos(phi), 0, sin(phi)}, 20000.0 + 1000.0 * t, 1.0};
        double lambda = 420 + 13.0 * t;
        biref_jones T;
        CHECK(biref_slab_jones(&s, 0.0, lambda, &T, NULL) == BIREF_OK);
        /* s = x, p = z at normal incidence; axis direction (cos phi, sin phi) in (s, p). */
        double ve[2] = {cos(phi), sin(phi)}, vo[2] = {-sin(phi), cos(phi)};
        double complex ae = ve[0] * T.m[0][0] + ve[1] * T.m[1][0], be = ve[0] * T.m[0][1] + ve[1] * T.m[1][1];
        double complex ao = vo[0] * T.m[0][0] + vo[1] * T.m[1][0], bo = vo[0] * T.m[0][1] + vo[1] * T.m[1][1];
        double complex ee = ae * ve[0] + be * ve[1], cross_e = ae * vo[0] + be * vo[1];
        double complex oo = ao * vo[0] + bo * vo[1], cross_o = ao * ve[0] + bo * ve[1];
        CHECK(cabs(cross_e) < 1e-10 && cabs(cross_o) < 1e-10);
        double complex te, to, r;
        tb_airy(0, 1.0, ne, s.thickness_nm, 0, lambda, &te, &r);
        tb_airy(0, 1.0, no, s.thickness_nm, 0, lambda, &to, &r);
        CHECK(cabs(ee - te) < 1e-10 && cabs(oo - to) < 1e-10);
    }
}

/* Index-matched surround: retardance = 2 pi d (n_e - n_o) / lambda without ripple. */
static void index_matched_surround_gives_the_retardance_phase(void)
{
    double ne = 1.5005, no = 1.5, phi = 0.6;
    biref_slab s = {no, ne, {cos(phi), 0, sin(phi)}, 1e6, 1.50025};
    double lambda = 550;
    biref_jones T;
    CHECK(biref_slab_jones(&s, 0.0, lambda, &T, NULL) == BIREF_OK);
    double ve[2] = {cos(phi), sin(phi)}, vo[2] = {-sin(phi), cos(phi)};
    double complex ee = 0, oo = 0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) ee += ve[i] * T.m[i][j] * ve[j], oo += vo[i] * T.m[i][j] * vo[j];
    double ret = carg(ee / oo), expect = remainder(2 * M_PI * s.thickness_nm * (ne - no) / lambda, 2 * M_PI);
    CHECK_NEAR(remainder(ret - expect, 2 * M_PI), 0.0, 1e-6);
}

/* Axis along the normal at normal incidence: degenerate modes, isotropic with eta_o. */
static void axis_along_the_normal_equals_isotropic_airy_formula(void)
{
    biref_slab s = {1.6, 1.7, {0, 1, 0}, 3000, 1.0};
    biref_jones T, R;
    CHECK(biref_slab_jones(&s, 0.0, 600, &T, &R) == BIREF_OK);
    for (int p = 0; p < 2; p++) {
        double complex ta, ra;
        tb_airy(p, 1.0, 1.6, 3000, 0, 600, &ta, &ra);
        CHECK(cabs(T.m[p][p] - ta) < 1e-10 && cabs(R.m[p][p] - ra) < 1e-10);
    }
}

/* Path expansion: the sum over paths of order <= n converges to the closed form, and the
 * extracted appendix B (subtracting the primary's path once per round trip) does not. */
static void path_sum_to_order_8_equals_closed_form(void)
{
    test_rng rng = {0xabcdefULL};
    int worse = 0, cases = 0;
    for (int t = 0; t < 30; t++) {
        biref_slab s;
        double theta, lambda;
        random_slab(&rng, &s, &theta, &lambda);
        /* Indices 1.6-2.0 and theta <= 40 deg: high orders matter (round-trip amplitude
         * up to ~0.15) yet the tail beyond order 8 stays below ~1e-8. */
        s.eta_o = 1.6 + (s.eta_o - 1.3) * 0.5;
        s.eta_e = s.eta_o + (s.eta_e - s.eta_o) * 0.5;
        theta *= 40.0 / 89.0;
        biref_slab_state st;
        CHECK(biref_slab_prepare(&s, theta, &st) == BIREF_OK);
        biref_jones T, R;
        biref_slab_jones_at(&st, lambda, &T, &R);
        for (int which = 0; which < 2; which++) {
            size_t n = biref_path_count(which, 8);
            biref_path *paths = malloc(n * sizeof *paths);
            CHECK(biref_slab_paths(&st, which, 8, paths, n) == n);
            CHECK(biref_slab_paths(&st, which, 8, paths, n - 1) == 0);
            double complex sum[2][2] = {{0}}, bad[2][2] = {{0}};
            double k = 2 * M_PI / lambda;
            for (size_t p = 0; p < n; p++) {
                double complex ph = cexp(I * k * paths[p].opl_nm);
                /* Appendix B as extracted: each round trip subtracts 2 P_o (the primary path). */
                int trips = paths[p].order;
                double complex phb = cexp(I * k * (paths[p].opl_nm - 2.0 * trips * st.opl_down[0]));
                for (int i = 0; i < 2; i++)
                    for (int j = 0; j < 2; j++) sum[i][j] += paths[p].amp[i][j] * ph, bad[i][j] += paths[p].amp[i][j] * phb;
            }
            const biref_jones *J = which ? &R : &T;
            double err = 0, errb = 0;
            for (int i = 0; i < 2; i++)
                for (int j = 0; j < 2; j++) err = fmax(err, cabs(sum[i][j] - J->m[i][j])), errb = fmax(errb, cabs(bad[i][j] - J->m[i][j]));
            CHECK(err < 2e-8);
            cases++;
            worse += errb > 1e-3;
            free(paths);
        }
    }
    CHECK(worse > cases / 2);
}

/* Flipping a prepared state (light from the other face) equals preparing the slab with
 * the axis rotated by 180 degrees about z, complex amplitudes included. */
static void flipping_a_prepared_state(void)
{
    test_rng rng = {0xf11bULL};
    double worst = 0;
    for (int t = 0; t < 300; t++) {
        biref_slab s;
        double theta, lambda;
        random_slab(&rng, &s, &theta, &lambda);
        biref_slab_state a, b, f;
        CHECK(biref_slab_prepare(&s, theta, &a) == BIREF_OK);
        biref_slab rot = s;
        rot.axis[0] = -s.axis[0];
        rot.axis[1] = -s.axis[1];
        CHECK(biref_slab_prepare(&rot, theta, &b) == BIREF_OK);
        biref_slab_state_flip(&a, &f);
        biref_jones Tb, Rb, Tf, Rf;
        biref_slab_jones_at(&b, lambda, &Tb, &Rb);
        biref_slab_jones_at(&f, lambda, &Tf, &Rf);
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++)
                worst = fmax(worst, fmax(cabs(Tb.m[i][o] - Tf.m[i][o]), cabs(Rb.m[i][o] - Rf.m[i][o])));
        for (int m = 0; m < 4; m++) CHECK(cabs(f.modes.q[m] - b.modes.q[m]) < 1e-12);
    }
    CHECK(worst < 1e-12);
}

/* Path counts: 2^(2n+1) transmitted and 2^(2n) reflected paths of order n. */
static void path_counts_per_order_and_too_high_order_refused(void)
{
    CHECK(biref_path_count(BIREF_TRANSMISSION, 0) == 2);
    CHECK(biref_path_count(BIREF_TRANSMISSION, 2) == 2 + 8 + 32);
    CHECK(biref_path_count(BIREF_REFLECTION, 2) == 1 + 4 + 16);
    CHECK(biref_path_count(BIREF_REFLECTION, 13) == 0);
}

/* A huge or tiny (but non-zero) finite axis means the same direction: no overflow. */
static void axis_length_does_not_change_the_result(void)
{
    biref_slab a = {1.5, 1.6, {1, 0, 1}, 5000, 1.0}, b = a, c = a;
    b.axis[0] = b.axis[2] = 1e300;
    c.axis[0] = c.axis[2] = 1e-6;
    biref_jones Ta, Tb, Tc;
    CHECK(biref_slab_jones(&a, 0.5, 550, &Ta, NULL) == BIREF_OK);
    CHECK(biref_slab_jones(&b, 0.5, 550, &Tb, NULL) == BIREF_OK);
    CHECK(biref_slab_jones(&c, 0.5, 550, &Tc, NULL) == BIREF_OK);
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) CHECK(cabs(Ta.m[i][o] - Tb.m[i][o]) < 1e-14 && cabs(Ta.m[i][o] - Tc.m[i][o]) < 1e-14);
    double u[3], zero[3] = {0, 0, 1e-13};
    CHECK(biref_axis_normalize(b.axis, u) == BIREF_OK && fabs(u[0] - M_SQRT1_2) < 1e-15 && u[1] == 0.0);
    CHECK(biref_axis_normalize(zero, u) == BIREF_ERR_INVALID);
}

/* Bad input. */
static void invalid_slab_angle_or_wavelength_is_refused(void)
{
    biref_slab good = {1.5, 1.6, {0, 0, 1}, 1000, 1.0};
    biref_jones T;
    CHECK(biref_slab_jones(&good, 0.1, 500, &T, NULL) == BIREF_OK);
    biref_slab b = good;
    b.eta_o = NAN;
    CHECK(biref_slab_jones(&b, 0.1, 500, &T, NULL) == BIREF_ERR_INVALID);
    b = good;
    b.eta_e = 0;
    CHECK(biref_slab_jones(&b, 0.1, 500, &T, NULL) == BIREF_ERR_INVALID);
    b = good;
    b.eta_i = INFINITY;
    CHECK(biref_slab_jones(&b, 0.1, 500, &T, NULL) == BIREF_ERR_INVALID);
    b = good;
    b.axis[2] = 0;
    CHECK(biref_slab_jones(&b, 0.1, 500, &T, NULL) == BIREF_ERR_INVALID);
    b = good;
    b.thickness_nm = -1;
    CHECK(biref_slab_jones(&b, 0.1, 500, &T, NULL) == BIREF_ERR_INVALID);
    CHECK(biref_slab_jones(&good, M_PI / 2, 500, &T, NULL) == BIREF_ERR_INVALID);
    CHECK(biref_slab_jones(&good, -0.01, 500, &T, NULL) == BIREF_ERR_INVALID);
    CHECK(biref_slab_jones(&good, 0.1, 0, &T, NULL) == BIREF_ERR_INVALID);
    CHECK(biref_slab_jones(&good, 0.1, NAN, &T, NULL) == BIREF_ERR_INVALID);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"isotropic_slab_equals_airy_formula", isotropic_slab_equals_airy_formula},
        {"frustrated_total_reflection_equals_airy_formula", frustrated_total_reflection_equals_airy_formula},
        {"lossless_random_slabs_have_t_plus_r_equal_to_one", lossless_random_slabs_have_t_plus_r_equal_to_one},
        {"normal_incidence_is_a_wave_plate_with_airy_eigenmodes",
         normal_incidence_is_a_wave_plate_with_airy_eigenmodes},
        {"index_matched_surround_gives_the_retardance_phase", index_matched_surround_gives_the_retardance_phase},
        {"axis_along_the_normal_equals_isotropic_airy_formula", axis_along_the_normal_equals_isotropic_airy_formula},
        {"path_sum_to_order_8_equals_closed_form", path_sum_to_order_8_equals_closed_form},
        {"flipping_a_prepared_state", flipping_a_prepared_state},
        {"path_counts_per_order_and_too_high_order_refused", path_counts_per_order_and_too_high_order_refused},
        {"axis_length_does_not_change_the_result", axis_length_does_not_change_the_result},
        {"invalid_slab_angle_or_wavelength_is_refused", invalid_slab_angle_or_wavelength_is_refused},
    };
    return test_run_cases("test_slab", cases, TEST_COUNT(cases), argc, argv);
}
