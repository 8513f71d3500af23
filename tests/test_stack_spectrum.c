/* Colours of stacks: the path groups reproduce the exact Jones matrices within their bound, the
 * expansion against the ground truth on the example stacks (unpolarized, s -> s, crossed s/p),
 * the numeric methods against the slab's, energy, and the fallback to adaptive integration. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "spectral/stack_internal.h"
#include "test_cases.h"

static biref_spectral *context(void)
{
    static biref_spectral *sp;
    if (!sp && biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK) abort();
    return sp;
}

static void random_stack(test_rng *r, biref_stack *s, double *theta)
{
    memset(s, 0, sizeof *s);
    s->eta_i = test_uniform(r, 0, 1) < 0.5 ? 1.0 : 1.33;
    s->n_layers = 1 + (int)test_uniform(r, 0, 4);
    for (int i = 0; i < s->n_layers; i++) {
        biref_layer *l = &s->layers[i];
        l->isotropic = test_uniform(r, 0, 1) < 0.25;
        l->eta_o = test_uniform(r, 1.4, 1.7);
        l->eta_e = l->isotropic ? l->eta_o : l->eta_o + test_uniform(r, -0.05, 0.05);
        test_random_axis(r, l->axis);
        l->thickness_nm = exp(test_uniform(r, log(200.0), log(1e5)));
    }
    *theta = test_uniform(r, 0, 60) * M_PI / 180;
}

/* sum_g M_g e^{ik phi_g} equals the exact Jones matrices to within the bound (amplitudes: the
 * bound is 2A + 3A^2 with A the amplitude left out). */
static void path_groups_sum_to_the_exact_jones_matrices(void)
{
    test_rng r = {0x9a7b5ULL};
    int n = test_quick() ? 20 : 80, used = 0;
    double worst = 0.0;
    for (int k = 0; k < n; k++) {
        biref_stack s;
        double theta;
        random_stack(&r, &s, &theta);
        biref_stack_state st;
        CHECK(biref_stack_prepare(&s, theta, &st) == BIREF_OK);
        biref_stack_groups g;
        CHECK(biref_stack_path_groups(&st, NULL, NULL, 1e-5, 1 << 14, &g) == BIREF_OK);
        if (g.reason) continue;
        used++;
        CHECK(g.bound <= 1e-5);
        for (int w = 0; w < 5; w++) {
            double lambda = 400 + 70 * w, kk = 2 * M_PI / lambda;
            biref_jones T, R;
            biref_stack_jones_at(&st, lambda, &T, &R);
            for (int f = 0; f < 2; f++) {
                double complex J[2][2] = {{0, 0}, {0, 0}};
                for (int h = 0; h < g.n[f]; h++)
                    for (int i = 0; i < 2; i++)
                        for (int o = 0; o < 2; o++) J[i][o] += g.g[f][h].M[i][o] * cexp(I * kk * g.g[f][h].phi);
                const biref_jones *E = f ? &R : &T;
                for (int i = 0; i < 2; i++)
                    for (int o = 0; o < 2; o++) worst = fmax(worst, cabs(J[i][o] - E->m[i][o]));
            }
        }
        biref_stack_groups_free(&g);
    }
    printf("  worst amplitude error of the path groups %.2e (bound 5e-6, %d stacks)\n", worst, used);
    CHECK(used > n / 2);
    CHECK(worst <= 5e-6);
}

static const char *const EXAMPLES[] = {"examples/stacks/solc_folded.json", "examples/stacks/cellophane3.json",
                                       "examples/stacks/film_on_glass.json", "examples/stacks/lyot_stage1.json"};

/* The expansion against the ground truth (16384 samples) on the example stacks at 0, 30, 60 deg,
 * seen with unpolarized light, s -> s and between crossed s/p filters. */
static void expansion_matches_ground_truth_on_examples(void)
{
    biref_spectral *sp = context();
    double sum = 0.0, worst = 0.0;
    int count = 0, fallbacks = 0;
    for (size_t e = 0; e < sizeof EXAMPLES / sizeof *EXAMPLES; e++) {
        biref_stack s;
        char msg[BIREF_MSG_SIZE];
        CHECK(biref_stack_load(EXAMPLES[e], &s, msg, sizeof msg) == BIREF_OK);
        for (int a = 0; a < 3; a++) {
            biref_stack_state st;
            CHECK(biref_stack_prepare(&s, a * 30 * M_PI / 180, &st) == BIREF_OK);
            biref_stack_spectrum_opts ox, og;
            biref_stack_spectrum_opts_default(&ox);
            biref_stack_spectrum_opts_default(&og);
            og.method = BIREF_METHOD_GROUND_TRUTH;
            biref_light un;
            const double half[2] = {0.5, 0.5}, all[2] = {1, 1};
            biref_light_sp(half, all, &un);
            biref_spectrum x, gt;
            double xt[3], gtt[3];
            biref_stack_spectrum_info info;
            CHECK(biref_stack_spectrum(sp, &st, &ox, &un, &x, xt, NULL, &info, msg, sizeof msg) == BIREF_OK);
            CHECK(biref_stack_spectrum(sp, &st, &og, &un, &gt, gtt, NULL, NULL, msg, sizeof msg) == BIREF_OK);
            fallbacks += info.fallback;
            const double de[3] = {biref_delta_e00_xyz(xt, gtt), biref_delta_e00_xyz(x.T[0][0], gt.T[0][0]),
                                  biref_delta_e00_xyz(x.T[0][1], gt.T[0][1])};
            for (int k = 0; k < 3; k++) sum += de[k], worst = fmax(worst, de[k]), count++;
            printf("  %-36s %2d deg: dE00 %.3f %.3f %.3f  groups %d/%d legs %d%s%s\n", EXAMPLES[e], a * 30, de[0],
                   de[1], de[2], info.groups[0], info.groups[1], info.legs, info.fallback ? "  fallback: " : "",
                   info.reason);
        }
    }
    printf("  expansion vs ground truth: mean dE00 %.3f, max %.3f (%d colours, %d fallbacks)\n", sum / count, worst,
           count, fallbacks);
    CHECK(sum / count <= 0.5);
    CHECK(worst <= 2.0);
}

/* The numeric methods of a one-layer stack are the slab's (the same Jones matrices, the same plan). */
static void one_layer_numeric_equals_slab(void)
{
    biref_spectral *sp = context();
    biref_slab slab = {1.55, 1.56, {0.3, 0.6, 0.7}, 20000.0, 1.0};
    biref_stack s;
    biref_stack_from_slab(&slab, &s);
    biref_slab_state ss;
    biref_stack_state st;
    CHECK(biref_slab_prepare(&slab, 0.4, &ss) == BIREF_OK);
    CHECK(biref_stack_prepare(&s, 0.4, &st) == BIREF_OK);
    biref_numeric_plan *plan;
    CHECK(biref_numeric_plan_create(sp, 512, &plan, NULL, 0) == BIREF_OK);
    biref_spectrum a, b;
    biref_spectrum_numeric(plan, &ss, &a);
    biref_stack_spectrum_opts o;
    biref_stack_spectrum_opts_default(&o);
    o.method = BIREF_METHOD_NUMERIC;
    o.samples = 512;
    CHECK(biref_stack_spectrum(sp, &st, &o, NULL, &b, NULL, NULL, NULL, NULL, 0) == BIREF_OK);
    double worst = 0.0;
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++)
            for (int c = 0; c < 3; c++)
                worst = fmax(worst, fmax(fabs(a.T[i][k][c] - b.T[i][k][c]), fabs(a.R[i][k][c] - b.R[i][k][c])));
    CHECK(worst < 1e-12);
    biref_numeric_plan_destroy(plan);
}

/* Per input and band, everything transmitted plus reflected is the light that came in (lossless),
 * to within the truncation bound (two faces). */
static void expansion_conserves_energy(void)
{
    biref_spectral *sp = context();
    test_rng r = {0xe4e7ULL};
    double worst = 0.0;
    for (int k = 0; k < (test_quick() ? 10 : 60); k++) {
        biref_stack s;
        double theta;
        random_stack(&r, &s, &theta);
        biref_stack_state st;
        CHECK(biref_stack_prepare(&s, theta, &st) == BIREF_OK);
        biref_spectrum x;
        biref_stack_spectrum_info info;
        CHECK(biref_stack_spectrum(sp, &st, NULL, NULL, &x, NULL, NULL, &info, NULL, 0) == BIREF_OK);
        if (info.fallback) continue;
        for (int i = 0; i < 2; i++)
            for (int c = 0; c < 3; c++)
                worst = fmax(worst, fabs(x.T[i][0][c] + x.T[i][1][c] + x.R[i][0][c] + x.R[i][1][c] - 1.0));
    }
    printf("  worst |T + R - 1| of the expansion %.2e\n", worst);
    CHECK(worst <= 4e-3);
}

/* Where the expansion does not apply it says why and integrates adaptively. */
static void fallback_is_reported(void)
{
    biref_spectral *sp = context();
    biref_stack s;
    memset(&s, 0, sizeof s);
    s.eta_i = 1.8; /* a rarer layer at 60 deg: evanescent */
    s.n_layers = 2;
    s.layers[0] = (biref_layer){1.5, 1.5, {0, 1, 0}, 300.0, 1, NULL};
    s.layers[1] = (biref_layer){1.9, 1.95, {1, 0, 0}, 5000.0, 0, NULL};
    biref_stack_state st;
    CHECK(biref_stack_prepare(&s, 60 * M_PI / 180, &st) == BIREF_OK && st.evanescent == 1);
    biref_spectrum x, gt;
    biref_stack_spectrum_info info;
    CHECK(biref_stack_spectrum(sp, &st, NULL, NULL, &x, NULL, NULL, &info, NULL, 0) == BIREF_OK);
    CHECK(info.fallback && strstr(info.reason, "evanescent") && info.samples >= 512);
    biref_stack_spectrum_opts o;
    biref_stack_spectrum_opts_default(&o);
    o.method = BIREF_METHOD_GROUND_TRUTH;
    CHECK(biref_stack_spectrum(sp, &st, &o, NULL, &gt, NULL, NULL, NULL, NULL, 0) == BIREF_OK);
    CHECK(biref_delta_e00_xyz(x.T[0][0], gt.T[0][0]) < 0.5 && biref_delta_e00_xyz(x.R[1][1], gt.R[1][1]) < 0.5);
    /* Too many groups for the limit. */
    CHECK(biref_stack_load("examples/stacks/solc_folded.json", &s, NULL, 0) == BIREF_OK);
    CHECK(biref_stack_prepare(&s, 0.2, &st) == BIREF_OK);
    biref_stack_spectrum_opts_default(&o);
    o.max_groups = 2;
    CHECK(biref_stack_spectrum(sp, &st, &o, NULL, &x, NULL, NULL, &info, NULL, 0) == BIREF_OK);
    CHECK(info.fallback && strstr(info.reason, "too many path groups"));
    /* Options outside their domain, the analytic method among them. */
    char msg[BIREF_MSG_SIZE] = "";
    o.method = BIREF_METHOD_ANALYTIC;
    CHECK(biref_stack_spectrum(sp, &st, &o, NULL, &x, NULL, NULL, NULL, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(strstr(msg, "no analytic method") != NULL);
    biref_stack_spectrum_opts_default(&o);
    o.tolerance = 0.5;
    CHECK(biref_stack_spectrum(sp, &st, &o, NULL, &x, NULL, NULL, NULL, msg, sizeof msg) == BIREF_ERR_INVALID);
}

static const test_case CASES[] = {
    {"path_groups_sum_to_the_exact_jones_matrices", path_groups_sum_to_the_exact_jones_matrices},
    {"expansion_matches_ground_truth_on_examples", expansion_matches_ground_truth_on_examples},
    {"one_layer_numeric_equals_slab", one_layer_numeric_equals_slab},
    {"expansion_conserves_energy", expansion_conserves_energy},
    {"fallback_is_reported", fallback_is_reported},
};

int main(int argc, char **argv)
{
    int rc = test_run_cases("test_stack_spectrum", CASES, TEST_COUNT(CASES), argc, argv);
    biref_spectral_destroy(context());
    return rc;
}
