/* Random real lights of a hit in the packet kernels' form (biref_packet_light), shared by the
 * analytic and the expansion kernels' tests. */
#ifndef BIREF_TEST_PACKET_LIGHTS_H
#define BIREF_TEST_PACKET_LIGHTS_H

#include <complex.h>
#include <math.h>

#include "spectral/analytic_packet.h"
#include "test_cases.h"

/* A random real light of a hit: a linear polarizer (C = e e^T, |e| <= 1) or partially polarized
 * light in the s/p plane (S3 = 0), and a world-fixed-like linear analyzer P = a (a / |a|)^T with
 * |a| <= 1 or none (P = I). */
static inline void random_real_light(test_rng *rng, biref_packet_light *l)
{
    const double g = test_uniform(rng, 0, M_PI), amp = test_uniform(rng, 0.2, 1);
    if (test_uniform(rng, 0, 1) < 0.5) {
        const double e[2] = {amp * cos(g), amp * sin(g)};
        l->C[0] = e[0] * e[0], l->C[1] = e[0] * e[1], l->C[2] = e[1] * e[1];
    } else {
        const double S1 = test_uniform(rng, -0.5, 0.5), S2 = test_uniform(rng, -0.5, 0.5);
        l->C[0] = 0.5 * (1 + S1), l->C[1] = 0.5 * S2, l->C[2] = 0.5 * (1 - S1);
    }
    if (test_uniform(rng, 0, 1) < 0.2) {
        l->P[0] = 1, l->P[1] = 0, l->P[2] = 0, l->P[3] = 1;
        return;
    }
    const double h = test_uniform(rng, 0, M_PI), len = test_uniform(rng, 0.3, 1);
    const double a[2] = {len * cos(h), len * sin(h)}, u[2] = {cos(h), sin(h)};
    l->P[0] = a[0] * u[0], l->P[1] = a[0] * u[1], l->P[2] = a[1] * u[0], l->P[3] = a[1] * u[1];
}

static inline void light_matrices(const biref_packet_light *l, double complex C[2][2], double complex P[2][2])
{
    C[0][0] = l->C[0], C[0][1] = C[1][0] = l->C[1], C[1][1] = l->C[2];
    P[0][0] = l->P[0], P[0][1] = l->P[1], P[1][0] = l->P[2], P[1][1] = l->P[3];
}

#endif
