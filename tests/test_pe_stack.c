/* Stress through the thickness of a plate, by the stack machinery: with fixed principal
 * directions the retardations add (integrated photoelasticity); a uniform twist of the
 * principal directions gives the twisted retarder's closed form, not the added retardations. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "biref/biref.h"
#include "test_cases.h"

/* The amplitude through a linear polarizer at psi_in, the stack, a linear analyzer at psi_out
 * (from x = s towards z = p at normal incidence). */
static double polariscope(const biref_stack *s, double lambda, double psi_in, double psi_out)
{
    biref_jones T;
    if (biref_stack_jones(s, 0.0, lambda, &T, NULL) != BIREF_OK) return NAN;
    const double e[2] = {cos(psi_in), sin(psi_in)}, u[2] = {cos(psi_out), sin(psi_out)};
    double complex a = 0.0;
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) a += e[i] * T.m[i][o] * u[o];
    return creal(a * conj(a));
}

/* Fixed principal directions, a parabolic (tempered-glass-like) profile of s1 - s2 through the
 * thickness: crossed polarizers see sin^2 2phi sin^2(Γ/2) with Γ = 2 pi C h <s1 - s2> / lambda. */
static void fixed_directions_retardations_add(void)
{
    biref_pe_material m;
    CHECK(biref_pe_material_preset("glass", &m) == BIREF_OK);
    const double h = 6e-3;
    for (int n = 4; n <= 32; n *= 2)
        for (int c = 0; c < 6; c++) {
            const double phi = 0.2 + 0.25 * c, lambda = 420 + 50 * c;
            biref_pe_stress st[32];
            double mean = 0.0;
            for (int k = 0; k < n; k++) {
                const double z = (k + 0.5) / n * 2 - 1;                  /* -1 .. 1 through the plate */
                const double d = 40e6 * (1.5 * z * z - 0.5) + 25e6 * c; /* Pa: compression at the faces */
                /* principal difference d along phi: s1 - s2 = |d|, direction phi or phi + 90 deg */
                st[k].sxx = 0.5 * d * (1 + cos(2 * phi));
                st[k].syy = 0.5 * d * (1 - cos(2 * phi));
                st[k].txy = 0.5 * d * sin(2 * phi);
                mean += d / n;
            }
            biref_stack s;
            char msg[BIREF_MSG_SIZE];
            CHECK(biref_pe_stack(&m, h, m.n0, n, st, &s, msg, sizeof msg) == BIREF_OK);
            const double G = 2 * M_PI * m.C_per_Pa * mean * h / (lambda * 1e-9);
            CHECK_NEAR(polariscope(&s, lambda, 0.0, M_PI / 2), pow(sin(2 * phi) * sin(G / 2), 2), 1e-5);
        }
}

/* Principal directions turning uniformly by alpha through the thickness at constant s1 - s2:
 * between a polarizer along the entrance direction and an analyzer across the exit direction,
 * T = (alpha / X)^2 sin^2 X, X = sqrt(alpha^2 + (Γ/2)^2) (twisted retarder); the added
 * retardations (fixed directions) would give 0 there. */
static void rotating_directions_twisted_retarder(void)
{
    biref_pe_material m;
    CHECK(biref_pe_material_preset("epoxy", &m) == BIREF_OK);
    const int n = 64;
    const double h = 5e-3, lambda = 550;
    double worst = 0.0, smallest_change = 1.0, largest = 0.0;
    for (int c = 0; c < 8; c++) {
        const double alpha = 0.2 * (c + 1), ds = 0.2e6 * (1 + c % 3);
        biref_pe_stress st[64];
        for (int k = 0; k < n; k++) {
            const double th = alpha * (k + 0.5) / n;
            st[k].sxx = 0.5 * ds * (1 + cos(2 * th));
            st[k].syy = 0.5 * ds * (1 - cos(2 * th));
            st[k].txy = 0.5 * ds * sin(2 * th);
        }
        biref_stack s;
        CHECK(biref_pe_stack(&m, h, m.n0, n, st, &s, NULL, 0) == BIREF_OK);
        const double G = 2 * M_PI * m.C_per_Pa * ds * h / (lambda * 1e-9), X = sqrt(alpha * alpha + G * G / 4);
        /* Layer k has the direction of the middle of its slice of the continuous twist 0 .. alpha. */
        const double a0 = 0.0, a1 = alpha;
        const double t = polariscope(&s, lambda, a0, a1 + M_PI / 2);
        const double expect = pow(alpha / X * sin(X), 2);
        worst = fmax(worst, fabs(t - expect));
        smallest_change = fmin(smallest_change, expect);
        largest = fmax(largest, expect);
    }
    printf("  twisted retarder: worst |T - closed form| %.2e, T from %.3f to %.3f (fixed directions: 0)\n", worst,
           smallest_change, largest);
    CHECK(worst < 5e-4); /* 64 layers: the staircase of the continuous twist, O(1/n^2) */
    CHECK(smallest_change > 0.03);
}

static void bad_plates_are_refused(void)
{
    biref_pe_material m;
    CHECK(biref_pe_material_preset("pmma", &m) == BIREF_OK);
    biref_pe_stress st[2] = {{1e6, 0, 0}, {NAN, 0, 0}};
    biref_stack s;
    char msg[BIREF_MSG_SIZE] = "";
    CHECK(biref_pe_stack(&m, 1e-3, 1.0, 2, st, &s, msg, sizeof msg) == BIREF_ERR_INVALID && strstr(msg, "layer 1"));
    CHECK(biref_pe_stack(&m, 1e-3, 1.0, 0, st, &s, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(biref_pe_stack(&m, -1e-3, 1.0, 1, st, &s, msg, sizeof msg) == BIREF_ERR_INVALID);
    /* An unstressed layer is isotropic in the plane: a valid (degenerate) uniaxial layer. */
    biref_pe_stress zero[1] = {{0, 0, 0}};
    CHECK(biref_pe_stack(&m, 1e-3, 1.0, 1, zero, &s, msg, sizeof msg) == BIREF_OK);
}

static const test_case CASES[] = {
    {"fixed_directions_retardations_add", fixed_directions_retardations_add},
    {"rotating_directions_twisted_retarder", rotating_directions_twisted_retarder},
    {"bad_plates_are_refused", bad_plates_are_refused},
};

int main(int argc, char **argv) { return test_run_cases("test_pe_stack", CASES, TEST_COUNT(CASES), argc, argv); }
