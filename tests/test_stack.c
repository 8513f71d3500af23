/* Stacks of layers at one wavelength: the textbook closed forms of wave-plate combinations
 * (ideal polarizers, normal incidence, surround index-matched so that Fresnel losses vanish),
 * the slab as a one-layer stack, energy, splitting a layer, the 4x4 transfer-matrix reference,
 * and the stack files' checks. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "test_cases.h"

/* Nearly index-matched plates: eta_o equals the surround, Δn small, so the Fresnel reflections
 * are ~(Δn / 2n)^2 ~ 1e-7 and the closed forms (no reflections) hold to ~1e-6. */
static const double MATCH_ETA = 1.5, MATCH_DN = 0.001;

static biref_layer plate(double azimuth_rad, double retardance_rad, double lambda)
{
    biref_layer l = {MATCH_ETA, MATCH_ETA + MATCH_DN, {cos(azimuth_rad), 0.0, sin(azimuth_rad)}, 0.0, 0, NULL};
    l.thickness_nm = retardance_rad * lambda / (2.0 * M_PI * MATCH_DN);
    return l;
}

static biref_stack matched_stack(void)
{
    biref_stack s;
    memset(&s, 0, sizeof s);
    s.eta_i = MATCH_ETA;
    return s;
}

/* |J_T[in][out]|^2 at normal incidence. */
static double power(const biref_stack *s, double lambda, int in, int out)
{
    biref_jones T;
    if (biref_stack_jones(s, 0.0, lambda, &T, NULL) != BIREF_OK) return NAN;
    return creal(T.m[in][out] * conj(T.m[in][out]));
}

/* One plate at azimuth phi between crossed polarizers: T = sin^2 2phi sin^2(Γ/2). */
static void one_plate_crossed_polarizers(void)
{
    const double lambda = 550.0;
    for (int k = 0; k < 24; k++) {
        double phi = 0.13 * k, G = 0.37 * k + 0.2;
        biref_stack s = matched_stack();
        s.n_layers = 1;
        s.layers[0] = plate(phi, G, lambda);
        CHECK_NEAR(power(&s, lambda, BIREF_S, BIREF_P), pow(sin(2 * phi) * sin(G / 2), 2), 2e-6);
    }
}

/* Lyot filter: stages of thicknesses d, 2d, ..., 2^(N-1) d at 45 degrees, each followed by a
 * polarizer parallel to the first: T = prod_k cos^2(2^k Γ / 2). The ideal polarizers between
 * the stages project onto s, so the filter's amplitude is the product of the stages' s -> s. */
static void lyot_filter(void)
{
    for (int N = 1; N <= 4; N++)
        for (int w = 0; w < 12; w++) {
            double lambda = 400.0 + 25.0 * w, d = 40e3 + 5e3 * N, G = 2 * M_PI * d * MATCH_DN / lambda;
            double T = 1.0, expect = 1.0;
            for (int k = 0; k < N; k++) {
                biref_stack s = matched_stack();
                s.n_layers = 1;
                s.layers[0] = plate(M_PI / 4, 0.0, lambda);
                s.layers[0].thickness_nm = d * (1 << k);
                T *= power(&s, lambda, BIREF_S, BIREF_S);
                expect *= pow(cos((1 << k) * G / 2), 2);
            }
            CHECK_NEAR(T, expect, 5e-6);
        }
}

/* Folded Šolc filter: N equal plates at +rho, -rho, ..., rho = pi / 4N, crossed polarizers:
 * T = tan^2 2rho cos^2 chi [sin N chi / sin chi]^2, cos chi = cos 2rho sin(Γ/2). */
static void solc_folded_filter(void)
{
    const double lambda = 600.0;
    for (int N = 2; N <= 9; N++) {
        double rho = M_PI / (4 * N);
        for (int g = 0; g < 10; g++) {
            double G = 0.1 + 0.63 * g;
            biref_stack s = matched_stack();
            s.n_layers = N;
            for (int i = 0; i < N; i++) s.layers[i] = plate(i % 2 ? -rho : rho, G, lambda);
            double chi = acos(cos(2 * rho) * sin(G / 2));
            double expect = pow(tan(2 * rho) * cos(chi) * sin(N * chi) / sin(chi), 2);
            CHECK_NEAR(power(&s, lambda, BIREF_S, BIREF_P), expect, 2e-5);
        }
    }
}

/* Two plates at phi1, phi2 between crossed polarizers:
 * T = (c2 s1 sin 2phi1 + c1 s2 sin 2phi2)^2 + s1^2 s2^2 sin^2 2(phi2 - phi1). */
static void two_plates_crossed_polarizers(void)
{
    test_rng r = {0x5eed2a7e5ULL};
    const double lambda = 500.0;
    for (int k = 0; k < 60; k++) {
        double p1 = test_uniform(&r, 0, M_PI), p2 = test_uniform(&r, 0, M_PI);
        double G1 = test_uniform(&r, 0.05, 12), G2 = test_uniform(&r, 0.05, 12);
        biref_stack s = matched_stack();
        s.n_layers = 2;
        s.layers[0] = plate(p1, G1, lambda);
        s.layers[1] = plate(p2, G2, lambda);
        double c1 = cos(G1 / 2), s1 = sin(G1 / 2), c2 = cos(G2 / 2), s2 = sin(G2 / 2);
        double expect = pow(c2 * s1 * sin(2 * p1) + c1 * s2 * sin(2 * p2), 2) + pow(s1 * s2 * sin(2 * (p2 - p1)), 2);
        CHECK_NEAR(power(&s, lambda, BIREF_S, BIREF_P), expect, 5e-6);
    }
}

static void random_layer(test_rng *r, biref_layer *l)
{
    memset(l, 0, sizeof *l);
    l->isotropic = test_uniform(r, 0, 1) < 0.25;
    l->eta_o = test_uniform(r, 1.3, 2.0);
    l->eta_e = l->isotropic ? l->eta_o : l->eta_o + test_uniform(r, -0.3, 0.3);
    test_random_axis(r, l->axis);
    l->thickness_nm = exp(test_uniform(r, log(50.0), log(2e5)));
}

static void random_stack(test_rng *r, biref_stack *s, double *theta, double *lambda)
{
    memset(s, 0, sizeof *s);
    double u = test_uniform(r, 0, 1);
    s->eta_i = u < 0.4 ? 1.0 : u < 0.8 ? 1.33 : 1.8; /* 1.8: evanescent layers at oblique incidence */
    s->n_layers = 1 + (int)test_uniform(r, 0, 6);
    for (int i = 0; i < s->n_layers; i++) random_layer(r, &s->layers[i]);
    *theta = test_uniform(r, 0, 85) * M_PI / 180;
    *lambda = test_uniform(r, 380, 700);
}

static double jones_diff(const biref_jones *a, const biref_jones *b)
{
    double m = 0.0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) m = fmax(m, cabs(a->m[i][j] - b->m[i][j]));
    return m;
}

/* Lossless: for each input, the power transmitted plus reflected is 1 (random stacks, evanescent
 * layers included: a stack is lossless whatever its modes). */
static void energy_conserved_on_random_stacks(void)
{
    test_rng r = {0x57ac4e11ULL};
    int n = test_quick() ? 300 : 2000;
    double worst = 0.0;
    for (int k = 0; k < n; k++) {
        biref_stack s;
        double theta, lambda;
        random_stack(&r, &s, &theta, &lambda);
        biref_jones T, R;
        CHECK(biref_stack_jones(&s, theta, lambda, &T, &R) == BIREF_OK);
        double PT[2][2], PR[2][2];
        biref_jones_intensity(&T, PT);
        biref_jones_intensity(&R, PR);
        for (int i = 0; i < 2; i++) worst = fmax(worst, fabs(PT[i][0] + PT[i][1] + PR[i][0] + PR[i][1] - 1.0));
    }
    printf("  worst |T + R - 1| %.2e on %d stacks\n", worst, n);
    CHECK(worst < 1e-9);
}

/* A one-layer stack is the slab: the same interface solves, the same recursion (1e-12). */
static void one_layer_stack_equals_slab(void)
{
    test_rng r = {0x51ab0001ULL};
    double worst = 0.0;
    for (int k = 0; k < 2000; k++) {
        biref_slab slab;
        double A[3];
        test_random_axis(&r, A);
        slab.eta_o = test_uniform(&r, 1.3, 2.0);
        slab.eta_e = slab.eta_o + test_uniform(&r, -0.3, 0.3);
        memcpy(slab.axis, A, sizeof A);
        slab.thickness_nm = exp(test_uniform(&r, log(500.0), log(2e6)));
        slab.eta_i = test_uniform(&r, 0, 1) < 0.5 ? 1.0 : 1.6;
        double theta = test_uniform(&r, 0, 89) * M_PI / 180, lambda = test_uniform(&r, 380, 700);
        biref_stack s;
        biref_stack_from_slab(&slab, &s);
        biref_jones T1, R1, T2, R2;
        CHECK(biref_slab_jones(&slab, theta, lambda, &T1, &R1) == BIREF_OK);
        CHECK(biref_stack_jones(&s, theta, lambda, &T2, &R2) == BIREF_OK);
        worst = fmax(worst, fmax(jones_diff(&T1, &T2), jones_diff(&R1, &R2)));
    }
    printf("  worst amplitude difference stack vs slab %.2e\n", worst);
    CHECK(worst < 1e-12);
}

/* Cutting a layer into two identical halves changes nothing (the interface between them reflects
 * nothing and transmits each mode into itself). */
static void splitting_a_layer_changes_nothing(void)
{
    test_rng r = {0x5b117ULL};
    double worst = 0.0;
    for (int k = 0; k < 500; k++) {
        biref_stack s, t;
        double theta, lambda;
        random_stack(&r, &s, &theta, &lambda);
        if (s.n_layers == BIREF_STACK_MAX_LAYERS) continue;
        int cut = (int)test_uniform(&r, 0, s.n_layers);
        t = s;
        t.n_layers = s.n_layers + 1;
        for (int i = s.n_layers; i > cut; i--) t.layers[i] = t.layers[i - 1];
        double f = test_uniform(&r, 0.1, 0.9);
        t.layers[cut].thickness_nm = f * s.layers[cut].thickness_nm;
        t.layers[cut + 1].thickness_nm = (1 - f) * s.layers[cut].thickness_nm;
        biref_jones T1, R1, T2, R2;
        CHECK(biref_stack_jones(&s, theta, lambda, &T1, &R1) == BIREF_OK);
        CHECK(biref_stack_jones(&t, theta, lambda, &T2, &R2) == BIREF_OK);
        worst = fmax(worst, fmax(jones_diff(&T1, &T2), jones_diff(&R1, &R2)));
    }
    printf("  worst amplitude difference after a split %.2e\n", worst);
    CHECK(worst < 1e-10);
}

/* Against the product of the layers' 4x4 Berreman matrices (numerical eigenvectors, no modes,
 * no interface solves): random stacks, wherever the transfer matrix trusts itself. */
static void stack_equals_transfer_matrix_product(void)
{
    test_rng r = {0x7a4e5ULL};
    int n = test_quick() ? 300 : 1500, compared = 0, evanescent = 0;
    double worst = 0.0;
    for (int k = 0; k < n; k++) {
        biref_stack s;
        double theta, lambda;
        random_stack(&r, &s, &theta, &lambda);
        if (k % 3 == 0) { /* thin layers under a dense surround: evanescent modes that still couple */
            s.eta_i = 1.8;
            theta = test_uniform(&r, 50, 85) * M_PI / 180;
            for (int i = 0; i < s.n_layers; i++) s.layers[i].thickness_nm = test_uniform(&r, 10, 300);
        }
        biref_jones T1, R1, T2, R2;
        if (biref_stack_jones_tmm(&s, theta, lambda, &T2, &R2) != BIREF_OK) continue;
        biref_stack_state st;
        CHECK(biref_stack_prepare(&s, theta, &st) == BIREF_OK);
        biref_stack_jones_at(&st, lambda, &T1, &R1);
        worst = fmax(worst, fmax(jones_diff(&T1, &T2), jones_diff(&R1, &R2)));
        compared++;
        evanescent += st.evanescent > 0;
    }
    printf("  worst amplitude difference vs 4x4 product %.2e (%d stacks, %d with evanescent layers)\n", worst,
           compared, evanescent);
    CHECK(compared > n / 2 && evanescent > n / 6);
    CHECK(worst < 1e-9);
}

/* Total reflection inside: a dense surround, a rare isotropic layer (frustrated total reflection
 * across a gap between two plates) conserves energy and matches the 4x4 product. */
static void frustrated_total_reflection_in_a_gap(void)
{
    biref_stack s = matched_stack();
    s.eta_i = 1.7;
    s.n_layers = 3;
    s.layers[0] = (biref_layer){1.65, 1.55, {0.3, 0.4, 0.8}, 2000.0, 0, NULL};
    s.layers[1] = (biref_layer){1.0, 1.0, {0, 1, 0}, 120.0, 1, NULL};
    s.layers[2] = (biref_layer){1.6, 1.7, {0.9, 0.1, 0.2}, 3000.0, 0, NULL};
    double theta = 50 * M_PI / 180;
    biref_jones T, R, T2, R2;
    CHECK(biref_stack_jones(&s, theta, 520, &T, &R) == BIREF_OK);
    CHECK(biref_stack_jones_tmm(&s, theta, 520, &T2, &R2) == BIREF_OK);
    CHECK(jones_diff(&T, &T2) < 1e-9 && jones_diff(&R, &R2) < 1e-9);
    double PT[2][2], PR[2][2];
    biref_jones_intensity(&T, PT);
    biref_jones_intensity(&R, PR);
    for (int i = 0; i < 2; i++) {
        CHECK_NEAR(PT[i][0] + PT[i][1] + PR[i][0] + PR[i][1], 1.0, 1e-10);
        CHECK(PT[i][0] + PT[i][1] > 0.01); /* the gap is thin: light tunnels */
    }
    /* A thick gap reflects everything; the recursion stays finite (only decaying exponentials). */
    s.layers[1].thickness_nm = 1e6;
    CHECK(biref_stack_jones(&s, theta, 520, &T, &R) == BIREF_OK);
    biref_jones_intensity(&R, PR);
    for (int i = 0; i < 2; i++) CHECK_NEAR(PR[i][0] + PR[i][1], 1.0, 1e-12);
}

static int parse_fails(const char *text, const char *expect)
{
    biref_stack s;
    char msg[BIREF_MSG_SIZE] = "";
    biref_status st = biref_stack_parse(text, strlen(text), &s, msg, sizeof msg);
    if (st == BIREF_OK || !strstr(msg, expect)) {
        fprintf(stderr, "  '%s': status %d, message '%s' (expected '%s')\n", text, st, msg, expect);
        return 0;
    }
    return 1;
}

static void stack_files_are_strict(void)
{
    const char *good = "{\"eta_i\": 1.33, \"layers\": [{\"eta\": 1.5, \"thickness_mm\": 1},"
                       " {\"eta_o\": 1.54, \"eta_e\": 1.55, \"azimuth_deg\": 90, \"thickness_um\": 25},"
                       " {\"eta_o\": 1.6, \"eta_e\": 1.5, \"axis\": [0, 2, 0], \"thickness_nm\": 300}]}";
    biref_stack s;
    char msg[BIREF_MSG_SIZE] = "";
    CHECK(biref_stack_parse(good, strlen(good), &s, msg, sizeof msg) == BIREF_OK);
    CHECK(s.n_layers == 3 && s.eta_i == 1.33 && s.layers[0].isotropic && s.layers[0].thickness_nm == 1e6);
    CHECK(fabs(s.layers[1].axis[0]) < 1e-15 && s.layers[1].axis[2] == 1.0 && s.layers[1].thickness_nm == 25e3);
    CHECK(s.layers[2].axis[1] == 2.0 && s.layers[2].thickness_nm == 300.0);
    CHECK(parse_fails("{\"layers\": []}", "layers: expected an array of 1 to 64 layers"));
    CHECK(parse_fails("{\"layers\": [{\"eta\": 1.5}]}", "layers[0].thickness_um: missing"));
    CHECK(parse_fails("{\"layers\": [{\"eta\": 1.5, \"thickness_um\": 1, \"thickness_mm\": 1}]}", "given twice"));
    CHECK(parse_fails("{\"layers\": [{\"eta\": 1.5, \"eta_e\": 1.6, \"thickness_um\": 1}]}",
                      "layers[0].eta_e: an isotropic layer"));
    CHECK(parse_fails("{\"layers\": [{\"eta_o\": 1.5, \"eta_e\": 1.6, \"thickness_um\": 1}]}",
                      "layers[0].axis: missing"));
    CHECK(parse_fails("{\"layers\": [{\"eta_o\": 1.5, \"eta_e\": 1.6, \"axis\": [0,0,0], \"thickness_um\": 1}]}",
                      "non-zero"));
    CHECK(parse_fails("{\"layers\": [{\"eta\": -1, \"thickness_um\": 1}]}", "layers[0].eta: must be positive"));
    CHECK(parse_fails("{\"layers\": [{\"eta\": 1.5, \"thickness_um\": 1, \"thikness\": 2}]}", "unknown field"));
    CHECK(parse_fails("{\"eta_i\": 0, \"layers\": [{\"eta\": 1.5, \"thickness_um\": 1}]}", "eta_i: must be positive"));
    CHECK(parse_fails("{\"layers\": [{\"eta\": 1.5, \"thickness_um\": 1}], \"x\": 1}", "x: unknown field"));
    CHECK(parse_fails("{\"layers\": [{\"eta\": 1.5, \"thickness_um\": 1e308}]}", "too large"));
    CHECK(parse_fails("[1]", "expected a JSON object"));
    biref_stack bad;
    memset(&bad, 0, sizeof bad);
    bad.eta_i = 1;
    bad.n_layers = BIREF_STACK_MAX_LAYERS + 1;
    CHECK(biref_stack_check(&bad, msg, sizeof msg) == BIREF_ERR_INVALID && strstr(msg, "1 to 64 layers"));
    biref_stack_state st;
    CHECK(biref_stack_prepare(&bad, 0.1, &st) == BIREF_ERR_INVALID);
    CHECK(biref_stack_jones(&s, 0.1, -1.0, NULL, NULL) == BIREF_ERR_INVALID);
    CHECK(biref_stack_jones(&s, M_PI / 2, 500.0, NULL, NULL) == BIREF_ERR_INVALID);
    CHECK(biref_stack_load("/nonexistent/stack.json", &s, msg, sizeof msg) == BIREF_ERR_IO);
}

static const test_case CASES[] = {
    {"one_plate_crossed_polarizers", one_plate_crossed_polarizers},
    {"lyot_filter", lyot_filter},
    {"solc_folded_filter", solc_folded_filter},
    {"two_plates_crossed_polarizers", two_plates_crossed_polarizers},
    {"energy_conserved_on_random_stacks", energy_conserved_on_random_stacks},
    {"one_layer_stack_equals_slab", one_layer_stack_equals_slab},
    {"splitting_a_layer_changes_nothing", splitting_a_layer_changes_nothing},
    {"stack_equals_transfer_matrix_product", stack_equals_transfer_matrix_product},
    {"frustrated_total_reflection_in_a_gap", frustrated_total_reflection_in_a_gap},
    {"stack_files_are_strict", stack_files_are_strict},
};

int main(int argc, char **argv) { return test_run_cases("test_stack", CASES, TEST_COUNT(CASES), argc, argv); }
