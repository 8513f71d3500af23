/*
 * A calcite-like slab seen at 30 degrees: power fractions at one wavelength and the colour of
 * unpolarized light transmitted and reflected, printed as JSON.
 *
 * Build against an installed biref:
 *   cc -std=c17 slab_colors.c $(pkg-config --cflags --libs biref) -o slab_colors
 */
#include <biref/biref.h>

#include <math.h>
#include <stdio.h>

static const char *const SP[2] = {"s", "p"};

static void print_fractions(const char *name, double f[2][2])
{
    printf("  \"%s\": {", name);
    for (int in = 0; in < 2; in++)
        printf("\"%s\": {\"s\": %.17g, \"p\": %.17g}%s", SP[in], f[in][0], f[in][1], in ? "" : ", ");
    printf("},\n");
}

int main(void)
{
    const double pi = 3.14159265358979323846;
    /* Slab frame: surface y = 0, slab below, light in the YZ plane; angles in radians. */
    biref_slab slab = {.eta_o = 1.775, .eta_e = 1.231, .axis = {0.084, 0.979, -0.187},
                       .thickness_nm = 1.15e6, .eta_i = 1.0};
    double theta = 30.0 * pi / 180.0;

    /* Functions that can fail for several reasons write one line into a buffer the caller owns;
     * the per-sample ones (biref_slab_jones, biref_slab_prepare) leave the reason to the check. */
    char msg[BIREF_MSG_SIZE];
    biref_status st = biref_slab_check(&slab, msg, sizeof msg);
    if (st != BIREF_OK) {
        fprintf(stderr, "slab_colors: %s\n", msg);
        return 1;
    }

    /* One wavelength: Jones matrices [input s/p][output s/p] and their power fractions. */
    biref_jones T, R;
    st = biref_slab_jones(&slab, theta, 550.0, &T, &R);
    if (st != BIREF_OK) {
        fprintf(stderr, "slab_colors: %s\n", biref_status_string(st));
        return 1;
    }
    double PT[2][2], PR[2][2];
    biref_jones_intensity(&T, PT);
    biref_jones_intensity(&R, PR);

    /* Colour: the spectral tables are built once and shared; the slab state once per angle. */
    biref_spectral_config cfg;
    biref_spectral_config_default(&cfg);
    biref_spectral *sp = NULL;
    st = biref_spectral_create(&cfg, &sp, msg, sizeof msg);
    if (st != BIREF_OK) {
        fprintf(stderr, "slab_colors: %s\n", msg);
        return 1;
    }
    biref_slab_state state;
    st = biref_slab_prepare(&slab, theta, &state);
    if (st != BIREF_OK) {
        fprintf(stderr, "slab_colors: %s\n", biref_status_string(st));
        biref_spectral_destroy(sp);
        return 1;
    }
    /* The integrator: one per method, created once (the analytic method by default). */
    biref_integrator_options opts;
    biref_integrator_options_default(&opts);
    biref_integrator *it = NULL;
    st = biref_integrator_create(sp, &opts, &it, msg, sizeof msg);
    if (st != BIREF_OK) {
        fprintf(stderr, "slab_colors: %s\n", msg);
        biref_spectral_destroy(sp);
        return 1;
    }
    biref_spectrum spectrum;
    st = biref_integrate_spectrum(it, &state, &spectrum);
    biref_integrator_destroy(it);
    if (st != BIREF_OK) {
        fprintf(stderr, "slab_colors: %s\n", biref_status_string(st));
        biref_spectral_destroy(sp);
        return 1;
    }
    const double unpolarized[2] = {0.5, 0.5}, no_analyzer[2] = {1.0, 1.0};
    double xyz_T[3], xyz_R[3], rgb_T[3], rgb_R[3];
    biref_spectrum_mix(spectrum.T, unpolarized, no_analyzer, xyz_T);
    biref_spectrum_mix(spectrum.R, unpolarized, no_analyzer, xyz_R);
    biref_xyz_to_srgb(xyz_T, rgb_T);
    biref_xyz_to_srgb(xyz_R, rgb_R);
    biref_spectral_destroy(sp);

    printf("{\n");
    print_fractions("T", PT);
    print_fractions("R", PR);
    printf("  \"srgb_T\": [%.6f, %.6f, %.6f],\n", rgb_T[0], rgb_T[1], rgb_T[2]);
    printf("  \"srgb_R\": [%.6f, %.6f, %.6f]\n}\n", rgb_R[0], rgb_R[1], rgb_R[2]);
    return isfinite(rgb_T[0]) ? 0 : 1;
}
