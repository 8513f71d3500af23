/* Pre-integrated phase table for spatial anti-aliasing (docs/PHYSICS.md, "Spatial anti-aliasing").
 *
 * The box average of S(e^{ikD}) over [a, b] is (Q(b) - Q(a)) / (b - a) with Q an antiderivative:
 *     Q(D) = S(e^{2 pi i D / lambda} lambda / (2 pi i)),   dQ/dD = S(e^{2 pi i D / lambda}).
 * Q is tabulated like the point table (spectral_context.c): demodulated by the band-centre
 * frequency nu_c, on the same nodes, with its derivative for cubic Hermite interpolation. Beyond
 * the table, the endpoint asymptotics of S integrated once more. */
#include "spectral/phase_prefilter.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>

#include "spectral/spectral_internal.h"
#include "spectral/subband.h"
#include "spectral/table_build.h"

/* Same quadrature as the point table (midpoint rule, relative error (phi' h)^2 / 24). */
#define BUILD_DLAMBDA_NM 0.05

struct biref_phase_prefilter {
    const biref_spectral *sp;
    double *table; /* [m][band][re, im, dre/dD, dim/dD] of q(D) = e^{-2 pi i nu_c D} Q(D) */
    double *packet_table; /* the same for the packet kernel (biref_table_packet_layout) */
};

/* Nodes per block of the parallel build. */
#define BUILD_BLOCK_NODES 64

/* Per wavelength sample: the band weights times the step, the rotation e^{2 pi i f step} from
 * node to node and the derivative factor 2 pi i f. */
typedef struct {
    double w[3];
    double complex rot, dz;
} build_sample;

/* The table by the midpoint rule over the wavelengths, each node summing them in ascending
 * order. z runs through the nodes by one rotation per node; the rotation chain of each
 * wavelength is walked first (in parallel over wavelengths) to record z at every block's
 * first node, then the blocks are summed in parallel: the same products in the same order as
 * one serial pass, so the table is the same to the bit for any number of threads. */
static biref_status build_prefilter_table(const biref_spectral *sp, double *table)
{
    const double lmin = sp->cfg.lambda_min_nm, lmax = sp->cfg.lambda_max_nm;
    const int n = (int)ceil((lmax - lmin) / BUILD_DLAMBDA_NM);
    const double dl = (lmax - lmin) / n;
    const int blocks = (sp->nodes + BUILD_BLOCK_NODES - 1) / BUILD_BLOCK_NODES;
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
        biref_cmf_band_eval(&sp->band, lambda, lam);
        for (int j = 0; j < 3; j++) smp[i].w[j] = lam[j] * dl;
        double f = 1.0 / lambda - sp->nu_c;
        smp[i].rot = cexp(2.0 * M_PI * I * f * sp->step);
        smp[i].dz = 2.0 * M_PI * I * f;
        double complex z = lambda / (2.0 * M_PI * I);
        for (int m = 0; m < sp->nodes; m++) {
            if (m % BUILD_BLOCK_NODES == 0) z0[(size_t)i * blocks + m / BUILD_BLOCK_NODES] = z;
            z *= smp[i].rot;
        }
    }
#pragma omp parallel for schedule(dynamic)
    for (int b = 0; b < blocks; b++) {
        const int m0 = b * BUILD_BLOCK_NODES;
        const int m1 = m0 + BUILD_BLOCK_NODES < sp->nodes ? m0 + BUILD_BLOCK_NODES : sp->nodes;
        for (int i = 0; i < n; i++) {
            (void)biref_table_accumulate(table + (size_t)m0 * 12, m1 - m0, smp[i].w, z0[(size_t)i * blocks + b],
                                         smp[i].rot, smp[i].dz);
        }
    }
    free(smp);
    free(z0);
    return BIREF_OK;
}

biref_status biref_phase_prefilter_create(const biref_spectral *sp, biref_phase_prefilter **out)
{
    if (!sp || !out) return BIREF_ERR_INVALID;
    *out = NULL;
    biref_phase_prefilter *pf = calloc(1, sizeof *pf);
    if (!pf) return BIREF_ERR_NOMEM;
    pf->sp = sp;
    pf->table = calloc((size_t)sp->nodes * 12, sizeof *pf->table);
    if (!pf->table) {
        free(pf);
        return BIREF_ERR_NOMEM;
    }
    if (build_prefilter_table(sp, pf->table) != BIREF_OK) {
        biref_phase_prefilter_destroy(pf);
        return BIREF_ERR_NOMEM;
    }
    /* Aligned for the kernel's whole-vector loads (as the point table's copy, spectral_context.c). */
    pf->packet_table = aligned_alloc(64, (size_t)sp->nodes * BIREF_PACKET_TABLE_STRIDE * sizeof *pf->packet_table);
    if (!pf->packet_table) {
        biref_phase_prefilter_destroy(pf);
        return BIREF_ERR_NOMEM;
    }
    biref_table_packet_layout(pf->table, sp->carrier, sp->nodes, pf->packet_table);
    *out = pf;
    return BIREF_OK;
}

void biref_phase_prefilter_destroy(biref_phase_prefilter *pf)
{
    if (!pf) return;
    free(pf->table);
    free(pf->packet_table);
    free(pf);
}

const double *biref_phase_prefilter_packet_table(const biref_phase_prefilter *pf) { return pf->packet_table; }

/* Q_j(D) for D >= 0. */
static void antiderivative(const biref_phase_prefilter *pf, double d, double complex q[3])
{
    const biref_spectral *sp = pf->sp;
    if (!(d <= sp->d_max)) {
        /* S's endpoint asymptotics i/(2 pi D) [Λ λ^2 e^{2 pi i D/λ}] integrated once more. */
        const double lmin = sp->cfg.lambda_min_nm, lmax = sp->cfg.lambda_max_nm;
        double complex ph_hi = cycles_exp(d / lmax), ph_lo = cycles_exp(d / lmin);
        double e = 1.0 / (4.0 * M_PI * M_PI * d);
        for (int j = 0; j < 3; j++) q[j] = e * (sp->edge_hi[j] * lmax * ph_hi - sp->edge_lo[j] * lmin * ph_lo);
        return;
    }
    spectral_table_eval(sp, pf->table, d, q);
}

/* Q_j(D) for any D: S(e^{-ikD}) = conj S(e^{ikD}) gives Q(-D) = -conj Q(D). */
static void antiderivative_signed(const biref_phase_prefilter *pf, double d, double complex q[3])
{
    antiderivative(pf, fabs(d), q);
    if (d < 0.0)
        for (int j = 0; j < 3; j++) q[j] = -conj(q[j]);
}

void biref_phase_integrals_box(const biref_phase_prefilter *pf, double opd, double width, double c[3], double s[3])
{
    width = fabs(width);
    if (!(width > BIREF_PREFILTER_POINT_WIDTH_NM)) {
        biref_spectral_phase_integrals(pf->sp, opd, c, s);
        return;
    }
    double lo = opd - 0.5 * width, hi = opd + 0.5 * width;
    const double far = pf->sp->d_far;
    if (lo > far || hi < -far) {
        for (int j = 0; j < 3; j++) c[j] = s[j] = 0.0;
        return;
    }
    double complex qa[3], qb[3];
    antiderivative_signed(pf, lo, qa);
    antiderivative_signed(pf, hi, qb);
    for (int j = 0; j < 3; j++) {
        double complex v = (qb[j] - qa[j]) / width;
        c[j] = creal(v);
        s[j] = cimag(v);
    }
}

void biref_opl_footprint_flip(const biref_opl_footprint *in, biref_opl_footprint *out)
{
    static const int swap[4] = {BIREF_LEG_UP_O, BIREF_LEG_UP_E, BIREF_LEG_DOWN_O, BIREF_LEG_DOWN_E};
    out->pf = in->pf;
    /* The legs' dispersion is per face: a flipped dispersive slab is integrated from its own
     * flipped geometry (analytic_dispersive.c), never through a flipped footprint. */
    out->disp = NULL;
    for (int l = 0; l < 4; l++) {
        out->grad[l][0] = in->grad[swap[l]][0];
        out->grad[l][1] = in->grad[swap[l]][1];
    }
}

void biref_phase_integrals_footprint(const biref_spectral *sp, const biref_opl_footprint *fp, double opd,
                                     const int n[4], double c[3], double s[3])
{
    if (fp && fp->disp) {
        biref_lag_integrals(sp, fp->disp, opd, n, c, s, NULL, NULL);
        return;
    }
    if (!fp || !fp->pf) {
        biref_spectral_phase_integrals(sp, opd, c, s);
        return;
    }
    double gx = 0.0, gy = 0.0;
    for (int l = 0; l < 4; l++) {
        gx += n[l] * fp->grad[l][0];
        gy += n[l] * fp->grad[l][1];
    }
    /* A box of the variance of the pixel's (trapezoidal) distribution of D: (gx^2 + gy^2) / 12. */
    biref_phase_integrals_box(fp->pf, opd, sqrt(gx * gx + gy * gy), c, s);
}
