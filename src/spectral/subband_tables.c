/* The sub-band phase tables (subband.h, docs/PHYSICS.md §7): the band's table split in
 * wavenumber. The finest level is built by the point table's midpoint rule with each wavelength
 * sample going to the sub-band that holds it; every coarser sub-band is the sum of its two
 * halves. The tables share the point table's nodes and carrier (spectral_table_eval), so a
 * sub-band's demodulated function is no harder to interpolate than the whole band's. */
#include <complex.h>
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>

#include "spectral/phase_tables.h"
#include "spectral/subband.h"
#include "spectral/table_build.h"

/* Nodes per block of the parallel build (the point table's, phase_tables.c). */
#define BUILD_BLOCK_NODES 64
/* Tables of levels 1..L: 2 + 4 + ... + 2^L. */
#define SUBBAND_TABLES ((1 << (BIREF_SUBBAND_LEVELS + 1)) - 2)

struct biref_subbands {
    const biref_spectral *sp;
    double k[BIREF_SUBBAND_POINTS];
    biref_band_nodes nodes;
    double *tables; /* [level, sub-band][node][12], level L sub-band b at index 2^L - 2 + b */
};

static double *table_of(const biref_subbands *sb, int level, int b)
{
    return sb->tables + (size_t)((1 << level) - 2 + b) * (size_t)sb->sp->nodes * 12;
}

/* The finest sub-band that holds wavenumber k: uniform in k^2 between the band's ends. */
static int finest_index(const biref_spectral *sp, double k)
{
    const double klo = 2.0 * M_PI / sp->cfg.lambda_max_nm, khi = 2.0 * M_PI / sp->cfg.lambda_min_nm;
    int b = (int)floor((k * k - klo * klo) / (khi * khi - klo * klo) * BIREF_SUBBAND_FINEST);
    return b < 0 ? 0 : b >= BIREF_SUBBAND_FINEST ? BIREF_SUBBAND_FINEST - 1 : b;
}

static biref_status build(biref_subbands *sb)
{
    const biref_spectral *sp = sb->sp;
    const double lmin = sp->cfg.lambda_min_nm, lmax = sp->cfg.lambda_max_nm;
    const double klo = 2.0 * M_PI / lmax, khi = 2.0 * M_PI / lmin;
    for (int p = 0; p < BIREF_SUBBAND_POINTS; p++)
        sb->k[p] = sqrt(klo * klo + (khi * khi - klo * klo) * p / (BIREF_SUBBAND_POINTS - 1));
    const int n = (int)ceil((lmax - lmin) / BIREF_TABLE_BUILD_DLAMBDA_NM);
    const double dl = (lmax - lmin) / n;
    double(*lam)[5] = malloc((size_t)n * sizeof *lam); /* band weights * dl, frequency, sub-band */
    if (!lam) return BIREF_ERR_NOMEM;
    double moment[3][4] = {{0.0}}; /* the nodes' moments about the centroids, by the same samples */
    for (int i = 0; i < n; i++) {
        double lambda = lmin + (i + 0.5) * dl, l3[3];
        biref_cmf_band_eval(&sp->band, lambda, l3);
        for (int j = 0; j < 3; j++) lam[i][j] = l3[j] * dl;
        lam[i][3] = 1.0 / lambda - sp->nu_c;
        lam[i][4] = finest_index(sp, 2.0 * M_PI / lambda);
        for (int j = 0; j < 3; j++) {
            const double x = 2.0 * M_PI / lambda - sp->k_centroid[j];
            moment[j][0] += lam[i][j];
            moment[j][1] += lam[i][j] * x;
            moment[j][2] += lam[i][j] * x * x;
            moment[j][3] += lam[i][j] * x * x * x;
        }
    }
    biref_band_nodes_choose((const double(*)[4])moment, sp->k_centroid, &sb->nodes);
    const int blocks = (sp->nodes + BUILD_BLOCK_NODES - 1) / BUILD_BLOCK_NODES;
#pragma omp parallel for schedule(dynamic)
    for (int blk = 0; blk < blocks; blk++) {
        const int m0 = blk * BUILD_BLOCK_NODES;
        const int m1 = m0 + BUILD_BLOCK_NODES < sp->nodes ? m0 + BUILD_BLOCK_NODES : sp->nodes;
        for (int i = 0; i < n; i++) {
            const double f = lam[i][3];
            double complex rot = cexp(2.0 * M_PI * I * f * sp->step);
            double complex z = cexp(2.0 * M_PI * I * f * (m0 * sp->step));
            double *t = table_of(sb, BIREF_SUBBAND_LEVELS, (int)lam[i][4]);
            (void)biref_table_accumulate(t + (size_t)m0 * 12, m1 - m0, lam[i], z, rot, 2.0 * M_PI * I * f);
        }
    }
    free(lam);
    const size_t len = (size_t)sp->nodes * 12;
    for (int level = BIREF_SUBBAND_LEVELS - 1; level >= 1; level--)
        for (int b = 0; b < (1 << level); b++) {
            double *t = table_of(sb, level, b);
            const double *lo = table_of(sb, level + 1, 2 * b), *hi = table_of(sb, level + 1, 2 * b + 1);
            for (size_t i = 0; i < len; i++) t[i] = lo[i] + hi[i];
        }
    return BIREF_OK;
}

static biref_subbands *create(const biref_spectral *sp)
{
    biref_subbands *sb = calloc(1, sizeof *sb);
    if (!sb) return NULL;
    sb->sp = sp;
    sb->tables = calloc((size_t)SUBBAND_TABLES * (size_t)sp->nodes * 12, sizeof *sb->tables);
    if (!sb->tables || build(sb) != BIREF_OK) {
        biref_subbands_destroy(sb);
        return NULL;
    }
    return sb;
}

const biref_subbands *biref_spectral_subbands(const biref_spectral *sp)
{
    /* The context is immutable for its users; the tables (12 MB, ~50 ms) are a cache that only
     * dispersive materials need, made once under a lock and published with release order. */
    biref_spectral *w = (biref_spectral *)sp;
    biref_subbands *sb = atomic_load_explicit(&w->subbands, memory_order_acquire);
    if (sb) return sb;
#pragma omp critical(biref_subband_tables)
    {
        sb = atomic_load_explicit(&w->subbands, memory_order_acquire);
        if (!sb) {
            sb = create(sp);
            if (sb) atomic_store_explicit(&w->subbands, sb, memory_order_release);
        }
    }
    return sb;
}

void biref_subbands_destroy(biref_subbands *sb)
{
    if (!sb) return;
    free(sb->tables);
    free(sb);
}

const double *biref_subband_points(const biref_subbands *sb) { return sb->k; }

const double *biref_subband_table(const biref_subbands *sb, int level, int b) { return table_of(sb, level, b); }

const biref_band_nodes *biref_subband_nodes(const biref_subbands *sb) { return &sb->nodes; }

void biref_subband_eval_moment(const biref_subbands *sb, int level, int b, double d, double complex v[3],
                               double complex vk[3])
{
    spectral_table_eval_moment(sb->sp, table_of(sb, level, b), fabs(d), v, vk);
    if (d < 0.0) /* k is real: both conjugate */
        for (int j = 0; j < 3; j++) v[j] = conj(v[j]), vk[j] = conj(vk[j]);
}

void biref_subband_eval(const biref_subbands *sb, int level, int b, double d, double complex v[3])
{
    spectral_table_eval(sb->sp, table_of(sb, level, b), fabs(d), v);
    if (d < 0.0) /* S(e^{-ikD}) = conj S(e^{ikD}) */
        for (int j = 0; j < 3; j++) v[j] = conj(v[j]);
}
