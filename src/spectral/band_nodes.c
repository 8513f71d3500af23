/* The wavenumbers at which the closed forms with dispersion take their amplitudes, and a lag's
 * phase integrals under the nodes' weights (subband.h, docs/PHYSICS.md §7). A method run on the
 * slab prepared at one wavenumber stands for the band only as far as its amplitudes (modes,
 * Fresnel coefficients) are constant across it; at the band's centroid the error is their
 * curvature times the band's variance. Two runs at the band's Gauss nodes, each integrating its
 * phases under the linear weight that is 1 at its node and 0 at the other, interpolate the
 * amplitudes linearly in k between the nodes under every phase and integrate them exactly to
 * cubic order where the phases are constant. The weights are smooth across the band, so each
 * run sees the whole band's coherence: a split of the band into parts would shorten it, and the
 * analytic method, which drops coherent pairs (eq. 26), would lose more by that than the split
 * gains. */
#include <complex.h>
#include <math.h>

#include "spectral/subband.h"

void biref_band_nodes_choose(const double moment[3][4], const double kref[3], biref_band_nodes *bn)
{
    for (int j = 0; j < 3; j++) {
        const double m0 = moment[j][0], mu = moment[j][1] / m0;
        /* Central moments of k under Λ_j (from moments about kref, near the centroid). */
        const double c2 = moment[j][2] / m0 - mu * mu;
        const double c3 = moment[j][3] / m0 - 3.0 * mu * moment[j][2] / m0 + 2.0 * mu * mu * mu;
        if (!(c2 > 0.0)) {
            bn->k[j][0] = bn->k[j][1] = kref[j] + mu;
            bn->mass[j][0] = m0, bn->mass[j][1] = 0.0;
            continue;
        }
        /* The degree-2 orthogonal polynomial of Λ_j about the centroid, x^2 - (c3/c2) x - c2:
         * its roots are the nodes, one on each side of the centroid. */
        const double a = c3 / c2, r = sqrt(a * a + 4.0 * c2);
        const double x[2] = {0.5 * (a - r), 0.5 * (a + r)};
        for (int i = 0; i < 2; i++) {
            bn->k[j][i] = kref[j] + mu + x[i];
            bn->mass[j][i] = m0 * (-x[1 - i]) / (x[i] - x[1 - i]); /* S(ℓ_i): ℓ_i at the centroid */
        }
    }
}

void biref_lag_node_integrals(const biref_band_nodes *bn, const double complex m0[3], const double complex m1[3],
                              int far, double complex node[BIREF_BAND_NODES][3])
{
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < BIREF_BAND_NODES; i++) {
            const double w = bn->mass[j][i], total = bn->mass[j][0] + bn->mass[j][1];
            if (!(w > 0.0))
                node[i][j] = 0.0;
            else if (far || !(bn->mass[j][1 - i] > 0.0)) /* the band's own mean */
                node[i][j] = m0[j] / total;
            else {
                /* ℓ_i(k) = (k - k_o) / (k_i - k_o) */
                const double ko = bn->k[j][1 - i];
                node[i][j] = (m1[j] - ko * m0[j]) / ((bn->k[j][i] - ko) * w);
            }
        }
}
