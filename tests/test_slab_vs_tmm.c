/* Closed form (paper eq. 17 and its reflection analogue) against the independent 4x4
 * Berreman transfer-matrix solver, complex amplitudes and power fractions, on seeded random
 * slabs spanning the range the optics must cover: 0.5 um - 2 mm, 0-89 deg, |dn| <= 0.3 of both signs,
 * random axes, eta_i in {1, 1.33}; plus thin slabs with evanescent modes inside. */
#include <complex.h>
#include <math.h>

#include "biref/biref.h"
#include "test_cases.h"

static void random_slab(test_rng *r, biref_slab *s, double *theta, double *lambda, double d_min, double d_max,
                        double n_lo, double n_hi)
{
    double A[3];
    test_random_axis(r, A);
    s->eta_o = test_uniform(r, n_lo, n_hi);
    s->eta_e = s->eta_o + test_uniform(r, -0.3, 0.3);
    for (int i = 0; i < 3; i++) s->axis[i] = A[i];
    s->thickness_nm = exp(test_uniform(r, log(d_min), log(d_max)));
    s->eta_i = test_uniform(r, 0, 1) < 0.5 ? 1.0 : 1.33;
    *theta = test_uniform(r, 0, 89) * M_PI / 180;
    *lambda = test_uniform(r, 380, 700);
}

static int compare(const biref_slab *s, double theta, double lambda, double *worst_amp, double *worst_pow)
{
    biref_jones Tc, Rc, Tt, Rt;
    if (biref_slab_jones_tmm(s, theta, lambda, &Tt, &Rt) != BIREF_OK) return 0;
    CHECK(biref_slab_jones(s, theta, lambda, &Tc, &Rc) == BIREF_OK);
    double PTc[2][2], PRc[2][2], PTt[2][2], PRt[2][2];
    biref_jones_intensity(&Tc, PTc);
    biref_jones_intensity(&Rc, PRc);
    biref_jones_intensity(&Tt, PTt);
    biref_jones_intensity(&Rt, PRt);
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++) {
            *worst_amp = fmax(*worst_amp, fmax(cabs(Tc.m[i][o] - Tt.m[i][o]), cabs(Rc.m[i][o] - Rt.m[i][o])));
            *worst_pow = fmax(*worst_pow, fmax(fabs(PTc[i][o] - PTt[i][o]), fabs(PRc[i][o] - PRt[i][o])));
        }
    return 1;
}

/* One stream of draws for all cases, in table order. */
static test_rng rng = {0xC0FFEEULL};

static void propagating_slabs_match_tmm(void)
{
    double worst_amp = 0, worst_pow = 0;
    int ran = 0, total = 2000;
    for (int t = 0; t < total; t++) {
        biref_slab s;
        double theta, lambda;
        random_slab(&rng, &s, &theta, &lambda, 500, 2e6, 1.3, 2.0);
        ran += compare(&s, theta, lambda, &worst_amp, &worst_pow);
    }
    printf("propagating set: %d of %d compared, worst |dJ| %.3g, worst |dT|,|dR| %.3g\n", ran, total, worst_amp,
           worst_pow);
    CHECK(ran > total * 0.95);
    CHECK(worst_amp < 1e-9); /* measured 3.8e-11 */
    CHECK(worst_pow < 1e-9);
}

/* Evanescent modes inside (slab indices below eta_i sin theta): thin slabs, where the
 * transfer matrix stays well conditioned. */
static void slabs_with_evanescent_modes_inside_match_tmm(void)
{
    double wa = 0, wp = 0;
    int ev = 0, ran_ev = 0;
    for (int t = 0; t < 1000; t++) {
        biref_slab s;
        double theta, lambda;
        random_slab(&rng, &s, &theta, &lambda, 50, 1500, 1.0, 1.35);
        s.eta_i = 1.33;
        if (s.eta_e < 0.9) s.eta_e = 0.9 + (0.9 - s.eta_e);
        biref_slab_state st;
        CHECK(biref_slab_prepare(&s, theta, &st) == BIREF_OK);
        if (!st.total_reflection) continue;
        ev++;
        ran_ev += compare(&s, theta, lambda, &wa, &wp);
    }
    printf("evanescent set: %d of %d compared, worst |dJ| %.3g, worst |dT|,|dR| %.3g\n", ran_ev, ev, wa, wp);
    CHECK(ev > 100 && ran_ev > ev / 2);
    CHECK(wa < 1e-9);
    CHECK(wp < 1e-9);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"propagating_slabs_match_tmm", propagating_slabs_match_tmm},
        {"slabs_with_evanescent_modes_inside_match_tmm", slabs_with_evanescent_modes_inside_match_tmm},
    };
    return test_run_cases("test_slab_vs_tmm", cases, TEST_COUNT(cases), argc, argv);
}
