/* Stokes vectors, coherency matrices and analyzer projectors (docs/CONVENTIONS.md). */
#include <complex.h>
#include <math.h>

#include "biref/polarization.h"

biref_status biref_stokes_to_coherency(const double S[4], double complex C[2][2])
{
    for (int i = 0; i < 4; i++)
        if (!isfinite(S[i])) return BIREF_ERR_INVALID;
    /* Degree of polarization <= 1, tested on S / S0 so that squares of large entries cannot
     * overflow; S0 + |S1| must stay finite for the coherency matrix itself. */
    if (S[0] < 0.0 || !isfinite(S[0] + fabs(S[1])) || !isfinite(fabs(S[2]) + fabs(S[3]))) return BIREF_ERR_INVALID;
    if (S[0] == 0.0) {
        if (S[1] != 0.0 || S[2] != 0.0 || S[3] != 0.0) return BIREF_ERR_INVALID;
    } else {
        const double s1 = S[1] / S[0], s2 = S[2] / S[0], s3 = S[3] / S[0];
        if (s1 * s1 + s2 * s2 + s3 * s3 > 1.0 + 1e-12) return BIREF_ERR_INVALID;
    }
    C[0][0] = 0.5 * (S[0] + S[1]);
    C[1][1] = 0.5 * (S[0] - S[1]);
    C[0][1] = 0.5 * (S[2] - I * S[3]);
    C[1][0] = 0.5 * (S[2] + I * S[3]);
    return BIREF_OK;
}

static void projector(const double complex u[2], double complex P[2][2])
{
    for (int k = 0; k < 2; k++)
        for (int o = 0; o < 2; o++) P[k][o] = conj(u[k]) * u[o];
}

void biref_analyzer_linear(double psi, double complex P[2][2])
{
    double complex u[2] = {cos(psi), sin(psi)};
    projector(u, P);
}

void biref_analyzer_circular(int handedness, double complex P[2][2])
{
    double complex u[2] = {M_SQRT1_2, (handedness >= 0 ? I : -I) * M_SQRT1_2};
    projector(u, P);
}
