/* Fringe orders from one colour picture: the calibration against an independent integration
 * (a "camera" whose sensitivities are the CIE 1931 functions must record the analytic white-light
 * XYZ), and the demodulation of a synthetic fringe ramp with noise, from a seed, by continuity. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "test_cases.h"

static biref_pe_setup setup_circular_dark(void)
{
    biref_pe_setup s;
    memset(&s, 0, sizeof s);
    biref_pe_material_preset("polycarbonate", &s.material);
    s.thickness = 6e-3;
    s.eta_i = 1.0;
    s.light = BIREF_PE_WHITE;
    biref_pe_polariscope_make(BIREF_PE_CIRCULAR, BIREF_PE_DARK, 0.0, &s.pol);
    return s;
}

/* The camera path (mono intensities integrated by trapezoids over sensitivities) with the CIE
 * 1931 functions over the white light's band (380-700 nm) is the analytic integration of the
 * spectral tables by another road: linear camera RGB = band-normalised XYZ. */
static void cie_camera_records_the_analytic_xyz(void)
{
    biref_pe_setup s = setup_circular_dark();
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    biref_cmf_band band;
    CHECK(biref_cmf_band_init(&band, BIREF_CMF_CIE1931, 380.0, 700.0, NULL, 0) == BIREF_OK);
    enum { NL = 1281 };
    static double lam[NL], sens[NL][3];
    for (int i = 0; i < NL; i++) {
        lam[i] = 380.0 + 0.25 * i;
        biref_cmf_band_eval(&band, lam[i], sens[i]);
    }
    const biref_pe_camera cam = {NL, lam, &sens[0][0]};
    enum { NO = 41 };
    double orders[NO], cam_rgb[NO][3], srgb[NO][3];
    for (int k = 0; k < NO; k++) orders[k] = 0.125 * k;
    char msg[256];
    CHECK(biref_pe_tfp_calibrate(&s, sp, &cam, 550.0, NO, orders, &cam_rgb[0][0], msg, sizeof msg) == BIREF_OK);
    CHECK(biref_pe_tfp_calibrate(&s, sp, NULL, 550.0, NO, orders, &srgb[0][0], msg, sizeof msg) == BIREF_OK);
    double err = 0, err_srgb = 0;
    for (int k = 0; k < NO; k++) {
        const double ds = orders[k] * 550e-9 / (s.thickness * s.material.C_per_Pa);
        biref_pe_principal p = {0.5 * ds, -0.5 * ds, 0.25 * M_PI, 0.0, 1.0};
        double xyz[3], enc[3];
        biref_pe_shade(&s, sp, &p, xyz);
        for (int c = 0; c < 3; c++) err = fmax(err, fabs(cam_rgb[k][c] - xyz[c]));
        biref_xyz_to_srgb(xyz, enc);
        for (int c = 0; c < 3; c++) err_srgb = fmax(err_srgb, fabs(srgb[k][c] - fmin(1, fmax(0, enc[c]))));
    }
    printf("  CIE camera vs analytic XYZ: max %.2e; sRGB table vs the picture's encoding: max %.2e\n", err, err_srgb);
    CHECK(err < 1e-4);
    CHECK(err_srgb < 1e-12);
    biref_spectral_destroy(sp);
}

/* A ramp N = 4 x / W across a picture (rows alike), its colours from the table plus seeded noise
 * of 2/255: demodulated from the left edge (N = 0) within 0.05 wherever N <= 3. */
static void noisy_ramp_demodulates_by_continuity(void)
{
    biref_pe_setup s = setup_circular_dark();
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    enum { NT = 601, W = 400, H = 8 };
    static double orders[NT], tab[NT][3];
    for (int k = 0; k < NT; k++) orders[k] = 0.01 * k;
    CHECK(biref_pe_tfp_calibrate(&s, sp, NULL, 550.0, NT, orders, &tab[0][0], NULL, 0) == BIREF_OK);
    static float img[H][W][3], out[H][W];
    double truth[W];
    unsigned seed = 99;
    double grid[NT][3];
    memcpy(grid, tab, sizeof grid);
    for (int x = 0; x < W; x++) {
        truth[x] = 4.0 * (x + 0.5) / W;
        const double f = truth[x] / 0.01;
        const int k = (int)f;
        const double t = f - k;
        for (int y = 0; y < H; y++)
            for (int c = 0; c < 3; c++) {
                /* Box-Muller from a seeded LCG */
                seed = seed * 1664525u + 1013904223u;
                const double u1 = ((seed >> 8) + 0.5) / 16777216.0;
                seed = seed * 1664525u + 1013904223u;
                const double u2 = ((seed >> 8) + 0.5) / 16777216.0;
                const double g = sqrt(-2 * log(u1)) * cos(2 * M_PI * u2);
                const double v = (1 - t) * grid[k][c] + t * grid[k + 1][c] + g * 2.0 / 255.0;
                img[y][x][c] = (float)(round(fmin(1, fmax(0, v)) * 255) / 255);
            }
    }
    biref_pe_tfp_opts o = {0, 4, 0.0, 0.3, 0.08};
    char msg[256];
    CHECK(biref_pe_tfp_demodulate(&img[0][0][0], W, H, NT, orders, &tab[0][0], &o, &out[0][0], NULL, msg, sizeof msg) ==
          BIREF_OK);
    double err = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            if (truth[x] <= 3) err = fmax(err, isnan(out[y][x]) ? 1e9 : fabs(out[y][x] - truth[x]));
    printf("  ramp 0..4, noise 2/255: max |dN| %.4f for N <= 3\n", err);
    CHECK(err < 0.05);
    /* A seed whose colour is not near its stated order, outside the picture, a table that does
     * not rise: one line each. */
    o.seed_order = 2.5;
    CHECK(biref_pe_tfp_demodulate(&img[0][0][0], W, H, NT, orders, &tab[0][0], &o, &out[0][0], NULL, msg, sizeof msg) !=
              BIREF_OK && strstr(msg, "matches no colour"));
    o.seed_x = W;
    CHECK(biref_pe_tfp_demodulate(&img[0][0][0], W, H, NT, orders, &tab[0][0], &o, &out[0][0], NULL, msg, sizeof msg) !=
              BIREF_OK && strstr(msg, "outside"));
    o.seed_x = 0;
    orders[5] = orders[4];
    CHECK(biref_pe_tfp_demodulate(&img[0][0][0], W, H, NT, orders, &tab[0][0], &o, &out[0][0], NULL, msg, sizeof msg) !=
              BIREF_OK && strstr(msg, "must rise"));
    biref_spectral_destroy(sp);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"cie_camera_records_the_analytic_xyz", cie_camera_records_the_analytic_xyz},
        {"noisy_ramp_demodulates_by_continuity", noisy_ramp_demodulates_by_continuity},
    };
    return test_run_cases("test_pe_tfp", cases, TEST_COUNT(cases), argc, argv);
}
