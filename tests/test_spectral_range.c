/* The spectral context integrates only where the colour-matching data is defined, and a result
 * that is not finite comes back as an error status, never as numbers. */
#include <complex.h>
#include <math.h>
#include <stdio.h>

#include "biref/biref.h"
#include "test_cases.h"

static biref_spectral_config config(biref_cmf_kind cmf, double lo, double hi)
{
    biref_spectral_config cfg;
    biref_spectral_config_default(&cfg);
    cfg.cmf = cmf;
    cfg.lambda_min_nm = lo;
    cfg.lambda_max_nm = hi;
    return cfg;
}

/* The status of creating a context for [lo, hi]; a context comes back exactly when it is OK. */
static biref_status create(biref_cmf_kind cmf, double lo, double hi)
{
    const biref_spectral_config cfg = config(cmf, lo, hi);
    biref_spectral *sp = NULL;
    biref_status s = biref_spectral_create(&cfg, &sp, NULL, 0);
    CHECK((s == BIREF_OK) == (sp != NULL));
    biref_spectral_destroy(sp);
    return s;
}

static void cmf_domains_are_reported(void)
{
    double lo, hi;
    CHECK(biref_cmf_domain(BIREF_CMF_CIE1931, &lo, &hi) == BIREF_OK && lo == 380 && hi == 780);
    CHECK(biref_cmf_domain(BIREF_CMF_WYMAN2013, &lo, &hi) == BIREF_OK && lo == 360 && hi == 830);
    CHECK(biref_cmf_domain((biref_cmf_kind)7, &lo, &hi) == BIREF_ERR_INVALID);
    CHECK(biref_cmf_domain(BIREF_CMF_CIE1931, NULL, &hi) == BIREF_ERR_INVALID);
}

/* Ranges that used to build a nonsense table (a band far wider than the look-up table's step
 * allows: +-1e15, +-169), overflow an int sample count, or give zeros. */
static void empty_reversed_or_out_of_domain_ranges_refused(void)
{
    const double bad[][2] = {{380, 1e9}, {1, 100000}, {10, 830}, {1e-300, 1e300}, {379.9, 700}, {380, 780.1},
                             {800, 900}, {0, 700}, {700, 380}, {500, 500}, {NAN, 700}, {380, INFINITY}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        CHECK(create(BIREF_CMF_CIE1931, bad[k][0], bad[k][1]) == BIREF_ERR_INVALID);
        CHECK(create(BIREF_CMF_WYMAN2013, bad[k][0] == 379.9 ? 359.9 : bad[k][0],
                     bad[k][1] == 780.1 ? 830.1 : bad[k][1]) == BIREF_ERR_INVALID);
    }
}

static void ranges_inside_the_cmf_domain_are_accepted(void)
{
    CHECK(create(BIREF_CMF_CIE1931, 380, 780) == BIREF_OK);
    CHECK(create(BIREF_CMF_CIE1931, 380, 700) == BIREF_OK);
    CHECK(create(BIREF_CMF_CIE1931, 550, 550.5) == BIREF_OK);
    CHECK(create(BIREF_CMF_WYMAN2013, 360, 830) == BIREF_OK);
}

/* The widest band allowed still integrates a slab physically and close to ground truth. */
static void widest_range_stays_close_to_ground_truth(void)
{
    const biref_spectral_config cfg = config(BIREF_CMF_WYMAN2013, 360, 830);
    biref_spectral *sp = NULL;
    biref_numeric_plan *gt = NULL;
    CHECK(biref_spectral_create(&cfg, &sp, NULL, 0) == BIREF_OK);
    CHECK(biref_numeric_plan_create(sp, BIREF_GROUND_TRUTH_SAMPLES, &gt, NULL, 0) == BIREF_OK);
    biref_slab slab = {1.55, 1.56, {0.3, 0.9, 0.1}, 20000, 1.0};
    biref_slab_state st;
    CHECK(biref_slab_prepare(&slab, 0.4, &st) == BIREF_OK);
    biref_spectrum a, g;
    biref_spectrum_analytic(sp, &st, &a);
    biref_spectrum_numeric(gt, &st, &g);
    double worst = 0;
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++)
            for (int j = 0; j < 3; j++) worst = fmax(worst, fabs(a.T[i][o][j] - g.T[i][o][j]));
    printf("360-830 nm, 20 um slab: analytic vs ground truth, worst |dT| %.2e\n", worst);
    CHECK(worst < 5e-3);
    biref_numeric_plan_destroy(gt);
    biref_spectral_destroy(sp);
}

/* Not finite in, error out: a state whose optical path is NaN (no valid slab gives one). */
static void non_finite_optical_path_is_an_error(void)
{
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    biref_slab slab = {1.5, 1.6, {0, 1, 0}, 1000, 1.0};
    biref_slab_state st;
    CHECK(biref_slab_prepare(&slab, 0.2, &st) == BIREF_OK);
    st.opl_down[1] = NAN;
    biref_spectrum x;
    CHECK(biref_spectrum_expansion(sp, &st, NULL, &x) == BIREF_ERR_ILLCOND);
    double complex C[2][2] = {{0.5, 0}, {0, 0.5}};
    double xyz[3];
    CHECK(biref_spectrum_expansion_polarized(sp, &st, BIREF_TRANSMISSION, (const double complex(*)[2])C, NULL, NULL,
                                             xyz, NULL) == BIREF_ERR_ILLCOND);
    const biref_method methods[] = {BIREF_METHOD_ANALYTIC, BIREF_METHOD_EXPANSION, BIREF_METHOD_NUMERIC};
    for (int m = 0; m < 3; m++) {
        biref_integrator_options io;
        biref_integrator_options_default(&io);
        io.method = methods[m];
        if (methods[m] == BIREF_METHOD_NUMERIC) io.samples = 64;
        biref_integrator *it = NULL;
        CHECK(biref_integrator_create(sp, &io, &it, NULL, 0) == BIREF_OK);
        if (it) CHECK(biref_integrate_spectrum(it, &st, &x) == BIREF_ERR_ILLCOND);
        biref_integrator_destroy(it);
    }
    biref_spectral_destroy(sp);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"cmf_domains_are_reported", cmf_domains_are_reported},
        {"empty_reversed_or_out_of_domain_ranges_refused", empty_reversed_or_out_of_domain_ranges_refused},
        {"ranges_inside_the_cmf_domain_are_accepted", ranges_inside_the_cmf_domain_are_accepted},
        {"widest_range_stays_close_to_ground_truth", widest_range_stays_close_to_ground_truth},
        {"non_finite_optical_path_is_an_error", non_finite_optical_path_is_an_error},
    };
    return test_run_cases("test_spectral_range", cases, TEST_COUNT(cases), argc, argv);
}
