/* Every spectral method gives physical numbers on every valid slab: band-integrated T and R in
 * [0, 1] and, per input polarization and band, T + R summed over the outputs at most 1 (lossless
 * slab), within 1e-6. Seeded random slabs of five kinds: thin (1 nm - 3 um), thick (3 um - 10 mm),
 * an ambient index above a slab index with the light beyond the critical angle inside (total
 * reflection, frustrated when thin), near the optic axis, and near grazing incidence. Also: the
 * analytic method and the expansion stay within their documented dE00 envelope of the ground
 * truth (docs/ACCURACY.md, "Where each method is valid") where the ground truth is alias-free. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "spectral/spectral_internal.h"
#include "test_cases.h"

enum { KIND_THIN, KIND_THICK, KIND_TIR, KIND_AXIS, KIND_GRAZING, N_KINDS };
static const char *const KIND_NAMES[N_KINDS] = {"thin", "thick", "eta_i > eta", "near axis", "near 90 deg"};

static void random_slab(test_rng *r, int kind, biref_slab *s, double *theta)
{
    double A[3];
    test_random_axis(r, A);
    s->eta_o = test_uniform(r, 1, 3);
    s->eta_e = fmin(3, fmax(1, s->eta_o + test_uniform(r, -0.5, 0.5)));
    s->eta_i = test_uniform(r, 1, 2);
    double lo = 1, hi = 1e7, th_lo = 0, th_hi = 89.99;
    switch (kind) {
    case KIND_THIN: hi = 3000; break;
    case KIND_THICK: lo = 3000; break;
    case KIND_TIR:
        /* eta_i above the smaller slab index and the angle beyond its critical angle. */
        s->eta_i = fmin(s->eta_o, s->eta_e) + test_uniform(r, 0.01, 0.8);
        th_lo = asin(fmin(1, fmin(s->eta_o, s->eta_e) / s->eta_i)) * 180 / M_PI;
        hi = test_uniform(r, 0, 1) < 0.7 ? 2000 : 1e7;
        break;
    case KIND_AXIS:
        /* At normal incidence the waves run along y: an axis within a few degrees of y. */
        A[0] = test_uniform(r, -0.05, 0.05), A[1] = 1, A[2] = test_uniform(r, -0.05, 0.05);
        th_hi = 3;
        break;
    case KIND_GRAZING: th_lo = 85; break;
    }
    for (int i = 0; i < 3; i++) s->axis[i] = A[i];
    s->thickness_nm = exp(test_uniform(r, log(lo), log(hi)));
    *theta = test_uniform(r, th_lo, th_hi) * M_PI / 180;
}

/* Largest violation of 0 <= T, R <= 1 and sum_out (T + R) <= 1 per input and band. */
static double violation(const biref_spectrum *x)
{
    double w = 0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 3; j++) {
            double sum = 0;
            for (int o = 0; o < 2; o++) {
                double t = x->T[i][o][j], r = x->R[i][o][j];
                if (!isfinite(t) || !isfinite(r)) return INFINITY;
                w = fmax(w, fmax(fmax(-t, -r), fmax(t - 1, r - 1)));
                sum += t + r;
            }
            w = fmax(w, sum - 1);
        }
    return w;
}

/* dE00 of the unpolarized light, open and crossed (s analyzer, p in), T and R. */
static double worst_de(const biref_spectrum *a, const biref_spectrum *g)
{
    static const double unpol[2] = {0.5, 0.5}, open[2] = {1, 1}, p_in[2] = {0, 1}, s_out[2] = {1, 0};
    double w = 0, xa[3], xg[3];
    for (int which = 0; which < 2; which++) {
        const double(*A)[2][3] = which ? a->R : a->T, (*G)[2][3] = which ? g->R : g->T;
        biref_spectrum_mix(A, unpol, open, xa);
        biref_spectrum_mix(G, unpol, open, xg);
        w = fmax(w, biref_delta_e00_xyz(xa, xg));
        biref_spectrum_mix(A, p_in, s_out, xa);
        biref_spectrum_mix(G, p_in, s_out, xg);
        w = fmax(w, biref_delta_e00_xyz(xa, xg));
    }
    return w;
}

enum { M_ANALYTIC, M_EXPANSION, M_EXPANSION8, M_NUMERIC32, M_GT, N_M };
static const char *const NAMES[N_M] = {"analytic", "expansion", "expansion order 8", "numeric-32", "ground truth"};

/* One seeded slab of a kind, its spectra by every method, and a random light and analyzer. */
typedef struct {
    int kind;
    biref_slab s;
    double theta;
    biref_slab_state st;
    biref_spectrum x[N_M];
    double complex C[2][2], P[2][2];
    /* Under that light (d <= 100 um only): the analytic method, the expansion, the ground truth,
     * [T/R][band]. */
    double pol[3][2][3];
} sample;

static biref_spectral *sp;
static sample *samples;
static int per_kind, n_samples;

/* The slabs and their spectra, computed once for all cases (the ground truth is the cost). */
static void compute_samples(void)
{
    if (samples) return;
    per_kind = test_quick() ? 40 : 200;
    samples = calloc((size_t)N_KINDS * per_kind, sizeof *samples);
    biref_numeric_plan *gt = NULL, *n32 = NULL;
    CHECK(samples != NULL);
    CHECK(biref_numeric_plan_create(sp, BIREF_GROUND_TRUTH_SAMPLES, &gt, NULL, 0) == BIREF_OK);
    CHECK(biref_numeric_plan_create(sp, 32, &n32, NULL, 0) == BIREF_OK);
    biref_integrator_options ao;
    biref_integrator_options_default(&ao);
    biref_integrator *an = NULL;
    CHECK(biref_integrator_create(sp, &ao, &an, NULL, 0) == BIREF_OK);
    if (!samples || !gt || !n32 || !an) goto done;
    test_rng rng = {20261123};
    for (int kind = 0; kind < N_KINDS; kind++)
        for (int t = 0; t < per_kind; t++) {
            sample *x = &samples[n_samples++];
            x->kind = kind;
            random_slab(&rng, kind, &x->s, &x->theta);
            char msg[256];
            CHECK(biref_slab_check(&x->s, msg, sizeof msg) == BIREF_OK);
            CHECK(biref_slab_prepare(&x->s, x->theta, &x->st) == BIREF_OK);
            biref_expansion_opts o8;
            biref_expansion_opts_default(&o8);
            o8.order = 8;
            biref_spectrum_analytic(sp, &x->st, &x->x[M_ANALYTIC]);
            CHECK(biref_spectrum_expansion(sp, &x->st, NULL, &x->x[M_EXPANSION]) == BIREF_OK);
            CHECK(biref_spectrum_expansion(sp, &x->st, &o8, &x->x[M_EXPANSION8]) == BIREF_OK);
            biref_spectrum_numeric(n32, &x->st, &x->x[M_NUMERIC32]);
            biref_spectrum_numeric(gt, &x->st, &x->x[M_GT]);
            double S[4];
            test_random_stokes(&rng, S);
            CHECK(biref_stokes_to_coherency(S, x->C) == BIREF_OK);
            if (t % 2)
                biref_analyzer_linear(test_uniform(&rng, 0, M_PI), x->P);
            else
                biref_analyzer_circular(t % 4 ? 1 : -1, x->P);
            if (x->s.thickness_nm > 1e5) continue;
            const double complex(*C)[2] = (const double complex(*)[2])x->C, (*P)[2] = (const double complex(*)[2])x->P;
            biref_light l;
            biref_light_coherency(C, &l);
            biref_light_set_analyzer(&l, P);
            biref_integration r;
            CHECK(biref_integrate(an, &x->st, BIREF_SIDE_BOTH, &l, &r) == BIREF_OK);
            for (int w = 0; w < 2; w++) {
                memcpy(x->pol[0][w], w ? r.R : r.T, sizeof r.T);
                CHECK(biref_spectrum_expansion_polarized(sp, &x->st, w, C, P, NULL, x->pol[1][w], NULL) == BIREF_OK);
                biref_spectrum_numeric_polarized(gt, &x->st, w, C, P, x->pol[2][w]);
            }
        }
done:
    biref_integrator_destroy(an);
    biref_numeric_plan_destroy(n32);
    biref_numeric_plan_destroy(gt);
}

static void every_method_stays_within_physical_bounds(void)
{
    compute_samples();
    double worst[N_KINDS][N_M] = {{0}};
    for (int k = 0; k < n_samples; k++) {
        const sample *x = &samples[k];
        for (int m = 0; m < N_M; m++) {
            double v = violation(&x->x[m]);
            worst[x->kind][m] = fmax(worst[x->kind][m], v);
            if (!(v <= 1e-6) && test_failures < 20)
                fprintf(stderr, "%s, %s: violation %.3g: eta_o %.4g eta_e %.4g axis (%.4g %.4g %.4g) d %.4g nm eta_i %.4g theta %.4f deg\n",
                        KIND_NAMES[x->kind], NAMES[m], v, x->s.eta_o, x->s.eta_e, x->s.axis[0], x->s.axis[1],
                        x->s.axis[2], x->s.thickness_nm, x->s.eta_i, x->theta * 180 / M_PI);
            CHECK(v <= 1e-6);
        }
    }
    printf("largest violation of 0 <= T, R <= 1, sum T + R <= 1 (per input and band):\n%-12s", "");
    for (int m = 0; m < N_M; m++) printf(" %18s", NAMES[m]);
    printf("\n");
    for (int kind = 0; kind < N_KINDS; kind++) {
        printf("%-12s", KIND_NAMES[kind]);
        for (int m = 0; m < N_M; m++) printf(" %18.3g", worst[kind][m]);
        printf("\n");
    }
}

/* Any light and analyzer: the detected intensity of unit incident light lies in [0, 1]. */
static void polarized_intensity_stays_within_0_and_1(void)
{
    compute_samples();
    double worst_polarized = 0;
    for (int k = 0; k < n_samples; k++) {
        const sample *x = &samples[k];
        for (int which = 0; which < 2; which++) {
            double xyz[3];
            CHECK(biref_spectrum_expansion_polarized(sp, &x->st, which, (const double complex(*)[2])x->C,
                                                     (const double complex(*)[2])x->P, NULL, xyz, NULL) == BIREF_OK);
            for (int j = 0; j < 3; j++) {
                worst_polarized = fmax(worst_polarized, fmax(-xyz[j], xyz[j] - 1));
                CHECK(xyz[j] >= -1e-6 && xyz[j] <= 1 + 1e-6);
            }
        }
    }
    printf("expansion, random Stokes input and analyzer: largest violation of 0 <= I <= 1: %.3g\n", worst_polarized);
}

/* The energy balance rests on this: the incoherent path energies E of eqs. 20-21 sum to 1 over
 * outputs and directions (each path's |a|^2 is its power fraction), wherever no evanescent leg
 * couples the faces. */
static void path_energies_sum_to_one_without_total_reflection(void)
{
    compute_samples();
    double worst_energy = 0;
    for (int k = 0; k < n_samples; k++) {
        const sample *x = &samples[k];
        if (x->st.total_reflection) continue;
        double E[2][2][2][3], H[2][2][3];
        for (int w = 0; w < 2; w++) biref_analytic_paper_terms(sp, &x->st, w, 0, E[w], H);
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 3; j++) {
                double sum = E[0][i][0][j] + E[0][i][1][j] + E[1][i][0][j] + E[1][i][1][j];
                worst_energy = fmax(worst_energy, fabs(sum - 1));
                CHECK_NEAR(sum, 1.0, 1e-9);
            }
    }
    printf("incoherent path energies E (no total reflection): largest |sum_out (E_T + E_R) - 1| %.3g\n", worst_energy);
}

/* The analytic method and the expansion against the ground truth where it is alias-free
 * (d <= 100 um): max, sum, count, count > 1, within the documented envelope. */
static void analytic_and_expansion_within_documented_envelope(void)
{
    compute_samples();
    double de_max[N_KINDS][2] = {{0}}, de_sum[N_KINDS][2] = {{0}};
    int de_n[N_KINDS] = {0}, de_over[N_KINDS][2] = {{0}};
    for (int k = 0; k < n_samples; k++) {
        const sample *x = &samples[k];
        if (x->s.thickness_nm > 1e5) continue;
        de_n[x->kind]++;
        for (int m = 0; m < 2; m++) {
            double de = worst_de(&x->x[m == 0 ? M_ANALYTIC : M_EXPANSION], &x->x[M_GT]);
            de_max[x->kind][m] = fmax(de_max[x->kind][m], de);
            de_sum[x->kind][m] += de;
            de_over[x->kind][m] += de > 1;
        }
    }
    printf("dE00 against the ground truth (d <= 100 um; unpolarized open and s-in/p-out crossed, T and R):\n"
           "%-12s %5s %30s %30s\n", "", "n", "analytic: mean / max / % > 1", "expansion: mean / max / % > 1");
    for (int kind = 0; kind < N_KINDS; kind++) {
        int n = de_n[kind] ? de_n[kind] : 1;
        printf("%-12s %5d %12.3g / %6.3g / %5.1f %12.3g / %6.3g / %5.1f\n", KIND_NAMES[kind], de_n[kind],
               de_sum[kind][0] / n, de_max[kind][0], 100.0 * de_over[kind][0] / n, de_sum[kind][1] / n,
               de_max[kind][1], 100.0 * de_over[kind][1] / n);
    }
    /* The envelope documented in docs/ACCURACY.md ("Where each method is valid"), measured on this
     * seed with some margin: analytic max 0.065 / 13.2 / 0.26 / 5.4 / 14.3 and means 0.0004 / 0.86
     * / 0.0015 / 0.28 / 0.82 for the five kinds; expansion max 0.0018 / 1.5 / 0.0026 / 0.15 / 2.9.
     * Eq. 26 as printed (no coherent regime, no energy balance) had means 18 / 0.98 / 52 / 6.2 /
     * 20 and maxima up to 141. */
    static const double env_max[N_KINDS][2] = {{0.2, 0.01}, {20, 2.5}, {0.5, 0.01}, {8, 0.3}, {20, 4}};
    static const double env_mean[N_KINDS][2] = {{0.01, 0.001}, {1.5, 0.1}, {0.01, 0.001}, {0.5, 0.01}, {1.5, 0.2}};
    for (int kind = 0; kind < N_KINDS; kind++)
        for (int m = 0; m < 2; m++) {
            CHECK(de_max[kind][m] <= env_max[kind][m]);
            CHECK(de_sum[kind][m] <= env_mean[kind][m] * de_n[kind]);
        }
}

/* Any light (random Stokes input, linear or circular analyzer): the analytic method's general
 * terms (the GPU shader's) against the ground truth where it is alias-free, within the envelope
 * of the paper's s/p light above, and never negative; the expansion alongside for scale. */
static void analytic_general_light_within_envelope(void)
{
    compute_samples();
    double de_max[N_KINDS][2] = {{0}}, de_sum[N_KINDS][2] = {{0}}, lowest = 0;
    int de_n[N_KINDS] = {0};
    for (int k = 0; k < n_samples; k++) {
        const sample *x = &samples[k];
        if (x->s.thickness_nm > 1e5) continue;
        de_n[x->kind]++;
        for (int m = 0; m < 2; m++) {
            double de = 0;
            for (int w = 0; w < 2; w++) de = fmax(de, biref_delta_e00_xyz(x->pol[m][w], x->pol[2][w]));
            de_max[x->kind][m] = fmax(de_max[x->kind][m], de);
            de_sum[x->kind][m] += de;
        }
        for (int w = 0; w < 2; w++)
            for (int j = 0; j < 3; j++) lowest = fmin(lowest, x->pol[0][w][j]);
    }
    printf("general light, dE00 against the ground truth (d <= 100 um; worse of T and R):\n"
           "%-12s %5s %22s %22s\n", "", "n", "analytic: mean / max", "expansion: mean / max");
    for (int kind = 0; kind < N_KINDS; kind++) {
        int n = de_n[kind] ? de_n[kind] : 1;
        printf("%-12s %5d %12.3g / %7.3g %12.3g / %7.3g\n", KIND_NAMES[kind], de_n[kind], de_sum[kind][0] / n,
               de_max[kind][0], de_sum[kind][1] / n, de_max[kind][1]);
    }
    /* The s/p analytic method's envelope (analytic_and_expansion_within_documented_envelope). */
    static const double env_max[N_KINDS] = {0.2, 20, 0.5, 8, 20};
    static const double env_mean[N_KINDS] = {0.01, 1.5, 0.01, 0.5, 1.5};
    for (int kind = 0; kind < N_KINDS; kind++) {
        CHECK(de_max[kind][0] <= env_max[kind]);
        CHECK(de_sum[kind][0] <= env_mean[kind] * de_n[kind]);
    }
    CHECK(lowest >= 0);
}

/* Where the fast methods switch to the exact integral, both agree with the ground truth
 * (alias-free there: short optical paths). */
static void coherent_regime_matches_ground_truth(void)
{
    compute_samples();
    double de_coherent[2] = {0, 0};
    int coherent_count = 0, evanescent_count = 0;
    for (int k = 0; k < n_samples; k++) {
        const sample *x = &samples[k];
        evanescent_count += x->st.total_reflection != 0;
        if (!biref_coherent_plan(sp, &x->st)) continue;
        coherent_count++;
        de_coherent[0] = fmax(de_coherent[0], worst_de(&x->x[M_ANALYTIC], &x->x[M_GT]));
        de_coherent[1] = fmax(de_coherent[1], worst_de(&x->x[M_EXPANSION], &x->x[M_GT]));
    }
    printf("coherent regime (%d of %d slabs, %d with evanescent modes): dE00 vs ground truth, analytic %.3g, "
           "expansion %.3g\n",
           coherent_count, N_KINDS * per_kind, evanescent_count, de_coherent[0], de_coherent[1]);
    CHECK(coherent_count > 0 && evanescent_count > 0);
    CHECK(de_coherent[0] <= 0.05 && de_coherent[1] <= 0.05);
}

int main(int argc, char **argv)
{
    if (biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK) return 1;
    static const test_case cases[] = {
        {"every_method_stays_within_physical_bounds", every_method_stays_within_physical_bounds},
        {"polarized_intensity_stays_within_0_and_1", polarized_intensity_stays_within_0_and_1},
        {"path_energies_sum_to_one_without_total_reflection", path_energies_sum_to_one_without_total_reflection},
        {"analytic_and_expansion_within_documented_envelope", analytic_and_expansion_within_documented_envelope},
        {"analytic_general_light_within_envelope", analytic_general_light_within_envelope},
        {"coherent_regime_matches_ground_truth", coherent_regime_matches_ground_truth},
    };
    int rc = test_run_cases("test_physical_bounds", cases, TEST_COUNT(cases), argc, argv);
    free(samples);
    biref_spectral_destroy(sp);
    return rc;
}
