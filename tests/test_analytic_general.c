/* The analytic method for a general light (incident coherency C, analyzer P; analytic_general.c,
 * the GLSL shader's formulas): for the paper's s/p light its terms equal the paper's terms mixed,
 * with and without the prefilter's footprint; the integrator takes any light with it; against the
 * exact path-group expansion and the ground truth, seeded random slabs under random Stokes input
 * and linear or circular analyzers stay within the analytic method's accuracy. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "biref/biref.h"
#include "spectral/analytic_terms.h"
#include "spectral/phase_prefilter.h"
#include "test_cases.h"

static biref_spectral *sp;
static biref_phase_prefilter *pf;

static void random_thick_slab(test_rng *r, biref_slab *s, double *theta)
{
    test_random_axis(r, s->axis);
    s->eta_o = test_uniform(r, 1.3, 2.2);
    s->eta_e = s->eta_o + test_uniform(r, -0.4, 0.4);
    s->eta_i = 1.0;
    s->thickness_nm = exp(test_uniform(r, log(2e4), log(2e6)));
    *theta = test_uniform(r, 0, 80) * M_PI / 180;
}

/* A footprint of random gradients (about a few hundred nm of path across the pixel). */
static void random_footprint(test_rng *r, biref_opl_footprint *fp)
{
    fp->pf = pf;
    fp->disp = NULL;
    for (int l = 0; l < 4; l++)
        for (int k = 0; k < 2; k++) fp->grad[l][k] = test_uniform(r, -300, 300);
}

/* C = diag(w), P = diag(mask): every term is the paper's sum_i w_i sum_o mask_o^2 (E, H)[i][o],
 * with point look-ups and averaged over a footprint. Real and evanescent states (a dense
 * surround: total reflection inside). */
static void sp_light_terms_equal_paper_terms_mixed(void)
{
    test_rng rng = {20261125};
    double worst = 0;
    for (int k = 0; k < 200; k++) {
        biref_slab s;
        double theta;
        random_thick_slab(&rng, &s, &theta);
        if (k % 4 == 3) s.eta_i = fmin(s.eta_o, s.eta_e) + 0.3, theta = test_uniform(&rng, 60, 85) * M_PI / 180;
        biref_slab_state st;
        CHECK(biref_slab_prepare(&s, theta, &st) == BIREF_OK);
        const double w[2] = {test_uniform(&rng, 0, 1), test_uniform(&rng, 0, 1)};
        const double m[2] = {test_uniform(&rng, 0, 1), test_uniform(&rng, 0, 1)};
        const double complex C[2][2] = {{w[0], 0}, {0, w[1]}}, P[2][2] = {{m[0], 0}, {0, m[1]}};
        biref_opl_footprint fp;
        random_footprint(&rng, &fp);
        for (int with_fp = 0; with_fp < 2; with_fp++)
            for (int which = 0; which < 2; which++) {
                const biref_opl_footprint *f = with_fp ? &fp : NULL;
                double E[2][2][3], H[2][2][3], Eg[3], Hg[3], Ep[3] = {0, 0, 0}, Hp[3] = {0, 0, 0};
                biref_analytic_paper_terms_footprint(sp, &st, f, which, k & 1, E, H);
                biref_analytic_general_terms(sp, &st, f, which, k & 1, C, P, Eg, Hg); /* both methods */
                for (int i = 0; i < 2; i++)
                    for (int o = 0; o < 2; o++)
                        for (int j = 0; j < 3; j++) {
                            Ep[j] += w[i] * m[o] * m[o] * E[i][o][j];
                            Hp[j] += w[i] * m[o] * m[o] * H[i][o][j];
                        }
                for (int j = 0; j < 3; j++) {
                    double scale = fmax(1.0, fabs(Ep[j]));
                    worst = fmax(worst, fmax(fabs(Eg[j] - Ep[j]), fabs(Hg[j] - Hp[j])) / scale);
                    CHECK_NEAR(Eg[j], Ep[j], 1e-12 * scale);
                    CHECK_NEAR(Hg[j], Hp[j], 1e-12 * scale);
                }
            }
    }
    printf("general terms vs paper terms mixed, s/p lights: largest difference %.3g\n", worst);
}

/* A general light's terms over a footprint: E (no phase) unchanged, H the point value for a
 * zero footprint and no larger than the light there is for a wide one. */
static void footprint_terms_reduce_to_points(void)
{
    test_rng rng = {777};
    for (int k = 0; k < 60; k++) {
        biref_slab s;
        double theta;
        random_thick_slab(&rng, &s, &theta);
        biref_slab_state st;
        CHECK(biref_slab_prepare(&s, theta, &st) == BIREF_OK);
        double S[4];
        test_random_stokes(&rng, S);
        double complex C[2][2], P[2][2];
        CHECK(biref_stokes_to_coherency(S, C) == BIREF_OK);
        biref_analyzer_linear(test_uniform(&rng, 0, M_PI), P);
        biref_opl_footprint fp, zero = {pf, {{0}}, NULL};
        random_footprint(&rng, &fp);
        for (int which = 0; which < 2; which++) {
            double E0[3], H0[3], Ez[3], Hz[3], Ef[3], Hf[3];
            biref_analytic_general_terms(sp, &st, NULL, which, 1, C, P, E0, H0);
            biref_analytic_general_terms(sp, &st, &zero, which, 1, C, P, Ez, Hz);
            biref_analytic_general_terms(sp, &st, &fp, which, 1, C, P, Ef, Hf);
            for (int j = 0; j < 3; j++) {
                CHECK(Ez[j] == E0[j] && Ef[j] == E0[j]); /* E has no phase */
                CHECK_NEAR(Hz[j], H0[j], 1e-12);
                /* Averaging shrinks every interference term's band integral: |H| cannot grow much. */
                CHECK(isfinite(Hf[j]) && fabs(Hf[j]) <= fabs(H0[j]) + 0.5 * E0[j] + 1e-12);
            }
        }
    }
}

/* The integrator takes any light with the analytic method; an s/p light keeps its path. */
static void integrator_takes_every_light(void)
{
    biref_integrator_options o;
    biref_integrator_options_default(&o);
    biref_integrator *it = NULL;
    CHECK(biref_integrator_create(sp, &o, &it, NULL, 0) == BIREF_OK);
    const biref_slab s = {1.775, 1.231, {0.084, 0.979, -0.187}, 1.15e6, 1.0};
    biref_slab_state st;
    CHECK(biref_slab_prepare(&s, 0.5, &st) == BIREF_OK);
    biref_light l;
    const double S[4] = {1, 0.3, -0.4, 0.5};
    CHECK(biref_light_stokes(S, &l) == BIREF_OK);
    double complex P[2][2];
    biref_analyzer_circular(-1, P);
    biref_light_set_analyzer(&l, (const double complex(*)[2])P);
    biref_integration r;
    CHECK(biref_integrate(it, &st, BIREF_SIDE_BOTH, &l, &r) == BIREF_OK);
    double T[3], R[3];
    biref_analytic_general(sp, &st, NULL, BIREF_TRANSMISSION, 0, (const double complex(*)[2])l.C,
                           (const double complex(*)[2])P, T);
    biref_analytic_general(sp, &st, NULL, BIREF_REFLECTION, 0, (const double complex(*)[2])l.C,
                           (const double complex(*)[2])P, R);
    for (int j = 0; j < 3; j++) CHECK(r.T[j] == T[j] && r.R[j] == R[j] && r.T[j] >= 0 && r.R[j] >= 0);
    biref_integrator_destroy(it);
}

/* dE00 of the general analytic method against the expansion (both with a footprint, and both
 * without) on thick slabs: random Stokes input, linear or circular analyzers. */
static void general_light_close_to_expansion(void)
{
    test_rng rng = {4242};
    const int n = test_quick() ? 40 : 200;
    double sum[2] = {0, 0}, worst[2] = {0, 0};
    for (int k = 0; k < n; k++) {
        biref_slab s;
        double theta;
        random_thick_slab(&rng, &s, &theta);
        biref_slab_state st;
        CHECK(biref_slab_prepare(&s, theta, &st) == BIREF_OK);
        double S[4];
        test_random_stokes(&rng, S);
        double complex C[2][2], P[2][2];
        CHECK(biref_stokes_to_coherency(S, C) == BIREF_OK);
        if (k % 2)
            biref_analyzer_linear(test_uniform(&rng, 0, M_PI), P);
        else
            biref_analyzer_circular(k % 4 ? 1 : -1, P);
        biref_opl_footprint fp;
        random_footprint(&rng, &fp);
        for (int with_fp = 0; with_fp < 2; with_fp++)
            for (int which = 0; which < 2; which++) {
                const biref_opl_footprint *f = with_fp ? &fp : NULL;
                double a[3], x[3];
                biref_analytic_general(sp, &st, f, which, 1, (const double complex(*)[2])C,
                                       (const double complex(*)[2])P, a);
                CHECK(biref_expansion_polarized_footprint(sp, &st, f, which, (const double complex(*)[2])C,
                                                          (const double complex(*)[2])P, NULL, x, NULL) == BIREF_OK);
                double de = biref_delta_e00_xyz(a, x);
                sum[with_fp] += de;
                worst[with_fp] = fmax(worst[with_fp], de);
            }
    }
    printf("general light, analytic vs expansion dE00 (thick slabs, T and R): points mean %.3g max %.3g; "
           "footprints mean %.3g max %.3g\n",
           sum[0] / (2 * n), worst[0], sum[1] / (2 * n), worst[1]);
    /* The s/p analytic method's envelope on thick slabs (test_physical_bounds): mean 1.5, max 20. */
    for (int f = 0; f < 2; f++) CHECK(sum[f] / (2 * n) <= 1.5 && worst[f] <= 20);
}

int main(int argc, char **argv)
{
    if (biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK || biref_phase_prefilter_create(sp, &pf) != BIREF_OK)
        return 1;
    static const test_case cases[] = {
        {"sp_light_terms_equal_paper_terms_mixed", sp_light_terms_equal_paper_terms_mixed},
        {"footprint_terms_reduce_to_points", footprint_terms_reduce_to_points},
        {"integrator_takes_every_light", integrator_takes_every_light},
        {"general_light_close_to_expansion", general_light_close_to_expansion},
    };
    int rc = test_run_cases("test_analytic_general", cases, TEST_COUNT(cases), argc, argv);
    biref_phase_prefilter_destroy(pf);
    biref_spectral_destroy(sp);
    return rc;
}
