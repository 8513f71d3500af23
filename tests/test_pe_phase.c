/* Phase stepping: the six (and four) settings of a circular polariscope, their intensity formulas
 * checked against the library's Jones-calculus polariscope (fast path and the general slab path),
 * the analyzer states against an independent Mueller-matrix calculation, and the round trip
 * disk -> images -> demodulate -> fringe order and isoclinic against the closed form. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/photoelastic.h"
#include "test_cases.h"

/* The state passed by a quarter-wave plate (fast axis xi) and a linear analyzer (beta), by Mueller
 * calculus: the analyzer's row (1, cos 2b, sin 2b, 0) times the plate's Mueller matrix. The sign
 * of the plate's circular terms follows the library's convention (the slow axis gains e^{+i pi/2};
 * S3 > 0 for (1, i)/sqrt2): then the rows below are M^T a. */
static void mueller_state(double xi, double beta, double s[4])
{
    const double c = cos(2 * xi), sn = sin(2 * xi), a1 = cos(2 * beta), a2 = sin(2 * beta);
    /* Quarter-wave retarder (delta = pi/2), fast axis at xi:
     * [1 0 0 0; 0 c^2 cs -sgn s; 0 cs s^2 sgn c; 0 sgn s -sgn c 0] with the convention's sign. */
    const double sg = -1.0;
    s[0] = 1.0;
    s[1] = c * c * a1 + c * sn * a2;
    s[2] = c * sn * a1 + sn * sn * a2;
    s[3] = -sg * sn * a1 + sg * c * a2;
}

/* Six and four steps exist, five do not; the six analyzer states are the Poincare sphere's poles. */
static void steps_are_the_poles_of_the_poincare_sphere(void)
{
    biref_pe_step st[6];
    CHECK(biref_pe_phase_steps(6, st) == 6);
    CHECK(biref_pe_phase_steps(4, st) == 4);
    CHECK(biref_pe_phase_steps(5, st) == 0);
    biref_pe_phase_steps(6, st);
    /* The six poles of the Poincare sphere: -S3, +S3, +S1, +S2, -S1, -S2. */
    static const double want[6][3] = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    for (int k = 0; k < 6; k++) {
        double m[4];
        mueller_state(st[k].qwp_deg * M_PI / 180, st[k].analyzer_deg * M_PI / 180, m);
        for (int i = 0; i < 3; i++) {
            CHECK_NEAR(st[k].stokes[i + 1], want[k][i], 1e-12);
            CHECK_NEAR(m[i + 1], want[k][i], 1e-12);
        }
    }
}

/* Steps 1 and 2 are the dark and light circular polariscope of biref_pe_polariscope_make. */
static void first_steps_are_the_dark_and_light_circular_polariscopes(void)
{
    biref_pe_polariscope a, b;
    biref_pe_polariscope_stepped(0, M_PI / 4, &a);
    biref_pe_polariscope_make(BIREF_PE_CIRCULAR, BIREF_PE_DARK, 0, &b);
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) CHECK(cabs(a.P[i][j] - b.P[i][j]) < 1e-15);
    biref_pe_polariscope_stepped(0, 3 * M_PI / 4, &a);
    biref_pe_polariscope_make(BIREF_PE_CIRCULAR, BIREF_PE_LIGHT, 0, &b);
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) CHECK(cabs(a.P[i][j] - b.P[i][j]) < 1e-15);
}

/* I = 1/2 (1 + a3 cos d + sin d (a2 cos 2phi - a1 sin 2phi)) against the Jones calculus: the fast
 * path and the general slab path (eq. 17 Jones matrix), index-matched (no reflections). */
static void intensity_formulas_match_jones_calculus(void)
{
    test_rng r = {777};
    biref_pe_step st[6];
    biref_pe_phase_steps(6, st);
    double worst_fast = 0, worst_gen = 0;
    for (int t = 0; t < 600; t++) {
        biref_pe_setup s;
        memset(&s, 0, sizeof s);
        biref_pe_material_preset("polycarbonate", &s.material);
        s.thickness = test_uniform(&r, 1, 10) * 1e-3;
        s.eta_i = s.material.n0;
        s.light = BIREF_PE_MONO;
        s.lambda_nm = test_uniform(&r, 450, 650);
        biref_pe_stress sig = {test_uniform(&r, -5, 5) * 1e6, test_uniform(&r, -5, 5) * 1e6,
                               test_uniform(&r, -3, 3) * 1e6};
        biref_pe_principal p;
        biref_pe_principal_of(&sig, &p);
        const int k = t % 6;
        biref_pe_polariscope_stepped(st[k].qwp_deg * M_PI / 180, st[k].analyzer_deg * M_PI / 180, &s.pol);
        const double d = 2 * M_PI * biref_pe_retardation_nm(&s, &p) / s.lambda_nm;
        const double *a = st[k].stokes;
        const double want = 0.5 * (1 + a[3] * cos(d) + sin(d) * (a[2] * cos(2 * p.phi) - a[1] * sin(2 * p.phi)));
        double f[3], g[3];
        biref_pe_shade(&s, NULL, &p, f);
        CHECK(biref_pe_shade_general(&s, NULL, &p, 1, 0, g) == BIREF_OK);
        worst_fast = fmax(worst_fast, fabs(f[0] - want));
        worst_gen = fmax(worst_gen, fabs(g[0] - want));
    }
    /* Residual: the e-mode's own reflectance, (dn / 2n)^2 ~ 1e-8 for these stresses. */
    printf("phase-step formulas vs Jones calculus (index-matched, 600 points): fast %.2e, general %.2e\n", worst_fast,
           worst_gen);
    CHECK(worst_fast < 1e-6);
    CHECK(worst_gen < 1e-6);
}

/* Disk in air, 589 nm, rendered through each step's polariscope, demodulated, compared with the
 * closed form away from the load points (and, for the isoclinic, away from the lines sin d = 0,
 * where the images do not hold it). */
static void round_trip(int n, double ib, double ia, double *worst_N, double *worst_phi)
{
    const int W = 160, H = 160;
    biref_pe_field f;
    char msg[256];
    CHECK(biref_pe_field_disk(&f, 0.025, 0.006, 500, msg, sizeof msg) == BIREF_OK);
    biref_pe_setup s;
    memset(&s, 0, sizeof s);
    biref_pe_material_preset("polycarbonate", &s.material);
    s.thickness = 0.006;
    s.eta_i = 1.0;
    s.light = BIREF_PE_MONO;
    s.lambda_nm = 589;
    biref_pe_image_opts io = {.width = W, .height = H, .supersample = 2, .threads = 1, .tint = {1, 1, 1}, .tilt = 0};
    biref_pe_step st[6];
    biref_pe_phase_steps(n, st);
    float *img[6], *xyz = malloc((size_t)W * H * 3 * sizeof *xyz);
    for (int k = 0; k < n; k++) {
        img[k] = malloc((size_t)W * H * sizeof(float));
        biref_pe_polariscope_stepped(st[k].qwp_deg * M_PI / 180, st[k].analyzer_deg * M_PI / 180, &s.pol);
        CHECK(biref_pe_render(&s, NULL, &f, &io, xyz, NULL, 0) == BIREF_OK);
        for (int i = 0; i < W * H; i++) img[k][i] = (float)(ib + ia * xyz[3 * i + 1]);
    }
    float *N = malloc((size_t)W * H * sizeof *N), *phi = malloc((size_t)W * H * sizeof *phi);
    float *mod = malloc((size_t)W * H * sizeof *mod), *bg = malloc((size_t)W * H * sizeof *bg);
    biref_pe_demod_maps out = {phi, NULL, N, mod, bg};
    biref_pe_demod_opts o = {1, 1, 0, 0.05}; /* the empty field in the corner: order 0 */
    CHECK(biref_pe_demodulate(n, (const float *const *)img, W, H, &o, &out, msg, sizeof msg) == BIREF_OK);
    *worst_N = *worst_phi = 0;
    int count = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            const double x = f.frame[0] + (i + 0.5) * (f.frame[1] - f.frame[0]) / W;
            const double y = f.frame[3] - (j + 0.5) * (f.frame[3] - f.frame[2]) / H;
            const double R = 0.025;
            if (hypot(x, y) > 0.9 * R || hypot(x, y - R) < 0.3 * R || hypot(x, y + R) < 0.3 * R) continue;
            biref_pe_stress sg;
            biref_pe_disk_stress(R, 0.006, 500, x, y, &sg);
            biref_pe_principal p;
            biref_pe_principal_of(&sg, &p);
            const double Nt = biref_pe_retardation_nm(&s, &p) / 589.0;
            const size_t q = (size_t)j * W + i;
            *worst_N = fmax(*worst_N, isnan(N[q]) ? INFINITY : fabs(N[q] - Nt));
            /* Where sin d ~ 0 the images hold no isoclinic (a pixel's samples average it away). */
            double dphi = fabs(remainder(phi[q] - p.phi * 180 / M_PI, 180.0));
            if (fabs(sin(2 * M_PI * Nt)) > 0.2) *worst_phi = fmax(*worst_phi, isnan(phi[q]) ? INFINITY : dphi);
            count++;
        }
    CHECK(count > 10000);
    /* Ia and Ib of the synthetic camera: Ia = ia (1 - R)^2 roughly, Ib = ib. */
    const size_t c = (size_t)(H / 2) * W + W / 2;
    CHECK_NEAR(bg[c], ib, 2e-3 * ia);
    CHECK(mod[c] > 0.85 * ia && mod[c] < 1.0 * ia);
    for (int k = 0; k < n; k++) free(img[k]);
    free(xyz);
    free(N);
    free(phi);
    free(mod);
    free(bg);
}

static void round_trip_six_steps(void)
{
    double wn, wp;
    round_trip(6, 0.0, 1.0, &wn, &wp);
    printf("round trip, 6 steps: |N - closed form| <= %.4f, isoclinic within %.3f deg where |sin d| > 0.2 (r <= "
           "0.9 R, >= 0.3 R from the loads)\n", wn, wp);
    CHECK(wn <= 0.02);
    CHECK(wp <= 1.0);
}

/* Four steps, with a background Ib = 0.1 and a camera gain Ia = 0.7. */
static void round_trip_four_steps_with_background_and_gain(void)
{
    double wn, wp;
    round_trip(4, 0.1, 0.7, &wn, &wp);
    printf("round trip, 4 steps, Ib = 0.1, Ia x 0.7: |N - closed form| <= %.4f, isoclinic within %.3f deg\n", wn, wp);
    CHECK(wn <= 0.02);
    CHECK(wp <= 1.0);
}

/* Five steps, images without modulation, a reference point outside the images. */
static void demodulation_refuses_bad_input(void)
{
    char msg[256];
    float a[4] = {0, 0, 0, 0};
    const float *im[6] = {a, a, a, a, a, a};
    biref_pe_demod_opts o = {0, 0, 0, 0.05};
    float N[4];
    biref_pe_demod_maps out = {NULL, NULL, N, NULL, NULL};
    CHECK(biref_pe_demodulate(5, im, 2, 2, &o, &out, msg, sizeof msg) != BIREF_OK);
    CHECK(biref_pe_demodulate(6, im, 2, 2, &o, &out, msg, sizeof msg) != BIREF_OK);
    CHECK(strstr(msg, "no modulation") != NULL);
    o.ref_x = 5;
    CHECK(biref_pe_demodulate(6, im, 2, 2, &o, &out, msg, sizeof msg) != BIREF_OK);
    CHECK(strstr(msg, "outside") != NULL);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"steps_are_the_poles_of_the_poincare_sphere", steps_are_the_poles_of_the_poincare_sphere},
        {"first_steps_are_the_dark_and_light_circular_polariscopes", first_steps_are_the_dark_and_light_circular_polariscopes},
        {"intensity_formulas_match_jones_calculus", intensity_formulas_match_jones_calculus},
        {"round_trip_six_steps", round_trip_six_steps},
        {"round_trip_four_steps_with_background_and_gain", round_trip_four_steps_with_background_and_gain},
        {"demodulation_refuses_bad_input", demodulation_refuses_bad_input},
    };
    return test_run_cases("test_pe_phase", cases, TEST_COUNT(cases), argc, argv);
}
