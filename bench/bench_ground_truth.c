/* bench_ground_truth — the ground truth (16384 midpoint samples of eq. 17) in lanes across
 * wavelengths against the per-wavelength path it replaced, on the accuracy study's grid
 * (docs/ACCURACY.md: the three fig. 9 materials, θ 0-85° in steps of 1°, 16 azimuths of the optic
 * axis about the normal): the largest difference of any band-normalised XYZ of the four s/p pairs,
 * transmission and reflection, and the largest ΔE00 of each material's light (fig. 9 captions),
 * with the time per state of both paths on one thread.
 *
 * The per-wavelength path is the plan created under BIREF_SIMD=scalar (numeric_jones.c, equal to
 * biref_slab_jones_at per wavelength to the bit); the lanes are the default plan. Measures, never
 * asserts. Usage: bench_ground_truth [--samples N] [--theta-step-deg S] [--azimuths N] [--json] */
#define BIREF_EXPERIMENTAL_API
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "biref/biref.h"

typedef struct {
    biref_slab slab;
    double w_in[2], mask[2];
} material;

/* docs/ACCURACY.md, "What is compared": fig. 9 (a), (b), (c) with their lights. */
static const material MATERIALS[3] = {
    {{1.40, 1.38, {-0.54, 0.80, 0.27}, 1.25e6, 1.0}, {0.75, 0.25}, {1, 1}},
    {{1.50, 1.51, {0.25, 0.97, 0.00}, 3.50e6, 1.0}, {0.5, 0.5}, {1, 1}},
    {{1.775, 1.231, {0.084, 0.979, -0.187}, 1.15e6, 1.0}, {0.02, 0.98}, {1, 0}},
};

static double now(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static biref_numeric_plan *plan_on(const biref_spectral *sp, int samples, const char *simd)
{
    if (simd)
        setenv("BIREF_SIMD", simd, 1);
    else
        unsetenv("BIREF_SIMD");
    biref_numeric_plan *p = NULL;
    char msg[BIREF_MSG_SIZE];
    if (biref_numeric_plan_create(sp, samples, &p, msg, sizeof msg) != BIREF_OK) {
        fprintf(stderr, "bench_ground_truth: %s\n", msg);
        exit(1);
    }
    unsetenv("BIREF_SIMD");
    return p;
}

int main(int argc, char **argv)
{
    int samples = BIREF_GROUND_TRUTH_SAMPLES, azimuths = 16, json = 0;
    double step = 1.0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--samples") && v)
            samples = atoi(argv[++i]);
        else if (!strcmp(a, "--theta-step-deg") && v)
            step = atof(argv[++i]);
        else if (!strcmp(a, "--azimuths") && v)
            azimuths = atoi(argv[++i]);
        else if (!strcmp(a, "--json"))
            json = 1;
        else {
            fprintf(stderr, "usage: bench_ground_truth [--samples N] [--theta-step-deg S] [--azimuths N] [--json]\n");
            return !strcmp(a, "-h") || !strcmp(a, "--help") ? 0 : 2;
        }
    }
    if (samples < 1 || samples > (1 << 24) || !(step > 0.0) || azimuths < 1 || azimuths > 360) {
        fprintf(stderr, "bench_ground_truth: samples 1..2^24, a positive step, 1..360 azimuths\n");
        return 2;
    }
    biref_spectral *sp = NULL;
    char msg[BIREF_MSG_SIZE];
    if (biref_spectral_create(NULL, &sp, msg, sizeof msg) != BIREF_OK) {
        fprintf(stderr, "bench_ground_truth: %s\n", msg);
        return 1;
    }
    biref_numeric_plan *lanes = plan_on(sp, samples, NULL), *scalar = plan_on(sp, samples, "scalar");
    double worst_xyz = 0.0, worst_de[3] = {0, 0, 0}, t_lanes = 0.0, t_scalar = 0.0;
    long states = 0;
    for (int m = 0; m < 3; m++)
        for (double th = 0.0; th <= 85.0 + 1e-9; th += step)
            for (int az = 0; az < azimuths; az++) {
                const double phi = 2.0 * M_PI * az / azimuths, *A = MATERIALS[m].slab.axis;
                biref_slab s = MATERIALS[m].slab;
                s.axis[0] = cos(phi) * A[0] + sin(phi) * A[2];
                s.axis[2] = -sin(phi) * A[0] + cos(phi) * A[2];
                biref_slab_state st;
                if (biref_slab_prepare(&s, th * M_PI / 180.0, &st) != BIREF_OK) continue;
                biref_spectrum a, b;
                double t0 = now(CLOCK_THREAD_CPUTIME_ID);
                biref_spectrum_numeric(lanes, &st, &a);
                double t1 = now(CLOCK_THREAD_CPUTIME_ID);
                biref_spectrum_numeric(scalar, &st, &b);
                double t2 = now(CLOCK_THREAD_CPUTIME_ID);
                t_lanes += t1 - t0, t_scalar += t2 - t1;
                states++;
                for (int i = 0; i < 2; i++)
                    for (int o = 0; o < 2; o++)
                        for (int j = 0; j < 3; j++)
                            worst_xyz = fmax(worst_xyz, fmax(fabs(a.T[i][o][j] - b.T[i][o][j]),
                                                             fabs(a.R[i][o][j] - b.R[i][o][j])));
                for (int side = 0; side < 2; side++) {
                    double xa[3], xb[3];
                    biref_spectrum_mix(side ? a.R : a.T, MATERIALS[m].w_in, MATERIALS[m].mask, xa);
                    biref_spectrum_mix(side ? b.R : b.T, MATERIALS[m].w_in, MATERIALS[m].mask, xb);
                    worst_de[m] = fmax(worst_de[m], biref_delta_e00_xyz(xa, xb));
                }
            }
    const double us_l = 1e6 * t_lanes / (double)states, us_s = 1e6 * t_scalar / (double)states;
    if (json)
        printf("{\"samples\": %d, \"states\": %ld, \"max_abs_dxyz\": %.3g, \"max_de00\": [%.3g, %.3g, %.3g], "
               "\"us_per_state_lanes\": %.1f, \"us_per_state_per_wavelength\": %.1f}\n",
               samples, states, worst_xyz, worst_de[0], worst_de[1], worst_de[2], us_l, us_s);
    else
        printf("%d samples, %ld states (fig. 9 a, b, c; θ 0-85° step %g°, %d azimuths)\n"
               "largest |ΔXYZ| (any pair, T and R, any band): %.3g\n"
               "largest ΔE00 of each material's light, T and R: a %.3g, b %.3g, c %.3g\n"
               "CPU per state (T and R, four pairs), one thread: lanes %.1f µs, per wavelength %.1f µs (%.1f×)\n",
               samples, states, step, azimuths, worst_xyz, worst_de[0], worst_de[1], worst_de[2], us_l, us_s,
               us_s / us_l);
    biref_numeric_plan_destroy(lanes);
    biref_numeric_plan_destroy(scalar);
    biref_spectral_destroy(sp);
    return 0;
}
