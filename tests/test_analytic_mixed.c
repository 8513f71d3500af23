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
#include "test_util.h"

static int same_c(const double complex *a, const double complex *b, size_t n)
{
    return memcmp(a, b, n * sizeof *a) == 0;
}

int main(void)
{
    int quick = getenv("BIREF_TEST_QUICK") != NULL;
    biref_spectral *sp = NULL;
    CHECK(biref_spectral_create(NULL, &sp) == BIREF_OK);
    test_rng rng = {0x5eed0a11u};
    const int n = quick ? 300 : 3000;
    double worst = 0.0;
    int tir = 0, zero_weight = 0, real_solves = 0;
    for (int k = 0; k < n; k++) {
        biref_slab s;
        test_random_axis(&rng, s.axis);
        s.eta_o = test_uniform(&rng, 1.3, 1.8);
        s.eta_e = s.eta_o + test_uniform(&rng, -0.3, 0.3);
        s.thickness_nm = exp(test_uniform(&rng, log(20.0), log(5e6)));
        s.eta_i = k % 4 == 3 ? test_uniform(&rng, 1.5, 2.0) : 1.0;
        double theta = test_uniform(&rng, 0, 89.5) * M_PI / 180;
        biref_slab_state st, tr, fl;
        if (biref_slab_prepare(&s, theta, &st) != BIREF_OK) continue;
        CHECK(biref_slab_prepare_trusted(&s, theta, &tr) == BIREF_OK);
        /* Every field the spectral methods read is the checked set-up's, bit for bit. */
        CHECK(same_c(&st.top.r_down[0][0], &tr.top.r_down[0][0], 16));
        CHECK(same_c(&st.bottom.r_down[0][0], &tr.bottom.r_down[0][0], 16));
        CHECK(same_c(st.opl_down, tr.opl_down, 2) && same_c(st.opl_up, tr.opl_up, 2));
        CHECK(same_c(st.modes.q, tr.modes.q, 4) && same_c(&st.modes.E[0][0], &tr.modes.E[0][0], 12));
        CHECK(memcmp(st.slab.axis, tr.slab.axis, sizeof st.slab.axis) == 0 && st.K == tr.K &&
              st.total_reflection == tr.total_reflection);
        tir += st.total_reflection;
        /* Without evanescent modes the interface solves run in real arithmetic: the complex
         * elimination of the same system gives the same numbers, bit for bit. */
        {
            biref_modes amb;
            biref_isotropic_modes(s.eta_i, st.K, &amb);
            biref_interface re[2], cx[2];
            int ok = biref_interface_from_modes_as(&amb, &st.modes, 1, &re[0]) == BIREF_OK &&
                     biref_interface_from_modes_as(&st.modes, &amb, 1, &re[1]) == BIREF_OK &&
                     biref_interface_from_modes_as(&amb, &st.modes, 0, &cx[0]) == BIREF_OK &&
                     biref_interface_from_modes_as(&st.modes, &amb, 0, &cx[1]) == BIREF_OK;
            CHECK(ok);
            const double complex *a = &re[0].r_down[0][0], *b = &cx[0].r_down[0][0];
            for (int q = 0; ok && q < 32; q++) CHECK(creal(a[q]) == creal(b[q]) && cimag(a[q]) == cimag(b[q]));
            real_solves += !st.total_reflection && s.eta_i == 1.0;
        }
        biref_slab_state_flip(&st, &fl);
        double w[2] = {test_uniform(&rng, 0, 1), test_uniform(&rng, 0, 1)};
        double m[2] = {k % 3 == 1 ? 0.0 : 1.0, k % 3 == 2 ? 0.0 : test_uniform(&rng, 0.5, 1)};
        if (k % 5 == 0) w[k % 2] = 0.0;
        zero_weight += w[0] == 0.0 || w[1] == 0.0 || m[0] == 0.0 || m[1] == 0.0;
        for (int which = 0; which < 2; which++) {
            const biref_slab_state *x = which == BIREF_REFLECTION ? &fl : &st;
            biref_spectrum ref_spectrum;
            double ref[3], got[3];
            biref_spectrum_analytic(sp, x, &ref_spectrum);
            biref_spectrum_mix(which == BIREF_REFLECTION ? ref_spectrum.R : ref_spectrum.T, w, m, ref);
            biref_analytic_mixed(sp, x, which, w, m, got);
            for (int j = 0; j < 3; j++) {
                double e = fabs(got[j] - ref[j]) / (1.0 + fabs(ref[j]));
                if (e > worst) worst = e;
                CHECK(got[j] == ref[j]); /* same terms, same order */
            }
        }
    }
    printf("one-pass vs analytic.c: worst relative difference %.3g over %d slabs (%d with total "
           "reflection, %d with a zero weight)\n",
           worst, n, tir, zero_weight);
    CHECK(tir > n / 20 && zero_weight > n / 4 && real_solves > n / 2);
    biref_spectral_destroy(sp);
    return test_report("test_analytic_mixed");
}
