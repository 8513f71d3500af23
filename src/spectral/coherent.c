/* The coherent regime: slabs for which the fast methods' path picture does not hold, integrated
 * exactly instead.
 *
 * The analytic method (eqs. 19-26) and the path-group expansion both sum the paths of the
 * geometric series (I - D)^{-1} of eq. 17 one by one, and both assume that paths whose optical
 * paths differ by a round trip or more hardly interfere after band integration. Two kinds of slab
 * break this (docs/ACCURACY.md, "Where each method is valid"):
 *
 * - thin slabs, whose round trips are shorter than the band's coherence length: every order
 *   interferes with every other, and the pairs that eq. 23 drops (order n with order n + 2, and
 *   siblings) are as large as the ones it keeps; at high internal reflectance E + 2H leaves
 *   [0, 1] (an isotropic film at r^2 > 1/2: 1 - 2r^2 < 0 at anti-resonance);
 * - evanescent legs that still couple the two faces (frustrated total reflection, only when
 *   eta_i exceeds a slab index): the "energy" |a|^2 of a path with an evanescent leg is no
 *   energy at all (the flux is carried by the cross term of the growing and decaying waves) and
 *   the reflection coefficients of evanescent waves are not bounded by 1, so the series of
 *   eq. 20-21 and the expansion's tail can diverge (spectral radius >= 1) while the closed form
 *   stays finite.
 *
 * In both cases the closed form of eq. 17 varies slowly with the wavelength (short optical
 * paths), so integrating it numerically is both exact and affordable: the midpoint rule of the
 * numeric method, with a number of samples that resolves the integrand's highest significant
 * frequency. A band integral of |J|^2 with positive weights is physical by construction (each
 * sample is a lossless slab: T + R = 1 at every wavelength). */
#include <complex.h>
#include <math.h>

#include "spectral/spectral_internal.h"

/* A leg counts as coupling the two faces while its amplitude decay at the band's longest
 * wavelength (the weakest decay) is above this. */
#define EVANESCENT_COUPLING 1e-7
/* Round trips shorter than this (nm of optical path, about a 3 um slab) are coherent: the pairs
 * eq. 23 drops still interfere after band integration. On random slabs (eta 1-3, |dn| <= 0.5,
 * 0-90 deg) eq. 26 is off by up to 0.33 in intensity (dE00 14-41) below a 2 um round trip and
 * 0.25 (dE00 10) below 5 um; the quadrature costs ~0.14 us per sample, a few hundred samples
 * here (docs/ACCURACY.md). */
#define COHERENT_ROUND_TRIP_NM BIREF_COHERENT_ROUND_TRIP_NM
/* Orders resolved by the quadrature: up to where the round-trip amplitude has fallen below this. */
#define ORDER_AMPLITUDE_FLOOR 1e-3
/* Midpoint samples per local period of the highest significant frequency at the short end of the
 * band, where e^{2 pi i D / lambda} turns fastest (2 pi D / lambda^2 per nm). The colour-matching
 * weights vanish towards both ends of the band, so the rule converges much faster than its
 * generic O(h^2) once the integrand is resolved. */
#define SAMPLES_PER_PERIOD 4.0
#define MIN_SAMPLES 48.0

/* Largest row sum of |D| (D = P_down r12 P_up r10, the round trip of eq. 15) with each leg's
 * decay taken at wavenumber k: a bound on the amplitude factor of one more round trip. */
static double round_trip_norm(const biref_slab_state *st, double k)
{
    double pd[2], pu[2], worst = 0.0;
    for (int m = 0; m < 2; m++) {
        pd[m] = exp(-k * cimag(st->opl_down[m]));
        pu[m] = exp(-k * cimag(st->opl_up[m]));
    }
    for (int x = 0; x < 2; x++) {
        double row = 0.0;
        for (int x2 = 0; x2 < 2; x2++) {
            double complex d = 0.0;
            for (int y = 0; y < 2; y++) d += pd[x] * st->bottom.r_down[x][y] * pu[y] * st->top.r_up[y][x2];
            row += cabs(d);
        }
        worst = fmax(worst, row);
    }
    return worst;
}

int biref_coherent_real_paths(const biref_slab_state *st)
{
    /* With real optical paths no leg is evanescent (no coupling test) and every round trip
     * propagates: only the shortest round trip decides, as in biref_coherent_plan. */
    double rt_min = INFINITY;
    for (int x = 0; x < 2; x++)
        for (int y = 0; y < 2; y++) rt_min = fmin(rt_min, fabs(creal(st->opl_down[x] + st->opl_up[y])));
    return rt_min < COHERENT_ROUND_TRIP_NM;
}

const biref_numeric_plan *biref_coherent_plan(const biref_spectral *sp, const biref_slab_state *st)
{
    const double k_lo = 2.0 * M_PI / sp->cfg.lambda_max_nm;
    int coupled = 0;
    for (int m = 0; m < 2; m++) {
        double im_d = cimag(st->opl_down[m]), im_u = cimag(st->opl_up[m]);
        if ((im_d != 0.0 && exp(-k_lo * fabs(im_d)) > EVANESCENT_COUPLING) ||
            (im_u != 0.0 && exp(-k_lo * fabs(im_u)) > EVANESCENT_COUPLING))
            coupled = 1;
    }
    /* Shortest and longest round trip (down x, up y) among the legs that propagate. */
    double rt_min = INFINITY, rt_max = 0.0;
    for (int x = 0; x < 2; x++)
        for (int y = 0; y < 2; y++) {
            double complex rt = st->opl_down[x] + st->opl_up[y];
            rt_max = fmax(rt_max, fabs(creal(rt)));
            if (exp(-k_lo * fabs(cimag(rt))) > EVANESCENT_COUPLING) rt_min = fmin(rt_min, fabs(creal(rt)));
        }
    if (!coupled && !(rt_min < COHERENT_ROUND_TRIP_NM)) return NULL;
    return biref_resolving_plan(sp, st);
}

const biref_numeric_plan *biref_resolving_plan(const biref_spectral *sp, const biref_slab_state *st)
{
    const double k_lo = 2.0 * M_PI / sp->cfg.lambda_max_nm;
    double rt_max = 0.0;
    for (int x = 0; x < 2; x++)
        for (int y = 0; y < 2; y++) rt_max = fmax(rt_max, fabs(creal(st->opl_down[x] + st->opl_up[y])));
    /* Highest significant optical path in |J(k)|^2: the order-0 retardances plus as many round
     * trips as it takes the round-trip amplitude to fall below the floor. */
    double rho = round_trip_norm(st, k_lo), orders;
    if (!(rho < 1.0 - 1e-9))
        orders = 1e9; /* amplifying evanescent reflections: resolve as far as the plans go */
    else
        orders = rho <= ORDER_AMPLITUDE_FLOOR ? 1.0 : ceil(log(ORDER_AMPLITUDE_FLOOR) / log(rho));
    double retard = fabs(creal(st->opl_down[1] - st->opl_down[0])) + fabs(creal(st->opl_up[1] - st->opl_up[0]));
    double opd = retard + orders * rt_max;
    const double lmin = sp->cfg.lambda_min_nm, lmax = sp->cfg.lambda_max_nm;
    double need = SAMPLES_PER_PERIOD * opd * (lmax - lmin) / (lmin * lmin) + MIN_SAMPLES;
    for (int p = 0; p < sp->n_coherent; p++)
        if (biref_numeric_plan_samples(sp->coherent[p]) >= need) return sp->coherent[p];
    /* More than the largest plan: still physical (positive weights), less resolved. */
    return sp->coherent[sp->n_coherent - 1];
}
