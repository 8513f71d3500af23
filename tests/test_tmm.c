/*
 * Tests of the 4x4 Berreman transfer-matrix reference (src/optics/slab_tmm.c)
 * against textbook results only — never against the closed-form slab model,
 * which this solver exists to check.
 *
 *  1. isotropic slab vs the Airy summation of Fresnel coefficients (complex
 *     amplitudes, s and p, including frustrated total reflection);
 *  2. energy conservation on random uniaxial slabs;
 *  3. normal incidence, axis in the surface: a linear retarder with phase
 *     k0 d (eta_e - eta_o); exact phases when the ambient matches one index;
 *  4. axis in the plane of incidence: s and p decouple, s is the ordinary
 *     wave, p follows the extraordinary Fresnel equation k.eps.k = eps_o eps_e;
 *  5. invariance under axis -> -axis;
 *  6. invalid inputs.
 */
#include <complex.h>
#include <math.h>
#include <stdio.h>

#include "biref/optics.h"
#include "test_cases.h"

static const double PI = 3.14159265358979323846;

static double deg(double x) { return x * PI / 180.0; }

/* Wraps a phase difference into (-pi, pi]. */
static double wrap(double x)
{
    x = fmod(x, 2.0 * PI);
    if (x > PI) x -= 2.0 * PI;
    if (x <= -PI) x += 2.0 * PI;
    return x;
}

static biref_slab make_slab(double eta_o, double eta_e, double ax, double ay, double az, double d_nm, double eta_i)
{
    biref_slab s = {eta_o, eta_e, {ax, ay, az}, d_nm, eta_i};
    return s;
}

/* ------------------------------------------------------------------------- */
/* 1. Airy formula                                                            */
/* ------------------------------------------------------------------------- */

/* Single-interface Fresnel coefficients from medium X into medium Y, in the
 * bases of CONVENTIONS.md (s = x, p = k^ x s), derived from continuity of
 * (Ex, Hz) and (Ez, Hx) with H = k x E:
 *   s: a wave of normal component q (sign = direction) has Hz = -q Ex, so
 *      r = (qX - qY)/(qX + qY), t = 2 qX/(qX + qY)   (|q| values);
 *   p: a down wave has (Ez, Hx) = (q/n, -n), an up wave (-q/n, -n), so with
 *      a = q/n^2:  r = (aX - aY)/(aX + aY), t = (nX/nY) 2 aX/(aX + aY).
 * The same expressions hold for a wave going down (X above Y) and for one
 * going up (X below Y): the bases are mirror images of each other. */
typedef struct {
    double complex r, t;
} fresnel;

static fresnel fresnel_s(double complex qX, double complex qY)
{
    fresnel f = {(qX - qY) / (qX + qY), 2.0 * qX / (qX + qY)};
    return f;
}

static fresnel fresnel_p(double nX, double complex qX, double nY, double complex qY)
{
    double complex aX = qX / (nX * nX), aY = qY / (nY * nY);
    fresnel f = {(aX - aY) / (aX + aY), (nX / nY) * 2.0 * aX / (aX + aY)};
    return f;
}

/* Airy sum of all internal reflections for a slab of index n1 in ambient n0:
 * the incident / reflected amplitudes refer to y = 0, the transmitted one to
 * y = -d, so each crossing contributes ph = exp(i k0 d q1). For q1 we take the
 * root with Im q1 >= 0 (csqrt), i.e. a wave decaying along its crossing when
 * K > n1 (frustrated total reflection); the formula is even in q1 anyway.
 *   t = t01 t10 ph / (1 - r10^2 ph^2),  r = r01 + t01 r10 t10 ph^2 / (1 - r10^2 ph^2). */
static void airy(double n0, double n1, double theta, double k0d, double complex t[2], double complex r[2])
{
    double K = n0 * sin(theta);
    double complex q0 = n0 * cos(theta);
    double complex q1 = csqrt((double complex)(n1 * n1 - K * K));
    double complex ph = cexp(I * k0d * q1);
    fresnel in[2] = {fresnel_s(q0, q1), fresnel_p(n0, q0, n1, q1)};
    fresnel out[2] = {fresnel_s(q1, q0), fresnel_p(n1, q1, n0, q0)};
    for (int p = 0; p < 2; p++) {
        double complex den = 1.0 - out[p].r * out[p].r * ph * ph;
        t[p] = in[p].t * out[p].t * ph / den;
        r[p] = in[p].r + in[p].t * out[p].r * out[p].t * ph * ph / den;
    }
}

static void test_isotropic_slab_equals_airy_formula(void)
{
    const double thetas[] = {0.0, 20.0, 45.0, 70.0, 85.0};
    const double thick[] = {500.0, 3217.0, 1.0e5, 2.0e6};
    const double lambdas[] = {400.0, 550.0, 700.0};
    const double etas_i[] = {1.0, 1.33};
    const double etas[] = {1.2, 1.5, 2.4};
    const double axes[3][3] = {{0.3, -0.5, 0.8}, {0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}};
    int n = 0;
    for (int ii = 0; ii < 2; ii++)
        for (int ie = 0; ie < 3; ie++)
            for (int it = 0; it < 5; it++)
                for (int id = 0; id < 4; id++)
                    for (int il = 0; il < 3; il++) {
                        if (etas_i[ii] * sin(deg(thetas[it])) >= etas[ie]) continue; /* FTIR: below */
                        const double *ax = axes[(ii + ie + it + id + il) % 3];
                        biref_slab s = make_slab(etas[ie], etas[ie], ax[0], ax[1], ax[2], thick[id], etas_i[ii]);
                        biref_jones T, R;
                        biref_status st = biref_slab_jones_tmm(&s, deg(thetas[it]), lambdas[il], &T, &R);
                        CHECK(st == BIREF_OK);
                        if (st != BIREF_OK) continue;
                        double complex t[2], r[2];
                        airy(etas_i[ii], etas[ie], deg(thetas[it]), 2.0 * PI / lambdas[il] * thick[id], t, r);
                        for (int p = 0; p < 2; p++) {
                            CHECK_NEAR(cabs(T.m[p][p] - t[p]), 0.0, 1e-9);
                            CHECK_NEAR(cabs(R.m[p][p] - r[p]), 0.0, 1e-9);
                            CHECK_NEAR(cabs(T.m[p][1 - p]), 0.0, 1e-9);
                            CHECK_NEAR(cabs(R.m[p][1 - p]), 0.0, 1e-9);
                        }
                        n++;
                    }
    CHECK(n > 300);

    /* Frustrated total reflection: K = eta_i sin(theta) > n1, thin slabs. */
    const struct {
        double eta_i, n1, theta_deg, d_nm, lambda;
    } ftir[] = {
        {1.33, 1.0, 60.0, 200.0, 550.0}, {1.33, 1.2, 70.0, 200.0, 550.0}, {1.33, 1.2, 70.0, 1000.0, 450.0},
        {1.33, 1.0, 85.0, 150.0, 700.0}, {1.33, 1.1, 56.0, 600.0, 400.0},
    };
    for (size_t k = 0; k < sizeof ftir / sizeof ftir[0]; k++) {
        CHECK(ftir[k].eta_i * sin(deg(ftir[k].theta_deg)) > ftir[k].n1);
        biref_slab s = make_slab(ftir[k].n1, ftir[k].n1, 0.2, 0.7, -0.4, ftir[k].d_nm, ftir[k].eta_i);
        biref_jones T, R;
        biref_status st = biref_slab_jones_tmm(&s, deg(ftir[k].theta_deg), ftir[k].lambda, &T, &R);
        CHECK(st == BIREF_OK);
        if (st != BIREF_OK) continue;
        double complex t[2], r[2];
        airy(ftir[k].eta_i, ftir[k].n1, deg(ftir[k].theta_deg), 2.0 * PI / ftir[k].lambda * ftir[k].d_nm, t, r);
        for (int p = 0; p < 2; p++) {
            CHECK_NEAR(cabs(T.m[p][p] - t[p]), 0.0, 1e-9);
            CHECK_NEAR(cabs(R.m[p][p] - r[p]), 0.0, 1e-9);
            CHECK_NEAR(cabs(T.m[p][1 - p]), 0.0, 1e-9);
            CHECK_NEAR(cabs(R.m[p][1 - p]), 0.0, 1e-9);
            CHECK(cabs(t[p]) > 1e-3); /* the tunnelling is really tested */
        }
    }

    /* Normal incidence sanity of the basis: r_p = -r_s (CONVENTIONS.md). */
    {
        biref_slab s = make_slab(1.5, 1.5, 1.0, 0.0, 0.0, 1234.0, 1.0);
        biref_jones R;
        CHECK(biref_slab_jones_tmm(&s, 0.0, 550.0, NULL, &R) == BIREF_OK);
        CHECK_NEAR(cabs(R.m[BIREF_P][BIREF_P] + R.m[BIREF_S][BIREF_S]), 0.0, 1e-12);
        CHECK(cabs(R.m[BIREF_S][BIREF_S]) > 0.01);
    }
}

/* ------------------------------------------------------------------------- */
/* 2. Energy conservation                                                     */
/* ------------------------------------------------------------------------- */

static void random_axis(test_rng *rng, double a[3])
{
    double n2;
    do {
        for (int i = 0; i < 3; i++) a[i] = test_uniform(rng, -1.0, 1.0);
        n2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    } while (n2 > 1.0 || n2 < 1e-4);
}

static void test_lossless_random_slabs_conserve_energy(void)
{
    test_rng rng = {0x9E3779B97F4A7C15ULL};
    int ran = 0, illcond = 0, other = 0;
    double worst = 0.0;
    const int cases = 1000;
    for (int k = 0; k < cases; k++) {
        double eta_o = test_uniform(&rng, 1.3, 2.0);
        double eta_e = eta_o + test_uniform(&rng, -0.3, 0.3);
        double a[3];
        random_axis(&rng, a);
        double d = 500.0 * pow(4000.0, test_uniform(&rng, 0.0, 1.0)); /* 0.5 um .. 2 mm, log-uniform */
        double theta = deg(test_uniform(&rng, 0.0, 89.0));
        double eta_i = test_uniform(&rng, 0.0, 1.0) < 0.5 ? 1.0 : 1.33;
        double lambda = test_uniform(&rng, 380.0, 700.0);
        biref_slab s = make_slab(eta_o, eta_e, a[0], a[1], a[2], d, eta_i);
        biref_jones T, R;
        biref_status st = biref_slab_jones_tmm(&s, theta, lambda, &T, &R);
        if (st == BIREF_ERR_ILLCOND) {
            illcond++;
            continue;
        }
        if (st != BIREF_OK) {
            other++;
            continue;
        }
        ran++;
        for (int p = 0; p < 2; p++) {
            double sum = 0.0;
            for (int o = 0; o < 2; o++) {
                double tt = cabs(T.m[p][o]), rr = cabs(R.m[p][o]);
                sum += tt * tt + rr * rr;
            }
            if (fabs(sum - 1.0) > worst) worst = fabs(sum - 1.0);
            CHECK_NEAR(sum, 1.0, 1e-9);
        }
    }
    printf("energy: %d ran, %d ill-conditioned, %d other errors, worst |sum - 1| = %.3g\n", ran, illcond, other,
           worst);
    CHECK(other == 0);
    CHECK(ran >= 950);
}

/* ------------------------------------------------------------------------- */
/* 3. Wave plate at normal incidence                                          */
/* ------------------------------------------------------------------------- */

/* Amplitudes of a retarder with axis (1,0,1)/sqrt2 at normal incidence in the
 * basis (o, e) of its eigenpolarizations. There s = x and p = z for the
 * incident and the transmitted wave, so e = (s + p)/sqrt2 (along the axis)
 * and o = (p - s)/sqrt2. For the reflected wave p = (0, -sin, -cos) = -z,
 * so the same physical directions are e = (s - p)/sqrt2, o = (-p - s)/sqrt2.
 * With out = in . J, J_oe[i][j] = u_i . J . v_j^T. */
static void to_oe(const biref_jones *J, int reflected, double complex out[2][2])
{
    const double h = sqrt(0.5), f = reflected ? -1.0 : 1.0;
    const double u[2][2] = {{-h, h}, {h, h}};         /* incident o, e in (s, p) */
    const double v[2][2] = {{-h, f * h}, {h, f * h}}; /* outgoing o, e in (s, p) */
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            double complex acc = 0.0;
            for (int a = 0; a < 2; a++)
                for (int b = 0; b < 2; b++) acc += u[i][a] * J->m[a][b] * v[j][b];
            out[i][j] = acc;
        }
}

static void test_normal_incidence_is_a_wave_plate(void)
{
    const double eta_o = 1.55, eta_e = 1.60;
    const double thick[] = {1000.0, 12345.0, 1.0e5, 1.0e6};
    double worst = 0.0;
    const double lambdas[] = {400.0, 550.0, 700.0};
    for (int id = 0; id < 4; id++)
        for (int il = 0; il < 3; il++) {
            double k0d = 2.0 * PI / lambdas[il] * thick[id];
            biref_jones T, R;
            double complex t[2][2], r[2][2];

            /* Nearly index-matched ambient: Fabry-Perot ripple ~ r^2 ~ 6e-5 rad. */
            biref_slab s = make_slab(eta_o, eta_e, 1.0, 0.0, 1.0, thick[id], 0.5 * (eta_o + eta_e));
            CHECK(biref_slab_jones_tmm(&s, 0.0, lambdas[il], &T, &R) == BIREF_OK);
            to_oe(&T, 0, t);
            to_oe(&R, 1, r);
            CHECK_NEAR(cabs(t[BIREF_O][BIREF_E]), 0.0, 1e-9); /* eigenpolarizations do not mix */
            CHECK_NEAR(cabs(t[BIREF_E][BIREF_O]), 0.0, 1e-9);
            CHECK_NEAR(cabs(r[BIREF_O][BIREF_E]), 0.0, 1e-9);
            CHECK_NEAR(cabs(r[BIREF_E][BIREF_O]), 0.0, 1e-9);
            double retard = carg(t[BIREF_E][BIREF_E] / t[BIREF_O][BIREF_O]);
            CHECK_NEAR(wrap(retard - k0d * (eta_e - eta_o)), 0.0, 1e-3);
            if (fabs(wrap(retard - k0d * (eta_e - eta_o))) > worst) worst = fabs(wrap(retard - k0d * (eta_e - eta_o)));

            /* Ambient equal to eta_o: the o wave sees no interface at all. */
            s.eta_i = eta_o;
            CHECK(biref_slab_jones_tmm(&s, 0.0, lambdas[il], &T, &R) == BIREF_OK);
            to_oe(&T, 0, t);
            to_oe(&R, 1, r);
            CHECK_NEAR(cabs(t[BIREF_O][BIREF_O] - cexp(I * k0d * eta_o)), 0.0, 1e-9);
            CHECK_NEAR(cabs(r[BIREF_O][BIREF_O]), 0.0, 1e-9);

            /* Ambient equal to eta_e: likewise for the e wave. */
            s.eta_i = eta_e;
            CHECK(biref_slab_jones_tmm(&s, 0.0, lambdas[il], &T, &R) == BIREF_OK);
            to_oe(&T, 0, t);
            to_oe(&R, 1, r);
            CHECK_NEAR(cabs(t[BIREF_E][BIREF_E] - cexp(I * k0d * eta_e)), 0.0, 1e-9);
            CHECK_NEAR(cabs(r[BIREF_E][BIREF_E]), 0.0, 1e-9);
        }
    printf("wave plate: worst |retardance - k0 d (eta_e - eta_o)| = %.3g rad (Fabry-Perot ripple)\n", worst);
}

/* ------------------------------------------------------------------------- */
/* 4. Axis in the plane of incidence                                          */
/* ------------------------------------------------------------------------- */

/* With A = (0, beta, gamma) the ordinary field (along k x A) is x = s and the
 * extraordinary one lies in the YZ plane = p: no s/p coupling. The
 * extraordinary wave obeys the Fresnel equation of uniaxial media
 * k.eps.k = eps_o eps_e (Born & Wolf sec. 15.3; Yeh 1979 eq. 12), here a
 * quadratic in q for k = (0, q, -K):
 *   (eps_o + de b^2) q^2 - 2 de b g K q + (eps_o + de g^2) K^2 - eps_o eps_e = 0,
 * whose down-going root (energy flow along eps k, y component < 0) takes the
 * minus sign of the square root. */
static double q_e_down(double eta_o, double eta_e, double b, double g, double K)
{
    double eo = eta_o * eta_o, ee = eta_e * eta_e, de = ee - eo;
    double A2 = eo + de * b * b, B = de * b * g * K, C = (eo + de * g * g) * K * K - eo * ee;
    return (B - sqrt(B * B - A2 * C)) / A2;
}

static void test_axis_azimuth_about_the_normal_matches_closed_forms(void)
{
    const double eta_o = 1.55, eta_e = 1.57;
    const double phis[] = {0.0, 30.0, 60.0, 90.0, 135.0};
    const double thetas[] = {10.0, 35.0, 55.0};
    double worst = 0.0;
    const double thick[] = {2000.0, 50000.0, 4.0e5};
    int sensitive = 0;
    for (int ip = 0; ip < 5; ip++)
        for (int it = 0; it < 3; it++)
            for (int id = 0; id < 3; id++) {
                double b = sin(deg(phis[ip])), g = cos(deg(phis[ip]));
                double theta = deg(thetas[it]), lambda = 523.0;
                double k0d = 2.0 * PI / lambda * thick[id];
                biref_jones T, R;

                /* Ambient = eta_o: s is the ordinary wave and crosses unreflected. */
                biref_slab s = make_slab(eta_o, eta_e, 0.0, b, g, thick[id], eta_o);
                double K = eta_o * sin(theta);
                CHECK(biref_slab_jones_tmm(&s, theta, lambda, &T, &R) == BIREF_OK);
                CHECK_NEAR(cabs(T.m[BIREF_S][BIREF_S] - cexp(I * k0d * sqrt(eta_o * eta_o - K * K))), 0.0, 1e-9);
                CHECK_NEAR(cabs(R.m[BIREF_S][BIREF_S]), 0.0, 1e-9);
                CHECK_NEAR(cabs(T.m[BIREF_S][BIREF_P]), 0.0, 1e-9);
                CHECK_NEAR(cabs(T.m[BIREF_P][BIREF_S]), 0.0, 1e-9);
                CHECK_NEAR(cabs(R.m[BIREF_S][BIREF_P]), 0.0, 1e-9);
                CHECK_NEAR(cabs(R.m[BIREF_P][BIREF_S]), 0.0, 1e-9);

                /* Ambient between the indices: p crosses as the extraordinary
                 * wave with small reflections (ripple ~ r^2 < 1e-4 rad). */
                s.eta_i = 0.5 * (eta_o + eta_e);
                K = s.eta_i * sin(theta);
                CHECK(biref_slab_jones_tmm(&s, theta, lambda, &T, &R) == BIREF_OK);
                double phase = -k0d * q_e_down(eta_o, eta_e, b, g, K);
                CHECK_NEAR(wrap(carg(T.m[BIREF_P][BIREF_P]) - phase), 0.0, 1e-3);
                CHECK(cabs(R.m[BIREF_P][BIREF_P]) < 0.02);
                if (fabs(wrap(carg(T.m[BIREF_P][BIREF_P]) - phase)) > worst)
                    worst = fabs(wrap(carg(T.m[BIREF_P][BIREF_P]) - phase));
                /* Would a mirrored axis (or K -> -K) have been noticed? */
                if (fabs(wrap(phase + k0d * q_e_down(eta_o, eta_e, b, -g, K))) > 0.1) sensitive++;
            }
    CHECK(sensitive >= 10);
    printf("plane of incidence: worst |arg T_pp - k0 d |q_e-|| = %.3g rad (Fabry-Perot ripple)\n", worst);
}

/* ------------------------------------------------------------------------- */
/* 5. Sign of the axis                                                        */
/* ------------------------------------------------------------------------- */

static void test_axis_sign_and_length_do_not_change_the_result(void)
{
    test_rng rng = {12345};
    for (int k = 0; k < 50; k++) {
        double a[3];
        random_axis(&rng, a);
        double eta_o = test_uniform(&rng, 1.4, 1.8), eta_e = eta_o + test_uniform(&rng, -0.2, 0.2);
        double d = test_uniform(&rng, 500.0, 20000.0), theta = deg(test_uniform(&rng, 0.0, 80.0));
        biref_slab s1 = make_slab(eta_o, eta_e, a[0], a[1], a[2], d, 1.0);
        biref_slab s2 = make_slab(eta_o, eta_e, -3.0 * a[0], -3.0 * a[1], -3.0 * a[2], d, 1.0);
        biref_jones T1, R1, T2, R2;
        biref_status st1 = biref_slab_jones_tmm(&s1, theta, 600.0, &T1, &R1);
        biref_status st2 = biref_slab_jones_tmm(&s2, theta, 600.0, &T2, &R2);
        CHECK(st1 == st2);
        if (st1 != BIREF_OK || st2 != BIREF_OK) continue;
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) {
                CHECK_NEAR(cabs(T1.m[i][j] - T2.m[i][j]), 0.0, 1e-10);
                CHECK_NEAR(cabs(R1.m[i][j] - R2.m[i][j]), 0.0, 1e-10);
            }
    }
    /* NULL outputs are allowed. */
    biref_slab s = make_slab(1.5, 1.6, 1.0, 2.0, 3.0, 1000.0, 1.0);
    CHECK(biref_slab_jones_tmm(&s, 0.3, 500.0, NULL, NULL) == BIREF_OK);
}

/* ------------------------------------------------------------------------- */
/* 6. Invalid inputs                                                          */
/* ------------------------------------------------------------------------- */

static void test_invalid_slabs_are_refused(void)
{
    const biref_slab good = make_slab(1.5, 1.6, 0.0, 0.0, 1.0, 1000.0, 1.0);
    biref_jones T, R;
    CHECK(biref_slab_jones_tmm(&good, 0.2, 550.0, &T, &R) == BIREF_OK);
    CHECK(biref_slab_jones_tmm(NULL, 0.2, 550.0, &T, &R) == BIREF_ERR_INVALID);

    const double bad_values[] = {0.0, -1.0, NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 5; k++) {
        double v = bad_values[k];
        biref_slab s = good;
        s.eta_o = v;
        CHECK(biref_slab_jones_tmm(&s, 0.2, 550.0, &T, &R) == BIREF_ERR_INVALID);
        s = good;
        s.eta_e = v;
        CHECK(biref_slab_jones_tmm(&s, 0.2, 550.0, &T, &R) == BIREF_ERR_INVALID);
        s = good;
        s.eta_i = v;
        CHECK(biref_slab_jones_tmm(&s, 0.2, 550.0, &T, &R) == BIREF_ERR_INVALID);
        s = good;
        s.thickness_nm = v;
        CHECK(biref_slab_jones_tmm(&s, 0.2, 550.0, &T, &R) == BIREF_ERR_INVALID);
        CHECK(biref_slab_jones_tmm(&good, 0.2, v, &T, &R) == BIREF_ERR_INVALID);
    }
    biref_slab s = good;
    s.axis[0] = s.axis[1] = s.axis[2] = 0.0;
    CHECK(biref_slab_jones_tmm(&s, 0.2, 550.0, &T, &R) == BIREF_ERR_INVALID);
    s = good;
    s.axis[1] = NAN;
    CHECK(biref_slab_jones_tmm(&s, 0.2, 550.0, &T, &R) == BIREF_ERR_INVALID);
    s = good;
    s.axis[2] = INFINITY;
    CHECK(biref_slab_jones_tmm(&s, 0.2, 550.0, &T, &R) == BIREF_ERR_INVALID);
    /* A huge but finite axis is fine (normalised without overflow). */
    s = good;
    s.axis[0] = 1e300;
    s.axis[2] = 1e300;
    CHECK(biref_slab_jones_tmm(&s, 0.2, 550.0, &T, &R) == BIREF_OK);

    const double bad_theta[] = {-1e-12, PI / 2.0, 2.0, NAN, INFINITY};
    for (int k = 0; k < 5; k++) CHECK(biref_slab_jones_tmm(&good, bad_theta[k], 550.0, &T, &R) == BIREF_ERR_INVALID);
    CHECK(biref_slab_jones_tmm(&good, deg(89.9), 550.0, &T, &R) == BIREF_OK);
}

/* ------------------------------------------------------------------------- */
/* Ill-conditioned cases are refused rather than answered badly.              */
/* ------------------------------------------------------------------------- */

static void test_thick_slab_in_total_reflection_reports_illcond(void)
{
    /* Thick slab under total reflection: evanescent growth exp(k0 d kappa) is astronomically large. */
    biref_slab s = make_slab(1.0, 1.0, 0.0, 0.0, 1.0, 1.0e5, 1.33);
    biref_jones T, R;
    CHECK(biref_slab_jones_tmm(&s, deg(70.0), 550.0, &T, &R) == BIREF_ERR_ILLCOND);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"isotropic_slab_equals_airy_formula", test_isotropic_slab_equals_airy_formula},
        {"lossless_random_slabs_conserve_energy", test_lossless_random_slabs_conserve_energy},
        {"normal_incidence_is_a_wave_plate", test_normal_incidence_is_a_wave_plate},
        {"axis_azimuth_about_the_normal_matches_closed_forms", test_axis_azimuth_about_the_normal_matches_closed_forms},
        {"axis_sign_and_length_do_not_change_the_result", test_axis_sign_and_length_do_not_change_the_result},
        {"invalid_slabs_are_refused", test_invalid_slabs_are_refused},
        {"thick_slab_in_total_reflection_reports_illcond", test_thick_slab_in_total_reflection_reports_illcond},
    };
    return test_run_cases("test_tmm", cases, TEST_COUNT(cases), argc, argv);
}
