/* Interface coefficients solved from the boundary conditions (paper appendix A): textbook
 * Fresnel for isotropic media, and energy-flux conservation for every pairing of
 * isotropic and uniaxial media, including anisotropic-to-anisotropic. */
#include <complex.h>
#include <math.h>

#include "biref/biref.h"
#include "test_cases.h"
#include "textbook.h"

/* Time-averaged normal flux Re(E* x H)_y of mode i with unit amplitude. */
static double flux_y(const biref_modes *m, int i)
{
    const double complex *E = m->E[i], *H = m->H[i];
    return creal(conj(E[2]) * H[0] - conj(E[0]) * H[2]);
}

static void random_medium(test_rng *r, biref_medium *m)
{
    if (test_uniform(r, 0, 1) < 0.25) {
        *m = biref_medium_isotropic(test_uniform(r, 1.0, 2.0));
        return;
    }
    double A[3] = {test_uniform(r, -1, 1), test_uniform(r, -1, 1), test_uniform(r, -1, 1)};
    double no = test_uniform(r, 1.3, 2.0);
    *m = biref_medium_uniaxial(no, no + test_uniform(r, -0.3, 0.3), A);
}

/* Isotropic -> isotropic equals Fresnel, cross-polarisation zero. */
static void isotropic_isotropic_equals_fresnel_cross(void)
{
    for (int t = 0; t < 50; t++) {
        double ea = 1.0 + 0.02 * t, eb = 1.9 - 0.015 * t, K = ea * sin(0.03 * t);
        biref_medium a = biref_medium_isotropic(ea), b = biref_medium_isotropic(eb);
        biref_interface f;
        CHECK(biref_interface_solve(&a, &b, K, &f) == BIREF_OK);
        for (int p = 0; p < 2; p++) {
            CHECK(cabs(f.r_down[p][p] - tb_fresnel_r(p, ea, eb, K)) < 1e-12);
            CHECK(cabs(f.t_down[p][p] - tb_fresnel_t(p, ea, eb, K)) < 1e-12);
            CHECK(cabs(f.r_up[p][p] - tb_fresnel_r(p, eb, ea, K)) < 1e-12);
            CHECK(cabs(f.t_up[p][p] - tb_fresnel_t(p, eb, ea, K)) < 1e-12);
            CHECK(cabs(f.r_down[p][1 - p]) < 1e-14 && cabs(f.t_down[p][1 - p]) < 1e-14);
        }
    }
}

/* Normal incidence in our basis: r_p = -r_s (docs/CONVENTIONS.md). */
static void normal_incidence_in_our_basis(void)
{
    biref_medium a = biref_medium_isotropic(1.0), b = biref_medium_isotropic(1.5);
    biref_interface f;
    CHECK(biref_interface_solve(&a, &b, 0.0, &f) == BIREF_OK);
    CHECK_NEAR(creal(f.r_down[0][0]), -0.2, 1e-14);
    CHECK_NEAR(creal(f.r_down[1][1]), 0.2, 1e-14);
}

/* Energy flux across random interfaces, from above and from below, all propagating cases. */
static void energy_flux_across_random_interfaces(void)
{
    test_rng rng = {0xfeedbeefULL};
    int tested = 0;
    for (int t = 0; t < 3000; t++) {
        biref_medium a, b;
        random_medium(&rng, &a);
        random_medium(&rng, &b);
        double K = test_uniform(&rng, 0.0, 1.25);
        biref_modes ma, mb;
        CHECK(biref_medium_modes(&a, K, &ma) == BIREF_OK);
        CHECK(biref_medium_modes(&b, K, &mb) == BIREF_OK);
        if (ma.evanescent_o || ma.evanescent_e || mb.evanescent_o || mb.evanescent_e) continue;
        biref_interface f;
        CHECK(biref_interface_solve(&a, &b, K, &f) == BIREF_OK);
        tested++;
        for (int i = 0; i < 2; i++) {
            double in = -flux_y(&ma, BIREF_MODE_O_DOWN + i), out = 0;
            for (int j = 0; j < 2; j++) {
                out += cabs(f.r_down[i][j]) * cabs(f.r_down[i][j]) * flux_y(&ma, BIREF_MODE_O_UP + j);
                out -= cabs(f.t_down[i][j]) * cabs(f.t_down[i][j]) * flux_y(&mb, BIREF_MODE_O_DOWN + j);
            }
            CHECK_NEAR(out / in, 1.0, 1e-10);
            in = flux_y(&mb, BIREF_MODE_O_UP + i);
            out = 0;
            for (int j = 0; j < 2; j++) {
                out += cabs(f.t_up[i][j]) * cabs(f.t_up[i][j]) * flux_y(&ma, BIREF_MODE_O_UP + j);
                out -= cabs(f.r_up[i][j]) * cabs(f.r_up[i][j]) * flux_y(&mb, BIREF_MODE_O_DOWN + j);
            }
            CHECK_NEAR(out / in, 1.0, 1e-10);
        }
    }
    CHECK(tested > 2000);
}

/* Total reflection: from a dense uniaxial medium into air beyond the critical angle the
 * reflected power equals the incident power (|r| weighted by flux). */
static void total_internal_reflection_returns_all_flux(void)
{
    double A[3] = {0.3, 0.5, 0.8};
    biref_medium u = biref_medium_uniaxial(1.6, 1.7, A), air = biref_medium_isotropic(1.0);
    biref_modes mu;
    double K = 1.2;
    CHECK(biref_medium_modes(&u, K, &mu) == BIREF_OK);
    biref_interface f;
    CHECK(biref_interface_solve(&u, &air, K, &f) == BIREF_OK);
    for (int i = 0; i < 2; i++) {
        double in = -flux_y(&mu, BIREF_MODE_O_DOWN + i), out = 0;
        for (int j = 0; j < 2; j++)
            out += cabs(f.r_down[i][j]) * cabs(f.r_down[i][j]) * flux_y(&mu, BIREF_MODE_O_UP + j);
        CHECK_NEAR(out / in, 1.0, 1e-10);
    }
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"isotropic_isotropic_equals_fresnel_cross", isotropic_isotropic_equals_fresnel_cross},
        {"normal_incidence_in_our_basis", normal_incidence_in_our_basis},
        {"energy_flux_across_random_interfaces", energy_flux_across_random_interfaces},
        {"total_internal_reflection_returns_all_flux", total_internal_reflection_returns_all_flux},
    };
    return test_run_cases("test_interface", cases, TEST_COUNT(cases), argc, argv);
}
