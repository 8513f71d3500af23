/* Textbook formulas (Fresnel, Airy) written independently of the library, in the basis of
 * docs/CONVENTIONS.md: s = x, p = k x s. Derivation of the p-wave signs: every p wave has
 * H = k x (k x x) = -eta x, so continuity of E_z and H_x gives the forms below. */
#ifndef BIREF_TEST_TEXTBOOK_H
#define BIREF_TEST_TEXTBOOK_H

#include <complex.h>
#include <math.h>

/* eta * cos(theta) in medium of index eta for incidence parameter K, on the branch with
 * Im >= 0 (evanescent waves decay away from the interface). */
static inline double complex tb_eta_cos(double eta, double K)
{
    return csqrt((double complex)(eta * eta - K * K));
}

/* Interface a -> b; pol 0 = s, 1 = p. nc = eta cos(theta) of each side. */
static inline double complex tb_fresnel_r(int pol, double ea, double eb, double K)
{
    double complex ca = tb_eta_cos(ea, K), cb = tb_eta_cos(eb, K);
    if (pol == 0) return (ca - cb) / (ca + cb);
    /* eta_b cos_a - eta_a cos_b over the sum, written with eta*cos products. */
    return (eb * eb * ca - ea * ea * cb) / (eb * eb * ca + ea * ea * cb);
}

static inline double complex tb_fresnel_t(int pol, double ea, double eb, double K)
{
    double complex ca = tb_eta_cos(ea, K), cb = tb_eta_cos(eb, K);
    if (pol == 0) return 2.0 * ca / (ca + cb);
    return 2.0 * ea * eb * ca / (eb * eb * ca + ea * ea * cb);
}

/* Airy sums for an isotropic slab of index es and thickness d (nm) in ambient ea; reference
 * planes y = 0 (incident, reflected) and y = -d (transmitted). */
static inline void tb_airy(int pol, double ea, double es, double d_nm, double theta, double lambda_nm,
                           double complex *t, double complex *r)
{
    double K = ea * sin(theta);
    double complex delta = 2.0 * M_PI / lambda_nm * d_nm * tb_eta_cos(es, K);
    double complex ph = cexp(I * delta);
    double complex r01 = tb_fresnel_r(pol, ea, es, K), t01 = tb_fresnel_t(pol, ea, es, K);
    double complex r10 = tb_fresnel_r(pol, es, ea, K), t10 = tb_fresnel_t(pol, es, ea, K);
    double complex den = 1.0 - r10 * r10 * ph * ph;
    *t = t01 * t10 * ph / den;
    *r = r01 + t01 * t10 * r10 * ph * ph / den;
}

#endif
