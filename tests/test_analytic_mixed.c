/* The renderer's analytic worker (both directions in one pass, far look-ups skipped)
 * against biref_spectrum_analytic mixed afterwards (bit for bit), and the unchecked slab set-up against
 * the checked one, on random slabs: thin and thick, weak and strong birefringence, grazing
 * angles and total reflection inside the slab (surround denser than the slab). */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "optics/modes_internal.h"
#include "optics/slab_internal.h"
#include "spectral/spectral_internal.h"
#include "test_cases.h"

/* One random slab, its checked set-up and the light (s/p weights and mask) it is mixed under. */
typedef struct {
    biref_slab s;
    double theta, w[2], m[2];
    biref_slab_state st;
} sample;

static biref_spectral *sp;
static sample *samples;
static int n_samples, n_drawn;

static int same_c(const double complex *a, const double complex *b, size_t n)
{
    return memcmp(a, b, n * sizeof *a) == 0;
}

/* The seeded slabs, drawn once for all cases; a slab the checked set-up refuses draws no light. */
static void draw_samples(void)
{
    if (samples) return;
    n_drawn = test_quick() ? 300 : 3000;
    samples = malloc((size_t)n_drawn * sizeof *samples);
    CHECK(samples != NULL);
    if (!samples) return;
    test_rng rng = {0x5eed0a11u};
    for (int k = 0; k < n_drawn; k++) {
        sample *x = &samples[n_samples];
        biref_slab *s = &x->s;
        test_random_axis(&rng, s->axis);
        s->eta_o = test_uniform(&rng, 1.3, 1.8);
        s->eta_e = s->eta_o + test_uniform(&rng, -0.3, 0.3);
        s->thickness_nm = exp(test_uniform(&rng, log(20.0), log(5e6)));
        s->eta_i = k % 4 == 3 ? test_uniform(&rng, 1.5, 2.0) : 1.0;
        x->theta = test_uniform(&rng, 0, 89.5) * M_PI / 180;
        if (biref_slab_prepare(s, x->theta, &x->st) != BIREF_OK) continue;
        x->w[0] = test_uniform(&rng, 0, 1);
        x->w[1] = test_uniform(&rng, 0, 1);
        x->m[0] = k % 3 == 1 ? 0.0 : 1.0;
        x->m[1] = k % 3 == 2 ? 0.0 : test_uniform(&rng, 0.5, 1);
        if (k % 5 == 0) x->w[k % 2] = 0.0;
        n_samples++;
    }
}

/* Every field the spectral methods read is the checked set-up's, bit for bit. */
static void trusted_setup_equals_checked_setup(void)
{
    draw_samples();
    int tir = 0;
    for (int k = 0; k < n_samples; k++) {
        const sample *x = &samples[k];
        const biref_slab_state *st = &x->st;
        biref_slab_state tr;
        CHECK(biref_slab_prepare_trusted(&x->s, x->theta, &tr) == BIREF_OK);
        CHECK(same_c(&st->top.r_down[0][0], &tr.top.r_down[0][0], 16));
        CHECK(same_c(&st->bottom.r_down[0][0], &tr.bottom.r_down[0][0], 16));
        CHECK(same_c(st->opl_down, tr.opl_down, 2) && same_c(st->opl_up, tr.opl_up, 2));
        CHECK(same_c(st->modes.q, tr.modes.q, 4) && same_c(&st->modes.E[0][0], &tr.modes.E[0][0], 12));
        CHECK(memcmp(st->slab.axis, tr.slab.axis, sizeof st->slab.axis) == 0 && st->K == tr.K &&
              st->total_reflection == tr.total_reflection);
        tir += st->total_reflection;
    }
    printf("%d slabs, %d with total reflection inside\n", n_samples, tir);
    CHECK(tir > n_drawn / 20);
}

/* Without evanescent modes the interface solves run in real arithmetic: the complex elimination
 * of the same system gives the same numbers, bit for bit. */
static void real_interface_solve_equals_complex_solve(void)
{
    draw_samples();
    int real_solves = 0;
    for (int k = 0; k < n_samples; k++) {
        const sample *x = &samples[k];
        biref_modes amb;
        biref_isotropic_modes(x->s.eta_i, x->st.K, &amb);
        biref_interface re[2], cx[2];
        int ok = biref_interface_from_modes_as(&amb, &x->st.modes, 1, &re[0]) == BIREF_OK &&
                 biref_interface_from_modes_as(&x->st.modes, &amb, 1, &re[1]) == BIREF_OK &&
                 biref_interface_from_modes_as(&amb, &x->st.modes, 0, &cx[0]) == BIREF_OK &&
                 biref_interface_from_modes_as(&x->st.modes, &amb, 0, &cx[1]) == BIREF_OK;
        CHECK(ok);
        /* Both interfaces: 2 x 16 coefficients. */
        const double complex *a = &re[0].r_down[0][0], *b = &cx[0].r_down[0][0];
        for (int q = 0; ok && q < 32; q++) CHECK(creal(a[q]) == creal(b[q]) && cimag(a[q]) == cimag(b[q]));
        real_solves += !x->st.total_reflection && x->s.eta_i == 1.0;
    }
    CHECK(real_solves > n_drawn / 2);
}

/* biref_analytic_mixed (both directions, far look-ups skipped) equals biref_spectrum_analytic
 * (or _pairs) mixed afterwards: same terms, same order. */
static void one_pass_mixed_equals_analytic_then_mix(void)
{
    draw_samples();
    double worst = 0.0;
    int zero_weight = 0;
    for (int k = 0; k < n_samples; k++) {
        const sample *x = &samples[k];
        biref_slab_state fl;
        biref_slab_state_flip(&x->st, &fl);
        zero_weight += x->w[0] == 0.0 || x->w[1] == 0.0 || x->m[0] == 0.0 || x->m[1] == 0.0;
        for (int which = 0; which < 2; which++) {
            const biref_slab_state *st = which == BIREF_REFLECTION ? &fl : &x->st;
            biref_spectrum ref_spectrum;
            double ref[3], got[3];
            const int pairs = k & 1; /* both analytic methods, each bit-identical */
            (pairs ? biref_spectrum_analytic_pairs : biref_spectrum_analytic)(sp, st, &ref_spectrum);
            biref_spectrum_mix(which == BIREF_REFLECTION ? ref_spectrum.R : ref_spectrum.T, x->w, x->m, ref);
            biref_analytic_mixed(sp, st, which, pairs, x->w, x->m, got);
            for (int j = 0; j < 3; j++) {
                double e = fabs(got[j] - ref[j]) / (1.0 + fabs(ref[j]));
                if (e > worst) worst = e;
                CHECK(got[j] == ref[j]);
            }
        }
    }
    printf("one-pass vs analytic.c: worst relative difference %.3g over %d slabs (%d with a zero weight)\n", worst,
           n_samples, zero_weight);
    CHECK(zero_weight > n_drawn / 4);
}

int main(int argc, char **argv)
{
    if (biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK) return 1;
    static const test_case cases[] = {
        {"trusted_setup_equals_checked_setup", trusted_setup_equals_checked_setup},
        {"real_interface_solve_equals_complex_solve", real_interface_solve_equals_complex_solve},
        {"one_pass_mixed_equals_analytic_then_mix", one_pass_mixed_equals_analytic_then_mix},
    };
    int rc = test_run_cases("test_analytic_mixed", cases, TEST_COUNT(cases), argc, argv);
    free(samples);
    biref_spectral_destroy(sp);
    return rc;
}
