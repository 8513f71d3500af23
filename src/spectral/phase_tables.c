/* The point and prefilter phase tables by quadrature (phase_tables.h). Kept apart from the
 * spectral context so that the build-time generator (tools/phase_tables/) compiles exactly this
 * code, with the library's flags, and writes the same bits as a run-time build. */
#include "spectral/phase_tables.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>

#include "spectral/table_build.h"

/* Nodes per block of the parallel builds: each block restarts its rotation chain (point table)
 * or takes its start from one serial chain (prefilter), so the tables depend on this constant
 * only, never on the threads. */
#define BUILD_BLOCK_NODES 64

void biref_phase_grid_init(biref_phase_grid *g, const biref_cmf_band *band, double lambda_min_nm, double lambda_max_nm)
{
    g->band = band;
    g->lambda_min_nm = lambda_min_nm;
    g->lambda_max_nm = lambda_max_nm;
    g->nu_c = 0.5 * (1.0 / lambda_min_nm + 1.0 / lambda_max_nm);
    g->step = BIREF_TABLE_STEP_NM;
    g->nodes = (int)(BIREF_TABLE_D_MAX_NM / BIREF_TABLE_STEP_NM) + 1;
}

/* The point table by the midpoint rule. Blocks of nodes are independent (each sums the
 * wavelengths in the same ascending order), so they are built in parallel. */
biref_status biref_phase_table_point(const biref_phase_grid *g, double *table)
{
    const double lmin = g->lambda_min_nm, lmax = g->lambda_max_nm;
    const int n = (int)ceil((lmax - lmin) / BIREF_TABLE_BUILD_DLAMBDA_NM);
    const double dl = (lmax - lmin) / n;
    double(*lam)[4] = malloc((size_t)n * sizeof *lam); /* band weights * dl and the frequency f */
    if (!lam) return BIREF_ERR_NOMEM;
    for (int i = 0; i < n; i++) {
        double lambda = lmin + (i + 0.5) * dl, l3[3];
        biref_cmf_band_eval(g->band, lambda, l3);
        for (int j = 0; j < 3; j++) lam[i][j] = l3[j] * dl;
        lam[i][3] = 1.0 / lambda - g->nu_c; /* demodulated frequency of this sample */
    }
    const int blocks = (g->nodes + BUILD_BLOCK_NODES - 1) / BUILD_BLOCK_NODES;
#pragma omp parallel for schedule(dynamic)
    for (int b = 0; b < blocks; b++) {
        const int m0 = b * BUILD_BLOCK_NODES;
        const int m1 = m0 + BUILD_BLOCK_NODES < g->nodes ? m0 + BUILD_BLOCK_NODES : g->nodes;
        for (int i = 0; i < n; i++) {
            const double f = lam[i][3];
            double complex rot = cexp(2.0 * M_PI * I * f * g->step);
            double complex z = cexp(2.0 * M_PI * I * f * (m0 * g->step));
            double complex dz = 2.0 * M_PI * I * f; /* d/dD of e^{2 pi i f D} is dz times it */
            (void)biref_table_accumulate(table + (size_t)m0 * BIREF_TABLE_ROW, m1 - m0, lam[i], z, rot, dz);
        }
    }
    free(lam);
    return BIREF_OK;
}

/* Per wavelength sample of the prefilter table: the band weights times the step, the rotation
 * e^{2 pi i f step} from node to node and the derivative factor 2 pi i f. */
typedef struct {
    double w[3];
    double complex rot, dz;
} build_sample;

/* The prefilter table by the midpoint rule over the wavelengths, each node summing them in
 * ascending order. z runs through the nodes by one rotation per node; the rotation chain of each
 * wavelength is walked first (in parallel over wavelengths) to record z at every block's first
 * node, then the blocks are summed in parallel: the same products in the same order as one
 * serial pass, so the table is the same to the bit for any number of threads. */
biref_status biref_phase_table_prefilter(const biref_phase_grid *g, double *table)
{
    const double lmin = g->lambda_min_nm, lmax = g->lambda_max_nm;
    const int n = (int)ceil((lmax - lmin) / BIREF_TABLE_BUILD_DLAMBDA_NM);
    const double dl = (lmax - lmin) / n;
    const int blocks = (g->nodes + BUILD_BLOCK_NODES - 1) / BUILD_BLOCK_NODES;
    build_sample *smp = malloc((size_t)n * sizeof *smp);
    double complex *z0 = malloc((size_t)n * (size_t)blocks * sizeof *z0);
    if (!smp || !z0) {
        free(smp);
        free(z0);
        return BIREF_ERR_NOMEM;
    }
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; i++) {
        double lambda = lmin + (i + 0.5) * dl, lam[3];
        biref_cmf_band_eval(g->band, lambda, lam);
        for (int j = 0; j < 3; j++) smp[i].w[j] = lam[j] * dl;
        double f = 1.0 / lambda - g->nu_c;
        smp[i].rot = cexp(2.0 * M_PI * I * f * g->step);
        smp[i].dz = 2.0 * M_PI * I * f;
        double complex z = lambda / (2.0 * M_PI * I);
        for (int m = 0; m < g->nodes; m++) {
            if (m % BUILD_BLOCK_NODES == 0) z0[(size_t)i * blocks + m / BUILD_BLOCK_NODES] = z;
            z *= smp[i].rot;
        }
    }
#pragma omp parallel for schedule(dynamic)
    for (int b = 0; b < blocks; b++) {
        const int m0 = b * BUILD_BLOCK_NODES;
        const int m1 = m0 + BUILD_BLOCK_NODES < g->nodes ? m0 + BUILD_BLOCK_NODES : g->nodes;
        for (int i = 0; i < n; i++) {
            (void)biref_table_accumulate(table + (size_t)m0 * BIREF_TABLE_ROW, m1 - m0, smp[i].w,
                                         z0[(size_t)i * blocks + b], smp[i].rot, smp[i].dz);
        }
    }
    free(smp);
    free(z0);
    return BIREF_OK;
}
