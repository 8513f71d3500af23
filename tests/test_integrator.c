/* The integrator and the light model against the method entry points they wrap, and physical
 * checks through them: energy conservation and the lossless isotropic limit. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "test_cases.h"

static biref_spectral *sp;

static const biref_slab SLAB = {1.775, 1.231, {0.084, 0.979, -0.187}, 20000.0, 1.0};

static biref_integrator *make(biref_method m, int samples)
{
    biref_integrator_options o;
    biref_integrator_options_default(&o);
    o.method = m;
    if (samples) o.samples = samples;
    biref_integrator *it = NULL;
    CHECK(biref_integrator_create(sp, &o, &it, NULL, 0) == BIREF_OK);
    return it;
}

static int same3(const double a[3], const double b[3]) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

static void options_are_checked(void)
{
    biref_integrator_options o;
    biref_integrator *it = (biref_integrator *)&o; /* must be reset to NULL on failure */
    biref_integrator_options_default(&o);
    CHECK(o.method == BIREF_METHOD_ANALYTIC && o.samples == 64 && o.expansion.order == -1);
    o.method = BIREF_METHOD_NUMERIC;
    o.samples = 0;
    CHECK(biref_integrator_create(sp, &o, &it, NULL, 0) == BIREF_ERR_INVALID && it == NULL);
    o.samples = BIREF_NUMERIC_MAX_SAMPLES + 1;
    CHECK(biref_integrator_create(sp, &o, &it, NULL, 0) == BIREF_ERR_INVALID);
    o.method = BIREF_METHOD_EXPANSION;
    o.expansion.order = BIREF_EXPANSION_MAX_ORDER + 1;
    CHECK(biref_integrator_create(sp, &o, &it, NULL, 0) == BIREF_ERR_INVALID);
    o.expansion.order = -1;
    o.expansion.tolerance = 1.0;
    CHECK(biref_integrator_create(sp, &o, &it, NULL, 0) == BIREF_ERR_INVALID);
    o.method = (biref_method)42;
    CHECK(biref_integrator_create(sp, &o, &it, NULL, 0) == BIREF_ERR_INVALID);
    CHECK(biref_integrator_create(NULL, &o, &it, NULL, 0) == BIREF_ERR_INVALID);
    it = make(BIREF_METHOD_GROUND_TRUTH, 0);
    CHECK(biref_integrator_method(it) == BIREF_METHOD_GROUND_TRUTH);
    CHECK(biref_integrator_samples(it) == BIREF_GROUND_TRUTH_SAMPLES);
    biref_integrator_destroy(it);
    it = make(BIREF_METHOD_NUMERIC, 12);
    CHECK(biref_integrator_samples(it) == 12);
    biref_integrator_destroy(it);
    biref_integrator_destroy(NULL);
}

static void light_constructors_set_coherency_and_analyzer_and_refuse_bad_input(void)
{
    biref_light l;
    const double w[2] = {0.3, 0.7}, none[2] = {1, 1}, s_only[2] = {1, 0};
    CHECK(biref_light_sp(w, none, &l) == BIREF_OK);
    CHECK(l.sp_model && !l.has_analyzer && creal(l.C[0][0]) == 0.3 && creal(l.C[1][1]) == 0.7 && l.C[0][1] == 0);
    CHECK(biref_light_sp(w, s_only, &l) == BIREF_OK);
    CHECK(l.sp_model && l.has_analyzer && l.P[0][0] == 1.0 && l.P[1][1] == 0.0);
    const double bad_w[2] = {-0.1, 1.1}, bad_mask[2] = {1, 2}, nan_w[2] = {NAN, 1};
    CHECK(biref_light_sp(bad_w, none, &l) == BIREF_ERR_INVALID);
    CHECK(biref_light_sp(w, bad_mask, &l) == BIREF_ERR_INVALID);
    CHECK(biref_light_sp(nan_w, none, &l) == BIREF_ERR_INVALID);
    const double S[4] = {1, 0.2, 0.3, 0.4}, unphysical[4] = {1, 1, 1, 0};
    CHECK(biref_light_stokes(S, &l) == BIREF_OK);
    CHECK(!l.sp_model && !l.has_analyzer && fabs(creal(l.C[0][1]) - 0.15) < 1e-15 && fabs(cimag(l.C[0][1]) + 0.2) < 1e-15);
    CHECK(biref_light_stokes(unphysical, &l) == BIREF_ERR_INVALID);
    double X[2][2][3] = {{{1, 2, 3}, {4, 5, 6}}, {{7, 8, 9}, {10, 11, 12}}}, xyz[3];
    CHECK(biref_light_stokes(S, &l) == BIREF_OK);
    CHECK(biref_light_mix(&l, (const double(*)[2][3])X, xyz) == BIREF_ERR_INVALID);
    CHECK(biref_light_sp(w, s_only, &l) == BIREF_OK);
    CHECK(biref_light_mix(&l, (const double(*)[2][3])X, xyz) == BIREF_OK);
    CHECK(xyz[0] == 0.3 * 1 + 0.7 * 7 && xyz[2] == 0.3 * 3 + 0.7 * 9);
    /* A general analyzer leaves the paper's model; removing it keeps the incident light. */
    double complex P[2][2];
    biref_analyzer_linear(0.3, P);
    biref_light_set_analyzer(&l, (const double complex(*)[2])P);
    CHECK(!l.sp_model && l.has_analyzer);
    CHECK(biref_light_sp(w, s_only, &l) == BIREF_OK);
    biref_light_set_analyzer(&l, NULL);
    CHECK(l.sp_model && !l.has_analyzer && l.mask[1] == 1.0);
}

/* Every method through biref_integrate equals its entry point (same arithmetic, bit for bit). */
static void integrate_equals_entry_points(void)
{
    biref_slab_state st;
    CHECK(biref_slab_prepare(&SLAB, 0.6, &st) == BIREF_OK);
    biref_light l;
    const double w[2] = {0.02, 0.98}, mask[2] = {1, 0};
    CHECK(biref_light_sp(w, mask, &l) == BIREF_OK);
    biref_integration r;
    biref_spectrum x;
    double T[3], R[3];

    biref_integrator *an = make(BIREF_METHOD_ANALYTIC, 0);
    CHECK(biref_integrate(an, &st, BIREF_SIDE_BOTH, &l, &r) == BIREF_OK);
    biref_spectrum_analytic(sp, &st, &x);
    biref_spectrum_mix(x.T, w, mask, T);
    biref_spectrum_mix(x.R, w, mask, R);
    CHECK(same3(r.T, T) && same3(r.R, R) && r.order_used[0] == -1);
    CHECK(biref_integrate_spectrum(an, &st, &x) == BIREF_OK);
    biref_integration rt;
    CHECK(biref_integrate(an, &st, BIREF_SIDE_REFLECTION, &l, &rt) == BIREF_OK && same3(rt.R, R));
    biref_integrator_destroy(an);

    biref_integrator *nu = make(BIREF_METHOD_NUMERIC, 37);
    biref_numeric_plan *plan = NULL;
    CHECK(biref_numeric_plan_create(sp, 37, &plan, NULL, 0) == BIREF_OK);
    CHECK(biref_integrate(nu, &st, BIREF_SIDE_BOTH, &l, &r) == BIREF_OK);
    biref_spectrum_numeric(plan, &st, &x);
    biref_spectrum_mix(x.T, w, mask, T);
    biref_spectrum_mix(x.R, w, mask, R);
    CHECK(same3(r.T, T) && same3(r.R, R));
    /* One side alone goes through the polarized integral: equal to rounding. */
    CHECK(biref_integrate(nu, &st, BIREF_SIDE_TRANSMISSION, &l, &rt) == BIREF_OK);
    for (int j = 0; j < 3; j++) CHECK_NEAR(rt.T[j], T[j], 1e-14);
    double S[4] = {1, 0.1, -0.5, 0.6}, G[3];
    double complex C[2][2], P[2][2];
    biref_stokes_to_coherency(S, C);
    biref_analyzer_circular(-1, P);
    CHECK(biref_light_stokes(S, &l) == BIREF_OK);
    biref_light_set_analyzer(&l, (const double complex(*)[2])P);
    CHECK(biref_integrate(nu, &st, BIREF_SIDE_BOTH, &l, &r) == BIREF_OK);
    biref_spectrum_numeric_polarized(plan, &st, BIREF_REFLECTION, (const double complex(*)[2])C,
                                     (const double complex(*)[2])P, G);
    CHECK(same3(r.R, G));
    biref_numeric_plan_destroy(plan);
    biref_integrator_destroy(nu);

    biref_integrator *ex = make(BIREF_METHOD_EXPANSION, 0);
    biref_expansion_opts xo;
    biref_expansion_opts_default(&xo);
    int order = -2;
    CHECK(biref_integrate(ex, &st, BIREF_SIDE_BOTH, &l, &r) == BIREF_OK);
    CHECK(biref_spectrum_expansion_polarized(sp, &st, BIREF_TRANSMISSION, (const double complex(*)[2])C,
                                             (const double complex(*)[2])P, &xo, G, &order) == BIREF_OK);
    CHECK(same3(r.T, G) && r.order_used[0] == order && r.order_used[1] >= 0);
    biref_spectrum y;
    CHECK(biref_integrate_spectrum(ex, &st, &x) == BIREF_OK);
    CHECK(biref_spectrum_expansion(sp, &st, &xo, &y) == BIREF_OK);
    CHECK(!memcmp(&x, &y, sizeof x));
    biref_integrator_destroy(ex);
}

static void integrate_refuses_unsupported_light_and_bad_sides(void)
{
    biref_slab_state st;
    CHECK(biref_slab_prepare(&SLAB, 0.3, &st) == BIREF_OK);
    biref_light l;
    const double S[4] = {1, 0, 1, 0};
    CHECK(biref_light_stokes(S, &l) == BIREF_OK);
    biref_integration r;
    biref_integrator *an = make(BIREF_METHOD_ANALYTIC, 0);
    /* Every method takes every light (the analytic method through its general terms); only a
     * request for no side or an unknown one is refused. */
    CHECK(biref_integrate(an, &st, BIREF_SIDE_TRANSMISSION, &l, &r) == BIREF_OK);
    const double w[2] = {0.5, 0.5}, m[2] = {1, 1};
    CHECK(biref_light_sp(w, m, &l) == BIREF_OK);
    CHECK(biref_integrate(an, &st, (biref_sides)0, &l, &r) == BIREF_ERR_INVALID);
    CHECK(biref_integrate(an, &st, (biref_sides)4, &l, &r) == BIREF_ERR_INVALID);
    biref_integrator_destroy(an);
}

/* A lossless slab, unpolarized light, no analyzer: T + R = 1 in every band (exact for the
 * numeric and expansion methods), and an isotropic slab at normal incidence gives the Airy
 * average: T = 2n / (n^2 + 1) once the fringes average out over the band. */
static void energy_is_conserved_and_isotropic_slab_is_airy(void)
{
    biref_light l;
    const double w[2] = {0.5, 0.5}, m[2] = {1, 1};
    CHECK(biref_light_sp(w, m, &l) == BIREF_OK);
    const biref_method methods[2] = {BIREF_METHOD_NUMERIC, BIREF_METHOD_EXPANSION};
    for (int k = 0; k < 2; k++) {
        biref_integrator *it = make(methods[k], 512);
        for (double theta = 0.0; theta < 1.5; theta += 0.35) {
            biref_slab_state st;
            CHECK(biref_slab_prepare(&SLAB, theta, &st) == BIREF_OK);
            biref_integration r;
            CHECK(biref_integrate(it, &st, BIREF_SIDE_BOTH, &l, &r) == BIREF_OK);
            for (int j = 0; j < 3; j++) CHECK_NEAR(r.T[j] + r.R[j], 1.0, k ? 2e-3 : 1e-9);
        }
        const double n = 1.5;
        const biref_slab iso = {n, n, {0, 1, 0}, 3e6, 1.0};
        biref_slab_state st;
        CHECK(biref_slab_prepare(&iso, 0.0, &st) == BIREF_OK);
        biref_integration r;
        CHECK(biref_integrate(it, &st, BIREF_SIDE_TRANSMISSION, &l, &r) == BIREF_OK);
        if (k == 1)
            for (int j = 0; j < 3; j++) CHECK_NEAR(r.T[j], 2 * n / (n * n + 1), 1e-3);
        biref_integrator_destroy(it);
    }
}

/* Within rounding: the analytic batch runs the packet kernel (contracted multiply-adds on
 * AVX2/AVX-512), the single call the scalar worker. */
static int close3(const double a[3], const double b[3])
{
    for (int j = 0; j < 3; j++)
        if (!(fabs(a[j] - b[j]) <= 1e-12 * fmax(1.0, fabs(b[j])))) return 0;
    return 1;
}

/* The batch call equals one call per state, with one light or a light per state. */
static void batch_equals_single_calls_and_bad_stride_is_refused(void)
{
    enum { N = 7 };
    biref_slab_state st[N];
    biref_light l[N];
    for (int i = 0; i < N; i++) {
        CHECK(biref_slab_prepare(&SLAB, 0.2 * i, &st[i]) == BIREF_OK);
        const double w[2] = {0.1 * i, 1 - 0.1 * i}, m[2] = {1, i % 2};
        CHECK(biref_light_sp(w, m, &l[i]) == BIREF_OK);
    }
    biref_integrator *it = make(BIREF_METHOD_ANALYTIC, 0);
    biref_integration out[N], one;
    biref_status status[N];
    for (size_t stride = 0; stride < 2; stride++) {
        CHECK(biref_integrate_batch(it, st, N, BIREF_SIDE_BOTH, l, stride, out, status) == BIREF_OK);
        for (int i = 0; i < N; i++) {
            CHECK(status[i] == BIREF_OK);
            CHECK(biref_integrate(it, &st[i], BIREF_SIDE_BOTH, &l[i * stride], &one) == BIREF_OK);
            CHECK(close3(out[i].T, one.T) && close3(out[i].R, one.R));
        }
    }
    CHECK(biref_integrate_batch(it, st, N, BIREF_SIDE_BOTH, l, 2, out, NULL) == BIREF_ERR_INVALID);
    biref_integrator_destroy(it);
}

/* The polariscope through the integrator equals the photoelastic entry points of each method. */
static void photoelastic_shading_through_integrator_equals_direct_paths(void)
{
    biref_pe_setup s;
    memset(&s, 0, sizeof s);
    CHECK(biref_pe_material_preset("polycarbonate", &s.material) == BIREF_OK);
    s.thickness = 3e-3;
    s.eta_i = 1.0;
    s.light = BIREF_PE_WHITE;
    biref_pe_polariscope_make(BIREF_PE_CIRCULAR, BIREF_PE_DARK, 0.3, &s.pol);
    biref_pe_principal p = {1.5e6, -0.5e6, 0.4, cos(0.8), sin(0.8)};
    double a[3], b[3];
    biref_integrator *ex = make(BIREF_METHOD_EXPANSION, 0);
    CHECK(biref_pe_shade_integrated(&s, ex, &p, 0.0, a) == BIREF_OK);
    CHECK(biref_pe_shade_general(&s, sp, &p, 0, 0, b) == BIREF_OK);
    CHECK(same3(a, b));
    CHECK(biref_pe_shade_integrated(&s, ex, &p, 0.4, a) == BIREF_OK);
    CHECK(biref_pe_shade_oblique(&s, sp, &p, 0.4, b) == BIREF_OK);
    CHECK(same3(a, b));
    biref_integrator *gt = make(BIREF_METHOD_GROUND_TRUTH, 0);
    /* The ground truth is the numeric method on the same plate and light. */
    biref_numeric_plan *plan = NULL;
    CHECK(biref_numeric_plan_create(sp, BIREF_GROUND_TRUTH_SAMPLES, &plan, NULL, 0) == BIREF_OK);
    CHECK(biref_pe_shade_integrated(&s, gt, &p, 0.0, a) == BIREF_OK);
    const biref_slab slab = biref_pe_slab_at(&s.material, s.thickness, s.eta_i, &p);
    biref_slab_state st;
    CHECK(biref_slab_prepare(&slab, 0.0, &st) == BIREF_OK);
    biref_spectrum_numeric_polarized(plan, &st, BIREF_TRANSMISSION, (const biref_complex(*)[2])s.pol.C,
                                     (const biref_complex(*)[2])s.pol.P, b);
    CHECK(same3(a, b));
    biref_integrator *an = make(BIREF_METHOD_ANALYTIC, 0);
    /* The polariscope is a general light: the analytic method integrates it (its general terms)
     * close to the ground truth b. */
    double c[3];
    CHECK(biref_pe_shade_integrated(&s, an, &p, 0.0, c) == BIREF_OK);
    printf("polariscope, analytic vs ground truth: dE00 %.3g\n", biref_delta_e00_xyz(c, b));
    CHECK(biref_delta_e00_xyz(c, b) < 0.5);
    s.light = BIREF_PE_MONO;
    CHECK(biref_pe_shade_integrated(&s, ex, &p, 0.0, a) == BIREF_ERR_INVALID);
    biref_numeric_plan_destroy(plan);
    biref_integrator_destroy(an);
    biref_integrator_destroy(gt);
    biref_integrator_destroy(ex);
}

/* The s/p analyzer's mask is a power transmittance: the detected colour is linear in it, so a
 * mask (a, b) gives a times the s-only colour plus b times the p-only colour, for every method
 * and both sides. (A mask used as a Jones amplitude would weight by a^2 and b^2.) */
static void fractional_mask_weights_power_for_every_method(void)
{
    biref_slab_state st;
    CHECK(biref_slab_prepare(&SLAB, 0.6, &st) == BIREF_OK);
    const double w[2] = {0.3, 0.7}, m[2] = {0.25, 0.6}, s_only[2] = {1, 0}, p_only[2] = {0, 1};
    const biref_method methods[3] = {BIREF_METHOD_ANALYTIC, BIREF_METHOD_NUMERIC, BIREF_METHOD_EXPANSION};
    for (int k = 0; k < 3; k++) {
        biref_integrator *it = make(methods[k], 64);
        biref_light l;
        biref_integration r, rs, rp;
        CHECK(biref_light_sp(w, m, &l) == BIREF_OK);
        CHECK(biref_integrate(it, &st, BIREF_SIDE_BOTH, &l, &r) == BIREF_OK);
        CHECK(biref_light_sp(w, s_only, &l) == BIREF_OK);
        CHECK(biref_integrate(it, &st, BIREF_SIDE_BOTH, &l, &rs) == BIREF_OK);
        CHECK(biref_light_sp(w, p_only, &l) == BIREF_OK);
        CHECK(biref_integrate(it, &st, BIREF_SIDE_BOTH, &l, &rp) == BIREF_OK);
        for (int j = 0; j < 3; j++) {
            CHECK_NEAR(r.T[j], m[0] * rs.T[j] + m[1] * rp.T[j], 1e-12);
            CHECK_NEAR(r.R[j], m[0] * rs.R[j] + m[1] * rp.R[j], 1e-12);
        }
        biref_integrator_destroy(it);
    }
}

int main(int argc, char **argv)
{
    biref_spectral_config cfg;
    biref_spectral_config_default(&cfg);
    if (biref_spectral_create(&cfg, &sp, NULL, 0) != BIREF_OK) return 1;
    static const test_case cases[] = {
        {"options_are_checked", options_are_checked},
        {"light_constructors_set_coherency_and_analyzer_and_refuse_bad_input",
         light_constructors_set_coherency_and_analyzer_and_refuse_bad_input},
        {"integrate_equals_entry_points", integrate_equals_entry_points},
        {"integrate_refuses_unsupported_light_and_bad_sides", integrate_refuses_unsupported_light_and_bad_sides},
        {"energy_is_conserved_and_isotropic_slab_is_airy", energy_is_conserved_and_isotropic_slab_is_airy},
        {"fractional_mask_weights_power_for_every_method", fractional_mask_weights_power_for_every_method},
        {"batch_equals_single_calls_and_bad_stride_is_refused", batch_equals_single_calls_and_bad_stride_is_refused},
        {"photoelastic_shading_through_integrator_equals_direct_paths",
         photoelastic_shading_through_integrator_equals_direct_paths},
    };
    int rc = test_run_cases("test_integrator", cases, TEST_COUNT(cases), argc, argv);
    biref_spectral_destroy(sp);
    return rc;
}
