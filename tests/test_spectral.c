/* Spectral integration (paper §5): look-up table vs direct quadrature, band normalisation,
 * convergence of numeric integration, the energy term E (eq. 21) vs brute-force path sums,
 * and the analytic approximation vs ground truth on thin slabs. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>

#include "biref/biref.h"
#include "spectral/spectral_internal.h"
#include "test_cases.h"

static int quick;
static biref_spectral *sp;

/* A seeded random slab (ambient index 1, 0-60 deg), prepared: thickness log-uniform in
 * [dmin, dmax], |eta_e - eta_o| <= dn. */
static void random_state(test_rng *r, double dmin, double dmax, double dn, biref_slab_state *st)
{
    biref_slab s;
    test_random_axis(r, s.axis);
    s.eta_o = test_uniform(r, 1.3, 1.8);
    s.eta_e = s.eta_o + test_uniform(r, -dn, dn);
    s.thickness_nm = exp(test_uniform(r, log(dmin), log(dmax)));
    s.eta_i = 1.0;
    const double theta = test_uniform(r, 0, 60) * M_PI / 180;
    CHECK(biref_slab_prepare(&s, theta, st) == BIREF_OK);
}

static double max_abs_diff3(const double a[3], const double b[3])
{
    return fmax(fabs(a[0] - b[0]), fmax(fabs(a[1] - b[1]), fabs(a[2] - b[2])));
}


/* Table vs direct quadrature over the table's range and past it (asymptotic tail). */
static void phase_table_matches_direct_quadrature(void)
{
    double worst = 0, worst_tail = 0;
    /* Quick: every sixth point, so that the tail (k >= 100) is still checked. */
    for (int k = 0; k < 120; k += quick ? 6 : 1) {
        double D = k < 100 ? 37.3 + 1003.7 * k : 1.0e5 + 4.1e3 * (k - 100) * (k - 99);
        double c[3], s[3], cd[3], sd[3];
        biref_spectral_phase_integrals(sp, D, c, s);
        biref_spectral_phase_integrals_direct(sp, D, cd, sd);
        double e = fmax(max_abs_diff3(c, cd), max_abs_diff3(s, sd));
        if (D <= 1e5)
            worst = fmax(worst, e);
        else
            worst_tail = fmax(worst_tail, e);
        /* Symmetry: cos even, sin odd. */
        double cm[3], sm[3];
        biref_spectral_phase_integrals(sp, -D, cm, sm);
        for (int j = 0; j < 3; j++) CHECK(cm[j] == c[j] && sm[j] == -s[j]);
    }
    CHECK(worst < 2e-5);
    CHECK(worst_tail < 2e-5);
    double c[3], s[3];
    biref_spectral_phase_integrals(sp, 0.0, c, s);
    for (int j = 0; j < 3; j++) {
        CHECK_NEAR(c[j], 1.0, 1e-9);
        CHECK_NEAR(s[j], 0.0, 1e-12);
    }
}

/* Band normalisation: an index-matched, non-birefringent slab transmits everything at
 * every wavelength; every method must give exactly (1, 1, 1) for s->s and p->p. */
static void every_method_is_band_normalised(void)
{
    biref_slab s = {1.5, 1.5, {0, 1, 0}, 1e5, 1.5};
    biref_slab_state st;
    CHECK(biref_slab_prepare(&s, 0.4, &st) == BIREF_OK);
    int ns[4] = {1, 3, 8, 1000};
    for (int k = 0; k < 4; k++) {
        biref_numeric_plan *plan = NULL;
        CHECK(biref_numeric_plan_create(sp, ns[k], &plan, NULL, 0) == BIREF_OK);
        biref_spectrum out;
        biref_spectrum_numeric(plan, &st, &out);
        for (int j = 0; j < 3; j++) {
            /* With one sample a band may lack weight entirely (then 0 by design). */
            if (ns[k] >= 3) {
                CHECK_NEAR(out.T[0][0][j], 1.0, 1e-12);
                CHECK_NEAR(out.T[1][1][j], 1.0, 1e-12);
            }
            CHECK_NEAR(out.R[0][0][j], 0.0, 1e-12);
        }
        biref_numeric_plan_destroy(plan);
    }
    biref_spectrum a;
    biref_spectrum_analytic(sp, &st, &a);
    for (int j = 0; j < 3; j++) {
        CHECK_NEAR(a.T[0][0][j], 1.0, 1e-9);
        CHECK_NEAR(a.T[1][1][j], 1.0, 1e-9);
    }
}

/* Numeric integration converges to the ground truth as N grows (thin slabs). */
static void numeric_integration_converges_to_ground_truth(void)
{
    biref_numeric_plan *gt = NULL, *p[4] = {NULL};
    int ns[4] = {32, 128, 512, 2048};
    CHECK(biref_numeric_plan_create(sp, BIREF_GROUND_TRUTH_SAMPLES, &gt, NULL, 0) == BIREF_OK);
    for (int k = 0; k < 4; k++) CHECK(biref_numeric_plan_create(sp, ns[k], &p[k], NULL, 0) == BIREF_OK);
    test_rng rng = {77};
    double err[4] = {0};
    for (int t = 0; t < (quick ? 5 : 30); t++) {
        biref_slab_state st;
        random_state(&rng, 1000, 20000, 0.1, &st);
        biref_spectrum g, n;
        biref_spectrum_numeric(gt, &st, &g);
        for (int k = 0; k < 4; k++) {
            biref_spectrum_numeric(p[k], &st, &n);
            for (int i = 0; i < 2; i++)
                for (int o = 0; o < 2; o++) err[k] = fmax(err[k], max_abs_diff3(n.T[i][o], g.T[i][o]));
        }
    }
    CHECK(err[1] < err[0] && err[2] < err[1] && err[3] < err[2]);
    CHECK(err[3] < 1e-5);
    biref_numeric_plan_destroy(gt);
    for (int k = 0; k < 4; k++) biref_numeric_plan_destroy(p[k]);
}

/* The energy term (eq. 21) is the incoherent sum of all path energies. The extracted
 * eq. 21, with reflection coefficients r_os, r_es in the right-hand vector instead of the
 * exit coefficients, would differ. */
static void energy_term_is_the_incoherent_path_sum(void)
{
    test_rng rng = {99};
    for (int t = 0; t < 20; t++) {
        biref_slab_state st;
        random_state(&rng, 1000, 1e6, 0.3, &st);
        for (int which = 0; which < 2; which++) {
            double E[2][2][3], H[2][2][3];
            biref_analytic_paper_terms(sp, &st, which, E, H);
            size_t n = biref_path_count(which, 8);
            biref_path *paths = malloc(n * sizeof *paths);
            CHECK(biref_slab_paths(&st, which, 8, paths, n) == n);
            double brute[2][2] = {{0}};
            for (size_t k = 0; k < n; k++)
                for (int i = 0; i < 2; i++)
                    for (int o = 0; o < 2; o++) {
                        double complex a = paths[k].amp[i][o];
                        brute[i][o] += creal(a * conj(a));
                    }
            for (int i = 0; i < 2; i++)
                for (int o = 0; o < 2; o++) CHECK_NEAR(E[i][o][0], brute[i][o], 1e-7);
            free(paths);
            if (which == BIREF_TRANSMISSION) {
                /* Extracted eq. 21 for order 0: sum_x |t_x|^2 |r_x,out|^2 (bottom reflections). */
                double wrong = 0;
                for (int x = 0; x < 2; x++)
                    wrong += creal(st.top.t_down[0][x] * conj(st.top.t_down[0][x])) *
                             creal(st.bottom.r_down[x][0] * conj(st.bottom.r_down[x][0]));
                CHECK(fabs(wrong - E[0][0][0]) > 0.1);
            }
        }
    }
}

/* Analytic approximation vs ground truth on thin slabs at moderate angles (colours that
 * the 16384-sample ground truth resolves without aliasing). */
static void analytic_approximation_matches_ground_truth_on_thin_slabs(void)
{
    biref_numeric_plan *gt = NULL;
    CHECK(biref_numeric_plan_create(sp, BIREF_GROUND_TRUTH_SAMPLES, &gt, NULL, 0) == BIREF_OK);
    test_rng rng = {2024};
    double sum = 0, worst = 0, sum_r = 0, worst_r = 0;
    int n = quick ? 10 : 150;
    for (int t = 0; t < n; t++) {
        biref_slab_state st;
        random_state(&rng, 2000, 50000, 0.05, &st);
        biref_spectrum a, g;
        biref_spectrum_analytic(sp, &st, &a);
        biref_spectrum_numeric(gt, &st, &g);
        double w[2] = {0.5, 0.5}, crossed[2] = {0, 1}, xa[3], xg[3];
        /* Crossed polarisers (s in, p out) amplify the birefringence colours. */
        double s_in[2] = {1, 0};
        biref_spectrum_mix(a.T, s_in, crossed, xa);
        biref_spectrum_mix(g.T, s_in, crossed, xg);
        double de = biref_delta_e00_xyz(xa, xg);
        double none[2] = {1, 1};
        biref_spectrum_mix(a.R, w, none, xa);
        biref_spectrum_mix(g.R, w, none, xg);
        double der = biref_delta_e00_xyz(xa, xg);
        sum += de, worst = fmax(worst, de), sum_r += der, worst_r = fmax(worst_r, der);
    }
    printf("analytic vs ground truth, thin slabs: T crossed mean %.3f max %.3f; R mean %.3f max %.3f\n", sum / n,
           worst, sum_r / n, worst_r);
    /* Measured (seed 2024, 150 slabs): T crossed mean 0.004, max 0.043; R mean 0.011, max 0.12.
     * Eq. 26 alone (no siblings) gave 0.129 and 1.89 (R 0.016, 0.29), and before the energy balance
     * 0.24 and 2.39: the bound holds the siblings' gain. */
    CHECK(sum / n < 0.02 && worst < 0.2);
    CHECK(sum_r / n < 0.05 && worst_r < 0.3);
    biref_numeric_plan_destroy(gt);
}

/* Bad input. */
static void bad_input_is_refused(void)
{
    biref_numeric_plan *p = NULL;
    CHECK(biref_numeric_plan_create(sp, 0, &p, NULL, 0) == BIREF_ERR_INVALID && p == NULL);
    CHECK(biref_numeric_plan_create(sp, -5, &p, NULL, 0) == BIREF_ERR_INVALID);
    biref_spectral_config cfg;
    biref_spectral_config_default(&cfg);
    cfg.lambda_min_nm = 700, cfg.lambda_max_nm = 380;
    biref_spectral *bad = NULL;
    CHECK(biref_spectral_create(&cfg, &bad, NULL, 0) == BIREF_ERR_INVALID && bad == NULL);
    biref_spectral_config_default(&cfg);
    cfg.lambda_max_nm = NAN;
    CHECK(biref_spectral_create(&cfg, &bad, NULL, 0) == BIREF_ERR_INVALID);
    biref_spectral_config_default(&cfg);
    cfg.cmf = (biref_cmf_kind)7;
    CHECK(biref_spectral_create(&cfg, &bad, NULL, 0) == BIREF_ERR_INVALID);
    biref_method m;
    CHECK(biref_method_from_name("magic", &m) == BIREF_ERR_INVALID);
    CHECK(biref_method_from_name("ground-truth", &m) == BIREF_OK && m == BIREF_METHOD_GROUND_TRUTH);
}

int main(int argc, char **argv)
{
    quick = test_quick();
    if (biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK) return 1;
    static const test_case cases[] = {
        {"phase_table_matches_direct_quadrature", phase_table_matches_direct_quadrature},
        {"every_method_is_band_normalised", every_method_is_band_normalised},
        {"numeric_integration_converges_to_ground_truth", numeric_integration_converges_to_ground_truth},
        {"energy_term_is_the_incoherent_path_sum", energy_term_is_the_incoherent_path_sum},
        {"analytic_approximation_matches_ground_truth_on_thin_slabs", analytic_approximation_matches_ground_truth_on_thin_slabs},
        {"bad_input_is_refused", bad_input_is_refused},
    };
    int rc = test_run_cases("test_spectral", cases, TEST_COUNT(cases), argc, argv);
    biref_spectral_destroy(sp);
    return rc;
}
