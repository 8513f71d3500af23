/* The numeric methods' wavelength blocks (numeric_jones.c) against the scalar closed form
 * (biref_slab_jones_at) one wavelength at a time: the same bits on every code path this
 * processor runs, for random slabs including total reflection and thin slabs; and the numeric
 * spectra against their per-wavelength sums. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "biref/biref.h"
#include "spectral/analytic_packet.h"
#include "spectral/numeric_jones.h"
#include "spectral/spectral_internal.h"
#include "test_cases.h"

enum { SEED = 7, SLABS = 3000 };

/* A random slab: indices 1.2-1.8, random axis, thickness log-uniform 10 nm - 5 mm; a third in a
 * dense surround (eta_i 1.9) so that total reflection and evanescent legs occur. */
static int random_state(test_rng *r, int i, biref_slab_state *st)
{
    biref_slab s;
    s.eta_o = test_uniform(r, 1.2, 1.8);
    s.eta_e = test_uniform(r, 1.2, 1.8);
    test_random_axis(r, s.axis);
    s.thickness_nm = exp(test_uniform(r, log(10.0), log(5e6)));
    s.eta_i = i % 3 == 0 ? 1.9 : 1.0;
    return biref_slab_prepare(&s, test_uniform(r, 0.0, 1.55), st) == BIREF_OK;
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* Entries of a block's Jones matrices that differ from the scalar path's, for each side. */
static int block_mismatches(const biref_slab_state *st, const double *lambda, int n, int avx2, int sides)
{
    double k[BIREF_NUMERIC_BLOCK];
    for (int l = 0; l < n; l++) k[l] = 2.0 * M_PI / lambda[l]; /* as the numeric plan computes it */
    biref_jones_block T, R;
    biref_numeric_jones_block_isa(st, k, n, sides & 1 ? &T : NULL, sides & 2 ? &R : NULL, avx2);
    int bad = 0;
    for (int l = 0; l < n; l++) {
        biref_jones t, r;
        biref_slab_jones_at(st, lambda[l], &t, &r);
        for (int a = 0; a < 2; a++)
            for (int b = 0; b < 2; b++) {
                if (sides & 1)
                    bad += !same_bits(T.re[a][b][l], creal(t.m[a][b])) + !same_bits(T.im[a][b][l], cimag(t.m[a][b]));
                if (sides & 2)
                    bad += !same_bits(R.re[a][b][l], creal(r.m[a][b])) + !same_bits(R.im[a][b][l], cimag(r.m[a][b]));
            }
    }
    return bad;
}

static void blocks_equal_scalar_jones_on_every_path(void)
{
    const int paths = biref_numeric_avx2_available() ? 2 : 1;
    test_rng r = {SEED};
    int bad[2] = {0, 0}, states = 0, evanescent = 0;
    for (int i = 0; i < SLABS; i++) {
        biref_slab_state st;
        if (!random_state(&r, i, &st)) continue;
        states++;
        evanescent += st.total_reflection;
        double lambda[BIREF_NUMERIC_BLOCK];
        const int n = 1 + i % BIREF_NUMERIC_BLOCK;
        for (int l = 0; l < n; l++) lambda[l] = test_uniform(&r, 380.0, 700.0);
        for (int p = 0; p < paths; p++) bad[p] += block_mismatches(&st, lambda, n, p, 1 + i % 3);
    }
    printf("%d states (%d in total reflection), %d code path(s): %d / %d differing entries\n", states, evanescent,
           paths, bad[0], bad[1]);
    CHECK(states > SLABS / 2 && evanescent > 100);
    CHECK(bad[0] == 0 && bad[1] == 0);
}

/* biref_spectrum_numeric and biref_spectrum_numeric_polarized on a plan of the scalar path
 * (BIREF_SIMD=scalar; the lanes, test_numeric_lanes, agree to ~1e-15 but not bitwise) as sums of
 * the scalar path one wavelength at a time (in ascending order): equal to the bit. */
static void spectra_equal_per_wavelength_sums(void)
{
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(NULL, &sp, NULL, 0) == BIREF_OK);
    if (!sp) return;
    static const int SAMPLES[] = {1, 3, 8, 31, 33, 100};
    const double complex C[2][2] = {{0.6, 0.1 + 0.2 * I}, {0.1 - 0.2 * I, 0.4}};
    const double complex P[2][2] = {{0.5, 0.5}, {0.5, 0.5}};
    test_rng r = {SEED + 1};
    int bad = 0, compared = 0;
    for (size_t s = 0; s < sizeof SAMPLES / sizeof SAMPLES[0]; s++) {
        biref_numeric_plan *plan = NULL;
        CHECK(biref_numeric_plan_create(sp, SAMPLES[s], &plan, NULL, 0) == BIREF_OK);
        if (!plan) continue;
        plan->isa = BIREF_SIMD_SCALAR;
        for (int i = 0; i < 60; i++) {
            biref_slab_state st;
            if (!random_state(&r, i, &st)) continue;
            biref_spectrum got, want;
            memset(&want, 0, sizeof want);
            double xyz_want[2][3] = {{0}}, xyz_got[2][3];
            for (int n = 0; n < plan->samples; n++) {
                biref_jones T, R;
                biref_slab_jones_at(&st, plan->lambda[n], &T, &R);
                double PT[2][2], PR[2][2];
                biref_jones_intensity(&T, PT);
                biref_jones_intensity(&R, PR);
                for (int a = 0; a < 2; a++)
                    for (int o = 0; o < 2; o++)
                        for (int j = 0; j < 3; j++) {
                            want.T[a][o][j] += plan->weight[n][j] * PT[a][o];
                            want.R[a][o][j] += plan->weight[n][j] * PR[a][o];
                        }
                for (int w = 0; w < 2; w++) {
                    const biref_jones *J = w ? &R : &T;
                    double complex M[2][2];
                    for (int a = 0; a < 2; a++)
                        for (int c = 0; c < 2; c++) M[a][c] = J->m[a][0] * P[0][c] + J->m[a][1] * P[1][c];
                    double I_det = 0.0;
                    for (int a = 0; a < 2; a++)
                        for (int b = 0; b < 2; b++)
                            for (int c = 0; c < 2; c++) I_det += creal(C[a][b] * M[a][c] * conj(M[b][c]));
                    for (int j = 0; j < 3; j++) xyz_want[w][j] += plan->weight[n][j] * I_det;
                }
            }
            biref_spectrum_numeric(plan, &st, &got);
            biref_spectrum_numeric_polarized(plan, &st, BIREF_TRANSMISSION, C, P, xyz_got[0]);
            biref_spectrum_numeric_polarized(plan, &st, BIREF_REFLECTION, C, P, xyz_got[1]);
            bad += memcmp(&got, &want, sizeof got) != 0;
            bad += memcmp(xyz_got, xyz_want, sizeof xyz_got) != 0;
            compared += 3;
        }
        biref_numeric_plan_destroy(plan);
    }
    printf("%d spectra compared, %d differ\n", compared, bad);
    CHECK(compared > 500);
    CHECK(bad == 0);
    biref_spectral_destroy(sp);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"blocks_equal_scalar_jones_on_every_path", blocks_equal_scalar_jones_on_every_path},
        {"spectra_equal_per_wavelength_sums", spectra_equal_per_wavelength_sums},
    };
    return test_run_cases("test_numeric_block", cases, TEST_COUNT(cases), argc, argv);
}
