/* Dispersion of birefringence in photoelasticity (docs/PHOTOELASTICITY.md, "Dispersion of
 * birefringence"): the law C(λ) = C (λref/λ)^alpha and the fringe constant, alpha = 0 giving the
 * pictures of a constant C exactly, the white-light fast path against an independent sum over
 * wavelengths of the slab's own Jones matrices (eq. 17) with C(λ), monochromatic light with C at
 * its wavelength, the colours moving with alpha, and the refusal of tilted white views. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "spectral/spectral_internal.h"
#include "test_cases.h"

static biref_spectral *context(void)
{
    static biref_spectral *sp;
    if (!sp && biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK) abort();
    return sp;
}

static biref_pe_setup setup(biref_pe_light_kind light, double alpha, double eta_i)
{
    biref_pe_setup s;
    memset(&s, 0, sizeof s);
    (void)biref_pe_material_preset("polycarbonate", &s.material);
    s.material.dispersion_alpha = alpha;
    s.thickness = 6e-3;
    s.eta_i = eta_i;
    s.light = light;
    s.lambda_nm = 589.0;
    biref_pe_polariscope_make(BIREF_PE_CIRCULAR, BIREF_PE_DARK, 0.0, &s.pol);
    return s;
}

/* Principal stresses of retardation delta_nm at the reference wavelength, direction phi. */
static biref_pe_principal principal(const biref_pe_setup *s, double delta_nm, double phi)
{
    biref_pe_principal p = {delta_nm / (s->material.C_per_Pa * s->thickness * 1e9), 0.0, phi, cos(2 * phi), sin(2 * phi)};
    return p;
}

static void law_and_fringe_constant(void)
{
    biref_pe_material m;
    CHECK(biref_pe_material_preset("epoxy", &m) == BIREF_OK);
    CHECK(m.dispersion_alpha == 0.0 && m.lambda_ref_nm == BIREF_PE_LAMBDA_REF_NM);
    CHECK(biref_pe_C_at(&m, 400.0) == m.C_per_Pa); /* no dispersion: the same bits everywhere */
    m.dispersion_alpha = 0.3;
    CHECK_NEAR(biref_pe_C_at(&m, BIREF_PE_LAMBDA_REF_NM), m.C_per_Pa, 1e-27);
    CHECK_NEAR(biref_pe_C_at(&m, 450.0) / m.C_per_Pa, pow(546.1 / 450.0, 0.3), 1e-15);
    CHECK_NEAR(biref_pe_C_at(&m, 650.0) / m.C_per_Pa, 0.949090, 1e-6); /* (546.1 / 650)^0.3 */
    /* f(λ) = λ / C(λ) grows as λ^(1 + alpha): two fringe values give alpha back. */
    const double f1 = biref_pe_fringe_constant(&m, 480.0), f2 = biref_pe_fringe_constant(&m, 640.0);
    CHECK_NEAR(log(f2 / f1) / log(640.0 / 480.0) - 1.0, 0.3, 1e-12);
    m.lambda_ref_nm = 600.0;
    CHECK_NEAR(biref_pe_C_at(&m, 600.0), m.C_per_Pa, 1e-27);
    char msg[128];
    m.dispersion_alpha = 5.0;
    CHECK(biref_pe_material_check(&m, msg, sizeof msg) == BIREF_ERR_INVALID && strstr(msg, "alpha"));
    m.dispersion_alpha = NAN;
    CHECK(biref_pe_material_check(&m, msg, sizeof msg) == BIREF_ERR_INVALID);
    m.dispersion_alpha = 0.2;
    m.lambda_ref_nm = 50.0;
    CHECK(biref_pe_material_check(&m, msg, sizeof msg) == BIREF_ERR_INVALID && strstr(msg, "reference wavelength"));
}

/* alpha = 0 written out (and a reference wavelength that then does not matter) renders the
 * presets' pictures bit for bit: white and mono, point-sampled and prefiltered. */
static void alpha_zero_is_todays_picture(void)
{
    biref_pe_field f;
    CHECK(biref_pe_field_disk(&f, 25e-3, 6e-3, 500.0, NULL, 0) == BIREF_OK);
    biref_pe_image_opts o;
    memset(&o, 0, sizeof o);
    o.width = o.height = test_quick() ? 24 : 64;
    o.supersample = 2;
    o.threads = 1;
    o.tint[0] = o.tint[1] = o.tint[2] = 1.0;
    const size_t n = (size_t)o.width * o.height * 3;
    float *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    for (int light = 0; light < 2; light++)
        for (int pre = 0; pre < 2; pre++) {
            biref_pe_setup s0 = setup((biref_pe_light_kind)light, 0.0, 1.0), s1 = s0;
            (void)biref_pe_material_preset("polycarbonate", &s0.material); /* the preset as it is */
            s1.material.lambda_ref_nm = 700.0;
            s1.material.dispersion_alpha = 0.0;
            biref_status r0 = pre ? biref_pe_render_prefiltered(&s0, context(), &f, &o, a, NULL, 0)
                                  : biref_pe_render(&s0, context(), &f, &o, a, NULL, 0);
            biref_status r1 = pre ? biref_pe_render_prefiltered(&s1, context(), &f, &o, b, NULL, 0)
                                  : biref_pe_render(&s1, context(), &f, &o, b, NULL, 0);
            CHECK(r0 == BIREF_OK && r1 == BIREF_OK);
            CHECK(memcmp(a, b, n * sizeof *a) == 0);
        }
    free(a);
    free(b);
}

/* |e J P|^2 summed over the polariscope's coherency. */
static double detect(const biref_pe_polariscope *pol, const biref_jones *J)
{
    double complex sum = 0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int o = 0; o < 2; o++) {
                double complex a = J->m[i][0] * pol->P[0][o] + J->m[i][1] * pol->P[1][o];
                double complex b = J->m[j][0] * pol->P[0][o] + J->m[j][1] * pol->P[1][o];
                sum += pol->C[i][j] * a * conj(b);
            }
    return creal(sum);
}

/* The white-light fast path with alpha against the band sum of the slab's closed-form Jones
 * matrix (eq. 17) with eta_e = n0 + C(λ) (s1 - s2) at each of 16384 wavelengths, in an
 * index-matched surround (no Fabry-Perot ripple for the samples to resolve). */
static void white_matches_slab_sum_over_wavelengths(void)
{
    biref_spectral *sp = context();
    biref_numeric_plan *plan;
    CHECK(biref_numeric_plan_create(sp, test_quick() ? 4096 : 16384, &plan, NULL, 0) == BIREF_OK);
    static const double alphas[] = {0.15, 0.4, -0.2};
    static const double deltas[] = {180.0, 700.0, 1500.0, 3200.0};
    double worst = 0.0, worst_de = 0.0;
    int failed = 0;
    for (int ia = 0; ia < 3; ia++)
        for (int id = 0; id < 4; id++) {
            biref_pe_setup s = setup(BIREF_PE_WHITE, alphas[ia], 1.586);
            biref_pe_polariscope_make(id % 2 ? BIREF_PE_PLANE : BIREF_PE_CIRCULAR, BIREF_PE_DARK, 0.2, &s.pol);
            biref_pe_principal p = principal(&s, deltas[id], 0.6);
            double fast[3], ref[3] = {0, 0, 0};
            biref_pe_shade(&s, sp, &p, fast);
            for (int n = 0; n < plan->samples; n++) {
                biref_pe_material m = s.material;
                m.C_per_Pa = biref_pe_C_at(&s.material, plan->lambda[n]);
                m.dispersion_alpha = 0.0;
                biref_slab slab = biref_pe_slab_at(&m, s.thickness, s.eta_i, &p);
                biref_jones T;
                failed += biref_slab_jones(&slab, 0.0, plan->lambda[n], &T, NULL) != BIREF_OK;
                const double v = detect(&s.pol, &T);
                for (int j = 0; j < 3; j++) ref[j] += plan->weight[n][j] * v;
            }
            for (int j = 0; j < 3; j++) worst = fmax(worst, fabs(fast[j] - ref[j]));
            worst_de = fmax(worst_de, biref_delta_e00_xyz(fast, ref));
        }
    printf("  white with alpha vs the slab summed over wavelengths: |dXYZ| %.2g, dE00 %.2g\n", worst, worst_de);
    CHECK(failed == 0);
    CHECK(worst < 2e-5);
    CHECK(worst_de < 0.005);
    biref_numeric_plan_destroy(plan);
}

/* Continuity at alpha -> 0: the dispersive sum at alpha 1e-9 is the table's colour. */
static void small_alpha_meets_the_table(void)
{
    double worst = 0.0;
    for (int id = 0; id < 6; id++) {
        biref_pe_setup s0 = setup(BIREF_PE_WHITE, 0.0, 1.0), s1 = setup(BIREF_PE_WHITE, 1e-9, 1.0);
        biref_pe_principal p = principal(&s0, 150.0 + 600.0 * id, 0.3);
        double a[3], b[3];
        biref_pe_shade(&s0, context(), &p, a);
        biref_pe_shade(&s1, context(), &p, b);
        for (int j = 0; j < 3; j++) worst = fmax(worst, fabs(a[j] - b[j]));
    }
    printf("  alpha 1e-9 vs alpha 0: %.2g\n", worst);
    CHECK(worst < 2e-5);
}

/* Monochromatic light sees C at its wavelength: alpha with C is alpha 0 with C(λ). The colours of
 * white light move with alpha (the isochromatic sequence is stretched): at N = 2 by several ΔE00. */
static void mono_uses_C_at_its_wavelength_and_colours_shift(void)
{
    double worst = 0.0;
    for (int k = 0; k < 20; k++) {
        biref_pe_setup s = setup(BIREF_PE_MONO, 0.35, 1.0), c = s;
        s.lambda_nm = c.lambda_nm = 420.0 + 15.0 * k;
        c.material.C_per_Pa = biref_pe_C_at(&s.material, s.lambda_nm);
        c.material.dispersion_alpha = 0.0;
        biref_pe_principal p = principal(&s, 100.0 + 97.0 * k, 0.2 * k);
        double a[3], b[3];
        biref_pe_shade(&s, NULL, &p, a);
        biref_pe_shade(&c, NULL, &p, b);
        worst = fmax(worst, fabs(a[0] - b[0]));
    }
    CHECK(worst <= 1e-15);
    biref_pe_setup s0 = setup(BIREF_PE_WHITE, 0.0, 1.0), s1 = setup(BIREF_PE_WHITE, 0.4, 1.0);
    biref_pe_principal p = principal(&s0, 2 * 550.0, 0.4);
    double a[3], b[3];
    biref_pe_shade(&s0, context(), &p, a);
    biref_pe_shade(&s1, context(), &p, b);
    const double de = biref_delta_e00_xyz(a, b);
    printf("  N = 2: dE00 %.3g between alpha 0 and 0.4\n", de);
    CHECK(de > 3.0);
}

/* A tilted white view cannot take alpha (one slab for the band): refused with one line. */
static void tilted_white_with_alpha_is_refused(void)
{
    biref_pe_field f;
    CHECK(biref_pe_field_disk(&f, 25e-3, 6e-3, 500.0, NULL, 0) == BIREF_OK);
    biref_pe_image_opts o;
    memset(&o, 0, sizeof o);
    o.width = o.height = 8;
    o.supersample = 1;
    o.tilt = 0.3;
    float px[8 * 8 * 3];
    biref_pe_setup s = setup(BIREF_PE_WHITE, 0.2, 1.0);
    char msg[BIREF_MSG_SIZE] = "";
    CHECK(biref_pe_render(&s, context(), &f, &o, px, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(strstr(msg, "normal incidence") != NULL);
    s.light = BIREF_PE_MONO; /* monochromatic: C at the wavelength, any view */
    CHECK(biref_pe_render(&s, context(), &f, &o, px, msg, sizeof msg) == BIREF_OK);
    biref_pe_principal p = principal(&s, 500.0, 0.1);
    double xyz[3];
    s.light = BIREF_PE_WHITE;
    CHECK(biref_pe_shade_general(&s, context(), &p, 1, 0.0, xyz) == BIREF_ERR_INVALID);
}

/* Through the thickness: the stack at a wavelength takes C there. alpha 0: the same layers as
 * biref_pe_stack at any wavelength; alpha 0.3, fixed principal directions, index-matched:
 * crossed polarizers see sin^2 2phi sin^2(Γ(λ)/2), Γ(λ) = 2 pi C(λ) h <s1 - s2> / λ. */
static void through_thickness_takes_C_at_each_wavelength(void)
{
    biref_pe_material m;
    CHECK(biref_pe_material_preset("glass", &m) == BIREF_OK);
    const double h = 6e-3, phi = 0.4;
    enum { N = 8 };
    biref_pe_stress st[N];
    double mean = 0.0;
    for (int k = 0; k < N; k++) {
        const double z = (k + 0.5) / N * 2 - 1, d = 40e6 * (1.5 * z * z - 0.5) + 60e6;
        st[k] = (biref_pe_stress){0.5 * d * (1 + cos(2 * phi)), 0.5 * d * (1 - cos(2 * phi)), 0.5 * d * sin(2 * phi)};
        mean += d / N;
    }
    biref_stack a, b;
    CHECK(biref_pe_stack(&m, h, m.n0, N, st, &a, NULL, 0) == BIREF_OK);
    CHECK(biref_pe_stack_at(&m, h, m.n0, N, st, 430.0, &b, NULL, 0) == BIREF_OK);
    CHECK(memcmp(&a, &b, sizeof a) == 0);
    m.dispersion_alpha = 0.3;
    double worst = 0.0;
    for (int c = 0; c < 8; c++) {
        const double lambda = 400 + 40 * c;
        CHECK(biref_pe_stack_at(&m, h, m.n0, N, st, lambda, &b, NULL, 0) == BIREF_OK);
        biref_jones T;
        CHECK(biref_stack_jones(&b, 0.0, lambda, &T, NULL) == BIREF_OK);
        const double G = 2 * M_PI * biref_pe_C_at(&m, lambda) * mean * h / (lambda * 1e-9);
        const double t = creal(T.m[0][1] * conj(T.m[0][1]));
        worst = fmax(worst, fabs(t - pow(sin(2 * phi) * sin(G / 2), 2)));
    }
    printf("  through the thickness, alpha 0.3 vs sin^2 2phi sin^2(Γ(λ)/2): %.2g\n", worst);
    CHECK(worst < 1e-5);
    CHECK(biref_pe_stack_at(&m, h, m.n0, N, st, -1.0, &b, NULL, 0) == BIREF_ERR_INVALID);
}

static const test_case CASES[] = {
    {"through_thickness_takes_C_at_each_wavelength", through_thickness_takes_C_at_each_wavelength},
    {"law_and_fringe_constant", law_and_fringe_constant},
    {"alpha_zero_is_todays_picture", alpha_zero_is_todays_picture},
    {"white_matches_slab_sum_over_wavelengths", white_matches_slab_sum_over_wavelengths},
    {"small_alpha_meets_the_table", small_alpha_meets_the_table},
    {"mono_uses_C_at_its_wavelength_and_colours_shift", mono_uses_C_at_its_wavelength_and_colours_shift},
    {"tilted_white_with_alpha_is_refused", tilted_white_with_alpha_is_refused},
};

int main(int argc, char **argv)
{
    int rc = test_run_cases("test_pe_dispersion", CASES, TEST_COUNT(CASES), argc, argv);
    biref_spectral_destroy(context());
    return rc;
}
